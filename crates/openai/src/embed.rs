//! Text embeddings (`/embeddings`).

use std::sync::Arc;

use scenethesis_models::{ProviderError, ProviderErrorKind, TextEmbedder, UsageMeter};
use serde_json::{json, Value};

use crate::http::{Body, On5xx, Transport};
use crate::message::shorten;

const PATH: &str = "/embeddings";

/// An embedding model behind an OpenAI-compatible `/embeddings` endpoint. It implements the one
/// embedder trait ([`TextEmbedder`]), which retrieval uses too, so a configured endpoint ranks
/// assets and maps unknown nouns to categories by meaning.
#[derive(Debug)]
pub struct OpenAiEmbedder {
    transport: Arc<Transport>,
    model: String,
    meter: UsageMeter,
}

impl OpenAiEmbedder {
    pub(crate) fn new(transport: Arc<Transport>, model: String) -> Self {
        let meter = UsageMeter::new(transport.config().endpoint_label(), model.clone());
        Self {
            transport,
            model,
            meter,
        }
    }

    /// Requests, retries and tokens so far.
    pub fn meter(&self) -> &UsageMeter {
        &self.meter
    }

    fn malformed(&self, message: String) -> ProviderError {
        ProviderError::new(
            self.transport.label(PATH),
            self.model.clone(),
            ProviderErrorKind::Malformed {
                message,
                source: None,
            },
        )
    }
}

impl TextEmbedder for OpenAiEmbedder {
    fn name(&self) -> String {
        format!("openai-compatible/{}", self.model)
    }

    fn embed(&self, texts: &[&str]) -> Result<Vec<Vec<f32>>, ProviderError> {
        if texts.is_empty() {
            return Ok(Vec::new());
        }
        let body = json!({"model": self.model, "input": texts, "encoding_format": "float"});
        let answer = self.transport.send(
            PATH,
            &self.model,
            Body::Json(&body),
            On5xx::Retry,
            &self.meter,
        )?;
        let value: Value = serde_json::from_slice(&answer.body).map_err(|_| {
            self.malformed(format!(
                "expected a JSON embeddings answer, found `{}`",
                shorten(&self.transport.masked(&answer.body))
            ))
        })?;
        if let Some(tokens) = value
            .pointer("/usage/prompt_tokens")
            .and_then(Value::as_u64)
        {
            self.meter.record_tokens(scenethesis_models::TokenUsage {
                prompt_tokens: tokens,
                completion_tokens: 0,
            });
        }
        let data = value.get("data").and_then(Value::as_array).ok_or_else(|| {
            self.malformed(format!(
                "expected a `data` array, found `{}`",
                shorten(&self.transport.mask(&value.to_string()))
            ))
        })?;
        if data.len() != texts.len() {
            return Err(self.malformed(format!(
                "expected {} embeddings, found {}",
                texts.len(),
                data.len()
            )));
        }
        let mut out: Vec<Option<Vec<f32>>> = vec![None; texts.len()];
        for (i, item) in data.iter().enumerate() {
            let index = item
                .get("index")
                .and_then(Value::as_u64)
                .map_or(i, |x| x as usize);
            let vector: Option<Vec<f32>> = item
                .get("embedding")
                .and_then(Value::as_array)
                .and_then(|a| a.iter().map(|x| x.as_f64().map(|f| f as f32)).collect());
            let vector = vector.ok_or_else(|| {
                self.malformed(format!(
                    "expected `data[{i}].embedding` to be an array of numbers"
                ))
            })?;
            match out.get_mut(index) {
                Some(slot @ None) => *slot = Some(vector),
                _ => {
                    return Err(self.malformed(format!(
                        "`data[{i}].index` {index} is out of range or repeated"
                    )))
                }
            }
        }
        let out: Vec<Vec<f32>> = out.into_iter().flatten().collect();
        let dim = out[0].len();
        if dim == 0 || out.iter().any(|v| v.len() != dim) {
            return Err(self.malformed("expected non-empty embeddings of one length".to_string()));
        }
        Ok(out)
    }
}
