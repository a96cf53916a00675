//! View presets: cameras computed from a scene's extent.
//!
//! Every preset frames its subject with a 5 % margin on each side: the camera looks at the
//! centre of the points to frame from a fixed direction and backs off until they all fit.

use std::f64::consts::{FRAC_PI_2, TAU};

use nalgebra::{Point3, Vector3};
use scenethesis_imagery::{Camera, Intrinsics, DEFAULT_VERTICAL_FOV};
use scenethesis_scene_graph::Environment;

use crate::{Backdrop, RenderScene};

/// Azimuth of the photo view: seen from the front (+Z), turned 26° toward +X.
pub const PHOTO_AZIMUTH: f64 = 0.45;
/// Elevation of the photo view above the horizon (about 29°).
pub const PHOTO_ELEVATION: f64 = 0.5;
/// Elevation of the orbit views (about 32°).
pub const ORBIT_ELEVATION: f64 = 0.55;

/// The three-quarter "photo" view: like an interior photograph, from the front right and
/// above, so that the room's far walls and floor frame the objects (the walls between the
/// camera and the room are cut away when rendering). Outdoors and in the studio it frames the
/// objects.
pub fn photo_view(scene: &RenderScene, width: u32, height: u32) -> Camera {
    orbit_view(scene, PHOTO_AZIMUTH, PHOTO_ELEVATION, width, height)
}

/// A view straight down onto the scene, with the back (−Z) at the top of the image and +X to
/// the right.
pub fn top_view(scene: &RenderScene, width: u32, height: u32) -> Camera {
    let intrinsics = Intrinsics::from_vertical_fov(width, height, DEFAULT_VERTICAL_FOV);
    let points = framing_points(scene, true);
    fit(&points, Vector3::y(), -Vector3::z(), intrinsics)
}

/// `n` views evenly spaced around the scene, starting at the photo view's azimuth.
pub fn orbit_views(scene: &RenderScene, n: usize, width: u32, height: u32) -> Vec<Camera> {
    (0..n)
        .map(|i| {
            let azimuth = PHOTO_AZIMUTH + TAU * i as f64 / n as f64;
            orbit_view(scene, azimuth, ORBIT_ELEVATION, width, height)
        })
        .collect()
}

/// A view from `azimuth` (radians about +Y, 0 = from +Z, π/2 = from +X) and `elevation`
/// (radians above the horizon, below π/2) that frames the scene.
pub fn orbit_view(
    scene: &RenderScene,
    azimuth: f64,
    elevation: f64,
    width: u32,
    height: u32,
) -> Camera {
    let elevation = elevation.clamp(-FRAC_PI_2 + 0.01, FRAC_PI_2 - 0.01);
    let direction = Vector3::new(
        azimuth.sin() * elevation.cos(),
        elevation.sin(),
        azimuth.cos() * elevation.cos(),
    );
    let intrinsics = Intrinsics::from_vertical_fov(width, height, DEFAULT_VERTICAL_FOV);
    let points = framing_points(scene, false);
    fit(&points, direction, Vector3::y(), intrinsics)
}

/// What a view should show: a room's floor (and the lower part of its walls, or their tops
/// from above), outdoor objects with a margin, or the objects alone.
fn framing_points(scene: &RenderScene, from_above: bool) -> Vec<Point3<f64>> {
    let mut points = Vec::new();
    let objects = scene.objects_bounds();
    if let Some(b) = objects {
        points.extend(b.corners());
    }
    match (&scene.architecture, scene.backdrop) {
        (Some(arch), Backdrop::Interior) | (Some(arch), Backdrop::Studio)
            if arch.environment == Environment::Indoor =>
        {
            let (lo, hi) = (arch.floor.min, arch.floor.max);
            let wall_top = arch.walls.iter().map(|w| w.height).fold(0.0, f64::max);
            let heights = if from_above {
                vec![0.0, wall_top]
            } else {
                vec![0.0, wall_top.min(1.0)]
            };
            for y in heights {
                for (x, z) in [(lo.x, lo.y), (hi.x, lo.y), (lo.x, hi.y), (hi.x, hi.y)] {
                    points.push(Point3::new(x, y, z));
                }
            }
        }
        (Some(arch), _) if objects.is_none() => {
            let (lo, hi) = (arch.floor.min, arch.floor.max);
            for (x, z) in [(lo.x, lo.y), (hi.x, lo.y), (lo.x, hi.y), (hi.x, hi.y)] {
                points.push(Point3::new(x, 0.0, z));
            }
        }
        (Some(_), _) => {
            // Outdoors: the objects and a metre of ground around them.
            let b = objects.expect("checked above");
            for (x, z) in [
                (b.min.x - 1.0, b.min.z - 1.0),
                (b.max.x + 1.0, b.min.z - 1.0),
                (b.min.x - 1.0, b.max.z + 1.0),
                (b.max.x + 1.0, b.max.z + 1.0),
            ] {
                points.push(Point3::new(x, 0.0, z));
            }
        }
        (None, _) => {}
    }
    if points.is_empty() {
        points.extend(scene.bounds().corners());
    }
    points
}

/// The camera looking along `-direction` at the centre of `points`, backed off until every
/// point projects inside the image with a 5 % margin.
fn fit(
    points: &[Point3<f64>],
    direction: Vector3<f64>,
    up: Vector3<f64>,
    intrinsics: Intrinsics,
) -> Camera {
    let lo = points
        .iter()
        .fold(Point3::from([f64::MAX; 3]), |a, p| a.inf(p));
    let hi = points
        .iter()
        .fold(Point3::from([f64::MIN; 3]), |a, p| a.sup(p));
    let target = nalgebra::center(&lo, &hi);
    let direction = direction.normalize();
    let camera_at =
        |distance: f64| Camera::look_at(intrinsics, target + direction * distance, target, up);
    let (w, h) = (intrinsics.width as f64, intrinsics.height as f64);
    let fits = |camera: &Camera| {
        points.iter().all(|p| {
            camera.project(p).is_some_and(|proj| {
                proj.depth > 0.05
                    && (0.05 * w..=0.95 * w).contains(&proj.pixel.x)
                    && (0.05 * h..=0.95 * h).contains(&proj.pixel.y)
            })
        })
    };
    let (mut near, mut far) = (0.05, 1.0);
    while !fits(&camera_at(far)) && far < 1e5 {
        near = far;
        far *= 2.0;
    }
    for _ in 0..48 {
        let mid = 0.5 * (near + far);
        if fits(&camera_at(mid)) {
            far = mid;
        } else {
            near = mid;
        }
    }
    camera_at(far)
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::Architecture;

    fn room() -> RenderScene {
        RenderScene::with_architecture(
            Vec::new(),
            Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9),
        )
    }

    #[test]
    fn photo_view_frames_the_floor_from_the_front_right() {
        let scene = room();
        let cam = photo_view(&scene, 800, 600);
        assert!(cam.position.x > 0.0 && cam.position.z > 0.0 && cam.position.y > 1.0);
        for corner in [[-3.0, -2.0], [3.0, -2.0], [-3.0, 2.0], [3.0, 2.0]] {
            let p = cam
                .project(&Point3::new(corner[0], 0.0, corner[1]))
                .expect("in front");
            assert!(p.pixel.x >= 39.0 && p.pixel.x <= 761.0, "{p:?}");
            assert!(p.pixel.y >= 29.0 && p.pixel.y <= 571.0, "{p:?}");
        }
    }

    #[test]
    fn top_view_looks_down_with_back_wall_on_top() {
        let cam = top_view(&room(), 400, 300);
        assert!((cam.forward() + Vector3::y()).norm() < 1e-9);
        let back = cam.project(&Point3::new(0.0, 0.0, -2.0)).unwrap();
        let front = cam.project(&Point3::new(0.0, 0.0, 2.0)).unwrap();
        let right = cam.project(&Point3::new(3.0, 0.0, 0.0)).unwrap();
        assert!(back.pixel.y < front.pixel.y && right.pixel.x > 200.0);
    }

    #[test]
    fn orbit_views_circle_the_scene() {
        let views = orbit_views(&room(), 4, 320, 240);
        assert_eq!(views.len(), 4);
        let c0 = views[0].position;
        let c2 = views[2].position;
        assert!((c0.x + c2.x).abs() < 1e-6 && (c0.z + c2.z).abs() < 1e-6);
    }
}
