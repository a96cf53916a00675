//! A rendered frame on the CPU: colour, metric depth and instance ids, with encoders.

use image::{GrayImage, ImageBuffer, Luma, RgbaImage};
use scenethesis_imagery::{encode_png, DepthMap};

use crate::RenderError;

/// The three images of one render, all `width × height`, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// sRGB colour, opaque.
    pub color: RgbaImage,
    /// Distance along the camera's optical axis (its −Z) in metres; `0.0` (unknown) where no
    /// geometry was hit (background).
    pub depth: DepthMap,
    /// Instance index per pixel, row-major: `0` for background, `k ≥ 1` for `ids[k - 1]`.
    pub instance: Vec<u32>,
    /// The id table: objects in the scene's order, then the architecture (floor, walls) and
    /// ground plane if any.
    pub ids: Vec<String>,
}

impl Frame {
    /// Image width in pixels.
    pub fn width(&self) -> u32 {
        self.color.width()
    }

    /// Image height in pixels.
    pub fn height(&self) -> u32 {
        self.color.height()
    }

    fn index(&self, x: u32, y: u32) -> usize {
        assert!(
            x < self.width() && y < self.height(),
            "pixel ({x}, {y}) is outside the {}×{} frame",
            self.width(),
            self.height()
        );
        (y * self.width() + x) as usize
    }

    /// Depth at pixel (x, y) in metres, or `None` for background (and outside the frame).
    pub fn depth_at(&self, x: u32, y: u32) -> Option<f32> {
        self.depth.get(x, y)
    }

    /// The id shown at pixel (x, y), or `None` for background.
    pub fn id_at(&self, x: u32, y: u32) -> Option<&str> {
        let k = self.instance[self.index(x, y)];
        self.id_of(k)
    }

    /// The id an instance index stands for (`None` for 0 or out of range).
    pub fn id_of(&self, index: u32) -> Option<&str> {
        (index as usize)
            .checked_sub(1)
            .and_then(|i| self.ids.get(i))
            .map(String::as_str)
    }

    /// The instance index of `id`, if the scene had it.
    pub fn index_of(&self, id: &str) -> Option<u32> {
        self.ids.iter().position(|x| x == id).map(|i| i as u32 + 1)
    }

    /// The visible mask of `id`: 255 where the object is seen, 0 elsewhere (all 0 for an
    /// unknown id).
    pub fn mask(&self, id: &str) -> GrayImage {
        let k = self.index_of(id).unwrap_or(0);
        let pixels = self
            .instance
            .iter()
            .map(|&v| if k != 0 && v == k { 255 } else { 0 })
            .collect();
        GrayImage::from_raw(self.width(), self.height(), pixels).expect("one byte per pixel")
    }

    /// Number of pixels showing `id`.
    pub fn pixel_count(&self, id: &str) -> usize {
        match self.index_of(id) {
            Some(k) => self.instance.iter().filter(|&&v| v == k).count(),
            None => 0,
        }
    }

    /// The colour image encoded as PNG.
    pub fn color_png(&self) -> Result<Vec<u8>, RenderError> {
        Ok(encode_png(&self.color)?)
    }

    /// Depth as a 16-bit greyscale image in millimetres (0 = background, saturating at
    /// 65.535 m), the common format of depth cameras.
    pub fn depth_u16_mm(&self) -> ImageBuffer<Luma<u16>, Vec<u16>> {
        let pixels = self
            .depth
            .values()
            .iter()
            .map(|&d| (d * 1000.0).round().clamp(0.0, 65535.0) as u16)
            .collect();
        ImageBuffer::from_raw(self.width(), self.height(), pixels).expect("one value per pixel")
    }

    /// The 16-bit millimetre depth image encoded as PNG.
    pub fn depth_png16(&self) -> Result<Vec<u8>, RenderError> {
        Ok(encode_png(&self.depth_u16_mm())?)
    }

    /// The instance image encoded as a 16-bit greyscale PNG of instance indices (ids beyond
    /// 65535 saturate).
    pub fn instance_png16(&self) -> Result<Vec<u8>, RenderError> {
        let pixels = self.instance.iter().map(|&k| k.min(65535) as u16).collect();
        let img: ImageBuffer<Luma<u16>, Vec<u16>> =
            ImageBuffer::from_raw(self.width(), self.height(), pixels).expect("one per pixel");
        Ok(encode_png(&img)?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn frame() -> Frame {
        Frame {
            color: RgbaImage::new(3, 2),
            depth: DepthMap::new(3, 2, vec![0.0, 1.5, 2.0, 0.0, 0.25, 70.0]).unwrap(),
            instance: vec![0, 1, 2, 0, 1, 2],
            ids: vec!["chair_0".into(), "floor".into()],
        }
    }

    #[test]
    fn lookups_and_masks_follow_the_id_table() {
        let f = frame();
        assert_eq!(f.id_at(1, 0), Some("chair_0"));
        assert_eq!(f.id_at(0, 0), None);
        assert_eq!(f.depth_at(0, 1), None);
        assert_eq!(f.depth_at(1, 1), Some(0.25));
        assert_eq!(f.mask("floor").into_raw(), vec![0, 0, 255, 0, 0, 255]);
        assert_eq!(f.pixel_count("chair_0"), 2);
        assert_eq!(f.pixel_count("nothing"), 0);
        assert_eq!(
            f.depth_u16_mm().into_raw(),
            vec![0, 1500, 2000, 0, 250, 65535]
        );
    }
}
