//! Analytic signed distance fields: boxes (walls, architecture), spheres and the ground plane.

use nalgebra::{Point3, Vector3};

use crate::SignedDistance;

/// A solid box centred on its frame's origin, given by its half extents (exact distance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxSdf {
    /// Half the edge lengths along x, y and z (metres, positive).
    pub half_extents: Vector3<f32>,
}

impl BoxSdf {
    /// A box centred on the origin with the given half extents.
    pub fn new(half_extents: Vector3<f32>) -> Self {
        Self { half_extents }
    }
}

impl SignedDistance for BoxSdf {
    #[inline]
    fn distance(&self, p: &Point3<f32>) -> f32 {
        let q = p.coords.abs() - self.half_extents;
        let outside = q.sup(&Vector3::zeros()).norm();
        let inside = q.max().min(0.0);
        outside + inside
    }

    fn gradient(&self, p: &Point3<f32>) -> Vector3<f32> {
        let q = p.coords.abs() - self.half_extents;
        let sign = p.coords.map(|v| if v < 0.0 { -1.0 } else { 1.0 });
        let outside = q.sup(&Vector3::zeros());
        if outside.norm_squared() > 0.0 {
            return outside.component_mul(&sign).normalize();
        }
        let axis = q.imax();
        let mut g = Vector3::zeros();
        g[axis] = sign[axis];
        g
    }

    fn is_lipschitz(&self) -> bool {
        true
    }

    fn local_bounds(&self) -> (Point3<f32>, Point3<f32>) {
        (
            Point3::from(-self.half_extents),
            Point3::from(self.half_extents),
        )
    }
}

/// A solid ball centred on its frame's origin (exact distance).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SphereSdf {
    /// Radius in metres.
    pub radius: f32,
}

impl SphereSdf {
    /// A ball of the given radius.
    pub fn new(radius: f32) -> Self {
        Self { radius }
    }
}

impl SignedDistance for SphereSdf {
    #[inline]
    fn distance(&self, p: &Point3<f32>) -> f32 {
        p.coords.norm() - self.radius
    }

    fn gradient(&self, p: &Point3<f32>) -> Vector3<f32> {
        p.coords.try_normalize(0.0).unwrap_or_else(Vector3::y)
    }

    fn is_lipschitz(&self) -> bool {
        true
    }

    fn local_bounds(&self) -> (Point3<f32>, Point3<f32>) {
        let r = Vector3::repeat(self.radius);
        (Point3::from(-r), Point3::from(r))
    }
}

/// The ground: the half-space `y ≤ 0` of its frame, negative below the plane.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct PlaneSdf;

impl SignedDistance for PlaneSdf {
    #[inline]
    fn distance(&self, p: &Point3<f32>) -> f32 {
        p.y
    }

    fn gradient(&self, _p: &Point3<f32>) -> Vector3<f32> {
        Vector3::y()
    }

    fn is_lipschitz(&self) -> bool {
        true
    }

    /// The whole solid half-space: infinite in x and z and downward, up to y = 0.
    fn local_bounds(&self) -> (Point3<f32>, Point3<f32>) {
        (
            Point3::new(f32::NEG_INFINITY, f32::NEG_INFINITY, f32::NEG_INFINITY),
            Point3::new(f32::INFINITY, 0.0, f32::INFINITY),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_distance_inside_outside_and_gradient() {
        let b = BoxSdf::new(Vector3::new(1.0, 2.0, 3.0));
        assert_eq!(b.distance(&Point3::new(0.0, 0.0, 0.0)), -1.0);
        assert_eq!(b.distance(&Point3::new(2.0, 0.0, 0.0)), 1.0);
        assert!((b.distance(&Point3::new(2.0, 3.0, 0.0)) - 2f32.sqrt()).abs() < 1e-6);
        assert_eq!(b.gradient(&Point3::new(-0.5, 0.0, 0.0)), -Vector3::x());
        assert_eq!(b.gradient(&Point3::new(0.0, 0.0, 5.0)), Vector3::z());
    }

    #[test]
    fn plane_is_negative_below() {
        assert_eq!(PlaneSdf.distance(&Point3::new(3.0, -0.25, 9.0)), -0.25);
        assert_eq!(PlaneSdf.gradient(&Point3::origin()), Vector3::y());
    }
}
