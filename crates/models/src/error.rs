//! Errors of model providers: every error names the endpoint and the model it concerns.

use std::fmt;
use std::path::PathBuf;
use std::time::Duration;

use crate::schema::SchemaViolation;

/// A boxed error from a lower layer (HTTP client, file system, decoder).
pub type BoxError = Box<dyn std::error::Error + Send + Sync + 'static>;

/// Why a provider call failed, naming the endpoint and the model.
///
/// `Display` prints `ENDPOINT (model `MODEL`): WHAT`; the lower-level cause, when there is one,
/// is available through [`std::error::Error::source`] and is not repeated in the message.
#[derive(Debug)]
pub struct ProviderError {
    /// The endpoint the call went to (a URL without credentials, or a provider name such as
    /// `cache` for offline replay).
    pub endpoint: String,
    /// The model the call asked for.
    pub model: String,
    /// What went wrong.
    pub kind: ProviderErrorKind,
}

impl ProviderError {
    /// An error of `kind` for `endpoint` and `model`.
    pub fn new(
        endpoint: impl Into<String>,
        model: impl Into<String>,
        kind: ProviderErrorKind,
    ) -> Self {
        Self {
            endpoint: endpoint.into(),
            model: model.into(),
            kind,
        }
    }

    /// Whether retrying the same request later could succeed (timeouts, refused connections,
    /// HTTP 429 and 5xx).
    pub fn is_transient(&self) -> bool {
        match &self.kind {
            ProviderErrorKind::Unreachable { .. } | ProviderErrorKind::Timeout { .. } => true,
            ProviderErrorKind::Status { status, .. } => *status == 429 || *status >= 500,
            _ => false,
        }
    }
}

impl fmt::Display for ProviderError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} (model `{}`): {}",
            self.endpoint, self.model, self.kind
        )
    }
}

impl std::error::Error for ProviderError {
    fn source(&self) -> Option<&(dyn std::error::Error + 'static)> {
        // The kind's message is already part of ours; hand on its cause only.
        std::error::Error::source(&self.kind)
    }
}

/// The message of [`ProviderErrorKind::Timeout`].
fn timeout_message(after: Duration, received: Option<usize>) -> String {
    match received {
        None => format!("no answer within {:.1} s", after.as_secs_f64()),
        Some(n) => format!(
            "timed out after {:.1} s with {} characters of the answer received",
            after.as_secs_f64(),
            grouped(n)
        ),
    }
}

/// `n` with its digits grouped by threes (`3,412`), for messages.
pub fn grouped(n: usize) -> String {
    let digits = n.to_string();
    let mut out = String::with_capacity(digits.len() + digits.len() / 3);
    for (i, c) in digits.chars().enumerate() {
        if i > 0 && (digits.len() - i) % 3 == 0 {
            out.push(',');
        }
        out.push(c);
    }
    out
}

/// What went wrong in a provider call.
#[derive(Debug, thiserror::Error)]
pub enum ProviderErrorKind {
    /// No connection could be made (refused, DNS, TLS).
    #[error("the server is unreachable: {message}")]
    Unreachable {
        /// A short description.
        message: String,
        /// The transport error.
        #[source]
        source: Option<BoxError>,
    },
    /// No complete answer arrived in time.
    #[error("{}", timeout_message(*after, *received))]
    Timeout {
        /// The time limit that was exceeded.
        after: Duration,
        /// Characters of a streamed answer that had arrived when the time ran out (`None`
        /// when nothing was streamed).
        received: Option<usize>,
    },
    /// The server answered with an HTTP error status.
    #[error("HTTP {status}: {message}")]
    Status {
        /// The HTTP status code.
        status: u16,
        /// The server's error message (shortened).
        message: String,
    },
    /// The answer is not in the expected shape (not JSON, missing fields, undecodable image).
    #[error("the answer is malformed: {message}")]
    Malformed {
        /// What was expected and what came.
        message: String,
        /// The decoder error.
        #[source]
        source: Option<BoxError>,
    },
    /// A structured answer does not satisfy the requested JSON schema (after the repair round).
    #[error("the answer violates the schema `{schema}`: {violation}")]
    Schema {
        /// Name of the schema.
        schema: String,
        /// The first violation found.
        violation: SchemaViolation,
    },
    /// Retries stopped because the total time budget is spent.
    #[error("gave up after {attempts} attempts in {:.1} s (budget {:.1} s); last failure: {last}", spent.as_secs_f64(), budget.as_secs_f64())]
    BudgetExhausted {
        /// Attempts made.
        attempts: u32,
        /// Time spent.
        spent: Duration,
        /// The budget.
        budget: Duration,
        /// The last failure's message.
        last: String,
    },
    /// The request cannot be sent as given (bad image, unsupported option).
    #[error("invalid request: {message}")]
    InvalidRequest {
        /// What is wrong.
        message: String,
    },
    /// Replay-only mode found no cached answer for the request.
    #[error("no cached answer for request {key} in {}; run once with the provider reachable to record it", dir.display())]
    CacheMiss {
        /// The request's hash.
        key: String,
        /// The cache directory.
        dir: PathBuf,
    },
    /// The response cache could not be read or written.
    #[error("response cache file {} cannot be used: {message}", path.display())]
    Cache {
        /// The cache file.
        path: PathBuf,
        /// What failed.
        message: String,
        /// The I/O or decoding error.
        #[source]
        source: Option<BoxError>,
    },
    /// The provider does not offer this operation.
    #[error("the provider does not support {operation}")]
    Unsupported {
        /// The operation (`image edits`, …).
        operation: String,
    },
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn timeouts_say_how_much_had_arrived() {
        assert_eq!(grouped(0), "0");
        assert_eq!(grouped(999), "999");
        assert_eq!(grouped(3412), "3,412");
        assert_eq!(grouped(1_234_567), "1,234,567");
        let after = Duration::from_secs(120);
        let none = ProviderErrorKind::Timeout {
            after,
            received: None,
        };
        assert_eq!(none.to_string(), "no answer within 120.0 s");
        let some = ProviderErrorKind::Timeout {
            after,
            received: Some(3412),
        };
        assert_eq!(
            some.to_string(),
            "timed out after 120.0 s with 3,412 characters of the answer received"
        );
    }
}
