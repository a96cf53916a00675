//! Hand-built scenes with known answers, shared by the tests and the benchmark.
#![allow(dead_code)]

use std::f64::consts::FRAC_PI_2;

use nalgebra::{Point2, Vector3};
use scenethesis_eval::stability::{BodyMotion, MAX_DISPLACEMENT, MAX_ROTATION};
use scenethesis_eval::{EvalObject, EvalScene};
use scenethesis_primitives::{cuboid, cylinder};
use scenethesis_scene_graph::{
    Architecture, DoorOpening, Material, Mesh, MeshPart, Pose, RelationKind, Wall,
};

/// A mesh of parts with one grey material.
pub fn mesh(parts: Vec<MeshPart>) -> Mesh {
    Mesh {
        parts,
        materials: vec![Material::new("grey", [0.5, 0.5, 0.5], 0.8)],
    }
}

/// A table in its own frame: a top `w × d` whose upper face is at `h`, `top` thick, four legs.
pub fn table(w: f32, d: f32, h: f32, top: f32) -> Mesh {
    let (hw, hd, leg) = (w / 2.0, d / 2.0, 0.05);
    let mut parts = vec![cuboid("top", 0, [-hw, h - top, -hd], [hw, h, hd])];
    for (k, (sx, sz)) in [(-1.0, -1.0), (1.0, -1.0), (-1.0, 1.0), (1.0, 1.0)]
        .into_iter()
        .enumerate()
    {
        let (x, z) = (sx * (hw - leg), sz * (hd - leg));
        parts.push(cuboid(
            &format!("leg_{k}"),
            0,
            [x - leg / 2.0, 0.0, z - leg / 2.0],
            [x + leg / 2.0, h - top, z + leg / 2.0],
        ));
    }
    mesh(parts)
}

/// A shelf 0.8 wide, 0.35 deep, 1.2 tall: two sides, four boards (bottom at 0.0–0.02 and then
/// every 0.4 m), a back panel. Compartment floors at y = 0.02, 0.42, 0.82.
pub fn shelf() -> Mesh {
    let (hw, hd, t) = (0.4f32, 0.175f32, 0.02f32);
    let mut parts = vec![
        cuboid("side_l", 0, [-hw, 0.0, -hd], [-hw + t, 1.2, hd]),
        cuboid("side_r", 0, [hw - t, 0.0, -hd], [hw, 1.2, hd]),
        cuboid("back", 0, [-hw + t, 0.0, -hd], [hw - t, 1.2, -hd + t]),
    ];
    for (k, y) in [0.0f32, 0.4, 0.8, 1.18].into_iter().enumerate() {
        parts.push(cuboid(
            &format!("board_{k}"),
            0,
            [-hw + t, y, -hd + t],
            [hw - t, y + t, hd],
        ));
    }
    mesh(parts)
}

/// A chair: 0.45 × 0.45 seat at 0.45 m, four legs, a back rest at −z.
pub fn chair() -> Mesh {
    let mut m = table(0.45, 0.45, 0.45, 0.04);
    m.parts.push(cuboid(
        "back",
        0,
        [-0.225, 0.45, -0.225],
        [0.225, 0.9, -0.185],
    ));
    m
}

/// A box `w × h × d` standing on its origin.
pub fn block(w: f32, h: f32, d: f32) -> Mesh {
    mesh(vec![cuboid(
        "box",
        0,
        [-w / 2.0, 0.0, -d / 2.0],
        [w / 2.0, h, d / 2.0],
    )])
}

/// A cup: a solid 24-sided cylinder of radius 4 cm and height 10 cm.
pub fn cup() -> Mesh {
    mesh(vec![cylinder("body", 0, [0.0, 0.0], 0.04, 0.0, 0.1, 24)])
}

/// An object placed with `pose`, resting on `parent` (`None` = ground).
pub fn place(
    id: &str,
    category: &str,
    asset: &Mesh,
    pose: Pose,
    parent: Option<&str>,
    support: RelationKind,
) -> EvalObject {
    EvalObject {
        id: id.into(),
        category: category.into(),
        mesh: asset.transformed(&pose),
        yaw: pose.yaw,
        parent: parent.map(str::to_owned),
        support: Some(support),
        relations: Vec::new(),
        joints: Vec::new(),
        parent_link: None,
    }
}

/// The optimizer's default gap between an object's bottom and its support (metres): the
/// stability simulation lets every object fall that far.
pub const SETTLE_DROP: f64 = 0.00125;

/// The built-in catalog's asset `name` generated with `seed`.
pub fn catalog_asset(name: &str, seed: u64) -> scenethesis_scene_graph::Asset {
    use scenethesis_procedural::catalog;
    let category = catalog::categories()
        .find(|c| c.name == name)
        .unwrap_or_else(|| panic!("the catalog has `{name}`"));
    catalog::generate(category, seed)
}

/// A catalog store shelf (`store_shelf`) standing at (`x`, `z`) with a catalog can every 9 cm
/// along each of its boards and its top (`can_1`, `can_2`, …), each dropped by
/// [`SETTLE_DROP`].
pub fn stocked_shelf(x: f64, z: f64) -> Vec<EvalObject> {
    use scenethesis_scene_graph::SurfaceKind;
    let shelf = catalog_asset("store_shelf", 0);
    let can = catalog_asset("can", 0);
    let mut objects = vec![place(
        "store_shelf",
        "store_shelf",
        &shelf.mesh,
        at(x, SETTLE_DROP, z, 0.0),
        None,
        RelationKind::OnFloor,
    )];
    for surface in shelf
        .info
        .support_surfaces
        .iter()
        .filter(|s| matches!(s.kind, SurfaceKind::Shelf | SurfaceKind::Top))
    {
        let xs = surface.polygon.iter().map(|p| p[0]);
        let (x0, x1) = xs.fold((f32::MAX, f32::MIN), |(a, b), x| (a.min(x), b.max(x)));
        let board_z = surface.center()[1];
        let y = surface.height as f64 + 2.0 * SETTLE_DROP;
        let mut along = x0 + 0.05;
        while along < x1 - 0.05 {
            let id = format!("can_{}", objects.len());
            let pose = at(x + along as f64, y, z + board_z as f64, 0.0);
            let inside = RelationKind::Inside;
            objects.push(place(
                &id,
                "can",
                &can.mesh,
                pose,
                Some("store_shelf"),
                inside,
            ));
            along += 0.09;
        }
    }
    objects
}

/// A pose with yaw and translation, unit scale.
pub fn at(x: f64, y: f64, z: f64, yaw: f64) -> Pose {
    Pose::new(1.0, yaw, Vector3::new(x, y, z))
}

/// A 6 × 4 m room with one door in the front wall, holding `objects`.
pub fn room(objects: Vec<EvalObject>) -> EvalScene {
    EvalScene {
        objects,
        architecture: Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9),
    }
}

/// A 6 × 4 m room split at x = 0 by a partition wall whose only opening is a 0.9 m door
/// centred at z = 0.
pub fn two_rooms(objects: Vec<EvalObject>) -> EvalScene {
    let mut arch = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
    arch.doors.clear();
    arch.walls.push(Wall {
        id: "partition".into(),
        start: Point2::new(0.0, -2.0),
        end: Point2::new(0.0, 2.0),
        height: 2.8,
        thickness: 0.1,
    });
    arch.doors.push(DoorOpening {
        id: "door_inner".into(),
        wall: "partition".into(),
        offset: 2.0,
        width: 0.9,
        height: 2.1,
        leaf: None,
        joins: None,
    });
    EvalScene {
        objects,
        architecture: arch,
    }
}

/// A furnished 30-object room: 4 tables each with a book and two cups, 8 chairs beside them,
/// and 2 shelves holding 2 boxes each.
pub fn thirty_objects() -> EvalScene {
    let mut objects = Vec::new();
    let (t, c, s, b, k) = (
        table(1.2, 0.8, 0.75, 0.04),
        chair(),
        shelf(),
        block(0.2, 0.3, 0.25),
        cup(),
    );
    let book = block(0.2, 0.04, 0.3);
    for (n, (x, z)) in [(-1.3, -0.5), (1.3, -0.5), (-1.3, 1.2), (1.3, 1.2)]
        .into_iter()
        .enumerate()
    {
        let tid = format!("table_{n}");
        objects.push(place(
            &tid,
            "table",
            &t,
            at(x, 0.0, z, 0.0),
            None,
            RelationKind::OnFloor,
        ));
        objects.push(place(
            &format!("book_{n}"),
            "book",
            &book,
            at(x - 0.3, 0.75, z, 0.3),
            Some(&tid),
            RelationKind::On,
        ));
        for (m, dx) in [0.1, 0.35].into_iter().enumerate() {
            objects.push(place(
                &format!("cup_{n}_{m}"),
                "cup",
                &k,
                at(x + dx, 0.75, z + 0.1, 0.0),
                Some(&tid),
                RelationKind::On,
            ));
        }
        for (m, (dx, yaw)) in [(-0.95, FRAC_PI_2), (0.95, -FRAC_PI_2)]
            .into_iter()
            .enumerate()
        {
            objects.push(place(
                &format!("chair_{n}_{m}"),
                "chair",
                &c,
                at(x + dx, 0.0, z, yaw),
                None,
                RelationKind::OnFloor,
            ));
        }
    }
    for (n, x) in [-0.5, 0.5].into_iter().enumerate() {
        let sid = format!("shelf_{n}");
        objects.push(place(
            &sid,
            "shelf",
            &s,
            at(x, 0.0, -1.8, 0.0),
            None,
            RelationKind::AgainstWall,
        ));
        for (m, y) in [0.42, 0.82].into_iter().enumerate() {
            objects.push(place(
                &format!("box_{n}_{m}"),
                "box",
                &b,
                at(x, y, -1.7, 0.0),
                Some(&sid),
                RelationKind::Inside,
            ));
        }
    }
    room(objects)
}

/// Writes a GLB holding one node per (name, mesh), meshes already in world coordinates, with
/// identity transforms.
pub fn write_glb(path: &std::path::Path, nodes: &[(&str, &Mesh)]) {
    write_glb_under(path, None, nodes)
}

/// Like [`write_glb`], with the nodes as children of one mesh-less root node when `root` names
/// one (as many exporters do).
pub fn write_glb_under(path: &std::path::Path, root: Option<&str>, nodes: &[(&str, &Mesh)]) {
    let mut bin: Vec<u8> = Vec::new();
    let mut views = Vec::new();
    let mut accessors = Vec::new();
    let mut meshes = Vec::new();
    let mut json_nodes = Vec::new();
    for (k, (name, mesh)) in nodes.iter().enumerate() {
        let (positions, triangles) = mesh.merged();
        let mut lo = [f32::MAX; 3];
        let mut hi = [f32::MIN; 3];
        let pos_offset = bin.len();
        for p in &positions {
            for a in 0..3 {
                lo[a] = lo[a].min(p[a]);
                hi[a] = hi[a].max(p[a]);
                bin.extend_from_slice(&p[a].to_le_bytes());
            }
        }
        let idx_offset = bin.len();
        for t in &triangles {
            for i in t {
                bin.extend_from_slice(&i.to_le_bytes());
            }
        }
        views.push(serde_json::json!({"buffer": 0, "byteOffset": pos_offset, "byteLength": positions.len() * 12}));
        views.push(serde_json::json!({"buffer": 0, "byteOffset": idx_offset, "byteLength": triangles.len() * 12}));
        accessors.push(serde_json::json!({"bufferView": 2 * k, "componentType": 5126, "count": positions.len(), "type": "VEC3", "min": lo, "max": hi}));
        accessors.push(serde_json::json!({"bufferView": 2 * k + 1, "componentType": 5125, "count": triangles.len() * 3, "type": "SCALAR"}));
        meshes.push(serde_json::json!({"primitives": [{"attributes": {"POSITION": 2 * k}, "indices": 2 * k + 1}]}));
        json_nodes.push(serde_json::json!({"name": name, "mesh": k}));
    }
    let scene_nodes = match root {
        Some(name) => {
            json_nodes.push(
                serde_json::json!({"name": name, "children": (0..nodes.len()).collect::<Vec<_>>()}),
            );
            vec![nodes.len()]
        }
        None => (0..nodes.len()).collect::<Vec<_>>(),
    };
    let json = serde_json::json!({
        "asset": {"version": "2.0"},
        "scene": 0,
        "scenes": [{"nodes": scene_nodes}],
        "nodes": json_nodes,
        "meshes": meshes,
        "accessors": accessors,
        "bufferViews": views,
        "buffers": [{"byteLength": bin.len()}],
    });
    let mut json_bytes = serde_json::to_vec(&json).unwrap();
    while json_bytes.len() % 4 != 0 {
        json_bytes.push(b' ');
    }
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let total = 12 + 8 + json_bytes.len() + 8 + bin.len();
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_bytes.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&json_bytes);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(&bin);
    std::fs::write(path, out).unwrap();
}

/// How far apart two runs of the stability simulation may leave a body (m, rad): a twentieth
/// of the metric's 1 cm and 0.1 rad.
pub const SAME_END: (f64, f64) = (0.0005, 0.005);

/// Whether the reference run left `m` clearly still (under half the metric's thresholds) or
/// clearly fallen (over twice them); a body in between is at the metric's edge, where any
/// perturbation (even rounding) may tip it either way, and is not compared.
pub fn clear_cut(m: &BodyMotion) -> Option<bool> {
    let (d, r) = (m.displacement / MAX_DISPLACEMENT, m.rotation / MAX_ROTATION);
    if d < 0.5 && r < 0.5 {
        Some(false)
    } else if m.non_finite || d > 2.0 || r > 2.0 {
        Some(true)
    } else {
        None
    }
}

/// Checks that `run` leaves every body where `reference` (the same bodies, in the same order)
/// does: within [`SAME_END`] of a body the reference leaves clearly still, unstable where the
/// reference clearly topples it. Returns the ids of the bodies at the edge, which are not
/// compared.
pub fn assert_same_ends<'a>(run: &[BodyMotion], reference: &'a [BodyMotion]) -> Vec<&'a str> {
    assert_eq!(
        run.len(),
        reference.len(),
        "the runs simulated different bodies"
    );
    let mut marginal = Vec::new();
    for (m, r) in run.iter().zip(reference) {
        assert_eq!(m.id, r.id, "bodies out of order");
        match clear_cut(r) {
            Some(false) => assert!(
                (m.displacement - r.displacement).abs() <= SAME_END.0
                    && (m.rotation - r.rotation).abs() <= SAME_END.1,
                "{} ends apart: {m:?} against {r:?}",
                r.id
            ),
            Some(true) => assert!(m.is_unstable(), "{} no longer falls: {m:?}", r.id),
            None => marginal.push(r.id.as_str()),
        }
    }
    marginal
}
