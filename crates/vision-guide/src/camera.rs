//! A camera for a guidance image that comes without one, estimated from the floor in its
//! depth map.
//!
//! The intrinsics are the depth model's, or a pinhole of [`DEFAULT_VERTICAL_FOV`](scenethesis_imagery::DEFAULT_VERTICAL_FOV) centred on
//! the image. The floor is the horizontal-looking plane (its normal within 72° of the image's
//! up) that most depth points lie on (deterministic RANSAC, 3 cm tolerance); it gives the
//! camera's height and its pitch and roll. What one image cannot tell — where in the room the
//! camera stands and which way it faces — is fixed by convention: it faces the back wall (−Z)
//! and the visible floor's median point is the floor's centre.

use nalgebra::{Matrix3, Point3, Rotation3, UnitQuaternion, Vector3};
use scenethesis_imagery::{Camera, DepthMap, Intrinsics};
use scenethesis_scene_graph::Architecture;

/// Estimates the camera of a depth map from its floor; the error says what was missing.
pub fn estimate_from_floor(
    depth: &DepthMap,
    intrinsics: Intrinsics,
    architecture: &Architecture,
) -> Result<Camera, String> {
    let k = intrinsics;
    let stride = (depth.width().max(depth.height()) / 160).max(1);
    let mut points: Vec<Vector3<f64>> = Vec::new();
    for v in (0..depth.height()).step_by(stride as usize) {
        for u in (0..depth.width()).step_by(stride as usize) {
            if let Some(z) = depth.get(u, v) {
                let z = z as f64;
                let (x, y) = (u as f64 + 0.5, v as f64 + 0.5);
                points.push(Vector3::new(
                    (x - k.cx) / k.fx * z,
                    -(y - k.cy) / k.fy * z,
                    -z,
                ));
            }
        }
    }
    if points.len() < 50 {
        return Err(format!(
            "the depth map has {} valid pixels; at least 50 are needed to find the floor",
            points.len()
        ));
    }
    let n_pts = points.len();
    let mut state: u64 = 0x2545_f491_4f6c_dd1d;
    let mut next = |n: usize| {
        state = state
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        ((state >> 33) as usize) % n
    };
    let tolerance = 0.03;
    let mut best: Option<(usize, Vector3<f64>, f64)> = None;
    for _ in 0..400 {
        let (a, b, c) = (
            points[next(n_pts)],
            points[next(n_pts)],
            points[next(n_pts)],
        );
        let cross = (b - a).cross(&(c - a));
        if cross.norm() < 1e-9 {
            continue;
        }
        let mut n = cross.normalize();
        let mut d = -n.dot(&a);
        if d < 0.0 {
            n = -n;
            d = -d;
        }
        // The floor is below the camera and roughly "up" in the image.
        if n.y < 0.3 || d < 0.05 {
            continue;
        }
        let count = points
            .iter()
            .filter(|p| (n.dot(p) + d).abs() < tolerance)
            .count();
        if best.is_none_or(|(c, _, bd)| count > c || (count == c && d > bd)) {
            best = Some((count, n, d));
        }
    }
    let Some((count, n, height)) = best else {
        return Err("no floor plane below the camera was found in the depth map".into());
    };
    if count < n_pts / 20 {
        return Err(format!(
            "the best floor plane holds {count} of {n_pts} depth points; expected at least 5 % (is the floor visible?)"
        ));
    }
    let up_c = n;
    let back = -Vector3::z();
    let fwd = back - up_c * up_c.dot(&back);
    if fwd.norm() < 1e-6 {
        return Err("the camera looks straight down; its heading cannot be told".into());
    }
    let fwd_c = fwd.normalize();
    let right_c = fwd_c.cross(&up_c);
    let c = Matrix3::from_columns(&[right_c, up_c, fwd_c]);
    let w = Matrix3::from_columns(&[Vector3::<f64>::x(), Vector3::y(), -Vector3::z()]);
    let rotation =
        UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(w * c.transpose()));
    let mut xs = Vec::new();
    let mut zs = Vec::new();
    for p in points
        .iter()
        .filter(|p| (n.dot(p) + height).abs() < tolerance)
    {
        let q = rotation * p;
        xs.push(q.x);
        zs.push(q.z);
    }
    let med = |v: &mut Vec<f64>| {
        v.sort_by(|a, b| a.total_cmp(b));
        v[v.len() / 2]
    };
    let floor = &architecture.floor;
    let centre = nalgebra::center(&floor.min, &floor.max);
    let position = Point3::new(centre.x - med(&mut xs), height, centre.y - med(&mut zs));
    Ok(Camera {
        intrinsics,
        position,
        rotation,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::Point2;
    use scenethesis_imagery::DEFAULT_VERTICAL_FOV;

    #[test]
    fn recovers_height_and_pitch_of_a_floor_view() {
        let k = Intrinsics::from_vertical_fov(160, 120, DEFAULT_VERTICAL_FOV);
        let truth = Camera::look_at(
            k,
            Point3::new(0.3, 1.5, 2.0),
            Point3::new(0.3, 0.0, -1.0),
            Vector3::y(),
        );
        // Floor everywhere below the horizon, a back wall at z = -3 above it.
        let depth = DepthMap::from_fn(160, 120, |u, v| {
            let p = truth.unproject(&Point2::new(u as f64 + 0.5, v as f64 + 0.5), 1.0);
            let dir = p - truth.position;
            let t_floor = if dir.y < 0.0 {
                -1.5 / dir.y
            } else {
                f64::INFINITY
            };
            let t_wall = if dir.z < 0.0 {
                (-3.0 - 2.0) / dir.z
            } else {
                f64::INFINITY
            };
            t_floor.min(t_wall) as f32
        });
        let arch = Architecture::rectangular_room(4.0, 6.0, 2.6, 0.9);
        let est = estimate_from_floor(&depth, k, &arch).unwrap();
        assert!((est.position.y - 1.5).abs() < 0.03, "{}", est.position.y);
        let pitch = |c: &Camera| c.forward().y.asin().to_degrees();
        assert!(
            (pitch(&est) - pitch(&truth)).abs() < 1.5,
            "{} vs {}",
            pitch(&est),
            pitch(&truth)
        );
        assert!(
            est.forward().x.abs() < 0.02,
            "faces −Z: {:?}",
            est.forward()
        );
    }
}
