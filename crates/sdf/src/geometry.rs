//! Small geometric kernels shared by the fields: closest point on a triangle, squared distances
//! to four triangles at once ([`TriPacket`]), triangle solid angle and point–box distance.

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

/// Squared distance from `p` to triangle `abc` (the reference for [`TriPacket::distances2`]).
#[cfg(test)]
fn distance2_to_triangle(p: V3, a: V3, b: V3, c: V3) -> f32 {
    (closest_on_triangle(p, a, b, c).0 - p).norm_squared()
}

/// Four `f32` lanes with element-wise arithmetic written so the compiler turns it into SIMD
/// instructions (plain Rust, no intrinsics).
#[derive(Debug, Clone, Copy, PartialEq)]
#[repr(C, align(16))]
pub(crate) struct F4(pub [f32; 4]);

macro_rules! lanes {
    ($f:expr) => {
        F4([$f(0), $f(1), $f(2), $f(3)])
    };
}

impl F4 {
    #[inline(always)]
    pub fn splat(x: f32) -> F4 {
        F4([x; 4])
    }
    /// Lane-wise minimum (`minps` semantics: NaN-free inputs assumed).
    #[inline(always)]
    pub fn min(self, o: F4) -> F4 {
        lanes!(|i: usize| if self.0[i] < o.0[i] {
            self.0[i]
        } else {
            o.0[i]
        })
    }
    /// Lane-wise maximum.
    #[inline(always)]
    pub fn max(self, o: F4) -> F4 {
        lanes!(|i: usize| if self.0[i] > o.0[i] {
            self.0[i]
        } else {
            o.0[i]
        })
    }
    /// `if self >= 0 { a } else { b }` per lane.
    #[inline(always)]
    pub fn select_nonnegative(self, a: F4, b: F4) -> F4 {
        lanes!(|i: usize| if self.0[i] >= 0.0 { a.0[i] } else { b.0[i] })
    }
    /// Smallest lane.
    #[inline(always)]
    pub fn min_lane(self) -> f32 {
        let a = self.0[0].min(self.0[1]);
        let b = self.0[2].min(self.0[3]);
        a.min(b)
    }
}

impl std::ops::Add for F4 {
    type Output = F4;
    #[inline(always)]
    fn add(self, o: F4) -> F4 {
        lanes!(|i: usize| self.0[i] + o.0[i])
    }
}

impl std::ops::Sub for F4 {
    type Output = F4;
    #[inline(always)]
    fn sub(self, o: F4) -> F4 {
        lanes!(|i: usize| self.0[i] - o.0[i])
    }
}

impl std::ops::Mul for F4 {
    type Output = F4;
    #[inline(always)]
    fn mul(self, o: F4) -> F4 {
        lanes!(|i: usize| self.0[i] * o.0[i])
    }
}

/// Dot product of two lane-wise 3-vectors.
#[inline(always)]
fn dot4(a: &[F4; 3], b: &[F4; 3]) -> F4 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Four triangles side by side (structure of arrays), laid out for a branch-free squared
/// distance from one point to all four at once: corners, edge vectors with their inverse squared
/// lengths, inward in-plane edge normals and unit face normals. Unused lanes hold a far-away
/// dummy whose distance is infinite.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub(crate) struct TriPacket {
    /// Corner `k` of each triangle: `corner[k][axis]`.
    corner: [[F4; 3]; 3],
    /// Edge `k` (from corner `k` to corner `k + 1`).
    edge: [[F4; 3]; 3],
    /// `1 / |edge k|²` (0 for a zero-length edge).
    inv_len2: [F4; 3],
    /// In-plane normal of edge `k` pointing into the triangle (`n × edge`).
    inward: [[F4; 3]; 3],
    /// Unit face normal.
    normal: [F4; 3],
    /// Subtracted from the first edge's inside test: 0, or 1 for degenerate lanes (whose
    /// inward normals are zero), so their projection never counts as inside.
    bias: F4,
}

impl TriPacket {
    /// Packs up to four triangles (`tris.len() <= 4`).
    pub fn new(tris: &[[V3; 3]]) -> Self {
        debug_assert!(tris.len() <= 4);
        let zero = [F4::splat(0.0); 3];
        let mut packet = TriPacket {
            corner: [[F4::splat(f32::MAX); 3]; 3],
            edge: [zero; 3],
            inv_len2: zero,
            inward: [zero; 3],
            normal: zero,
            bias: F4::splat(1.0),
        };
        for (lane, t) in tris.iter().enumerate() {
            let n = (t[1] - t[0]).cross(&(t[2] - t[0]));
            let unit = n
                .try_normalize(0.0)
                .filter(|u| u.iter().all(|c| c.is_finite()));
            for k in 0..3 {
                let e = t[(k + 1) % 3] - t[k];
                let len2 = e.norm_squared();
                packet.inv_len2[k].0[lane] = if len2 > 0.0 { 1.0 / len2 } else { 0.0 };
                let m = unit.map_or_else(V3::zeros, |u| u.cross(&e));
                for axis in 0..3 {
                    packet.corner[k][axis].0[lane] = t[k][axis];
                    packet.edge[k][axis].0[lane] = e[axis];
                    packet.inward[k][axis].0[lane] = m[axis];
                }
            }
            let u = unit.unwrap_or_else(V3::zeros);
            for axis in 0..3 {
                packet.normal[axis].0[lane] = u[axis];
            }
            packet.bias.0[lane] = if unit.is_some() { 0.0 } else { 1.0 };
        }
        packet
    }

    /// The corners of the triangle in `lane`, exactly as packed.
    #[inline]
    pub fn triangle(&self, lane: usize) -> [V3; 3] {
        std::array::from_fn(|k| {
            V3::new(
                self.corner[k][0].0[lane],
                self.corner[k][1].0[lane],
                self.corner[k][2].0[lane],
            )
        })
    }

    /// The unit face normal of the triangle in `lane` (zero if it is degenerate).
    #[inline]
    pub fn face_normal(&self, lane: usize) -> V3 {
        V3::new(
            self.normal[0].0[lane],
            self.normal[1].0[lane],
            self.normal[2].0[lane],
        )
    }

    /// Squared distances from `p` to the four triangles: the squared distance to the plane when
    /// the projection of `p` falls inside the triangle, else to the nearest of its three edges.
    #[inline(always)]
    pub fn distances2(&self, p: &[F4; 3]) -> F4 {
        let zero = F4::splat(0.0);
        let one = F4::splat(1.0);
        let mut edge_d2 = F4::splat(f32::INFINITY);
        let mut side = zero - self.bias;
        let mut plane = zero;
        for k in 0..3 {
            let c = &self.corner[k];
            let e = &self.edge[k];
            let w = [p[0] - c[0], p[1] - c[1], p[2] - c[2]];
            let t = (dot4(&w, e) * self.inv_len2[k]).max(zero).min(one);
            let d = [w[0] - t * e[0], w[1] - t * e[1], w[2] - t * e[2]];
            edge_d2 = edge_d2.min(dot4(&d, &d));
            side = side.min(dot4(&w, &self.inward[k]));
            if k == 0 {
                plane = dot4(&w, &self.normal);
            }
        }
        side.select_nonnegative(plane * plane, edge_d2)
    }
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
    fn packet_distances_match_the_voronoi_walk() {
        let tris = [
            [
                V3::new(0.0, 0.0, 0.0),
                V3::new(1.0, 0.0, 0.0),
                V3::new(0.0, 1.0, 0.0),
            ],
            [
                V3::new(0.2, -0.3, 0.5),
                V3::new(-0.4, 0.9, 0.1),
                V3::new(0.7, 0.6, -0.8),
            ],
            // Degenerate: collinear corners and a repeated corner.
            [
                V3::new(0.0, 0.0, 0.0),
                V3::new(1.0, 1.0, 1.0),
                V3::new(2.0, 2.0, 2.0),
            ],
        ];
        let packet = TriPacket::new(&tris);
        let probes = [
            V3::new(0.25, 0.25, 2.0),
            V3::new(-1.0, -1.0, 0.0),
            V3::new(0.5, -1.0, 0.3),
            V3::new(1.0, 1.0, 0.0),
            V3::new(0.3, 0.4, -0.2),
            V3::new(3.0, -2.0, 1.5),
            V3::new(1.5, 1.4, 1.6),
        ];
        for p in probes {
            let d = packet
                .distances2(&[F4::splat(p.x), F4::splat(p.y), F4::splat(p.z)])
                .0;
            for (lane, t) in tris.iter().enumerate() {
                let expected = distance2_to_triangle(p, t[0], t[1], t[2]);
                assert!(
                    (d[lane] - expected).abs() <= 1e-5 * (1.0 + expected),
                    "{p:?} lane {lane}: {} vs {expected}",
                    d[lane]
                );
            }
            assert_eq!(d[3], f32::INFINITY, "the unused lane is never nearest");
        }
    }

    #[test]
    fn solid_angle_of_octant_triangle() {
        // The triangle (1,0,0),(0,1,0),(0,0,1) covers one octant: 4π/8 from the origin.
        let o = V3::zeros();
        let w = solid_angle(o, V3::x(), V3::y(), V3::z());
        assert!((w - std::f32::consts::PI / 2.0).abs() < 1e-5, "{w}");
    }
}
