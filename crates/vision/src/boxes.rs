//! Phase 4: one gravity-aligned box per object, and the whole lift ([`lift_scene`]).
//!
//! Heights come first: the box spans the robust vertical extent of the object's points, snapped
//! to the floor when its bottom is within reach of it. The footprint is the minimum-area floor
//! rectangle of the points. A camera sees only the near faces of an object, so when the caller
//! knows the object's real size (the retrieved asset's, as a prior) the box is completed: the
//! rectangle's orientation is chosen to match the prior's proportions and each horizontal extent
//! grows to the prior's, away from the camera, where the hidden part is.

use std::collections::BTreeMap;

use nalgebra::{Point2, Point3, Vector2, Vector3};
use serde::{Deserialize, Serialize};

use crate::footprint::{min_area_rectangle, FloorRectangle};
pub use crate::lifted_box::{DepthSource, LiftedBox};
use crate::metrology::floor_contact_points;
use crate::metrology::floor_hit;
use crate::points::{largest_cluster, mask_points, median, quantile};
use crate::support::{infer_supports, SupportGuess};
use crate::{Guidance, LiftError};
use scenethesis_correspondence::{DepthMap, Mask};
use scenethesis_scene_graph::Camera;

/// Tuning of the lift. The defaults suit indoor scenes seen from a person's height.
#[derive(Debug, Clone, PartialEq)]
pub struct LiftOptions {
    /// Pixel subsampling (1 = every pixel).
    pub stride: u32,
    /// Smallest clustering voxel edge in metres; grows with distance (3 % of the median depth)
    /// so depth noise does not split an object.
    pub voxel: f64,
    /// Fraction of points ignored at each end of every extent (robustness to stray points).
    pub trim: f64,
    /// Largest gap in metres between a bottom and the floor or a supporting top that still
    /// counts as contact.
    pub contact_gap: f64,
    /// Radius in pixels of the median filter applied to each mask's depth before lifting
    /// (0 = none, the default: on the round trip's perturbed renders a 5 × 5 median did not
    /// lower the median errors).
    pub depth_filter_radius: u32,
    /// Fewer points than this and the object is reported missing.
    pub min_points: usize,
    /// Rescale the depth map so that the visible floor (pixels outside every mask whose ray
    /// meets y = 0) lies at y = 0: monocular depth models get the global scale wrong by several
    /// per cent, and the known camera height fixes it.
    pub calibrate_on_floor: bool,
    /// Known full sizes `(x, y, z)` in metres per object id, in the object's own frame
    /// (+Z front): used to complete the hidden side and to pick the footprint's orientation.
    pub priors: BTreeMap<String, Vector3<f64>>,
}

impl Default for LiftOptions {
    fn default() -> Self {
        Self {
            stride: 1,
            voxel: 0.06,
            trim: 0.01,
            contact_gap: 0.06,
            depth_filter_radius: 0,
            min_points: 12,
            calibrate_on_floor: true,
            priors: BTreeMap::new(),
        }
    }
}

impl LiftOptions {
    fn check(&self) -> Result<(), LiftError> {
        let bad = |field, value: f64, expected| {
            Err(LiftError::BadOption {
                field,
                value,
                expected,
            })
        };
        if !self.voxel.is_finite() || self.voxel <= 0.0 {
            return bad("voxel", self.voxel, "a positive number of metres");
        }
        if !(0.0..0.5).contains(&self.trim) {
            return bad("trim", self.trim, "a fraction in [0, 0.5)");
        }
        if !self.contact_gap.is_finite() || self.contact_gap < 0.0 {
            return bad(
                "contact_gap",
                self.contact_gap,
                "a non-negative number of metres",
            );
        }
        Ok(())
    }
}

/// The lift of a whole guidance image.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LiftedScene {
    /// One box per recovered object, by id.
    pub boxes: Vec<LiftedBox>,
    /// Ids whose masks gave too few points to place (never invented).
    pub missing: Vec<String>,
    /// The support of every box, by id.
    pub supports: Vec<SupportGuess>,
    /// The factor the depth map was multiplied by (1 when not calibrated or without depth).
    pub depth_scale: f64,
}

/// Lifts every mask of `guidance` to a box and infers their supports. Uses the depth map when
/// there is one and single-view metrology otherwise.
pub fn lift_scene(guidance: &Guidance, options: &LiftOptions) -> Result<LiftedScene, LiftError> {
    options.check()?;
    let camera = &guidance.camera;
    let mut depth_scale = 1.0;
    let scaled;
    let depth = match &guidance.depth {
        Some(d) if options.calibrate_on_floor => {
            match floor_depth_scale(camera, d, guidance.masks.values()) {
                Some(s) if (s - 1.0).abs() > 1e-3 => {
                    depth_scale = s;
                    scaled = DepthMap::from_fn(d.width(), d.height(), |u, v| {
                        d.get(u, v).map_or(f32::NAN, |z| (z as f64 * s) as f32)
                    });
                    Some(&scaled)
                }
                _ => Some(d),
            }
        }
        other => other.as_ref(),
    };
    let mut boxes = Vec::new();
    let mut missing = Vec::new();
    for (id, mask) in &guidance.masks {
        let (points, source) = match depth {
            Some(depth) => (
                mask_points(
                    camera,
                    depth,
                    mask,
                    options.stride,
                    options.depth_filter_radius,
                ),
                DepthSource::Measured,
            ),
            None => (
                floor_contact_points(
                    camera,
                    mask,
                    options.stride,
                    options.priors.get(id).map(|p| p.y),
                )?,
                DepthSource::FloorContact,
            ),
        };
        match lift_points(id, &points, source, camera.position, options) {
            Some(b) => boxes.push(b),
            None => missing.push(id.clone()),
        }
    }
    let supports = infer_supports(&boxes, options.contact_gap);
    Ok(LiftedScene {
        boxes,
        missing,
        supports,
        depth_scale,
    })
}

/// Lifts one object's world points to a box; `None` when fewer than `options.min_points`
/// remain after clustering. `eye` is the camera centre (the hidden side lies away from it).
pub fn lift_points(
    id: &str,
    points: &[Point3<f64>],
    source: DepthSource,
    eye: Point3<f64>,
    options: &LiftOptions,
) -> Option<LiftedBox> {
    if points.len() < options.min_points {
        return None;
    }
    let mut dist: Vec<f64> = points.iter().map(|p| (p - eye).norm()).collect();
    let voxel = options.voxel.max(0.03 * median(&mut dist).unwrap_or(0.0));
    let kept = largest_cluster(points, voxel);
    if kept.len() < options.min_points {
        return None;
    }
    let mut ys: Vec<f64> = kept.iter().map(|p| p.y).collect();
    ys.sort_by(|a, b| a.total_cmp(b));
    let mut top = quantile(&ys, 1.0 - options.trim).max(0.0);
    let mut bottom = quantile(&ys, options.trim).max(0.0);
    if bottom <= options.contact_gap {
        bottom = 0.0;
    }
    let floor: Vec<Point2<f64>> = kept.iter().map(|p| Point2::new(p.x, p.z)).collect();
    let mut rect = min_area_rectangle(&floor, options.trim)?;
    let mut completed = false;
    if let Some(prior) = options.priors.get(id) {
        completed = true;
        // Height first: when the known height reaches down to the floor, the object stands on
        // it (its bottom is hidden, or thin legs were trimmed as strays).
        if bottom > 0.0 && top - prior.y <= 2.0 * options.contact_gap {
            bottom = 0.0;
        }
        // The prior's proportions at the measured height's scale (clamped: a measured height far
        // from the prior's is more likely occlusion or noise than a different object).
        let s = ((top - bottom) / prior.y.max(1e-6)).clamp(0.75, 1.33);
        top = bottom + prior.y * s;
        rect = complete_footprint(
            rect,
            Vector2::new(prior.x * s, prior.z * s),
            Point2::new(eye.x, eye.z),
        );
    }
    let half_y = ((top - bottom) / 2.0).max(0.005);
    Some(LiftedBox {
        id: id.to_string(),
        center: Point3::new(rect.center.x, bottom + half_y, rect.center.y),
        half_extents: Vector3::new(
            rect.half_extents.x.max(0.005),
            half_y,
            rect.half_extents.y.max(0.005),
        ),
        yaw: rect.yaw,
        points: kept.len(),
        depth_source: source,
        completed,
    })
}

/// Orients `rect` so its proportions best match `prior` (full x, z sizes) and gives it the
/// prior's extents: a side shorter than the prior's grows away from `eye` (the hidden part is
/// behind what the camera saw); a longer one (noise, mask bleed) shrinks about its centre.
pub fn complete_footprint(
    rect: FloorRectangle,
    prior: Vector2<f64>,
    eye: Point2<f64>,
) -> FloorRectangle {
    let measured = rect.half_extents * 2.0;
    let cost = |m: Vector2<f64>| {
        let r = |a: f64, b: f64| (a.max(0.01) / b.max(0.01)).ln().abs();
        r(m.x, prior.x) + r(m.y, prior.y)
    };
    let swapped = Vector2::new(measured.y, measured.x);
    let mut out = rect;
    if cost(swapped) < cost(measured) {
        // Turning by 90° swaps the rectangle's axes; fold back into [-π/4, π/4) + {0, π/2}.
        out.yaw = rect.yaw + std::f64::consts::FRAC_PI_2;
        out.half_extents = Vector2::new(rect.half_extents.y, rect.half_extents.x);
    }
    let away = out.center - eye;
    for (axis, half, full) in [
        (out.axis_x(), out.half_extents.x, prior.x),
        (out.axis_z(), out.half_extents.y, prior.y),
    ] {
        let grow = full - 2.0 * half;
        if grow > 0.0 {
            let sign = if away.dot(&axis) >= 0.0 { 1.0 } else { -1.0 };
            out.center += axis * (sign * grow / 2.0);
        }
    }
    out.half_extents = prior / 2.0;
    out
}

/// The factor that brings the measured depth of the visible floor to its true depth under the
/// known camera. For every pixel outside the masks whose ray meets y = 0, the ratio of the
/// floor's ray depth to the measured depth is taken; floor pixels agree on one ratio while walls
/// and unlabelled furniture spread out, so the answer is the median of the densest window of
/// ratios ±3 % wide (the mode), not the median of all. Ratios outside [0.5, 2] are ignored, and
/// at least 200 pixels must agree, else `None`.
pub fn floor_depth_scale<'a>(
    camera: &Camera,
    depth: &DepthMap,
    masks: impl IntoIterator<Item = &'a Mask>,
) -> Option<f64> {
    let masks: Vec<&Mask> = masks.into_iter().collect();
    let mut ratios = Vec::new();
    for v in 0..depth.height() {
        for u in 0..depth.width() {
            if masks.iter().any(|m| m.contains(u, v)) {
                continue;
            }
            let Some(measured) = depth.get(u, v).filter(|d| d.is_finite() && *d > 0.0) else {
                continue;
            };
            let pixel = Point2::new(u as f64 + 0.5, v as f64 + 0.5);
            let Some(hit) = floor_hit(camera, &pixel) else {
                continue;
            };
            // Depth along the optical axis of the floor point.
            let truth = -camera.world_to_camera(&hit).z;
            let r = truth / measured as f64;
            if (0.5..=2.0).contains(&r) {
                ratios.push(r);
            }
        }
    }
    ratios.sort_by(|a, b| a.total_cmp(b));
    // Densest window [r, r · 1.06]: two pointers over the sorted ratios.
    let (mut best, mut best_range) = (0usize, (0usize, 0usize));
    let mut hi = 0;
    for lo in 0..ratios.len() {
        while hi < ratios.len() && ratios[hi] <= ratios[lo] * 1.06 {
            hi += 1;
        }
        if hi - lo > best {
            best = hi - lo;
            best_range = (lo, hi);
        }
    }
    if best < 200 {
        return None;
    }
    let window = &ratios[best_range.0..best_range.1];
    Some(window[(window.len() - 1) / 2])
}
