//! Image rasters shared by the depth and segmentation pre/post-processing: decoding, resizing,
//! normalisation into NCHW tensors and bilinear sampling of float planes.

use image::RgbImage;
use scenethesis_models::ImageData;

/// Per-channel normalisation of 8-bit RGB: `(value / 255 - mean[c]) / std[c]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Normalisation {
    /// Channel means on the 0..1 scale (R, G, B).
    pub mean: [f32; 3],
    /// Channel standard deviations on the 0..1 scale (R, G, B).
    pub std: [f32; 3],
}

impl Normalisation {
    /// ImageNet statistics, used by Depth Anything and by SAM (whose 0..255 constants
    /// 123.675/116.28/103.53 and 58.395/57.12/57.375 are these times 255).
    pub const IMAGENET: Self = Self {
        mean: [0.485, 0.456, 0.406],
        std: [0.229, 0.224, 0.225],
    };

    /// The normalised value of an 8-bit sample of channel `c`.
    pub fn apply(&self, c: usize, value: u8) -> f32 {
        (f32::from(value) / 255.0 - self.mean[c]) / self.std[c]
    }
}

/// Decodes PNG or JPEG bytes to 8-bit RGB (alpha is dropped).
pub fn decode_rgb(image: &ImageData) -> Result<RgbImage, String> {
    image::load_from_memory(&image.bytes)
        .map(|decoded| decoded.to_rgb8())
        .map_err(|e| format!("cannot decode the {:?} image: {e}", image.format))
}

/// `image` resized to `width` x `height` with a triangle (bilinear, antialiased when shrinking)
/// filter; the image itself when the size already matches.
pub fn resize_rgb(image: &RgbImage, width: u32, height: u32) -> RgbImage {
    if image.dimensions() == (width, height) {
        return image.clone();
    }
    image::imageops::resize(image, width, height, image::imageops::FilterType::Triangle)
}

/// A `[1, 3, frame_height, frame_width]` float tensor (row-major, channel planes R, G, B) with
/// the normalised `image` in its top-left corner and zeros elsewhere (SAM pads after
/// normalising). The frame must be at least as large as the image.
pub fn to_nchw(
    image: &RgbImage,
    norm: &Normalisation,
    frame_width: u32,
    frame_height: u32,
) -> Vec<f32> {
    let (w, h) = image.dimensions();
    assert!(
        w <= frame_width && h <= frame_height,
        "image larger than its frame"
    );
    let plane = (frame_width * frame_height) as usize;
    let mut out = vec![0.0f32; 3 * plane];
    for (x, y, pixel) in image.enumerate_pixels() {
        let at = (y * frame_width + x) as usize;
        for c in 0..3 {
            out[c * plane + at] = norm.apply(c, pixel[c]);
        }
    }
    out
}

/// Bilinear sample of a row-major `width` x `height` plane at continuous pixel coordinates
/// (`0.0` is the centre of the first pixel), clamped to the border.
pub fn sample_bilinear(plane: &[f32], width: usize, height: usize, x: f32, y: f32) -> f32 {
    debug_assert_eq!(plane.len(), width * height);
    let x = x.clamp(0.0, (width - 1) as f32);
    let y = y.clamp(0.0, (height - 1) as f32);
    let (x0, y0) = (x.floor() as usize, y.floor() as usize);
    let (x1, y1) = ((x0 + 1).min(width - 1), (y0 + 1).min(height - 1));
    let (tx, ty) = (x - x0 as f32, y - y0 as f32);
    let at = |xx: usize, yy: usize| plane[yy * width + xx];
    let top = at(x0, y0) * (1.0 - tx) + at(x1, y0) * tx;
    let bottom = at(x0, y1) * (1.0 - tx) + at(x1, y1) * tx;
    top * (1.0 - ty) + bottom * ty
}

/// A plane resized to `to_width` x `to_height` by bilinear sampling with pixel centres aligned
/// (`align_corners = false`), the convention of PyTorch's `interpolate` that depth models are
/// trained with.
pub fn resize_plane(
    plane: &[f32],
    width: usize,
    height: usize,
    to_width: usize,
    to_height: usize,
) -> Vec<f32> {
    let sx = width as f32 / to_width as f32;
    let sy = height as f32 / to_height as f32;
    let mut out = Vec::with_capacity(to_width * to_height);
    for y in 0..to_height {
        let fy = (y as f32 + 0.5) * sy - 0.5;
        for x in 0..to_width {
            let fx = (x as f32 + 0.5) * sx - 0.5;
            out.push(sample_bilinear(plane, width, height, fx, fy));
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn normalisation_matches_sams_pixel_constants() {
        let n = Normalisation::IMAGENET;
        // SAM: (255 - 123.675) / 58.395 for red.
        assert!((n.apply(0, 255) - (255.0 - 123.675) / 58.395).abs() < 1e-5);
        assert!((n.apply(2, 0) - (0.0 - 103.53) / 57.375).abs() < 1e-5);
    }

    #[test]
    fn nchw_places_the_image_top_left_and_pads_with_zeros() {
        let mut img = RgbImage::new(2, 1);
        img.put_pixel(0, 0, image::Rgb([255, 0, 0]));
        img.put_pixel(1, 0, image::Rgb([0, 255, 0]));
        let n = Normalisation {
            mean: [0.0; 3],
            std: [1.0; 3],
        };
        let t = to_nchw(&img, &n, 3, 2);
        assert_eq!(t.len(), 3 * 6);
        // Red plane: 1 at (0,0), 0 elsewhere; green plane: 1 at (1,0).
        assert_eq!(&t[0..6], &[1.0, 0.0, 0.0, 0.0, 0.0, 0.0]);
        assert_eq!(&t[6..12], &[0.0, 1.0, 0.0, 0.0, 0.0, 0.0]);
        assert!(t[12..].iter().all(|v| *v == 0.0));
    }

    #[test]
    fn bilinear_is_exact_on_linear_ramps_and_clamps() {
        // f(x, y) = 2x + 3y on a 4x3 grid.
        let (w, h) = (4, 3);
        let plane: Vec<f32> = (0..h)
            .flat_map(|y| (0..w).map(move |x| 2.0 * x as f32 + 3.0 * y as f32))
            .collect();
        assert!((sample_bilinear(&plane, w, h, 1.25, 0.5) - 4.0).abs() < 1e-6);
        assert_eq!(sample_bilinear(&plane, w, h, -5.0, -1.0), 0.0);
        assert_eq!(sample_bilinear(&plane, w, h, 10.0, 10.0), 12.0);
        // Doubling the size keeps the ramp inside (centres at (x + 0.5) / 2 - 0.5).
        let big = resize_plane(&plane, w, h, 8, 6);
        let v = big[2 * 8 + 3]; // x = 3 -> 1.25, y = 2 -> 0.75
        assert!((v - (2.0 * 1.25 + 3.0 * 0.75)).abs() < 1e-5, "{v}");
    }
}
