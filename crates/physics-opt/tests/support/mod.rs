//! Hand-built assets and scenes with known answers, shared by the integration tests and the
//! benchmark (`#[path]`-included there).
#![allow(dead_code)]

use std::sync::Arc;

use nalgebra::Vector3;
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use scenethesis_physics_opt::{Obstacles, PrepareSettings, PreparedAsset, SceneProblem};
use scenethesis_primitives::{cuboid, cylinder};
use scenethesis_scene_graph::{
    Aabb, Architecture, AssetRef, Material, Mesh, MeshPart, ParentRef, Pose, RelationKind, Scene,
    SceneObject,
};
use scenethesis_scene_graph::{Placement, SupportSurface, SurfaceKind};
use scenethesis_sdf::BoxSdf;

/// Table top height.
pub const TABLE_TOP: f64 = 0.76;
/// Shelf board tops (compartment floors) from the bottom.
pub const SHELF_BOARDS: [f64; 3] = [0.02, 0.42, 0.82];
/// Inner half width of the shelf (between the side boards).
pub const SHELF_INNER_HALF_WIDTH: f64 = 0.38;

fn mesh(parts: Vec<MeshPart>) -> Mesh {
    Mesh {
        parts,
        materials: vec![Material::new("wood", [0.6, 0.45, 0.3], 0.7)],
    }
}

fn square(x0: f32, z0: f32, x1: f32, z1: f32) -> Vec<[f32; 2]> {
    // Counter-clockwise seen from above (+Y toward the viewer): x right, z down the page.
    vec![[x0, z0], [x0, z1], [x1, z1], [x1, z0]]
}

/// Exact obstacles: the floor slab (its top at y = 0, 6 m square) and `shelf` at the origin,
/// unturned, with its check samples.
pub fn floor_and_shelf(shelf: &PreparedAsset) -> Obstacles {
    let mut o = Obstacles::new(true);
    o.insert(
        "floor",
        Arc::new(BoxSdf::new(Vector3::new(3.0, 0.25, 3.0))),
        Pose::new(1.0, 0.0, Vector3::new(0.0, -0.25, 0.0)),
        true,
        &[],
    );
    o.insert(
        "shelf",
        shelf.exact_field(),
        at(0.0, 0.0, 0.0, 0.0),
        false,
        shelf.check_points(),
    );
    o
}

/// A 1.2 × 0.8 m table, 0.76 m high: a 4 cm top on four 5 cm legs.
pub fn table() -> PreparedAsset {
    let (mesh, surfaces) = table_mesh();
    prepare("table", &mesh, surfaces, [0.8, 1.2], Placement::Floor)
}

/// The table's mesh and support surfaces.
pub fn table_mesh() -> (Mesh, Vec<SupportSurface>) {
    let mut parts = vec![cuboid("top", 0, [-0.6, 0.72, -0.4], [0.6, 0.76, 0.4])];
    for (i, (x, z)) in [(-0.55, -0.35), (0.55, -0.35), (-0.55, 0.35), (0.55, 0.35)]
        .into_iter()
        .enumerate()
    {
        parts.push(cuboid(
            &format!("leg_{i}"),
            0,
            [x - 0.025, 0.0, z - 0.025],
            [x + 0.025, 0.72, z + 0.025],
        ));
    }
    let surfaces = vec![
        SupportSurface {
            name: "top".into(),
            kind: SurfaceKind::Top,
            polygon: square(-0.58, -0.38, 0.58, 0.38),
            height: 0.76,
            clearance: None,
        },
        SupportSurface {
            name: "under".into(),
            kind: SurfaceKind::Under,
            polygon: square(-0.52, -0.32, 0.52, 0.32),
            height: 0.0,
            clearance: Some(0.72),
        },
    ];
    (mesh(parts), surfaces)
}

/// A 0.8 × 1.2 × 0.3 m open shelf: two side boards, four horizontal boards (compartment floors
/// at 0.02, 0.42 and 0.82 m, 38 cm clear height each) and a back panel.
pub fn shelf() -> PreparedAsset {
    let (mesh, surfaces) = shelf_mesh();
    prepare("shelf", &mesh, surfaces, [0.9, 1.1], Placement::Floor)
}

/// The shelf's mesh and support surfaces.
pub fn shelf_mesh() -> (Mesh, Vec<SupportSurface>) {
    let mut parts = vec![
        cuboid("side_l", 0, [-0.4, 0.0, -0.15], [-0.38, 1.2, 0.15]),
        cuboid("side_r", 0, [0.38, 0.0, -0.15], [0.4, 1.2, 0.15]),
        cuboid("back", 0, [-0.4, 0.0, -0.15], [0.4, 1.2, -0.14]),
    ];
    for (i, y) in [0.0f32, 0.40, 0.80, 1.18].into_iter().enumerate() {
        parts.push(cuboid(
            &format!("board_{i}"),
            0,
            [-0.4, y, -0.15],
            [0.4, y + 0.02, 0.15],
        ));
    }
    let mut surfaces: Vec<SupportSurface> = SHELF_BOARDS
        .iter()
        .enumerate()
        .map(|(i, h)| SupportSurface {
            name: format!("shelf_{i}"),
            kind: SurfaceKind::Shelf,
            polygon: square(-0.38, -0.14, 0.38, 0.15),
            height: *h as f32,
            clearance: Some(0.38),
        })
        .collect();
    surfaces.push(SupportSurface {
        name: "top".into(),
        kind: SurfaceKind::Top,
        polygon: square(-0.4, -0.15, 0.4, 0.15),
        height: 1.2,
        clearance: None,
    });
    (mesh(parts), surfaces)
}

/// A box of the given size standing on its bottom face.
pub fn boxed(size: [f32; 3], scale_range: [f64; 2]) -> PreparedAsset {
    prepare(
        "box",
        &box_mesh(size),
        Vec::new(),
        scale_range,
        Placement::Floor,
    )
}

/// A box mesh of the given size standing on its bottom face.
pub fn box_mesh(size: [f32; 3]) -> Mesh {
    let [x, y, z] = size;
    mesh(vec![cuboid(
        "box",
        0,
        [-x / 2.0, 0.0, -z / 2.0],
        [x / 2.0, y, z / 2.0],
    )])
}

/// A 20 × 3 × 28 cm book lying flat.
pub fn book() -> PreparedAsset {
    prepare(
        "book",
        &book_mesh(),
        Vec::new(),
        [0.8, 1.2],
        Placement::Surface,
    )
}

/// The book's mesh.
pub fn book_mesh() -> Mesh {
    mesh(vec![cuboid(
        "book",
        0,
        [-0.1, 0.0, -0.14],
        [0.1, 0.03, 0.14],
    )])
}

/// The cup's mesh.
pub fn cup_mesh() -> Mesh {
    mesh(vec![cylinder("cup", 0, [0.0, 0.0], 0.04, 0.0, 0.1, 24)])
}

/// The asset-frame mesh of an object of [`thirty_object_room`], from its id.
pub fn thirty_object_room_mesh(id: &str) -> Mesh {
    match id.split('_').collect::<Vec<_>>().as_slice() {
        ["table", ..] => table_mesh().0,
        ["shelf", ..] => shelf_mesh().0,
        ["cup", ..] => cup_mesh(),
        ["book", ..] | ["item", _, "1"] => book_mesh(),
        ["item", ..] => box_mesh(CRATE),
        ["chair", ..] => box_mesh(CHAIR),
        _ => panic!("unknown object {id}"),
    }
}

/// Size of the storage crates in the shelves.
pub const CRATE: [f32; 3] = [0.25, 0.2, 0.2];
/// Size of the chair stand-ins.
pub const CHAIR: [f32; 3] = [0.45, 0.9, 0.45];

/// A cup: a cylinder of 4 cm radius and 10 cm height.
pub fn cup() -> PreparedAsset {
    prepare(
        "cup",
        &cup_mesh(),
        Vec::new(),
        [0.8, 1.2],
        Placement::Surface,
    )
}

fn prepare(
    name: &str,
    mesh: &Mesh,
    surfaces: Vec<SupportSurface>,
    scale_range: [f64; 2],
    placement: Placement,
) -> PreparedAsset {
    PreparedAsset::new(
        name,
        mesh,
        surfaces,
        scale_range,
        placement,
        &PrepareSettings::default(),
    )
    .unwrap()
}

/// A scene object (its bounds are informative only; the optimizer uses the prepared asset).
pub fn object(
    id: &str,
    parent: Option<&str>,
    support: RelationKind,
    asset: &PreparedAsset,
    pose: Pose,
) -> SceneObject {
    SceneObject {
        id: id.into(),
        category: id
            .trim_end_matches(|c: char| c.is_ascii_digit() || c == '_')
            .into(),
        asset: AssetRef::Procedural {
            generator: id.into(),
            seed: 0,
            look: None,
        },
        pose,
        parent: parent.map_or(ParentRef::Ground, |p| ParentRef::Object(p.into())),
        support,
        relations: Vec::new(),
        local_bounds: Aabb::new(asset.bounds().min, asset.bounds().max),
        joints: Vec::new(),
        parent_link: None,
        room: None,
    }
}

/// A pose with unit scale.
pub fn at(x: f64, y: f64, z: f64, yaw: f64) -> Pose {
    Pose::new(1.0, yaw, Vector3::new(x, y, z))
}

/// Builds a problem from (object, asset) pairs in a 6 × 4 m room.
pub fn problem(anchor: &str, objects: Vec<(SceneObject, Arc<PreparedAsset>)>) -> SceneProblem {
    let mut scene = Scene::new(Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9));
    scene.anchor = Some(anchor.into());
    let mut assets = Vec::new();
    for (o, a) in objects {
        assets.push((o.id.clone(), a));
        scene.objects.push(o);
    }
    let mut problem = SceneProblem::new(scene);
    for (id, a) in assets {
        problem.set_asset(&id, a);
    }
    problem
}

/// A 30-object living/study room in an 8 × 6 m room: 4 tables with 2 cups and a book each,
/// 2 shelves with 3 items in their compartments each, and 6 floor boxes (chairs, cabinets),
/// all displaced from a valid layout by seeded noise (sunk, floating, overlapping).
pub fn thirty_object_room(seed: u64) -> SceneProblem {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let table = Arc::new(table());
    let shelf = Arc::new(shelf());
    let cup = Arc::new(cup());
    let book = Arc::new(book());
    let crate_box = Arc::new(boxed(CRATE, [0.7, 1.1]));
    let chair = Arc::new(boxed(CHAIR, [0.8, 1.1]));
    let mut scene = Scene::new(Architecture::rectangular_room(8.0, 6.0, 2.8, 0.9));
    scene.anchor = Some("table_0".into());
    let mut assets: Vec<(String, Arc<PreparedAsset>)> = Vec::new();
    let mut push = |scene: &mut Scene, o: SceneObject, a: &Arc<PreparedAsset>| {
        assets.push((o.id.clone(), a.clone()));
        scene.objects.push(o);
    };
    let mut noise = |r: f64| rng.random_range(-r..r);
    let tables = [(-2.0, -1.0), (1.5, -1.0), (-2.0, 1.5), (1.5, 1.5)];
    for (t, (x, z)) in tables.iter().enumerate() {
        let id = format!("table_{t}");
        let pose = Pose::new(
            1.0,
            noise(0.1),
            Vector3::new(x + noise(0.05), noise(0.02), z + noise(0.05)),
        );
        push(
            &mut scene,
            object(&id, None, RelationKind::OnFloor, &table, pose),
            &table,
        );
        for c in 0..2 {
            let cid = format!("cup_{t}_{c}");
            let p = Pose::new(
                1.0,
                0.0,
                Vector3::new(
                    x - 0.3 + 0.6 * c as f64 + noise(0.03),
                    TABLE_TOP + noise(0.03),
                    z + noise(0.1),
                ),
            );
            push(
                &mut scene,
                object(&cid, Some(&id), RelationKind::On, &cup, p),
                &cup,
            );
        }
        let bid = format!("book_{t}");
        let p = Pose::new(
            1.0,
            noise(0.5),
            Vector3::new(
                x + noise(0.05),
                TABLE_TOP - 0.02 + noise(0.01),
                z + 0.2 + noise(0.03),
            ),
        );
        push(
            &mut scene,
            object(&bid, Some(&id), RelationKind::On, &book, p),
            &book,
        );
    }
    for (s, x) in [-1.0f64, 1.0].iter().enumerate() {
        let id = format!("shelf_{s}");
        let pose = Pose::new(1.0, 0.0, Vector3::new(*x, noise(0.01), -2.78 + noise(0.05)));
        push(
            &mut scene,
            object(&id, None, RelationKind::AgainstWall, &shelf, pose),
            &shelf,
        );
        for (k, board) in SHELF_BOARDS.iter().enumerate() {
            let iid = format!("item_{s}_{k}");
            let p = Pose::new(
                1.0,
                noise(0.2),
                Vector3::new(x + noise(0.15), board + noise(0.01), -2.78 + noise(0.02)),
            );
            let asset = if k == 1 { &book } else { &crate_box };
            push(
                &mut scene,
                object(&iid, Some(&id), RelationKind::Inside, asset, p),
                asset,
            );
        }
    }
    let chairs = [
        (-2.0, -0.3),
        (-2.0, -1.7),
        (1.5, -0.3),
        (1.5, -1.7),
        (-3.5, 0.3),
        (3.5, 0.3),
    ];
    for (c, (x, z)) in chairs.iter().enumerate() {
        let id = format!("chair_{c}");
        let pose = Pose::new(
            1.0,
            noise(0.3),
            Vector3::new(x + noise(0.08), noise(0.02), z + noise(0.08)),
        );
        push(
            &mut scene,
            object(&id, None, RelationKind::OnFloor, &chair, pose),
            &chair,
        );
    }
    let mut problem = SceneProblem::new(scene);
    for (id, a) in assets {
        problem.set_asset(&id, a);
    }
    problem
}

/// Top of the board of [`lipped_shelf`].
pub const LIPPED_BOARD: f64 = 0.42;

/// A low 0.8 × 0.3 m shelf with one level at [`LIPPED_BOARD`], a top board at 0.8 m and a
/// 3 cm lip along the level's front edge (as store shelves have for price labels).
pub fn lipped_shelf() -> PreparedAsset {
    let parts = vec![
        cuboid("side_l", 0, [-0.4, 0.0, -0.15], [-0.38, 0.82, 0.15]),
        cuboid("side_r", 0, [0.38, 0.0, -0.15], [0.4, 0.82, 0.15]),
        cuboid("back", 0, [-0.4, 0.0, -0.15], [0.4, 0.82, -0.14]),
        cuboid("board", 0, [-0.4, 0.4, -0.15], [0.4, 0.42, 0.15]),
        cuboid("lip", 0, [-0.38, 0.42, 0.13], [0.38, 0.45, 0.15]),
        cuboid("top", 0, [-0.4, 0.8, -0.15], [0.4, 0.82, 0.15]),
    ];
    let surfaces = vec![SupportSurface {
        name: "level".into(),
        kind: SurfaceKind::Shelf,
        polygon: square(-0.38, -0.14, 0.38, 0.13),
        height: LIPPED_BOARD as f32,
        clearance: Some(0.38),
    }];
    prepare(
        "lipped_shelf",
        &mesh(parts),
        surfaces,
        [0.95, 1.05],
        Placement::Floor,
    )
}

/// A box of the given size standing on its bottom face, resting on surfaces.
pub fn surface_box(size: [f32; 3], scale_range: [f64; 2]) -> PreparedAsset {
    prepare(
        "box",
        &box_mesh(size),
        Vec::new(),
        scale_range,
        Placement::Surface,
    )
}
