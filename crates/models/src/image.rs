//! Images exchanged with providers: PNG or JPEG bytes, sent as base64 data URLs.

use base64::Engine as _;
use serde::{Deserialize, Serialize};

/// The encodings providers accept for image input.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum ImageFormat {
    /// `image/png`.
    Png,
    /// `image/jpeg`.
    Jpeg,
}

impl ImageFormat {
    /// The MIME type.
    pub fn mime(self) -> &'static str {
        match self {
            Self::Png => "image/png",
            Self::Jpeg => "image/jpeg",
        }
    }

    /// The format whose signature starts `bytes`, if PNG or JPEG.
    pub fn sniff(bytes: &[u8]) -> Option<Self> {
        if bytes.starts_with(&[0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A]) {
            Some(Self::Png)
        } else if bytes.starts_with(&[0xFF, 0xD8, 0xFF]) {
            Some(Self::Jpeg)
        } else {
            None
        }
    }
}

/// Why bytes are not an image a provider accepts.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ImageError {
    /// The bytes start with neither the PNG nor the JPEG signature.
    #[error("{what}: expected PNG or JPEG bytes, found {found}")]
    UnknownFormat {
        /// What the bytes are (a file name, `answer image`, …).
        what: String,
        /// A description of the first bytes.
        found: String,
    },
    /// A data URL or base64 text could not be decoded.
    #[error("{what}: {message}")]
    Decode {
        /// What was decoded.
        what: String,
        /// What is wrong.
        message: String,
    },
}

/// An encoded image (PNG or JPEG) with its format.
#[derive(Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct ImageData {
    /// The encoding.
    pub format: ImageFormat,
    /// The encoded bytes (base64 in JSON).
    #[serde(with = "base64_bytes")]
    pub bytes: Vec<u8>,
}

impl std::fmt::Debug for ImageData {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("ImageData")
            .field("format", &self.format)
            .field("bytes", &self.bytes.len())
            .finish()
    }
}

impl ImageData {
    /// Wraps encoded bytes, detecting PNG or JPEG from their signature; `what` names the source
    /// in errors.
    pub fn from_bytes(bytes: Vec<u8>, what: &str) -> Result<Self, ImageError> {
        match ImageFormat::sniff(&bytes) {
            Some(format) => Ok(Self { format, bytes }),
            None => Err(ImageError::UnknownFormat {
                what: what.to_string(),
                found: describe_start(&bytes),
            }),
        }
    }

    /// Decodes base64 text (as in an OpenAI `b64_json` field) holding PNG or JPEG bytes.
    pub fn from_base64(text: &str, what: &str) -> Result<Self, ImageError> {
        let bytes = base64::engine::general_purpose::STANDARD
            .decode(text.trim())
            .map_err(|e| ImageError::Decode {
                what: what.to_string(),
                message: format!("invalid base64: {e}"),
            })?;
        Self::from_bytes(bytes, what)
    }

    /// Parses a `data:image/png;base64,…` or `data:image/jpeg;base64,…` URL.
    pub fn from_data_url(url: &str, what: &str) -> Result<Self, ImageError> {
        let rest = url
            .strip_prefix("data:")
            .ok_or_else(|| ImageError::Decode {
                what: what.to_string(),
                message: "expected a URL starting with `data:`".to_string(),
            })?;
        let (header, payload) = rest.split_once(',').ok_or_else(|| ImageError::Decode {
            what: what.to_string(),
            message: "expected `,` after the data URL header".to_string(),
        })?;
        if !header.ends_with(";base64") {
            return Err(ImageError::Decode {
                what: what.to_string(),
                message: format!("expected a base64 data URL, found header `{header}`"),
            });
        }
        Self::from_base64(payload, what)
    }

    /// The base64 text of the bytes.
    pub fn to_base64(&self) -> String {
        base64::engine::general_purpose::STANDARD.encode(&self.bytes)
    }

    /// The `data:` URL chat APIs take as an `image_url`.
    pub fn to_data_url(&self) -> String {
        format!("data:{};base64,{}", self.format.mime(), self.to_base64())
    }
}

fn describe_start(bytes: &[u8]) -> String {
    if bytes.is_empty() {
        return "no bytes".to_string();
    }
    let head: Vec<String> = bytes.iter().take(8).map(|b| format!("{b:02x}")).collect();
    format!("{} bytes starting {}", bytes.len(), head.join(" "))
}

mod base64_bytes {
    use base64::Engine as _;
    use serde::{Deserialize, Deserializer, Serializer};

    pub fn serialize<S: Serializer>(bytes: &[u8], s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&base64::engine::general_purpose::STANDARD.encode(bytes))
    }

    pub fn deserialize<'de, D: Deserializer<'de>>(d: D) -> Result<Vec<u8>, D::Error> {
        let text = String::deserialize(d)?;
        base64::engine::general_purpose::STANDARD
            .decode(text)
            .map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const PNG_HEAD: &[u8] = &[0x89, b'P', b'N', b'G', 0x0D, 0x0A, 0x1A, 0x0A, 0, 0];

    #[test]
    fn data_url_round_trip() {
        let image = ImageData::from_bytes(PNG_HEAD.to_vec(), "test").unwrap();
        let url = image.to_data_url();
        assert!(url.starts_with("data:image/png;base64,iVBORw0KGgo"));
        assert_eq!(ImageData::from_data_url(&url, "test").unwrap(), image);
        let jpeg = ImageData::from_bytes(vec![0xFF, 0xD8, 0xFF, 0xE0], "j").unwrap();
        assert_eq!(jpeg.format, ImageFormat::Jpeg);
        assert!(jpeg.to_data_url().starts_with("data:image/jpeg;base64,"));
    }

    #[test]
    fn rejects_other_bytes_naming_the_source() {
        let err = ImageData::from_bytes(b"GIF89a".to_vec(), "guide.gif").unwrap_err();
        assert_eq!(
            err.to_string(),
            "guide.gif: expected PNG or JPEG bytes, found 6 bytes starting 47 49 46 38 39 61"
        );
        let err = ImageData::from_data_url("data:image/png,abc", "answer").unwrap_err();
        assert!(err.to_string().contains("base64"), "{err}");
        let err = ImageData::from_base64("***", "b64_json").unwrap_err();
        assert!(
            err.to_string().starts_with("b64_json: invalid base64"),
            "{err}"
        );
    }

    #[test]
    fn serde_uses_base64() {
        let image = ImageData::from_bytes(PNG_HEAD.to_vec(), "t").unwrap();
        let json = serde_json::to_string(&image).unwrap();
        assert_eq!(json, r#"{"format":"png","bytes":"iVBORw0KGgoAAA=="}"#);
        let back: ImageData = serde_json::from_str(&json).unwrap();
        assert_eq!(back, image);
    }
}
