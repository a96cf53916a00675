//! Base-colour textures of imported materials. A usable texture (a PNG or JPEG within the
//! limits) is decoded, re-encoded as PNG and carried on its material as a
//! [`TextureImage`](scenethesis_scene_graph::TextureImage) with its mean colour; the parts
//! wearing the material keep their texture coordinates, so the exporters and the renderer
//! draw the image itself. A texture that cannot be used (missing, outside the asset folder,
//! over a limit, not a PNG or JPEG) leaves the plain base colour and a warning naming the
//! file.

use std::io::Cursor;

use scenethesis_scene_graph::TextureImage;

use super::limits::MAX_TEXTURE_PIXELS;

/// At most this many texels a side are averaged: a larger image is sampled on a regular grid.
const SAMPLES_PER_SIDE: u32 = 256;

/// An encoded PNG or JPEG image as a texture: decoded, re-encoded as an 8-bit PNG (RGB, or
/// RGBA when the image has an alpha channel; the same image always gives the same bytes) with
/// its mean linear colour; or why it cannot be used.
pub(crate) fn texture_image(bytes: &[u8]) -> Result<TextureImage, String> {
    let image = decode(bytes)?;
    let mean = mean_of(&image.to_rgb8());
    let mut png = Vec::new();
    let encoded = if image.color().has_alpha() {
        image::DynamicImage::ImageRgba8(image.to_rgba8())
    } else {
        image::DynamicImage::ImageRgb8(image.to_rgb8())
    };
    encoded
        .write_to(&mut Cursor::new(&mut png), image::ImageFormat::Png)
        .map_err(|e| format!("cannot encode the image as PNG: {e}"))?;
    TextureImage::from_png(png, mean).map_err(|e| e.to_string())
}

/// The mean linear RGB colour of an encoded PNG or JPEG image, or why it cannot be decoded.
#[cfg(test)]
fn mean_linear_colour(bytes: &[u8]) -> Result<[f32; 3], String> {
    decode(bytes).map(|image| mean_of(&image.to_rgb8()))
}

/// Decodes a PNG or JPEG image within [`MAX_TEXTURE_PIXELS`].
fn decode(bytes: &[u8]) -> Result<image::DynamicImage, String> {
    let reader = image::ImageReader::new(Cursor::new(bytes))
        .with_guessed_format()
        .map_err(|e| e.to_string())?;
    if reader.format().is_none() {
        return Err("not a PNG or JPEG image".into());
    }
    let (w, h) = reader
        .into_dimensions()
        .map_err(|e| format!("cannot read the image header: {e}"))?;
    if u64::from(w) * u64::from(h) > MAX_TEXTURE_PIXELS || w == 0 || h == 0 {
        return Err(format!(
            "the image is {w} x {h} pixels; expected 1 to {MAX_TEXTURE_PIXELS} pixels"
        ));
    }
    image::load_from_memory(bytes).map_err(|e| format!("cannot decode the image: {e}"))
}

/// The mean linear colour of an sRGB image, over at most [`SAMPLES_PER_SIDE`]² texels.
fn mean_of(image: &image::RgbImage) -> [f32; 3] {
    let (w, h) = image.dimensions();
    let (sx, sy) = (w.min(SAMPLES_PER_SIDE), h.min(SAMPLES_PER_SIDE));
    let mut sum = [0.0f64; 3];
    for j in 0..sy {
        for i in 0..sx {
            let px = image.get_pixel(i * w / sx, j * h / sy);
            for (s, c) in sum.iter_mut().zip(px.0) {
                *s += f64::from(srgb_to_linear(c));
            }
        }
    }
    let n = f64::from(sx * sy);
    sum.map(|s| (s / n) as f32)
}

/// One 8-bit sRGB channel as a linear value in 0..=1.
fn srgb_to_linear(c: u8) -> f32 {
    let c = f32::from(c) / 255.0;
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(w: u32, h: u32, pixel: impl Fn(u32, u32) -> [u8; 3]) -> Vec<u8> {
        let image = image::RgbImage::from_fn(w, h, |x, y| image::Rgb(pixel(x, y)));
        let mut bytes = Vec::new();
        image
            .write_to(&mut Cursor::new(&mut bytes), image::ImageFormat::Png)
            .unwrap();
        bytes
    }

    #[test]
    fn mean_of_a_checker_is_its_linear_average() {
        let bytes = png(8, 8, |x, y| {
            if (x + y) % 2 == 0 {
                [255, 0, 0]
            } else {
                [0, 0, 255]
            }
        });
        let mean = mean_linear_colour(&bytes).unwrap();
        assert!(
            (mean[0] - 0.5).abs() < 1e-6 && mean[1].abs() < 1e-6,
            "{mean:?}"
        );
        assert!((mean[2] - 0.5).abs() < 1e-6, "{mean:?}");
    }

    #[test]
    fn large_images_are_sampled() {
        let bytes = png(1000, 600, |_, _| [188, 188, 188]);
        let mean = mean_linear_colour(&bytes).unwrap();
        assert!((mean[0] - srgb_to_linear(188)).abs() < 1e-6, "{mean:?}");
    }

    #[test]
    fn broken_bytes_say_why() {
        let err = mean_linear_colour(b"definitely not an image").unwrap_err();
        assert!(err.contains("PNG or JPEG"), "{err}");
        let mut truncated = png(16, 16, |x, _| [x as u8 * 10, 0, 0]);
        truncated.truncate(truncated.len() / 2);
        let err = mean_linear_colour(&truncated).unwrap_err();
        assert!(err.contains("decode"), "{err}");
    }

    #[test]
    fn textures_are_png_with_their_mean_and_the_same_bytes_every_time() {
        let bytes = png(4, 2, |x, _| if x < 2 { [255, 0, 0] } else { [0, 0, 255] });
        let image = texture_image(&bytes).unwrap();
        assert_eq!((image.width(), image.height()), (4, 2));
        let mean = image.mean_color();
        assert!(
            (mean[0] - 0.5).abs() < 1e-6 && (mean[2] - 0.5).abs() < 1e-6,
            "{mean:?}"
        );
        let again = texture_image(&bytes).unwrap();
        assert_eq!(image.png(), again.png());
        let decoded = image::load_from_memory(image.png()).unwrap().to_rgb8();
        assert_eq!(decoded.get_pixel(0, 0).0, [255, 0, 0]);
        assert_eq!(decoded.get_pixel(3, 1).0, [0, 0, 255]);
        assert!(texture_image(b"not an image").is_err());
    }
}
