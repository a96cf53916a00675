//! `camera.json`: the guidance camera, range-checked before anything uses it.

use std::path::Path;

use nalgebra::{Quaternion, UnitQuaternion};
use scenethesis_imagery::Camera;
use scenethesis_scene_graph::limits::MAX_COORDINATE;

use super::{check_image_size, invalid, read_bounded_to, FileError};
#[cfg(doc)]
use super::{MAX_PIXELS, MAX_SIDE};

/// Largest `camera.json` read, in bytes (1 MiB).
pub const MAX_CAMERA_JSON_BYTES: u64 = 1 << 20;
/// Smallest focal length, as a fraction of the image's larger side (about a 168° view).
pub const MIN_FOCAL_RATIO: f64 = 0.05;
/// Largest focal length, as a multiple of the image's larger side (about a 0.6° view).
pub const MAX_FOCAL_RATIO: f64 = 100.0;
/// How far the principal point may lie outside the image, as a multiple of its side: `cx` in
/// `[-w, 2w]`, `cy` in `[-h, 2h]`.
pub const PRINCIPAL_POINT_MARGIN: f64 = 1.0;

/// Reads a camera file and checks its values ([`check_camera`]).
pub fn read_camera(path: &Path) -> Result<Camera, FileError> {
    let bytes = read_bounded_to(path, MAX_CAMERA_JSON_BYTES)?;
    let camera: Camera = serde_json::from_slice(&bytes).map_err(|e| {
        invalid(
            path,
            format!("expected {{\"intrinsics\": {{width, height, fx, fy, cx, cy}}, \"position\": [x, y, z], \"rotation\": [i, j, k, w]}} ({e})"),
        )
    })?;
    check_camera(camera).map_err(|problem| invalid(path, problem))
}

/// Checks a camera's values and returns it with a unit rotation: image sides 1–[`MAX_SIDE`]
/// and at most [`MAX_PIXELS`] pixels; finite focal lengths between [`MIN_FOCAL_RATIO`] and
/// [`MAX_FOCAL_RATIO`] times the larger side; the principal point within
/// [`PRINCIPAL_POINT_MARGIN`] image sides of the image; the position within ±`MAX_COORDINATE`
/// metres; a rotation quaternion of non-zero finite length (normalised when not unit).
pub fn check_camera(mut camera: Camera) -> Result<Camera, String> {
    check_image_size(camera.intrinsics.width, camera.intrinsics.height)
        .map_err(|problem| format!("intrinsics: {problem}"))?;
    check_intrinsics(&camera)?;
    check_position(&camera)?;
    camera.rotation = unit_rotation(camera.rotation.quaternion())?;
    Ok(camera)
}

fn check_intrinsics(camera: &Camera) -> Result<(), String> {
    let k = &camera.intrinsics;
    let side = k.width.max(k.height) as f64;
    let (lo, hi) = (MIN_FOCAL_RATIO * side, MAX_FOCAL_RATIO * side);
    for (name, f) in [("fx", k.fx), ("fy", k.fy)] {
        if !(f.is_finite() && f >= lo && f <= hi) {
            return Err(format!(
                "intrinsics: focal length {name} is {f}: expected a finite value between {lo} and {hi} pixels ({MIN_FOCAL_RATIO}–{MAX_FOCAL_RATIO} × the larger image side)"
            ));
        }
    }
    let m = PRINCIPAL_POINT_MARGIN;
    for (name, c, size) in [("cx", k.cx, k.width as f64), ("cy", k.cy, k.height as f64)] {
        if !(c.is_finite() && c >= -m * size && c <= (1.0 + m) * size) {
            return Err(format!(
                "intrinsics: principal point {name} is {c}: expected a finite value between {} and {} pixels",
                -m * size,
                (1.0 + m) * size
            ));
        }
    }
    Ok(())
}

fn check_position(camera: &Camera) -> Result<(), String> {
    let p = &camera.position;
    if p.iter().all(|v| v.is_finite() && v.abs() <= MAX_COORDINATE) {
        return Ok(());
    }
    Err(format!(
        "position [{:?}, {:?}, {:?}]: expected finite coordinates within ±{MAX_COORDINATE} m (MAX_COORDINATE)",
        p.x, p.y, p.z
    ))
}

/// The rotation as a unit quaternion; refuses non-finite and zero-length ones. A quaternion
/// within 1e-9 of unit length is kept as written, so files written by `render` read back exact.
fn unit_rotation(q: &Quaternion<f64>) -> Result<UnitQuaternion<f64>, String> {
    if !q.coords.iter().all(|v| v.is_finite()) {
        return Err(format!(
            "rotation [{}, {}, {}, {}]: expected finite numbers (a unit quaternion [i, j, k, w])",
            q.i, q.j, q.k, q.w
        ));
    }
    let norm = q.norm();
    if norm < 1e-6 {
        return Err("rotation quaternion has zero length; expected a unit quaternion".into());
    }
    if (norm - 1.0).abs() <= 1e-9 {
        return Ok(UnitQuaternion::new_unchecked(*q));
    }
    Ok(UnitQuaternion::from_quaternion(*q))
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::{Point3, Vector3};
    use scenethesis_imagery::Intrinsics;

    fn camera(w: u32, h: u32) -> Camera {
        Camera::look_at(
            Intrinsics::from_vertical_fov(w, h, 1.0),
            Point3::new(0.0, 1.5, 3.0),
            Point3::origin(),
            Vector3::y(),
        )
    }

    fn err(c: Camera) -> String {
        check_camera(c).unwrap_err()
    }

    #[test]
    fn a_normal_camera_passes_unchanged() {
        let c = camera(640, 480);
        assert_eq!(check_camera(c).unwrap(), c);
    }

    #[test]
    fn position_is_bounded_by_max_coordinate() {
        let mut c = camera(64, 48);
        c.position.x = MAX_COORDINATE;
        assert!(check_camera(c).is_ok());
        c.position.x = MAX_COORDINATE * 1.000001;
        assert!(err(c).contains("position ["), "{}", err(c));
        c.position.x = 1e300;
        // Written short, not as 301 digits.
        assert!(err(c).starts_with("position [1e300, "), "{}", err(c));
        assert!(err(c).contains("within ±1000 m"));
    }

    #[test]
    fn a_zero_quaternion_gets_its_own_message_and_others_are_normalised() {
        let mut c = camera(64, 48);
        c.rotation = UnitQuaternion::new_unchecked(Quaternion::new(0.0, 0.0, 0.0, 0.0));
        assert_eq!(
            err(c),
            "rotation quaternion has zero length; expected a unit quaternion"
        );
        c.rotation = UnitQuaternion::new_unchecked(Quaternion::new(2.0, 0.0, 0.0, 0.0));
        let unit = check_camera(c).unwrap();
        assert!((unit.rotation.quaternion().norm() - 1.0).abs() < 1e-12);
        c.rotation = UnitQuaternion::new_unchecked(Quaternion::new(f64::NAN, 0.0, 0.0, 1.0));
        assert!(err(c).contains("finite numbers"));
    }

    #[test]
    fn focal_lengths_and_principal_point_stay_in_their_windows() {
        let mut c = camera(100, 50);
        c.intrinsics.fx = MIN_FOCAL_RATIO * 100.0;
        c.intrinsics.fy = MAX_FOCAL_RATIO * 100.0;
        assert!(check_camera(c).is_ok());
        c.intrinsics.fx = MIN_FOCAL_RATIO * 100.0 * 0.999;
        assert!(err(c).contains("focal length fx"));
        c.intrinsics.fx = 10.0;
        c.intrinsics.fy = MAX_FOCAL_RATIO * 100.0 * 1.001;
        assert!(err(c).contains("focal length fy"));
        c.intrinsics.fy = 0.0;
        assert!(err(c).contains("focal length fy"));
        c.intrinsics.fy = 100.0;
        c.intrinsics.cx = -100.0;
        c.intrinsics.cy = 100.0;
        assert!(check_camera(c).is_ok());
        c.intrinsics.cx = -100.5;
        assert!(err(c).contains("principal point cx"));
        c.intrinsics.cx = 50.0;
        c.intrinsics.cy = 100.5;
        assert!(err(c).contains("principal point cy"));
    }

    #[test]
    fn image_size_is_bounded_by_max_side_and_max_pixels() {
        use crate::files::{MAX_PIXELS, MAX_SIDE};
        let side = (MAX_PIXELS as f64).sqrt() as u32;
        assert!(check_camera(camera(side, side)).is_ok());
        assert!(err(camera(side, side + 1)).contains("MAX_PIXELS"));
        assert!(err(camera(MAX_SIDE + 1, 1)).contains("each side 1–8192"));
        assert!(err(camera(0, 10)).contains("each side"));
    }
}
