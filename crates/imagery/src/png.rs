//! The workspace's one PNG encoder, kept with the image types it encodes (decoding stays with
//! the readers of each file format).

use std::io::Cursor;
use std::ops::Deref;

use image::{EncodableLayout, ImageBuffer, ImageFormat, PixelWithColorType};

/// Encodes `image` as PNG file bytes, in the pixel format it holds (8-bit RGB or RGBA, 16-bit
/// grey, …). Every PNG the workspace writes goes through here, so equal pixels give equal
/// bytes wherever they are encoded.
///
/// ```
/// use scenethesis_imagery::encode_png;
/// let grey = image::GrayImage::from_pixel(3, 2, image::Luma([128]));
/// let bytes = encode_png(&grey).unwrap();
/// assert_eq!(&bytes[1..4], b"PNG");
/// ```
///
/// # Errors
/// The encoder's error, e.g. for an image with a side of zero pixels.
pub fn encode_png<P, C>(image: &ImageBuffer<P, C>) -> Result<Vec<u8>, image::ImageError>
where
    P: PixelWithColorType,
    [P::Subpixel]: EncodableLayout,
    C: Deref<Target = [P::Subpixel]>,
{
    let mut bytes = Vec::new();
    image.write_to(&mut Cursor::new(&mut bytes), ImageFormat::Png)?;
    Ok(bytes)
}
