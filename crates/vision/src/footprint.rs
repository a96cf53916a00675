//! Phase 3: the floor footprint of a point set as a minimum-area rectangle.
//!
//! Points are projected onto the floor plane (x, z). The rectangle's orientation comes from the
//! convex hull (rotating calipers: the minimum-area rectangle has a side on a hull edge); its
//! extents are then taken between robust quantiles along its axes so that a few stray points do
//! not stretch it.

use nalgebra::{Point2, Vector2};
use scenethesis_scene_graph::convex_hull;

use crate::points::quantile;

/// A rectangle on the floor: centre `(x, z)`, half extents along its own x and z axes, and the
/// yaw about +Y that turns its own axes into the world's (positive turns +Z toward +X).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FloorRectangle {
    /// Centre on the floor, as world `(x, z)`.
    pub center: Point2<f64>,
    /// Half extents along the rectangle's own x and z axes, in metres.
    pub half_extents: Vector2<f64>,
    /// Yaw in radians, in `[-π/4, π/4)`: a rectangle has four equivalent yaws; the prior-aware
    /// completion in [`crate::boxes`] picks among them.
    pub yaw: f64,
}

impl FloorRectangle {
    /// The rectangle's own x axis (world x, z), unit length.
    pub fn axis_x(&self) -> Vector2<f64> {
        Vector2::new(self.yaw.cos(), -self.yaw.sin())
    }

    /// The rectangle's own z axis (world x, z), unit length: its front for yaw 0.
    pub fn axis_z(&self) -> Vector2<f64> {
        Vector2::new(self.yaw.sin(), self.yaw.cos())
    }

    /// Whether the world floor point `(x, z)` lies inside, with `margin` metres of slack.
    pub fn contains(&self, p: &Point2<f64>, margin: f64) -> bool {
        let d = p - self.center;
        d.dot(&self.axis_x()).abs() <= self.half_extents.x + margin
            && d.dot(&self.axis_z()).abs() <= self.half_extents.y + margin
    }

    /// The rectangle's area in square metres.
    pub fn area(&self) -> f64 {
        4.0 * self.half_extents.x * self.half_extents.y
    }

    /// The four corners (world `(x, z)`), counter-clockwise seen from above (+Y).
    pub fn corners(&self) -> [Point2<f64>; 4] {
        let (ax, az) = (
            self.axis_x() * self.half_extents.x,
            self.axis_z() * self.half_extents.y,
        );
        let c = self.center;
        [c - ax - az, c + ax - az, c + ax + az, c - ax + az]
    }

    /// The area of the intersection with `other`, exact (convex polygon clipping).
    pub fn intersection_area(&self, other: &FloorRectangle) -> f64 {
        let mut poly: Vec<Point2<f64>> = self.corners().to_vec();
        let clip = oriented(other.corners());
        for i in 0..4 {
            let (a, b) = (clip[i], clip[(i + 1) % 4]);
            let inside = |p: &Point2<f64>| (b - a).perp(&(p - a)) >= 0.0;
            let mut next = Vec::with_capacity(poly.len() + 4);
            for j in 0..poly.len() {
                let (p, q) = (poly[j], poly[(j + 1) % poly.len()]);
                let (pin, qin) = (inside(&p), inside(&q));
                if pin {
                    next.push(p);
                }
                if pin != qin {
                    let (dp, dq) = ((b - a).perp(&(p - a)), (b - a).perp(&(q - a)));
                    let t = dp / (dp - dq);
                    next.push(p + (q - p) * t);
                }
            }
            poly = next;
            if poly.is_empty() {
                return 0.0;
            }
        }
        polygon_area(&poly).abs()
    }

    /// The fraction of this rectangle's area that lies inside `other`, estimated on a 9 × 9 grid
    /// of sample points.
    pub fn fraction_inside(&self, other: &FloorRectangle, margin: f64) -> f64 {
        const N: usize = 9;
        let (ax, az) = (self.axis_x(), self.axis_z());
        let mut inside = 0;
        for i in 0..N {
            for j in 0..N {
                let s = (i as f64 + 0.5) / N as f64 * 2.0 - 1.0;
                let t = (j as f64 + 0.5) / N as f64 * 2.0 - 1.0;
                let p =
                    self.center + ax * (s * self.half_extents.x) + az * (t * self.half_extents.y);
                inside += other.contains(&p, margin) as usize;
            }
        }
        inside as f64 / (N * N) as f64
    }
}

/// The corners in counter-clockwise order for the (x, z) plane's orientation used by `perp`.
fn oriented(c: [Point2<f64>; 4]) -> [Point2<f64>; 4] {
    if polygon_area(&c) < 0.0 {
        [c[3], c[2], c[1], c[0]]
    } else {
        c
    }
}

/// Signed shoelace area of a polygon.
fn polygon_area(p: &[Point2<f64>]) -> f64 {
    (0..p.len())
        .map(|i| p[i].coords.perp(&p[(i + 1) % p.len()].coords))
        .sum::<f64>()
        / 2.0
}

/// The minimum-area floor rectangle around `points` (world `(x, z)` pairs), with its extents
/// taken between the `trim` and `1 − trim` quantiles along its axes (`trim` = 0 keeps every
/// point). `None` for an empty input.
pub fn min_area_rectangle(points: &[Point2<f64>], trim: f64) -> Option<FloorRectangle> {
    let hull = convex_hull(points);
    if hull.is_empty() {
        return None;
    }
    // Candidate orientations: every hull edge, folded into [-π/4, π/4).
    let mut best: Option<(f64, f64)> = None; // (area, yaw)
    let fold = |a: f64| {
        let q = std::f64::consts::FRAC_PI_2;
        let mut y = a.rem_euclid(q);
        if y >= q / 2.0 {
            y -= q;
        }
        y
    };
    let n = hull.len();
    let mut yaws = vec![0.0];
    if n >= 2 {
        for i in 0..n {
            let e = hull[(i + 1) % n] - hull[i];
            if e.norm() > 1e-12 {
                // An edge along the rectangle's x axis (cos ψ, −sin ψ) has ψ = atan2(−e.z, e.x).
                yaws.push(fold((-e.y).atan2(e.x)));
            }
        }
    }
    for &yaw in &yaws {
        let r = extents(&hull, yaw, 0.0);
        let area = r.half_extents.x * r.half_extents.y;
        if best.is_none_or(|(a, y)| area < a - 1e-12 || ((area - a).abs() <= 1e-12 && yaw < y)) {
            best = Some((area, yaw));
        }
    }
    let (_, yaw) = best?;
    Some(extents(points, yaw, trim))
}

/// The rectangle of yaw `yaw` around `points` (world `(x, z)` pairs), with its extents taken
/// between the `trim` and `1 − trim` quantiles along its axes. `yaw` is folded into
/// `[-π/4, π/4)` like [`min_area_rectangle`]'s. Panics on an empty input.
pub fn rectangle_at(points: &[Point2<f64>], yaw: f64, trim: f64) -> FloorRectangle {
    let q = std::f64::consts::FRAC_PI_2;
    let mut y = yaw.rem_euclid(q);
    if y >= q / 2.0 {
        y -= q;
    }
    extents(points, y, trim)
}

fn extents(points: &[Point2<f64>], yaw: f64, trim: f64) -> FloorRectangle {
    let ax = Vector2::new(yaw.cos(), -yaw.sin());
    let az = Vector2::new(yaw.sin(), yaw.cos());
    let mut s: Vec<f64> = points.iter().map(|p| p.coords.dot(&ax)).collect();
    let mut t: Vec<f64> = points.iter().map(|p| p.coords.dot(&az)).collect();
    s.sort_by(|a, b| a.total_cmp(b));
    t.sort_by(|a, b| a.total_cmp(b));
    let (s0, s1) = (quantile(&s, trim), quantile(&s, 1.0 - trim));
    let (t0, t1) = (quantile(&t, trim), quantile(&t, 1.0 - trim));
    let c = ax * ((s0 + s1) / 2.0) + az * ((t0 + t1) / 2.0);
    FloorRectangle {
        center: Point2::from(c),
        half_extents: Vector2::new((s1 - s0) / 2.0, (t1 - t0) / 2.0),
        yaw,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rect_points(cx: f64, cz: f64, hx: f64, hz: f64, yaw: f64) -> Vec<Point2<f64>> {
        let ax = Vector2::new(yaw.cos(), -yaw.sin());
        let az = Vector2::new(yaw.sin(), yaw.cos());
        let mut out = Vec::new();
        for i in 0..=20 {
            for j in 0..=20 {
                let s = (i as f64 / 20.0 * 2.0 - 1.0) * hx;
                let t = (j as f64 / 20.0 * 2.0 - 1.0) * hz;
                out.push(Point2::new(cx, cz) + ax * s + az * t);
            }
        }
        out
    }

    #[test]
    fn recovers_a_rotated_rectangle() {
        for yaw in [-0.7, -0.3, 0.0, 0.2, 0.5] {
            let r = min_area_rectangle(&rect_points(1.0, -2.0, 0.8, 0.3, yaw), 0.0).unwrap();
            assert!((r.center - Point2::new(1.0, -2.0)).norm() < 1e-9);
            let area = r.half_extents.x * r.half_extents.y;
            assert!((area - 0.24).abs() < 1e-9, "yaw {yaw}: area {area}");
            // The recovered yaw equals the true one modulo 90°.
            let d = (r.yaw - yaw).rem_euclid(std::f64::consts::FRAC_PI_2);
            assert!(
                d < 1e-9 || (std::f64::consts::FRAC_PI_2 - d) < 1e-9,
                "yaw {yaw} -> {}",
                r.yaw
            );
        }
    }

    #[test]
    fn intersection_of_rotated_rectangles() {
        let r = |cx: f64, cz: f64, hx: f64, hz: f64, yaw: f64| FloorRectangle {
            center: Point2::new(cx, cz),
            half_extents: Vector2::new(hx, hz),
            yaw,
        };
        let a = r(0.0, 0.0, 1.0, 1.0, 0.0);
        assert!((a.intersection_area(&a) - 4.0).abs() < 1e-9);
        assert!((a.intersection_area(&r(1.0, 0.0, 1.0, 1.0, 0.0)) - 2.0).abs() < 1e-9);
        assert_eq!(a.intersection_area(&r(5.0, 0.0, 1.0, 1.0, 0.3)), 0.0);
        // A square turned by 45° inside a larger one: its whole area.
        let small = r(0.0, 0.0, 0.5, 0.5, std::f64::consts::FRAC_PI_4);
        assert!((small.intersection_area(&a) - 1.0).abs() < 1e-9);
        assert!((a.intersection_area(&small) - 1.0).abs() < 1e-9);
    }

    #[test]
    fn overlap_fraction() {
        let a = min_area_rectangle(&rect_points(0.0, 0.0, 1.0, 1.0, 0.0), 0.0).unwrap();
        let b = min_area_rectangle(&rect_points(0.2, 0.2, 0.2, 0.2, 0.0), 0.0).unwrap();
        assert_eq!(b.fraction_inside(&a, 0.0), 1.0);
        assert!(a.fraction_inside(&b, 0.0) < 0.1);
    }
}
