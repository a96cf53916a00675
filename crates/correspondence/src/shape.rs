//! The default matcher: shape over texture. A retrieved or procedural asset rarely looks like
//! the photographed object, but its silhouette and depth do: [`ShapeMatcher`] pairs the
//! rendered silhouette with the object's mask (chamfer pairs both ways, through a nearest-pixel
//! map) and the rendered depth with the guidance depth (robust depth pairs), ignoring rendered
//! pixels hidden by nearer objects. [`shape_score`] and [`search_yaw`] rank discrete yaw
//! hypotheses by occlusion-aware silhouette IoU and depth agreement before any continuous
//! refinement.

use nalgebra::{Point2, Vector3};
use scenethesis_imagery::Camera;
use scenethesis_scene_graph::{yaw_distance, Mesh, Pose};

use crate::matcher::{MatchKind, Matcher, PixelMatch, TargetRegion};
use crate::raster::{rasterize_coarse, RenderedView, Window};

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

/// The upper median (the element at `len / 2` in sorted order), by selection (no full sort).
fn median(v: &mut [f64]) -> f64 {
    if v.is_empty() {
        return 0.0;
    }
    let mid = v.len() / 2;
    *v.select_nth_unstable_by(mid, f64::total_cmp).1
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
/// (`usize::MAX` when none is), exactly in Euclidean distance: the nearest set pixel of each
/// column, then per row the lower envelope of the parabolas `(x − x')² + dy(x')²`
/// (Felzenszwalb–Huttenlocher), linear in the number of pixels.
pub fn nearest_set_pixel(flags: &[bool], w: usize, h: usize) -> Vec<usize> {
    const NONE: u32 = u32::MAX;
    let mut out = vec![usize::MAX; w * h];
    if w == 0 || h == 0 || flags.len() < w * h {
        return out;
    }
    // The row of the nearest set pixel in the same column.
    let mut column = vec![NONE; w * h];
    for x in 0..w {
        let mut last = NONE;
        for y in 0..h {
            if flags[y * w + x] {
                last = y as u32;
            }
            column[y * w + x] = last;
        }
        let mut next = NONE;
        for y in (0..h).rev() {
            if flags[y * w + x] {
                next = y as u32;
            }
            let here = &mut column[y * w + x];
            if next != NONE && (*here == NONE || next as usize - y < y - *here as usize) {
                *here = next;
            }
        }
    }
    let mut sites = vec![0usize; w];
    let mut bounds = vec![0f64; w + 1];
    for y in 0..h {
        let row = &column[y * w..(y + 1) * w];
        let height = |x: usize| {
            let d = row[x] as f64 - y as f64;
            d * d + (x * x) as f64
        };
        let mut count = 0usize;
        for (q, &r) in row.iter().enumerate() {
            if r == NONE {
                continue;
            }
            loop {
                if count == 0 {
                    sites[0] = q;
                    bounds[0] = f64::NEG_INFINITY;
                    bounds[1] = f64::INFINITY;
                    count = 1;
                    break;
                }
                let p = sites[count - 1];
                let s = (height(q) - height(p)) / (2.0 * (q - p) as f64);
                if s <= bounds[count - 1] {
                    count -= 1;
                    continue;
                }
                sites[count] = q;
                bounds[count] = s;
                bounds[count + 1] = f64::INFINITY;
                count += 1;
                break;
            }
        }
        if count == 0 {
            continue;
        }
        let mut j = 0;
        for x in 0..w {
            while bounds[j + 1] < x as f64 {
                j += 1;
            }
            let p = sites[j];
            out[y * w + x] = row[p] as usize * w + p;
        }
    }
    out
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
        let w = c.w;
        let centre = |i: usize| {
            let (gx, gy) = view.to_guidance((i % w) as u32, (i / w) as u32);
            Point2::new(gx as f64 + 0.5, gy as f64 + 0.5)
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
    search_yaw_coarse(mesh, start, camera, target, window, yaws, matcher, 1)
}

/// [`search_yaw`] on views rendered at `stride` ([`rasterize_coarse`]): about `stride²` times
/// cheaper, for a first pass over many hypotheses.
#[allow(clippy::too_many_arguments)]
pub fn search_yaw_coarse(
    mesh: &Mesh,
    start: &Pose,
    camera: &Camera,
    target: &TargetRegion<'_>,
    window: Window,
    yaws: &[f64],
    matcher: &ShapeMatcher,
    stride: u32,
) -> Vec<YawCandidate> {
    let pivot = mesh
        .bounds()
        .map_or(nalgebra::Point3::origin(), |b| b.center());
    yaws.iter()
        .map(|&yaw| {
            let pose = turned(start, &pivot, yaw);
            let view = rasterize_coarse(mesh, &pose, camera, window, stride);
            YawCandidate {
                pose,
                score: shape_score(&view, target, matcher),
            }
        })
        .collect()
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

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_set_pixel_is_exact() {
        let (w, h) = (23usize, 17usize);
        // A few scattered seeds and a blob.
        let mut flags = vec![false; w * h];
        for (x, y) in [
            (0, 0),
            (22, 3),
            (5, 16),
            (11, 8),
            (12, 8),
            (11, 9),
            (17, 12),
        ] {
            flags[y * w + x] = true;
        }
        let near = nearest_set_pixel(&flags, w, h);
        for y in 0..h {
            for x in 0..w {
                let d2 = |s: usize| {
                    let (sx, sy) = ((s % w) as i64, (s / w) as i64);
                    (sx - x as i64).pow(2) + (sy - y as i64).pow(2)
                };
                let best = (0..w * h).filter(|&s| flags[s]).map(d2).min().unwrap();
                let got = near[y * w + x];
                assert!(flags[got], "({x}, {y}) points at an unset pixel");
                assert_eq!(d2(got), best, "({x}, {y})");
            }
        }
        assert!(nearest_set_pixel(&vec![false; w * h], w, h)
            .iter()
            .all(|&s| s == usize::MAX));
    }
}
