//! Automatic support surfaces for meshes that come without them: upward, near-horizontal faces
//! grouped by height and connectivity, kept above a minimum area, with the free clearance above
//! measured by casting rays against the mesh.

use std::collections::BTreeMap;

use nalgebra::Vector3;
use scenethesis_scene_graph::Mesh;

use scenethesis_scene_graph::{SupportSurface, SurfaceKind};

/// Parameters of [`find_support_surfaces`].
#[derive(Debug, Clone, PartialEq)]
pub struct SurfaceSearch {
    /// Smallest usable surface area in m² (after shrinking by `margin`).
    pub min_area: f32,
    /// Largest tilt from horizontal of a face that still counts, in degrees.
    pub max_tilt_degrees: f32,
    /// Faces whose heights differ by at most this many metres belong to one surface.
    pub height_tolerance: f32,
    /// Inset of the polygon from the faces' outline, metres.
    pub margin: f32,
    /// A surface with less free height above it than this (metres) is dropped as unusable.
    pub min_clearance: f32,
    /// At most this many surfaces are kept (the largest).
    pub max_surfaces: usize,
}

impl Default for SurfaceSearch {
    fn default() -> Self {
        Self {
            min_area: 0.004,
            max_tilt_degrees: 10.0,
            height_tolerance: 0.01,
            margin: 0.01,
            min_clearance: 0.03,
            max_surfaces: 16,
        }
    }
}

type V = Vector3<f64>;

/// Finds the support surfaces of a normalised mesh (+Y up, metres): tops open above, shelves
/// with a clearance, and interiors of open containers (open above, walled around).
pub fn find_support_surfaces(mesh: &Mesh, search: &SurfaceSearch) -> Vec<SupportSurface> {
    let triangles: Vec<[V; 3]> = mesh
        .parts
        .iter()
        .flat_map(|p| {
            p.triangles
                .iter()
                .map(move |t| t.map(|i| Vector3::from(p.positions[i as usize]).cast::<f64>()))
        })
        .collect();
    let cos_tilt = (search.max_tilt_degrees as f64).to_radians().cos();
    // Upward faces: (height, area, triangle index).
    let mut up: Vec<(f64, f64, usize)> = triangles
        .iter()
        .enumerate()
        .filter_map(|(k, [a, b, c])| {
            let n = (b - a).cross(&(c - a));
            let len = n.norm();
            (len > 1e-12 && n.y / len >= cos_tilt).then(|| ((a.y + b.y + c.y) / 3.0, len / 2.0, k))
        })
        .collect();
    up.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.2.cmp(&b.2)));
    let mut found = Vec::new();
    let mut start = 0;
    while start < up.len() {
        let mut end = start + 1;
        while end < up.len() && up[end].0 - up[start].0 <= search.height_tolerance as f64 {
            end += 1;
        }
        for component in components(&up[start..end], &triangles) {
            if let Some(s) = surface(&component, &triangles, search) {
                found.push(s);
            }
        }
        start = end;
    }
    found.sort_by(|a, b| b.area().total_cmp(&a.area()));
    found.truncate(search.max_surfaces);
    found.sort_by(|a, b| {
        a.height
            .total_cmp(&b.height)
            .then(a.center()[0].total_cmp(&b.center()[0]))
    });
    let mut counts: BTreeMap<&'static str, usize> = BTreeMap::new();
    for s in &mut found {
        let kind = match s.kind {
            SurfaceKind::Top => "top",
            SurfaceKind::Shelf => "shelf",
            SurfaceKind::Interior => "interior",
            SurfaceKind::Under => "under",
        };
        let k = counts.entry(kind).or_default();
        s.name = format!("{kind}_{k}");
        *k += 1;
    }
    found
}

/// Splits faces of one height band into groups connected through shared vertex positions.
fn components(band: &[(f64, f64, usize)], triangles: &[[V; 3]]) -> Vec<Vec<(f64, f64, usize)>> {
    let mut parent: Vec<usize> = (0..band.len()).collect();
    fn find(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    let mut first_at: BTreeMap<(i64, i64), usize> = BTreeMap::new();
    for (j, &(_, _, k)) in band.iter().enumerate() {
        for v in &triangles[k] {
            let key = ((v.x * 1e4).round() as i64, (v.z * 1e4).round() as i64);
            match first_at.get(&key) {
                Some(&other) => {
                    let (ra, rb) = (find(&mut parent, j), find(&mut parent, other));
                    if ra != rb {
                        parent[ra.max(rb)] = ra.min(rb);
                    }
                }
                None => {
                    first_at.insert(key, j);
                }
            }
        }
    }
    let mut groups: BTreeMap<usize, Vec<(f64, f64, usize)>> = BTreeMap::new();
    for (j, item) in band.iter().enumerate() {
        let r = find(&mut parent, j);
        groups.entry(r).or_default().push(*item);
    }
    groups.into_values().collect()
}

/// Builds the surface of one connected group of upward faces, or `None` if it is too small or
/// covered too closely.
fn surface(
    group: &[(f64, f64, usize)],
    triangles: &[[V; 3]],
    search: &SurfaceSearch,
) -> Option<SupportSurface> {
    let area: f64 = group.iter().map(|g| g.1).sum();
    if area < search.min_area as f64 {
        return None;
    }
    let height = group.iter().map(|g| g.0 * g.1).sum::<f64>() / area;
    if height < 1e-3 {
        return None; // Faces on the ground plane are the floor, not the asset.
    }
    let points: Vec<[f64; 2]> = group
        .iter()
        .flat_map(|g| triangles[g.2].iter().map(|v| [v.x, v.z]))
        .collect();
    let hull = convex_hull_2d(&points);
    let polygon = inset(&hull, search.margin as f64)?;
    let poly_area = shoelace(&polygon).abs() / 2.0;
    if poly_area < search.min_area as f64 * 0.5 {
        return None;
    }
    let probe = probe(&polygon, height, triangles, search);
    if probe.free.is_empty() {
        return None;
    }
    let polygon = if probe.blocked == 0 {
        polygon
    } else {
        let hull = convex_hull_2d(&probe.free);
        if hull.len() < 3 || shoelace(&hull).abs() / 2.0 < search.min_area as f64 * 0.5 {
            return None;
        }
        hull
    };
    let kind = surface_kind(&polygon, height, probe.clearance, triangles);
    Some(SupportSurface {
        name: String::new(),
        kind,
        polygon: polygon.iter().map(|p| [p[0] as f32, p[1] as f32]).collect(),
        height: height as f32,
        clearance: probe.clearance.map(|c| (c + 1e-3) as f32),
    })
}

/// What probing a grid over a candidate surface found.
struct Probe {
    /// The free samples, (x, z).
    free: Vec<[f64; 2]>,
    /// How many samples were blocked.
    blocked: usize,
    /// The least free height above a free sample, when anything is above at all.
    clearance: Option<f64>,
}

/// The (x, z) bounding box of a polygon, as (min, max).
fn bounds_2d(polygon: &[[f64; 2]]) -> ([f64; 2], [f64; 2]) {
    polygon
        .iter()
        .fold(([f64::MAX; 2], [f64::MIN; 2]), |(lo, hi), p| {
            (
                [lo[0].min(p[0]), lo[1].min(p[1])],
                [hi[0].max(p[0]), hi[1].max(p[1])],
            )
        })
}

/// Probes a grid over the polygon at `height`: a sample is blocked when geometry stands on it
/// (a vertical ray hits within `min_clearance`) or hugs it (a wall within `wall_gap` sideways,
/// which also catches samples inside walls that overlap the floor). Free samples give the
/// clearance.
fn probe(polygon: &[[f64; 2]], height: f64, triangles: &[[V; 3]], search: &SurfaceSearch) -> Probe {
    let (lo, hi) = bounds_2d(polygon);
    // Only triangles reaching above the surface near its box can block it.
    let reach = 0.05;
    let nearby: Vec<[V; 3]> = triangles
        .iter()
        .filter(|t| {
            t.iter().any(|v| v.y > height + 1e-4)
                && t.iter().any(|v| v.x >= lo[0] - reach)
                && t.iter().any(|v| v.x <= hi[0] + reach)
                && t.iter().any(|v| v.z >= lo[1] - reach)
                && t.iter().any(|v| v.z <= hi[1] + reach)
        })
        .copied()
        .collect();
    let wall_gap = (search.margin as f64).max(0.015);
    let grid = 9;
    let mut free = Vec::new();
    let mut blocked = 0;
    let mut clearance: Option<f64> = None;
    for gx in 0..grid {
        for gz in 0..grid {
            let x = lo[0] + (hi[0] - lo[0]) * (gx as f64 + 0.5) / grid as f64;
            let z = lo[1] + (hi[1] - lo[1]) * (gz as f64 + 0.5) / grid as f64;
            if !inside(polygon, [x, z]) {
                continue;
            }
            let origin = V::new(x, height + 1e-3, z);
            let above = cast(&origin, &V::y(), &nearby);
            let side = V::new(x, height + 5e-3, z);
            let hugged = [V::x(), -V::x(), V::z(), -V::z()]
                .iter()
                .any(|d| cast(&side, d, &nearby).is_some_and(|t| t < wall_gap));
            if hugged || above.is_some_and(|t| t < search.min_clearance as f64) {
                blocked += 1;
                continue;
            }
            if let Some(t) = above {
                clearance = Some(clearance.map_or(t, |c: f64| c.min(t)));
            }
            free.push([x, z]);
        }
    }
    Probe {
        free,
        blocked,
        clearance,
    }
}

/// A shelf when something is above it; else an interior when walls stand on all four sides of
/// its centroid just above it (an open container), else a top.
fn surface_kind(
    polygon: &[[f64; 2]],
    height: f64,
    clearance: Option<f64>,
    triangles: &[[V; 3]],
) -> SurfaceKind {
    let centroid = polygon
        .iter()
        .fold([0.0, 0.0], |c, p| [c[0] + p[0], c[1] + p[1]])
        .map(|c| c / polygon.len() as f64);
    match clearance {
        Some(_) => SurfaceKind::Shelf,
        None => {
            let origin = V::new(centroid[0], height + 0.02, centroid[1]);
            let walled = [V::x(), -V::x(), V::z(), -V::z()]
                .iter()
                .all(|d| cast(&origin, d, triangles).is_some());
            if walled {
                SurfaceKind::Interior
            } else {
                SurfaceKind::Top
            }
        }
    }
}

/// Whether an (x, z) point lies inside a convex polygon (either winding) or on its border.
fn inside(poly: &[[f64; 2]], p: [f64; 2]) -> bool {
    let n = poly.len();
    let mut sign = 0.0f64;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let c = (b[0] - a[0]) * (p[1] - a[1]) - (b[1] - a[1]) * (p[0] - a[0]);
        if c.abs() > 1e-12 {
            if sign != 0.0 && c.signum() != sign {
                return false;
            }
            sign = c.signum();
        }
    }
    true
}

/// Distance along `dir` from `origin` to the nearest triangle hit (either side), if any.
fn cast(origin: &V, dir: &V, triangles: &[[V; 3]]) -> Option<f64> {
    let mut best: Option<f64> = None;
    for [a, b, c] in triangles {
        let (e1, e2) = (b - a, c - a);
        let p = dir.cross(&e2);
        let det = e1.dot(&p);
        if det.abs() < 1e-14 {
            continue;
        }
        let inv = 1.0 / det;
        let s = origin - a;
        let u = s.dot(&p) * inv;
        if !(0.0..=1.0).contains(&u) {
            continue;
        }
        let q = s.cross(&e1);
        let v = dir.dot(&q) * inv;
        if v < 0.0 || u + v > 1.0 {
            continue;
        }
        let t = e2.dot(&q) * inv;
        if t > 1e-6 && best.is_none_or(|b| t < b) {
            best = Some(t);
        }
    }
    best
}

/// Convex hull of (x, z) points, counter-clockwise seen from above (+Y toward the viewer).
fn convex_hull_2d(points: &[[f64; 2]]) -> Vec<[f64; 2]> {
    let mut pts = points.to_vec();
    pts.sort_by(|a, b| a[0].total_cmp(&b[0]).then(a[1].total_cmp(&b[1])));
    pts.dedup_by(|a, b| (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9);
    if pts.len() < 3 {
        return pts;
    }
    let cross = |o: [f64; 2], a: [f64; 2], b: [f64; 2]| {
        (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
    };
    let mut hull: Vec<[f64; 2]> = Vec::new();
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &[f64; 2]>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 1e-12
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    // Monotone chain gives positive (x, z) orientation; counter-clockwise seen from +Y is the
    // opposite.
    hull.reverse();
    hull
}

/// Twice the signed area in (x, z).
fn shoelace(poly: &[[f64; 2]]) -> f64 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum()
}

/// Moves every edge of a convex polygon inward by `d` (the intersection of the shifted
/// half-planes, so short edges vanish cleanly), or `None` if nothing is left.
fn inset(poly: &[[f64; 2]], d: f64) -> Option<Vec<[f64; 2]>> {
    let n = poly.len();
    if n < 3 {
        return None;
    }
    // Inward normal for a polygon with negative (x, z) orientation.
    let sign = if shoelace(poly) < 0.0 { 1.0 } else { -1.0 };
    let mut out = poly.to_vec();
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let e = [b[0] - a[0], b[1] - a[1]];
        let len = (e[0] * e[0] + e[1] * e[1]).sqrt();
        if len < 1e-12 {
            continue;
        }
        let inward = [sign * e[1] / len, -sign * e[0] / len];
        let side = |p: [f64; 2]| (p[0] - a[0]) * inward[0] + (p[1] - a[1]) * inward[1] - d;
        let mut clipped = Vec::with_capacity(out.len() + 1);
        for k in 0..out.len() {
            let (p, q) = (out[k], out[(k + 1) % out.len()]);
            let (sp, sq) = (side(p), side(q));
            if sp >= 0.0 {
                clipped.push(p);
            }
            if (sp >= 0.0) != (sq >= 0.0) {
                let t = sp / (sp - sq);
                clipped.push([p[0] + (q[0] - p[0]) * t, p[1] + (q[1] - p[1]) * t]);
            }
        }
        out = clipped;
        if out.len() < 3 {
            return None;
        }
    }
    (shoelace(&out).abs() > 1e-12).then_some(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_primitives::cuboid;
    use scenethesis_scene_graph::Material;

    fn mesh(parts: Vec<scenethesis_scene_graph::MeshPart>) -> Mesh {
        Mesh {
            parts,
            materials: vec![Material::new("m", [0.5; 3], 0.5)],
        }
    }

    #[test]
    fn table_top_is_an_open_top_at_the_right_height() {
        let mut parts = vec![cuboid("top", 0, [-0.6, 0.72, -0.4], [0.6, 0.75, 0.4])];
        for (i, (x, z)) in [(-0.55, -0.35), (0.55, -0.35), (-0.55, 0.35), (0.55, 0.35)]
            .iter()
            .enumerate()
        {
            parts.push(cuboid(
                &format!("leg{i}"),
                0,
                [x - 0.02, 0.0, z - 0.02],
                [x + 0.02, 0.72, z + 0.02],
            ));
        }
        let surfaces = find_support_surfaces(&mesh(parts), &SurfaceSearch::default());
        assert_eq!(surfaces.len(), 1, "{surfaces:?}");
        let s = &surfaces[0];
        assert_eq!(s.kind, SurfaceKind::Top);
        assert!((s.height - 0.75).abs() < 1e-5);
        assert!(s.clearance.is_none());
        assert!((s.area() - 1.18 * 0.78).abs() < 1e-3, "area {}", s.area());
        assert!(s.contains(0.0, 0.0) && !s.contains(0.7, 0.0));
    }

    #[test]
    fn shelves_get_clearance_and_open_boxes_get_interiors() {
        // Two boards 0.4 m apart: the lower one is a shelf with 0.4 m clearance (minus board).
        let shelf = mesh(vec![
            cuboid("low", 0, [-0.4, 0.3, -0.15], [0.4, 0.32, 0.15]),
            cuboid("high", 0, [-0.4, 0.72, -0.15], [0.4, 0.74, 0.15]),
            cuboid("side", 0, [-0.42, 0.0, -0.15], [-0.4, 0.74, 0.15]),
        ]);
        let s = find_support_surfaces(&shelf, &SurfaceSearch::default());
        let low = s
            .iter()
            .find(|s| (s.height - 0.32).abs() < 1e-4)
            .expect("lower board");
        assert_eq!(low.kind, SurfaceKind::Shelf);
        assert!(
            (low.clearance.unwrap() - 0.4).abs() < 0.005,
            "{:?}",
            low.clearance
        );
        let high = s
            .iter()
            .find(|s| (s.height - 0.74).abs() < 1e-4)
            .expect("upper board");
        assert_eq!(high.kind, SurfaceKind::Top);
        // An open box: floor and four 3 cm walls standing through it.
        let open = mesh(vec![
            cuboid("floor", 0, [-0.2, 0.0, -0.2], [0.2, 0.02, 0.2]),
            cuboid("w0", 0, [-0.2, 0.0, -0.2], [0.2, 0.3, -0.17]),
            cuboid("w1", 0, [-0.2, 0.0, 0.17], [0.2, 0.3, 0.2]),
            cuboid("w2", 0, [-0.2, 0.0, -0.2], [-0.17, 0.3, 0.2]),
            cuboid("w3", 0, [0.17, 0.0, -0.2], [0.2, 0.3, 0.2]),
        ]);
        let s = find_support_surfaces(&open, &SurfaceSearch::default());
        let floor = s
            .iter()
            .find(|s| (s.height - 0.02).abs() < 1e-4)
            .expect("inner floor");
        assert_eq!(floor.kind, SurfaceKind::Interior);
        assert!(floor.clearance.is_none());
        assert!(
            floor
                .polygon
                .iter()
                .all(|p| p[0].abs() < 0.17 && p[1].abs() < 0.17),
            "the interior stops at the walls: {:?}",
            floor.polygon
        );
        assert!(
            floor.area() > 0.5 * 0.34 * 0.34 * 0.5,
            "area {}",
            floor.area()
        );
    }

    #[test]
    fn inset_shrinks_a_square_evenly() {
        let sq = convex_hull_2d(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0], [0.5, 0.5]]);
        assert_eq!(sq.len(), 4);
        assert!(shoelace(&sq) < 0.0, "counter-clockwise seen from above");
        let inner = inset(&sq, 0.1).unwrap();
        assert!((shoelace(&inner).abs() / 2.0 - 0.64).abs() < 1e-9);
        assert!(inset(&sq, 0.6).is_none());
    }
}
