//! Pose alignment to a guidance image with matches refreshed while the pose moves: discrete
//! yaw hypotheses scored by shape agreement, then rounds of (render the asset at its current
//! pose → match → lift → robust fit of the alignment loss), keeping the best-agreeing pose.

use std::cell::Cell;
use std::time::Instant;

use nalgebra::Point3;
use scenethesis_scene_graph::{wrap_yaw, yaw_distance, Mesh, Pose, FACING_TOLERANCE};
use serde::{Deserialize, Serialize};

use crate::alignment::{FitOptions, PoseAlignment, ScalePrior};
use crate::deadline::{deadline_after, past};
use crate::matcher::{lift, Matcher, TargetRegion};
use crate::raster::{projected_bbox, rasterize, Window};
use crate::shape::{
    pick_yaw, search_yaw, search_yaw_coarse, shape_score, ShapeMatcher, ShapeScore,
};

/// Settings of [`align_to_guidance`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GuidedSettings {
    /// Yaw hypotheses, evenly spaced over the full turn from the starting yaw (0 or 1: keep
    /// the starting yaw).
    pub yaw_candidates: usize,
    /// Candidates within this fraction of the best score count as tied; a facing hint picks
    /// among them.
    pub hint_tie: f64,
    /// With a facing hint, only yaws within this many radians of it are tried, and a starting
    /// pose outside it is not kept: an object backed onto a wall faces out of it and one
    /// facing another faces it (the judge allows 50°, [`FACING_TOLERANCE`]; the default window
    /// is 30°); a silhouette that fits a little better turned away is a front/back
    /// confusion, not evidence.
    #[serde(default = "default_hint_window")]
    pub hint_window: f64,
    /// The yaw hypotheses are first ranked on views subsampled by this stride (1: every
    /// hypothesis at full resolution).
    #[serde(default = "default_coarse_stride")]
    pub coarse_stride: u32,
    /// How many of the best coarse hypotheses are scored again at full resolution.
    #[serde(default = "default_coarse_keep")]
    pub coarse_keep: usize,
    /// Match refresh rounds (render, match, lift, fit) at most.
    pub refreshes: usize,
    /// Robust fit per round.
    pub fit: FitOptions,
    /// Weight of the 2D term per squared pixel, `1/σ²` for the pixel noise σ of mask
    /// boundaries (default σ = 5 px: a segmenter's masks are often a couple of pixels too wide
    /// or too narrow, and the depth pairs, not the outline, should say how far away it is;
    /// weighted higher, that bias would pull the object toward or away from the camera, or,
    /// without a scale prior, change its size).
    pub weight_2d: f64,
    /// Depth noise σ as a fraction of the object's depth: the 3D/depth weight is `1/σ²`.
    pub depth_noise: f64,
    /// Margin around the mask's pixel box that the renders cover, as a fraction of its larger
    /// side (at least 6 pixels).
    pub window_margin: f64,
    /// Masks with fewer pixels are not matched.
    pub min_mask_pixels: usize,
    /// Rounds stop once the pose moves less than this (metres and radians).
    pub tolerance: f64,
    /// Relative uncertainty of the starting scale (the lift's or the catalogue's size): the
    /// fit is pulled toward the starting scale by a [`ScalePrior`] of this σ, so silhouettes
    /// and depth change the size only as far as they constrain it (≤ 0: no prior).
    #[serde(default = "default_scale_sigma")]
    pub scale_sigma: f64,
    /// The pose the match rounds end at is kept unless its shape score is more than this
    /// fraction below the best score seen (then the best-scoring pose is kept). The score
    /// ranks yaw hypotheses well but hardly moves with a shift of a few centimetres and not at
    /// all with a shift along the line of sight (its depth term ignores a common offset), so
    /// among poses that fit the mask about as well the fitted one, which the depth pairs place,
    /// is the better; the tolerance only guards against a fit that went astray.
    #[serde(default = "default_refine_tolerance")]
    pub refine_tolerance: f64,
    /// Wall-clock budget of the alignment, in seconds (default
    /// [`DEFAULT_TIME_BUDGET_SECS`]; infinite: none). It is shared by every object aligned
    /// with the settings [`GuidedSettings::started`] returned, else counted per call of
    /// [`align_to_guidance`]. When it runs out, the yaw search and the match rounds not yet
    /// begun are skipped and the best pose found so far is kept, with
    /// [`GuidedPose::out_of_time`] set; a run that does not reach it is unchanged by it.
    #[serde(default = "default_time_budget")]
    pub time_budget: f64,
    /// The shared deadline set by [`GuidedSettings::started`] (never serialized).
    #[serde(skip)]
    pub deadline: Option<Instant>,
}

/// Default [`GuidedSettings::time_budget`], seconds. Aligning the objects of a benchmark scene
/// takes well under a second in a release build, so the budget only ends runaway work (huge
/// windows, guidance the optimizer cannot agree with).
pub const DEFAULT_TIME_BUDGET_SECS: f64 = 30.0;

fn default_time_budget() -> f64 {
    DEFAULT_TIME_BUDGET_SECS
}

impl GuidedSettings {
    /// These settings with their deadline fixed `time_budget` seconds from now, to share one
    /// budget between the objects of a stage.
    pub fn started(&self) -> Self {
        Self {
            deadline: deadline_after(self.time_budget),
            ..self.clone()
        }
    }

    /// The deadline of an alignment starting now: the shared one, else `time_budget` from now.
    fn deadline(&self) -> Option<Instant> {
        self.deadline.or_else(|| deadline_after(self.time_budget))
    }
}

/// Three fifths of the judge's facing tolerance: the object's target (or its own position)
/// may still move after alignment, so the yaw must face it with room to spare.
fn default_hint_window() -> f64 {
    0.6 * FACING_TOLERANCE
}

fn default_refine_tolerance() -> f64 {
    0.1
}

fn default_scale_sigma() -> f64 {
    0.03
}

fn default_coarse_stride() -> u32 {
    2
}

fn default_coarse_keep() -> usize {
    6
}

impl Default for GuidedSettings {
    fn default() -> Self {
        Self {
            yaw_candidates: 24,
            hint_tie: 0.03,
            hint_window: default_hint_window(),
            coarse_stride: default_coarse_stride(),
            coarse_keep: default_coarse_keep(),
            refreshes: 10,
            fit: FitOptions {
                iterations: 12,
                ..FitOptions::default()
            },
            weight_2d: 0.04,
            depth_noise: 0.03,
            window_margin: 0.25,
            min_mask_pixels: 30,
            tolerance: 1e-3,
            scale_sigma: default_scale_sigma(),
            refine_tolerance: default_refine_tolerance(),
            time_budget: default_time_budget(),
            deadline: None,
        }
    }
}

/// What [`align_to_guidance`] found for one object.
#[derive(Debug, Clone, PartialEq)]
pub struct GuidedPose {
    /// The aligned pose.
    pub pose: Pose,
    /// The correspondences matched at that pose, for the optimizer's alignment stage.
    pub alignment: PoseAlignment,
    /// Shape agreement at the starting pose.
    pub start_score: ShapeScore,
    /// Shape agreement at the aligned pose.
    pub score: ShapeScore,
    /// Refresh rounds run.
    pub rounds: usize,
    /// Why the starting pose (the raw lift) was kept instead of the fitted one, when it was:
    /// it agrees with the object's mask and depth better by the alignment's own measures
    /// (its shape score and its match residual); `None` when the alignment moved the object.
    pub kept_start: Option<String>,
    /// The time budget ran out: the pose is the best found before it did.
    pub out_of_time: bool,
}

/// `pose` shifted horizontally so that the asset's visible silhouette (rendered pixels not
/// hidden by nearer guidance) has the mask's pixel centroid and the mask's median depth.
fn recentred(mesh: &Mesh, pose: &Pose, target: &TargetRegion<'_>, window: Window) -> Option<Pose> {
    let view = rasterize(mesh, pose, target.camera, window);
    let median = |mut v: Vec<f64>| {
        v.sort_by(f64::total_cmp);
        v.get(v.len() / 2).copied()
    };
    let (mut rx, mut ry, mut rd) = (Vec::new(), Vec::new(), Vec::new());
    for y in 0..view.depth.height() {
        for x in 0..view.depth.width() {
            let Some(d) = view.depth.get(x, y) else {
                continue;
            };
            let (gx, gy) = view.to_guidance(x, y);
            let hidden = !target.mask.contains(gx, gy)
                && target.depth_at(gx, gy).is_some_and(|t| t < d - 0.05);
            if !hidden {
                rx.push(gx as f64);
                ry.push(gy as f64);
                rd.push(d as f64);
            }
        }
    }
    let (mut mx, mut my, mut md) = (Vec::new(), Vec::new(), Vec::new());
    for (x, y) in target.mask.pixels() {
        mx.push(x as f64);
        my.push(y as f64);
        if let Some(d) = target.depth_at(x, y) {
            md.push(d as f64);
        }
    }
    if rx.is_empty() || mx.is_empty() {
        return None;
    }
    let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
    let centre = pose.transform_point(&mesh.bounds()?.center());
    let p = target.camera.project(&centre)?;
    let depth = match (median(md), median(rd)) {
        (Some(m), Some(r)) => p.depth + (m - r),
        _ => p.depth,
    };
    let pixel = p.pixel + nalgebra::Vector2::new(mean(&mx) - mean(&rx), mean(&my) - mean(&ry));
    let moved = target.camera.unproject(&pixel, depth.max(0.05));
    let mut out = *pose;
    out.translation.x += moved.x - centre.x;
    out.translation.z += moved.z - centre.z;
    Some(out)
}

/// Aligns `mesh`, starting at `start`, to its object's guidance `target`: yaw hypotheses ranked
/// by [`ShapeMatcher`] scores (a facing `hint` settles ties such as front/back), then rounds of
/// matching with `matcher` and robust fitting of the pose-alignment loss. The scale stays in
/// `scale_range`. Returns the fitted pose, or the best-scoring pose seen when the fitted one
/// scores more than [`GuidedSettings::refine_tolerance`] below it, or `None` when the mask is
/// too small or the asset is not in view.
pub fn align_to_guidance(
    mesh: &Mesh,
    start: &Pose,
    scale_range: [f64; 2],
    target: &TargetRegion<'_>,
    matcher: &dyn Matcher,
    hint: Option<f64>,
    settings: &GuidedSettings,
) -> Option<GuidedPose> {
    let camera = target.camera;
    let (w, h) = (camera.intrinsics.width, camera.intrinsics.height);
    if target.mask.area() < settings.min_mask_pixels {
        return None;
    }
    let bbox = target.mask.bounding_box()?;
    let side = (bbox.2 - bbox.0).max(bbox.3 - bbox.1) as f64;
    let margin = ((side * settings.window_margin) as u32).max(6);
    let aligner = Aligner {
        mesh,
        target,
        matcher,
        settings,
        mask_window: Window::around(bbox, margin, w, h)?,
        scorer: ShapeMatcher::default(),
        deadline: settings.deadline(),
        hint,
        cut: Cell::new(false),
    };
    let start_score = aligner.score_at(start);
    let mut best = (*start, start_score);
    let fits_hint = |p: &Pose| aligner.fits_hint(p.yaw);
    if settings.yaw_candidates > 1 && !aligner.over() {
        if let Some(found) = aligner.best_yaw(start) {
            if found.1.score > best.1.score || (!fits_hint(start) && fits_hint(&found.0)) {
                best = found;
            }
        }
    }
    // A lift thrown off by stray depth (a mask spilling onto the wall behind) can leave the
    // object far from its mask: try the best pose so far moved so that its visible silhouette's centroid
    // and median depth match the mask's.
    let recentred = (!aligner.over())
        .then(|| recentred(mesh, &best.0, target, aligner.window_at(&best.0)))
        .flatten();
    if let Some(moved) = recentred {
        let score = aligner.score_at(&moved);
        if score.score > best.1.score {
            best = (moved, score);
        }
    }
    let refined = aligner.refine(start, scale_range, &mut best)?;
    let rounds = refined.rounds;
    let (mut best, mut alignment) = aligner.keep(refined, scale_range, best)?;
    let mut kept_start = None;
    if best.0 != *start && fits_hint(start) {
        let sigma = aligner.depth_sigma(start)?;
        let before = aligner.evidence(start, sigma, scale_range);
        let after = aligner.evidence(&best.0, sigma, scale_range);
        if let Some(reason) = before.beats(&after, settings.refine_tolerance) {
            kept_start = Some(reason);
            best = (*start, before.score);
            alignment = before.alignment;
        }
    }
    Some(GuidedPose {
        pose: best.0,
        alignment,
        start_score,
        score: best.1,
        rounds,
        kept_start,
        out_of_time: aligner.cut.get(),
    })
}

/// How well one pose agrees with its object's guidance, by the alignment's own measures (no
/// ground truth): the shape score of its view, and the robust alignment loss of the matches
/// made at that pose (silhouette pairs both ways and depth pairs, the scale prior left out),
/// a mean per pair, so poses with different match counts compare.
pub(crate) struct Evidence {
    /// The shape agreement of the pose's view.
    pub score: ShapeScore,
    /// The mean robust alignment loss of the pose's own matches (infinite without matches).
    pub residual: f64,
    /// The matches at the pose, outliers trimmed, for the optimizer.
    pub alignment: PoseAlignment,
}

impl Evidence {
    /// Why `self` (the starting pose) agrees with the guidance better than `fitted`, when it
    /// does: its matches fit with a lower residual and its shape score is not more than
    /// `tolerance` (a fraction) below the fitted pose's — or its shape score is more than
    /// `tolerance` above and its residual no higher.
    pub(crate) fn beats(&self, fitted: &Evidence, tolerance: f64) -> Option<String> {
        let tol = tolerance.clamp(0.0, 1.0);
        let (a, b) = (self.score.score, fitted.score.score);
        let fits_better = self.residual < fitted.residual && a >= b * (1.0 - tol);
        let looks_better = a > b * (1.0 + tol) && self.residual <= fitted.residual;
        (self.residual.is_finite() && (fits_better || looks_better)).then(|| {
            format!(
                "the raw lift agrees with the mask and depth better than the fitted pose \
                 (match residual {:.4} vs {:.4}, shape score {:.3} vs {:.3})",
                self.residual, fitted.residual, a, b
            )
        })
    }
}

/// One object's alignment: its mesh, its guidance, the matcher and settings, the mask's
/// window, the shape scorer, and the time budget (with whether it cut a step short).
struct Aligner<'a> {
    mesh: &'a Mesh,
    target: &'a TargetRegion<'a>,
    matcher: &'a dyn Matcher,
    settings: &'a GuidedSettings,
    mask_window: Window,
    scorer: ShapeMatcher,
    deadline: Option<Instant>,
    /// The facing hint, when there is one: no fit turns the object out of its window.
    hint: Option<f64>,
    /// Set when the budget made a step be skipped.
    cut: Cell<bool>,
}

/// What the refresh rounds leave: the last fitted pose, its shape score when known, the
/// alignment of its matches, and the rounds run.
struct Refined {
    pose: Pose,
    pose_score: Option<ShapeScore>,
    alignment: PoseAlignment,
    rounds: usize,
}

impl Aligner<'_> {
    /// Whether the budget is spent (and so a step is skipped).
    fn over(&self) -> bool {
        let p = past(self.deadline);
        if p {
            self.cut.set(true);
        }
        p
    }

    /// The window a view of the asset at `pose` is rendered in: its projected box grown by 2
    /// pixels, joined with the mask's window.
    fn window_at(&self, pose: &Pose) -> Window {
        let camera = self.target.camera;
        let (w, h) = (camera.intrinsics.width, camera.intrinsics.height);
        projected_bbox(self.mesh, pose, camera)
            .and_then(|b| Window::around(b, 2, w, h))
            .map_or(self.mask_window, |p| p.union(&self.mask_window))
    }

    /// The depth noise σ (metres) at the distance of the asset at `pose`: the 3D weight of
    /// its matches is `1/σ²`. `None` when the mesh has no bounds.
    fn depth_sigma(&self, pose: &Pose) -> Option<f64> {
        let depth = self
            .target
            .camera
            .project(&pose.transform_point(&self.mesh.bounds()?.center()))
            .map_or(1.0, |p| p.depth);
        Some((self.settings.depth_noise * depth).max(0.01))
    }

    /// The alignment of `pairs` under the settings' weights, for depth noise `sigma`.
    fn alignment_of(&self, pairs: Vec<crate::Correspondence>, sigma: f64) -> PoseAlignment {
        PoseAlignment {
            weight_2d: self.settings.weight_2d,
            weight_3d: 1.0 / (sigma * sigma),
            ..PoseAlignment::new(*self.target.camera, pairs)
        }
    }

    /// The robust fit options for depth noise `sigma`.
    fn fit_options(&self, scale_range: [f64; 2], sigma: f64) -> FitOptions {
        FitOptions {
            scale_range,
            huber_m: self.settings.fit.huber_m.max(2.0 * sigma),
            ..self.settings.fit
        }
    }

    /// The [`Evidence`] of `pose`, its matches weighted for depth noise `sigma` (the same σ
    /// for every pose compared, so their residuals are on one scale).
    fn evidence(&self, pose: &Pose, sigma: f64, scale_range: [f64; 2]) -> Evidence {
        let view = rasterize(self.mesh, pose, self.target.camera, self.window_at(pose));
        let score = shape_score(&view, self.target, &self.scorer);
        let pairs = lift(
            &self.matcher.match_view(&view, self.target),
            &view,
            self.target,
        );
        let mut alignment = self.alignment_of(pairs, sigma);
        let fit = self.fit_options(scale_range, sigma);
        let residual = if alignment.active().count() == 0 {
            f64::INFINITY
        } else {
            alignment.robust_loss(pose, &fit)
        };
        alignment.trim_outliers(pose, &fit, 2.0);
        Evidence {
            score,
            residual,
            alignment,
        }
    }

    /// The shape agreement of the asset at `pose` with the guidance.
    fn score_at(&self, pose: &Pose) -> ShapeScore {
        let view = rasterize(self.mesh, pose, self.target.camera, self.window_at(pose));
        shape_score(&view, self.target, &self.scorer)
    }

    /// The yaw hypotheses over the full turn from `start` (a coarse pass first when set),
    /// the pick among them (the facing hint settling ties and bounding them to its window), and its score.
    fn best_yaw(&self, start: &Pose) -> Option<(Pose, ShapeScore)> {
        let (mesh, camera, target, settings) =
            (self.mesh, self.target.camera, self.target, self.settings);
        let (w, h) = (camera.intrinsics.width, camera.intrinsics.height);
        let step = std::f64::consts::TAU / settings.yaw_candidates as f64;
        let all = (0..settings.yaw_candidates).map(|k| start.yaw + k as f64 * step);
        let within: Vec<f64> = all.clone().filter(|&y| self.fits_hint(y)).collect();
        let yaws: Vec<f64> = if within.is_empty() {
            all.collect()
        } else {
            within
        };
        // One window for every hypothesis: the mask's, grown to what the asset can cover.
        let radius = mesh.bounds().map_or(0.0, |b| {
            let e = b.max - b.min;
            (e.x * e.x + e.z * e.z).sqrt() / 2.0
        }) * start.scale;
        let pivot = mesh.bounds().map_or(Point3::origin(), |b| b.center());
        let centre = start.transform_point(&pivot);
        let reach = camera.project(&centre).map(|p| {
            let r = (camera.intrinsics.fx * radius / p.depth).ceil() as u32 + 2;
            let (x, y) = (p.pixel.x.max(0.0) as u32, p.pixel.y.max(0.0) as u32);
            Window::around((x, y, x + 1, y + 1), r, w, h)
        });
        let window = match reach.flatten() {
            Some(r) => r.union(&self.window_at(start)),
            None => self.window_at(start),
        };
        let scorer = &self.scorer;
        let candidates = if settings.coarse_stride > 1 && settings.coarse_keep < yaws.len() {
            let mut coarse = search_yaw_coarse(
                mesh,
                start,
                camera,
                target,
                window,
                &yaws,
                scorer,
                settings.coarse_stride,
            );
            // Stable: equal scores keep their order, so the shortlist is deterministic.
            coarse.sort_by(|a, b| b.score.score.total_cmp(&a.score.score));
            let shortlist: Vec<f64> = coarse
                .iter()
                .take(settings.coarse_keep.max(1))
                .map(|c| c.pose.yaw)
                .collect();
            search_yaw(mesh, start, camera, target, window, &shortlist, scorer)
        } else {
            search_yaw(mesh, start, camera, target, window, &yaws, scorer)
        };
        let pick = pick_yaw(&candidates, self.hint, settings.hint_tie)?;
        Some((pick.pose, self.score_at(&pick.pose)))
    }

    /// Rounds of matching at the current pose and robust fitting of the alignment loss, from
    /// the best pose so far, until the pose stops moving, too few matches remain, the rounds
    /// or the budget run out; `best` follows every scored pose. `None` when the mesh has no
    /// bounds.
    fn refine(
        &self,
        start: &Pose,
        scale_range: [f64; 2],
        best: &mut (Pose, ShapeScore),
    ) -> Option<Refined> {
        let (mesh, camera, target, settings) =
            (self.mesh, self.target.camera, self.target, self.settings);
        let scale_prior = (settings.scale_sigma > 0.0).then_some(ScalePrior {
            scale: start.scale,
            sigma: settings.scale_sigma,
        });
        let mut pose = best.0;
        let mut alignment = PoseAlignment::new(*camera, Vec::new());
        let mut rounds = 0;
        // The shape score of `pose` once known (the view rendered for matching scores it too).
        let mut pose_score = Some(best.1);
        for _ in 0..settings.refreshes {
            if self.over() {
                break;
            }
            rounds += 1;
            let view = rasterize(mesh, &pose, camera, self.window_at(&pose));
            let score = *pose_score.get_or_insert_with(|| shape_score(&view, target, &self.scorer));
            if score.score > best.1.score {
                *best = (pose, score);
            }
            let pairs = lift(&self.matcher.match_view(&view, target), &view, target);
            let sigma = self.depth_sigma(&pose)?;
            alignment = PoseAlignment {
                scale_prior,
                ..self.alignment_of(pairs, sigma)
            };
            if alignment.active().count() < 6 {
                break;
            }
            let fit = self.fit_options(scale_range, sigma);
            let next = self.within_hint(alignment.fit(&pose, &fit));
            let moved = (next.translation - pose.translation)
                .norm()
                .max((next.yaw - pose.yaw).abs())
                .max((next.scale - pose.scale).abs());
            pose = next;
            pose_score = None;
            if moved < settings.tolerance {
                break;
            }
        }
        Some(Refined {
            pose,
            pose_score,
            alignment,
            rounds,
        })
    }

    /// Whether `yaw` lies within the hint window of the facing hint (any yaw without one).
    fn fits_hint(&self, yaw: f64) -> bool {
        self.hint
            .is_none_or(|h| yaw_distance(yaw, h) <= self.settings.hint_window)
    }

    /// `pose` turned back, when a fit turned it more than the hint window away from the facing
    /// hint, to the window's nearer edge (yaw kept continuous with `pose`'s).
    fn within_hint(&self, mut pose: Pose) -> Pose {
        if let Some(h) = self.hint {
            let window = self.settings.hint_window;
            let off = wrap_yaw(pose.yaw - h);
            pose.yaw -= off - off.clamp(-window, window);
        }
        pose
    }

    /// The pose kept — the fitted one, unless it scores clearly worse than the best seen —
    /// with the matches of that pose, their outliers trimmed. `None` when the mesh has no
    /// bounds.
    fn keep(
        &self,
        refined: Refined,
        scale_range: [f64; 2],
        mut best: (Pose, ShapeScore),
    ) -> Option<((Pose, ShapeScore), PoseAlignment)> {
        let (mesh, camera, target, settings) =
            (self.mesh, self.target.camera, self.target, self.settings);
        let Refined {
            pose,
            pose_score,
            mut alignment,
            ..
        } = refined;
        if best.0 != pose {
            let score = pose_score.unwrap_or_else(|| self.score_at(&pose));
            if score.score >= best.1.score * (1.0 - settings.refine_tolerance.clamp(0.0, 1.0)) {
                best = (pose, score);
            }
        }
        if best.0 != pose {
            // Hand the optimizer the matches of the pose kept.
            let view = rasterize(mesh, &best.0, camera, self.window_at(&best.0));
            alignment.correspondences =
                lift(&self.matcher.match_view(&view, target), &view, target);
        }
        let trim = self.fit_options(scale_range, self.depth_sigma(&best.0)?);
        alignment.trim_outliers(&best.0, &trim, 2.0);
        Some((best, alignment))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Vector3;
    use scenethesis_imagery::{Camera, Intrinsics};

    fn evidence(score: f64, residual: f64) -> Evidence {
        let camera = Camera::look_at(
            Intrinsics::from_vertical_fov(64, 48, 1.0),
            Point3::new(0.0, 1.5, 3.0),
            Point3::origin(),
            Vector3::y(),
        );
        Evidence {
            score: ShapeScore {
                iou: score,
                depth_agreement: 1.0,
                score,
            },
            residual,
            alignment: PoseAlignment::new(camera, Vec::new()),
        }
    }

    #[test]
    fn the_lift_is_kept_only_when_the_image_says_it_is_better() {
        let fitted = evidence(0.80, 0.30);
        // Lower residual, shape score within 10 %: kept, with both measures in the reason.
        let reason = evidence(0.75, 0.20).beats(&fitted, 0.1).unwrap();
        assert!(reason.contains("0.2000 vs 0.3000"), "{reason}");
        // Clearly better shape score at an equal residual: kept.
        assert!(evidence(0.95, 0.30).beats(&fitted, 0.1).is_some());
        // Lower residual but a clearly worse shape score, or a higher residual: not kept.
        assert!(evidence(0.60, 0.20).beats(&fitted, 0.1).is_none());
        assert!(evidence(0.95, 0.31).beats(&fitted, 0.1).is_none());
        // No matches at the lift: nothing says it is better.
        assert!(evidence(0.95, f64::INFINITY).beats(&fitted, 0.1).is_none());
    }
}
