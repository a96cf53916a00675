//! Traits and exchange types for model providers, with no HTTP, GPU or async runtime, so that
//! both the stages that use models and the crates that implement them can depend on it.
//!
//! - [`ChatModel`]: chat and vision-language models; messages with text and image parts
//!   ([`ImageData`], PNG or JPEG, sent as data URLs); structured output under a [`JsonSchema`].
//! - [`ImageGenerator`] (generate and edit), [`Segmenter`] (box-prompted masks, each a
//!   [`Segment`]), [`DepthEstimator`] (metric depth, a [`DepthEstimate`]), [`TextEmbedder`];
//!   masks, depth maps and intrinsics are the `scenethesis-imagery` types every stage uses.
//! - [`ProviderError`]: every failure names the endpoint and the model.
//! - [`JsonSchema`]: a local validator for the schema subset the project emits, with JSON-pointer
//!   paths in its violations, so every structured answer is checked whatever the server claims.
//! - [`ResponseCache`] and [`Cached`]: answers recorded under the SHA-256 of the canonical
//!   request, so a run replays offline byte for byte.
//! - [`UsageMeter`]: requests, tokens and cache hits of a model, for `report.json`.
//!
//! ```
//! use scenethesis_models::{
//!     CacheMode, Cached, ChatModel, ChatRequest, ChatResponse, JsonSchema, Message,
//!     ProviderError, ResponseCache, TokenUsage, UsageMeter,
//! };
//! use serde_json::json;
//!
//! /// A model that names the longest word of the last message.
//! struct LongestWord;
//!
//! impl ChatModel for LongestWord {
//!     fn name(&self) -> String {
//!         "local/longest-word".into()
//!     }
//!     fn chat(&self, request: &ChatRequest) -> Result<ChatResponse, ProviderError> {
//!         let text = request.messages.last().map(|m| m.joined_text()).unwrap_or_default();
//!         let word = text.split_whitespace().max_by_key(|w| w.len()).unwrap_or("");
//!         let json = json!({ "word": word });
//!         Ok(ChatResponse {
//!             text: json.to_string(),
//!             json: Some(json),
//!             model: "longest-word".into(),
//!             usage: TokenUsage::default(),
//!             notes: vec![],
//!         })
//!     }
//! }
//!
//! let schema = JsonSchema::new(
//!     "word",
//!     json!({"type": "object", "required": ["word"], "properties": {"word": {"type": "string"}}}),
//! )?;
//! let request = ChatRequest::structured(vec![Message::user("a cozy reading nook")], schema.clone());
//!
//! let dir = std::env::temp_dir().join(format!("models-doc-{}", std::process::id()));
//! let meter = UsageMeter::new("local", "longest-word");
//! let recording = Cached::new(LongestWord, ResponseCache::open(&dir, CacheMode::ReadWrite)?);
//! let first = recording.chat(&request)?;
//! assert_eq!(first.json, Some(json!({"word": "reading"})));
//! schema.validate(first.json.as_ref().unwrap()).unwrap();
//!
//! // Replay without the model: the same answer, from the cache.
//! let replay = Cached::new(LongestWord, ResponseCache::open(&dir, CacheMode::ReplayOnly)?)
//!     .with_meter(meter.clone());
//! assert_eq!(replay.chat(&request)?, first);
//! assert_eq!(meter.snapshot().cache_hits, 1);
//! # std::fs::remove_dir_all(&dir).ok();
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```
#![warn(missing_docs)]

mod cache;
mod chat;
mod error;
mod image;
mod progress;
mod providers;
mod schema;
mod usage;

pub use cache::{
    canonical_json, sha256_hex, CacheMode, Cached, ResponseCache, MAX_CACHE_ENTRY_BYTES,
};
pub use chat::{
    check_structured, extract_json, ChatModel, ChatRequest, ChatResponse, ContentPart, Message,
    Role, TokenUsage,
};
pub use error::{grouped, BoxError, ProviderError, ProviderErrorKind};
pub use image::{ImageData, ImageError, ImageFormat};
pub use progress::{report_answer_progress, with_answer_listener, AnswerListener, AnswerProgress};
pub use providers::{
    cosine, BoxPrompt, DepthEstimate, DepthEstimator, GeneratedImage, ImageEditRequest,
    ImageGenerator, ImageRequest, Segment, Segmenter, TextEmbedder,
};
pub use schema::{JsonSchema, SchemaError, SchemaViolation};
pub use usage::{metered, UsageMeter, UsageReport};
