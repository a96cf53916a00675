//! Small geometric kernels shared by the fields: closest point on a triangle, triangle solid
//! angle and point–box distance.

use nalgebra::Vector3;

type V3 = Vector3<f32>;

/// Which feature of a triangle holds the closest point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(crate) enum Feature {
    /// The interior of the face.
    Face,
    /// An edge: 0 = ab, 1 = bc, 2 = ca.
    Edge(u8),
    /// A corner: 0 = a, 1 = b, 2 = c.
    Vertex(u8),
}

/// Closest point to `p` on the segment `a`–`b` (handles `a == b`).
#[inline]
fn closest_on_segment(p: V3, a: V3, b: V3) -> V3 {
    let ab = b - a;
    let len2 = ab.norm_squared();
    if len2 <= 0.0 {
        return a;
    }
    let t = ((p - a).dot(&ab) / len2).clamp(0.0, 1.0);
    a + ab * t
}

/// Closest point to `p` on triangle `abc` and the feature holding it (Voronoi-region walk).
#[inline(always)]
pub(crate) fn closest_on_triangle(p: V3, a: V3, b: V3, c: V3) -> (V3, Feature) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(&ap);
    let d2 = ac.dot(&ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, Feature::Vertex(0));
    }
    let bp = p - b;
    let d3 = ab.dot(&bp);
    let d4 = ac.dot(&bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, Feature::Vertex(1));
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let den = d1 - d3;
        let v = if den > 0.0 { d1 / den } else { 0.0 };
        return (a + ab * v, Feature::Edge(0));
    }
    let cp = p - c;
    let d5 = ab.dot(&cp);
    let d6 = ac.dot(&cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, Feature::Vertex(2));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let den = d2 - d6;
        let w = if den > 0.0 { d2 / den } else { 0.0 };
        return (a + ac * w, Feature::Edge(2));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let den = (d4 - d3) + (d5 - d6);
        let w = if den > 0.0 { (d4 - d3) / den } else { 0.0 };
        return (b + (c - b) * w, Feature::Edge(1));
    }
    let sum = va + vb + vc;
    if sum > 0.0 && sum.is_finite() {
        let v = vb / sum;
        let w = vc / sum;
        return (a + ab * v + ac * w, Feature::Face);
    }
    // Degenerate (collinear) triangle: nearest of its three segments.
    let candidates = [
        (closest_on_segment(p, a, b), Feature::Edge(0)),
        (closest_on_segment(p, b, c), Feature::Edge(1)),
        (closest_on_segment(p, c, a), Feature::Edge(2)),
    ];
    let mut best = candidates[0];
    for cand in &candidates[1..] {
        if (cand.0 - p).norm_squared() < (best.0 - p).norm_squared() {
            best = *cand;
        }
    }
    best
}

/// Squared distance from `p` to triangle `abc`.
#[inline(always)]
pub(crate) fn distance2_to_triangle(p: V3, a: V3, b: V3, c: V3) -> f32 {
    (closest_on_triangle(p, a, b, c).0 - p).norm_squared()
}

/// Signed solid angle subtended by triangle `abc` seen from `p` (positive when `p` is behind
/// the counter-clockwise face, i.e. inside a closed outward-oriented surface).
#[inline]
pub(crate) fn solid_angle(p: V3, a: V3, b: V3, c: V3) -> f32 {
    let (a, b, c) = (a - p, b - p, c - p);
    let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
    let det = a.dot(&b.cross(&c));
    let den = la * lb * lc + a.dot(&b) * lc + a.dot(&c) * lb + b.dot(&c) * la;
    2.0 * det.atan2(den)
}

/// Squared distance from `p` to the box `[min, max]` (zero inside).
#[inline(always)]
pub(crate) fn distance2_to_box(p: &[f32; 3], min: &[f32; 3], max: &[f32; 3]) -> f32 {
    let mut d2 = 0.0;
    for i in 0..3 {
        let d = (min[i] - p[i]).max(p[i] - max[i]).max(0.0);
        d2 += d * d;
    }
    d2
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn closest_point_regions() {
        let a = V3::new(0.0, 0.0, 0.0);
        let b = V3::new(1.0, 0.0, 0.0);
        let c = V3::new(0.0, 1.0, 0.0);
        let (q, f) = closest_on_triangle(V3::new(0.25, 0.25, 2.0), a, b, c);
        assert_eq!(f, Feature::Face);
        assert!((q - V3::new(0.25, 0.25, 0.0)).norm() < 1e-6);
        let (q, f) = closest_on_triangle(V3::new(-1.0, -1.0, 0.0), a, b, c);
        assert_eq!((q, f), (a, Feature::Vertex(0)));
        let (q, f) = closest_on_triangle(V3::new(0.5, -1.0, 0.3), a, b, c);
        assert_eq!(f, Feature::Edge(0));
        assert!((q - V3::new(0.5, 0.0, 0.0)).norm() < 1e-6);
        let (q, f) = closest_on_triangle(V3::new(1.0, 1.0, 0.0), a, b, c);
        assert_eq!(f, Feature::Edge(1));
        assert!((q - V3::new(0.5, 0.5, 0.0)).norm() < 1e-6);
        // Degenerate triangle still gives the nearest point of its segment.
        let (q, _) = closest_on_triangle(V3::new(0.5, 1.0, 0.0), a, b, b);
        assert!((q - V3::new(0.5, 0.0, 0.0)).norm() < 1e-6);
    }

    #[test]
    fn solid_angle_of_octant_triangle() {
        // The triangle (1,0,0),(0,1,0),(0,0,1) covers one octant: 4π/8 from the origin.
        let o = V3::zeros();
        let w = solid_angle(o, V3::x(), V3::y(), V3::z());
        assert!((w - std::f32::consts::PI / 2.0).abs() < 1e-5, "{w}");
    }
}
