//! Phase 1: mask pixels with metric depth → world points of one object.
//!
//! Pixels whose depth is unknown (NaN, zero, negative) are skipped. Masks from a segmenter
//! bleed into the background at their borders; those pixels lie far behind the object in depth,
//! so the points are clustered on a voxel grid and only the largest connected cluster is kept.

use std::collections::{BTreeMap, BTreeSet, VecDeque};

use nalgebra::{Point2, Point3};
use scenethesis_correspondence::{DepthMap, Mask};
use scenethesis_scene_graph::Camera;

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
        out.push(camera.unproject(&pixel, d as f64));
    }
    out
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
    fn quantiles_and_median() {
        let mut v = vec![3.0, 1.0, 2.0, 4.0];
        assert_eq!(median(&mut v), Some(2.0));
        assert_eq!(quantile(&v, 1.0), 4.0);
        assert_eq!(quantile(&v, 0.0), 1.0);
    }
}
