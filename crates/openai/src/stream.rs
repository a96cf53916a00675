//! Streamed chat answers: Server-Sent Events (`data: {...}` lines whose
//! `choices[0].delta.content` pieces make up the answer, ending with `data: [DONE]`), assembled
//! as they arrive with progress reported, so a timeout or a cut connection can say how much
//! had arrived and a lenient caller can salvage it.

use std::time::{Duration, Instant};

use scenethesis_models::{grouped, report_answer_progress, AnswerProgress, TokenUsage};
use serde_json::Value;

/// Requests whose `max_tokens` is below this are not streamed (short answers gain nothing);
/// requests without `max_tokens` are.
pub const STREAM_MIN_TOKENS: u32 = 256;

/// How often progress is logged (at `info`) while an answer streams in.
const LOG_EVERY: Duration = Duration::from_secs(10);

/// Why a stream stopped before its end.
#[derive(Debug)]
pub(crate) enum Interruption {
    /// The request's time limit ran out.
    Timeout(Duration),
    /// The connection closed, or the body could not be read, before the end.
    Cut(Option<reqwest::Error>),
    /// The stream passed the size limit (bytes).
    TooLarge(usize),
}

/// An answer assembled from a stream (the key is not masked yet: the caller masks).
#[derive(Debug, Default)]
pub(crate) struct Streamed {
    /// The content pieces, joined.
    pub(crate) text: String,
    /// The model the server named.
    pub(crate) model: Option<String>,
    /// The last `finish_reason` seen.
    pub(crate) finish_reason: Option<String>,
    /// A refusal, when the model refused.
    pub(crate) refusal: Option<String>,
    /// Token counts, when the server sent them (`stream_options.include_usage`).
    pub(crate) usage: TokenUsage,
    /// Pieces received.
    pub(crate) pieces: usize,
    /// Characters of `text`.
    characters: usize,
    /// Whether `data: [DONE]` arrived.
    done: bool,
    /// An error the server reported inside the stream (`data: {"error": ...}`), unmasked.
    server_error: Option<String>,
    /// Why the stream stopped early, if it did.
    pub(crate) interrupted: Option<Interruption>,
    /// Bytes of the stream read.
    bytes: usize,
    /// The unfinished last line.
    pending: Vec<u8>,
}

impl Streamed {
    /// Characters of the answer received.
    pub(crate) fn characters(&self) -> usize {
        self.characters
    }

    /// Whether the stream ended properly: `[DONE]`, or closed after a `finish_reason`.
    pub(crate) fn is_complete(&self) -> bool {
        self.interrupted.is_none() && (self.done || self.finish_reason.is_some())
    }

    /// Reads one chunk of the stream; `false` once it passes `cap` bytes.
    fn feed(&mut self, chunk: &[u8], cap: usize) -> bool {
        self.bytes += chunk.len();
        if self.bytes > cap {
            self.interrupted = Some(Interruption::TooLarge(cap));
            return false;
        }
        // Only the new bytes are searched for line ends: a long line arriving in many chunks
        // is scanned once.
        let mut search = self.pending.len();
        self.pending.extend_from_slice(chunk);
        let mut start = 0;
        while let Some(offset) = self.pending[search..].iter().position(|&b| b == b'\n') {
            let end = search + offset;
            let line = String::from_utf8_lossy(&self.pending[start..end]).into_owned();
            self.line(line.trim_end_matches('\r'));
            start = end + 1;
            search = start;
        }
        self.pending.drain(..start);
        true
    }

    /// One line of the event stream: only `data:` lines matter (comments, `event:`, `id:` and
    /// blank lines are skipped, as are data lines that are not JSON).
    fn line(&mut self, line: &str) {
        let Some(data) = line.strip_prefix("data:") else {
            return;
        };
        let data = data.trim();
        if data == "[DONE]" {
            self.done = true;
            return;
        }
        if let Ok(event) = serde_json::from_str::<Value>(data) {
            self.event(&event);
        }
    }

    fn event(&mut self, event: &Value) {
        if let Some(error) = event.get("error").filter(|e| !e.is_null()) {
            let message = error.get("message").unwrap_or(error);
            self.server_error = Some(match message {
                Value::String(m) => m.clone(),
                other => other.to_string(),
            });
        }
        if let Some(model) = event.get("model").and_then(Value::as_str) {
            self.model.get_or_insert_with(|| model.to_owned());
        }
        if let Some(usage) = event.get("usage").filter(|u| u.is_object()) {
            let count = |name: &str| usage.get(name).and_then(Value::as_u64).unwrap_or(0);
            self.usage = TokenUsage {
                prompt_tokens: count("prompt_tokens"),
                completion_tokens: count("completion_tokens"),
            };
        }
        let Some(choice) = event.pointer("/choices/0") else {
            return;
        };
        let delta = choice.get("delta");
        if let Some(piece) = delta.and_then(|d| d.get("content")).and_then(Value::as_str) {
            if !piece.is_empty() {
                self.text.push_str(piece);
                self.characters += piece.chars().count();
                self.pieces += 1;
            }
        }
        if let Some(refusal) = delta.and_then(|d| d.get("refusal")).and_then(Value::as_str) {
            self.refusal
                .get_or_insert_with(String::new)
                .push_str(refusal);
        }
        if let Some(reason) = choice.get("finish_reason").and_then(Value::as_str) {
            self.finish_reason = Some(reason.to_owned());
        }
    }

    /// What happened to an incomplete stream, for messages: "timed out after 2.0 s with 3,412
    /// characters of the answer received". It may quote the server: the caller masks the key.
    pub(crate) fn interruption_message(&self) -> String {
        let received = grouped(self.characters());
        match &self.interrupted {
            Some(Interruption::Timeout(after)) => format!(
                "timed out after {:.1} s with {received} characters of the answer received",
                after.as_secs_f64()
            ),
            Some(Interruption::TooLarge(cap)) => format!(
                "the streamed answer is larger than the limit of {cap} bytes \
                 (max_response_bytes, MAX_RESPONSE_BYTES by default, see docs/limits.md); \
                 reading stopped with {received} characters of the answer received"
            ),
            Some(Interruption::Cut(_)) | None => match &self.server_error {
                Some(error) => format!(
                    "the server reported an error after {received} characters of the answer: \
                     {}",
                    crate::message::shorten(error)
                ),
                None => format!(
                    "the connection closed after {received} characters of the answer, before \
                     its end (`data: [DONE]`)"
                ),
            },
        }
    }
}

/// Reads an event stream to its end, the cap, an error or the time limit, reporting progress
/// to this thread's answer listener and logging it every [`LOG_EVERY`].
pub(crate) async fn read_events(
    mut response: reqwest::Response,
    cap: usize,
    timeout: Duration,
    started: Instant,
) -> Streamed {
    let mut streamed = Streamed::default();
    let mut logged = Instant::now();
    loop {
        match response.chunk().await {
            Ok(Some(chunk)) => {
                if !streamed.feed(&chunk, cap) {
                    break;
                }
                let progress = AnswerProgress {
                    characters: streamed.characters(),
                    pieces: streamed.pieces,
                    elapsed: started.elapsed(),
                };
                report_answer_progress(&progress);
                if logged.elapsed() >= LOG_EVERY {
                    logged = Instant::now();
                    tracing::info!(
                        "{} characters of the answer received in {:.0} s",
                        grouped(progress.characters),
                        progress.elapsed.as_secs_f64()
                    );
                }
            }
            Ok(None) => break,
            Err(e) if e.is_timeout() => {
                streamed.interrupted = Some(Interruption::Timeout(timeout));
                break;
            }
            Err(e) => {
                streamed.interrupted = Some(Interruption::Cut(Some(e.without_url())));
                break;
            }
        }
    }
    if !streamed.pending.is_empty() {
        let rest = std::mem::take(&mut streamed.pending);
        streamed.line(String::from_utf8_lossy(&rest).trim_end());
    }
    if streamed.interrupted.is_none() && !streamed.is_complete() {
        streamed.interrupted = Some(Interruption::Cut(None));
    }
    streamed
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn events_split_anywhere_assemble_the_answer() {
        let stream = concat!(
            ": keep-alive\n\n",
            "data: {\"model\":\"m1\",\"choices\":[{\"delta\":{\"role\":\"assistant\"}}]}\n\n",
            "data: {\"choices\":[{\"delta\":{\"content\":\"{\\\"a\\\": \"}}]}\r\n\r\n",
            "event: message\ndata: {\"choices\":[{\"delta\":{\"content\":\"1}\"},",
            "\"finish_reason\":\"stop\"}]}\n\n",
            "data: {\"choices\":[],\"usage\":{\"prompt_tokens\":7,\"completion_tokens\":3}}\n\n",
            "data: [DONE]\n\n"
        )
        .as_bytes();
        for split in [1, 3, 17, stream.len()] {
            let mut s = Streamed::default();
            for chunk in stream.chunks(split) {
                assert!(s.feed(chunk, 10_000));
            }
            assert_eq!(s.text, "{\"a\": 1}");
            assert_eq!(s.model.as_deref(), Some("m1"));
            assert_eq!(s.finish_reason.as_deref(), Some("stop"));
            assert_eq!((s.usage.prompt_tokens, s.usage.completion_tokens), (7, 3));
            assert_eq!(s.pieces, 2);
            assert!(s.is_complete());
        }
        let mut s = Streamed::default();
        let failing = "data: {\"choices\":[{\"delta\":{\"content\":\"ab\"}}]}\n\n\
                       data: {\"error\":{\"message\":\"out of memory\"}}\n\n";
        assert!(s.feed(failing.as_bytes(), 10_000));
        assert!(!s.is_complete());
        assert_eq!(
            s.interruption_message(),
            "the server reported an error after 2 characters of the answer: out of memory"
        );
        // A long line in many small chunks is read in linear time.
        let long = format!(
            "data: {}\n\ndata: [DONE]\n\n",
            serde_json::json!({"choices": [{"delta": {"content": "é".repeat(2_000_000)}}]})
        );
        // (Rescanning per chunk would take minutes here; speed is not timed in unit tests.)
        let mut s = Streamed::default();
        for chunk in long.as_bytes().chunks(1024) {
            assert!(s.feed(chunk, usize::MAX));
        }
        assert_eq!((s.characters(), s.pieces), (2_000_000, 1));
        assert!(s.is_complete());
        let mut s = Streamed::default();
        assert!(!s.feed(stream, 10), "past the cap");
        assert!(s
            .interruption_message()
            .contains("larger than the limit of 10 bytes"));
    }
}
