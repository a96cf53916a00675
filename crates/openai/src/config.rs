//! Client configuration: command-line flags over environment variables over a TOML file.

use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Duration;

use serde::Deserialize;

/// Environment variable with the endpoint's base URL (`https://api.openai.com/v1`).
pub const ENV_BASE_URL: &str = "OPENAI_BASE_URL";
/// Environment variable with the API key.
pub const ENV_API_KEY: &str = "OPENAI_API_KEY";
/// Environment variable with the language model's name.
pub const ENV_LLM_MODEL: &str = "SCENETHESIS_LLM_MODEL";
/// Environment variable with the vision-language model's name.
pub const ENV_VLM_MODEL: &str = "SCENETHESIS_VLM_MODEL";
/// Environment variable with the image model's name.
pub const ENV_IMAGE_MODEL: &str = "SCENETHESIS_IMAGE_MODEL";
/// Environment variable with the embedding model's name.
pub const ENV_EMBEDDING_MODEL: &str = "SCENETHESIS_EMBEDDING_MODEL";

/// The base URL used when none is configured.
/// Environment variable naming the server software (`vllm`), for its request extras.
pub const ENV_SERVER: &str = "SCENETHESIS_LLM_SERVER";
/// The default base URL (OpenAI).
pub const DEFAULT_BASE_URL: &str = "https://api.openai.com/v1";

/// An API key. It prints as `***` in `Debug` and has no `Display`, so it cannot reach logs,
/// error messages or reports by accident.
#[derive(Clone, PartialEq, Eq)]
pub struct ApiKey(String);

impl ApiKey {
    /// Wraps a key.
    pub fn new(key: impl Into<String>) -> Self {
        Self(key.into())
    }

    /// The key itself, for the `Authorization` header only.
    pub fn expose(&self) -> &str {
        &self.0
    }

    /// `text` with the key replaced by `***`: for anything a server sends back (error bodies
    /// and model text may echo the key), before it is shortened or shown. Besides the key
    /// itself, a reshaped echo is masked: any run of the text that spells
    /// [`crate::min_masked_run`] or more consecutive letters and digits of the key, whatever
    /// separators (spaces, newlines, hyphens, punctuation) or letter case it is written with
    /// (keys of fewer than [`crate::MIN_RESHAPED_KEY_CHARS`] letters and digits only whole).
    pub fn mask<'a>(&self, text: &'a str) -> std::borrow::Cow<'a, str> {
        crate::mask::mask_key(&self.0, text)
    }
}

impl fmt::Debug for ApiKey {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("ApiKey(***)")
    }
}

/// Largest client configuration file (`--llm-config`) read, in bytes (1 MiB).
pub const MAX_CONFIG_BYTES: u64 = 1024 * 1024;

/// Why a configuration could not be resolved.
#[derive(Debug, thiserror::Error)]
pub enum ConfigError {
    /// The configuration file could not be read.
    #[error("cannot read the client configuration file {}", path.display())]
    Read {
        /// The file.
        path: PathBuf,
        /// The I/O error.
        #[source]
        source: std::io::Error,
    },
    /// The configuration file is not valid TOML of the expected shape.
    #[error("client configuration file {}: {message}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// The parser's message (names the field).
        message: String,
    },
    /// A value is out of range or malformed.
    #[error("client configuration `{field}` (from {origin}): {message}")]
    Invalid {
        /// The field.
        field: &'static str,
        /// Where the value came from (a flag, an environment variable or a file).
        origin: String,
        /// What was expected.
        message: String,
    },
    /// A model an operation needs is not configured.
    #[error(
        "no {what} model configured: pass {flag}, set {env} or `{field}` in the configuration file"
    )]
    MissingModel {
        /// Which model (`language`, `vision-language`, `image`, `embedding`).
        what: &'static str,
        /// The flag.
        flag: &'static str,
        /// The environment variable.
        env: &'static str,
        /// The configuration-file field.
        field: &'static str,
    },
}

/// Settings given on the command line (or by a program); each set field wins over the
/// environment and the file.
#[derive(Debug, Clone, Default, PartialEq, Eq)]
pub struct Overrides {
    /// Base URL.
    pub base_url: Option<String>,
    /// API key.
    pub api_key: Option<ApiKey>,
    /// Language model.
    pub llm_model: Option<String>,
    /// Vision-language model.
    pub vlm_model: Option<String>,
    /// Image model.
    pub image_model: Option<String>,
    /// Embedding model.
    pub embedding_model: Option<String>,
    /// Per-request timeout.
    pub timeout: Option<Duration>,
}

/// The TOML configuration file's fields (all optional).
#[derive(Debug, Default, Deserialize)]
#[serde(deny_unknown_fields)]
struct FileConfig {
    base_url: Option<String>,
    api_key: Option<String>,
    /// Name of an environment variable holding the key (keeps the key out of the file).
    api_key_env: Option<String>,
    llm_model: Option<String>,
    vlm_model: Option<String>,
    image_model: Option<String>,
    embedding_model: Option<String>,
    timeout_secs: Option<f64>,
    max_attempts: Option<u32>,
    budget_secs: Option<f64>,
    backoff_ms: Option<u64>,
    server: Option<String>,
    stream: Option<bool>,
}

/// The server software behind an OpenAI-compatible endpoint, where it needs request fields
/// beyond OpenAI's own.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub enum ServerKind {
    /// Any OpenAI-compatible server: OpenAI's request fields only.
    #[default]
    OpenAiCompatible,
    /// vLLM: structured requests also send `structured_outputs: {"json": schema}`, the field
    /// vLLM 0.12+ constrains decoding with (it replaced `guided_json`).
    Vllm,
}

impl ServerKind {
    /// Parses a configured name: `openai` (or `openai-compatible`, `ollama`, `llama.cpp`,
    /// `lmstudio`: no extras) or `vllm`.
    pub fn parse(name: &str) -> Option<Self> {
        match name.trim().to_ascii_lowercase().as_str() {
            "vllm" => Some(Self::Vllm),
            "openai" | "openai-compatible" | "ollama" | "llama.cpp" | "llamacpp" | "lmstudio" => {
                Some(Self::OpenAiCompatible)
            }
            _ => None,
        }
    }
}

/// A resolved client configuration. Its `Debug` output shows the base URL without
/// credentials and the key as `***`.
#[derive(Clone, PartialEq)]
pub struct ClientConfig {
    /// Base URL ending before `/chat/completions` etc. (`http://127.0.0.1:8000/v1`).
    pub base_url: String,
    /// API key, if the endpoint needs one.
    pub api_key: Option<ApiKey>,
    /// Language model.
    pub llm_model: Option<String>,
    /// Vision-language model (the language model when unset).
    pub vlm_model: Option<String>,
    /// Image model.
    pub image_model: Option<String>,
    /// Embedding model.
    pub embedding_model: Option<String>,
    /// Time limit of one HTTP request (connect to last byte).
    pub timeout: Duration,
    /// Attempts per request on transient failures (HTTP 429/5xx, timeouts, refused connections).
    pub max_attempts: u32,
    /// Bound on the total time one call may take, retries and waits included.
    pub budget: Duration,
    /// First backoff delay; doubled after each retry unless the server sends `Retry-After`.
    pub backoff: Duration,
    /// The server software, for request fields beyond OpenAI's (`server` in the file,
    /// `SCENETHESIS_LLM_SERVER`).
    pub server: ServerKind,
    /// Largest answer body read, in bytes ([`crate::MAX_RESPONSE_BYTES`] unless lowered).
    pub max_response_bytes: usize,
    /// Ask for long chat answers (no `max_tokens`, or at least [`crate::STREAM_MIN_TOKENS`])
    /// as a stream (`stream: true`), so progress shows while they arrive and a timeout says how
    /// much had arrived (`stream` in the file; on by default). A server that ignores it and
    /// answers whole works as well.
    pub stream: bool,
}

impl fmt::Debug for ClientConfig {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("ClientConfig")
            .field("base_url", &self.endpoint_label())
            .field("api_key", &self.api_key)
            .field("llm_model", &self.llm_model)
            .field("vlm_model", &self.vlm_model)
            .field("image_model", &self.image_model)
            .field("embedding_model", &self.embedding_model)
            .field("timeout", &self.timeout)
            .field("max_attempts", &self.max_attempts)
            .field("budget", &self.budget)
            .field("backoff", &self.backoff)
            .field("server", &self.server)
            .field("max_response_bytes", &self.max_response_bytes)
            .field("stream", &self.stream)
            .finish()
    }
}

impl ClientConfig {
    /// A configuration for `base_url` with defaults: no key, no models, 120 s timeout,
    /// 4 attempts, 300 s budget, 500 ms first backoff, long answers streamed.
    pub fn new(base_url: impl Into<String>) -> Self {
        Self {
            base_url: base_url.into().trim_end_matches('/').to_string(),
            api_key: None,
            llm_model: None,
            vlm_model: None,
            image_model: None,
            embedding_model: None,
            timeout: Duration::from_secs(120),
            max_attempts: 4,
            budget: Duration::from_secs(300),
            backoff: Duration::from_millis(500),
            server: ServerKind::OpenAiCompatible,
            max_response_bytes: crate::MAX_RESPONSE_BYTES,
            stream: true,
        }
    }

    /// Resolves flags over the process environment over `file` (when given).
    pub fn resolve(overrides: &Overrides, file: Option<&Path>) -> Result<Self, ConfigError> {
        Self::resolve_with(overrides, &|name| std::env::var(name).ok(), file)
    }

    /// Resolves flags over `env` (a lookup of environment variables) over `file`.
    pub fn resolve_with(
        overrides: &Overrides,
        env: &dyn Fn(&str) -> Option<String>,
        file: Option<&Path>,
    ) -> Result<Self, ConfigError> {
        let file_config = match file {
            Some(path) => {
                let read_err = |source| ConfigError::Read {
                    path: path.to_path_buf(),
                    source,
                };
                let bytes = scenethesis_scene_graph::read_bounded(path, MAX_CONFIG_BYTES)
                    .map_err(read_err)?;
                let text = String::from_utf8(bytes).map_err(|_| {
                    read_err(std::io::Error::new(
                        std::io::ErrorKind::InvalidData,
                        "is not UTF-8 text",
                    ))
                })?;
                toml::from_str::<FileConfig>(&text).map_err(|e| ConfigError::Parse {
                    path: path.to_path_buf(),
                    message: e.message().to_string(),
                })?
            }
            None => FileConfig::default(),
        };
        let env = |name: &str| env(name).filter(|v| !v.trim().is_empty());
        let file_origin = || file.map_or_else(String::new, |p| format!("file {}", p.display()));

        let base_url = overrides
            .base_url
            .clone()
            .or_else(|| env(ENV_BASE_URL))
            .or(file_config.base_url)
            .unwrap_or_else(|| DEFAULT_BASE_URL.to_string());
        if !(base_url.starts_with("http://") || base_url.starts_with("https://")) {
            return Err(ConfigError::Invalid {
                field: "base_url",
                origin: "flag, OPENAI_BASE_URL or file".to_string(),
                message: format!("expected an http:// or https:// URL, found `{base_url}`"),
            });
        }
        let mut config = Self::new(base_url);
        let file_key = match (&file_config.api_key_env, file_config.api_key) {
            (Some(var), _) => env(var),
            (None, key) => key,
        };
        config.api_key = overrides
            .api_key
            .clone()
            .or_else(|| env(ENV_API_KEY).map(ApiKey::new))
            .or_else(|| file_key.map(ApiKey::new));
        let pick = |flag: &Option<String>, var: &str, file: Option<String>| {
            flag.clone().or_else(|| env(var)).or(file)
        };
        config.llm_model = pick(&overrides.llm_model, ENV_LLM_MODEL, file_config.llm_model);
        config.vlm_model = pick(&overrides.vlm_model, ENV_VLM_MODEL, file_config.vlm_model);
        config.image_model = pick(
            &overrides.image_model,
            ENV_IMAGE_MODEL,
            file_config.image_model,
        );
        config.embedding_model = pick(
            &overrides.embedding_model,
            ENV_EMBEDDING_MODEL,
            file_config.embedding_model,
        );
        let secs = |field: &'static str, v: f64| {
            if v.is_finite() && v > 0.0 && v < 86_400.0 {
                Ok(Duration::from_secs_f64(v))
            } else {
                Err(ConfigError::Invalid {
                    field,
                    origin: file_origin(),
                    message: format!("expected seconds in (0, 86400), found {v}"),
                })
            }
        };
        if let Some(t) = overrides.timeout {
            config.timeout = t;
        } else if let Some(v) = file_config.timeout_secs {
            config.timeout = secs("timeout_secs", v)?;
        }
        if let Some(v) = file_config.budget_secs {
            config.budget = secs("budget_secs", v)?;
        }
        if let Some(n) = file_config.max_attempts {
            if n == 0 {
                return Err(ConfigError::Invalid {
                    field: "max_attempts",
                    origin: file_origin(),
                    message: "expected at least 1".to_string(),
                });
            }
            config.max_attempts = n;
        }
        if let Some(ms) = file_config.backoff_ms {
            config.backoff = Duration::from_millis(ms);
        }
        if let Some(stream) = file_config.stream {
            config.stream = stream;
        }
        let (server, origin) = match env(ENV_SERVER) {
            Some(name) => (Some(name), ENV_SERVER.to_string()),
            None => (file_config.server, file_origin()),
        };
        if let Some(name) = server {
            config.server = ServerKind::parse(&name).ok_or_else(|| ConfigError::Invalid {
                field: "server",
                origin,
                message: format!(
                    "expected `vllm` or `openai` (also ollama, llama.cpp, lmstudio), found `{name}`"
                ),
            })?;
        }
        Ok(config)
    }

    /// The language model, or an error saying how to configure one.
    pub fn require_llm(&self) -> Result<&str, ConfigError> {
        self.llm_model.as_deref().ok_or(ConfigError::MissingModel {
            what: "language",
            flag: "--llm-model",
            env: ENV_LLM_MODEL,
            field: "llm_model",
        })
    }

    /// The vision-language model (the language model when none is set), or an error.
    pub fn require_vlm(&self) -> Result<&str, ConfigError> {
        self.vlm_model
            .as_deref()
            .or(self.llm_model.as_deref())
            .ok_or(ConfigError::MissingModel {
                what: "vision-language",
                flag: "--vlm-model",
                env: ENV_VLM_MODEL,
                field: "vlm_model",
            })
    }

    /// The image model, or an error.
    pub fn require_image(&self) -> Result<&str, ConfigError> {
        self.image_model
            .as_deref()
            .ok_or(ConfigError::MissingModel {
                what: "image",
                flag: "--image-model",
                env: ENV_IMAGE_MODEL,
                field: "image_model",
            })
    }

    /// The embedding model, or an error.
    pub fn require_embedding(&self) -> Result<&str, ConfigError> {
        self.embedding_model
            .as_deref()
            .ok_or(ConfigError::MissingModel {
                what: "embedding",
                flag: "--embedding-model",
                env: ENV_EMBEDDING_MODEL,
                field: "embedding_model",
            })
    }

    /// The base URL without credentials or query, for logs, errors and reports.
    pub fn endpoint_label(&self) -> String {
        redact_url(&self.base_url)
    }
}

/// Removes user information (`user:pass@`) and the query string from a URL.
pub fn redact_url(url: &str) -> String {
    let (scheme, rest) = match url.split_once("://") {
        Some((s, r)) => (Some(s), r),
        None => (None, url),
    };
    let rest = rest.split(['?', '#']).next().unwrap_or("");
    let (authority, path) = match rest.find('/') {
        Some(i) => (&rest[..i], &rest[i..]),
        None => (rest, ""),
    };
    let host = authority.rsplit_once('@').map_or(authority, |(_, h)| h);
    match scheme {
        Some(s) => format!("{s}://{host}{path}"),
        None => format!("{host}{path}"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn env_of(pairs: &[(&str, &str)]) -> impl Fn(&str) -> Option<String> {
        let map: HashMap<String, String> = pairs
            .iter()
            .map(|(k, v)| (k.to_string(), v.to_string()))
            .collect();
        move |k| map.get(k).cloned()
    }

    #[test]
    fn flags_over_env_over_file() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("llm.toml");
        std::fs::write(
            &file,
            "base_url = \"http://file:1/v1\"\napi_key = \"file-key\"\nllm_model = \"file-llm\"\n\
             vlm_model = \"file-vlm\"\nimage_model = \"file-img\"\ntimeout_secs = 7.5\n\
             max_attempts = 2\nbudget_secs = 30\n",
        )
        .unwrap();
        let env = env_of(&[
            (ENV_BASE_URL, "http://env:2/v1/"),
            (ENV_LLM_MODEL, "env-llm"),
            (ENV_VLM_MODEL, ""),
        ]);
        let flags = Overrides {
            llm_model: Some("flag-llm".into()),
            ..Overrides::default()
        };
        let c = ClientConfig::resolve_with(&flags, &env, Some(&file)).unwrap();
        assert_eq!(c.base_url, "http://env:2/v1");
        assert_eq!(c.llm_model.as_deref(), Some("flag-llm"));
        assert_eq!(
            c.vlm_model.as_deref(),
            Some("file-vlm"),
            "empty env is unset"
        );
        assert_eq!(c.image_model.as_deref(), Some("file-img"));
        assert_eq!(c.api_key, Some(ApiKey::new("file-key")));
        assert_eq!(c.timeout, Duration::from_millis(7500));
        assert_eq!((c.max_attempts, c.budget), (2, Duration::from_secs(30)));
        assert!(c.require_embedding().is_err());
    }

    #[test]
    fn key_never_prints() {
        let mut c = ClientConfig::new("https://user:secret-key@example.test/v1?key=secret-key");
        c.api_key = Some(ApiKey::new("secret-key"));
        let shown = format!("{c:?} {}", c.endpoint_label());
        assert!(!shown.contains("secret-key"), "{shown}");
        assert_eq!(c.endpoint_label(), "https://example.test/v1");
    }

    #[test]
    fn file_errors_name_file_and_field() {
        let dir = tempfile::tempdir().unwrap();
        let file = dir.path().join("bad.toml");
        std::fs::write(&file, "llm_modle = \"x\"\n").unwrap();
        let err = ClientConfig::resolve_with(&Overrides::default(), &env_of(&[]), Some(&file))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("bad.toml") && err.contains("llm_modle"),
            "{err}"
        );
        std::fs::write(&file, "max_attempts = 0\n").unwrap();
        let err = ClientConfig::resolve_with(&Overrides::default(), &env_of(&[]), Some(&file))
            .unwrap_err()
            .to_string();
        assert!(
            err.contains("max_attempts") && err.contains("at least 1"),
            "{err}"
        );
        let flags = Overrides {
            base_url: Some("localhost:8000".into()),
            ..Overrides::default()
        };
        let err = ClientConfig::resolve_with(&flags, &env_of(&[]), None).unwrap_err();
        assert!(err.to_string().contains("http:// or https://"), "{err}");
        let missing = ClientConfig::new("http://x").require_llm().unwrap_err();
        assert_eq!(
            missing.to_string(),
            "no language model configured: pass --llm-model, set SCENETHESIS_LLM_MODEL or `llm_model` in the configuration file"
        );
    }
}
