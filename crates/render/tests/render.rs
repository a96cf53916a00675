//! Real renders on whatever adapter the machine offers (GL llvmpipe in CI).

use std::path::PathBuf;
use std::sync::{Arc, OnceLock};

use nalgebra::{Point2, Point3, Vector3};
use scenethesis_imagery::{Camera, Intrinsics};
use scenethesis_render::{views, Frame, Instance, RenderScene, Renderer, RendererOptions};
use scenethesis_scene_graph::{convex_hull, Architecture, Material, Mesh, MeshPart, Pose};

fn renderer() -> &'static Renderer {
    static RENDERER: OnceLock<Renderer> = OnceLock::new();
    RENDERER.get_or_init(|| {
        let r = Renderer::from_env().expect("a graphics adapter (Mesa llvmpipe in CI)");
        eprintln!("rendering on {}", r.adapter_description());
        r
    })
}

/// A closed cylinder along +Y standing on y = 0.
fn cylinder(name: &str, material: usize, radius: f32, height: f32, segments: u32) -> MeshPart {
    let mut positions = vec![[0.0, 0.0, 0.0], [0.0, height, 0.0]];
    for i in 0..segments {
        let a = std::f32::consts::TAU * i as f32 / segments as f32;
        let (x, z) = (radius * a.cos(), -radius * a.sin());
        positions.push([x, 0.0, z]);
        positions.push([x, height, z]);
    }
    let mut triangles = Vec::new();
    for i in 0..segments {
        let (b0, t0) = (2 + 2 * i, 3 + 2 * i);
        let (b1, t1) = (2 + 2 * ((i + 1) % segments), 3 + 2 * ((i + 1) % segments));
        triangles.push([0, b1, b0]);
        triangles.push([1, t0, t1]);
        triangles.push([b0, b1, t1]);
        triangles.push([b0, t1, t0]);
    }
    MeshPart {
        name: name.into(),
        material,
        positions,
        triangles,
        joint: None,
        uvs: None,
    }
}

fn unit_cube() -> Arc<Mesh> {
    Arc::new(Mesh {
        parts: vec![MeshPart::cuboid(
            "cube",
            0,
            [-0.5, 0.0, -0.5],
            [0.5, 1.0, 0.5],
        )],
        materials: vec![Material::new("red", [0.7, 0.1, 0.1], 0.6)],
    })
}

fn cube_scene(pose: Pose) -> RenderScene {
    RenderScene::studio(vec![Instance::new("cube", unit_cube(), pose)])
}

fn cube_pose() -> Pose {
    Pose::new(1.2, 0.4, Vector3::new(0.2, 0.0, -0.3))
}

fn pixel_centre(x: u32, y: u32) -> Point2<f64> {
    Point2::new(x as f64 + 0.5, y as f64 + 0.5)
}

#[test]
fn depth_through_a_cube_face_centre_is_the_known_distance() {
    let pose = cube_pose();
    let scene = cube_scene(pose);
    let face_centre = pose.transform_point(&Point3::new(0.0, 0.5, 0.5));
    let normal = pose.front();
    // Straight on: the face is perpendicular to the optical axis 2.5 m away. An odd image
    // size puts the face centre at the centre of pixel (80, 60).
    let k = Intrinsics::from_vertical_fov(161, 121, 0.9);
    let camera = Camera::look_at(k, face_centre + normal * 2.5, face_centre, Vector3::y());
    let frame = renderer().render(&scene, &camera).unwrap();
    let depth = frame.depth_at(80, 60).expect("the cube is hit");
    assert!((depth as f64 - 2.5).abs() < 0.01, "depth {depth}");
    assert_eq!(frame.id_at(80, 60), Some("cube"));

    // Obliquely: the depth at a pixel near the face centre equals the ray–plane distance.
    let eye = face_centre + normal * 2.0 + Vector3::new(0.9, 0.7, 0.0);
    let camera = Camera::look_at(k, eye, face_centre, Vector3::y());
    let frame = renderer().render(&scene, &camera).unwrap();
    let proj = camera.project(&face_centre).unwrap();
    let (x, y) = (proj.pixel.x.floor() as u32, proj.pixel.y.floor() as u32);
    let along = camera.unproject(&pixel_centre(x, y), 1.0) - camera.position;
    let expected = (face_centre - camera.position).dot(&normal) / along.dot(&normal);
    let depth = frame.depth_at(x, y).expect("the cube is hit");
    assert!(
        (depth as f64 - expected).abs() < 0.01,
        "depth {depth}, expected {expected}"
    );
}

/// Whether `p` is inside the convex polygon `hull` (counter-clockwise in image space with v
/// down, i.e. clockwise on screen: handled by checking sign consistency), and its distance to
/// the polygon's border.
fn inside_and_border_distance(hull: &[Point2<f64>], p: Point2<f64>) -> (bool, f64) {
    let n = hull.len();
    let mut sign = 0.0f64;
    let mut inside = true;
    let mut border = f64::MAX;
    for i in 0..n {
        let (a, b) = (hull[i], hull[(i + 1) % n]);
        let e = b - a;
        let cross = e.x * (p.y - a.y) - e.y * (p.x - a.x);
        if cross != 0.0 {
            if sign == 0.0 {
                sign = cross.signum();
            } else if cross.signum() != sign {
                inside = false;
            }
        }
        let t = ((p - a).dot(&e) / e.norm_squared()).clamp(0.0, 1.0);
        border = border.min((a + e * t - p).norm());
    }
    (inside, border)
}

#[test]
fn instance_mask_equals_the_projected_silhouette_within_one_pixel() {
    let pose = cube_pose();
    let scene = cube_scene(pose);
    let k = Intrinsics::from_vertical_fov(160, 120, 0.8);
    let camera = Camera::look_at(
        k,
        Point3::new(2.4, 1.9, 2.1),
        Point3::new(0.2, 0.55, -0.3),
        Vector3::y(),
    );
    let frame = renderer().render(&scene, &camera).unwrap();
    let corners: Vec<Point2<f64>> = unit_cube()
        .bounds()
        .unwrap()
        .corners()
        .iter()
        .map(|c| camera.project(&pose.transform_point(c)).unwrap().pixel)
        .collect();
    let hull = convex_hull(&corners);
    let mask = frame.mask("cube");
    let (mut inside_count, mut mismatches) = (0, 0);
    for y in 0..k.height {
        for x in 0..k.width {
            let (inside, border) = inside_and_border_distance(&hull, pixel_centre(x, y));
            let shown = mask.get_pixel(x, y).0[0] == 255;
            inside_count += inside as usize;
            if inside != shown {
                mismatches += 1;
                assert!(
                    border <= 1.0,
                    "pixel ({x}, {y}) is {} the silhouette but {} in the mask, {border:.2} px \
                     from the border",
                    if inside { "inside" } else { "outside" },
                    if shown { "set" } else { "unset" },
                );
            }
        }
    }
    assert!(inside_count > 2000, "the cube covers {inside_count} pixels");
    assert!(
        mismatches < inside_count / 20,
        "{mismatches} border mismatches"
    );
}

fn room_scene() -> RenderScene {
    let wood = Material::new("wood", [0.45, 0.28, 0.14], 0.7);
    let fabric = Material::new("fabric", [0.12, 0.25, 0.55], 0.9);
    let ceramic = Material::new("ceramic", [0.85, 0.85, 0.8], 0.3);
    let table = Arc::new(Mesh {
        parts: vec![
            MeshPart::cuboid("top", 0, [-0.6, 0.70, -0.4], [0.6, 0.75, 0.4]),
            MeshPart::cuboid("leg_0", 0, [-0.55, 0.0, -0.35], [-0.5, 0.7, -0.3]),
            MeshPart::cuboid("leg_1", 0, [0.5, 0.0, -0.35], [0.55, 0.7, -0.3]),
            MeshPart::cuboid("leg_2", 0, [-0.55, 0.0, 0.3], [-0.5, 0.7, 0.35]),
            MeshPart::cuboid("leg_3", 0, [0.5, 0.0, 0.3], [0.55, 0.7, 0.35]),
        ],
        materials: vec![wood],
    });
    let sofa = Arc::new(Mesh {
        parts: vec![
            MeshPart::cuboid("seat", 0, [-1.0, 0.0, -0.45], [1.0, 0.45, 0.45]),
            MeshPart::cuboid("back", 0, [-1.0, 0.0, -0.45], [1.0, 0.9, -0.25]),
            MeshPart::cuboid("arm_l", 0, [-1.0, 0.0, -0.45], [-0.85, 0.65, 0.45]),
            MeshPart::cuboid("arm_r", 0, [0.85, 0.0, -0.45], [1.0, 0.65, 0.45]),
        ],
        materials: vec![fabric],
    });
    let vase = Arc::new(Mesh {
        parts: vec![cylinder("body", 0, 0.08, 0.3, 24)],
        materials: vec![ceramic],
    });
    RenderScene::with_architecture(
        vec![
            Instance::new(
                "sofa_0",
                sofa,
                Pose::new(1.0, 0.0, Vector3::new(0.0, 0.0, -1.4)),
            ),
            Instance::new(
                "table_0",
                table,
                Pose::new(1.0, 0.2, Vector3::new(0.1, 0.0, 0.0)),
            ),
            Instance::new(
                "vase_0",
                vase,
                Pose::new(1.0, 0.0, Vector3::new(0.2, 0.75, 0.05)),
            ),
        ],
        Architecture::rectangular_room(4.0, 3.6, 2.6, 0.9),
    )
}

#[test]
fn same_scene_and_camera_give_identical_frames() {
    let scene = room_scene();
    let camera = views::photo_view(&scene, 96, 72);
    let a = renderer().render(&scene, &camera).unwrap();
    let b = renderer().render(&scene, &camera).unwrap();
    assert!(a == b, "two renders of one scene differ");
    assert!(a.pixel_count("table_0") > 50);
}

#[test]
fn near_walls_are_cut_away_and_far_walls_and_door_gap_stay() {
    let mut scene = room_scene();
    let camera = views::photo_view(&scene, 160, 120);
    let frame: Frame = renderer().render(&scene, &camera).unwrap();
    // wall_0 is the back wall (−z), wall_2 the front wall (+z) that holds the door.
    assert_eq!(
        frame.pixel_count("wall_2"),
        0,
        "the front wall hides the room"
    );
    assert!(frame.pixel_count("wall_0") > 500);
    assert!(frame.pixel_count("floor") > 2000);
    assert!(frame.pixel_count("sofa_0") > 300);

    scene.cut_away_walls = false;
    let closed = renderer().render(&scene, &camera).unwrap();
    assert!(closed.pixel_count("wall_2") > 2000);
    // The door's closed leaf fills the opening, drawn under the door's id (and cut away with
    // its wall above).
    let door_centre = Point3::new(0.0, 1.0, 1.85);
    let p = camera.project(&door_centre).unwrap().pixel;
    assert_eq!(closed.id_at(p.x as u32, p.y as u32), Some("door_0"));
    assert_eq!(frame.pixel_count("door_0"), 0);
    // Without its leaf, the opening lets the camera see through the front wall.
    scene.architecture.as_mut().unwrap().doors[0].leaf = None;
    let open = renderer().render(&scene, &camera).unwrap();
    let seen = open.id_at(p.x as u32, p.y as u32);
    assert!(seen != Some("wall_2") && seen != Some("door_0"), "{seen:?}");
}

#[test]
fn objects_cast_shadows_on_the_floor() {
    let scene = cube_scene(Pose::new(1.0, 0.0, Vector3::zeros()));
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(160, 120, 0.9),
        Point3::new(-2.5, 3.0, -3.0),
        Point3::new(0.0, 0.3, 0.0),
        Vector3::y(),
    );
    let lit = Renderer::new(RendererOptions {
        shadows: false,
        ..RendererOptions::from_env().unwrap()
    })
    .unwrap()
    .render(&scene, &camera)
    .unwrap();
    let shaded = renderer().render(&scene, &camera).unwrap();
    let luminance = |f: &Frame, p: Point3<f64>| {
        let px = camera.project(&p).unwrap().pixel;
        let c = f.color.get_pixel(px.x as u32, px.y as u32).0;
        c[0] as i32 + c[1] as i32 + c[2] as i32
    };
    // The sun comes from (0.4, 1, 0.6): the cube's shadow falls behind it, toward −x −z.
    let in_shadow = Point3::new(-0.4, 0.0, -0.9);
    let open_floor = Point3::new(1.2, 0.0, -1.2);
    assert!(luminance(&shaded, in_shadow) + 60 < luminance(&lit, in_shadow));
    assert!((luminance(&shaded, open_floor) - luminance(&lit, open_floor)).abs() <= 3);
}

/// A unit cube of see-through material `color` (linear RGB) and `opacity` in the studio.
fn glass_cube(color: [f32; 3], opacity: f32) -> RenderScene {
    let mut mesh = (*unit_cube()).clone();
    mesh.materials[0] = Material {
        name: "glass".into(),
        base_color: [color[0], color[1], color[2], opacity],
        roughness: 0.05,
        metallic: 0.0,
        texture: None,
    };
    RenderScene::studio(vec![Instance::new(
        "cube",
        Arc::new(mesh),
        Pose::new(1.0, 0.0, Vector3::zeros()),
    )])
}

/// The colour of the floor where the unit cube's shadow falls (the sun comes from
/// (0.4, 1, 0.6), so toward −x −z), seen from above and behind.
fn shadow_color(scene: &RenderScene) -> [i32; 3] {
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(160, 120, 0.9),
        Point3::new(-2.5, 3.0, -3.0),
        Point3::new(0.0, 0.3, 0.0),
        Vector3::y(),
    );
    let f = renderer().render(scene, &camera).unwrap();
    let px = camera.project(&Point3::new(-0.4, 0.0, -0.9)).unwrap().pixel;
    let c = f.color.get_pixel(px.x as u32, px.y as u32).0;
    [c[0] as i32, c[1] as i32, c[2] as i32]
}

#[test]
fn glass_casts_a_partial_shadow() {
    let luminance = |c: [i32; 3]| c.iter().sum::<i32>();
    let opaque = luminance(shadow_color(&cube_scene(Pose::new(
        1.0,
        0.0,
        Vector3::zeros(),
    ))));
    let clear_white = [0.9, 0.95, 0.95];
    let glass = luminance(shadow_color(&glass_cube(clear_white, 0.3)));
    let clear = luminance(shadow_color(&glass_cube(clear_white, 0.0)));
    assert!(
        opaque + 40 < glass && glass + 10 < clear,
        "opaque {opaque}, glass {glass}, fully clear {clear}"
    );
}

#[test]
fn coloured_glass_tints_its_shadow() {
    let [r, g, b] = shadow_color(&glass_cube([0.1, 0.8, 0.1], 0.3));
    assert!(
        g > r + 25 && g > b + 25,
        "green glass's shadow is {r} {g} {b}"
    );
    let [r, g, b] = shadow_color(&glass_cube([0.9, 0.9, 0.9], 0.3));
    assert!(
        (g - r).abs() <= 8 && (g - b).abs() <= 8,
        "clear glass's shadow is {r} {g} {b}"
    );
}

#[test]
fn what_stands_on_glass_is_not_tinted_by_it() {
    // A green glass slab 2 cm thick with an opaque cube standing on it: the cube's sunlit top
    // is as bright as without the slab; the floor under the slab is green.
    let box_of = |name: &str, material: Material, min: [f32; 3], max: [f32; 3]| {
        Instance::new(
            name,
            Arc::new(Mesh::cuboid(name, material, min, max)),
            Pose::IDENTITY,
        )
    };
    let green_glass = Material {
        name: "glass".into(),
        base_color: [0.1, 0.8, 0.1, 0.3],
        roughness: 0.05,
        metallic: 0.0,
        texture: None,
    };
    let slab = box_of("slab", green_glass, [-1.0, 0.0, -1.0], [1.0, 0.02, 1.0]);
    let cube = || {
        box_of(
            "cube",
            Material::new("grey", [0.6, 0.6, 0.6], 0.6),
            [-0.2, 0.02, -0.2],
            [0.2, 0.42, 0.2],
        )
    };
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(160, 120, 0.9),
        Point3::new(2.0, 3.0, 3.0),
        Point3::new(0.0, 0.0, 0.0),
        Vector3::y(),
    );
    let color_at = |scene: &RenderScene, p: Point3<f64>| {
        let f = renderer().render(scene, &camera).unwrap();
        let px = camera.project(&p).unwrap().pixel;
        f.color.get_pixel(px.x as u32, px.y as u32).0
    };
    let top = Point3::new(0.0, 0.42, 0.0);
    let alone = color_at(&RenderScene::studio(vec![cube()]), top);
    let on_glass = color_at(&RenderScene::studio(vec![slab, cube()]), top);
    for c in 0..3 {
        assert!(
            (alone[c] as i32 - on_glass[c] as i32).abs() <= 6,
            "the cube's top alone {alone:?}, on green glass {on_glass:?}"
        );
    }
}

#[test]
fn outdoor_scenes_get_a_sky_and_ground() {
    let scene = RenderScene::with_architecture(
        vec![Instance::new("cube", unit_cube(), Pose::IDENTITY)],
        Architecture::open_ground(10.0, 10.0),
    );
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(80, 60, 0.9),
        Point3::new(0.0, 1.5, 6.0),
        Point3::new(0.0, 1.0, 0.0),
        Vector3::y(),
    );
    let frame = renderer().render(&scene, &camera).unwrap();
    let sky = frame.color.get_pixel(40, 1).0;
    assert!(sky[2] > sky[0] + 20, "sky colour {sky:?}");
    assert_eq!(frame.id_at(40, 1), None);
    assert_eq!(frame.depth_at(40, 1), None);
    assert_eq!(frame.id_at(40, 58), Some("ground_plane"));
}

#[test]
fn depth_encodings_round_trip() {
    let scene = cube_scene(cube_pose());
    let camera = views::photo_view(&scene, 64, 48);
    let frame = renderer().render(&scene, &camera).unwrap();
    let png = image::load_from_memory(&frame.depth_png16().unwrap())
        .unwrap()
        .into_luma16();
    assert_eq!(png.into_raw(), frame.depth_u16_mm().into_raw());
    let colour = image::load_from_memory(&frame.color_png().unwrap()).unwrap();
    assert_eq!(colour.into_rgba8(), frame.color);
}

#[test]
fn golden_room_render_matches_within_tolerance() {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../fixtures/render/golden_room_128x96.png");
    let scene = room_scene();
    let frame = renderer()
        .render(&scene, &views::photo_view(&scene, 128, 96))
        .unwrap();
    if std::env::var_os("SCENETHESIS_BLESS").is_some() {
        std::fs::write(&path, frame.color_png().unwrap()).unwrap();
        return;
    }
    let golden = image::open(&path)
        .unwrap_or_else(|e| {
            panic!(
                "cannot read {}: {e}; run with SCENETHESIS_BLESS=1 to create it",
                path.display()
            )
        })
        .into_rgba8();
    assert_eq!(golden.dimensions(), frame.color.dimensions());
    // Software rasterizers differ slightly (llvmpipe vs lavapipe, filtering, rounding): allow
    // small colour differences everywhere and larger ones on a few edge pixels.
    let mut total = 0u64;
    let mut far_off = 0usize;
    for (a, b) in golden.pixels().zip(frame.color.pixels()) {
        let diff = (0..3).map(|c| a.0[c].abs_diff(b.0[c])).max().unwrap();
        total += diff as u64;
        far_off += (diff > 40) as usize;
    }
    let pixels = (golden.width() * golden.height()) as usize;
    let mean = total as f64 / pixels as f64;
    assert!(
        mean < 3.0 && far_off * 100 < pixels * 2,
        "render differs from {}: mean difference {mean:.2}, {far_off} pixels off by more \
         than 40 (rerun with SCENETHESIS_BLESS=1 after an intended change)",
        path.display()
    );
}

#[test]
fn a_missing_backend_gives_one_clear_error_or_a_working_renderer() {
    use scenethesis_render::{BackendChoice, RenderError};
    for backend in [BackendChoice::Vulkan, BackendChoice::Gl] {
        match Renderer::new(RendererOptions {
            backend,
            ..RendererOptions::default()
        }) {
            Ok(r) => {
                let scene = cube_scene(Pose::IDENTITY);
                let frame = r
                    .render(&scene, &views::photo_view(&scene, 32, 24))
                    .unwrap();
                assert!(
                    frame.pixel_count("cube") > 20,
                    "{}",
                    r.adapter_description()
                );
            }
            Err(err @ RenderError::NoAdapter { .. }) => {
                let text = err.to_string();
                assert!(
                    text.contains("Mesa") && text.contains("GPU driver"),
                    "{text}"
                );
            }
            Err(other) => panic!("unexpected error for {backend}: {other}"),
        }
    }
}

/// The scene graph of [`room_scene`] (each instance an object of that id and pose) with its
/// meshes by object id, plus an object whose mesh is missing.
fn room_scene_graph() -> (
    scenethesis_scene_graph::Scene,
    std::collections::BTreeMap<String, Mesh>,
) {
    use scenethesis_scene_graph::{AssetRef, ParentRef, RelationKind, Scene, SceneObject};
    let rs = room_scene();
    let mut scene = Scene::new(rs.architecture.clone().unwrap());
    let mut meshes = std::collections::BTreeMap::new();
    let object = |id: &str, pose: Pose, mesh: &Mesh| SceneObject {
        id: id.into(),
        category: "thing".into(),
        asset: AssetRef::Procedural {
            generator: "thing".into(),
            seed: 0,
            look: None,
        },
        pose,
        parent: ParentRef::Ground,
        support: RelationKind::OnFloor,
        relations: Vec::new(),
        local_bounds: mesh.bounds().unwrap(),
        joints: Vec::new(),
        parent_link: None,
        room: None,
    };
    for instance in &rs.instances {
        scene
            .objects
            .push(object(&instance.id, instance.pose, &instance.mesh));
        meshes.insert(instance.id.clone(), (*instance.mesh).clone());
    }
    scene
        .objects
        .push(object("ghost_0", cube_pose(), &unit_cube()));
    (scene, meshes)
}

#[test]
fn the_seam_draws_exactly_what_the_renderer_draws_of_the_converted_scene() {
    use scenethesis_render_api::{SceneRenderer, ViewKind, ViewRequest};
    let (scene, meshes) = room_scene_graph();
    let rs = RenderScene::from_scene(&scene, &meshes);
    let ids: Vec<&str> = rs.instances.iter().map(|i| i.id.as_str()).collect();
    assert_eq!(
        ids,
        ["sofa_0", "table_0", "vase_0"],
        "objects without a mesh are left out"
    );
    assert_eq!(rs.backdrop, room_scene().backdrop);

    let requests = [
        ViewRequest::new(ViewKind::Photo, [96, 72]),
        ViewRequest::new(ViewKind::Top, [48, 48]).supersampled(2),
    ];
    let images = renderer().render_views(&scene, &meshes, &requests).unwrap();
    let photo = views::photo_view(&rs, 96, 72);
    let top = views::top_view(&rs, 48, 48);
    let prepared = renderer().prepare(&rs).unwrap();
    assert_eq!(images[0].camera, photo);
    assert!(images[0].color == renderer().render_prepared(&prepared, &photo).unwrap().color);
    assert_eq!(images[1].camera, top);
    assert!(
        images[1].color
            == renderer()
                .render_color_supersampled(&prepared, &top, 2)
                .unwrap()
    );
}

/// A 2 × 1 × 0.2 m slab wearing `material`, seen square-on from the front (+z) so that its
/// front face fills the middle of a 160 × 120 image.
fn slab_front(material: Material, renderer: &Renderer) -> Frame {
    let slab = Arc::new(Mesh {
        parts: vec![MeshPart::cuboid(
            "slab",
            0,
            [-1.0, 0.0, -0.1],
            [1.0, 1.0, 0.1],
        )],
        materials: vec![material],
    });
    let scene = RenderScene::studio(vec![Instance::new("slab", slab, Pose::IDENTITY)]);
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(160, 120, 0.6),
        Point3::new(0.0, 0.5, 2.5),
        Point3::new(0.0, 0.5, 0.0),
        Vector3::y(),
    );
    renderer.render(&scene, &camera).unwrap()
}

/// Mean and standard deviation of the luminance (0–255 scale) in the 40 × 20 pixel window
/// at the image's centre (more than the occlusion radius above the floor).
fn centre_statistics(frame: &Frame) -> (f64, f64) {
    let values: Vec<f64> = (50..70)
        .flat_map(|y| (60..100).map(move |x| (x, y)))
        .map(|(x, y)| {
            let c = frame.color.get_pixel(x, y).0;
            0.3 * c[0] as f64 + 0.6 * c[1] as f64 + 0.1 * c[2] as f64
        })
        .collect();
    let mean = values.iter().sum::<f64>() / values.len() as f64;
    let var = values.iter().map(|v| (v - mean).powi(2)).sum::<f64>() / values.len() as f64;
    (mean, var.sqrt())
}

#[test]
fn library_materials_show_their_texture_and_keep_their_colour() {
    let colour = [0.40, 0.26, 0.14];
    assert!(scenethesis_materials::resolve("flat_colour").is_none());
    let plain = slab_front(Material::new("flat_colour", colour, 0.6), renderer());
    let oak = slab_front(Material::new("oak", colour, 0.6), renderer());
    assert_eq!(oak.id_at(80, 60), Some("slab"));
    let (plain_mean, plain_spread) = centre_statistics(&plain);
    let (oak_mean, oak_spread) = centre_statistics(&oak);
    // A flat face under one sun is one colour; oak's grain varies across it.
    assert!(plain_spread < 1.5, "plain face varies: {plain_spread:.2}");
    assert!(oak_spread > 4.0, "oak shows no grain: {oak_spread:.2}");
    // The texture multiplies the surface's own colour so that it averages that colour.
    assert!(
        (oak_mean - plain_mean).abs() < 0.15 * plain_mean,
        "oak {oak_mean:.1} vs plain {plain_mean:.1}"
    );
    // Another tint of the same texture keeps the grain and changes the colour.
    let red = slab_front(Material::new("oak", [0.5, 0.05, 0.04], 0.6), renderer());
    let (c, o) = (red.color.get_pixel(80, 60).0, oak.color.get_pixel(80, 60).0);
    assert!(c[0] > c[1] + 40 && o[0] < o[1] + 60, "{c:?} vs {o:?}");
}

/// An empty 4 × 3.6 m room seen from inside, looking at the back wall's left corner.
fn empty_room_corner(renderer: &Renderer) -> (Frame, Camera) {
    let scene = RenderScene::with_architecture(
        Vec::new(),
        Architecture::rectangular_room(4.0, 3.6, 2.6, 0.9),
    );
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(160, 120, 1.0),
        Point3::new(0.2, 1.4, 0.4),
        Point3::new(-2.0, 0.3, -1.8),
        Vector3::y(),
    );
    (renderer.render(&scene, &camera).unwrap(), camera)
}

#[test]
fn ambient_occlusion_darkens_the_corner_where_floor_meets_walls() {
    let flat = Renderer::new(RendererOptions {
        ambient_occlusion: false,
        ..RendererOptions::from_env().unwrap()
    })
    .unwrap();
    let (occluded, camera) = empty_room_corner(renderer());
    let (open, _) = empty_room_corner(&flat);
    let level = |f: &Frame, p: Point3<f64>| {
        let px = camera.project(&p).unwrap().pixel;
        let c = f.color.get_pixel(px.x as u32, px.y as u32).0;
        c[0] as i32 + c[1] as i32 + c[2] as i32
    };
    // The room's inner faces: back wall at z = −1.8, left wall at x = −2.
    let corner = Point3::new(-1.96, 0.03, -1.76);
    let middle = Point3::new(-0.6, 0.0, -0.6);
    let (dark, light) = (level(&occluded, corner), level(&open, corner));
    assert!(
        dark + 20 < light,
        "corner {dark} with AO vs {light} without"
    );
    let (a, b) = (level(&occluded, middle), level(&open, middle));
    assert!((a - b).abs() <= 6, "open floor {a} with AO vs {b} without");
}

#[test]
fn rooms_show_a_sky_beyond_their_walls() {
    let scene = room_scene();
    // From inside, looking up over the back wall (rooms have no ceiling).
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(80, 60, 0.9),
        Point3::new(0.0, 1.5, 1.0),
        Point3::new(0.0, 3.6, -1.8),
        Vector3::y(),
    );
    let frame = renderer().render(&scene, &camera).unwrap();
    assert_eq!(frame.id_at(40, 1), None);
    let sky = frame.color.get_pixel(40, 1).0;
    assert!(sky[2] > sky[0] + 30 && sky[2] > 150, "sky colour {sky:?}");
}

/// A cube of side 1 standing on y = 0 whose top face alone shows the whole of a 4 × 4 checker
/// of red and blue pixels (texture coordinates per vertex, v down), its sides the image's
/// top-left corner.
fn checker_cube() -> Arc<Mesh> {
    let image = image::RgbImage::from_fn(4, 4, |x, y| {
        image::Rgb(if (x + y) % 2 == 0 {
            [220, 30, 30]
        } else {
            [30, 40, 220]
        })
    });
    let mut png = Vec::new();
    image
        .write_to(&mut std::io::Cursor::new(&mut png), image::ImageFormat::Png)
        .unwrap();
    let texture = scenethesis_scene_graph::TextureImage::from_png(png, [0.35, 0.02, 0.35]).unwrap();
    let mut part = MeshPart::cuboid("cube", 0, [-0.5, 0.0, -0.5], [0.5, 1.0, 0.5]);
    // Corners 2, 3, 6, 7 are the top (y = 1): the image spans x and z across it.
    part.uvs = Some(
        part.positions
            .iter()
            .map(|p| {
                if p[1] > 0.5 {
                    [p[0] + 0.5, p[2] + 0.5]
                } else {
                    [0.0, 0.0]
                }
            })
            .collect(),
    );
    let mut material = Material::new("checker", [1.0; 3], 0.8);
    material.texture = Some(texture);
    Arc::new(Mesh {
        parts: vec![part],
        materials: vec![material],
    })
}

#[test]
fn an_imported_image_is_drawn_at_the_parts_own_coordinates() {
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(160, 120, 0.9),
        Point3::new(0.0, 3.2, 0.6),
        Point3::new(0.0, 1.0, 0.0),
        Vector3::y(),
    );
    let render = |mesh: Arc<Mesh>| {
        let scene = RenderScene::studio(vec![Instance::new(
            "cube",
            mesh,
            Pose::new(1.0, 0.0, Vector3::zeros()),
        )]);
        renderer().render(&scene, &camera).unwrap()
    };
    let frame = render(checker_cube());
    if let Some(dir) = std::env::var_os("SCENETHESIS_RENDER_OUT") {
        frame
            .color
            .save(PathBuf::from(dir).join("checker_cube.png"))
            .unwrap();
    }
    // The top face's pixels: clearly red ones and clearly blue ones.
    let (mut red, mut blue) = (0, 0);
    for x in 0..5 {
        for z in 0..5 {
            let p = Point3::new(-0.4 + 0.2 * x as f64, 1.0, -0.4 + 0.2 * z as f64);
            let px = camera.project(&p).unwrap().pixel;
            let [r, _, b, _] = frame.color.get_pixel(px.x as u32, px.y as u32).0;
            if r as i32 > b as i32 + 60 {
                red += 1;
            } else if b as i32 > r as i32 + 60 {
                blue += 1;
            }
        }
    }
    assert!(
        red >= 5 && blue >= 5,
        "red {red}, blue {blue} of 25 samples"
    );
    assert_eq!(frame.color, render(checker_cube()).color, "deterministic");
    // Without its coordinates the part wears the image's flat colour: one purple, no checker.
    let mut plain = (*checker_cube()).clone();
    plain.parts[0].uvs = None;
    let flat = render(Arc::new(plain));
    let centre = camera.project(&Point3::new(0.0, 1.0, 0.0)).unwrap().pixel;
    let [r, g, b, _] = flat.color.get_pixel(centre.x as u32, centre.y as u32).0;
    assert!(
        (r as i32 - b as i32).abs() < 40 && g < r && g < b,
        "{r} {g} {b}"
    );
}
