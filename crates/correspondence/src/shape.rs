//! The default matcher: shape over texture. A retrieved or procedural asset rarely looks like
//! the photographed object, but its silhouette and depth do: [`ShapeMatcher`] pairs the
//! rendered silhouette with the object's mask (chamfer pairs both ways, through a nearest-pixel
//! map) and the rendered depth with the guidance depth (robust depth pairs), ignoring rendered
//! pixels hidden by nearer objects. [`shape_score`] and [`search_yaw`] rank discrete yaw
//! hypotheses by occlusion-aware silhouette IoU and depth agreement before any continuous
//! refinement.

use nalgebra::{Point2, Vector3};
use scenethesis_scene_graph::{Camera, Mesh, Pose};

use crate::matcher::{MatchKind, Matcher, PixelMatch, TargetRegion};
use crate::raster::{rasterize, RenderedView, Window};

/// Silhouette and depth matching of a rendered asset against its object's mask and depth.
#[derive(Debug, Clone, PartialEq)]
pub struct ShapeMatcher {
    /// Relative depth noise of the guidance (σ as a fraction of depth) used to trim depth
    /// pairs.
    pub depth_noise: f64,
    /// Smallest depth σ in metres.
    pub min_depth_sigma: f64,
    /// A rendered pixel outside the mask whose guidance depth is nearer than the rendered depth
    /// by more than this (metres) is hidden by another object and ignored.
    pub occlusion_margin: f64,
    /// At most this many pairs of each kind (silhouette, depth), taken evenly.
    pub max_pairs: usize,
}

impl Default for ShapeMatcher {
    fn default() -> Self {
        Self {
            depth_noise: 0.03,
            min_depth_sigma: 0.02,
            occlusion_margin: 0.05,
            max_pairs: 400,
        }
    }
}

/// How well a rendered view agrees with its object's mask and depth.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShapeScore {
    /// Intersection over union of the rendered silhouette (pixels hidden by nearer objects
    /// removed) and the mask, inside the view's window.
    pub iou: f64,
    /// Fraction of the overlap whose depth difference is within tolerance of the median
    /// difference (1 without guidance depth).
    pub depth_agreement: f64,
    /// The ranking score `iou · (0.5 + 0.5 · depth_agreement)`.
    pub score: f64,
}

/// Per-pixel classification of a view against its target.
struct Classified {
    w: usize,
    h: usize,
    /// Rendered depth per view pixel (NaN = not covered).
    rendered: Vec<f32>,
    /// Guidance mask per view pixel.
    mask: Vec<bool>,
    /// Guidance depth per view pixel (NaN = unknown).
    target: Vec<f32>,
    /// Rendered and not hidden by a nearer object.
    visible: Vec<bool>,
}

fn classify(view: &RenderedView, target: &TargetRegion<'_>, margin: f64) -> Classified {
    let (w, h) = (view.depth.width() as usize, view.depth.height() as usize);
    let mut rendered = Vec::with_capacity(w * h);
    let mut mask = Vec::with_capacity(w * h);
    let mut tdepth = Vec::with_capacity(w * h);
    let mut visible = Vec::with_capacity(w * h);
    for y in 0..h as u32 {
        for x in 0..w as u32 {
            let (gx, gy) = view.to_guidance(x, y);
            let r = view.depth.get(x, y).unwrap_or(f32::NAN);
            let m = target.mask.contains(gx, gy);
            let t = target.depth_at(gx, gy).unwrap_or(f32::NAN);
            let hidden = !m && r.is_finite() && t.is_finite() && (t as f64) < r as f64 - margin;
            rendered.push(r);
            mask.push(m);
            tdepth.push(t);
            visible.push(r.is_finite() && !hidden);
        }
    }
    Classified {
        w,
        h,
        rendered,
        mask,
        target: tdepth,
        visible,
    }
}

fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// The robust centre and spread (1.4826 · MAD) of the depth differences over the overlap.
fn depth_offsets(c: &Classified) -> Option<(f64, f64)> {
    let mut d: Vec<f64> = (0..c.w * c.h)
        .filter(|&i| c.mask[i] && c.rendered[i].is_finite() && c.target[i].is_finite())
        .map(|i| (c.rendered[i] - c.target[i]) as f64)
        .collect();
    if d.is_empty() {
        return None;
    }
    let centre = median(&mut d);
    let mut dev: Vec<f64> = d.iter().map(|x| (x - centre).abs()).collect();
    Some((centre, 1.4826 * median(&mut dev)))
}

/// The score of `view` against `target` (see [`ShapeScore`]).
pub fn shape_score(
    view: &RenderedView,
    target: &TargetRegion<'_>,
    matcher: &ShapeMatcher,
) -> ShapeScore {
    let c = classify(view, target, matcher.occlusion_margin);
    let (mut inter, mut rend, mut mask) = (0usize, 0usize, 0usize);
    for i in 0..c.w * c.h {
        rend += c.visible[i] as usize;
        mask += c.mask[i] as usize;
        inter += (c.visible[i] && c.mask[i]) as usize;
    }
    let union = rend + mask - inter;
    let iou = if union == 0 {
        0.0
    } else {
        inter as f64 / union as f64
    };
    let depth_agreement = match depth_offsets(&c) {
        None if target.depth.is_some() && inter > 0 => 0.0,
        None => 1.0,
        Some((centre, _)) => {
            let (mut good, mut all) = (0usize, 0usize);
            for i in 0..c.w * c.h {
                if c.mask[i] && c.rendered[i].is_finite() && c.target[i].is_finite() {
                    all += 1;
                    let t = c.target[i] as f64;
                    let tol = 2.0 * (matcher.depth_noise * t).max(matcher.min_depth_sigma);
                    good += (((c.rendered[i] - c.target[i]) as f64 - centre).abs() <= tol) as usize;
                }
            }
            good as f64 / all.max(1) as f64
        }
    };
    ShapeScore {
        iou,
        depth_agreement,
        score: iou * (0.5 + 0.5 * depth_agreement),
    }
}

/// For every pixel of a `w × h` grid, the index of the nearest pixel whose flag is set
/// (`usize::MAX` when none is): two raster passes propagating nearest seeds over 8-neighbours
/// (exact within a pixel or so for the convex-ish regions of object masks).
pub fn nearest_set_pixel(flags: &[bool], w: usize, h: usize) -> Vec<usize> {
    let mut near = vec![usize::MAX; w * h];
    for (i, &f) in flags.iter().enumerate() {
        if f {
            near[i] = i;
        }
    }
    let d2 = |i: usize, s: usize| {
        let (ax, ay) = ((i % w) as i64, (i / w) as i64);
        let (bx, by) = ((s % w) as i64, (s / w) as i64);
        (ax - bx).pow(2) + (ay - by).pow(2)
    };
    let relax = |near: &mut Vec<usize>, x: usize, y: usize, offsets: &[(i64, i64)]| {
        let i = y * w + x;
        for (dx, dy) in offsets {
            let (nx, ny) = (x as i64 + dx, y as i64 + dy);
            if nx < 0 || ny < 0 || nx >= w as i64 || ny >= h as i64 {
                continue;
            }
            let s = near[ny as usize * w + nx as usize];
            if s != usize::MAX && (near[i] == usize::MAX || d2(i, s) < d2(i, near[i])) {
                near[i] = s;
            }
        }
    };
    let forward = [(-1, 0), (-1, -1), (0, -1), (1, -1)];
    let backward = [(1, 0), (1, 1), (0, 1), (-1, 1)];
    for _ in 0..2 {
        for y in 0..h {
            for x in 0..w {
                relax(&mut near, x, y, &forward);
            }
            for x in (0..w).rev() {
                relax(&mut near, x, y, &[(1, 0)]);
            }
        }
        for y in (0..h).rev() {
            for x in (0..w).rev() {
                relax(&mut near, x, y, &backward);
            }
            for x in 0..w {
                relax(&mut near, x, y, &[(-1, 0)]);
            }
        }
    }
    near
}

/// Every `k`-th item so that at most `max` remain.
fn thin<T>(v: Vec<T>, max: usize) -> Vec<T> {
    if v.len() <= max || max == 0 {
        return v;
    }
    let step = v.len().div_ceil(max);
    v.into_iter().step_by(step).collect()
}

impl Matcher for ShapeMatcher {
    fn name(&self) -> &str {
        "shape"
    }

    /// Silhouette pairs both ways (a rendered pixel outside the mask → the nearest mask pixel;
    /// a mask pixel the render misses → the nearest rendered pixel), rendered pixels hidden by
    /// nearer objects ignored; and a depth pair per overlapping pixel, trimmed at three σ
    /// (the larger of the stated noise and the robust spread) around the median difference.
    fn match_view(&self, view: &RenderedView, target: &TargetRegion<'_>) -> Vec<PixelMatch> {
        let c = classify(view, target, self.occlusion_margin);
        let (w, off) = (c.w, view.offset);
        let centre = |i: usize| {
            Point2::new(
                (i % w) as f64 + off[0] as f64 + 0.5,
                (i / w) as f64 + off[1] as f64 + 0.5,
            )
        };
        let pixel = |i: usize| [(i % w) as u32, (i / w) as u32];
        let near_mask = nearest_set_pixel(&c.mask, c.w, c.h);
        let near_render = nearest_set_pixel(&c.visible, c.w, c.h);
        let mut silhouette = Vec::new();
        for i in 0..c.w * c.h {
            if c.visible[i] && !c.mask[i] && near_mask[i] != usize::MAX {
                silhouette.push(PixelMatch {
                    rendered: pixel(i),
                    target: centre(near_mask[i]),
                    confidence: 1.0,
                    kind: MatchKind::Silhouette,
                });
            } else if c.mask[i] && !c.visible[i] && near_render[i] != usize::MAX {
                silhouette.push(PixelMatch {
                    rendered: pixel(near_render[i]),
                    target: centre(i),
                    confidence: 1.0,
                    kind: MatchKind::Silhouette,
                });
            }
        }
        let mut depth = Vec::new();
        if let Some((med, spread)) = depth_offsets(&c) {
            for i in 0..c.w * c.h {
                if !(c.mask[i] && c.rendered[i].is_finite() && c.target[i].is_finite()) {
                    continue;
                }
                let t = c.target[i] as f64;
                let sigma = (self.depth_noise * t).max(self.min_depth_sigma).max(spread);
                let inlier = (((c.rendered[i] - c.target[i]) as f64) - med).abs() <= 3.0 * sigma;
                depth.push(PixelMatch {
                    rendered: pixel(i),
                    target: centre(i),
                    confidence: if inlier { 1.0 } else { 0.0 },
                    kind: MatchKind::Depth,
                });
            }
        }
        let mut out = thin(silhouette, self.max_pairs);
        out.extend(thin(depth, self.max_pairs));
        out
    }
}

/// `pose` turned to `yaw` about the vertical axis through the asset's local point `pivot`
/// (so the object's box centre stays put).
pub fn turned(pose: &Pose, pivot: &nalgebra::Point3<f64>, yaw: f64) -> Pose {
    let rot = |a: f64, v: &Vector3<f64>| {
        let (s, c) = a.sin_cos();
        Vector3::new(c * v.x + s * v.z, v.y, -s * v.x + c * v.z)
    };
    let arm = pivot.coords * pose.scale;
    let translation = pose.translation + rot(pose.yaw, &arm) - rot(yaw, &arm);
    Pose::new(pose.scale, yaw, translation)
}

/// One yaw hypothesis and its score.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct YawCandidate {
    /// The pose with the hypothesis' yaw (turned about the asset's box centre).
    pub pose: Pose,
    /// Its score.
    pub score: ShapeScore,
}

/// Renders `mesh` at each yaw of `yaws` (turned about its box centre from `start`) inside
/// `window` and scores it against `target`.
pub fn search_yaw(
    mesh: &Mesh,
    start: &Pose,
    camera: &Camera,
    target: &TargetRegion<'_>,
    window: Window,
    yaws: &[f64],
    matcher: &ShapeMatcher,
) -> Vec<YawCandidate> {
    let pivot = mesh
        .bounds()
        .map_or(nalgebra::Point3::origin(), |b| b.center());
    yaws.iter()
        .map(|&yaw| {
            let pose = turned(start, &pivot, yaw);
            let view = rasterize(mesh, &pose, camera, window);
            YawCandidate {
                pose,
                score: shape_score(&view, target, matcher),
            }
        })
        .collect()
}

/// The angle between two yaws, in [0, π].
pub fn yaw_distance(a: f64, b: f64) -> f64 {
    let d = (a - b).rem_euclid(std::f64::consts::TAU);
    d.min(std::f64::consts::TAU - d)
}

/// The best candidate; among those within `tie` (relative) of the best score, the one nearest
/// to `hint` when a hint is given (a facing direction from the plan or scene graph, which is
/// what settles a silhouette's front/back ambiguity).
pub fn pick_yaw(candidates: &[YawCandidate], hint: Option<f64>, tie: f64) -> Option<YawCandidate> {
    let best = candidates
        .iter()
        .max_by(|a, b| a.score.score.total_cmp(&b.score.score))?;
    let Some(hint) = hint else {
        return Some(*best);
    };
    candidates
        .iter()
        .filter(|c| c.score.score >= best.score.score * (1.0 - tie))
        .min_by(|a, b| yaw_distance(a.pose.yaw, hint).total_cmp(&yaw_distance(b.pose.yaw, hint)))
        .copied()
}
