//! The colour image, the metric depth map and the guidance data a vision guide hands the
//! optimizer: camera, colour image, optional metric depth and one instance mask per object.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::camera::Camera;
use crate::error::GuidanceError;
use crate::mask::Mask;

fn check_len(
    what: &str,
    width: u32,
    height: u32,
    len: usize,
    per_pixel: usize,
) -> Result<(), GuidanceError> {
    let expected = width as usize * height as usize * per_pixel;
    if len == expected {
        Ok(())
    } else {
        Err(GuidanceError::BufferSize {
            what: what.to_owned(),
            width,
            height,
            len,
            expected,
        })
    }
}

/// An 8-bit sRGB colour image, rows top to bottom, 3 bytes per pixel.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct RgbImage {
    width: u32,
    height: u32,
    data: Vec<u8>,
}

impl RgbImage {
    /// An image from `width × height × 3` bytes (row-major RGB).
    pub fn new(width: u32, height: u32, data: Vec<u8>) -> Result<Self, GuidanceError> {
        check_len("image", width, height, data.len(), 3)?;
        Ok(Self {
            width,
            height,
            data,
        })
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The RGB bytes, row-major.
    pub fn as_bytes(&self) -> &[u8] {
        &self.data
    }

    /// The colour at pixel (x, y); `None` outside the image.
    pub fn get(&self, x: u32, y: u32) -> Option<[u8; 3]> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let i = (y as usize * self.width as usize + x as usize) * 3;
        Some([self.data[i], self.data[i + 1], self.data[i + 2]])
    }

    /// The image as PNG file bytes (8-bit RGB).
    ///
    /// ```
    /// use scenethesis_imagery::RgbImage;
    /// let red = RgbImage::new(2, 1, vec![255, 0, 0, 255, 0, 0]).unwrap();
    /// assert_eq!(&red.to_png()[1..4], b"PNG");
    /// ```
    pub fn to_png(&self) -> Vec<u8> {
        let view = image::ImageBuffer::<image::Rgb<u8>, &[u8]>::from_raw(
            self.width,
            self.height,
            &self.data,
        )
        .expect("a checked RGB buffer holds its pixels");
        crate::encode_png(&view).expect("an in-memory PNG of a checked RGB buffer encodes")
    }

    /// The colour channels of an RGBA image (alpha dropped), e.g. a render's opaque colour.
    ///
    /// ```
    /// use scenethesis_imagery::RgbImage;
    /// let rgba = image::RgbaImage::from_pixel(2, 1, image::Rgba([10, 20, 30, 255]));
    /// assert_eq!(RgbImage::from_rgba(&rgba).get(1, 0), Some([10, 20, 30]));
    /// ```
    pub fn from_rgba(image: &image::RgbaImage) -> Self {
        Self {
            width: image.width(),
            height: image.height(),
            data: image
                .pixels()
                .flat_map(|p| [p.0[0], p.0[1], p.0[2]])
                .collect(),
        }
    }
}

/// Metric depth along the camera's optical axis (its −Z), in metres, rows top to bottom.
/// `NaN` or `0` marks an unknown pixel.
///
/// In JSON (a depth model's recorded answer) it is `{"width", "height", "metres"}` with `0`
/// for every unknown pixel, since JSON holds no `NaN`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(into = "DepthRecord", try_from = "DepthRecord")]
pub struct DepthMap {
    width: u32,
    height: u32,
    data: Vec<f32>,
}

/// A [`DepthMap`] as written to JSON.
#[derive(Serialize, Deserialize)]
struct DepthRecord {
    width: u32,
    height: u32,
    metres: Vec<f32>,
}

impl From<DepthMap> for DepthRecord {
    fn from(d: DepthMap) -> Self {
        Self {
            width: d.width,
            height: d.height,
            metres: d
                .data
                .into_iter()
                .map(|v| if v.is_nan() { 0.0 } else { v })
                .collect(),
        }
    }
}

impl TryFrom<DepthRecord> for DepthMap {
    type Error = GuidanceError;

    fn try_from(r: DepthRecord) -> Result<Self, GuidanceError> {
        DepthMap::new(r.width, r.height, r.metres)
    }
}

impl DepthMap {
    /// A depth map from `width × height` values in metres; rejects negative or infinite values.
    pub fn new(width: u32, height: u32, data: Vec<f32>) -> Result<Self, GuidanceError> {
        check_len("depth", width, height, data.len(), 1)?;
        if let Some(i) = data.iter().position(|d| d.is_infinite() || *d < 0.0) {
            return Err(GuidanceError::BadDepth {
                x: (i % width as usize) as u32,
                y: (i / width as usize) as u32,
                value: data[i],
            });
        }
        Ok(Self {
            width,
            height,
            data,
        })
    }

    /// A depth map whose value at (x, y) is `f(x, y)`; negative or infinite values become
    /// unknown (`NaN`).
    pub fn from_fn(width: u32, height: u32, mut f: impl FnMut(u32, u32) -> f32) -> Self {
        let mut data = Vec::with_capacity(width as usize * height as usize);
        for y in 0..height {
            for x in 0..width {
                let d = f(x, y);
                data.push(if d.is_infinite() || d < 0.0 {
                    f32::NAN
                } else {
                    d
                });
            }
        }
        Self {
            width,
            height,
            data,
        }
    }

    /// Width in pixels.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// Height in pixels.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// The raw values, row-major (`NaN` or `0` = unknown).
    pub fn values(&self) -> &[f32] {
        &self.data
    }

    /// The depth at pixel (x, y) in metres; `None` outside the image or where unknown.
    pub fn get(&self, x: u32, y: u32) -> Option<f32> {
        if x >= self.width || y >= self.height {
            return None;
        }
        let d = self.data[y as usize * self.width as usize + x as usize];
        (d.is_finite() && d > 0.0).then_some(d)
    }
}

/// What a guide saw, handed to the optimizer's alignment stage: the camera, the guidance
/// image, optional metric depth and the visible mask of each object by id.
#[derive(Debug, Clone, PartialEq)]
pub struct Guidance {
    /// The camera the image was taken with (its intrinsics give the image size).
    pub camera: Camera,
    /// The guidance colour image.
    pub image: RgbImage,
    /// Metric depth of the guidance image, when known.
    pub depth: Option<DepthMap>,
    /// The visible pixels of each object, by object id.
    pub masks: BTreeMap<String, Mask>,
}

impl Guidance {
    /// Guidance from its parts, checking that the image, depth and masks all have the
    /// camera's size.
    pub fn new(
        camera: Camera,
        image: RgbImage,
        depth: Option<DepthMap>,
        masks: BTreeMap<String, Mask>,
    ) -> Result<Self, GuidanceError> {
        let (cw, ch) = (camera.intrinsics.width, camera.intrinsics.height);
        let check = |what: String, w: u32, h: u32| {
            if (w, h) == (cw, ch) {
                Ok(())
            } else {
                Err(GuidanceError::SizeMismatch {
                    what,
                    width: w,
                    height: h,
                    camera_width: cw,
                    camera_height: ch,
                })
            }
        };
        check("the guidance image".into(), image.width(), image.height())?;
        if let Some(d) = &depth {
            check("the depth map".into(), d.width(), d.height())?;
        }
        for (id, m) in &masks {
            check(format!("the mask of `{id}`"), m.width(), m.height())?;
        }
        Ok(Self {
            camera,
            image,
            depth,
            masks,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::camera::Intrinsics;
    use nalgebra::{Point3, Vector3};

    fn camera(w: u32, h: u32) -> Camera {
        Camera::look_at(
            Intrinsics::from_vertical_fov(w, h, 1.0),
            Point3::new(0.0, 1.5, 3.0),
            Point3::origin(),
            Vector3::y(),
        )
    }

    #[test]
    fn buffers_must_match_their_size() {
        assert!(RgbImage::new(2, 2, vec![0; 12]).is_ok());
        let e = RgbImage::new(2, 2, vec![0; 11]).unwrap_err();
        assert!(e.to_string().contains("expected 12"), "{e}");
        assert!(Mask::from_flags(3, 1, vec![true; 2]).is_err());
    }

    #[test]
    fn depth_rejects_negative_and_infinite_values_and_hides_unknown_ones() {
        let e = DepthMap::new(2, 1, vec![1.0, -0.5]).unwrap_err();
        assert_eq!(
            e,
            GuidanceError::BadDepth {
                x: 1,
                y: 0,
                value: -0.5
            }
        );
        assert!(DepthMap::new(1, 1, vec![f32::INFINITY]).is_err());
        let d = DepthMap::new(3, 1, vec![f32::NAN, 0.0, 1.5]).unwrap();
        assert_eq!(
            (d.get(0, 0), d.get(1, 0), d.get(2, 0)),
            (None, None, Some(1.5))
        );
        assert_eq!(d.get(3, 0), None);
    }

    #[test]
    fn depth_round_trips_through_json_with_unknown_as_zero() {
        let d = DepthMap::new(3, 1, vec![f32::NAN, 0.0, 1.5]).unwrap();
        let json = serde_json::to_string(&d).unwrap();
        assert_eq!(json, r#"{"width":3,"height":1,"metres":[0.0,0.0,1.5]}"#);
        let back: DepthMap = serde_json::from_str(&json).unwrap();
        assert_eq!((back.get(0, 0), back.get(2, 0)), (None, Some(1.5)));
        assert!(
            serde_json::from_str::<DepthMap>(r#"{"width":2,"height":1,"metres":[1.0]}"#).is_err()
        );
    }

    #[test]
    fn guidance_checks_every_image_against_the_camera() {
        let img = RgbImage::new(8, 6, vec![0; 8 * 6 * 3]).unwrap();
        let mut masks = BTreeMap::new();
        masks.insert("sofa_0".to_owned(), Mask::new(8, 6));
        assert!(Guidance::new(camera(8, 6), img.clone(), None, masks.clone()).is_ok());
        masks.insert("lamp_0".to_owned(), Mask::new(8, 5));
        let e = Guidance::new(camera(8, 6), img, None, masks).unwrap_err();
        assert!(e.to_string().contains("`lamp_0`"), "{e}");
    }
}
