//! The matcher seam with two implementations: the default shape matcher, and an oracle that
//! knows the true pose (as a dense learned matcher would ideally behave), both lifted by the
//! same `lift`.

use nalgebra::{Point3, Vector3};
use scenethesis_correspondence::shape::{pick_yaw, search_yaw};
use scenethesis_correspondence::{
    lift, rasterize, MatchKind, Matcher, PairKind, PixelMatch, RenderedView, ShapeMatcher,
    TargetRegion, Window,
};
use scenethesis_imagery::{Camera, DepthMap, Intrinsics, Mask};
use scenethesis_scene_graph::{yaw_distance, Material, Mesh, Pose};

/// A grey axis-aligned box from `min` to `max`.
fn box_mesh(min: [f32; 3], max: [f32; 3]) -> Mesh {
    Mesh::cuboid("box", Material::new("grey", [0.5; 3], 0.8), min, max)
}

/// An L-shaped asset (a sofa-like seat with a back), whose silhouette tells front from back.
fn l_mesh() -> Mesh {
    let mut seat = box_mesh([-1.0, 0.0, -0.45], [1.0, 0.45, 0.45]);
    let back = box_mesh([-1.0, 0.45, -0.45], [1.0, 0.9, -0.2]);
    let n = seat.parts[0].positions.len() as u32;
    seat.parts[0]
        .positions
        .extend(back.parts[0].positions.iter());
    let tris: Vec<[u32; 3]> = back.parts[0]
        .triangles
        .iter()
        .map(|t| [t[0] + n, t[1] + n, t[2] + n])
        .collect();
    seat.parts[0].triangles.extend(tris);
    seat
}

fn camera() -> Camera {
    Camera::look_at(
        Intrinsics::from_vertical_fov(160, 120, 1.0),
        Point3::new(1.5, 2.0, 4.5),
        Point3::new(0.0, 0.4, 0.0),
        Vector3::y(),
    )
}

/// Guidance rendered by the CPU rasterizer: the object's mask and the depth of the whole
/// image (the object plus optional occluders).
fn guidance(camera: &Camera, objects: &[(&Mesh, Pose)]) -> (Mask, DepthMap) {
    let full = Window::full(camera);
    let views: Vec<RenderedView> = objects
        .iter()
        .map(|(m, p)| rasterize(m, p, camera, full))
        .collect();
    let (w, h) = (full.width, full.height);
    let mut mask = Mask::new(w, h);
    let depth = DepthMap::from_fn(w, h, |x, y| {
        let mut best = f32::INFINITY;
        let mut who = usize::MAX;
        for (k, v) in views.iter().enumerate() {
            if let Some(d) = v.depth.get(x, y) {
                if d < best {
                    best = d;
                    who = k;
                }
            }
        }
        if who == 0 {
            mask.set(x, y, true);
        }
        if best.is_finite() {
            best
        } else {
            0.0
        }
    });
    (mask, depth)
}

/// The second implementation: knows the true pose and pairs each rendered pixel with where
/// the same asset point really is.
struct Oracle {
    truth: Pose,
}

impl Matcher for Oracle {
    fn name(&self) -> &str {
        "oracle"
    }

    fn match_view(&self, view: &RenderedView, target: &TargetRegion<'_>) -> Vec<PixelMatch> {
        let mut out = Vec::new();
        for y in 0..view.depth.height() {
            for x in 0..view.depth.width() {
                let Some(p) = view.asset_point(x, y) else {
                    continue;
                };
                let Some(q) = target.camera.project(&self.truth.transform_point(&p)) else {
                    continue;
                };
                out.push(PixelMatch {
                    rendered: [x, y],
                    target: q.pixel,
                    confidence: 0.9,
                    kind: MatchKind::Point,
                });
            }
        }
        out
    }
}

#[test]
fn lift_turns_oracle_pairs_into_true_correspondences() {
    let cam = camera();
    let mesh = box_mesh([-0.4, 0.0, -0.3], [0.4, 0.8, 0.3]);
    let truth = Pose::new(1.0, 0.3, Vector3::new(0.1, 0.0, -0.2));
    let start = Pose::new(1.0, 0.1, Vector3::new(0.25, 0.0, -0.1));
    let (mask, depth) = guidance(&cam, &[(&mesh, truth)]);
    let target = TargetRegion {
        camera: &cam,
        mask: &mask,
        depth: Some(&depth),
        image: None,
    };
    let view = rasterize(&mesh, &start, &cam, Window::full(&cam));
    let oracle: &dyn Matcher = &Oracle { truth };
    let pairs = lift(&oracle.match_view(&view, &target), &view, &target);
    assert!(pairs.len() > 100, "{}", pairs.len());
    let mut good = 0;
    for c in &pairs {
        assert_eq!(c.kind, PairKind::Point);
        let world = truth.transform_point(&c.asset_point);
        let pixel = cam.project(&world).unwrap().pixel;
        assert!((pixel - c.target_pixel).norm() < 1e-6);
        // Where the true point is visible, the lifted target point is that point.
        if let Some(t) = c.target_point {
            if (t - world).norm() < 0.02 {
                good += 1;
            }
        }
    }
    assert!(good * 2 > pairs.len(), "{good} of {}", pairs.len());
}

#[test]
fn shape_matcher_pairs_silhouettes_and_depths_and_ignores_occluded_pixels() {
    let cam = camera();
    let mesh = box_mesh([-0.4, 0.0, -0.3], [0.4, 0.8, 0.3]);
    let truth = Pose::new(1.0, 0.0, Vector3::zeros());
    // A wall in front of the right half of the object, nearer to the camera.
    let wall = box_mesh([0.0, 0.0, 0.0], [1.0, 1.0, 0.05]);
    let wall_pose = Pose::new(1.0, 0.0, Vector3::new(0.1, 0.0, 1.2));
    let (mask, depth) = guidance(&cam, &[(&mesh, truth), (&wall, wall_pose)]);
    let target = TargetRegion {
        camera: &cam,
        mask: &mask,
        depth: Some(&depth),
        image: None,
    };
    let matcher = ShapeMatcher::default();
    // At the true pose, the only silhouette disagreement would be the hidden part, which is
    // ignored: no silhouette pairs, and every depth pair is an inlier at zero difference.
    let view = rasterize(&mesh, &truth, &cam, Window::full(&cam));
    let at_truth = matcher.match_view(&view, &target);
    assert!(at_truth.iter().all(|m| m.kind != MatchKind::Silhouette));
    assert!(at_truth.iter().all(|m| m.confidence == 1.0));
    let score = scenethesis_correspondence::shape::shape_score(&view, &target, &matcher);
    assert!(
        score.iou > 0.99 && score.depth_agreement > 0.99,
        "{score:?}"
    );
    // Shifted left, the render leaves mask pixels uncovered: silhouette pairs pull it right.
    let shifted = Pose::new(1.0, 0.0, Vector3::new(-0.15, 0.0, 0.0));
    let view = rasterize(&mesh, &shifted, &cam, Window::full(&cam));
    let pairs = lift(&matcher.match_view(&view, &target), &view, &target);
    let sil: Vec<_> = pairs.iter().filter(|c| c.target_point.is_none()).collect();
    assert!(!sil.is_empty());
    let mean_du: f64 = sil
        .iter()
        .map(|c| {
            let now = cam
                .project(&shifted.transform_point(&c.asset_point))
                .unwrap()
                .pixel;
            c.target_pixel.x - now.x
        })
        .sum::<f64>()
        / sil.len() as f64;
    assert!(
        mean_du > 1.0,
        "silhouette pairs should pull right, got {mean_du}"
    );
    assert!(pairs.iter().any(|c| c.kind == PairKind::Depth));
}

#[test]
fn yaw_search_finds_the_yaw_and_a_hint_settles_front_and_back() {
    let cam = camera();
    let mesh = l_mesh();
    let truth = Pose::new(1.0, 0.6, Vector3::new(0.0, 0.0, 0.0));
    let (mask, depth) = guidance(&cam, &[(&mesh, truth)]);
    let target = TargetRegion {
        camera: &cam,
        mask: &mask,
        depth: Some(&depth),
        image: None,
    };
    let window = Window::full(&cam);
    let yaws: Vec<f64> = (0..24).map(|k| k as f64 * 15f64.to_radians()).collect();
    let matcher = ShapeMatcher::default();
    let cands = search_yaw(&mesh, &truth, &cam, &target, window, &yaws, &matcher);
    let best = pick_yaw(&cands, None, 0.0).unwrap();
    assert!(
        yaw_distance(best.pose.yaw, 0.6) < 10f64.to_radians(),
        "{}",
        best.pose.yaw
    );
    // Without depth the silhouette of a symmetric box cannot tell front from back: a hint does.
    let plain = box_mesh([-1.0, 0.0, -0.4], [1.0, 0.8, 0.4]);
    let (mask, _) = guidance(&cam, &[(&plain, truth)]);
    let target = TargetRegion {
        camera: &cam,
        mask: &mask,
        depth: None,
        image: None,
    };
    let cands = search_yaw(&plain, &truth, &cam, &target, window, &yaws, &matcher);
    let flipped = 0.6 + std::f64::consts::PI;
    let hinted = pick_yaw(&cands, Some(flipped), 0.02).unwrap();
    assert!(yaw_distance(hinted.pose.yaw, flipped) < 10f64.to_radians());
}
