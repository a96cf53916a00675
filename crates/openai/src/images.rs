//! Image generation (`/images/generations`) and editing (`/images/edits`, multipart).

use std::sync::Arc;

use scenethesis_models::{
    GeneratedImage, ImageData, ImageEditRequest, ImageGenerator, ImageRequest, ProviderError,
    ProviderErrorKind, UsageMeter,
};
use serde_json::{json, Value};

use crate::http::{Body, On5xx, Part, Transport};
use crate::message::shorten;

const GENERATIONS: &str = "/images/generations";
const EDITS: &str = "/images/edits";

/// An image model behind OpenAI-compatible image endpoints (OpenAI, LocalAI,
/// stable-diffusion.cpp's server). Answers may carry `b64_json` or a `url` (absolute, or
/// relative to the server as LocalAI gives them), which is then downloaded.
#[derive(Debug)]
pub struct OpenAiImages {
    transport: Arc<Transport>,
    model: String,
    meter: UsageMeter,
}

impl OpenAiImages {
    pub(crate) fn new(transport: Arc<Transport>, model: String) -> Self {
        let meter = UsageMeter::new(transport.config().endpoint_label(), model.clone());
        Self {
            transport,
            model,
            meter,
        }
    }

    /// Requests and retries so far.
    pub fn meter(&self) -> &UsageMeter {
        &self.meter
    }

    /// DALL·E models answer with a URL unless asked for base64; GPT image models and most
    /// local servers always answer base64 and reject the parameter.
    fn wants_response_format(&self) -> bool {
        self.model.starts_with("dall-e")
    }

    fn error(&self, path: &str, kind: ProviderErrorKind) -> ProviderError {
        ProviderError::new(self.transport.label(path), self.model.clone(), kind)
    }

    fn decode(&self, path: &str, body: &[u8]) -> Result<GeneratedImage, ProviderError> {
        let malformed = |message: String| {
            self.error(
                path,
                ProviderErrorKind::Malformed {
                    message,
                    source: None,
                },
            )
        };
        let value: Value = serde_json::from_slice(body).map_err(|_| {
            malformed(format!(
                "expected a JSON image answer, found `{}`",
                shorten(&self.transport.masked(body))
            ))
        })?;
        let first = value.pointer("/data/0").ok_or_else(|| {
            malformed(format!(
                "expected `data[0]` in the answer, found `{}`",
                shorten(&self.transport.mask(&value.to_string()))
            ))
        })?;
        let revised_prompt = first
            .get("revised_prompt")
            .and_then(Value::as_str)
            .map(str::to_string);
        let image = if let Some(b64) = first.get("b64_json").and_then(Value::as_str) {
            ImageData::from_base64(b64, "data[0].b64_json").map_err(|e| malformed(e.to_string()))?
        } else if let Some(url) = first.get("url").and_then(Value::as_str) {
            let absolute = self.absolute(url);
            let answer = self.transport.get(&absolute, &self.model, &self.meter)?;
            ImageData::from_bytes(answer.body, "the image at data[0].url")
                .map_err(|e| malformed(e.to_string()))?
        } else {
            return Err(malformed(
                "expected `data[0].b64_json` or `data[0].url`, found neither".to_string(),
            ));
        };
        Ok(GeneratedImage {
            image,
            revised_prompt,
        })
    }

    /// Resolves a relative image URL against the server's origin.
    fn absolute(&self, url: &str) -> String {
        if url.starts_with("http://") || url.starts_with("https://") {
            return url.to_string();
        }
        let base = &self.transport.config().base_url;
        let origin_end = base
            .find("://")
            .and_then(|i| base[i + 3..].find('/').map(|j| i + 3 + j))
            .unwrap_or(base.len());
        format!("{}/{}", &base[..origin_end], url.trim_start_matches('/'))
    }
}

fn size(s: [u32; 2]) -> String {
    format!("{}x{}", s[0], s[1])
}

impl ImageGenerator for OpenAiImages {
    fn name(&self) -> String {
        format!("openai-compatible/{}", self.model)
    }

    fn generate(&self, request: &ImageRequest) -> Result<GeneratedImage, ProviderError> {
        let mut body = json!({
            "model": self.model,
            "prompt": request.prompt,
            "n": 1,
            "size": size(request.size),
        });
        if self.wants_response_format() {
            body["response_format"] = json!("b64_json");
        }
        if let Some(seed) = request.seed {
            body["seed"] = json!(seed);
        }
        let answer = self.transport.send(
            GENERATIONS,
            &self.model,
            Body::Json(&body),
            On5xx::Retry,
            &self.meter,
        )?;
        self.decode(GENERATIONS, &answer.body)
    }

    fn edit(&self, request: &ImageEditRequest) -> Result<GeneratedImage, ProviderError> {
        let file = |name: &'static str, image: &ImageData| Part::File {
            name,
            file_name: format!(
                "{name}.{}",
                match image.format {
                    scenethesis_models::ImageFormat::Png => "png",
                    scenethesis_models::ImageFormat::Jpeg => "jpg",
                }
            ),
            mime: image.format.mime(),
            bytes: image.bytes.clone(),
        };
        let mut parts = vec![
            Part::Text("model", self.model.clone()),
            Part::Text("prompt", request.prompt.clone()),
            Part::Text("n", "1".to_string()),
            Part::Text("size", size(request.size)),
            file("image", &request.image),
        ];
        if let Some(mask) = &request.mask {
            parts.push(file("mask", mask));
        }
        if self.wants_response_format() {
            parts.push(Part::Text("response_format", "b64_json".to_string()));
        }
        let answer = self.transport.send(
            EDITS,
            &self.model,
            Body::Multipart(&parts),
            On5xx::Retry,
            &self.meter,
        )?;
        self.decode(EDITS, &answer.body)
    }
}
