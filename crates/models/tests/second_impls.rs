//! Every provider trait implemented a second time, without any network, and driven through
//! the generic [`Cached`] wrapper: the traits carry what a real provider needs and nothing
//! ties them to HTTP.

use scenethesis_imagery::{DepthMap, Intrinsics, Mask};
use scenethesis_models::{
    cosine, BoxPrompt, CacheMode, Cached, ChatModel, ChatRequest, ChatResponse, DepthEstimate,
    DepthEstimator, GeneratedImage, ImageData, ImageEditRequest, ImageGenerator, ImageRequest,
    JsonSchema, Message, ProviderError, ProviderErrorKind, ResponseCache, Segment, Segmenter,
    TextEmbedder, TokenUsage, UsageMeter,
};
use serde_json::json;

fn png(img: &image::RgbaImage) -> ImageData {
    let mut out = std::io::Cursor::new(Vec::new());
    img.write_to(&mut out, image::ImageFormat::Png).unwrap();
    ImageData::from_bytes(out.into_inner(), "test image").unwrap()
}

fn decode(data: &ImageData) -> image::RgbaImage {
    image::load_from_memory(&data.bytes).unwrap().to_rgba8()
}

/// Lists the furniture words of the prompt that a tiny lexicon knows.
struct LexiconModel;

const LEXICON: &[&str] = &["bed", "desk", "chair", "lamp", "shelf", "sofa", "table"];

impl ChatModel for LexiconModel {
    fn name(&self) -> String {
        "local/lexicon".into()
    }

    fn chat(&self, request: &ChatRequest) -> Result<ChatResponse, ProviderError> {
        let text = request
            .messages
            .iter()
            .map(Message::joined_text)
            .collect::<Vec<_>>()
            .join(" ");
        let found: Vec<&str> = LEXICON
            .iter()
            .copied()
            .filter(|w| {
                text.split(|c: char| !c.is_alphanumeric())
                    .any(|t| t.eq_ignore_ascii_case(w))
            })
            .collect();
        let value = json!({"objects": found});
        if let Some(schema) = &request.schema {
            schema.validate(&value).map_err(|violation| {
                ProviderError::new(
                    "local",
                    "lexicon",
                    ProviderErrorKind::Schema {
                        schema: schema.name.clone(),
                        violation,
                    },
                )
            })?;
        }
        Ok(ChatResponse {
            text: value.to_string(),
            json: Some(value),
            model: "lexicon".into(),
            usage: TokenUsage {
                prompt_tokens: text.split_whitespace().count() as u64,
                completion_tokens: found.len() as u64,
            },
            notes: vec![],
        })
    }
}

/// Draws a flat colour derived from the prompt; edits paint it where the mask is transparent.
struct FlatPainter;

fn colour_of(prompt: &str) -> image::Rgba<u8> {
    let h = prompt.bytes().fold(2166136261u32, |h, b| {
        (h ^ u32::from(b)).wrapping_mul(16777619)
    });
    image::Rgba([h as u8, (h >> 8) as u8, (h >> 16) as u8, 255])
}

impl ImageGenerator for FlatPainter {
    fn name(&self) -> String {
        "local/flat".into()
    }

    fn generate(&self, r: &ImageRequest) -> Result<GeneratedImage, ProviderError> {
        let img = image::RgbaImage::from_pixel(r.size[0], r.size[1], colour_of(&r.prompt));
        Ok(GeneratedImage {
            image: png(&img),
            revised_prompt: None,
        })
    }

    fn edit(&self, r: &ImageEditRequest) -> Result<GeneratedImage, ProviderError> {
        let mut img = decode(&r.image);
        let mask = r.mask.as_ref().map(decode);
        for (x, y, px) in img.enumerate_pixels_mut() {
            if mask.as_ref().is_none_or(|m| m.get_pixel(x, y)[3] == 0) {
                *px = colour_of(&r.prompt);
            }
        }
        Ok(GeneratedImage {
            image: png(&img),
            revised_prompt: Some(r.prompt.clone()),
        })
    }
}

/// Masks the pixels of each box whose colour differs from the image's corner (background).
struct ContrastSegmenter;

impl Segmenter for ContrastSegmenter {
    fn name(&self) -> String {
        "local/contrast".into()
    }

    fn segment(
        &self,
        image: &ImageData,
        boxes: &[BoxPrompt],
    ) -> Result<Vec<Segment>, ProviderError> {
        let img = decode(image);
        let (w, h) = img.dimensions();
        let background = *img.get_pixel(0, 0);
        Ok(boxes
            .iter()
            .map(|b| {
                let (x0, y0) = ((b.bbox[0] * w as f32) as u32, (b.bbox[1] * h as f32) as u32);
                let (x1, y1) = (
                    (b.bbox[2] * w as f32).ceil() as u32,
                    (b.bbox[3] * h as f32).ceil() as u32,
                );
                let pixels = (0..h)
                    .flat_map(|y| (0..w).map(move |x| (x, y)))
                    .map(|(x, y)| {
                        x >= x0 && x < x1 && y >= y0 && y < y1 && *img.get_pixel(x, y) != background
                    })
                    .collect();
                Segment {
                    label: b.label.clone(),
                    mask: Mask::from_flags(w, h, pixels).unwrap(),
                    score: 1.0,
                }
            })
            .collect())
    }
}

/// Depth of a level floor seen by a level camera at a known height: rows below the horizon hit
/// the floor at fy·h / (v − cy); rows at or above it see no floor (0, unknown).
struct FloorPlane {
    camera_height: f64,
}

impl DepthEstimator for FloorPlane {
    fn name(&self) -> String {
        "local/floor-plane".into()
    }

    fn estimate(
        &self,
        image: &ImageData,
        k: Option<Intrinsics>,
    ) -> Result<DepthEstimate, ProviderError> {
        let (w, h) = decode(image).dimensions();
        let k = k.unwrap_or(Intrinsics {
            width: w,
            height: h,
            fx: w as f64,
            fy: w as f64,
            cx: w as f64 / 2.0,
            cy: h as f64 / 2.0,
        });
        let depth = DepthMap::from_fn(w, h, |_, v| {
            let dv = v as f64 + 0.5 - k.cy;
            if dv > 0.0 {
                (k.fy * self.camera_height / dv) as f32
            } else {
                0.0
            }
        });
        Ok(DepthEstimate {
            depth,
            intrinsics: k,
        })
    }
}

/// Counts character trigrams into 64 buckets.
struct TrigramEmbedder;

impl TextEmbedder for TrigramEmbedder {
    fn name(&self) -> String {
        "local/trigram".into()
    }

    fn embed(&self, texts: &[&str]) -> Result<Vec<Vec<f32>>, ProviderError> {
        Ok(texts
            .iter()
            .map(|t| {
                let padded: Vec<char> = format!("  {}  ", t.to_lowercase()).chars().collect();
                let mut v = vec![0.0f32; 64];
                for w in padded.windows(3) {
                    let h = w
                        .iter()
                        .fold(7u32, |h, c| h.wrapping_mul(31).wrapping_add(*c as u32));
                    v[(h % 64) as usize] += 1.0;
                }
                v
            })
            .collect())
    }
}

fn cache(dir: &std::path::Path, mode: CacheMode) -> ResponseCache {
    ResponseCache::open(dir, mode).unwrap()
}

#[test]
fn chat_model_with_schema_through_the_cache() {
    let dir = tempfile::tempdir().unwrap();
    let schema = JsonSchema::new(
        "objects",
        json!({
            "type": "object", "required": ["objects"],
            "properties": {"objects": {"type": "array", "minItems": 1, "items": {"enum": LEXICON}}}
        }),
    )
    .unwrap();
    let req = ChatRequest::structured(
        vec![Message::user("a study with a desk, a chair and a lamp")],
        schema.clone(),
    );
    let model = Cached::new(LexiconModel, cache(dir.path(), CacheMode::ReadWrite));
    let answer = model.chat(&req).unwrap();
    assert_eq!(
        answer.json,
        Some(json!({"objects": ["desk", "chair", "lamp"]}))
    );
    let err = model
        .chat(&ChatRequest::structured(
            vec![Message::user("an empty hall")],
            schema,
        ))
        .unwrap_err();
    assert!(
        err.to_string()
            .contains("at /objects: expected at least 1 items"),
        "{err}"
    );
    let meter = UsageMeter::new("local", "lexicon");
    let replay = Cached::new(LexiconModel, cache(dir.path(), CacheMode::ReplayOnly))
        .with_meter(meter.clone());
    assert_eq!(replay.chat(&req).unwrap(), answer);
    assert_eq!(meter.snapshot().cache_hits, 1);
}

#[test]
fn image_generator_generate_and_edit() {
    let dir = tempfile::tempdir().unwrap();
    let painter = Cached::new(FlatPainter, cache(dir.path(), CacheMode::ReadWrite));
    let out = painter
        .generate(&ImageRequest {
            prompt: "a red room".into(),
            size: [6, 4],
            seed: None,
        })
        .unwrap();
    let img = decode(&out.image);
    assert_eq!(img.dimensions(), (6, 4));
    assert_eq!(*img.get_pixel(5, 3), colour_of("a red room"));
    // Edit only the left half (transparent in the mask).
    let mut mask = image::RgbaImage::from_pixel(6, 4, image::Rgba([0, 0, 0, 255]));
    for y in 0..4 {
        for x in 0..3 {
            mask.put_pixel(x, y, image::Rgba([0, 0, 0, 0]));
        }
    }
    let edit = ImageEditRequest {
        prompt: "paint".into(),
        image: out.image.clone(),
        mask: Some(png(&mask)),
        size: [6, 4],
        seed: None,
    };
    let edited = decode(&painter.edit(&edit).unwrap().image);
    assert_eq!(*edited.get_pixel(0, 0), colour_of("paint"));
    assert_eq!(*edited.get_pixel(5, 0), colour_of("a red room"));
    let replay = Cached::new(FlatPainter, cache(dir.path(), CacheMode::ReplayOnly));
    assert_eq!(replay.edit(&edit).unwrap(), painter.edit(&edit).unwrap());
}

#[test]
fn segmenter_masks_follow_boxes_and_content() {
    let mut img = image::RgbaImage::from_pixel(10, 10, image::Rgba([255, 255, 255, 255]));
    for y in 2..5 {
        for x in 2..6 {
            img.put_pixel(x, y, image::Rgba([200, 0, 0, 255]));
        }
    }
    let dir = tempfile::tempdir().unwrap();
    let seg = Cached::new(ContrastSegmenter, cache(dir.path(), CacheMode::ReadWrite));
    let boxes = [
        BoxPrompt {
            label: "sofa_0".into(),
            bbox: [0.1, 0.1, 0.7, 0.6],
        },
        BoxPrompt {
            label: "empty".into(),
            bbox: [0.7, 0.7, 1.0, 1.0],
        },
    ];
    let masks = seg.segment(&png(&img), &boxes).unwrap();
    assert_eq!(masks.len(), 2);
    assert_eq!(
        (masks[0].label.as_str(), masks[0].mask.area()),
        ("sofa_0", 12)
    );
    assert_eq!(masks[1].mask.area(), 0);
    let replay = Cached::new(ContrastSegmenter, cache(dir.path(), CacheMode::ReplayOnly));
    assert_eq!(replay.segment(&png(&img), &boxes).unwrap(), masks);
}

#[test]
fn depth_estimator_gives_metric_floor_depth() {
    let img = png(&image::RgbaImage::new(8, 8));
    let k = Intrinsics {
        width: 8,
        height: 8,
        fx: 8.0,
        fy: 8.0,
        cx: 4.0,
        cy: 4.0,
    };
    let dir = tempfile::tempdir().unwrap();
    let depth = Cached::new(
        FloorPlane { camera_height: 1.5 },
        cache(dir.path(), CacheMode::ReadWrite),
    );
    let map = depth.estimate(&img, Some(k)).unwrap();
    // Row 7: dv = 3.5 → 8 · 1.5 / 3.5 m.
    assert!((map.depth.get(0, 7).unwrap() - 12.0 / 3.5).abs() < 1e-6);
    // Above the horizon: no floor, so unknown.
    assert_eq!(map.depth.get(3, 0), None);
    assert_eq!(map.depth.get(8, 0), None);
    let replay = Cached::new(
        FloorPlane { camera_height: 1.5 },
        cache(dir.path(), CacheMode::ReplayOnly),
    );
    assert_eq!(replay.estimate(&img, Some(k)).unwrap(), map);
}

/// A depth estimator whose answer JSON cannot hold.
struct Broken;

impl DepthEstimator for Broken {
    fn name(&self) -> String {
        "local/broken".into()
    }

    fn estimate(
        &self,
        _: &ImageData,
        _: Option<Intrinsics>,
    ) -> Result<DepthEstimate, ProviderError> {
        // A focal length of NaN: JSON writes it as null, which reads back as no number.
        Ok(DepthEstimate {
            depth: DepthMap::from_fn(1, 1, |_, _| 1.0),
            intrinsics: Intrinsics {
                width: 1,
                height: 1,
                fx: f64::NAN,
                fy: 1.0,
                cx: 0.5,
                cy: 0.5,
            },
        })
    }
}

#[test]
fn an_answer_the_cache_cannot_hold_fails_when_recorded() {
    let dir = tempfile::tempdir().unwrap();
    let broken = Cached::new(Broken, cache(dir.path(), CacheMode::ReadWrite));
    let err = broken
        .estimate(&png(&image::RgbaImage::new(1, 1)), None)
        .unwrap_err();
    assert!(matches!(err.kind, ProviderErrorKind::Cache { .. }), "{err}");
    assert_eq!(err.model, "local/broken");
}

#[test]
fn text_embedder_ranks_by_similarity() {
    let dir = tempfile::tempdir().unwrap();
    let e = Cached::new(TrigramEmbedder, cache(dir.path(), CacheMode::ReadWrite));
    let v = e
        .embed(&["bookshelf", "bookshelves", "ceiling fan"])
        .unwrap();
    assert!(cosine(&v[0], &v[1]) > cosine(&v[0], &v[2]));
    assert_eq!(cosine(&v[0], &[1.0]), 0.0);
    let replay = Cached::new(TrigramEmbedder, cache(dir.path(), CacheMode::ReplayOnly));
    assert_eq!(
        replay
            .embed(&["bookshelf", "bookshelves", "ceiling fan"])
            .unwrap(),
        v
    );
}
