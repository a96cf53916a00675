//! Base-colour images of imported materials: PNG bytes shared by every clone of a material,
//! named by a digest of those bytes.

use std::fmt;
use std::sync::Arc;

use base64::Engine as _;
use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::fnv1a64;

/// The eight bytes every PNG file starts with.
const PNG_SIGNATURE: [u8; 8] = [0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n'];

/// Why bytes are not a usable [`TextureImage`].
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum TextureError {
    /// The bytes do not start with a PNG signature and an `IHDR` header.
    #[error("not a PNG image (no PNG signature and IHDR header)")]
    NotPng,
    /// The header gives a width or height of 0.
    #[error("the PNG image is {width} x {height} pixels; expected at least 1 x 1")]
    Empty {
        /// Width in the header.
        width: u32,
        /// Height in the header.
        height: u32,
    },
    /// The PNG data of a serialized image is not valid base64.
    #[error("the image's PNG data is not valid base64")]
    Base64,
    /// A serialized image's digest is not the digest of its bytes.
    #[error("the image's digest {stated} does not match its bytes ({actual})")]
    Digest {
        /// The digest written beside the bytes.
        stated: String,
        /// The digest of the bytes.
        actual: String,
    },
}

/// A material's base-colour image: PNG-encoded 8-bit sRGB texels (row 0 the image's top),
/// held behind a reference count so that every clone of the material (each object of an
/// imported asset) shares one copy, and named by the 64-bit FNV-1a digest of those bytes,
/// under which the exporters write it once per file however many materials wear it. It also
/// keeps its mean linear colour, for what shows a material as one colour
/// ([`Material::flat_color`](crate::Material::flat_color)).
///
/// ```
/// use scenethesis_scene_graph::TextureImage;
///
/// // The smallest PNG header: signature, IHDR length and tag, 2 x 3 pixels.
/// let mut png = vec![0x89, b'P', b'N', b'G', b'\r', b'\n', 0x1a, b'\n', 0, 0, 0, 13];
/// png.extend_from_slice(b"IHDR");
/// png.extend_from_slice(&2u32.to_be_bytes());
/// png.extend_from_slice(&3u32.to_be_bytes());
/// png.extend_from_slice(&[8, 2, 0, 0, 0]);
/// let image = TextureImage::from_png(png, [0.5, 0.25, 1.0]).unwrap();
/// assert_eq!((image.width(), image.height()), (2, 3));
/// assert_eq!(image.digest_hex().len(), 16);
/// assert_eq!(image.mean_color(), [0.5, 0.25, 1.0]);
/// assert!(TextureImage::from_png(b"GIF89a".to_vec(), [1.0; 3]).is_err());
/// ```
#[derive(Clone)]
pub struct TextureImage {
    png: Arc<[u8]>,
    digest: u64,
    width: u32,
    height: u32,
    mean: [f32; 3],
}

impl TextureImage {
    /// The image of encoded PNG bytes whose texels average `mean` (linear RGB, each channel
    /// clamped to [0, 1], 0 when not finite), checked to start with a PNG signature and an
    /// `IHDR` header of at least 1 × 1 pixels (the texels themselves are decoded by the
    /// readers).
    pub fn from_png(png: Vec<u8>, mean: [f32; 3]) -> Result<Self, TextureError> {
        if png.len() < 24 || png[..8] != PNG_SIGNATURE || &png[12..16] != b"IHDR" {
            return Err(TextureError::NotPng);
        }
        let be = |at: usize| u32::from_be_bytes([png[at], png[at + 1], png[at + 2], png[at + 3]]);
        let (width, height) = (be(16), be(20));
        if width == 0 || height == 0 {
            return Err(TextureError::Empty { width, height });
        }
        Ok(Self {
            digest: fnv1a64(&png),
            png: png.into(),
            width,
            height,
            mean: mean.map(|c| {
                if c.is_finite() {
                    c.clamp(0.0, 1.0)
                } else {
                    0.0
                }
            }),
        })
    }

    /// The mean linear RGB colour of the texels.
    pub fn mean_color(&self) -> [f32; 3] {
        self.mean
    }

    /// The PNG bytes.
    pub fn png(&self) -> &[u8] {
        &self.png
    }

    /// The 64-bit FNV-1a digest of the PNG bytes.
    pub fn digest(&self) -> u64 {
        self.digest
    }

    /// The digest as 16 lowercase hex digits, the name of the image in exports.
    pub fn digest_hex(&self) -> String {
        format!("{:016x}", self.digest)
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }
}

impl PartialEq for TextureImage {
    fn eq(&self, other: &Self) -> bool {
        self.digest == other.digest && (Arc::ptr_eq(&self.png, &other.png) || self.png == other.png)
    }
}

impl fmt::Debug for TextureImage {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("TextureImage")
            .field("digest", &self.digest_hex())
            .field("width", &self.width)
            .field("height", &self.height)
            .field("mean", &self.mean)
            .field("bytes", &self.png.len())
            .finish()
    }
}

/// The serialized form: the digest, the mean colour and the PNG bytes in standard base64.
#[derive(Serialize, Deserialize)]
struct Stored {
    digest: String,
    mean: [f32; 3],
    png: String,
}

impl Serialize for TextureImage {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        Stored {
            digest: self.digest_hex(),
            mean: self.mean,
            png: base64::engine::general_purpose::STANDARD.encode(&self.png),
        }
        .serialize(s)
    }
}

impl<'de> Deserialize<'de> for TextureImage {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let stored = Stored::deserialize(d)?;
        let bytes = base64::engine::general_purpose::STANDARD
            .decode(stored.png.as_bytes())
            .map_err(|_| serde::de::Error::custom(TextureError::Base64))?;
        let image = TextureImage::from_png(bytes, stored.mean).map_err(serde::de::Error::custom)?;
        if image.digest_hex() != stored.digest {
            return Err(serde::de::Error::custom(TextureError::Digest {
                stated: stored.digest,
                actual: image.digest_hex(),
            }));
        }
        Ok(image)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn header(width: u32, height: u32) -> Vec<u8> {
        let mut png = PNG_SIGNATURE.to_vec();
        png.extend_from_slice(&13u32.to_be_bytes());
        png.extend_from_slice(b"IHDR");
        png.extend_from_slice(&width.to_be_bytes());
        png.extend_from_slice(&height.to_be_bytes());
        png.extend_from_slice(&[8, 6, 0, 0, 0]);
        png
    }

    #[test]
    fn images_round_trip_through_json_and_refuse_a_wrong_digest() {
        let image = TextureImage::from_png(header(4, 2), [0.1, 0.2, 0.3]).unwrap();
        let json = serde_json::to_string(&image).unwrap();
        assert!(json.contains(&image.digest_hex()), "{json}");
        let back: TextureImage = serde_json::from_str(&json).unwrap();
        assert_eq!(back, image);
        let tampered = json.replace(&image.digest_hex(), "0000000000000000");
        let err = serde_json::from_str::<TextureImage>(&tampered).unwrap_err();
        assert!(err.to_string().contains("does not match"), "{err}");
        assert_eq!(
            TextureImage::from_png(header(0, 2), [1.0; 3]).unwrap_err(),
            TextureError::Empty {
                width: 0,
                height: 2
            }
        );
    }

    #[test]
    fn clones_share_their_bytes() {
        let image = TextureImage::from_png(header(1, 1), [1.0; 3]).unwrap();
        let copy = image.clone();
        assert!(std::ptr::eq(image.png().as_ptr(), copy.png().as_ptr()));
    }
}
