//! Pose alignment: 2D pixel and 3D point distances of correspondences between an object's
//! asset and the guidance image, under the guide's pinhole camera.

use crate::pair::{Correspondence, PairKind};
use nalgebra::Vector3;
use scenethesis_imagery::Camera;
use scenethesis_scene_graph::Pose;
use serde::{Deserialize, Serialize};

use crate::damped::{damped_step, take, NormalEquations};
use crate::params::{world_point, world_point_jacobian, PoseVector, SCALE};

/// Which pair a residual row belongs to, and whether it is measured in pixels.
#[derive(Debug, Clone, Copy)]
struct RowTag {
    pair: usize,
    pixels: bool,
}

/// The row tag of the scale prior (never robustified, never trimmed).
const PRIOR: usize = usize::MAX;

/// A Gaussian prior on an object's scale: the size it already has (from the lift or the
/// catalogue) is known to within `sigma` (relative), so the matches move the scale only as far
/// as they constrain it. Silhouette and depth matches constrain the scale weakly (a larger
/// object farther away looks alike), so without a prior their noise leaks into the size.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ScalePrior {
    /// The prior scale.
    pub scale: f64,
    /// Its relative uncertainty σ: the prior's residual is `ln(s / scale) / σ`.
    pub sigma: f64,
}

/// Options of [`PoseAlignment::fit`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FitOptions {
    /// Levenberg–Marquardt iterations at most.
    pub iterations: usize,
    /// Huber threshold of a pair's pixel error, pixels (≤ 0: plain least squares).
    pub huber_px: f64,
    /// Huber threshold of a pair's 3D or depth error, metres (≤ 0: plain least squares).
    pub huber_m: f64,
    /// The allowed scale range.
    pub scale_range: [f64; 2],
    /// Keep the starting scale.
    pub fix_scale: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            iterations: 30,
            huber_px: 2.0,
            huber_m: 0.05,
            scale_range: [0.0, f64::INFINITY],
            fix_scale: false,
        }
    }
}

/// The pose-alignment objective of one object:
/// `L_pose = λ_2d · mean ‖π(x_k) − q_k‖² + λ_3d · mean ‖x_k − X_k‖²`, where `x_k` is the posed
/// asset point, `π` the camera projection, `q_k` the target pixel and `X_k` the target point.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PoseAlignment {
    /// The camera the guidance image was taken with.
    pub camera: Camera,
    /// The matched pairs.
    pub correspondences: Vec<Correspondence>,
    /// Weight of the 2D term, per squared pixel.
    pub weight_2d: f64,
    /// Weight of the 3D term, per squared metre.
    pub weight_3d: f64,
    /// Pairs with a lower confidence are ignored (the paper uses τ = 0.6).
    pub min_confidence: f64,
    /// A prior on the scale, added to the loss as one squared residual `(ln(s/s₀)/σ)²` (on
    /// the scale of one mean pair term); `None`: the matches alone set the scale.
    #[serde(default)]
    pub scale_prior: Option<ScalePrior>,
}

impl PoseAlignment {
    /// An alignment with the default weights: the 2D term measured in focal lengths (so that a
    /// pixel error counts like the angle it subtends), the 3D term in metres, and τ = 0.6.
    pub fn new(camera: Camera, correspondences: Vec<Correspondence>) -> Self {
        let f = camera.intrinsics.fx.max(1e-9);
        Self {
            camera,
            correspondences,
            weight_2d: 1.0 / (f * f),
            weight_3d: 1.0,
            min_confidence: 0.6,
            scale_prior: None,
        }
    }

    /// The pairs that pass the confidence threshold.
    pub fn active(&self) -> impl Iterator<Item = &Correspondence> + '_ {
        self.correspondences
            .iter()
            .filter(move |c| c.confidence >= self.min_confidence)
    }

    /// Stacked weighted residuals `r` (so that `L_pose = Σ r²`) and, when `jacobian` is given,
    /// their derivatives with respect to the pose vector, one row per residual. Pairs whose
    /// point falls behind the camera contribute only their 3D residual; depth pairs
    /// ([`PairKind::Depth`]) contribute one row, the depth difference along the optical axis.
    pub fn residuals(&self, pose: &Pose, jacobian: Option<&mut Vec<PoseVector>>) -> Vec<f64> {
        self.rows(pose, jacobian, None)
    }

    /// [`Self::residuals`], also recording for every row which pair it belongs to and whether
    /// it is a pixel row (else a metre row).
    fn rows(
        &self,
        pose: &Pose,
        mut jacobian: Option<&mut Vec<PoseVector>>,
        mut tags: Option<&mut Vec<RowTag>>,
    ) -> Vec<f64> {
        let n = self.active().count().max(1) as f64;
        let w2 = (self.weight_2d / n).sqrt();
        let w3 = (self.weight_3d / n).sqrt();
        let cam = &self.camera;
        let k = &cam.intrinsics;
        let cam_from_world = cam.rotation.inverse();
        let mut out = Vec::new();
        if let Some(j) = jacobian.as_deref_mut() {
            j.clear();
        }
        if let Some(t) = tags.as_deref_mut() {
            t.clear();
        }
        let mut tag = |pair: usize, pixels: bool, count: usize| {
            if let Some(t) = tags.as_deref_mut() {
                for _ in 0..count {
                    t.push(RowTag { pair, pixels });
                }
            }
        };
        for (index, c) in self.active().enumerate() {
            let x = world_point(pose, &c.asset_point);
            let dx = world_point_jacobian(pose, &c.asset_point);
            let local = cam_from_world * (x - cam.position);
            let depth = -local.z;
            if c.kind == PairKind::Depth {
                let Some(target) = c.target_point else {
                    continue;
                };
                let target_depth = -(cam_from_world * (target - cam.position)).z;
                out.push(w3 * (depth - target_depth));
                tag(index, false, 1);
                if let Some(j) = jacobian.as_deref_mut() {
                    let mut row = PoseVector::zeros();
                    for (col, d) in dx.iter().enumerate() {
                        row[col] = -w3 * (cam_from_world * d).z;
                    }
                    j.push(row);
                }
                continue;
            }
            if depth > 1e-6 {
                let u = k.cx + k.fx * local.x / depth;
                let v = k.cy - k.fy * local.y / depth;
                out.push(w2 * (u - c.target_pixel.x));
                out.push(w2 * (v - c.target_pixel.y));
                tag(index, true, 2);
                if let Some(j) = jacobian.as_deref_mut() {
                    // u = cx + fx·x/(−z), v = cy + fy·y/z in the camera frame.
                    let du = Vector3::new(k.fx / depth, 0.0, k.fx * local.x / (depth * depth));
                    let dv = Vector3::new(0.0, -k.fy / depth, -k.fy * local.y / (depth * depth));
                    let mut ju = PoseVector::zeros();
                    let mut jv = PoseVector::zeros();
                    for (col, d) in dx.iter().enumerate() {
                        let dc = cam_from_world * d;
                        ju[col] = w2 * du.dot(&dc);
                        jv[col] = w2 * dv.dot(&dc);
                    }
                    j.push(ju);
                    j.push(jv);
                }
            }
            if let Some(target) = c.target_point {
                let r = x - target;
                tag(index, false, 3);
                for axis in 0..3 {
                    out.push(w3 * r[axis]);
                    if let Some(j) = jacobian.as_deref_mut() {
                        let mut row = PoseVector::zeros();
                        for (col, d) in dx.iter().enumerate() {
                            row[col] = w3 * d[axis];
                        }
                        j.push(row);
                    }
                }
            }
        }
        if let Some(prior) = self.scale_prior {
            if prior.sigma > 0.0 && pose.scale > 0.0 && prior.scale > 0.0 {
                out.push((pose.scale / prior.scale).ln() / prior.sigma);
                tag(PRIOR, false, 1);
                if let Some(j) = jacobian {
                    let mut row = PoseVector::zeros();
                    row[SCALE] = 1.0 / (pose.scale * prior.sigma);
                    j.push(row);
                }
            }
        }
        out
    }

    /// Per-row robust weights (Huber): each pair's pixel rows and metre rows are judged by
    /// their unweighted error norm against `options.huber_px` / `options.huber_m`.
    fn huber_weights(&self, r: &[f64], tags: &[RowTag], options: &FitOptions) -> Vec<f64> {
        let n = self.active().count().max(1) as f64;
        let w2 = (self.weight_2d / n).sqrt().max(1e-300);
        let w3 = (self.weight_3d / n).sqrt().max(1e-300);
        let mut norms: std::collections::HashMap<(usize, bool), f64> = Default::default();
        for (ri, t) in r.iter().zip(tags).filter(|(_, t)| t.pair != PRIOR) {
            let raw = ri / if t.pixels { w2 } else { w3 };
            *norms.entry((t.pair, t.pixels)).or_default() += raw * raw;
        }
        tags.iter()
            .map(|t| {
                if t.pair == PRIOR {
                    return 1.0;
                }
                let e = norms[&(t.pair, t.pixels)].sqrt();
                let delta = if t.pixels {
                    options.huber_px
                } else {
                    options.huber_m
                };
                if e <= delta || delta <= 0.0 {
                    1.0
                } else {
                    delta / e
                }
            })
            .collect()
    }

    /// The robust (Huber) loss at `pose`: each pair's pixel and metre errors count
    /// quadratically up to their threshold and linearly beyond it.
    pub fn robust_loss(&self, pose: &Pose, options: &FitOptions) -> f64 {
        let mut tags = Vec::new();
        let r = self.rows(pose, None, Some(&mut tags));
        let n = self.active().count().max(1) as f64;
        let w2 = (self.weight_2d / n).sqrt().max(1e-300);
        let w3 = (self.weight_3d / n).sqrt().max(1e-300);
        let mut norms: std::collections::BTreeMap<(usize, bool), f64> = Default::default();
        let mut prior = 0.0;
        for (ri, t) in r.iter().zip(&tags) {
            if t.pair == PRIOR {
                prior += ri * ri;
                continue;
            }
            let raw = ri / if t.pixels { w2 } else { w3 };
            *norms.entry((t.pair, t.pixels)).or_default() += raw * raw;
        }
        prior
            + norms
                .iter()
                .map(|(&(_, pixels), &e2)| {
                    let (w, delta) = if pixels {
                        (self.weight_2d / n, options.huber_px)
                    } else {
                        (self.weight_3d / n, options.huber_m)
                    };
                    let e = e2.sqrt();
                    w * if e <= delta || delta <= 0.0 {
                        e2
                    } else {
                        2.0 * delta * e - delta * delta
                    }
                })
                .sum::<f64>()
    }

    /// Sets the confidence of every pair whose pixel or metre error at `pose` exceeds `k`
    /// times its Huber threshold to 0 (so plain least squares on the rest agrees with the
    /// robust fit); returns how many pairs were dropped.
    pub fn trim_outliers(&mut self, pose: &Pose, options: &FitOptions, k: f64) -> usize {
        let mut tags = Vec::new();
        let r = self.rows(pose, None, Some(&mut tags));
        let weights = self.huber_weights(&r, &tags, options);
        let mut bad = std::collections::BTreeSet::new();
        for (t, w) in tags.iter().zip(&weights) {
            // Huber weight δ/e below 1/k means e > k·δ.
            if *w < 1.0 / k && t.pair != PRIOR {
                bad.insert(t.pair);
            }
        }
        let min = self.min_confidence;
        let mut dropped = 0;
        for (index, c) in self
            .correspondences
            .iter_mut()
            .filter(|c| c.confidence >= min)
            .enumerate()
        {
            if bad.contains(&index) {
                c.confidence = 0.0;
                dropped += 1;
            }
        }
        dropped
    }

    /// Minimises the robust loss from `start` by Levenberg–Marquardt on iteratively reweighted
    /// residuals, keeping the scale in `options.scale_range` (or fixed). Gravity stays fixed:
    /// only scale, yaw and translation move.
    pub fn fit(&self, start: &Pose, options: &FitOptions) -> Pose {
        let clamp = |p: Pose| {
            let mut p = p;
            p.scale = if options.fix_scale {
                start.scale
            } else {
                p.scale
                    .clamp(options.scale_range[0], options.scale_range[1])
            };
            p
        };
        let mut pose = clamp(*start);
        let mut cost = self.robust_loss(&pose, options);
        let mut lambda = 1e-3;
        let (mut jac, mut tags) = (Vec::new(), Vec::new());
        for _ in 0..options.iterations {
            let r = self.rows(&pose, Some(&mut jac), Some(&mut tags));
            if r.is_empty() {
                break;
            }
            let weights = self.huber_weights(&r, &tags, options);
            let mut normal = NormalEquations::of(&r, &jac, Some(&weights));
            if options.fix_scale {
                for k in 0..5 {
                    normal.jtj[(SCALE, k)] = 0.0;
                    normal.jtj[(k, SCALE)] = 0.0;
                }
                normal.jtj[(SCALE, SCALE)] = 1.0;
                normal.jtr[SCALE] = 0.0;
            }
            let cost_of = |p: &Pose| self.robust_loss(p, options);
            let step = damped_step(&normal, &pose, cost, &mut lambda, 10, clamp, cost_of);
            if !take(step, &mut pose, &mut cost) {
                break;
            }
        }
        pose
    }

    /// The loss `L_pose` at `pose`.
    pub fn loss(&self, pose: &Pose) -> f64 {
        self.residuals(pose, None).iter().map(|r| r * r).sum()
    }

    /// The loss and its gradient with respect to the pose vector.
    pub fn loss_and_gradient(&self, pose: &Pose) -> (f64, PoseVector) {
        let mut jac = Vec::new();
        let r = self.residuals(pose, Some(&mut jac));
        let mut grad = PoseVector::zeros();
        for (ri, row) in r.iter().zip(&jac) {
            grad += row * (2.0 * ri);
        }
        (r.iter().map(|x| x * x).sum(), grad)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::{from_vector, to_vector};
    use nalgebra::Point3;
    use scenethesis_imagery::Intrinsics;

    fn setup() -> (PoseAlignment, Pose) {
        let camera = Camera::look_at(
            Intrinsics::from_vertical_fov(640, 480, 1.0),
            Point3::new(2.0, 1.8, 3.0),
            Point3::new(0.0, 0.4, 0.0),
            Vector3::y(),
        );
        let truth = Pose::new(1.1, 0.3, Vector3::new(0.2, 0.0, -0.1));
        let points = [
            Point3::new(0.2, 0.1, 0.3),
            Point3::new(-0.3, 0.5, 0.1),
            Point3::new(0.1, 0.8, -0.2),
        ];
        let correspondences = points
            .iter()
            .map(|p| Correspondence::exact(&camera, *p, world_point(&truth, p), 0.9).unwrap())
            .collect();
        (PoseAlignment::new(camera, correspondences), truth)
    }

    #[test]
    fn loss_vanishes_at_the_true_pose_and_gradient_matches_differences() {
        let (align, truth) = setup();
        assert!(align.loss(&truth) < 1e-20);
        let pose = Pose::new(0.9, 0.1, Vector3::new(0.0, 0.05, 0.1));
        let (_, grad) = align.loss_and_gradient(&pose);
        let v = to_vector(&pose);
        for k in 0..5 {
            let h = 1e-6;
            let (mut a, mut b) = (v, v);
            a[k] += h;
            b[k] -= h;
            let fd = (align.loss(&from_vector(&a)) - align.loss(&from_vector(&b))) / (2.0 * h);
            assert!(
                (fd - grad[k]).abs() < 1e-5 * (1.0 + fd.abs()),
                "parameter {k}: {fd} vs {}",
                grad[k]
            );
        }
    }

    #[test]
    fn scale_prior_pulls_the_size_and_leaves_the_rest_to_the_matches() {
        let (mut align, truth) = setup();
        let start = Pose::new(1.0, 0.2, truth.translation + Vector3::new(0.1, 0.0, -0.1));
        let options = FitOptions {
            scale_range: [0.5, 2.0],
            ..FitOptions::default()
        };
        // A loose prior at the true scale: the matches recover the pose.
        align.scale_prior = Some(ScalePrior {
            scale: truth.scale,
            sigma: 0.05,
        });
        let fit = align.fit(&start, &options);
        assert!((fit.scale - truth.scale).abs() < 1e-3, "{fit:?}");
        assert!(
            (fit.translation - truth.translation).norm() < 1e-3,
            "{fit:?}"
        );
        // Its gradient is part of the loss's.
        let (_, grad) = align.loss_and_gradient(&start);
        let h = 1e-6;
        let (mut a, mut b) = (to_vector(&start), to_vector(&start));
        a[SCALE] += h;
        b[SCALE] -= h;
        let fd = (align.loss(&from_vector(&a)) - align.loss(&from_vector(&b))) / (2.0 * h);
        assert!((fd - grad[SCALE]).abs() < 1e-5 * (1.0 + fd.abs()));
        // A tight prior elsewhere holds the scale there; trimming never drops it.
        align.scale_prior = Some(ScalePrior {
            scale: 1.0,
            sigma: 1e-4,
        });
        let held = align.fit(&start, &options);
        assert!((held.scale - 1.0).abs() < 2e-3, "{held:?}");
        align.trim_outliers(&held, &options, 2.0);
        assert!(align.residuals(&held, None).len() > 1);
        assert!(align.scale_prior.is_some());
    }

    #[test]
    fn low_confidence_pairs_are_ignored() {
        let (mut align, truth) = setup();
        align.correspondences[0].confidence = 0.1;
        align.correspondences[0].target_pixel.x += 500.0;
        assert!(align.loss(&truth) < 1e-20);
    }
}
