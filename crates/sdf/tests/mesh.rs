//! Exact mesh signed distance: analytic shapes, union of overlapping parts, holes, gradients.

use nalgebra::{Point3, Vector3};
use proptest::prelude::*;
use scenethesis_scene_graph::{Material, Mesh, MeshPart};
use scenethesis_sdf::{shapes, BoxSdf, MeshSdf, SignRule, SignedDistance};

fn cube_sdf(h: Vector3<f32>) -> MeshSdf {
    let (p, t) = shapes::cuboid(h);
    MeshSdf::new(&p, &t).unwrap()
}

fn part(
    name: &str,
    (positions, triangles): shapes::TriangleMesh,
    offset: Vector3<f32>,
) -> MeshPart {
    MeshPart {
        name: name.into(),
        material: 0,
        positions: positions
            .iter()
            .map(|p| (Vector3::from(*p) + offset).into())
            .collect(),
        triangles,
        joint: None,
        uvs: None,
    }
}

/// Brute-force winding number (sum of exact solid angles over every triangle).
fn brute_winding(positions: &[[f32; 3]], triangles: &[[u32; 3]], p: &Point3<f32>) -> f64 {
    let mut sum = 0.0f64;
    for t in triangles {
        let [a, b, c] =
            t.map(|i| Vector3::from(positions[i as usize]).cast::<f64>() - p.coords.cast::<f64>());
        let (la, lb, lc) = (a.norm(), b.norm(), c.norm());
        let det = a.dot(&b.cross(&c));
        let den = la * lb * lc + a.dot(&b) * lc + a.dot(&c) * lb + b.dot(&c) * la;
        sum += 2.0 * det.atan2(den);
    }
    sum / (4.0 * std::f64::consts::PI)
}

/// Brute-force unsigned distance in f64: the smallest point–triangle distance over all
/// triangles (projection onto the plane when it falls inside, else the nearest edge).
fn brute_distance(positions: &[[f32; 3]], triangles: &[[u32; 3]], p: &Point3<f32>) -> f64 {
    type V = Vector3<f64>;
    let p = p.coords.cast::<f64>();
    let segment = |a: V, b: V| {
        let ab = b - a;
        let t = ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0);
        (p - (a + ab * t)).norm()
    };
    triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|i| Vector3::from(positions[i as usize]).cast::<f64>());
            let n = (b - a).cross(&(c - a));
            let q = p - n * ((p - a).dot(&n) / n.norm_squared());
            let inside = [(a, b), (b, c), (c, a)]
                .iter()
                .all(|(u, w)| (w - u).cross(&(q - u)).dot(&n) >= 0.0);
            if inside {
                (p - q).norm()
            } else {
                segment(a, b).min(segment(b, c)).min(segment(c, a))
            }
        })
        .fold(f64::INFINITY, f64::min)
}

fn table() -> Mesh {
    // A top slab and four legs that poke into it.
    let mut parts = vec![part(
        "top",
        shapes::cuboid(Vector3::new(0.6, 0.03, 0.4)),
        Vector3::new(0.0, 0.72, 0.0),
    )];
    for (i, (x, z)) in [(-0.5, -0.3), (0.5, -0.3), (-0.5, 0.3), (0.5, 0.3)]
        .iter()
        .enumerate()
    {
        parts.push(part(
            &format!("leg_{i}"),
            shapes::cuboid(Vector3::new(0.03, 0.37, 0.03)),
            Vector3::new(*x, 0.37, *z),
        ));
    }
    Mesh {
        parts,
        materials: vec![Material::new("wood", [0.5, 0.3, 0.1], 0.7)],
    }
}

#[test]
fn closed_cube_is_signed_by_pseudo_normals() {
    let sdf = cube_sdf(Vector3::new(0.5, 0.5, 0.5));
    assert_eq!(sdf.sign_rules(), vec![SignRule::PseudoNormal]);
    assert!((sdf.distance(&Point3::origin()) + 0.5).abs() < 1e-6);
    assert!((sdf.distance(&Point3::new(1.5, 0.0, 0.0)) - 1.0).abs() < 1e-6);
    // Corner region: nearest feature is a vertex.
    let d = sdf.distance(&Point3::new(1.5, 1.5, 1.5));
    assert!((d - 3f32.sqrt()).abs() < 1e-5, "{d}");
    let q = sdf.query(&Point3::new(0.0, 0.2, 0.45));
    assert!((q.distance + 0.05).abs() < 1e-6);
    assert!((q.gradient - Vector3::z()).norm() < 1e-5);
    assert!((q.closest_point - Point3::new(0.0, 0.2, 0.5)).norm() < 1e-6);
}

#[test]
fn overlapping_parts_form_a_union() {
    let mesh = table();
    let sdf = MeshSdf::from_mesh(&mesh).unwrap();
    assert_eq!(sdf.sign_rules().len(), 5);
    // Inside a leg just below the top slab, where the slab's bottom face is closer than any
    // leg face: still inside.
    let p = Point3::new(-0.5, 0.685, -0.3);
    let d = sdf.distance(&p);
    assert!(d < 0.0, "inside leg under the top: {d}");
    // Inside the overlap of leg and top.
    assert!(sdf.distance(&Point3::new(0.5, 0.71, 0.3)) < 0.0);
    // Between legs, under the top: outside, 0.69 − 0.4 = 0.29 below the slab.
    let d = sdf.distance(&Point3::new(0.0, 0.4, 0.0));
    assert!((d - 0.29).abs() < 1e-5, "{d}");
    // Merged into one triangle list it still works (components are found by connectivity).
    let (p2, t2) = mesh.merged();
    let merged = MeshSdf::new(&p2, &t2).unwrap();
    assert!(merged.distance(&p) < 0.0);
    assert_eq!(merged.sign_rules().len(), 5);
}

#[test]
fn only_closed_solids_promise_a_lipschitz_distance() {
    let (p, mut t) = shapes::bumpy_sphere(0.5, 0.0, 24, 12);
    assert!(MeshSdf::new(&p, &t).unwrap().is_lipschitz());
    assert!(MeshSdf::from_mesh(&table()).unwrap().is_lipschitz());
    t.remove(100);
    // A holed mesh is signed by its winding number, which may flip away from the surface.
    assert!(!MeshSdf::new(&p, &t).unwrap().is_lipschitz());
    assert!(BoxSdf::new(Vector3::new(1.0, 1.0, 1.0)).is_lipschitz());
}

#[test]
fn mesh_with_small_hole_keeps_its_inside() {
    let (p, mut t) = shapes::bumpy_sphere(0.5, 0.0, 24, 12);
    t.remove(100); // punch a hole
    let sdf = MeshSdf::new(&p, &t).unwrap();
    assert_eq!(sdf.sign_rules(), vec![SignRule::WindingNumber]);
    assert!(sdf.distance(&Point3::origin()) < -0.45);
    assert!(sdf.distance(&Point3::new(0.0, 0.2, 0.1)) < 0.0);
    assert!(sdf.distance(&Point3::new(0.9, 0.0, 0.0)) > 0.35);
}

#[test]
fn bad_input_is_rejected_with_context() {
    let err = MeshSdf::new(&[[0.0; 3]; 3], &[[0, 1, 5]]).unwrap_err();
    assert!(err.to_string().contains("vertex 5"), "{err}");
    let err = MeshSdf::new(
        &[[0.0; 3], [1.0, 0.0, 0.0], [f32::NAN, 0.0, 0.0]],
        &[[0, 1, 2]],
    )
    .unwrap_err();
    assert!(err.to_string().contains("non-finite"), "{err}");
    assert!(MeshSdf::new(&[[0.0; 3]; 3], &[[0, 0, 1]]).is_err());
    // Non-finite query points give NaN, not a panic.
    let sdf = cube_sdf(Vector3::new(0.5, 0.5, 0.5));
    assert!(sdf
        .query(&Point3::new(f32::NAN, 0.0, 0.0))
        .distance
        .is_nan());
    assert!(!sdf
        .distance(&Point3::new(f32::INFINITY, 0.0, 0.0))
        .is_finite());
}

fn sphere() -> MeshSdf {
    let (p, t) = shapes::bumpy_sphere(1.0, 0.0, 48, 24);
    MeshSdf::new(&p, &t).unwrap()
}

fn bumpy_sphere() -> &'static MeshSdf {
    static SDF: std::sync::OnceLock<MeshSdf> = std::sync::OnceLock::new();
    SDF.get_or_init(|| {
        let (p, t) = shapes::bumpy_sphere(0.5, 0.15, 40, 21);
        MeshSdf::new(&p, &t).unwrap()
    })
}

fn coord() -> impl Strategy<Value = f32> {
    -1.5f32..1.5
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(64))]

    #[test]
    fn box_mesh_matches_analytic_box(x in coord(), y in coord(), z in coord()) {
        let h = Vector3::new(0.4, 0.7, 0.25);
        let mesh = cube_sdf(h);
        let exact = BoxSdf::new(h);
        let p = Point3::new(x, y, z);
        prop_assert!((mesh.distance(&p) - exact.distance(&p)).abs() < 1e-5);
    }

    #[test]
    fn sphere_mesh_matches_distance_to_its_triangles(x in coord(), y in coord(), z in coord()) {
        // A flat-faced sphere is not a sphere: compare to the polyhedron's exact distance,
        // brute-forced, and to the analytic ball within the faceting error.
        let (positions, triangles) = shapes::bumpy_sphere(1.0, 0.0, 48, 24);
        let sdf = sphere();
        let p = Point3::new(x, y, z);
        let d = sdf.distance(&p);
        let inside = brute_winding(&positions, &triangles, &p) > 0.5;
        prop_assert_eq!(d < 0.0, inside);
        let analytic = p.coords.norm() - 1.0;
        prop_assert!((d - analytic).abs() < 0.01, "{} vs {}", d, analytic);
        let exact = brute_distance(&positions, &triangles, &p);
        prop_assert!((d.abs() as f64 - exact).abs() < 1e-5, "{} vs brute force {}", d, exact);
    }

    #[test]
    fn bumpy_sphere_matches_brute_force(x in -0.8f32..0.8, y in -0.8f32..0.8, z in -0.8f32..0.8) {
        // Non-convex: exact distance and sign against brute force over every triangle.
        let (positions, triangles) = shapes::bumpy_sphere(0.5, 0.15, 40, 21);
        let sdf = bumpy_sphere();
        let p = Point3::new(x, y, z);
        let d = sdf.distance(&p);
        let exact = brute_distance(&positions, &triangles, &p);
        prop_assert!((d.abs() as f64 - exact).abs() < 1e-5, "{} vs brute force {}", d, exact);
        prop_assume!(exact > 1e-4);
        let inside = brute_winding(&positions, &triangles, &p) > 0.5;
        prop_assert_eq!(d < 0.0, inside);
    }

    #[test]
    fn sign_matches_brute_force_winding_number(x in coord(), y in -0.2f32..1.2, z in coord()) {
        let mesh = table();
        let sdf = MeshSdf::from_mesh(&mesh).unwrap();
        let p = Point3::new(x * 0.5, y, z * 0.4);
        let inside = mesh.parts.iter().any(|part| brute_winding(&part.positions, &part.triangles, &p) > 0.5);
        prop_assert_eq!(sdf.distance(&p) < 0.0, inside);
    }

    #[test]
    fn surface_within_agrees_with_the_brute_force_distance(
        x in -0.8f32..0.8, y in -0.8f32..0.8, z in -0.8f32..0.8, radius in 0.0005f32..0.2,
    ) {
        let (positions, triangles) = shapes::bumpy_sphere(0.5, 0.15, 40, 21);
        let p = Point3::new(x, y, z);
        let exact = brute_distance(&positions, &triangles, &p);
        // Points within rounding of the radius may go either way.
        prop_assume!((exact - f64::from(radius)).abs() > 1e-5);
        prop_assert_eq!(
            bumpy_sphere().surface_within(&p, radius),
            Some(exact < f64::from(radius)),
            "{} from the surface, radius {}", exact, radius
        );
    }

    #[test]
    fn is_one_lipschitz(x in coord(), y in coord(), z in coord(), dx in -0.3f32..0.3, dy in -0.3f32..0.3, dz in -0.3f32..0.3) {
        let sdf = MeshSdf::from_mesh(&table()).unwrap();
        let p = Point3::new(x, y, z);
        let q = p + Vector3::new(dx, dy, dz);
        prop_assert!((sdf.distance(&p) - sdf.distance(&q)).abs() <= (p - q).norm() + 1e-5);
    }

    #[test]
    fn gradient_points_away_from_surface(x in coord(), y in coord(), z in coord()) {
        let sdf = sphere();
        let p = Point3::new(x, y, z);
        let q = sdf.query(&p);
        prop_assume!(q.distance.abs() > 1e-3);
        prop_assert!((q.gradient.norm() - 1.0).abs() < 1e-4);
        // One small step along the gradient increases the distance by about the step.
        let step = 1e-3;
        let d2 = sdf.distance(&(p + q.gradient * step));
        prop_assert!(d2 > q.distance + 0.5 * step, "{} -> {}", q.distance, d2);
        // Closest point lies at |distance| from p.
        prop_assert!(((q.closest_point - p).norm() - q.distance.abs()).abs() < 1e-5);
    }
}
