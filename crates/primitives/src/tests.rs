//! Closedness, volume, convexity and winding of the building blocks, and the builder's
//! normalisation.

use nalgebra::Vector3;
use rand::Rng;
use scenethesis_scene_graph::{Material, MeshPart, Placement, SurfaceKind};

use crate::*;

fn check(part: &MeshPart, volume: f64, tol: f64) {
    assert!(
        part.is_closed_and_oriented(),
        "{} is not closed and oriented",
        part.name
    );
    let v = part.signed_volume();
    assert!(
        (v - volume).abs() <= tol * volume,
        "{}: volume {v}, expected {volume}",
        part.name
    );
}

#[test]
fn primitives_are_closed_outward_and_have_the_right_volume() {
    use std::f64::consts::PI;
    check(
        &cuboid("box", 0, [0.0, 0.0, 0.0], [1.0, 2.0, 3.0]),
        6.0,
        1e-6,
    );
    let post = square_post("post", 0, [1.0, 2.0], 0.2, 0.5, 3.5);
    check(&post, 0.12, 1e-5);
    assert_eq!(post.positions[0], [0.9, 0.5, 1.9]);
    check(
        &cylinder("cyl", 0, [0.5, 0.5], 0.5, 0.0, 2.0, 64),
        PI * 0.25 * 2.0,
        0.01,
    );
    check(
        &frustum("cone", 0, [0.0, 0.0], 1.0, 0.0, 0.0, 3.0, 128),
        PI,
        0.01,
    );
    check(
        &frustum("cone_down", 0, [0.0, 0.0], 0.0, 1.0, 0.0, 3.0, 128),
        PI,
        0.01,
    );
    check(
        &sphere("ball", 0, [0.0, 1.0, 0.0], 1.0, 48, 96),
        4.0 / 3.0 * PI,
        0.01,
    );
    check(
        &box_yaw("turned", 0, [1.0, 2.0], [0.5, 1.0], 0.0, 3.0, 0.7),
        6.0,
        1e-5,
    );
    check(
        &beam("bar", 0, [0.0, 0.0, 0.0], [1.0, 2.0, 2.0], [0.1, 0.2]),
        0.06,
        1e-5,
    );
    check(
        &strut("strut", 0, [0.0, 0.0, 0.0], [0.3, 2.0, -0.2], [0.1, 0.2]),
        0.04,
        1e-5,
    );
    check(
        &rod("rod", 0, [0.0, 0.0, 0.0], [0.0, 0.0, -2.0], 0.5, 0.5, 128),
        PI * 0.25 * 2.0,
        0.01,
    );
    let square = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]];
    check(&prism_y("py", 0, &square, 0.0, 2.0), 2.0, 1e-6);
    check(&prism_x("px", 0, &square, 1.0, 0.0), 1.0, 1e-6);
    check(&prism_z("pz", 0, &square, 0.0, 3.0), 3.0, 1e-6);
    let wedge = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [1.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
        [1.0, 0.0, 1.0],
        [0.0, 0.5, 1.0],
        [1.0, 0.5, 1.0],
    ];
    check(&hexahedron("wedge", 0, wedge), 0.75, 1e-6);
    let mut mirrored = wedge;
    mirrored.swap(0, 1);
    mirrored.swap(2, 3);
    mirrored.swap(4, 5);
    mirrored.swap(6, 7);
    check(&hexahedron("mirrored", 0, mirrored), 0.75, 1e-6);
}

fn is_convex(part: &MeshPart) -> bool {
    part.triangles.iter().all(|t| {
        let [a, b, c] = t.map(|i| Vector3::from(part.positions[i as usize]).cast::<f64>());
        let n = (b - a).cross(&(c - a));
        part.positions.iter().all(|p| {
            n.dot(&(Vector3::from(*p).cast::<f64>() - a)) <= 1e-9 * n.norm().max(1e-12) + 1e-7
        })
    })
}

#[test]
fn builders_make_closed_outward_convex_parts() {
    let parts = [
        ring_slab(
            "slab",
            0,
            [0.0, 0.0],
            0.0,
            0.7,
            (0.03, 0.04, 0.0),
            (0.05, 0.06, 0.1),
        ),
        tube("tube", 0, [0.1, 0.2, 0.3], [0.5, 0.1, -0.4], 0.03, 0.02, 12),
        rotated_box(
            "box",
            0,
            [1.0, 0.0, 0.0],
            [0.1, 0.2, 0.3],
            &rotation([1.0, 1.0, 0.0], 0.6),
        ),
        rotated_ellipsoid(
            "ell",
            0,
            [0.0, 1.0, 0.0],
            [0.3, 0.05, 0.1],
            &rotation([0.0, 0.0, 1.0], 0.4),
        ),
    ];
    for part in &parts {
        assert!(part.is_closed_and_oriented(), "{}", part.name);
        assert!(part.signed_volume() > 0.0, "{}", part.name);
        assert!(is_convex(part), "{} is not convex", part.name);
    }
}

#[test]
fn convex_hull_of_random_points_is_closed_convex_and_contains_them() {
    use rand::SeedableRng;
    let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(7);
    let points: Vec<[f32; 3]> = (0..40)
        .map(|_| {
            [
                rng.random_range(-1.0..=1.0),
                rng.random_range(0.0..=0.5),
                rng.random_range(-0.3..=0.3),
            ]
        })
        .collect();
    let hull = convex_hull("rock", 0, &points).unwrap();
    assert!(hull.is_closed_and_oriented());
    assert!(is_convex(&hull));
    let cube: Vec<[f32; 3]> = (0..8)
        .map(|i| [(i & 1) as f32, ((i >> 1) & 1) as f32, ((i >> 2) & 1) as f32])
        .collect();
    let hull = convex_hull("cube", 0, &cube).unwrap();
    assert!((hull.signed_volume() - 1.0).abs() < 1e-6);
    assert!(convex_hull(
        "flat",
        0,
        &[[0.0; 3], [1.0, 0.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 1.0]]
    )
    .is_none());
}

#[test]
fn polygons_wind_counter_clockwise_seen_from_above() {
    // Counter-clockwise seen from +Y is negative in the (x, z) shoelace sum.
    for poly in [
        rect(-1.0, -1.0, 1.0, 2.0),
        regular_polygon([0.0, 0.0], 1.0, 12),
    ] {
        let n = poly.len();
        let twice: f32 = (0..n)
            .map(|i| poly[i][0] * poly[(i + 1) % n][1] - poly[(i + 1) % n][0] * poly[i][1])
            .sum();
        assert!(twice < 0.0);
    }
}

#[test]
fn builder_moves_the_footprint_centre_to_the_origin() {
    let mut b = AssetBuilder::new();
    let material = || Material {
        name: "m".into(),
        base_color: [0.1, 0.2, 0.3, 1.0],
        roughness: 0.5,
        metallic: 0.0,
        texture: None,
    };
    let m = b.material(material());
    assert_eq!(b.material(material()), m);
    b.cuboid("slab", m, [1.0, 2.0, 3.0], [3.0, 2.5, 4.0]);
    b.surface(rect_surface(
        "top",
        SurfaceKind::Top,
        [1.0, 3.0],
        [3.0, 4.0],
        2.5,
        None,
        0.1,
    ));
    let asset = b.finish(Placement::Floor, [0.9, 1.1]);
    assert_eq!(asset.info.size, [2.0, 0.5, 1.0]);
    let top = &asset.info.support_surfaces[0];
    assert_eq!(top.height, 0.5);
    assert!((top.area() - 1.8 * 0.8).abs() < 1e-5);
    let [cx, cz] = top.center();
    assert!(cx.abs() < 1e-6 && cz.abs() < 1e-6, "centre {cx} {cz}");
    let bounds = asset.mesh.bounds().unwrap();
    assert_eq!(bounds.min.y, 0.0);
    assert_eq!(bounds.min.x, -1.0);
}
