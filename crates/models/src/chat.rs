//! Chat (and vision-language) models: messages with text and image parts, optional structured
//! output under a JSON schema.

use serde::{Deserialize, Serialize};
use serde_json::Value;

use crate::error::{ProviderError, ProviderErrorKind};
use crate::image::ImageData;
use crate::schema::JsonSchema;

/// Who speaks a message.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Role {
    /// Instructions to the model.
    System,
    /// The user's turn.
    User,
    /// A previous answer of the model.
    Assistant,
}

/// One part of a message.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "type", rename_all = "lowercase")]
pub enum ContentPart {
    /// Text.
    Text {
        /// The text.
        text: String,
    },
    /// An image (sent as a data URL).
    Image {
        /// The image.
        image: ImageData,
    },
}

/// A message: a role and its parts.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct Message {
    /// The speaker.
    pub role: Role,
    /// Text and image parts, in order.
    pub content: Vec<ContentPart>,
}

impl Message {
    /// A text-only message.
    pub fn text(role: Role, text: impl Into<String>) -> Self {
        Self {
            role,
            content: vec![ContentPart::Text { text: text.into() }],
        }
    }

    /// A system message.
    pub fn system(text: impl Into<String>) -> Self {
        Self::text(Role::System, text)
    }

    /// A user message.
    pub fn user(text: impl Into<String>) -> Self {
        Self::text(Role::User, text)
    }

    /// An assistant message.
    pub fn assistant(text: impl Into<String>) -> Self {
        Self::text(Role::Assistant, text)
    }

    /// Appends an image part.
    pub fn with_image(mut self, image: ImageData) -> Self {
        self.content.push(ContentPart::Image { image });
        self
    }

    /// The text parts joined by newlines.
    pub fn joined_text(&self) -> String {
        let texts: Vec<&str> = self
            .content
            .iter()
            .filter_map(|p| match p {
                ContentPart::Text { text } => Some(text.as_str()),
                ContentPart::Image { .. } => None,
            })
            .collect();
        texts.join("\n")
    }
}

/// A chat request.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChatRequest {
    /// The conversation so far.
    pub messages: Vec<Message>,
    /// When set, the answer must be a JSON value satisfying this schema.
    pub schema: Option<JsonSchema>,
    /// Sampling temperature (providers' default when unset); 0 for reproducible answers.
    pub temperature: Option<f32>,
    /// Upper bound on answer tokens.
    pub max_tokens: Option<u32>,
    /// Sampling seed, for providers that honour one.
    pub seed: Option<u64>,
    /// For a structured request: when the answer still breaks the schema after the repair
    /// round (or is not JSON at all, as an answer cut off by `max_tokens` is), hand it back
    /// instead of failing: [`ChatResponse::json`] is then the parsed value unchecked (or
    /// `None` when the text is not JSON) and [`ChatResponse::notes`] say what is wrong. The
    /// caller salvages what it can.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub lenient: bool,
}

impl ChatRequest {
    /// A free-text request.
    pub fn new(messages: Vec<Message>) -> Self {
        Self {
            messages,
            schema: None,
            temperature: Some(0.0),
            max_tokens: None,
            seed: None,
            lenient: false,
        }
    }

    /// A request whose answer must satisfy `schema`.
    pub fn structured(messages: Vec<Message>, schema: JsonSchema) -> Self {
        Self {
            schema: Some(schema),
            ..Self::new(messages)
        }
    }
}

/// Tokens a call consumed, as the provider reports them.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq, Serialize, Deserialize)]
pub struct TokenUsage {
    /// Tokens of the request.
    pub prompt_tokens: u64,
    /// Tokens of the answer.
    pub completion_tokens: u64,
}

impl std::ops::AddAssign for TokenUsage {
    fn add_assign(&mut self, rhs: Self) {
        self.prompt_tokens += rhs.prompt_tokens;
        self.completion_tokens += rhs.completion_tokens;
    }
}

/// A chat answer.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ChatResponse {
    /// The answer text.
    pub text: String,
    /// For a structured request: the parsed answer, valid under the request's schema (unless
    /// the request is [`ChatRequest::lenient`]).
    pub json: Option<Value>,
    /// The model that answered, as the provider names it.
    pub model: String,
    /// Tokens consumed (summed over fallback and repair rounds).
    pub usage: TokenUsage,
    /// Remarks on how the answer was obtained (format fallbacks, repair rounds).
    pub notes: Vec<String>,
}

/// A chat or vision-language model.
///
/// Implementations answer a [`ChatRequest`]; when the request carries a schema, the returned
/// [`ChatResponse::json`] must be `Some` and valid under it (implementations validate locally
/// with [`JsonSchema::validate`] and fail with [`crate::ProviderErrorKind::Schema`] otherwise).
pub trait ChatModel: Send + Sync {
    /// `provider/model`, e.g. `openai/gpt-4o`; recorded in reports and cache keys.
    fn name(&self) -> String;

    /// Answers the conversation.
    fn chat(&self, request: &ChatRequest) -> Result<ChatResponse, ProviderError>;
}

impl<M: ChatModel + ?Sized> ChatModel for &M {
    fn name(&self) -> String {
        (**self).name()
    }
    fn chat(&self, request: &ChatRequest) -> Result<ChatResponse, ProviderError> {
        (**self).chat(request)
    }
}

impl<M: ChatModel + ?Sized> ChatModel for Box<M> {
    fn name(&self) -> String {
        (**self).name()
    }
    fn chat(&self, request: &ChatRequest) -> Result<ChatResponse, ProviderError> {
        (**self).chat(request)
    }
}

/// Extracts the JSON value from a model's answer text: the whole text, else the content of a
/// fenced code block, else the outermost `{…}` or `[…]` span. Small models often wrap JSON in
/// prose or Markdown.
pub fn extract_json(text: &str) -> Option<Value> {
    let trimmed = text.trim();
    if let Ok(v) = serde_json::from_str(trimmed) {
        return Some(v);
    }
    if let Some(start) = trimmed.find("```") {
        let after = &trimmed[start + 3..];
        let body_start = after.find('\n').map_or(0, |i| i + 1);
        let body = &after[body_start..];
        if let Some(end) = body.find("```") {
            if let Ok(v) = serde_json::from_str(body[..end].trim()) {
                return Some(v);
            }
        }
    }
    for (open, close) in [('{', '}'), ('[', ']')] {
        if let (Some(a), Some(b)) = (trimmed.find(open), trimmed.rfind(close)) {
            if a < b {
                if let Ok(v) = serde_json::from_str(&trimmed[a..=b]) {
                    return Some(v);
                }
            }
        }
    }
    None
}

/// Checks an answer to `request` the way a client checks a live one: for a structured request
/// the JSON value must be present and satisfy the schema. A lenient request gets the answer
/// back with a note saying what is wrong; another gets [`ProviderErrorKind::Malformed`] or
/// [`ProviderErrorKind::Schema`]. Used on answers that did not come from a live check (replayed
/// from a response cache).
pub fn check_structured(
    request: &ChatRequest,
    mut response: ChatResponse,
) -> Result<ChatResponse, ProviderErrorKind> {
    let Some(schema) = &request.schema else {
        return Ok(response);
    };
    let problem = match &response.json {
        None => format!("is not a JSON value for schema `{}`", schema.name),
        Some(v) => match schema.violations(v) {
            violations if violations.is_empty() => return Ok(response),
            mut violations if !request.lenient => {
                return Err(ProviderErrorKind::Schema {
                    schema: schema.name.clone(),
                    violation: violations.swap_remove(0),
                })
            }
            violations => format!(
                "violates the schema `{}`: {} ({} violations)",
                schema.name,
                violations[0],
                violations.len()
            ),
        },
    };
    if !request.lenient {
        return Err(ProviderErrorKind::Malformed {
            message: format!("the recorded answer {problem}"),
            source: None,
        });
    }
    response.notes.push(format!("the answer {problem}"));
    Ok(response)
}

#[cfg(test)]
mod tests {
    use super::*;
    use serde_json::json;

    #[test]
    fn extracts_json_from_wrapped_answers() {
        assert_eq!(extract_json(" {\"a\":1} "), Some(json!({"a": 1})));
        assert_eq!(
            extract_json("Here you go:\n```json\n{\"a\": [1, 2]}\n```\nEnjoy"),
            Some(json!({"a": [1, 2]}))
        );
        assert_eq!(
            extract_json("Sure! {\"a\": {\"b\": true}} hope it helps"),
            Some(json!({"a": {"b": true}}))
        );
        assert_eq!(extract_json("no json here"), None);
        assert_eq!(extract_json("{\"a\": "), None);
    }

    #[test]
    fn message_helpers() {
        let m = Message::user("look")
            .with_image(ImageData::from_bytes(vec![0xFF, 0xD8, 0xFF, 0xDB], "t").unwrap());
        assert_eq!(m.content.len(), 2);
        assert_eq!(m.joined_text(), "look");
        let json = serde_json::to_value(&m).unwrap();
        assert_eq!(json["content"][1]["type"], "image");
        assert_eq!(json["content"][0], json!({"type": "text", "text": "look"}));
    }
}
