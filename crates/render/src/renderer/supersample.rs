//! Anti-aliased colour images: a view rendered at a multiple of its size and averaged down in
//! linear light.

use image::RgbaImage;
use scenethesis_imagery::Camera;

use super::{PreparedScene, Renderer};
use crate::RenderError;

impl Renderer {
    /// The colour image of `camera`'s view rendered at `factor` × its resolution and averaged
    /// down (in linear light) to the camera's size: anti-aliased previews. `factor` 1 is a
    /// plain render.
    pub fn render_color_supersampled(
        &self,
        scene: &PreparedScene,
        camera: &Camera,
        factor: u32,
    ) -> Result<RgbaImage, RenderError> {
        let factor = factor.max(1);
        let k = camera.intrinsics;
        let mut big = *camera;
        big.intrinsics = k.resized(k.width * factor, k.height * factor);
        let frame = self.render_prepared(scene, &big)?;
        if factor == 1 {
            return Ok(frame.color);
        }
        let to_linear: Vec<f32> = (0..256).map(|v| srgb_to_linear(v as f32 / 255.0)).collect();
        let n = (factor * factor) as f32;
        Ok(RgbaImage::from_fn(k.width, k.height, |x, y| {
            let mut sum = [0.0f32; 3];
            for dy in 0..factor {
                for dx in 0..factor {
                    let p = frame.color.get_pixel(x * factor + dx, y * factor + dy).0;
                    for c in 0..3 {
                        sum[c] += to_linear[p[c] as usize];
                    }
                }
            }
            image::Rgba([
                linear_to_srgb8(sum[0] / n),
                linear_to_srgb8(sum[1] / n),
                linear_to_srgb8(sum[2] / n),
                255,
            ])
        }))
    }
}

/// An sRGB-encoded value in [0, 1] in linear light.
fn srgb_to_linear(c: f32) -> f32 {
    if c <= 0.04045 {
        c / 12.92
    } else {
        ((c + 0.055) / 1.055).powf(2.4)
    }
}

/// A linear-light value as an 8-bit sRGB level.
fn linear_to_srgb8(l: f32) -> u8 {
    let c = if l <= 0.003_130_8 {
        l * 12.92
    } else {
        1.055 * l.powf(1.0 / 2.4) - 0.055
    };
    (c * 255.0).round().clamp(0.0, 255.0) as u8
}
