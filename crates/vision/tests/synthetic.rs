//! Lifts ray-cast guidance of known boxes and compares the recovered boxes with the truth.

use std::collections::BTreeMap;

use nalgebra::{Point2, Point3, Rotation3, Vector3};
use scenethesis_imagery::{Camera, DepthMap, Guidance, Intrinsics, Mask, RgbImage};
use scenethesis_vision::{lift_scene, LiftError, LiftOptions, SupportKind};

struct TrueBox {
    id: &'static str,
    center: Point3<f64>,
    size: Vector3<f64>,
    yaw: f64,
}

fn truth() -> Vec<TrueBox> {
    let b = |id, x: f64, bottom: f64, z: f64, size: [f64; 3], yaw| TrueBox {
        id,
        center: Point3::new(x, bottom + size[1] / 2.0, z),
        size: Vector3::from(size),
        yaw,
    };
    vec![
        b("table_0", 0.0, 0.0, -1.0, [1.2, 0.75, 0.8], 0.3),
        b("box_0", 0.1, 0.75, -1.0, [0.3, 0.2, 0.25], 0.5),
        b("cabinet_0", -1.6, 0.0, -2.2, [0.9, 1.0, 0.45], -0.2),
        b("chair_0", 1.5, 0.0, -0.4, [0.5, 0.9, 0.55], 0.8),
    ]
}

fn camera() -> Camera {
    let k = Intrinsics::from_vertical_fov(320, 240, 60f64.to_radians());
    Camera::look_at(
        k,
        Point3::new(0.0, 1.7, 2.6),
        Point3::new(0.0, 0.4, -1.0),
        Vector3::y(),
    )
}

/// Distance along the ray (in units of `dir`) to the box, if hit.
fn hit(b: &TrueBox, eye: &Point3<f64>, dir: &Vector3<f64>) -> Option<f64> {
    let inv = Rotation3::from_axis_angle(&Vector3::y_axis(), -b.yaw);
    let o = inv * (eye - b.center);
    let d = inv * dir;
    let (mut t0, mut t1) = (0.0f64, f64::INFINITY);
    for k in 0..3 {
        let h = b.size[k] / 2.0;
        if d[k].abs() < 1e-12 {
            if o[k].abs() > h {
                return None;
            }
            continue;
        }
        let (a, c) = ((-h - o[k]) / d[k], (h - o[k]) / d[k]);
        t0 = t0.max(a.min(c));
        t1 = t1.min(a.max(c));
    }
    (t0 <= t1 && t0 > 0.0).then_some(t0)
}

fn render(boxes: &[TrueBox], with_depth: bool) -> Guidance {
    let cam = camera();
    let (w, h) = (cam.intrinsics.width, cam.intrinsics.height);
    let mut masks: BTreeMap<String, Mask> = boxes
        .iter()
        .map(|b| (b.id.to_string(), Mask::new(w, h)))
        .collect();
    let mut depth = vec![f32::NAN; (w * h) as usize];
    for v in 0..h {
        for u in 0..w {
            let dir =
                cam.unproject(&Point2::new(u as f64 + 0.5, v as f64 + 0.5), 1.0) - cam.position;
            let mut best: Option<(f64, Option<&str>)> = None;
            if dir.y < 0.0 {
                best = Some((-cam.position.y / dir.y, None));
            }
            for b in boxes {
                if let Some(t) = hit(b, &cam.position, &dir) {
                    if best.is_none_or(|(s, _)| t < s) {
                        best = Some((t, Some(b.id)));
                    }
                }
            }
            if let Some((t, id)) = best {
                depth[(v * w + u) as usize] = t as f32;
                if let Some(id) = id {
                    masks.get_mut(id).unwrap().set(u, v, true);
                }
            }
        }
    }
    let image = RgbImage::new(w, h, vec![100; (w * h * 3) as usize]).unwrap();
    let depth = with_depth.then(|| DepthMap::new(w, h, depth).unwrap());
    Guidance::new(cam, image, depth, masks).unwrap()
}

fn priors(boxes: &[TrueBox]) -> BTreeMap<String, Vector3<f64>> {
    boxes.iter().map(|b| (b.id.to_string(), b.size)).collect()
}

/// Yaw difference modulo 180° (a box's front is ambiguous), in degrees.
fn yaw_error(a: f64, b: f64) -> f64 {
    scenethesis_scene_graph::yaw_distance_modulo(a, b, std::f64::consts::PI).to_degrees()
}

#[test]
fn depth_lift_recovers_boxes_and_supports() {
    let boxes = truth();
    let guidance = render(&boxes, true);
    let options = LiftOptions {
        priors: priors(&boxes),
        // The masks are exact: no boundary margin (at 320 × 240 a 2-px margin leaves the
        // cabinet's top face a sliver whose footprint turns by 20°).
        mask_margin_px: 0,
        ..LiftOptions::default()
    };
    let lifted = lift_scene(&guidance, &options).unwrap();
    assert!(lifted.missing.is_empty(), "missing {:?}", lifted.missing);
    for t in &boxes {
        let b = lifted.boxes.iter().find(|b| b.id == t.id).unwrap();
        let dc = (b.center - t.center).norm();
        assert!(
            dc < 0.05,
            "{}: centre off by {dc:.3} m ({:?} vs {:?})",
            t.id,
            b.center,
            t.center
        );
        assert!(
            yaw_error(b.yaw, t.yaw) < 4.0,
            "{}: yaw {:.1}° vs {:.1}°",
            t.id,
            b.yaw.to_degrees(),
            t.yaw.to_degrees()
        );
        let h = b.size().y;
        assert!(
            (h - t.size.y).abs() / t.size.y < 0.06,
            "{}: height {h:.3} vs {:.3}",
            t.id,
            t.size.y
        );
    }
    let support = |id: &str| lifted.supports.iter().find(|s| s.id == id).unwrap().clone();
    assert_eq!(support("box_0").parent.as_deref(), Some("table_0"));
    assert_eq!(support("box_0").kind, SupportKind::On);
    for id in ["table_0", "cabinet_0", "chair_0"] {
        assert_eq!(support(id).kind, SupportKind::Ground, "{id}");
    }
}

#[test]
fn metrology_places_grounded_objects_without_depth() {
    let boxes: Vec<TrueBox> = truth()
        .into_iter()
        .filter(|b| b.center.y - b.size.y / 2.0 < 1e-9)
        .collect();
    let guidance = render(&boxes, false);
    let options = LiftOptions {
        priors: priors(&boxes),
        ..LiftOptions::default()
    };
    let lifted = lift_scene(&guidance, &options).unwrap();
    for t in &boxes {
        let b = lifted.boxes.iter().find(|b| b.id == t.id).unwrap();
        let dc = (b.center - t.center).norm();
        assert!(dc < 0.25, "{}: centre off by {dc:.3} m", t.id);
        assert!(b.bottom().abs() < 1e-9, "{} stands on the floor", t.id);
        assert!(
            (b.size().y - t.size.y).abs() / t.size.y < 0.2,
            "{}: height {:.3}",
            t.id,
            b.size().y
        );
    }
}

#[test]
fn an_object_the_masks_miss_is_missing_not_invented() {
    let boxes = truth();
    let mut guidance = render(&boxes, true);
    guidance.masks.insert("ghost_0".into(), Mask::new(320, 240));
    let lifted = lift_scene(&guidance, &LiftOptions::default()).unwrap();
    assert_eq!(lifted.missing, vec!["ghost_0".to_string()]);
    assert_eq!(lifted.boxes.len(), boxes.len());
}

#[test]
fn a_camera_looking_up_is_refused_without_depth() {
    let boxes = truth();
    let mut guidance = render(&boxes, false);
    let k = guidance.camera.intrinsics;
    guidance.camera = Camera::look_at(
        k,
        Point3::new(0.0, 1.0, 0.0),
        Point3::new(0.0, 3.0, -1.0),
        Vector3::y(),
    );
    let err = lift_scene(&guidance, &LiftOptions::default()).unwrap_err();
    assert!(
        matches!(err, LiftError::CameraNotLookingDown { .. }),
        "{err}"
    );
    assert!(err.to_string().contains("looking down"));
}

/// A deterministic uniform value in [-1, 1] per pixel.
fn noise(u: u32, v: u32) -> f64 {
    let mut x = (u as u64) << 32 | v as u64 | 0x9E37_79B9_0000_0000;
    x ^= x >> 33;
    x = x.wrapping_mul(0xff51_afd7_ed55_8ccd);
    x ^= x >> 33;
    x = x.wrapping_mul(0xc4ce_b9fe_1a85_ec53);
    x ^= x >> 33;
    (x >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
}

#[test]
fn noisy_scaled_depth_is_calibrated_on_the_floor() {
    let boxes = truth();
    let clean = render(&boxes, true);
    let d = clean.depth.as_ref().unwrap();
    // 7 % global scale error and 2 % per-pixel noise, as a monocular depth model gives.
    let noisy = DepthMap::from_fn(d.width(), d.height(), |u, v| {
        d.get(u, v).map_or(f32::NAN, |z| {
            (z as f64 * 1.07 * (1.0 + 0.02 * noise(u, v))) as f32
        })
    });
    let guidance = Guidance::new(
        clean.camera,
        clean.image.clone(),
        Some(noisy),
        clean.masks.clone(),
    )
    .unwrap();
    let options = LiftOptions {
        priors: priors(&boxes),
        // Exact masks (see above); and no median filter: a 5 × 5 window cut by the edge of
        // box_0's small mask (30 × 25 px) bends its outline by 20°.
        mask_margin_px: 0,
        noisy_filter_radius: 0,
        ..LiftOptions::default()
    };
    let lifted = lift_scene(&guidance, &options).unwrap();
    assert!(
        (lifted.depth_scale * 1.07 - 1.0).abs() < 0.01,
        "scale {}",
        lifted.depth_scale
    );
    for t in &boxes {
        let b = lifted.boxes.iter().find(|b| b.id == t.id).unwrap();
        let dc = (b.center - t.center).norm();
        assert!(dc < 0.10, "{}: centre off by {dc:.3} m", t.id);
        // Under noise a footprint within 20 % of square (box_0: 0.30 × 0.25 m) can come out a
        // quarter turn off: compare it modulo 90°.
        let near_square = (t.size.x - t.size.z).abs() <= 0.2 * t.size.x.max(t.size.z);
        let err = yaw_error(b.yaw, t.yaw);
        let err = if near_square {
            err.min(90.0 - err)
        } else {
            err
        };
        assert!(err < 10.0, "{}: yaw {:.1}°", t.id, b.yaw.to_degrees());
    }
}

#[test]
fn seen_height_is_what_the_image_shows_whatever_the_prior_says() {
    let boxes = truth();
    let guidance = render(&boxes, true);
    // Priors 40 % too tall (a catalogue's generic size for an object the image shows
    // smaller): the boxes lean toward them, the seen heights do not.
    let tall: BTreeMap<String, Vector3<f64>> = priors(&boxes)
        .into_iter()
        .map(|(id, s)| (id, Vector3::new(s.x, s.y * 1.4, s.z)))
        .collect();
    let options = LiftOptions {
        priors: tall,
        mask_margin_px: 0,
        ..LiftOptions::default()
    };
    let lifted = lift_scene(&guidance, &options).unwrap();
    for t in &boxes {
        let b = lifted.boxes.iter().find(|b| b.id == t.id).unwrap();
        assert!(
            (b.seen_height - t.size.y).abs() / t.size.y < 0.06,
            "{}: seen {:.3} vs {:.3}",
            t.id,
            b.seen_height,
            t.size.y
        );
        assert!(
            b.size().y > t.size.y * 1.04,
            "{}: the prior is blended in ({:.3} vs {:.3})",
            t.id,
            b.size().y,
            t.size.y
        );
    }
}
