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

use crate::footprint::{min_area_rectangle, rectangle_at, FloorRectangle};
pub use crate::lifted_box::{DepthSource, LiftedBox};
use crate::metrology::floor_contact_points;
use crate::metrology::floor_hit;
use crate::points::{
    depth_noise, interior, largest_cluster, mask_pixel_points, mask_points, median, quantile,
    vertical_margins,
};
use crate::support::{
    infer_supports_within, mount_on_walls, prefer_tiers, wall_offset, SupportGuess, SupportKind,
    MOUNT_WALL_REACH,
};
use crate::LiftError;
use scenethesis_imagery::{Camera, DepthMap, Guidance, Mask};
use scenethesis_scene_graph::Wall;

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
    /// Shelf and interior heights per object id, as fractions of the object's height (from
    /// its asset): where a box standing on a box in a shelf bay really stands on the board
    /// above it ([`crate::support::prefer_tiers`]). Empty when the assets are unknown.
    pub tiers: BTreeMap<String, Vec<f64>>,
    /// Relative standard deviation of a prior's size (how far the real object may be scaled
    /// from it). The measured scale and the prior's are blended by their uncertainties: a
    /// precise measurement keeps its own size, a noisy one leans on the prior.
    pub prior_scale_sigma: f64,
    /// How far in pixels a mask's boundary may be off (segmenters err by a pixel or two); it
    /// enters the uncertainty of a measured height.
    pub mask_boundary_px: f64,
    /// Radius in pixels of the median filter applied instead of `depth_filter_radius` when the
    /// depth map is noisy (its [`crate::points::depth_noise`] is above `noisy_depth`); 0 never.
    pub noisy_filter_radius: u32,
    /// Relative depth noise above which the depth map counts as noisy.
    pub noisy_depth: f64,
    /// Yaws in radians of the room's walls (any of the four equivalent yaws of a wall
    /// direction); empty when the room is unknown. A footprint turned less than `yaw_snap` from
    /// a wall direction is aligned with it: rooms are furnished along their walls.
    pub wall_yaws: Vec<f64>,
    /// Largest turn in radians that snaps a footprint to a wall direction.
    pub yaw_snap: f64,
    /// Pixels this close to a mask's boundary are not lifted when the interior keeps at least
    /// `interior_min_points` pixels (`noisy_interior_min_points` on a noisy map): a mask that
    /// bleeds by a pixel or two picks up the objects standing on or behind it, at depths that
    /// join its cluster. The extents are widened by the margin's metric size instead.
    pub mask_margin_px: u32,
    /// Fewest interior pixels for the margin to apply (else the whole mask is lifted).
    pub interior_min_points: usize,
    /// [`LiftOptions::interior_min_points`] on a noisy depth map (above `noisy_depth`): there a
    /// bleeding boundary's pixels cannot be told from the object's by their depth (the largest
    /// cluster keeps them), so the margin is left out of small masks too; on a clean map the
    /// boundary of a small mask carries too much of the object to drop.
    pub noisy_interior_min_points: usize,
    /// How far in metres a bottom may be from the top below it and still rest on it when
    /// nothing is within `contact_gap` ([`crate::support::infer_supports_within`]).
    pub support_reach: f64,
    /// Move each box resting on another onto that box's top (its bottom at the parent's
    /// top): what holds it up is known better than its noisy height.
    pub settle: bool,
    /// On a noisy depth map (above `noisy_depth`), the share of the depth noise's inflation
    /// taken off the footprint ([`deflate`]): along each of the rectangle's axes the trimmed
    /// extremes of noisy points sit about z(trim) σ beyond the true faces. 0 = none; the
    /// default 0.75 did best on the round trip's perturbed renders (a full correction
    /// over-shrinks small objects whose top is seen as well as their front).
    pub footprint_deflation: f64,
    /// The room's walls; empty when the room is unknown. A box held by nothing whose back is
    /// near one of them, high up ([`crate::support::mount_on_walls`]), is moved along
    /// the wall's normal until its back touches the wall's inner face: where a mounted object
    /// is, is known better from the wall than from its noisy depth (a painting a few
    /// centimetres thick loses half its overlap to a 1 cm offset).
    pub walls: Vec<Wall>,
    /// How far in metres the back of a box hung on a wall stands off the wall's inner face
    /// (a frame's hook holds it about a centimetre proud; the layout keeps the same clearance
    /// so that nothing touches a wall).
    pub wall_standoff: f64,
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
            tiers: BTreeMap::new(),
            prior_scale_sigma: 0.1,
            mask_boundary_px: 1.0,
            noisy_filter_radius: 2,
            noisy_depth: 0.005,
            wall_yaws: Vec::new(),
            yaw_snap: 12f64.to_radians(),
            mask_margin_px: 2,
            interior_min_points: 200,
            noisy_interior_min_points: 24,
            support_reach: 0.3,
            settle: true,
            footprint_deflation: 0.75,
            walls: Vec::new(),
            wall_standoff: 0.01,
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
        if !(0.0..MOUNT_WALL_REACH).contains(&self.wall_standoff) {
            return bad(
                "wall_standoff",
                self.wall_standoff,
                "metres in [0, MOUNT_WALL_REACH)",
            );
        }
        if !(0.0..0.5).contains(&self.trim) {
            return bad("trim", self.trim, "a fraction in [0, 0.5)");
        }
        if !self.prior_scale_sigma.is_finite() || self.prior_scale_sigma <= 0.0 {
            return bad(
                "prior_scale_sigma",
                self.prior_scale_sigma,
                "a positive fraction",
            );
        }
        if !self.mask_boundary_px.is_finite() || self.mask_boundary_px < 0.0 {
            return bad(
                "mask_boundary_px",
                self.mask_boundary_px,
                "a non-negative number of pixels",
            );
        }
        if !(0.0..std::f64::consts::FRAC_PI_4).contains(&self.yaw_snap) {
            return bad("yaw_snap", self.yaw_snap, "radians in [0, π/4)");
        }
        if !(0.0..=2.0).contains(&self.footprint_deflation) {
            return bad(
                "footprint_deflation",
                self.footprint_deflation,
                "a share in [0, 2]",
            );
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
    /// The depth map's relative per-pixel noise ([`crate::points::depth_noise`]; 0 without
    /// depth).
    pub depth_noise: f64,
}

impl LiftedScene {
    /// Reconciles the lifted supports with the relations a model `stated`
    /// ([`crate::cross_check::cross_check`], with `options`' contact gap and support reach):
    /// where the model's answer is taken, the box is moved to match (onto its new parent's top,
    /// or down to the floor) and boxes resting on it follow. Returns every disagreement.
    pub fn cross_check(
        &mut self,
        stated: &[SupportGuess],
        options: &LiftOptions,
    ) -> Vec<crate::cross_check::SupportCheck> {
        use crate::cross_check::Decision;
        let checks = crate::cross_check::cross_check(
            &self.boxes,
            &mut self.supports,
            stated,
            options.contact_gap,
            options.support_reach,
        );
        let taken: Vec<&str> = checks
            .iter()
            .filter(|c| c.decision == Decision::Model)
            .map(|c| c.id.as_str())
            .collect();
        if taken.is_empty() {
            return checks;
        }
        for b in self
            .boxes
            .iter_mut()
            .filter(|b| taken.contains(&b.id.as_str()))
        {
            let grounded = self
                .supports
                .iter()
                .any(|s| s.id == b.id && s.kind == SupportKind::Ground);
            if grounded {
                b.center.y = b.half_extents.y;
            }
        }
        if options.settle {
            settle(&mut self.boxes, &self.supports);
        }
        checks
    }
}

/// How precise one object's points are, for weighing them against a size prior.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Precision {
    /// Relative standard deviation of each point's depth after any filtering (0 = exact).
    pub depth_noise: f64,
    /// Angle in radians one pixel spans (the boundary of a mask is uncertain by pixels).
    pub pixel_angle: f64,
    /// Pixels left out along the mask's boundary (their metric size is added back to the
    /// footprint).
    pub margin_px: f64,
    /// Height in metres the surfaces at the bottom and the top of the silhouette continue
    /// over the left-out pixels ([`crate::points::vertical_margins`]).
    pub vertical_margins: (f64, f64),
    /// The [`vertical_extent`] of the whole mask's points when the points lifted are its
    /// interior: with a prior, the extent whose height is nearer the prior's is used.
    pub outline_heights: Option<(f64, f64)>,
    /// Whether the depth map counts as noisy ([`LiftOptions::noisy_depth`]): the footprint's
    /// noise inflation is then taken off ([`LiftOptions::footprint_deflation`]).
    pub noisy: bool,
}

impl Precision {
    /// Exact points: the measurement alone decides.
    pub const EXACT: Precision = Precision {
        depth_noise: 0.0,
        pixel_angle: 0.0,
        margin_px: 0.0,
        vertical_margins: (0.0, 0.0),
        outline_heights: None,
        noisy: false,
    };
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
    let noise = depth.and_then(depth_noise).unwrap_or(0.0);
    let radius = if noise > options.noisy_depth {
        options.depth_filter_radius.max(options.noisy_filter_radius)
    } else {
        options.depth_filter_radius
    };
    // A median over the (2r + 1)² window lowers Gaussian noise by about 1.25 / (2r + 1).
    let filtered_noise = if radius > 0 {
        noise * 1.25 / (2 * radius + 1) as f64
    } else {
        noise
    };
    let precision = Precision {
        depth_noise: filtered_noise,
        pixel_angle: 1.0 / camera.intrinsics.fy.abs().max(1e-9),
        margin_px: 0.0,
        vertical_margins: (0.0, 0.0),
        outline_heights: None,
        noisy: noise > options.noisy_depth,
    };
    let interior_min_points = if precision.noisy {
        options.noisy_interior_min_points
    } else {
        options.interior_min_points
    };
    let mut boxes = Vec::new();
    let mut missing = Vec::new();
    for (id, mask) in &guidance.masks {
        let mut precision = precision;
        let (points, source) = match depth {
            Some(depth) => {
                let inner = interior(mask, options.mask_margin_px);
                let points = if options.mask_margin_px > 0 && inner.area() >= interior_min_points {
                    let points = mask_pixel_points(camera, depth, &inner, options.stride, radius);
                    precision.margin_px = options.mask_margin_px as f64;
                    precision.vertical_margins = vertical_margins(&points, options.mask_margin_px);
                    let all = mask_points(camera, depth, mask, options.stride, radius);
                    precision.outline_heights =
                        vertical_extent(&all, camera.position, precision.depth_noise, options);
                    points.into_iter().map(|(_, p)| p).collect()
                } else {
                    mask_points(camera, depth, mask, options.stride, radius)
                };
                (points, DepthSource::Measured)
            }
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
        match lift_points_with(id, &points, source, camera.position, precision, options) {
            Some(b) => boxes.push(b),
            None => missing.push(id.clone()),
        }
    }
    let mut supports = infer_supports_within(&boxes, options.contact_gap, options.support_reach);
    prefer_tiers(&boxes, &mut supports, &options.tiers);
    if options.settle {
        settle(&mut boxes, &supports);
    }
    if !options.walls.is_empty() {
        // The guesses stay unsupported: whether such a box really hangs on the wall (or was
        // lifted off its shelf) is the caller's to decide with what it knows of the asset.
        let mut mounted = supports.clone();
        mount_on_walls(&mut mounted, &boxes, &options.walls);
        hang(&mut boxes, &mounted, &options.walls, options.wall_standoff);
    }
    Ok(LiftedScene {
        boxes,
        missing,
        supports,
        depth_scale,
        depth_noise: noise,
    })
}

/// Lifts one object's exact world points to a box; `None` when fewer than
/// `options.min_points` remain after clustering. `eye` is the camera centre (the hidden side
/// lies away from it).
pub fn lift_points(
    id: &str,
    points: &[Point3<f64>],
    source: DepthSource,
    eye: Point3<f64>,
    options: &LiftOptions,
) -> Option<LiftedBox> {
    lift_points_with(id, points, source, eye, Precision::EXACT, options)
}

/// Puts every box that rests on another ([`SupportKind::On`]) onto its parent's top, parents
/// first (a box on a box on a table follows the one below), and every box on the ground onto
/// the floor.
fn settle(boxes: &mut [LiftedBox], supports: &[SupportGuess]) {
    let mut order: Vec<usize> = (0..boxes.len()).collect();
    order.sort_by(|&a, &b| boxes[a].bottom().total_cmp(&boxes[b].bottom()));
    for i in order {
        let Some(s) = supports.iter().find(|s| s.id == boxes[i].id) else {
            continue;
        };
        if s.kind == SupportKind::Ground {
            // A low box found standing on nothing stands on the floor.
            boxes[i].center.y = boxes[i].half_extents.y;
            continue;
        }
        if s.kind != SupportKind::On {
            continue;
        }
        let Some(top) = s
            .parent
            .as_ref()
            .and_then(|p| boxes.iter().find(|b| &b.id == p))
            .map(LiftedBox::top)
        else {
            continue;
        };
        boxes[i].center.y = top + boxes[i].half_extents.y;
    }
}

/// Moves every box mounted on a wall ([`SupportKind::Mounted`], its parent one of `walls`)
/// along the wall's inward normal until the footprint corner nearest the wall lies `standoff`
/// in front of its inner face.
fn hang(boxes: &mut [LiftedBox], supports: &[SupportGuess], walls: &[Wall], standoff: f64) {
    for s in supports.iter().filter(|s| s.kind == SupportKind::Mounted) {
        let (Some(wall), Some(b)) = (
            s.parent
                .as_ref()
                .and_then(|p| walls.iter().find(|w| &w.id == p)),
            boxes.iter_mut().find(|b| b.id == s.id),
        ) else {
            continue;
        };
        let off = wall_offset(wall, &b.footprint()) - standoff;
        let n = wall.inward_normal();
        b.center.x -= n.x * off;
        b.center.z -= n.y * off;
    }
}

/// The largest cluster of `points` on a voxel grid that grows with distance (3 % of the
/// median distance from `eye`, at least `options.voxel`), so depth noise does not split an
/// object.
fn cluster(points: &[Point3<f64>], eye: Point3<f64>, options: &LiftOptions) -> Vec<Point3<f64>> {
    let mut dist: Vec<f64> = points.iter().map(|p| (p - eye).norm()).collect();
    let voxel = options.voxel.max(0.03 * median(&mut dist).unwrap_or(0.0));
    largest_cluster(points, voxel)
}

/// The trimmed vertical extent of an object's points with the noise's inflation taken off.
struct Heights {
    lo: f64,
    hi: f64,
    /// Median distance of the points from the eye.
    distance: f64,
    /// Vertical spread of one point from depth noise.
    sigma_y: f64,
}

impl Heights {
    /// `kept` must not be empty; `noise` is the relative depth noise of each point.
    fn of(kept: &[Point3<f64>], eye: Point3<f64>, noise: f64, trim: f64) -> Heights {
        let mut ys: Vec<f64> = kept.iter().map(|p| p.y).collect();
        ys.sort_by(|a, b| a.total_cmp(b));
        // Noise along the rays spreads the points vertically by σ_y = noise · distance · |ray_y|;
        // the trimmed quantiles sit about z(trim) σ_y beyond the true faces.
        let mut dist: Vec<f64> = kept.iter().map(|p| (p - eye).norm()).collect();
        let distance = median(&mut dist).unwrap_or(0.0);
        let mut drop: Vec<f64> = kept
            .iter()
            .map(|p| ((p.y - eye.y) / (p - eye).norm().max(1e-9)).abs())
            .collect();
        let ray_y = median(&mut drop).unwrap_or(0.0);
        let sigma_y = noise * distance * ray_y;
        let inflation = normal_quantile(1.0 - trim.max(1e-6)) * sigma_y;
        let (lo, hi) = (quantile(&ys, trim), quantile(&ys, 1.0 - trim));
        let (lo, hi) = if hi - lo > 2.0 * inflation {
            (lo + inflation, hi - inflation)
        } else {
            let mid = (lo + hi) / 2.0;
            (mid, mid)
        };
        Heights {
            lo,
            hi,
            distance,
            sigma_y,
        }
    }
}

/// The trimmed vertical extent `(bottom, top)` of the largest cluster of `points` (noise
/// inflation taken off), `None` with fewer than `options.min_points` points.
pub fn vertical_extent(
    points: &[Point3<f64>],
    eye: Point3<f64>,
    noise: f64,
    options: &LiftOptions,
) -> Option<(f64, f64)> {
    let kept = cluster(points, eye, options);
    (kept.len() >= options.min_points).then(|| {
        let h = Heights::of(&kept, eye, noise, options.trim);
        (h.lo, h.hi)
    })
}

/// The standard normal quantile of `p` in (0, 1) (Abramowitz & Stegun 26.2.23, error below
/// 4.5e-4).
fn normal_quantile(p: f64) -> f64 {
    let q = if p < 0.5 { p } else { 1.0 - p }.clamp(1e-12, 0.5);
    let t = (-2.0 * q.ln()).sqrt();
    let z = t
        - (2.515517 + 0.802853 * t + 0.010328 * t * t)
            / (1.0 + 1.432788 * t + 0.189269 * t * t + 0.001308 * t * t * t);
    if p < 0.5 {
        -z
    } else {
        z
    }
}

/// A known object no side of which is longer than this (metres: a billiard ball, a can, a
/// cup) is placed from as few as [`SMALL_MIN_POINTS`]: a few pixels fix where it is, and its
/// size prior what it spans.
const SMALL_PRIOR: f64 = 0.15;
/// The fewest points that place an object of a small prior ([`SMALL_PRIOR`]).
const SMALL_MIN_POINTS: usize = 4;

/// The fewest points that place object `id`: `options.min_points`, or for an object with a
/// small size prior [`SMALL_MIN_POINTS`] (when fewer).
fn required_points(id: &str, options: &LiftOptions) -> usize {
    let small = options
        .priors
        .get(id)
        .is_some_and(|p| p.x.max(p.y).max(p.z) <= SMALL_PRIOR);
    if small {
        options.min_points.min(SMALL_MIN_POINTS)
    } else {
        options.min_points
    }
}

/// [`lift_points`] for points of known `precision`: the noise's inflation of the trimmed
/// vertical extent is taken off, and with a prior the measured scale is blended with the
/// prior's by their uncertainties.
pub fn lift_points_with(
    id: &str,
    points: &[Point3<f64>],
    source: DepthSource,
    eye: Point3<f64>,
    precision: Precision,
    options: &LiftOptions,
) -> Option<LiftedBox> {
    let required = required_points(id, options);
    if points.len() < required {
        return None;
    }
    let kept = cluster(points, eye, options);
    if kept.len() < required {
        return None;
    }
    let heights = Heights::of(&kept, eye, precision.depth_noise, options.trim);
    let (distance, sigma_y) = (heights.distance, heights.sigma_y);
    // The margin left out along the mask's boundary, in metres at the object's distance.
    let margin = precision.margin_px * precision.pixel_angle * distance;
    let (mut lo, mut hi) = (
        heights.lo - precision.vertical_margins.0,
        heights.hi + precision.vertical_margins.1,
    );
    let span = |lo: f64, hi: f64| {
        let bottom = if lo <= options.contact_gap { 0.0 } else { lo };
        hi.max(0.0) - bottom.max(0.0)
    };
    if let (Some(prior), Some((olo, ohi))) = (options.priors.get(id), precision.outline_heights) {
        // A mask's interior loses thin parts (posts, a raised shelf); its whole area may carry
        // what a bleeding boundary picked up. The one whose height is nearer the prior's wins.
        let off = |h: f64| (h.max(1e-3) / prior.y.max(1e-6)).ln().abs();
        if off(span(olo, ohi)) < off(span(lo, hi)) {
            (lo, hi) = (olo, ohi);
        }
    }
    let mut top = hi.max(0.0);
    let mut bottom = lo.max(0.0);
    if bottom <= options.contact_gap {
        bottom = 0.0;
    }
    let floor: Vec<Point2<f64>> = kept.iter().map(|p| Point2::new(p.x, p.z)).collect();
    let mut rect = min_area_rectangle(&floor, options.trim)?;
    if let Some(yaw) = snap_to_walls(rect.yaw, &options.wall_yaws, options.yaw_snap) {
        rect = rectangle_at(&floor, yaw, options.trim);
    } else {
        // How far each of the rectangle's sides is uncertain: a pixel's footprint at the
        // object's distance and the depth noise left along the ray.
        let resolution = (options.mask_boundary_px.max(1.0) * precision.pixel_angle
            + precision.depth_noise)
            * distance;
        if let Some(walled) = unresolved_yaw(&rect, &floor, options, resolution) {
            rect = walled;
        }
    }
    if precision.noisy && options.footprint_deflation > 0.0 {
        deflate(
            &mut rect,
            &kept,
            eye,
            precision.depth_noise * options.footprint_deflation,
            options.trim,
        );
    }
    // The left-out boundary narrows what is seen across the line of sight; along it the
    // near face stays where it is.
    let sight = (rect.center - Point2::new(eye.x, eye.z))
        .try_normalize(1e-9)
        .unwrap_or_else(Vector2::zeros);
    rect.half_extents.x += margin * sight.perp(&rect.axis_x()).abs();
    rect.half_extents.y += margin * sight.perp(&rect.axis_z()).abs();
    let mut completed = false;
    let seen_height = top - bottom;
    if let Some(prior) = options.priors.get(id) {
        completed = true;
        // Height first: when the known height reaches down to the floor, the object stands on
        // it (its bottom is hidden, or thin legs were trimmed as strays).
        if bottom > 0.0 && top - prior.y <= 2.0 * options.contact_gap {
            bottom = 0.0;
        }
        // The prior's proportions at the measured height's scale (clamped: a measured height far
        // from the prior's is more likely occlusion or noise than a different object), blended
        // with the prior's own scale by their uncertainties (in log scale).
        let measured = ((top - bottom) / prior.y.max(1e-6)).clamp(0.75, 1.33);
        // Each face's height is uncertain by the residual noise and by the mask boundary.
        let face = (sigma_y.powi(2)
            + (options.mask_boundary_px * precision.pixel_angle * distance).powi(2))
        .sqrt();
        let sigma_m = std::f64::consts::SQRT_2 * face / (top - bottom).max(1e-3);
        let sigma_p = options.prior_scale_sigma;
        let w = sigma_p.powi(2) / (sigma_p.powi(2) + sigma_m.powi(2));
        let s = (w * measured.ln()).exp();
        top = bottom + prior.y * s;
        rect = complete_footprint(
            rect,
            Vector2::new(prior.x * s, prior.z * s),
            Point2::new(eye.x, eye.z),
        );
    }
    // A box is at least 1 cm tall unless a prior says how thin it is (a magazine, a towel).
    let thinnest = if completed { 0.0005 } else { 0.005 };
    let half_y = ((top - bottom) / 2.0).max(thinnest);
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
        seen_height: seen_height.max(0.0),
    })
}

/// Takes the depth noise's inflation off `rect`, the trimmed footprint of `points`: noise of
/// relative spread `noise` along each ray moves a point across the floor by
/// `noise · distance · |horizontal ray · axis|` along each of the rectangle's axes, and the
/// trimmed extremes sit about z(1 − `trim`) of that beyond the true faces. Each half extent
/// shrinks by it (never below zero), the centre stays.
pub fn deflate(
    rect: &mut FloorRectangle,
    points: &[Point3<f64>],
    eye: Point3<f64>,
    noise: f64,
    trim: f64,
) {
    if points.is_empty() {
        return;
    }
    let z = normal_quantile(1.0 - trim.max(1e-6));
    for (k, axis) in [(0, rect.axis_x()), (1, rect.axis_z())] {
        let mut spread: Vec<f64> = points
            .iter()
            .map(|p| {
                let ray = p - eye;
                noise * Vector2::new(ray.x, ray.z).dot(&axis).abs()
            })
            .collect();
        let sigma = median(&mut spread).unwrap_or(0.0);
        let half = &mut rect.half_extents[k];
        *half = (*half - z * sigma).max(0.0);
    }
}

/// The rectangle of `points` aligned with the room's walls when the footprint cannot tell its
/// orientation apart from theirs: `rect` is the minimum-area rectangle, and a wall-aligned one
/// whose area is within what `resolution` (how far each side may be off, metres) allows —
/// every side of `rect` lengthened by `2 · resolution` — fits the points as well. Round
/// objects (every yaw fits as well) and objects a few pixels wide at a distance then take the
/// room's axes, as furniture mostly does; the wall direction whose rectangle is smallest wins.
/// `None` without walls or when the footprint is resolved.
fn unresolved_yaw(
    rect: &FloorRectangle,
    points: &[Point2<f64>],
    options: &LiftOptions,
    resolution: f64,
) -> Option<FloorRectangle> {
    let quarter = std::f64::consts::FRAC_PI_2;
    let size = rect.half_extents * 2.0;
    let limit = (size.x + 2.0 * resolution) * (size.y + 2.0 * resolution);
    options
        .wall_yaws
        .iter()
        .map(|w| rectangle_at(points, w.rem_euclid(quarter), options.trim))
        .filter(|r| r.area() <= limit)
        .min_by(|a, b| a.area().total_cmp(&b.area()))
}

/// The yaw `yaw` snapped to the nearest of `walls` (modulo 90°) when within `tolerance`.
fn snap_to_walls(yaw: f64, walls: &[f64], tolerance: f64) -> Option<f64> {
    let quarter = std::f64::consts::FRAC_PI_2;
    let fold = |a: f64| {
        let y = a.rem_euclid(quarter);
        if y >= quarter / 2.0 {
            y - quarter
        } else {
            y
        }
    };
    walls
        .iter()
        .map(|w| fold(yaw - w))
        .filter(|d| d.abs() <= tolerance)
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))
        .map(|d| fold(yaw - d))
}

/// Orients `rect` so its proportions best match `prior` (full x, z sizes) and gives it the
/// prior's extents: a side shorter than the prior's grows away from `eye` (the hidden part is
/// behind what the camera saw) when it runs along the line of sight, and about its centre when
/// it runs across it; a longer one (noise, mask bleed) shrinks about its centre.
pub fn complete_footprint(
    rect: FloorRectangle,
    prior: Vector2<f64>,
    eye: Point2<f64>,
) -> FloorRectangle {
    grow_to_prior(orient_to_prior(rect, prior), prior, eye)
}

/// `rect`, or `rect` turned by 90° (its axes swapped) when that matches the proportions of
/// `prior` (full x, z sizes) better.
pub fn orient_to_prior(rect: FloorRectangle, prior: Vector2<f64>) -> FloorRectangle {
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
    out
}

/// The second half of [`complete_footprint`]: gives an oriented `rect` the prior's extents.
fn grow_to_prior(rect: FloorRectangle, prior: Vector2<f64>, eye: Point2<f64>) -> FloorRectangle {
    let mut out = rect;
    let away = (out.center - eye)
        .try_normalize(1e-9)
        .unwrap_or_else(Vector2::zeros);
    for (axis, half, full) in [
        (out.axis_x(), out.half_extents.x, prior.x),
        (out.axis_z(), out.half_extents.y, prior.y),
    ] {
        let grow = full - 2.0 * half;
        if grow > 0.0 {
            // Along the view the missing part is hidden behind; across it a shortfall is as
            // likely on either side (a mask boundary), so the growth is shared: all of it goes
            // away from the eye at 45° or more to the line of sight, none when perpendicular.
            let along = (away.dot(&axis) * std::f64::consts::SQRT_2).clamp(-1.0, 1.0);
            out.center += axis * (along * grow / 2.0);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// Standard normal deviates from a fixed linear congruential generator seeded by `seed`
    /// (Box–Muller), so the tests' noise is the same on every run.
    fn gaussian(seed: u64) -> impl FnMut() -> f64 {
        let mut state = seed;
        move || {
            let mut u = || {
                state = state
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                ((state >> 11) as f64 / (1u64 << 53) as f64).max(1e-12)
            };
            let (a, b) = (u(), u());
            (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos()
        }
    }

    #[test]
    fn a_mounted_box_is_put_against_its_wall_and_others_stay() {
        // 6 × 4 m room: the back wall `wall_0` has its inner face at z = −2.
        let room = scenethesis_scene_graph::Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let mut boxes = vec![
            // A painting lifted 4 cm out from the wall (its back at z = −1.96).
            LiftedBox::axis_aligned("painting", [0.5, 1.6, -1.94], [0.4, 0.3, 0.02]),
            // One lifted 1 cm into the wall.
            LiftedBox::axis_aligned("mirror", [-1.0, 1.5, -1.99], [0.3, 0.4, 0.02]),
            // A cabinet standing 5 cm off the wall: not mounted, not moved.
            LiftedBox::axis_aligned("cabinet", [2.0, 0.5, -1.75], [0.4, 0.5, 0.2]),
        ];
        let mut supports = infer_supports_within(&boxes, 0.06, 0.3);
        mount_on_walls(&mut supports, &boxes, &room.walls);
        hang(&mut boxes, &supports, &room.walls, 0.01);
        // Backs 1 cm in front of the wall.
        assert!(
            (boxes[0].center.z - -1.97).abs() < 1e-9,
            "{}",
            boxes[0].center.z
        );
        assert!(
            (boxes[1].center.z - -1.97).abs() < 1e-9,
            "{}",
            boxes[1].center.z
        );
        assert_eq!(boxes[0].center.x, 0.5);
        assert_eq!(boxes[0].center.y, 1.6);
        assert_eq!(boxes[2].center.z, -1.75);
    }

    #[test]
    fn a_small_known_object_is_placed_from_a_few_points() {
        // Six points of a billiard ball 4 m from the camera, on a table top at 0.8 m.
        let points: Vec<Point3<f64>> = (0..6)
            .map(|k| {
                let (x, y) = ((k % 3) as f64 * 0.01, (k / 3) as f64 * 0.02);
                Point3::new(1.0 + x, 0.81 + y, -0.03)
            })
            .collect();
        let eye = Point3::new(1.0, 2.0, 4.0);
        let mut options = LiftOptions::default();
        assert!(lift_points("ball", &points, DepthSource::Measured, eye, &options).is_none());
        options
            .priors
            .insert("ball".into(), Vector3::new(0.057, 0.057, 0.057));
        let ball = lift_points("ball", &points, DepthSource::Measured, eye, &options)
            .expect("a small prior needs only a few points");
        assert!((ball.center.x - 1.01).abs() < 0.05, "{:?}", ball.center);
        // A large prior still needs the full count.
        options
            .priors
            .insert("ball".into(), Vector3::new(0.6, 0.5, 0.4));
        assert!(lift_points("ball", &points, DepthSource::Measured, eye, &options).is_none());
    }

    #[test]
    fn yaws_near_a_wall_snap_to_it() {
        let walls = [0.0, std::f64::consts::FRAC_PI_2];
        let snap = 12f64.to_radians();
        assert!(snap_to_walls(0.1, &walls, snap).unwrap().abs() < 1e-12);
        assert!(snap_to_walls(-0.15, &walls, snap).unwrap().abs() < 1e-12);
        assert_eq!(snap_to_walls(0.5, &walls, snap), None);
        // A room turned by 30°: its walls' directions are 30° and 120°.
        let turned = [30f64.to_radians()];
        let y = snap_to_walls(-0.95, &turned, snap).unwrap();
        let d = (y - 30f64.to_radians()).rem_euclid(std::f64::consts::FRAC_PI_2);
        assert!(d.min(std::f64::consts::FRAC_PI_2 - d) < 1e-9, "{y}");
    }

    #[test]
    fn a_round_footprint_takes_the_walls_yaw_and_an_oblong_one_keeps_its_own() {
        let options = LiftOptions {
            wall_yaws: vec![0.0, std::f64::consts::FRAC_PI_2],
            ..LiftOptions::default()
        };
        // A disc of radius 0.2 m sampled on a polar grid: every yaw fits it equally well.
        let disc: Vec<Point2<f64>> = (1..=10)
            .flat_map(|r| {
                (0..72).map(move |k| {
                    let (a, r) = (k as f64 * 5f64.to_radians() + 0.03, r as f64 * 0.02);
                    Point2::new(r * a.cos(), r * a.sin())
                })
            })
            .collect();
        let rect = min_area_rectangle(&disc, 0.0).unwrap();
        let walled = unresolved_yaw(&rect, &disc, &options, 0.005).expect("round");
        assert!(walled.yaw.abs() < 1e-12, "{walled:?}");
        // A 1.0 × 0.4 m rectangle turned by 30°, seen to the millimetre, keeps its yaw.
        let yaw = 30f64.to_radians();
        let (ax, az) = (
            Vector2::new(yaw.cos(), -yaw.sin()),
            Vector2::new(yaw.sin(), yaw.cos()),
        );
        let oblong: Vec<Point2<f64>> = (0..=50)
            .flat_map(|i| {
                (0..=20).map(move |j| {
                    Point2::from(ax * (i as f64 * 0.02 - 0.5) + az * (j as f64 * 0.02 - 0.2))
                })
            })
            .collect();
        let rect = min_area_rectangle(&oblong, 0.0).unwrap();
        assert_eq!(unresolved_yaw(&rect, &oblong, &options, 0.001), None);
        // Seen a few pixels wide from far away, its orientation is no longer resolved.
        assert!(unresolved_yaw(&rect, &oblong, &options, 0.3).is_some());
    }

    /// A small block (10 × 12 × 6 cm, its front at z = −3) on the floor seen from 1.6 m up, the
    /// far wall at z = −6, every depth off by 2 % Gaussian noise (a fixed generator), and the
    /// block's mask dilated by 2 px so it bleeds onto the floor and the wall behind.
    fn bleeding_block() -> (Guidance, Point3<f64>) {
        use scenethesis_imagery::{Intrinsics, RgbImage};
        let (w, h) = (320u32, 240u32);
        let k = Intrinsics::from_vertical_fov(w, h, 1.0);
        let camera = Camera::look_at(
            k,
            Point3::new(0.0, 1.6, 0.0),
            Point3::new(0.0, 0.0, -3.0),
            Vector3::y(),
        );
        let (lo, hi) = (
            Point3::new(-0.05, 0.0, -3.06),
            Point3::new(0.05, 0.12, -3.0),
        );
        let hit = |u: u32, v: u32| -> (f64, bool) {
            let ray = camera.unproject(&Point2::new(u as f64 + 0.5, v as f64 + 0.5), 1.0);
            let (o, d) = (camera.position, ray - camera.position);
            let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
            for a in 0..3 {
                let (p, q) = ((lo[a] - o[a]) / d[a], (hi[a] - o[a]) / d[a]);
                t0 = t0.max(p.min(q));
                t1 = t1.min(p.max(q));
            }
            if t0 <= t1 {
                return (t0, true);
            }
            let floor = if d.y < 0.0 { -o.y / d.y } else { f64::INFINITY };
            let wall = (-6.0 - o.z) / d.z;
            (floor.min(wall), false)
        };
        let mut gauss = gaussian(11);
        let depth = DepthMap::from_fn(w, h, |u, v| {
            // Depth along the optical axis: the ray parameter for a unit-depth unprojection.
            (hit(u, v).0 * (1.0 + 0.02 * gauss())) as f32
        });
        let mut mask = Mask::new(w, h);
        for v in 0..h {
            for u in 0..w {
                let near = (u.saturating_sub(2)..=(u + 2).min(w - 1))
                    .any(|x| (v.saturating_sub(2)..=(v + 2).min(h - 1)).any(|y| hit(x, y).1));
                mask.set(u, v, near);
            }
        }
        let image = RgbImage::new(w, h, vec![128; (w * h * 3) as usize]).unwrap();
        let guidance = Guidance::new(
            camera,
            image,
            Some(depth),
            BTreeMap::from([("block".to_string(), mask)]),
        )
        .unwrap();
        (guidance, Point3::new(0.0, 0.06, -3.03))
    }

    #[test]
    fn on_a_noisy_map_a_small_bleeding_mask_is_lifted_from_its_interior() {
        let (guidance, truth) = bleeding_block();
        let options = LiftOptions {
            priors: BTreeMap::from([("block".to_string(), Vector3::new(0.1, 0.12, 0.06))]),
            ..LiftOptions::default()
        };
        let error = |options: &LiftOptions| {
            let lifted = lift_scene(&guidance, options).unwrap();
            assert!(lifted.depth_noise > options.noisy_depth);
            let b = &lifted.boxes[0];
            Vector2::new(b.center.x - truth.x, b.center.z - truth.z).norm()
        };
        let interior = error(&options);
        let whole = error(&LiftOptions {
            noisy_interior_min_points: usize::MAX,
            ..options.clone()
        });
        assert!(
            interior < whole,
            "interior {interior} m, whole mask {whole} m"
        );
    }

    /// The visible faces (front, top) of a 1.0 × 0.8 × 0.5 m box on the floor 5 m in front of
    /// an eye 1.6 m up, sampled every 2 cm, each point pushed along its ray by Gaussian noise of
    /// `noise` times its distance (a fixed generator).
    fn noisy_box(noise: f64) -> (Vec<Point3<f64>>, Point3<f64>) {
        let eye = Point3::new(0.0, 1.6, 0.0);
        let (cz, hz) = (-5.0, 0.25);
        let mut gauss = gaussian(7);
        let mut out = Vec::new();
        for i in 0..=50 {
            let x = -0.5 + i as f64 * 0.02;
            for j in 0..=40 {
                out.push(Point3::new(x, j as f64 * 0.02, cz + hz));
            }
            for k in 0..=25 {
                out.push(Point3::new(x, 0.8, cz + hz - k as f64 * 0.02));
            }
        }
        let noisy = out
            .into_iter()
            .map(|p| eye + (p - eye) * (1.0 + noise * gauss()))
            .collect();
        (noisy, eye)
    }

    #[test]
    fn a_noisy_box_is_recovered_within_bounds() {
        let (points, eye) = noisy_box(0.005);
        let options = LiftOptions {
            priors: BTreeMap::from([("box".to_string(), Vector3::new(1.0, 0.8, 0.5))]),
            ..LiftOptions::default()
        };
        let precision = Precision {
            depth_noise: 0.005,
            pixel_angle: 1.0 / 500.0,
            ..Precision::EXACT
        };
        let b = lift_points_with(
            "box",
            &points,
            DepthSource::Measured,
            eye,
            precision,
            &options,
        )
        .unwrap();
        let truth = Point3::new(0.0, 0.4, -5.0);
        assert!((b.center - truth).norm() < 0.05, "centre {:?}", b.center);
        assert!(
            (b.size().y - 0.8).abs() < 0.8 * 0.03,
            "height {}",
            b.size().y
        );
        assert!(b.yaw.abs() < 3f64.to_radians(), "yaw {}", b.yaw);
        // Read as exact, the same points overstate the height: the noise is what the
        // correction takes off.
        let exact = lift_points_with(
            "box",
            &points,
            DepthSource::Measured,
            eye,
            Precision::EXACT,
            &options,
        )
        .unwrap();
        assert!(
            exact.size().y > b.size().y,
            "{} vs {}",
            exact.size().y,
            b.size().y
        );
    }

    #[test]
    fn a_precise_measurement_keeps_its_scale_and_a_noisy_one_leans_on_the_prior() {
        // The box is 10 % taller than the prior says.
        let (points, eye) = noisy_box(0.0);
        let options = LiftOptions {
            priors: BTreeMap::from([("box".to_string(), Vector3::new(1.0, 0.8 / 1.1, 0.5))]),
            ..LiftOptions::default()
        };
        let exact = lift_points_with(
            "box",
            &points,
            DepthSource::Measured,
            eye,
            Precision::EXACT,
            &options,
        )
        .unwrap();
        assert!((exact.size().y - 0.8).abs() < 0.01, "{}", exact.size().y);
        let (points, eye) = noisy_box(0.02);
        let noisy = Precision {
            depth_noise: 0.02,
            pixel_angle: 1.0 / 500.0,
            ..Precision::EXACT
        };
        let b =
            lift_points_with("box", &points, DepthSource::Measured, eye, noisy, &options).unwrap();
        // The blend moves it toward the prior by a share that grows with the noise.
        let prior = 0.8 / 1.1;
        assert!(
            (b.size().y - prior).abs() < (exact.size().y - prior).abs() - 0.01,
            "{} leans on the prior {prior} (exact {})",
            b.size().y,
            exact.size().y
        );
    }

    #[test]
    fn deflation_takes_the_noise_spread_off_the_axes_it_runs_along() {
        // Eye 5 m away along -z: rays run along z, so noise widens the footprint's z extent.
        let eye = Point3::new(0.0, 1.6, 5.0);
        let points: Vec<Point3<f64>> = (0..100)
            .map(|i| Point3::new(i as f64 * 0.01 - 0.5, 0.4, (i % 10) as f64 * 0.01))
            .collect();
        let mut rect = FloorRectangle {
            center: Point2::new(0.0, 0.0),
            half_extents: Vector2::new(0.5, 0.3),
            yaw: 0.0,
        };
        deflate(&mut rect, &points, eye, 0.01, 0.01);
        // σ along z ≈ 0.01 · 5 m = 5 cm, z(0.99) ≈ 2.33: about 11.6 cm off; across, ~1 cm.
        assert!(
            (rect.half_extents.y - (0.3 - 0.116)).abs() < 0.01,
            "{:?}",
            rect
        );
        assert!(rect.half_extents.x > 0.48, "{:?}", rect);
        assert_eq!(rect.center, Point2::new(0.0, 0.0));
    }
}
