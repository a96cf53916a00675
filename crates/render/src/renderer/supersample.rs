//! Anti-aliased colour images: a view rendered at a multiple of its size and averaged down in
//! linear light on the device, by the ambient-occlusion pass, so that only the final image at
//! its own size is shaded for occlusion and read back.

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
        let mut planes = self.render_planes(scene, &big, factor)?;
        let color = planes.swap_remove(0);
        RgbaImage::from_raw(k.width, k.height, color)
            .ok_or_else(|| RenderError::Readback("the colour plane read back malformed".into()))
    }
}
