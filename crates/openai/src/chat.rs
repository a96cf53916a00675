//! Chat completions (`/chat/completions`) with text and image parts and structured output.

use std::sync::atomic::{AtomicU8, Ordering};
use std::sync::Arc;

use scenethesis_models::{
    extract_json, ChatModel, ChatRequest, ChatResponse, ContentPart, JsonSchema, Message,
    ProviderError, ProviderErrorKind, Role, SchemaViolation, TokenUsage, UsageMeter,
};
use serde_json::{json, Map, Value};

use crate::config::ServerKind;
use crate::http::{Answered, Body, On5xx, Transport};
use crate::message::shorten;
use crate::stream::{Streamed, STREAM_MIN_TOKENS};

const PATH: &str = "/chat/completions";

/// How a structured answer is requested, most constrained first.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
#[repr(u8)]
pub enum OutputFormat {
    /// `response_format: {type: json_schema, json_schema: {name, schema, strict}}`.
    JsonSchema = 0,
    /// `response_format: {type: json_object, schema}` plus the schema in the instructions
    /// (llama-cpp-python enforces a `schema` given here).
    JsonObject = 1,
    /// No `response_format`; the schema in the instructions only.
    Plain = 2,
}

impl OutputFormat {
    fn from_u8(v: u8) -> Self {
        match v {
            0 => Self::JsonSchema,
            1 => Self::JsonObject,
            _ => Self::Plain,
        }
    }

    fn label(self) -> &'static str {
        match self {
            Self::JsonSchema => "json_schema",
            Self::JsonObject => "json_object",
            Self::Plain => "a plain instruction",
        }
    }
}

/// A chat model behind an OpenAI-compatible `/chat/completions` endpoint.
///
/// Structured requests try `json_schema`, then `json_object`, then a plain instruction,
/// moving on whenever the server rejects a format (HTTP 400, 422, 501, or 500 with a message
/// about the format; other 5xx answers are retried as server failures) and remembering the
/// format that worked for later calls. Every structured answer is validated locally; an
/// invalid one gets one repair round that quotes the violations, then fails with
/// [`ProviderErrorKind::Schema`].
#[derive(Debug)]
pub struct OpenAiChat {
    transport: Arc<Transport>,
    model: String,
    meter: UsageMeter,
    first_format: AtomicU8,
}

impl OpenAiChat {
    pub(crate) fn new(transport: Arc<Transport>, model: String) -> Self {
        let meter = UsageMeter::new(transport.config().endpoint_label(), model.clone());
        Self {
            transport,
            model,
            meter,
            first_format: AtomicU8::new(OutputFormat::JsonSchema as u8),
        }
    }

    /// Starts structured requests at `format` (skipping more constrained ones), for servers
    /// known not to support them (LM Studio has no `json_object`; old servers neither).
    pub fn with_first_format(self, format: OutputFormat) -> Self {
        self.first_format.store(format as u8, Ordering::Relaxed);
        self
    }

    /// The model name.
    pub fn model(&self) -> &str {
        &self.model
    }

    /// The format structured requests currently start with.
    pub fn first_format(&self) -> OutputFormat {
        OutputFormat::from_u8(self.first_format.load(Ordering::Relaxed))
    }

    /// Requests, retries and tokens of this model so far.
    pub fn meter(&self) -> &UsageMeter {
        &self.meter
    }

    fn error(&self, kind: ProviderErrorKind) -> ProviderError {
        ProviderError::new(self.transport.label(PATH), self.model.clone(), kind)
    }

    /// Whether `request` is asked for as a stream: when the configuration allows it and its
    /// answer may be long (no `max_tokens`, or at least [`STREAM_MIN_TOKENS`]).
    fn streams(&self, request: &ChatRequest) -> bool {
        self.transport.config().stream && request.max_tokens.is_none_or(|n| n >= STREAM_MIN_TOKENS)
    }

    /// One completion: sends the body (streamed when it asks for a stream), returns the answer
    /// with the API key masked in all of it (a server or a model may echo the key). A lenient
    /// structured request keeps the part of a stream that arrived before a timeout or a cut
    /// connection, marked as cut off.
    fn complete(
        &self,
        request: &ChatRequest,
        body: &Value,
        on_5xx: On5xx,
    ) -> Result<Completion, ProviderError> {
        if body.get("stream") != Some(&Value::Bool(true)) {
            let answer =
                self.transport
                    .send(PATH, &self.model, Body::Json(body), on_5xx, &self.meter)?;
            return self.completion_of_body(&answer.body);
        }
        let keep_partial = request.lenient && request.schema.is_some();
        let answered = self.transport.send_streaming(
            PATH,
            &self.model,
            body,
            on_5xx,
            &self.meter,
            keep_partial,
        )?;
        match answered {
            Answered::Body(answer) => self.completion_of_body(&answer.body),
            Answered::Streamed(streamed) => self.completion_of_stream(streamed),
        }
    }

    /// The completion of an assembled stream, masked.
    fn completion_of_stream(&self, streamed: Streamed) -> Result<Completion, ProviderError> {
        if streamed.text.is_empty() {
            if let Some(refusal) = &streamed.refusal {
                return Err(self.error(ProviderErrorKind::Malformed {
                    message: format!(
                        "the model refused: {}",
                        shorten(&self.transport.mask(refusal))
                    ),
                    source: None,
                }));
            }
        }
        self.meter.record_tokens(streamed.usage);
        let interrupted = streamed
            .interrupted
            .is_some()
            .then(|| self.transport.mask(&streamed.interruption_message()));
        Ok(Completion {
            text: self.transport.mask(&streamed.text),
            model: streamed
                .model
                .as_deref()
                .map_or_else(|| self.model.clone(), |m| self.transport.mask(m)),
            tokens: streamed.usage,
            cut_off: interrupted.is_some() || streamed.finish_reason.as_deref() == Some("length"),
            interrupted,
        })
    }

    /// The completion of an ordinary JSON answer body, masked.
    fn completion_of_body(&self, body: &[u8]) -> Result<Completion, ProviderError> {
        let masked = self.transport.masked(body);
        let value: Value = serde_json::from_str(&masked).map_err(|e| {
            self.error(ProviderErrorKind::Malformed {
                message: format!(
                    "expected a JSON chat completion, found `{}`",
                    shorten(&masked)
                ),
                source: Some(Box::new(e)),
            })
        })?;
        let message = value.pointer("/choices/0/message");
        // Masked again once decoded: JSON escapes can spell the key in the raw body otherwise.
        let text = match message.and_then(|m| m.get("content")) {
            Some(Value::String(s)) => self.transport.mask(s),
            Some(Value::Array(parts)) => parts
                .iter()
                .filter_map(|p| p.get("text").and_then(Value::as_str))
                .map(|t| self.transport.mask(t))
                .collect::<Vec<_>>()
                .join(""),
            _ => {
                let refusal = message
                    .and_then(|m| m.get("refusal"))
                    .and_then(Value::as_str);
                return Err(self.error(ProviderErrorKind::Malformed {
                    message: match refusal {
                        Some(r) => {
                            format!("the model refused: {}", shorten(&self.transport.mask(r)))
                        }
                        None => format!(
                            "expected `choices[0].message.content` text, found `{}`",
                            shorten(&value.to_string())
                        ),
                    },
                    source: None,
                }));
            }
        };
        let tokens = TokenUsage {
            prompt_tokens: value
                .pointer("/usage/prompt_tokens")
                .and_then(Value::as_u64)
                .unwrap_or(0),
            completion_tokens: value
                .pointer("/usage/completion_tokens")
                .and_then(Value::as_u64)
                .unwrap_or(0),
        };
        self.meter.record_tokens(tokens);
        let model = value
            .get("model")
            .and_then(Value::as_str)
            .unwrap_or(&self.model)
            .to_string();
        let cut_off = value.pointer("/choices/0/finish_reason") == Some(&json!("length"));
        Ok(Completion {
            text,
            model,
            tokens,
            cut_off,
            interrupted: None,
        })
    }

    fn body(
        &self,
        request: &ChatRequest,
        messages: &[Message],
        format: Option<OutputFormat>,
    ) -> Value {
        let mut wire: Vec<Value> = Vec::with_capacity(messages.len() + 1);
        if let (Some(schema), Some(f)) = (&request.schema, format) {
            if f != OutputFormat::JsonSchema {
                wire.push(json!({"role": "system", "content": schema_instruction(schema)}));
            }
        }
        wire.extend(messages.iter().map(message_json));
        let mut body = Map::new();
        body.insert("model".into(), json!(self.model));
        body.insert("messages".into(), Value::Array(wire));
        if let Some(t) = request.temperature {
            body.insert("temperature".into(), json!(t));
        }
        if let Some(n) = request.max_tokens {
            body.insert("max_tokens".into(), json!(n));
        }
        if let Some(s) = request.seed {
            body.insert("seed".into(), json!(s));
        }
        if self.streams(request) {
            body.insert("stream".into(), json!(true));
            body.insert("stream_options".into(), json!({"include_usage": true}));
        }
        if let (Some(schema), Some(f)) = (&request.schema, format) {
            match f {
                OutputFormat::JsonSchema => {
                    body.insert(
                        "response_format".into(),
                        json!({"type": "json_schema", "json_schema": {
                            "name": schema.name,
                            "schema": schema.schema,
                            "strict": is_strict_compatible(&schema.schema),
                        }}),
                    );
                    if self.transport.config().server == ServerKind::Vllm {
                        body.insert("structured_outputs".into(), json!({"json": schema.schema}));
                    }
                }
                OutputFormat::JsonObject => {
                    body.insert(
                        "response_format".into(),
                        json!({"type": "json_object", "schema": schema.schema}),
                    );
                }
                OutputFormat::Plain => {}
            }
        }
        Value::Object(body)
    }

    /// A structured answer: asked in the most constrained output format the server accepts
    /// ([`Self::formatted_answer`]), checked against `schema`, and repaired once when it
    /// fails the check (unless lenient and cut off, when the part received is kept).
    fn structured(
        &self,
        request: &ChatRequest,
        schema: &JsonSchema,
    ) -> Result<ChatResponse, ProviderError> {
        let mut notes = Vec::new();
        let mut usage = TokenUsage::default();
        let (answer, format) = self.formatted_answer(request, &mut notes, &mut usage)?;
        let FormattedAnswer {
            text,
            model,
            cut_off,
        } = answer;
        let problem = match check(schema, &text) {
            Ok(json) => {
                return Ok(ChatResponse {
                    text,
                    json: Some(json),
                    model,
                    usage,
                    notes,
                })
            }
            Err(problem) => problem,
        };
        if let (true, Some(why)) = (request.lenient, &cut_off) {
            // Cut off by max_tokens (or by a timeout or a closed connection): a repair round
            // would be cut off again.
            notes.push(if why.is_empty() {
                format!(
                    "the answer was cut off at max_tokens ({}) and {}",
                    request
                        .max_tokens
                        .map_or("the server's limit".to_string(), |n| n.to_string()),
                    problem.summary()
                )
            } else {
                format!("the part received {}", problem.summary())
            });
            return Ok(lenient_response(text, model, usage, notes));
        }
        let failed = Failed {
            text,
            problem,
            format,
        };
        self.repair(request, schema, failed, notes, usage)
    }

    /// The first answer, in the most constrained output format the server accepts: a format
    /// the server rejects is noted, remembered for later calls, and the next less constrained
    /// one tried.
    fn formatted_answer(
        &self,
        request: &ChatRequest,
        notes: &mut Vec<String>,
        usage: &mut TokenUsage,
    ) -> Result<(FormattedAnswer, OutputFormat), ProviderError> {
        let mut format = self.first_format();
        loop {
            let on_5xx = if format == OutputFormat::Plain {
                On5xx::Retry
            } else {
                On5xx::RetryUnlessAboutFormat
            };
            let body = self.body(request, &request.messages, Some(format));
            match self.complete(request, &body, on_5xx) {
                Ok(c) => {
                    *usage += c.tokens;
                    notes.extend(c.interruption_note());
                    let answer = FormattedAnswer {
                        text: c.text,
                        model: c.model,
                        cut_off: c.interrupted.or(c.cut_off.then(String::new)),
                    };
                    return Ok((answer, format));
                }
                Err(e) if format != OutputFormat::Plain && rejects_format(&e) => {
                    let next = OutputFormat::from_u8(format as u8 + 1);
                    let note = format!(
                        "{} rejected response format {} ({}); using {}",
                        e.endpoint,
                        format.label(),
                        e.kind,
                        next.label()
                    );
                    tracing::info!(model = %self.model, "{note}");
                    notes.push(note);
                    // Remember for later calls (only ever moves to less constrained formats).
                    self.first_format.fetch_max(next as u8, Ordering::Relaxed);
                    format = next;
                }
                Err(e) => return Err(e),
            }
        }
    }

    /// One repair round quoting what was wrong with the `failed` answer; a second failure is
    /// an error, or the lenient answer with a note.
    fn repair(
        &self,
        request: &ChatRequest,
        schema: &JsonSchema,
        failed: Failed,
        mut notes: Vec<String>,
        mut usage: TokenUsage,
    ) -> Result<ChatResponse, ProviderError> {
        let Failed {
            text,
            problem,
            format,
        } = failed;
        notes.push(format!("answer repaired once: {}", problem.summary()));
        let mut messages = request.messages.clone();
        messages.push(Message::assistant(text));
        messages.push(Message::user(format!(
            "Your answer {}. Reply again with only the corrected JSON value, satisfying the \
             schema `{}`.",
            problem.summary(),
            schema.name
        )));
        // The server accepted this format already: a 5xx now is a server failure.
        let repaired = self.complete(
            request,
            &self.body(request, &messages, Some(format)),
            On5xx::Retry,
        )?;
        notes.extend(repaired.interruption_note());
        let Completion {
            text,
            model,
            tokens,
            ..
        } = repaired;
        usage += tokens;
        match check(schema, &text) {
            Ok(json) => Ok(ChatResponse {
                text,
                json: Some(json),
                model,
                usage,
                notes,
            }),
            Err(problem) if request.lenient => {
                notes.push(format!(
                    "the answer {} (after one repair round)",
                    problem.summary()
                ));
                Ok(lenient_response(text, model, usage, notes))
            }
            Err(Problem::NotJson) => Err(self.error(ProviderErrorKind::Malformed {
                message: format!(
                    "expected a JSON value for schema `{}` (after one repair round), found `{}`",
                    schema.name,
                    shorten(&text)
                ),
                source: None,
            })),
            Err(Problem::Violations(v)) => Err(self.error(ProviderErrorKind::Schema {
                schema: schema.name.clone(),
                violation: v.into_iter().next().expect("at least one violation"),
            })),
        }
    }
}

/// The first answer of a structured request.
struct FormattedAnswer {
    text: String,
    model: String,
    /// Why it was cut off: empty for `max_tokens`, else the interruption; `None` when whole.
    cut_off: Option<String>,
}

/// An answer that failed the schema check, with the format it was asked in.
struct Failed {
    text: String,
    problem: Problem,
    format: OutputFormat,
}

/// One completion's answer.
struct Completion {
    /// The answer text.
    text: String,
    /// The model that answered.
    model: String,
    /// Tokens it consumed.
    tokens: TokenUsage,
    /// Whether the server stopped it at `max_tokens` (`finish_reason: length`), or the stream
    /// stopped early.
    cut_off: bool,
    /// Why a streamed answer stopped before its end (a timeout or a closed connection, saying
    /// how much had arrived); only a lenient request gets such an answer.
    interrupted: Option<String>,
}

impl Completion {
    /// The note saying that the answer stopped early, if it did.
    fn interruption_note(&self) -> Option<String> {
        self.interrupted
            .as_ref()
            .map(|why| format!("the answer stopped early ({why}); the part received is used"))
    }
}

/// The answer to a lenient request whose answer breaks its schema: the JSON value as far as
/// it parses, for the caller to salvage.
fn lenient_response(
    text: String,
    model: String,
    usage: TokenUsage,
    notes: Vec<String>,
) -> ChatResponse {
    ChatResponse {
        json: extract_json(&text),
        text,
        model,
        usage,
        notes,
    }
}

/// What is wrong with a structured answer.
enum Problem {
    NotJson,
    Violations(Vec<SchemaViolation>),
}

impl Problem {
    fn summary(&self) -> String {
        match self {
            Self::NotJson => "is not valid JSON".to_string(),
            Self::Violations(v) => {
                let shown: Vec<String> = v.iter().take(5).map(ToString::to_string).collect();
                let more = if v.len() > 5 {
                    format!(" (and {} more)", v.len() - 5)
                } else {
                    String::new()
                };
                format!("violates the JSON schema: {}{more}", shown.join("; "))
            }
        }
    }
}

fn check(schema: &JsonSchema, text: &str) -> Result<Value, Problem> {
    let value = extract_json(text).ok_or(Problem::NotJson)?;
    let violations = schema.violations(&value);
    if violations.is_empty() {
        Ok(value)
    } else {
        Err(Problem::Violations(violations))
    }
}

/// Whether an error means the server does not accept the requested `response_format`: HTTP
/// 400, 422 or 501, or a 500 whose message speaks of the format (llama-cpp-python's answer to
/// `json_schema`).
fn rejects_format(e: &ProviderError) -> bool {
    match e.kind {
        ProviderErrorKind::Status { status, .. } => {
            matches!(status, 400 | 422 | 501) || (status == 500 && mentions_format(e))
        }
        _ => false,
    }
}

/// Whether a server's error message is about the output format.
fn mentions_format(e: &ProviderError) -> bool {
    match &e.kind {
        ProviderErrorKind::Status { message, .. } => crate::http::about_format(message),
        _ => false,
    }
}

/// The instruction that carries the schema when the server does not enforce it.
fn schema_instruction(schema: &JsonSchema) -> String {
    format!(
        "Answer with a single JSON value and nothing else (no prose, no Markdown). It must \
         satisfy this JSON schema named `{}`:\n{}",
        schema.name, schema.schema
    )
}

/// OpenAI's strict mode needs every object closed (`additionalProperties: false`) with every
/// property required.
fn is_strict_compatible(schema: &Value) -> bool {
    let Value::Object(map) = schema else {
        return true;
    };
    let is_object = match map.get("type") {
        Some(Value::String(t)) => t == "object",
        Some(Value::Array(ts)) => ts.iter().any(|t| t == "object"),
        _ => map.contains_key("properties"),
    };
    if is_object {
        if map.get("additionalProperties") != Some(&Value::Bool(false)) {
            return false;
        }
        let required: Vec<&str> = map
            .get("required")
            .and_then(Value::as_array)
            .map(|r| r.iter().filter_map(Value::as_str).collect())
            .unwrap_or_default();
        if let Some(Value::Object(props)) = map.get("properties") {
            if props.keys().any(|k| !required.contains(&k.as_str())) {
                return false;
            }
            if !props.values().all(is_strict_compatible) {
                return false;
            }
        }
    }
    map.get("items").is_none_or(is_strict_compatible)
}

fn message_json(message: &Message) -> Value {
    let role = match message.role {
        Role::System => "system",
        Role::User => "user",
        Role::Assistant => "assistant",
    };
    let text_only = message
        .content
        .iter()
        .all(|p| matches!(p, ContentPart::Text { .. }));
    // Plain string content for text: every server accepts it, not all accept part arrays.
    if text_only {
        return json!({"role": role, "content": message.joined_text()});
    }
    let parts: Vec<Value> = message
        .content
        .iter()
        .map(|p| match p {
            ContentPart::Text { text } => json!({"type": "text", "text": text}),
            ContentPart::Image { image } => {
                json!({"type": "image_url", "image_url": {"url": image.to_data_url()}})
            }
        })
        .collect();
    json!({"role": role, "content": parts})
}

impl ChatModel for OpenAiChat {
    fn name(&self) -> String {
        format!("openai-compatible/{}", self.model)
    }

    fn chat(&self, request: &ChatRequest) -> Result<ChatResponse, ProviderError> {
        match &request.schema {
            Some(schema) => self.structured(request, schema),
            None => {
                let body = self.body(request, &request.messages, None);
                let c = self.complete(request, &body, On5xx::Retry)?;
                Ok(ChatResponse {
                    text: c.text,
                    json: None,
                    model: c.model,
                    usage: c.tokens,
                    notes: Vec::new(),
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn strict_compatibility() {
        assert!(is_strict_compatible(&json!({
            "type": "object", "additionalProperties": false, "required": ["a"],
            "properties": {"a": {"type": "array", "items": {"type": "string"}}}})));
        assert!(!is_strict_compatible(&json!({
            "type": "object", "additionalProperties": false, "required": [],
            "properties": {"a": {"type": "string"}}})));
        assert!(!is_strict_compatible(&json!({
            "type": "object", "required": ["a"], "properties": {"a": {"type": "string"}}})));
        assert!(!is_strict_compatible(&json!({"type": "array", "items": {
            "type": "object", "properties": {"a": {}}}})));
    }

    #[test]
    fn text_messages_are_strings_and_images_are_parts() {
        let m = message_json(&Message::system("be brief"));
        assert_eq!(m, json!({"role": "system", "content": "be brief"}));
        let image =
            scenethesis_models::ImageData::from_bytes(vec![0xFF, 0xD8, 0xFF, 0x00], "t").unwrap();
        let m = message_json(&Message::user("what is this").with_image(image));
        assert_eq!(
            m["content"][0],
            json!({"type": "text", "text": "what is this"})
        );
        assert_eq!(
            m["content"][1]["image_url"]["url"],
            json!("data:image/jpeg;base64,/9j/AA==")
        );
    }
}
