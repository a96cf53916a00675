//! Phase 1: mask pixels with metric depth → world points of one object.
//!
//! Pixels whose depth is unknown (NaN, zero, negative) are skipped. Masks from a segmenter
//! bleed into the background at their borders; those pixels lie far behind the object in depth,
//! so the points are clustered on a voxel grid and only the largest connected cluster is kept.

use std::collections::{BTreeMap, BTreeSet, VecDeque};

use nalgebra::{Point2, Point3};
use scenethesis_imagery::{Camera, DepthMap, Mask};

/// The world points seen through `mask`, one per pixel with a valid depth, in row order.
///
/// `stride` subsamples rows and columns (1 = every pixel) to bound the work for large masks.
/// `radius` > 0 replaces each depth by the median of the valid depths of the mask's pixels
/// within that many pixels (a square window), which suppresses per-pixel depth noise without
/// mixing in other objects.
pub fn mask_points(
    camera: &Camera,
    depth: &DepthMap,
    mask: &Mask,
    stride: u32,
    radius: u32,
) -> Vec<Point3<f64>> {
    mask_pixel_points(camera, depth, mask, stride, radius)
        .into_iter()
        .map(|(_, p)| p)
        .collect()
}

/// [`mask_points`] with the pixel `(u, v)` each point was lifted from.
pub fn mask_pixel_points(
    camera: &Camera,
    depth: &DepthMap,
    mask: &Mask,
    stride: u32,
    radius: u32,
) -> Vec<([u32; 2], Point3<f64>)> {
    let stride = stride.max(1);
    let mut out = Vec::new();
    for (u, v) in mask.pixels() {
        if u % stride != 0 || v % stride != 0 {
            continue;
        }
        let valid = |x: u32, y: u32| {
            depth
                .get(x, y)
                .filter(|d| d.is_finite() && *d > 0.0 && mask.contains(x, y))
        };
        let d = if radius == 0 {
            match valid(u, v) {
                Some(d) => d,
                None => continue,
            }
        } else {
            let mut window: Vec<f64> =
                Vec::with_capacity(((2 * radius + 1) * (2 * radius + 1)) as usize);
            for y in v.saturating_sub(radius)..=(v + radius).min(mask.height() - 1) {
                for x in u.saturating_sub(radius)..=(u + radius).min(mask.width() - 1) {
                    if let Some(d) = valid(x, y) {
                        window.push(d as f64);
                    }
                }
            }
            match median(&mut window) {
                Some(d) => d as f32,
                None => continue,
            }
        };
        let pixel = Point2::new(u as f64 + 0.5, v as f64 + 0.5);
        out.push(([u, v], camera.unproject(&pixel, d as f64)));
    }
    out
}

/// How far the surface seen at the top and at the bottom of a point set's silhouette continues
/// in height over `margin` more pixel rows: the height change per row between the band of the
/// first `margin + 1` rows and the next band, extrapolated over `margin` rows (never negative).
/// A top face seen from above gains nothing, a vertical face about `margin` pixels' worth of
/// height. Returns `(below, above)` in metres.
pub fn vertical_margins(points: &[([u32; 2], Point3<f64>)], margin: u32) -> (f64, f64) {
    if points.is_empty() || margin == 0 {
        return (0.0, 0.0);
    }
    let band = margin + 1;
    let (v0, v1) = points.iter().fold((u32::MAX, 0), |(a, b), (px, _)| {
        (a.min(px[1]), b.max(px[1]))
    });
    let band_y = |from: i64, to: i64| {
        let mut ys: Vec<f64> = points
            .iter()
            .filter(|(px, _)| (from..=to).contains(&(px[1] as i64)))
            .map(|(_, p)| p.y)
            .collect();
        median(&mut ys)
    };
    let per_row = |a: Option<f64>, b: Option<f64>| match (a, b) {
        (Some(a), Some(b)) => ((a - b) / band as f64).max(0.0),
        _ => 0.0,
    };
    let (t, b) = (v0 as i64, v1 as i64);
    let band = band as i64;
    let above = per_row(band_y(t, t + band - 1), band_y(t + band, t + 2 * band - 1));
    let below = per_row(band_y(b - 2 * band + 1, b - band), band_y(b - band + 1, b));
    (below * margin as f64, above * margin as f64)
}

/// The pixels of `mask` at least `radius` pixels (in the chessboard metric) inside it: the
/// mask eroded by a `(2 radius + 1)²` square. Pixels near the image border count as inside
/// when their in-image neighbours are.
pub fn interior(mask: &Mask, radius: u32) -> Mask {
    let (w, h) = (mask.width(), mask.height());
    if radius == 0 {
        return mask.clone();
    }
    // Separable erosion: rows first, then columns.
    let r = radius as i64;
    let run = |len: u32, get: &dyn Fn(u32) -> bool| -> Vec<bool> {
        (0..len as i64)
            .map(|i| ((i - r).max(0)..=(i + r).min(len as i64 - 1)).all(|j| get(j as u32)))
            .collect()
    };
    let mut rows = vec![false; (w * h) as usize];
    for y in 0..h {
        let line = run(w, &|x| mask.contains(x, y));
        rows[(y * w) as usize..((y + 1) * w) as usize].copy_from_slice(&line);
    }
    let mut out = Mask::new(w, h);
    for x in 0..w {
        let line = run(h, &|y| rows[(y * w + x) as usize]);
        for (y, &inside) in line.iter().enumerate() {
            if inside {
                out.set(x, y as u32, true);
            }
        }
    }
    out
}

/// The relative per-pixel noise of a depth map: the robust standard deviation (1.4826 × the
/// median absolute value) of each pixel's relative difference from the median of its valid
/// 8-neighbours, over every pixel whose neighbours are all valid. A smooth surface, tilted or
/// not, gives 0 (its depth is locally linear and the median of a symmetric neighbourhood is the
/// centre's); independent Gaussian noise of σ gives about σ. Depth edges are a minority of
/// pixels and fall outside the median. `None` when no pixel qualifies.
pub fn depth_noise(depth: &DepthMap) -> Option<f64> {
    let (w, h) = (depth.width(), depth.height());
    let valid = |u: u32, v: u32| depth.get(u, v).filter(|d| d.is_finite() && *d > 0.0);
    let mut residuals = Vec::new();
    let mut ring = Vec::with_capacity(8);
    for v in 1..h.saturating_sub(1) {
        'pixel: for u in 1..w.saturating_sub(1) {
            let Some(c) = valid(u, v) else { continue };
            ring.clear();
            for (du, dv) in [
                (-1, -1),
                (0, -1),
                (1, -1),
                (-1, 0),
                (1, 0),
                (-1, 1),
                (0, 1),
                (1, 1),
            ] {
                match valid((u as i64 + du) as u32, (v as i64 + dv) as u32) {
                    Some(d) => ring.push(d as f64),
                    None => continue 'pixel,
                }
            }
            ring.sort_by(|a, b| a.total_cmp(b));
            let m = (ring[3] + ring[4]) / 2.0;
            residuals.push(((c as f64 - m) / m).abs());
        }
    }
    // The residual of a pixel against the median of 8 noisy neighbours has a standard deviation
    // of about 1.1 σ.
    median(&mut residuals).map(|mad| 1.4826 * mad / 1.1)
}

/// The largest 26-connected cluster of `points` on a voxel grid of edge `voxel` metres
/// (ties broken by the lowest voxel, so the result is deterministic). Returns the kept points
/// in their input order.
pub fn largest_cluster(points: &[Point3<f64>], voxel: f64) -> Vec<Point3<f64>> {
    if points.len() < 2 || voxel.is_nan() || voxel <= 0.0 {
        return points.to_vec();
    }
    let key = |p: &Point3<f64>| -> [i64; 3] {
        [
            (p.x / voxel).floor() as i64,
            (p.y / voxel).floor() as i64,
            (p.z / voxel).floor() as i64,
        ]
    };
    let mut cells: BTreeMap<[i64; 3], usize> = BTreeMap::new();
    for p in points {
        *cells.entry(key(p)).or_default() += 1;
    }
    let mut label: BTreeMap<[i64; 3], usize> = BTreeMap::new();
    let mut sizes: Vec<usize> = Vec::new();
    for &start in cells.keys() {
        if label.contains_key(&start) {
            continue;
        }
        let id = sizes.len();
        let mut count = 0;
        let mut queue = VecDeque::from([start]);
        label.insert(start, id);
        while let Some(c) = queue.pop_front() {
            count += cells[&c];
            for dx in -1..=1 {
                for dy in -1..=1 {
                    for dz in -1..=1 {
                        let n = [c[0] + dx, c[1] + dy, c[2] + dz];
                        if cells.contains_key(&n) && !label.contains_key(&n) {
                            label.insert(n, id);
                            queue.push_back(n);
                        }
                    }
                }
            }
        }
        sizes.push(count);
    }
    // First label with the maximum size: labels are assigned in voxel order.
    let best = (0..sizes.len()).fold(0, |b, i| if sizes[i] > sizes[b] { i } else { b });
    let keep: BTreeSet<[i64; 3]> = label
        .iter()
        .filter(|(_, &l)| l == best)
        .map(|(k, _)| *k)
        .collect();
    points
        .iter()
        .copied()
        .filter(|p| keep.contains(&key(p)))
        .collect()
}

/// The median of `values` (the lower middle for an even count); `None` when empty.
pub(crate) fn median(values: &mut [f64]) -> Option<f64> {
    if values.is_empty() {
        return None;
    }
    values.sort_by(|a, b| a.total_cmp(b));
    Some(values[(values.len() - 1) / 2])
}

/// The value below which a fraction `q` (0–1) of `sorted` lies (nearest rank).
pub(crate) fn quantile(sorted: &[f64], q: f64) -> f64 {
    let i = ((sorted.len() - 1) as f64 * q.clamp(0.0, 1.0)).round() as usize;
    sorted[i]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn far_bleed_is_dropped() {
        let mut pts: Vec<Point3<f64>> = (0..100)
            .map(|i| Point3::new((i % 10) as f64 * 0.02, 0.5, (i / 10) as f64 * 0.02))
            .collect();
        pts.extend((0..20).map(|i| Point3::new(i as f64 * 0.02, 0.0, 3.0)));
        let kept = largest_cluster(&pts, 0.05);
        assert_eq!(kept.len(), 100);
        assert!(kept.iter().all(|p| p.z < 1.0));
    }

    #[test]
    fn depth_noise_measures_gaussian_noise_and_ignores_tilt() {
        // A tilted plane: depth linear in u and v.
        let plane = DepthMap::from_fn(80, 60, |u, v| 2.0 + 0.01 * u as f32 + 0.03 * v as f32);
        assert!(depth_noise(&plane).unwrap() < 1e-4);
        // The same plane with 2 % Gaussian noise (Box–Muller from a fixed LCG).
        let mut state = 12345u64;
        let mut uniform = move || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((state >> 11) as f64 / (1u64 << 53) as f64).max(1e-12)
        };
        let noisy = DepthMap::from_fn(80, 60, |u, v| {
            let g = (-2.0 * uniform().ln()).sqrt() * (std::f64::consts::TAU * uniform()).cos();
            ((2.0 + 0.01 * u as f64 + 0.03 * v as f64) * (1.0 + 0.02 * g)) as f32
        });
        let sigma = depth_noise(&noisy).unwrap();
        assert!((0.016..0.024).contains(&sigma), "estimated {sigma}");
    }

    #[test]
    fn interior_erodes_by_the_radius() {
        let mut m = Mask::new(20, 20);
        for y in 5..15 {
            for x in 3..15 {
                m.set(x, y, true);
            }
        }
        let inner = interior(&m, 2);
        assert_eq!(inner.area(), 8 * 6);
        assert!(inner.contains(5, 7) && !inner.contains(4, 7) && !inner.contains(5, 6));
        assert_eq!(interior(&m, 0), m);
    }

    #[test]
    fn quantiles_and_median() {
        let mut v = vec![3.0, 1.0, 2.0, 4.0];
        assert_eq!(median(&mut v), Some(2.0));
        assert_eq!(quantile(&v, 1.0), 4.0);
        assert_eq!(quantile(&v, 0.0), 1.0);
    }
}
