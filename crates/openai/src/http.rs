//! The HTTP transport: a reqwest client on a private current-thread tokio runtime, with
//! timeouts, retries on transient failures (honouring `Retry-After`) and a total time budget.

use std::time::{Duration, Instant};

use scenethesis_models::{ProviderError, ProviderErrorKind, TokenUsage, UsageMeter};
use serde_json::Value;

use crate::config::{redact_url, ClientConfig};
use crate::message::shorten;
use crate::stream::{read_events, Interruption, Streamed};

/// How a call treats HTTP 5xx answers.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum On5xx {
    /// Retry with backoff (the default).
    Retry,
    /// Retry, except when the message is about the output format: the caller then falls back
    /// to another request format (llama-cpp-python answers an unsupported `response_format`
    /// with HTTP 500).
    RetryUnlessAboutFormat,
}

/// A successful HTTP answer.
pub(crate) struct Answer {
    pub(crate) body: Vec<u8>,
}

/// A successful answer to a request that asked for a stream: the server streamed it, or
/// ignored `stream` and answered with an ordinary body.
pub(crate) enum Answered {
    /// An ordinary body.
    Body(Answer),
    /// An event stream, assembled; incomplete only when the caller keeps partial answers.
    Streamed(Streamed),
}

impl Answered {
    /// The body of an answer to a request that did not ask for a stream.
    fn into_body(self) -> Answer {
        match self {
            Self::Body(answer) => answer,
            Self::Streamed(_) => unreachable!("streams are read only when asked for"),
        }
    }
}

/// How a request reads a 2xx answer in `text/event-stream`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Events {
    /// Not streamed: every body is read whole.
    No,
    /// Assembled from its events; a stream cut short is retried like any transient failure.
    Whole,
    /// Assembled; a stream cut short (timeout, closed connection) after some of the answer
    /// arrived is returned as it is, for the caller to salvage, instead of being retried.
    KeepPartial,
}

/// What one attempt read.
enum Read {
    Body(Option<Vec<u8>>),
    Events(Streamed),
}

/// One part of a multipart form, rebuilt for every attempt.
#[derive(Clone)]
pub(crate) enum Part {
    Text(&'static str, String),
    File {
        name: &'static str,
        file_name: String,
        mime: &'static str,
        bytes: Vec<u8>,
    },
}

/// What a request sends.
pub(crate) enum Body<'a> {
    Json(&'a Value),
    Multipart(&'a [Part]),
}

/// The shared HTTP machinery of the clients.
pub(crate) struct Transport {
    config: ClientConfig,
    client: reqwest::Client,
    runtime: tokio::runtime::Runtime,
}

impl std::fmt::Debug for Transport {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Transport")
            .field("endpoint", &self.config.endpoint_label())
            .finish()
    }
}

/// Installs the ring crypto provider for rustls once per process (reqwest is built without a
/// provider of its own).
fn install_crypto_provider() {
    // An error means a provider is already installed, which is all we need.
    let _ = rustls::crypto::ring::default_provider().install_default();
}

impl Transport {
    pub(crate) fn new(config: ClientConfig) -> Result<Self, ProviderError> {
        install_crypto_provider();
        let endpoint = config.endpoint_label();
        let fail = |message: String, source: Option<scenethesis_models::BoxError>| {
            ProviderError::new(
                endpoint.clone(),
                "",
                ProviderErrorKind::Unreachable { message, source },
            )
        };
        let client = reqwest::Client::builder()
            .timeout(config.timeout)
            .connect_timeout(config.timeout.min(Duration::from_secs(30)))
            .build()
            .map_err(|e| {
                fail(
                    "cannot build the HTTP client".into(),
                    Some(Box::new(e.without_url())),
                )
            })?;
        let runtime = tokio::runtime::Builder::new_current_thread()
            .enable_all()
            .build()
            .map_err(|e| fail("cannot start the HTTP runtime".into(), Some(Box::new(e))))?;
        Ok(Self {
            config,
            client,
            runtime,
        })
    }

    pub(crate) fn config(&self) -> &ClientConfig {
        &self.config
    }

    /// The full URL of an API path (`/chat/completions`).
    pub(crate) fn url(&self, path: &str) -> String {
        format!("{}{}", self.config.base_url, path)
    }

    /// The URL of `path` without credentials, for messages.
    pub(crate) fn label(&self, path: &str) -> String {
        redact_url(&self.url(path))
    }

    /// Sends `body` to `path` and returns the body of a 2xx answer, retrying transient
    /// failures within the budget. Every attempt counts as a request on `meter`.
    pub(crate) fn send(
        &self,
        path: &str,
        model: &str,
        body: Body<'_>,
        on_5xx: On5xx,
        meter: &UsageMeter,
    ) -> Result<Answer, ProviderError> {
        Ok(self
            .post(path, model, body, on_5xx, meter, Events::No)?
            .into_body())
    }

    /// Sends `body` (which asks for `stream: true`) to `path`: a 2xx answer in
    /// `text/event-stream` is assembled from its events, any other is read whole. With
    /// `keep_partial`, a stream cut short after some of the answer arrived comes back as it is
    /// (see [`Events::KeepPartial`]).
    pub(crate) fn send_streaming(
        &self,
        path: &str,
        model: &str,
        body: &Value,
        on_5xx: On5xx,
        meter: &UsageMeter,
        keep_partial: bool,
    ) -> Result<Answered, ProviderError> {
        let events = if keep_partial {
            Events::KeepPartial
        } else {
            Events::Whole
        };
        self.post(path, model, Body::Json(body), on_5xx, meter, events)
    }

    fn post(
        &self,
        path: &str,
        model: &str,
        body: Body<'_>,
        on_5xx: On5xx,
        meter: &UsageMeter,
        events: Events,
    ) -> Result<Answered, ProviderError> {
        let url = self.url(path);
        let build = || {
            let mut request = self.client.post(&url);
            if let Some(key) = &self.config.api_key {
                request = request.bearer_auth(key.expose());
            }
            match &body {
                Body::Json(v) => request.json(v),
                Body::Multipart(parts) => request.multipart(form(parts)),
            }
        };
        self.with_retries(&self.label(path), model, on_5xx, meter, events, build)
    }

    /// Downloads `url` (an image an endpoint answered with).
    pub(crate) fn get(
        &self,
        url: &str,
        model: &str,
        meter: &UsageMeter,
    ) -> Result<Answer, ProviderError> {
        let build = || self.client.get(url);
        let endpoint = redact_url(url);
        Ok(self
            .with_retries(&endpoint, model, On5xx::Retry, meter, Events::No, build)?
            .into_body())
    }

    fn with_retries(
        &self,
        endpoint: &str,
        model: &str,
        on_5xx: On5xx,
        meter: &UsageMeter,
        events: Events,
        build: impl Fn() -> reqwest::RequestBuilder,
    ) -> Result<Answered, ProviderError> {
        let started = Instant::now();
        let budget = self.config.budget;
        let err = |kind| ProviderError::new(endpoint, model, kind);
        let mut backoff = self.config.backoff;
        let mut attempt = 0u32;
        loop {
            attempt += 1;
            let remaining = budget.saturating_sub(started.elapsed());
            let timeout = self.config.timeout.min(remaining);
            let outcome = self.runtime.block_on(async {
                let sent = Instant::now();
                let response = build().timeout(timeout).send().await?;
                let status = response.status().as_u16();
                let retry_after = response
                    .headers()
                    .get(reqwest::header::RETRY_AFTER)
                    .and_then(|v| v.to_str().ok())
                    .and_then(parse_retry_after);
                let cap = self.config.max_response_bytes;
                let read = if events != Events::No
                    && (200..300).contains(&status)
                    && is_event_stream(&response)
                {
                    Read::Events(read_events(response, cap, timeout, sent).await)
                } else {
                    Read::Body(read_capped(response, cap).await?)
                };
                Ok::<_, reqwest::Error>((status, retry_after, read))
            });
            meter.record_request(TokenUsage::default());
            let (failure, retry_after) = match outcome {
                Ok((_, _, Read::Events(streamed))) => match stream_failure(streamed, events) {
                    Ok(streamed) => return Ok(Answered::Streamed(streamed)),
                    Err(StreamFailure::Final(kind)) => return Err(err(self.masked_kind(kind))),
                    Err(StreamFailure::Transient(kind)) => (self.masked_kind(kind), None),
                },
                Ok((_, _, Read::Body(None))) => {
                    return Err(err(too_large(self.config.max_response_bytes)))
                }
                Ok((status, _, Read::Body(Some(body)))) if (200..300).contains(&status) => {
                    return Ok(Answered::Body(Answer { body }));
                }
                Ok((status, retry_after, Read::Body(Some(body)))) => {
                    let message = self.error_message(&body);
                    let transient = status == 429
                        || (status >= 500 && (on_5xx == On5xx::Retry || !about_format(&message)));
                    let kind = ProviderErrorKind::Status { status, message };
                    if !transient {
                        return Err(err(kind));
                    }
                    (kind, retry_after)
                }
                Err(e) => (transport_kind(e, self.config.timeout.min(remaining)), None),
            };
            if attempt >= self.config.max_attempts {
                return Err(err(failure));
            }
            let wait = retry_after.unwrap_or(backoff);
            let spent = started.elapsed();
            if spent + wait >= budget {
                let asked = retry_after.map_or_else(String::new, |w| {
                    format!(
                        "; the server asked to wait {:.0} s before retrying (Retry-After), past \
                         the budget",
                        w.as_secs_f64()
                    )
                });
                return Err(err(ProviderErrorKind::BudgetExhausted {
                    attempts: attempt,
                    spent,
                    budget,
                    last: format!("{failure}{asked}"),
                }));
            }
            tracing::warn!(
                endpoint,
                model,
                attempt,
                wait_ms = wait.as_millis() as u64,
                "{failure}; retrying"
            );
            meter.record_retry();
            std::thread::sleep(wait);
            backoff = backoff.saturating_mul(2);
        }
    }
}

impl Transport {
    /// The message of an error body, with the API key masked before and after decoding and
    /// before it is shortened.
    fn error_message(&self, body: &[u8]) -> String {
        shorten(&self.mask(&server_message(self.masked(body).as_bytes())))
    }

    /// `kind` with the API key masked in its message (a stream's failure may quote the server).
    fn masked_kind(&self, kind: ProviderErrorKind) -> ProviderErrorKind {
        match kind {
            ProviderErrorKind::Malformed { message, source } => ProviderErrorKind::Malformed {
                message: self.mask(&message),
                source,
            },
            other => other,
        }
    }

    /// A server's answer as text with the API key masked (servers may echo it).
    pub(crate) fn masked(&self, body: &[u8]) -> String {
        self.mask(&String::from_utf8_lossy(body))
    }

    /// `text` (an answer, or a value decoded from one) with the API key masked.
    pub(crate) fn mask(&self, text: &str) -> String {
        match &self.config.api_key {
            Some(key) => key.mask(text).into_owned(),
            None => text.to_string(),
        }
    }
}

/// Largest HTTP answer read, in bytes (64 MiB: a generated image in base64 with room to
/// spare). The body is read in chunks and reading stops past the limit.
pub const MAX_RESPONSE_BYTES: usize = 64 * 1024 * 1024;

/// The error of an answer past `limit` bytes.
fn too_large(limit: usize) -> ProviderErrorKind {
    ProviderErrorKind::Malformed {
        message: format!(
            "the answer is larger than the limit of {limit} bytes (max_response_bytes, \
             MAX_RESPONSE_BYTES by default, see docs/limits.md); reading stopped there"
        ),
        source: None,
    }
}

/// Whether `response` is a Server-Sent Events stream (by its `Content-Type`).
fn is_event_stream(response: &reqwest::Response) -> bool {
    response
        .headers()
        .get(reqwest::header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| {
            v.trim()
                .to_ascii_lowercase()
                .starts_with("text/event-stream")
        })
}

/// Why an event stream is not an answer.
enum StreamFailure {
    /// Not worth retrying (past the size limit).
    Final(ProviderErrorKind),
    /// Retried like other transport failures (timeout, connection closed early).
    Transient(ProviderErrorKind),
}

/// `streamed` as an answer: complete, or cut short with some of the answer when `events`
/// keeps partial answers; else the failure, saying how much had arrived.
fn stream_failure(streamed: Streamed, events: Events) -> Result<Streamed, StreamFailure> {
    let keep = events == Events::KeepPartial && !streamed.text.is_empty();
    match &streamed.interrupted {
        None => Ok(streamed),
        Some(Interruption::TooLarge(_)) => {
            Err(StreamFailure::Final(ProviderErrorKind::Malformed {
                message: streamed.interruption_message(),
                source: None,
            }))
        }
        Some(_) if keep => Ok(streamed),
        Some(Interruption::Timeout(after)) => {
            Err(StreamFailure::Transient(ProviderErrorKind::Timeout {
                after: *after,
                received: Some(streamed.characters()),
            }))
        }
        Some(Interruption::Cut(_)) => {
            let message = streamed.interruption_message();
            let source = match streamed.interrupted {
                Some(Interruption::Cut(Some(e))) => {
                    Some(Box::new(e) as scenethesis_models::BoxError)
                }
                _ => None,
            };
            Err(StreamFailure::Transient(ProviderErrorKind::Malformed {
                message,
                source,
            }))
        }
    }
}

/// The body of `response`, read chunk by chunk; `None` as soon as it passes `cap` bytes (or
/// its `Content-Length` says it will).
async fn read_capped(
    mut response: reqwest::Response,
    cap: usize,
) -> Result<Option<Vec<u8>>, reqwest::Error> {
    if response.content_length().is_some_and(|n| n > cap as u64) {
        return Ok(None);
    }
    let mut body = Vec::new();
    while let Some(chunk) = response.chunk().await? {
        if body.len() + chunk.len() > cap {
            return Ok(None);
        }
        body.extend_from_slice(&chunk);
    }
    Ok(Some(body))
}

fn form(parts: &[Part]) -> reqwest::multipart::Form {
    let mut form = reqwest::multipart::Form::new();
    for part in parts {
        form = match part.clone() {
            Part::Text(name, value) => form.text(name, value),
            Part::File {
                name,
                file_name,
                mime,
                bytes,
            } => {
                let p = reqwest::multipart::Part::bytes(bytes)
                    .file_name(file_name)
                    .mime_str(mime)
                    .expect("static MIME types parse");
                form.part(name, p)
            }
        };
    }
    form
}

/// Classifies a transport error; the URL is dropped from the source so that a key in a URL
/// cannot leak.
fn transport_kind(e: reqwest::Error, timeout: Duration) -> ProviderErrorKind {
    if e.is_timeout() {
        ProviderErrorKind::Timeout {
            after: timeout,
            received: None,
        }
    } else if e.is_connect() {
        ProviderErrorKind::Unreachable {
            message: "connection failed (is the server running and the base URL right?)".into(),
            source: Some(Box::new(e.without_url())),
        }
    } else if e.is_body() || e.is_decode() {
        ProviderErrorKind::Malformed {
            message: "the answer body could not be read".into(),
            source: Some(Box::new(e.without_url())),
        }
    } else {
        ProviderErrorKind::Unreachable {
            message: "the request failed".into(),
            source: Some(Box::new(e.without_url())),
        }
    }
}

/// `Retry-After` in seconds (integer or fractional); HTTP dates are not used by the servers
/// we target and fall back to the backoff.
fn parse_retry_after(value: &str) -> Option<Duration> {
    let secs: f64 = value.trim().parse().ok()?;
    // Kept as asked (up to a year, so that the sum with elapsed time cannot overflow): a wait
    // past the budget ends the retries saying so.
    (secs.is_finite() && secs >= 0.0).then(|| Duration::from_secs_f64(secs.min(31_536_000.0)))
}

/// The error message of an error body: OpenAI's `error.message`, a string `error`, FastAPI's
/// `detail`, else the body's start.
/// The message is not shortened (the caller masks the key first).
fn server_message(body: &[u8]) -> String {
    let text = String::from_utf8_lossy(body);
    if let Ok(v) = serde_json::from_str::<Value>(&text) {
        let found = v
            .pointer("/error/message")
            .or_else(|| v.get("error"))
            .or_else(|| v.get("detail"))
            .or_else(|| v.get("message"));
        if let Some(m) = found {
            return match m {
                Value::String(s) => s.clone(),
                other => other.to_string(),
            };
        }
    }
    if text.trim().is_empty() {
        "(empty body)".to_string()
    } else {
        text.trim().to_string()
    }
}

/// Whether a server's error message is about the requested output format.
pub(crate) fn about_format(message: &str) -> bool {
    let m = message.to_lowercase();
    [
        "response_format",
        "json_schema",
        "json_object",
        "schema",
        "grammar",
    ]
    .iter()
    .any(|k| m.contains(k))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn retry_after_and_messages() {
        assert_eq!(parse_retry_after("2"), Some(Duration::from_secs(2)));
        assert_eq!(
            parse_retry_after(" 0.25 "),
            Some(Duration::from_millis(250))
        );
        assert_eq!(parse_retry_after("Wed, 21 Oct 2015 07:28:00 GMT"), None);
        assert_eq!(
            server_message(br#"{"error":{"message":"Rate limit","type":"x"}}"#),
            "Rate limit"
        );
        assert_eq!(
            server_message(br#"{"error":"model not found"}"#),
            "model not found"
        );
        assert_eq!(
            server_message(br#"{"detail":[{"msg":"bad"}]}"#),
            r#"[{"msg":"bad"}]"#
        );
        assert_eq!(server_message(b""), "(empty body)");
        assert_eq!(shorten(&server_message(&[b'x'; 400])).chars().count(), 300);
    }
}
