//! Dense matching through a LoFTR-style ONNX model, implementing the correspond stage's
//! [`Matcher`](scenethesis_correspondence::Matcher) seam.
//!
//! Expected signature (every name configurable in [`MatcherConfig`]):
//! - two inputs `image0` and `image1`, float32 `[1, C, H, W]` with `C` = 1 (grey 0..1, as LoFTR
//!   exports take) or 3 (the grey value in every channel). When `H` and `W` are static both
//!   images are resized to exactly that size; when dynamic, so that the longer side is
//!   [`MatcherConfig::input_size`] (aspect kept, sides rounded to
//!   [`MatcherConfig::multiple_of`], 8 for LoFTR's coarse grid).
//! - outputs `keypoints0` and `keypoints1`, float32 `[N, 2]` or `[1, N, 2]`: matched points of
//!   the two images in model-input pixels (`x` right, `y` down, pixel `k`'s centre at `k`), and
//!   `confidence`, float32 `[N]` or `[1, N]`.
//!
//! What the model sees: `image0` is the asset rendered at its current pose — its colour when
//! the renderer gave one, else shading from the rendered depth (the surface normal against the
//! viewing ray), so untextured procedural assets still show their faces and edges — and
//! `image1` is the guidance image's grey values under the object's visible mask. Both are cut
//! from the same window of the guidance image (the rendered view's window joined with the
//! mask's box and a margin) and are black elsewhere, so the model compares only the asset with
//! its object. Matches below [`MatcherConfig::min_confidence`], on pixels the asset does not
//! cover, or off the mask (pixels hidden by nearer objects, or another object) are dropped; the
//! most confident [`MatcherConfig::max_matches`] are kept.

use nalgebra::{Point2, Vector3};
use scenethesis_correspondence::{MatchKind, PixelMatch, RenderedView, TargetRegion};

/// How the two images are fed to a dense matcher and how its matches are read.
#[derive(Debug, Clone, PartialEq)]
pub struct MatcherConfig {
    /// Input: the rendered asset.
    pub image0: String,
    /// Input: the guidance region.
    pub image1: String,
    /// Output: matched points in `image0`.
    pub keypoints0: String,
    /// Output: matched points in `image1`.
    pub keypoints1: String,
    /// Output: one confidence per match.
    pub confidence: String,
    /// Longer side of the model input when the model's input size is dynamic.
    pub input_size: u32,
    /// Both input sides are rounded to a multiple of this when the size is dynamic.
    pub multiple_of: u32,
    /// Matches less confident than this are dropped.
    pub min_confidence: f32,
    /// At most this many matches are kept (the most confident).
    pub max_matches: usize,
    /// Guidance pixels added around the window both images are cut from.
    pub margin: u32,
}

impl Default for MatcherConfig {
    fn default() -> Self {
        Self {
            image0: "image0".into(),
            image1: "image1".into(),
            keypoints0: "keypoints0".into(),
            keypoints1: "keypoints1".into(),
            confidence: "confidence".into(),
            input_size: 640,
            multiple_of: 8,
            min_confidence: 0.2,
            max_matches: 400,
            margin: 8,
        }
    }
}

impl MatcherConfig {
    /// The model input size (width, height) for a window of `width` x `height` when the model
    /// accepts any size: longer side `input_size`, aspect kept, both sides rounded to the
    /// nearest multiple of `multiple_of` (at least one multiple).
    ///
    /// ```
    /// use scenethesis_onnx::MatcherConfig;
    /// let c = MatcherConfig::default();
    /// assert_eq!(c.dynamic_input_size(200, 100), (640, 320));
    /// assert_eq!(c.dynamic_input_size(90, 300), (192, 640));
    /// ```
    pub fn dynamic_input_size(&self, width: u32, height: u32) -> (u32, u32) {
        let scale = self.input_size as f64 / f64::from(width.max(height).max(1));
        let m = f64::from(self.multiple_of.max(1));
        let round = |side: u32| ((f64::from(side) * scale / m).round().max(1.0) * m) as u32;
        (round(width), round(height))
    }

    #[cfg_attr(not(feature = "runtime"), allow(dead_code))]
    pub(crate) fn validate(&self) -> Result<(), crate::OnnxError> {
        let bad = |what: &str, message: String| {
            Err(crate::OnnxError::Config {
                what: format!("matcher setting `{what}`"),
                message,
            })
        };
        if self.input_size == 0 || self.multiple_of == 0 {
            return bad(
                "input_size/multiple_of",
                format!(
                    "both must be positive, got {} and {}",
                    self.input_size, self.multiple_of
                ),
            );
        }
        if !(0.0..=1.0).contains(&self.min_confidence) {
            return bad(
                "min_confidence",
                format!("expected a value in [0, 1], got {}", self.min_confidence),
            );
        }
        if self.max_matches == 0 {
            return bad("max_matches", "must be at least 1".into());
        }
        Ok(())
    }
}

/// The window of the guidance image both matcher inputs are cut from, in guidance pixels.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Crop {
    /// Left column.
    pub x0: u32,
    /// Top row.
    pub y0: u32,
    /// Width in pixels (at least 1).
    pub width: u32,
    /// Height in pixels (at least 1).
    pub height: u32,
}

/// The rendered view's window joined with the mask's box, grown by `margin` and clamped to the
/// guidance image; `None` when the mask is empty or the view lies outside the image.
pub fn crop_for(view: &RenderedView, target: &TargetRegion<'_>, margin: u32) -> Option<Crop> {
    let (iw, ih) = (
        target.camera.intrinsics.width,
        target.camera.intrinsics.height,
    );
    let (mx0, my0, mx1, my1) = target.mask.bounding_box()?;
    let s = view.stride.max(1);
    let (vx0, vy0) = (view.offset[0], view.offset[1]);
    let (vx1, vy1) = (vx0 + view.depth.width() * s, vy0 + view.depth.height() * s);
    let x0 = mx0.min(vx0).saturating_sub(margin);
    let y0 = my0.min(vy0).saturating_sub(margin);
    let x1 = (mx1.max(vx1) + margin).min(iw);
    let y1 = (my1.max(vy1) + margin).min(ih);
    (x1 > x0 && y1 > y0).then_some(Crop {
        x0,
        y0,
        width: x1 - x0,
        height: y1 - y0,
    })
}

/// Grey levels (0..1) of the rendered asset per view pixel, row-major: the view's colour
/// (Rec. 601 luma) when it has one, else `0.25 + 0.75 |n · r|` for the surface normal `n`
/// estimated from the rendered depth and the viewing ray `r`; 0 where the asset is not seen.
pub fn rendered_grey(view: &RenderedView) -> Vec<f32> {
    let (w, h) = (view.depth.width(), view.depth.height());
    // Every covered pixel's surface point, unprojected once (each is also its neighbours'
    // neighbour).
    let points: Vec<Option<Vector3<f64>>> = (0..w * h)
        .map(|i| {
            let (x, y) = (i % w, i / w);
            view.depth.get(x, y).map(|d| {
                view.camera
                    .unproject(&Point2::new(x as f64 + 0.5, y as f64 + 0.5), d as f64)
                    .coords
            })
        })
        .collect();
    let point = |x: u32, y: u32| points[(y * w + x) as usize];
    let mut out = vec![0.0f32; (w * h) as usize];
    for y in 0..h {
        for x in 0..w {
            let Some(p) = point(x, y) else { continue };
            let value = match &view.color {
                Some(colour) => colour.get(x, y).map_or(0.0, luma),
                None => {
                    // Central differences where both neighbours are on the asset, one-sided
                    // otherwise.
                    let along = |a: Option<Vector3<f64>>, b: Option<Vector3<f64>>| match (a, b) {
                        (Some(a), Some(b)) => Some(b - a),
                        (Some(a), None) => Some(p - a),
                        (None, Some(b)) => Some(b - p),
                        (None, None) => None,
                    };
                    let du = along(
                        x.checked_sub(1).and_then(|xl| point(xl, y)),
                        (x + 1 < w).then(|| point(x + 1, y)).flatten(),
                    );
                    let dv = along(
                        y.checked_sub(1).and_then(|yu| point(x, yu)),
                        (y + 1 < h).then(|| point(x, y + 1)).flatten(),
                    );
                    let ray = (p - view.camera.position.coords).normalize();
                    match (du, dv) {
                        (Some(du), Some(dv)) => {
                            let n = du.cross(&dv);
                            let norm = n.norm();
                            if norm > 0.0 {
                                (0.25 + 0.75 * (n / norm).dot(&ray).abs()) as f32
                            } else {
                                1.0
                            }
                        }
                        _ => 1.0,
                    }
                }
            };
            out[(y * w + x) as usize] = value;
        }
    }
    out
}

fn luma(rgb: [u8; 3]) -> f32 {
    (0.299 * f32::from(rgb[0]) + 0.587 * f32::from(rgb[1]) + 0.114 * f32::from(rgb[2])) / 255.0
}

/// The two matcher inputs over `crop`, row-major `crop.width` x `crop.height` grey planes:
/// the rendered asset at its guidance pixels (see [`rendered_grey`]) and the guidance image
/// under the object's mask; 0 elsewhere. `None` when the target has no colour image.
pub fn matcher_inputs(
    view: &RenderedView,
    target: &TargetRegion<'_>,
    crop: Crop,
) -> Option<(Vec<f32>, Vec<f32>)> {
    let image = target.image?;
    let grey = rendered_grey(view);
    let (vw, vh) = (view.depth.width(), view.depth.height());
    let s = view.stride.max(1);
    let n = (crop.width * crop.height) as usize;
    let (mut rendered, mut guidance) = (vec![0.0f32; n], vec![0.0f32; n]);
    for cy in 0..crop.height {
        for cx in 0..crop.width {
            let (gx, gy) = (crop.x0 + cx, crop.y0 + cy);
            let at = (cy * crop.width + cx) as usize;
            if gx >= view.offset[0] && gy >= view.offset[1] {
                let (vx, vy) = ((gx - view.offset[0]) / s, (gy - view.offset[1]) / s);
                if vx < vw && vy < vh {
                    rendered[at] = grey[(vy * vw + vx) as usize];
                }
            }
            if target.mask.contains(gx, gy) {
                guidance[at] = image.get(gx, gy).map_or(0.0, luma);
            }
        }
    }
    Some((rendered, guidance))
}

/// Resizes a row-major grey plane bilinearly (antialiased when shrinking).
pub fn resize_plane(plane: &[f32], width: u32, height: u32, to: (u32, u32)) -> Vec<f32> {
    if (width, height) == to {
        return plane.to_vec();
    }
    let buffer: image::ImageBuffer<image::Luma<f32>, Vec<f32>> =
        image::ImageBuffer::from_raw(width, height, plane.to_vec()).expect("one value per pixel");
    image::imageops::resize(&buffer, to.0, to.1, image::imageops::FilterType::Triangle).into_raw()
}

/// A dense matcher's answer for one pair of inputs.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct RawMatches {
    /// Matched points of `image0` in model-input pixels (centre of pixel `k` at `k`).
    pub keypoints0: Vec<[f32; 2]>,
    /// The matching points of `image1`.
    pub keypoints1: Vec<[f32; 2]>,
    /// One confidence per match.
    pub confidence: Vec<f32>,
    /// The model input's size (width, height).
    pub model_size: (u32, u32),
}

/// The model's matches as pixel pairs of the view and the guidance image: keypoints are mapped
/// back through `crop`; matches below the confidence floor, off the asset, or off the object's
/// mask are dropped, and the most confident `max_matches` kept (ties in model order).
pub fn pixel_matches(
    raw: &RawMatches,
    crop: Crop,
    view: &RenderedView,
    target: &TargetRegion<'_>,
    config: &MatcherConfig,
) -> Vec<PixelMatch> {
    let model = raw.model_size;
    let sx = f64::from(crop.width) / f64::from(model.0.max(1));
    let sy = f64::from(crop.height) / f64::from(model.1.max(1));
    // Continuous guidance coordinates (pixel k spans [k, k + 1)).
    let to_guidance = |k: [f32; 2]| {
        Point2::new(
            f64::from(crop.x0) + (f64::from(k[0]) + 0.5) * sx,
            f64::from(crop.y0) + (f64::from(k[1]) + 0.5) * sy,
        )
    };
    let s = f64::from(view.stride.max(1));
    let (vw, vh) = (view.depth.width(), view.depth.height());
    let mut out: Vec<PixelMatch> = raw
        .keypoints0
        .iter()
        .zip(&raw.keypoints1)
        .zip(&raw.confidence)
        .filter_map(|((k0, k1), &c)| {
            if !(c.is_finite() && c >= config.min_confidence) {
                return None;
            }
            let r = to_guidance(*k0);
            let vx = ((r.x - f64::from(view.offset[0])) / s).floor();
            let vy = ((r.y - f64::from(view.offset[1])) / s).floor();
            if !(vx >= 0.0 && vy >= 0.0 && vx < f64::from(vw) && vy < f64::from(vh)) {
                return None;
            }
            let rendered = [vx as u32, vy as u32];
            view.depth.get(rendered[0], rendered[1])?;
            let t = to_guidance(*k1);
            if !(t.x >= 0.0 && t.y >= 0.0 && target.mask.contains(t.x as u32, t.y as u32)) {
                return None;
            }
            Some(PixelMatch {
                rendered,
                target: t,
                confidence: f64::from(c.min(1.0)),
                kind: MatchKind::Point,
            })
        })
        .collect();
    out.sort_by(|a, b| b.confidence.total_cmp(&a.confidence));
    out.truncate(config.max_matches);
    out
}

/// Points of an output `[N, 2]` or `[1, N, 2]`.
pub fn points_of(shape: &[i64], data: &[f32]) -> Result<Vec<[f32; 2]>, String> {
    let n = match shape {
        [n, 2] | [1, n, 2] if *n >= 0 => *n as usize,
        _ => {
            return Err(format!(
                "expected [N, 2] or [1, N, 2] keypoints, got {shape:?}"
            ))
        }
    };
    if data.len() != 2 * n {
        return Err(format!(
            "shape {shape:?} holds {} values, got {}",
            2 * n,
            data.len()
        ));
    }
    Ok(data.chunks_exact(2).map(|p| [p[0], p[1]]).collect())
}

#[cfg(feature = "runtime")]
pub use with_runtime::OnnxMatcher;

#[cfg(feature = "runtime")]
mod with_runtime {
    use std::path::Path;

    use scenethesis_correspondence::{Matcher, PixelMatch, RenderedView, TargetRegion};

    use super::{
        crop_for, matcher_inputs, pixel_matches, points_of, resize_plane, MatcherConfig, RawMatches,
    };
    use crate::runtime::{Model, Runtime, TensorF32};
    use crate::signature::Signature;
    use crate::OnnxError;

    /// A LoFTR-style dense matcher run through ONNX Runtime (the module docs give the
    /// signature and processing). Running the model never fails the pipeline: a run that
    /// fails yields no matches, and the failure is logged with the model file.
    pub struct OnnxMatcher {
        model: Model,
        config: MatcherConfig,
        /// Static input (width, height), when the model declares one.
        fixed_size: Option<(u32, u32)>,
        /// Channels of the image inputs (1 or 3).
        channels: u32,
        name: String,
    }

    impl std::fmt::Debug for OnnxMatcher {
        fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
            f.debug_struct("OnnxMatcher")
                .field("model", &self.model.path)
                .field("config", &self.config)
                .finish()
        }
    }

    impl OnnxMatcher {
        /// Opens the model at `path` and checks its signature against `config`.
        pub fn new(
            runtime: &Runtime,
            path: impl AsRef<Path>,
            config: MatcherConfig,
        ) -> Result<Self, OnnxError> {
            config.validate()?;
            let path = path.as_ref();
            let model = Model::open(runtime, path)?;
            let signature = Signature::new(&model, "model");
            let mut shapes = Vec::new();
            for name in [&config.image0, &config.image1] {
                let port = signature.input(name, " (a grey image [1, 1, H, W])")?;
                match port.image_dims(|c| matches!(c, 1 | 3 | -1)) {
                    Some(dims) => shapes.push(dims),
                    None => {
                        return Err(signature.error(format!(
                            "input {} should be float32 [1, 1, H, W] (or [1, 3, H, W])",
                            port.describe()
                        )))
                    }
                }
            }
            if shapes[0] != shapes[1] {
                return Err(signature.error(format!(
                    "inputs `{}` and `{}` should have the same shape",
                    config.image0, config.image1
                )));
            }
            let (c, h, w) = shapes[0];
            let fixed_size = (h > 0 && w > 0).then_some((w as u32, h as u32));
            for (name, ranks) in [
                (&config.keypoints0, [2usize, 3]),
                (&config.keypoints1, [2, 3]),
                (&config.confidence, [1, 2]),
            ] {
                let port = signature.output(name)?;
                let rank_ok = port
                    .shape
                    .as_ref()
                    .is_some_and(|s| ranks.contains(&s.len()));
                if !port.float32 || !rank_ok {
                    return Err(signature.error(format!(
                        "output {} should be float32 {}",
                        port.describe(),
                        if ranks[0] == 2 {
                            "[N, 2] or [1, N, 2]"
                        } else {
                            "[N] or [1, N]"
                        }
                    )));
                }
            }
            let name = format!("onnx/{}", crate::model_stem(path));
            Ok(Self {
                model,
                config,
                fixed_size,
                channels: if c == 3 { 3 } else { 1 },
                name,
            })
        }

        /// The model file.
        pub fn model_path(&self) -> &Path {
            &self.model.path
        }

        /// The model input size (width, height) for a window of `width` x `height`.
        pub fn input_size_for(&self, width: u32, height: u32) -> (u32, u32) {
            self.fixed_size
                .unwrap_or_else(|| self.config.dynamic_input_size(width, height))
        }

        fn tensor(&self, plane: Vec<f32>, (w, h): (u32, u32)) -> TensorF32 {
            let data = if self.channels == 3 {
                plane.repeat(3)
            } else {
                plane
            };
            TensorF32 {
                shape: vec![1, i64::from(self.channels), i64::from(h), i64::from(w)],
                data,
            }
        }

        fn run(
            &self,
            view: &RenderedView,
            target: &TargetRegion<'_>,
        ) -> Result<Vec<PixelMatch>, String> {
            let Some(crop) = crop_for(view, target, self.config.margin) else {
                return Ok(Vec::new());
            };
            let Some((rendered, guidance)) = matcher_inputs(view, target, crop) else {
                return Ok(Vec::new());
            };
            let size = self.input_size_for(crop.width, crop.height);
            let c = &self.config;
            let inputs = vec![
                (
                    c.image0.clone(),
                    self.tensor(resize_plane(&rendered, crop.width, crop.height, size), size),
                ),
                (
                    c.image1.clone(),
                    self.tensor(resize_plane(&guidance, crop.width, crop.height, size), size),
                ),
            ];
            let mut outputs = self
                .model
                .run(inputs, &[&c.keypoints0, &c.keypoints1, &c.confidence])?;
            let k0 = points_of(&outputs[0].shape, &outputs[0].data)
                .map_err(|e| format!("output `{}`: {e}", c.keypoints0))?;
            let k1 = points_of(&outputs[1].shape, &outputs[1].data)
                .map_err(|e| format!("output `{}`: {e}", c.keypoints1))?;
            let conf = outputs.swap_remove(2).data;
            if k0.len() != k1.len() || k0.len() != conf.len() {
                return Err(format!(
                    "outputs disagree on the number of matches: {} `{}`, {} `{}`, {} `{}`",
                    k0.len(),
                    c.keypoints0,
                    k1.len(),
                    c.keypoints1,
                    conf.len(),
                    c.confidence
                ));
            }
            let raw = RawMatches {
                keypoints0: k0,
                keypoints1: k1,
                confidence: conf,
                model_size: size,
            };
            Ok(pixel_matches(&raw, crop, view, target, &self.config))
        }
    }

    impl Matcher for OnnxMatcher {
        fn name(&self) -> &str {
            &self.name
        }

        fn match_view(&self, view: &RenderedView, target: &TargetRegion<'_>) -> Vec<PixelMatch> {
            match self.run(view, target) {
                Ok(matches) => matches,
                Err(message) => {
                    tracing::warn!(
                        model = %self.model.path.display(),
                        "the dense matcher failed, so this view has no matches: {message}"
                    );
                    Vec::new()
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_imagery::{Camera, DepthMap, Intrinsics, Mask, RgbImage};
    use scenethesis_scene_graph::Pose;

    fn camera(w: u32, h: u32) -> Camera {
        Camera::look_at(
            Intrinsics::from_vertical_fov(w, h, 45f64.to_radians()),
            nalgebra::Point3::new(0.0, 0.0, 3.0),
            nalgebra::Point3::origin(),
            Vector3::y(),
        )
    }

    /// A view of a plane facing the camera at depth 3 covering view pixels x in 2..6, y in 1..4,
    /// placed at guidance offset (10, 20).
    fn flat_view() -> RenderedView {
        let depth = DepthMap::from_fn(8, 6, |x, y| {
            if (2..6).contains(&x) && (1..4).contains(&y) {
                3.0
            } else {
                f32::NAN
            }
        });
        RenderedView {
            camera: camera(8, 6),
            offset: [10, 20],
            stride: 1,
            pose: Pose::IDENTITY,
            depth,
            color: None,
        }
    }

    #[test]
    fn dynamic_input_keeps_the_aspect_in_multiples() {
        let c = MatcherConfig::default();
        assert_eq!(c.dynamic_input_size(640, 480), (640, 480));
        assert_eq!(c.dynamic_input_size(33, 31), (640, 600));
        let small = MatcherConfig {
            input_size: 20,
            multiple_of: 8,
            ..c
        };
        assert_eq!(small.dynamic_input_size(100, 10), (24, 8));
    }

    #[test]
    fn bad_settings_are_named() {
        let c = MatcherConfig {
            min_confidence: 2.0,
            ..MatcherConfig::default()
        };
        let e = c.validate().unwrap_err().to_string();
        assert!(e.contains("min_confidence") && e.contains("[0, 1]"), "{e}");
    }

    #[test]
    fn a_plane_facing_the_camera_is_bright_and_uncovered_pixels_black() {
        let grey = rendered_grey(&flat_view());
        assert_eq!(grey.len(), 48);
        assert_eq!(grey[0], 0.0);
        // Facing the ray: |n · r| ≈ 1 (off-axis pixels lean a little).
        let centre = grey[2 * 8 + 3];
        assert!(centre > 0.97, "{centre}");
        assert!(grey.iter().filter(|v| **v > 0.0).count() == 12);
    }

    #[test]
    fn a_tilted_plane_is_darker_than_a_facing_one() {
        let mut view = flat_view();
        // Depth growing 0.5 m per pixel column: a plane seen at a glancing angle.
        view.depth = DepthMap::from_fn(8, 6, |x, _| 3.0 + 0.5 * x as f32);
        let grey = rendered_grey(&view);
        let facing = rendered_grey(&flat_view())[2 * 8 + 3];
        assert!(
            grey[2 * 8 + 3] < facing - 0.1,
            "{} vs {facing}",
            grey[2 * 8 + 3]
        );
    }

    fn target_parts() -> (Camera, Mask, RgbImage) {
        let cam = camera(64, 48);
        let mut mask = Mask::new(64, 48);
        for y in 22..26 {
            for x in 14..20 {
                mask.set(x, y, true);
            }
        }
        let image = RgbImage::new(64, 48, vec![200; 64 * 48 * 3]).unwrap();
        (cam, mask, image)
    }

    #[test]
    fn inputs_cover_the_view_and_the_mask_and_black_out_the_rest() {
        let (cam, mask, image) = target_parts();
        let target = TargetRegion {
            camera: &cam,
            mask: &mask,
            depth: None,
            image: Some(&image),
        };
        let view = flat_view();
        let crop = crop_for(&view, &target, 2).unwrap();
        // View window x 10..18, y 20..26; mask x 14..20, y 22..26; grown by 2.
        assert_eq!(
            crop,
            Crop {
                x0: 8,
                y0: 18,
                width: 14,
                height: 10
            }
        );
        let (rendered, guidance) = matcher_inputs(&view, &target, crop).unwrap();
        let at = |x: u32, y: u32| ((y - crop.y0) * crop.width + (x - crop.x0)) as usize;
        assert!(rendered[at(13, 22)] > 0.9 && rendered[at(16, 22)] == 0.0);
        let grey200 = 200.0 / 255.0;
        assert!((guidance[at(15, 23)] - grey200).abs() < 1e-5);
        assert_eq!(guidance[at(12, 23)], 0.0, "off the mask");
        let without_image = TargetRegion {
            image: None,
            ..target
        };
        assert!(matcher_inputs(&view, &without_image, crop).is_none());
    }

    #[test]
    fn matches_map_back_and_are_filtered() {
        let (cam, mask, image) = target_parts();
        let target = TargetRegion {
            camera: &cam,
            mask: &mask,
            depth: None,
            image: Some(&image),
        };
        let view = flat_view();
        let crop = Crop {
            x0: 8,
            y0: 18,
            width: 14,
            height: 10,
        };
        let raw = RawMatches {
            keypoints0: vec![[10.0, 8.0], [10.0, 8.0], [0.0, 0.0], [10.0, 8.0]],
            keypoints1: vec![[14.0, 10.0], [14.0, 10.0], [14.0, 10.0], [0.0, 0.0]],
            confidence: vec![0.9, 0.1, 0.9, 0.9],
            // The model saw the crop at twice its size.
            model_size: (28, 20),
        };
        let m = pixel_matches(&raw, crop, &view, &target, &MatcherConfig::default());
        // Kept: the first (the second is not confident, the third is off the asset, the last
        // off the mask).
        assert_eq!(m.len(), 1, "{m:?}");
        // Model (10, 8) → guidance 8 + 10.5 · 0.5 = 13.25, 18 + 8.5 · 0.5 = 22.25 → view (3, 2).
        assert_eq!(m[0].rendered, [3, 2]);
        assert!((m[0].target.x - 15.25).abs() < 1e-9 && (m[0].target.y - 23.25).abs() < 1e-9);
        assert_eq!(m[0].kind, MatchKind::Point);
    }

    #[test]
    fn keypoint_shapes_are_checked() {
        assert_eq!(
            points_of(&[1, 2, 2], &[1.0, 2.0, 3.0, 4.0]),
            Ok(vec![[1.0, 2.0], [3.0, 4.0]])
        );
        assert!(points_of(&[2, 3], &[0.0; 6]).is_err());
        assert!(points_of(&[3, 2], &[0.0; 4]).is_err());
    }
}
