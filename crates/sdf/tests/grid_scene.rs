//! Baked grids (error bound against the exact field) and scene queries (poses, exclusion).

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use proptest::prelude::*;
use scenethesis_sdf::{
    sampling, shapes, BoxSdf, GridSdf, MeshSdf, PlaneSdf, Pose, SceneSdf, SignedDistance, SphereSdf,
};

fn torus_sdf() -> MeshSdf {
    let (p, t) = shapes::torus(0.3, 0.1, 32, 16);
    MeshSdf::new(&p, &t).unwrap()
}

#[test]
fn default_resolution_follows_object_size() {
    assert!(GridSdf::default_cell_size(0.49) <= 0.01);
    assert!((GridSdf::default_cell_size(0.64) - 0.01).abs() < 1e-6);
    assert!((GridSdf::default_cell_size(2.0) - 0.02).abs() < 1e-6);
    assert!((GridSdf::default_cell_size(10.0) - 10.0 / 256.0).abs() < 1e-6);
    // A 40 cm torus gets cells under 1 cm.
    let (p, t) = shapes::torus(0.15, 0.05, 32, 16);
    let sdf = MeshSdf::new(&p, &t).unwrap();
    let grid = GridSdf::bake(&sdf, None);
    assert!(grid.cell_size() <= 0.01, "{}", grid.cell_size());
    let coarse = GridSdf::bake(&sdf, Some(0.03));
    assert_eq!(
        coarse.cell_size(),
        grid.cell_size(),
        "max_cell only refines"
    );
    let fine = GridSdf::bake(&sdf, Some(0.004));
    assert_eq!(fine.cell_size(), 0.004);
}

#[test]
fn bake_is_deterministic_across_thread_counts() {
    let sdf = torus_sdf();
    let one = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let two = rayon::ThreadPoolBuilder::new()
        .num_threads(2)
        .build()
        .unwrap();
    let a = one.install(|| GridSdf::bake_with_cell(&sdf, 0.02));
    let b = two.install(|| GridSdf::bake_with_cell(&sdf, 0.02));
    assert_eq!(a.values(), b.values());
}

#[test]
fn a_bake_on_the_calling_thread_is_the_parallel_bake() {
    let sdf = torus_sdf();
    let parallel = GridSdf::bake(&sdf, Some(0.02));
    let serial = GridSdf::bake_on_this_thread(&sdf, Some(0.02));
    assert_eq!(serial.cell_size(), parallel.cell_size());
    assert_eq!(serial.values(), parallel.values());
    assert_eq!(serial.local_bounds(), sdf.local_bounds());
}

fn baked() -> &'static (MeshSdf, GridSdf) {
    static CELL: std::sync::OnceLock<(MeshSdf, GridSdf)> = std::sync::OnceLock::new();
    CELL.get_or_init(|| {
        let sdf = torus_sdf();
        let grid = GridSdf::bake_with_cell(&sdf, 0.02);
        (sdf, grid)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn grid_error_is_within_a_cell_diagonal_near_the_surface(x in -0.5f32..0.5, y in -0.2f32..0.2, z in -0.5f32..0.5) {
        let (sdf, grid) = baked();
        let p = Point3::new(x, y, z);
        let exact = sdf.distance(&p);
        let approx = grid.distance(&p);
        let diag = grid.cell_diagonal();
        if exact.abs() <= diag {
            prop_assert!((approx - exact).abs() <= diag * 1.0001, "{} vs {}", approx, exact);
        } else {
            prop_assert_eq!(approx < 0.0, exact < 0.0, "sign at {:?}: {} vs {}", p, approx, exact);
        }
        // The grid gradient points outward like the exact one, away from the medial axes (the
        // tube's centre circle at depth 0.1, the hole's axis 0.2 out).
        if exact.abs() > diag && exact.abs() < 0.05 {
            let g = grid.gradient(&p);
            prop_assert!(g.dot(&sdf.gradient(&p)) > 0.8);
        }
    }

    #[test]
    fn grid_is_conservative_outside_its_box(x in 1.0f32..3.0, y in -2.0f32..2.0, z in -2.0f32..2.0) {
        let (sdf, grid) = baked();
        let p = Point3::new(x, y, z);
        prop_assert!(grid.distance(&p) >= sdf.distance(&p) - 1e-4);
        prop_assert!(grid.distance(&p) > 0.0);
    }

    #[test]
    fn moved_object_equals_original_at_inverse_moved_point(
        scale in 0.3f64..3.0, yaw in -3.2f64..3.2, tx in -2.0f64..2.0, ty in -1.0f64..1.0, tz in -2.0f64..2.0,
        x in -3.0f32..3.0, y in -2.0f32..2.0, z in -3.0f32..3.0,
    ) {
        let field: Arc<dyn SignedDistance> = Arc::new(BoxSdf::new(Vector3::new(0.4, 0.2, 0.3)));
        let pose = Pose::new(scale, yaw, Vector3::new(tx, ty, tz));
        let mut scene = SceneSdf::new();
        scene.insert("box", field.clone(), pose);
        let p = Point3::new(x, y, z);
        let local = pose.inverse_transform_point(&p.cast()).cast::<f32>();
        let expected = scale as f32 * field.distance(&local);
        let got = scene.distance(&p, &[]);
        prop_assert!((got - expected).abs() < 1e-4 * (1.0 + expected.abs()), "{} vs {}", got, expected);
        // The world gradient is the rotated local gradient.
        let q = scene.query(&p, &[]).unwrap();
        let lg = field.gradient(&local);
        let wg = pose.transform_vector(&lg.cast()).cast::<f32>();
        prop_assert!((q.gradient - wg).norm() < 1e-4);
    }

    #[test]
    fn scene_distance_is_min_over_included_objects(x in -3.0f32..3.0, y in -1.0f32..2.0, z in -3.0f32..3.0) {
        let scene = three_objects();
        let p = Point3::new(x, y, z);
        let each: Vec<f32> = ["a", "b", "floor"].iter().map(|id| scene.distance_to(id, &p).unwrap()).collect();
        let all = scene.distance(&p, &[]);
        prop_assert!((all - each.iter().cloned().fold(f32::INFINITY, f32::min)).abs() < 1e-6);
        let without_a = scene.distance(&p, &["a"]);
        prop_assert!((without_a - each[1].min(each[2])).abs() < 1e-6);
        let (id, d) = scene.nearest(&p, &["floor"]).unwrap();
        prop_assert_eq!(d, each[0].min(each[1]));
        prop_assert_eq!(id, if each[0] <= each[1] { "a" } else { "b" });
    }
}

fn three_objects() -> SceneSdf {
    let mut scene = SceneSdf::new();
    scene.insert("floor", Arc::new(PlaneSdf), Pose::IDENTITY);
    scene.insert(
        "a",
        Arc::new(SphereSdf::new(0.5)),
        Pose::new(1.0, 0.0, Vector3::new(-1.0, 0.5, 0.0)),
    );
    let (p, t) = shapes::cuboid(Vector3::new(0.3, 0.3, 0.3));
    scene.insert(
        "b",
        Arc::new(MeshSdf::new(&p, &t).unwrap()),
        Pose::new(2.0, 0.7, Vector3::new(1.0, 0.6, 0.5)),
    );
    scene
}

#[test]
fn set_pose_moves_without_rebaking_and_batches_match() {
    let mut scene = three_objects();
    let before = scene.field("b").unwrap().clone();
    let p = Point3::new(2.5, 0.6, 0.5);
    let d0 = scene.distance(&p, &["floor"]);
    scene
        .set_pose("b", Pose::new(2.0, 0.7, Vector3::new(2.5, 0.6, 0.5)))
        .unwrap();
    assert!(Arc::ptr_eq(&before, scene.field("b").unwrap()));
    let d1 = scene.distance(&p, &["floor"]);
    assert!(d1 < 0.0 && d0 > 0.0, "{d0} → {d1}");
    assert!(scene.set_pose("nope", Pose::IDENTITY).is_err());
    assert!(scene
        .set_pose("b", Pose::new(0.0, 0.0, Vector3::zeros()))
        .is_err());

    let points: Vec<Point3<f32>> = (0..500)
        .map(|i| {
            Point3::new(
                (i % 10) as f32 * 0.4 - 2.0,
                (i / 100) as f32 * 0.3,
                ((i / 10) % 10) as f32 * 0.4 - 2.0,
            )
        })
        .collect();
    let batch = scene.distances(&points, &["a"]);
    for (p, d) in points.iter().zip(&batch) {
        assert_eq!(*d, scene.distance(p, &["a"]));
    }
    scene.remove("a");
    scene.remove("b");
    scene.remove("floor");
    assert!(scene.is_empty());
    assert_eq!(scene.distance(&p, &[]), f32::INFINITY);
    assert!(scene.nearest(&p, &[]).is_none());
}

#[test]
fn penetrating_surface_points_cluster_per_contact() {
    // A bar resting across two boxes that it sinks into: two separate penetration regions.
    let (p, t) = shapes::cuboid(Vector3::new(1.0, 0.05, 0.05));
    let mesh = scenethesis_sdf::Mesh {
        parts: vec![scenethesis_scene_graph::MeshPart {
            name: "bar".into(),
            material: 0,
            positions: p,
            triangles: t,
            joint: None,
            uvs: None,
        }],
        materials: vec![],
    };
    let points = sampling::surface_points(&mesh, 2000, 3);
    let mut scene = SceneSdf::new();
    let block: Arc<dyn SignedDistance> = Arc::new(BoxSdf::new(Vector3::new(0.1, 0.5, 0.5)));
    scene.insert(
        "left",
        block.clone(),
        Pose::new(1.0, 0.0, Vector3::new(-0.8, -0.48, 0.0)),
    );
    scene.insert(
        "right",
        block,
        Pose::new(1.0, 0.0, Vector3::new(0.8, -0.48, 0.0)),
    );
    let d = scene.distances(&points, &[]);
    let clusters = sampling::negative_clusters(&points, &d, 0.05);
    assert_eq!(clusters.len(), 2);
    for c in &clusters {
        assert!(c.iter().all(|&i| d[i] < 0.0));
    }
}

fn table_mesh() -> scenethesis_sdf::Mesh {
    let part = |name: &str, h: Vector3<f32>, at: Vector3<f32>| {
        let (p, t) = shapes::cuboid(h);
        scenethesis_scene_graph::MeshPart {
            name: name.into(),
            material: 0,
            positions: p.iter().map(|v| (Vector3::from(*v) + at).into()).collect(),
            triangles: t,
            joint: None,
            uvs: None,
        }
    };
    let mut parts = vec![part(
        "top",
        Vector3::new(0.3, 0.02, 0.2),
        Vector3::new(0.0, 0.38, 0.0),
    )];
    for (i, (x, z)) in [(-0.25, -0.15), (0.25, -0.15), (-0.25, 0.15), (0.25, 0.15)]
        .into_iter()
        .enumerate()
    {
        parts.push(part(
            &format!("leg_{i}"),
            Vector3::new(0.02, 0.2, 0.02),
            Vector3::new(x, 0.2, z),
        ));
    }
    scenethesis_sdf::Mesh {
        parts,
        materials: vec![],
    }
}

fn baked_table() -> &'static (MeshSdf, GridSdf) {
    static CELL: std::sync::OnceLock<(MeshSdf, GridSdf)> = std::sync::OnceLock::new();
    CELL.get_or_init(|| {
        let sdf = MeshSdf::from_mesh(&table_mesh()).unwrap();
        let grid = GridSdf::bake(&sdf, None);
        (sdf, grid)
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    #[test]
    fn grid_of_overlapping_parts_keeps_bound_and_sign(x in -0.4f32..0.4, y in -0.05f32..0.45, z in -0.3f32..0.3) {
        let (sdf, grid) = baked_table();
        prop_assert!(grid.cell_size() <= 0.01);
        let p = Point3::new(x, y, z);
        let exact = sdf.distance(&p);
        let approx = grid.distance(&p);
        let diag = grid.cell_diagonal();
        if exact.abs() <= diag {
            prop_assert!((approx - exact).abs() <= diag * 1.0001, "{} vs {}", approx, exact);
        } else {
            prop_assert_eq!(approx < 0.0, exact < 0.0, "sign at {:?}: {} vs {}", p, approx, exact);
        }
    }
}
