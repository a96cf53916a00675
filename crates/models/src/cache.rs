//! A response cache keyed by the SHA-256 of the canonical request, and [`Cached`], a wrapper
//! that answers repeated requests from it, so a run can be replayed offline byte for byte.

use std::fs;
use std::io::Write as _;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use serde::de::DeserializeOwned;
use serde::Serialize;
use serde_json::Value;
use sha2::{Digest, Sha256};

use crate::chat::{check_structured, ChatModel, ChatRequest, ChatResponse};
use crate::error::{ProviderError, ProviderErrorKind};
use crate::image::ImageData;
use crate::providers::{
    BoxPrompt, DepthEstimate, DepthEstimator, GeneratedImage, ImageEditRequest, ImageGenerator,
    ImageRequest, Segment, Segmenter, TextEmbedder,
};
use crate::usage::UsageMeter;
use scenethesis_imagery::Intrinsics;

/// Version of the key derivation and file layout; part of every key.
const CACHE_VERSION: u32 = 1;

/// Largest response-cache entry read, in bytes (64 MiB: a generated image in base64 with room
/// to spare). A larger file, a device such as `/dev/zero` or a folder in its place is refused.
pub const MAX_CACHE_ENTRY_BYTES: u64 = 64 * 1024 * 1024;

/// Whether the cache may call the provider on a miss.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum CacheMode {
    /// Answer hits from the cache; on a miss call the provider and record its answer.
    ReadWrite,
    /// Answer only from the cache; a miss is an error (offline replay, tests).
    ReplayOnly,
}

/// Writes `value` as JSON with object keys sorted, no whitespace; the same value always gives
/// the same bytes.
pub fn canonical_json(value: &Value) -> String {
    let mut out = String::new();
    write_canonical(value, &mut out);
    out
}

fn write_canonical(value: &Value, out: &mut String) {
    match value {
        Value::Object(map) => {
            let mut keys: Vec<&String> = map.keys().collect();
            keys.sort();
            out.push('{');
            for (i, k) in keys.into_iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                out.push_str(&Value::String(k.clone()).to_string());
                out.push(':');
                write_canonical(&map[k], out);
            }
            out.push('}');
        }
        Value::Array(items) => {
            out.push('[');
            for (i, item) in items.iter().enumerate() {
                if i > 0 {
                    out.push(',');
                }
                write_canonical(item, out);
            }
            out.push(']');
        }
        scalar => out.push_str(&scalar.to_string()),
    }
}

/// Lower-case hex SHA-256 of `bytes`.
pub fn sha256_hex(bytes: &[u8]) -> String {
    Sha256::digest(bytes)
        .iter()
        .map(|b| format!("{b:02x}"))
        .collect()
}

/// A directory of recorded answers, one JSON file per request, named by the request's key.
#[derive(Debug, Clone)]
pub struct ResponseCache {
    dir: PathBuf,
    mode: CacheMode,
}

/// Distinguishes temporary files of concurrent writers within one process.
static TMP_COUNTER: AtomicU64 = AtomicU64::new(0);

impl ResponseCache {
    /// Opens the cache in `dir`: created if needed to record, and refused once here (rather
    /// than at every request) when replaying from a folder that does not exist.
    pub fn open(dir: impl Into<PathBuf>, mode: CacheMode) -> Result<Self, ProviderError> {
        let dir = dir.into();
        match mode {
            CacheMode::ReadWrite => {
                fs::create_dir_all(&dir).map_err(|e| cache_error(&dir, "cannot create", e))?;
            }
            CacheMode::ReplayOnly if !dir.is_dir() => {
                let e = std::io::Error::new(
                    std::io::ErrorKind::NotFound,
                    "is not a folder; replay needs the folder a recording run wrote",
                );
                return Err(cache_error(&dir, "cannot replay from it", e));
            }
            CacheMode::ReplayOnly => {}
        }
        Ok(Self { dir, mode })
    }

    /// The cache directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The mode.
    pub fn mode(&self) -> CacheMode {
        self.mode
    }

    /// The record a request is stored under: operation, model and request, canonical.
    fn envelope(operation: &str, model: &str, request: &Value) -> Value {
        serde_json::json!({
            "version": CACHE_VERSION,
            "operation": operation,
            "model": model,
            "request": request,
        })
    }

    /// The key of a request: SHA-256 of the canonical JSON of operation, model and request.
    pub fn key<Q: Serialize + ?Sized>(operation: &str, model: &str, request: &Q) -> String {
        let request = serde_json::to_value(request).unwrap_or(Value::Null);
        sha256_hex(canonical_json(&Self::envelope(operation, model, &request)).as_bytes())
    }

    /// The file of a key.
    pub fn path(&self, key: &str) -> PathBuf {
        self.dir.join(format!("{key}.json"))
    }

    /// The recorded answer for `key`, if any.
    pub fn get<R: DeserializeOwned>(&self, key: &str) -> Result<Option<R>, ProviderError> {
        let path = self.path(key);
        let bytes = match scenethesis_scene_graph::read_bounded(&path, MAX_CACHE_ENTRY_BYTES) {
            Ok(b) => b,
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(None),
            Err(e) => return Err(cache_error(&path, "cannot read", e)),
        };
        let record: Value =
            serde_json::from_slice(&bytes).map_err(|e| cache_error(&path, "is not JSON", e))?;
        self.check_version(&path, &record)?;
        let response = record.get("response").cloned().ok_or_else(|| {
            ProviderError::new(
                self.dir.display().to_string(),
                "",
                ProviderErrorKind::Cache {
                    path: path.clone(),
                    message: "has no `response` field".to_string(),
                    source: None,
                },
            )
        })?;
        serde_json::from_value(response)
            .map(Some)
            .map_err(|e| cache_error(&path, "holds an answer of the wrong shape", e))
    }

    /// Refuses a record of another cache version than this build writes: its answer may not
    /// mean what this build expects, so it is not replayed.
    fn check_version(&self, path: &Path, record: &Value) -> Result<(), ProviderError> {
        let version = record.get("version");
        if version.and_then(Value::as_u64) == Some(u64::from(CACHE_VERSION)) {
            return Ok(());
        }
        let found = version.map_or_else(|| "no version".to_string(), |v| format!("version {v}"));
        Err(ProviderError::new(
            self.dir.display().to_string(),
            "",
            ProviderErrorKind::Cache {
                path: path.to_path_buf(),
                message: format!(
                    "holds {found}, but this build reads cache version {CACHE_VERSION}; record \
                     it again (run without --llm-replay into an empty --llm-cache folder)"
                ),
                source: None,
            },
        ))
    }

    /// Records `response` for a request (atomically: a temporary file renamed into place).
    pub fn put<Q: Serialize + ?Sized, R: Serialize>(
        &self,
        operation: &str,
        model: &str,
        request: &Q,
        response: &R,
    ) -> Result<String, ProviderError> {
        let request = serde_json::to_value(request).unwrap_or(Value::Null);
        let envelope = Self::envelope(operation, model, &request);
        let key = sha256_hex(canonical_json(&envelope).as_bytes());
        let mut record = envelope;
        record["response"] = serde_json::to_value(response).unwrap_or(Value::Null);
        let path = self.path(&key);
        let tmp = self.dir.join(format!(
            ".{key}.{}.{}.tmp",
            std::process::id(),
            TMP_COUNTER.fetch_add(1, Ordering::Relaxed)
        ));
        let write = || -> std::io::Result<()> {
            let mut file = fs::File::create(&tmp)?;
            file.write_all(canonical_json(&record).as_bytes())?;
            file.write_all(b"\n")?;
            file.sync_all()?;
            fs::rename(&tmp, &path)
        };
        write().map_err(|e| {
            let _ = fs::remove_file(&tmp);
            cache_error(&path, "cannot write", e)
        })?;
        Ok(key)
    }
}

fn cache_error(
    path: &Path,
    what: &str,
    e: impl std::error::Error + Send + Sync + 'static,
) -> ProviderError {
    ProviderError::new(
        "response cache",
        "",
        ProviderErrorKind::Cache {
            path: path.to_path_buf(),
            message: format!("{what}: {e}"),
            source: Some(Box::new(e)),
        },
    )
}

/// A provider wrapped with a [`ResponseCache`]: identical requests are answered from the cache
/// (counted as cache hits on the meter), new ones go to the inner provider and are recorded.
#[derive(Debug)]
pub struct Cached<M> {
    inner: M,
    cache: ResponseCache,
    meter: Option<UsageMeter>,
}

impl<M> Cached<M> {
    /// Wraps `inner`.
    pub fn new(inner: M, cache: ResponseCache) -> Self {
        Self {
            inner,
            cache,
            meter: None,
        }
    }

    /// Counts cache hits on `meter`.
    pub fn with_meter(mut self, meter: UsageMeter) -> Self {
        self.meter = Some(meter);
        self
    }

    /// The wrapped provider.
    pub fn inner(&self) -> &M {
        &self.inner
    }

    /// The cache.
    pub fn cache(&self) -> &ResponseCache {
        &self.cache
    }

    fn through<Q, R>(
        &self,
        operation: &str,
        model: &str,
        request: &Q,
        call: impl FnOnce() -> Result<R, ProviderError>,
    ) -> Result<R, ProviderError>
    where
        Q: Serialize + ?Sized,
        R: Serialize + DeserializeOwned,
    {
        let key = ResponseCache::key(operation, model, request);
        if let Some(hit) = self
            .cache
            .get::<R>(&key)
            .map_err(|e| with_model(e, model))?
        {
            if let Some(m) = &self.meter {
                m.record_cache_hit();
            }
            return Ok(hit);
        }
        if self.cache.mode == CacheMode::ReplayOnly {
            return Err(ProviderError::new(
                "response cache",
                model,
                ProviderErrorKind::CacheMiss {
                    key,
                    dir: self.cache.dir.clone(),
                },
            ));
        }
        let answer = call()?;
        let key = self
            .cache
            .put(operation, model, request, &answer)
            .map_err(|e| with_model(e, model))?;
        // Hand back what a replay will read, so recording and replaying runs see the same
        // values (and an answer JSON cannot hold, such as a NaN, fails now, not on replay).
        self.cache
            .get::<R>(&key)
            .map_err(|e| with_model(e, model))?
            .ok_or_else(|| {
                ProviderError::new(
                    "response cache",
                    model,
                    ProviderErrorKind::Cache {
                        path: self.cache.path(&key),
                        message: "vanished right after it was written".to_string(),
                        source: None,
                    },
                )
            })
    }
}

fn with_model(mut e: ProviderError, model: &str) -> ProviderError {
    e.model = model.to_string();
    e
}

impl<M: ChatModel> ChatModel for Cached<M> {
    fn name(&self) -> String {
        self.inner.name()
    }

    /// Answers from the cache or the inner model; a recorded answer to a structured request
    /// is checked against the request's schema as a live one is ([`check_structured`]).
    fn chat(&self, request: &ChatRequest) -> Result<ChatResponse, ProviderError> {
        let name = self.inner.name();
        let response = self.through("chat", &name, request, || self.inner.chat(request))?;
        check_structured(request, response)
            .map_err(|kind| ProviderError::new("response cache", name, kind))
    }
}

impl<M: ImageGenerator> ImageGenerator for Cached<M> {
    fn name(&self) -> String {
        self.inner.name()
    }

    fn generate(&self, request: &ImageRequest) -> Result<GeneratedImage, ProviderError> {
        self.through("image-generate", &self.inner.name(), request, || {
            self.inner.generate(request)
        })
    }

    fn edit(&self, request: &ImageEditRequest) -> Result<GeneratedImage, ProviderError> {
        self.through(
            "image-edit",
            &self.inner.name(),
            &EditKey::of(request),
            || self.inner.edit(request),
        )
    }
}

/// What an image edit is recorded under: the request with its input image and mask replaced by
/// their digests, so a record stays small and names its input without holding it.
#[derive(Serialize)]
struct EditKey<'a> {
    prompt: &'a str,
    image: ImageDigest,
    mask: Option<ImageDigest>,
    size: [u32; 2],
    seed: Option<u64>,
}

/// An encoded image named by its format and the SHA-256 of its bytes.
#[derive(Serialize)]
struct ImageDigest {
    format: crate::image::ImageFormat,
    sha256: String,
}

impl ImageDigest {
    fn of(image: &ImageData) -> Self {
        Self {
            format: image.format,
            sha256: sha256_hex(&image.bytes),
        }
    }
}

impl<'a> EditKey<'a> {
    fn of(request: &'a ImageEditRequest) -> Self {
        Self {
            prompt: &request.prompt,
            image: ImageDigest::of(&request.image),
            mask: request.mask.as_ref().map(ImageDigest::of),
            size: request.size,
            seed: request.seed,
        }
    }
}

impl<M: Segmenter> Segmenter for Cached<M> {
    fn name(&self) -> String {
        self.inner.name()
    }

    fn segment(
        &self,
        image: &ImageData,
        boxes: &[BoxPrompt],
    ) -> Result<Vec<Segment>, ProviderError> {
        self.through("segment", &self.inner.name(), &(image, boxes), || {
            self.inner.segment(image, boxes)
        })
    }
}

impl<M: DepthEstimator> DepthEstimator for Cached<M> {
    fn name(&self) -> String {
        self.inner.name()
    }

    fn estimate(
        &self,
        image: &ImageData,
        intrinsics: Option<Intrinsics>,
    ) -> Result<DepthEstimate, ProviderError> {
        self.through("depth", &self.inner.name(), &(image, intrinsics), || {
            self.inner.estimate(image, intrinsics)
        })
    }
}

impl<M: TextEmbedder> TextEmbedder for Cached<M> {
    fn name(&self) -> String {
        self.inner.name()
    }

    fn embed(&self, texts: &[&str]) -> Result<Vec<Vec<f32>>, ProviderError> {
        self.through("embed", &self.inner.name(), texts, || {
            self.inner.embed(texts)
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn sha256_matches_known_vectors() {
        assert_eq!(
            sha256_hex(b""),
            "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855"
        );
        assert_eq!(
            sha256_hex(b"abc"),
            "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad"
        );
    }

    #[test]
    fn canonical_json_sorts_keys_at_every_level() {
        let a = json!({"b": 1, "a": {"y": [1, {"d": 2, "c": 3}], "x": "s"}});
        assert_eq!(
            canonical_json(&a),
            r#"{"a":{"x":"s","y":[1,{"c":3,"d":2}]},"b":1}"#
        );
    }

    #[test]
    fn key_depends_on_operation_model_and_request() {
        let k = ResponseCache::key("chat", "m", &json!({"a": 1}));
        assert_eq!(k.len(), 64);
        assert_eq!(k, ResponseCache::key("chat", "m", &json!({"a": 1})));
        assert_ne!(k, ResponseCache::key("chat", "m2", &json!({"a": 1})));
        assert_ne!(k, ResponseCache::key("embed", "m", &json!({"a": 1})));
        assert_ne!(k, ResponseCache::key("chat", "m", &json!({"a": 2})));
    }

    #[test]
    fn put_then_get_and_leaves_no_temporary_files() {
        let dir = tempfile::tempdir().unwrap();
        let cache = ResponseCache::open(dir.path().join("c"), CacheMode::ReadWrite).unwrap();
        let key = cache
            .put("embed", "m", &["a"], &vec![vec![0.1f32, 0.2]])
            .unwrap();
        assert_eq!(key, ResponseCache::key("embed", "m", &["a"]));
        let got: Option<Vec<Vec<f32>>> = cache.get(&key).unwrap();
        assert_eq!(got, Some(vec![vec![0.1f32, 0.2]]));
        let names: Vec<String> = fs::read_dir(cache.dir())
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, vec![format!("{key}.json")]);
        assert_eq!(cache.get::<Value>(&"0".repeat(64)).unwrap(), None);
    }

    #[test]
    fn corrupt_file_is_an_error_naming_it() {
        let dir = tempfile::tempdir().unwrap();
        let cache = ResponseCache::open(dir.path(), CacheMode::ReadWrite).unwrap();
        let key = "f".repeat(64);
        fs::write(cache.path(&key), "{not json").unwrap();
        let err = cache.get::<Value>(&key).unwrap_err();
        let text = err.to_string();
        assert!(text.contains(&format!("{key}.json")), "{text}");
        assert!(text.contains("is not JSON"), "{text}");
        assert!(std::error::Error::source(&err).is_some());
    }

    #[test]
    fn replaying_from_a_missing_folder_is_refused_when_opened() {
        let dir = tempfile::tempdir().unwrap();
        let missing = dir.path().join("nowhere");
        let text = ResponseCache::open(&missing, CacheMode::ReplayOnly)
            .unwrap_err()
            .to_string();
        assert!(
            text.contains("nowhere") && text.contains("is not a folder"),
            "{text}"
        );
        ResponseCache::open(&missing, CacheMode::ReadWrite).unwrap();
        assert!(missing.is_dir(), "created to record");
        ResponseCache::open(&missing, CacheMode::ReplayOnly).unwrap();
    }

    #[test]
    fn a_record_of_another_version_is_refused_naming_both_versions() {
        let dir = tempfile::tempdir().unwrap();
        let cache = ResponseCache::open(dir.path(), CacheMode::ReplayOnly).unwrap();
        let key = "e".repeat(64);
        for (record, found) in [
            (json!({"version": 99, "response": 1}), "holds version 99"),
            (json!({"response": 1}), "holds no version"),
        ] {
            fs::write(cache.path(&key), record.to_string()).unwrap();
            let text = cache.get::<Value>(&key).unwrap_err().to_string();
            assert!(text.contains(found), "{text}");
            assert!(text.contains("reads cache version 1"), "{text}");
            assert!(text.contains(&format!("{key}.json")), "{text}");
        }
    }

    #[cfg(unix)]
    #[test]
    fn an_entry_that_is_a_device_or_too_large_is_refused() {
        let dir = tempfile::tempdir().unwrap();
        let cache = ResponseCache::open(dir.path(), CacheMode::ReplayOnly).unwrap();
        let key = "d".repeat(64);
        std::os::unix::fs::symlink("/dev/zero", cache.path(&key)).unwrap();
        let text = cache.get::<Value>(&key).unwrap_err().to_string();
        assert!(text.contains("device"), "{text}");
        let key = "b".repeat(64);
        let file = fs::File::create(cache.path(&key)).unwrap();
        file.set_len(MAX_CACHE_ENTRY_BYTES + 1).unwrap();
        let text = cache.get::<Value>(&key).unwrap_err().to_string();
        assert!(text.contains("larger than the limit"), "{text}");
    }

    /// A chat model that must not be called (replay only).
    struct Silent;

    impl ChatModel for Silent {
        fn name(&self) -> String {
            "test/silent".into()
        }
        fn chat(&self, _: &ChatRequest) -> Result<ChatResponse, ProviderError> {
            unreachable!("replay only")
        }
    }

    #[test]
    fn a_replayed_structured_answer_is_checked_against_the_schema() {
        let schema = crate::JsonSchema::new(
            "few",
            json!({"type": "object", "properties": {"items": {"type": "array", "maxItems": 2}}}),
        )
        .unwrap();
        let mut request = ChatRequest::structured(vec![crate::Message::user("hi")], schema);
        let many = json!({"items": [1, 2, 3]});
        let recorded = ChatResponse {
            text: many.to_string(),
            json: Some(many),
            model: "m".into(),
            usage: Default::default(),
            notes: vec![],
        };
        let dir = tempfile::tempdir().unwrap();
        let cache = ResponseCache::open(dir.path(), CacheMode::ReadWrite).unwrap();
        let replay = Cached::new(
            Silent,
            ResponseCache::open(dir.path(), CacheMode::ReplayOnly).unwrap(),
        );
        cache
            .put("chat", "test/silent", &request, &recorded)
            .unwrap();
        let err = replay.chat(&request).unwrap_err();
        assert!(
            matches!(err.kind, ProviderErrorKind::Schema { .. }),
            "{err}"
        );
        // A lenient request gets the answer back with the violation noted, as live.
        request.lenient = true;
        cache
            .put("chat", "test/silent", &request, &recorded)
            .unwrap();
        let answer = replay.chat(&request).unwrap();
        assert!(
            answer
                .notes
                .iter()
                .any(|n| n.contains("violates the schema `few`")),
            "{:?}",
            answer.notes
        );
        // A valid answer is replayed as recorded.
        request.lenient = false;
        let few = ChatResponse {
            json: Some(json!({"items": [1]})),
            ..recorded
        };
        cache.put("chat", "test/silent", &request, &few).unwrap();
        assert_eq!(replay.chat(&request).unwrap(), few);
    }

    /// An image model that paints a fresh image per call (a counter in its first pixel byte),
    /// so a replay that went to it would differ.
    struct Painter(std::sync::atomic::AtomicU8);

    impl ImageGenerator for Painter {
        fn name(&self) -> String {
            "test/painter".to_string()
        }
        fn generate(&self, _: &ImageRequest) -> Result<GeneratedImage, ProviderError> {
            unreachable!("the test only edits")
        }
        fn edit(&self, request: &ImageEditRequest) -> Result<GeneratedImage, ProviderError> {
            let n = self.0.fetch_add(1, Ordering::Relaxed);
            let mut bytes = request.image.bytes.clone();
            bytes.push(n);
            Ok(GeneratedImage {
                image: ImageData {
                    format: request.image.format,
                    bytes,
                },
                revised_prompt: None,
            })
        }
    }

    #[test]
    fn image_edits_are_recorded_under_the_input_digest_and_replayed() {
        let dir = tempfile::tempdir().unwrap();
        let request = |image: &[u8], size| ImageEditRequest {
            prompt: "furnish it".to_string(),
            image: ImageData {
                format: crate::image::ImageFormat::Png,
                bytes: image.to_vec(),
            },
            mask: None,
            size,
            seed: Some(3),
        };
        let input = vec![7u8; 4096];
        let painter = Painter(Default::default());
        let recording = Cached::new(
            painter,
            ResponseCache::open(dir.path(), CacheMode::ReadWrite).unwrap(),
        );
        let first = recording.edit(&request(&input, [64, 32])).unwrap();
        // A second identical request is a hit: the painter is not called again.
        assert_eq!(recording.edit(&request(&input, [64, 32])).unwrap(), first);
        assert_eq!(recording.inner().0.load(Ordering::Relaxed), 1);
        // Another input image or size is another request.
        let other = recording.edit(&request(&[8u8; 4096], [64, 32])).unwrap();
        assert_ne!(other, first);
        recording.edit(&request(&input, [32, 64])).unwrap();
        assert_eq!(recording.inner().0.load(Ordering::Relaxed), 3);
        // The record names the input by its digest and does not hold it.
        let record = fs::read_to_string(dir.path().join(format!(
            "{}.json",
            ResponseCache::key(
                "image-edit",
                "test/painter",
                &EditKey::of(&request(&input, [64, 32]))
            )
        )))
        .unwrap();
        assert!(record.contains(&sha256_hex(&input)), "{record}");
        // Only the answer's image is held (base64 of 4 kB is 5.5 kB), not the input's as well.
        assert!(record.len() < 8000, "{} bytes", record.len());
        // Offline replay answers byte for byte without the provider.
        let replay = Cached::new(
            Painter(Default::default()),
            ResponseCache::open(dir.path(), CacheMode::ReplayOnly).unwrap(),
        );
        assert_eq!(replay.edit(&request(&input, [64, 32])).unwrap(), first);
        assert_eq!(replay.inner().0.load(Ordering::Relaxed), 0);
        let miss = replay.edit(&request(&input, [16, 16])).unwrap_err();
        assert!(
            matches!(miss.kind, ProviderErrorKind::CacheMiss { .. }),
            "{miss}"
        );
    }
}
