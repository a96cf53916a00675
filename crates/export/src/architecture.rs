//! The static architecture as solid boxes: a floor slab under y = 0, wall boxes split around
//! their door and window openings, the glass pane in each window, and the leaves hung in the
//! doors. Every exporter builds floor, walls, panes and leaves from these pieces so that the
//! formats agree.

use nalgebra::{Point3, Rotation3, Vector3};
use scenethesis_materials::{outdoor_ground, surface_or};
use scenethesis_scene_graph::{
    Architecture, Environment, JointState, Material, Mesh, MeshPart, SceneLook, Wall, WallBox,
};

/// Thickness of the floor slab below y = 0, in metres.
pub const FLOOR_THICKNESS: f64 = 0.05;

/// What a piece of architecture is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum PieceKind {
    /// The floor slab (its top face is the plane y = 0).
    Floor,
    /// A wall, possibly split into several boxes around door and window openings.
    Wall,
    /// A window's glass pane, filling its opening.
    Window,
}

/// An oriented box in world coordinates: centre, half extents along its own axes, and a yaw
/// about +Y (its local +X runs along a wall's centre line, local +Z across the thickness).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrientedBox {
    /// Centre of the box in world coordinates.
    pub center: Point3<f64>,
    /// Half of the box's size along its local x, y and z axes.
    pub half_extents: Vector3<f64>,
    /// Rotation about +Y in radians (the scene's yaw convention: +Z turns toward +X).
    pub yaw: f64,
}

impl OrientedBox {
    /// The box's rotation.
    pub fn rotation(&self) -> Rotation3<f64> {
        Rotation3::from_axis_angle(&Vector3::y_axis(), self.yaw)
    }

    /// The box as a closed, outward-oriented mesh part in world coordinates.
    pub fn to_mesh_part(&self, name: &str, material: usize) -> MeshPart {
        let rotation = self.rotation();
        let h = self.half_extents;
        let corners = std::array::from_fn(|i| {
            let local = Vector3::new(
                if i & 1 == 0 { -h.x } else { h.x },
                if i & 2 == 0 { -h.y } else { h.y },
                if i & 4 == 0 { -h.z } else { h.z },
            );
            let p = self.center + rotation * local;
            [p.x as f32, p.y as f32, p.z as f32]
        });
        // A rotation keeps the corner numbering right-handed, so the faces stay outward.
        MeshPart::from_box_corners(name, material, corners)
    }
}

/// One named piece of architecture (the floor or one wall) made of boxes.
#[derive(Debug, Clone, PartialEq)]
pub struct Piece {
    /// The architecture id (`floor`, `wall_0`, …): the node name in every format.
    pub id: String,
    /// Floor or wall.
    pub kind: PieceKind,
    /// The solid boxes; a wall with a door has a box on each side and a lintel above it.
    pub boxes: Vec<OrientedBox>,
    /// Its surface: [`floor_material`] indoors, the look's ground ([`outdoor_ground`]) outdoors,
    /// [`wall_material`] for walls, [`glass_material`] for window panes.
    pub material: Material,
}

impl Piece {
    /// The piece as a mesh in world coordinates, one part per box, with one material.
    pub fn to_mesh(&self) -> Mesh {
        let material = self.material.clone();
        let parts = self
            .boxes
            .iter()
            .enumerate()
            .map(|(i, b)| b.to_mesh_part(&format!("{}_{i}", self.id), 0))
            .collect();
        Mesh {
            parts,
            materials: vec![material],
        }
    }
}

pub use scenethesis_materials::{floor_material, glass_material, ground_material, wall_material};

/// The architecture as solid pieces: the floor slab first, then each wall in order, cut around
/// the door and window openings it holds ([`Architecture::wall_spans`]: a box left and right of
/// each opening, a lintel above it when it is lower than the wall, and under a window the wall
/// below its sill), then each window's glass pane ([`Architecture::window_pane`], in
/// [`glass_material`]), named by the window's id. Indoors the floor and
/// walls wear the materials `look` records for the surfaces `floor` and `walls`
/// ([`SceneLook::surfaces`]), else [`floor_material`] and [`wall_material`]; outdoors the
/// ground wears the look's `ground` ([`outdoor_ground`]).
pub fn pieces(architecture: &Architecture, look: &SceneLook) -> Vec<Piece> {
    let floor = &architecture.floor;
    let extent = floor.extent();
    let outdoor = architecture.environment == Environment::Outdoor;
    let wall_look = surface_or(&look.surfaces, "walls", wall_material);
    let mut out = vec![Piece {
        id: floor.id.clone(),
        kind: PieceKind::Floor,
        material: if outdoor {
            outdoor_ground(&look.surfaces)
        } else {
            surface_or(&look.surfaces, "floor", floor_material)
        },
        boxes: vec![OrientedBox {
            center: Point3::new(
                (floor.min.x + floor.max.x) / 2.0,
                -FLOOR_THICKNESS / 2.0,
                (floor.min.y + floor.max.y) / 2.0,
            ),
            half_extents: Vector3::new(extent.x / 2.0, FLOOR_THICKNESS / 2.0, extent.y / 2.0),
            yaw: 0.0,
        }],
    }];
    for wall in &architecture.walls {
        let boxes: Vec<_> = architecture
            .wall_spans(wall)
            .iter()
            .map(|span| oriented(wall, span))
            .collect();
        if boxes.is_empty() {
            continue;
        }
        out.push(Piece {
            id: wall.id.clone(),
            kind: PieceKind::Wall,
            material: wall_look.clone(),
            boxes,
        });
    }
    for window in &architecture.windows {
        if let Some((wall, pane)) = architecture.window_pane(window) {
            out.push(Piece {
                id: window.id.clone(),
                kind: PieceKind::Window,
                material: glass_material(),
                boxes: vec![oriented(wall, &pane)],
            });
        }
    }
    out
}

/// A box of `wall` ([`WallBox`]) as an oriented box in world coordinates.
fn oriented(wall: &Wall, span: &WallBox) -> OrientedBox {
    let direction = wall.direction();
    OrientedBox {
        center: span.center(wall),
        half_extents: span.half_extents(),
        yaw: (-direction.y).atan2(direction.x),
    }
}

/// A room door's leaves: moving links fixed to the world by their hinges (the articulation of
/// [`crate::articulation::Articulation::of_leaf`]); one for a single door, two mirrored for a
/// double door.
pub(crate) struct Leaf {
    /// The door's id: writers name each leaf's link `<door>_<joint>` (`<door>_leaf`,
    /// `<door>_leaf_2`), as an object's links.
    pub door: String,
    /// The id of the wall the door is cut into.
    pub wall: String,
    /// The leaves' joints in world coordinates, with their states.
    pub joints: Vec<JointState>,
    /// The closed leaves' boxes in world coordinates: one part per leaf, carried by the joint
    /// of its name.
    pub mesh: Mesh,
}

/// The leaves of every door that has any, in the order of the doors.
pub(crate) fn leaves(architecture: &Architecture) -> Vec<Leaf> {
    architecture
        .doors
        .iter()
        .filter_map(|door| {
            let geometry = architecture.door_leaves(door);
            let first = geometry.first()?;
            Some(Leaf {
                door: door.id.clone(),
                wall: door.wall.clone(),
                joints: geometry.iter().map(|g| g.joint.clone()).collect(),
                mesh: Mesh {
                    parts: geometry.iter().flat_map(|g| g.mesh.parts.clone()).collect(),
                    materials: first.mesh.materials.clone(),
                },
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn room_has_floor_and_four_walls_with_a_door_gap() {
        let room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let pieces = pieces(&room, &SceneLook::default());
        let ids: Vec<_> = pieces.iter().map(|p| p.id.as_str()).collect();
        assert_eq!(ids, ["floor", "wall_0", "wall_1", "wall_2", "wall_3"]);
        assert_eq!(pieces[1].boxes.len(), 1);
        // wall_2 holds the door: left, lintel, right.
        let door_wall = &pieces[3];
        assert_eq!(door_wall.boxes.len(), 3);
        let (door, _) = room.door_position(&room.doors[0]).unwrap();
        for b in &door_wall.boxes {
            let part = b.to_mesh_part("b", 0);
            assert!(part.is_closed_and_oriented());
            assert!(part.signed_volume() > 0.0);
            let mesh = Mesh {
                parts: vec![part],
                materials: vec![wall_material()],
            };
            let bounds = mesh.bounds().unwrap();
            // Nothing solid in the door opening below the door's height.
            let in_gap_x = bounds.min.x < door.x + 0.44 && bounds.max.x > door.x - 0.44;
            if in_gap_x {
                assert!(
                    bounds.min.y >= 2.1 - 1e-5,
                    "box blocks the door: {bounds:?}"
                );
            }
        }
        // A wall without doors spans its length plus the thickness and sits on the centre line.
        let w0 = &pieces[1].boxes[0];
        assert!((w0.half_extents.x * 2.0 - (room.walls[0].length() + 0.1)).abs() < 1e-9);
        let part = w0.to_mesh_part("w", 0);
        let b = Mesh {
            parts: vec![part],
            materials: vec![wall_material()],
        }
        .bounds()
        .unwrap();
        let expected = room.walls[0].aabb();
        assert!((b.min - expected.min).norm() < 1e-5 && (b.max - expected.max).norm() < 1e-5);
    }

    #[test]
    fn floor_and_walls_wear_the_looks_surfaces() {
        let room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let mut look = SceneLook::default();
        let walnut = Material::new("walnut", [0.11, 0.05, 0.025], 0.55);
        let sage = Material::new("sage_paint", [0.33, 0.43, 0.25], 0.5);
        look.surfaces.insert("floor".into(), walnut.clone());
        look.surfaces.insert("walls".into(), sage.clone());
        let pieces = pieces(&room, &look);
        let floor = &pieces[0].material;
        assert_eq!(floor.name, "walnut_floorboards");
        assert_eq!(floor.base_color, walnut.base_color);
        let library = |m: &Material| scenethesis_materials::resolve(&m.name).map(|l| l.id);
        assert_eq!(library(floor), Some("oak_floorboards"));
        for wall in &pieces[1..] {
            assert_eq!(library(&wall.material), Some("wall_paint"));
            assert_eq!(wall.material.base_color, sage.base_color);
        }
        // Without a look the defaults stay.
        let plain = super::pieces(&room, &SceneLook::default());
        assert_eq!(plain[0].material, floor_material());
        assert_eq!(plain[1].material, wall_material());
    }

    #[test]
    fn floor_slab_top_is_at_zero() {
        let room = Architecture::open_ground(10.0, 8.0);
        let pieces = pieces(&room, &SceneLook::default());
        assert_eq!(pieces.len(), 1);
        let b = pieces[0].to_mesh().bounds().unwrap();
        assert!(b.max.y.abs() < 1e-9 && (b.min.y + FLOOR_THICKNESS).abs() < 1e-6);
        assert!((b.max.x - 5.0).abs() < 1e-6 && (b.min.z + 4.0).abs() < 1e-6);
    }

    #[test]
    fn open_ground_wears_the_looks_ground_else_soil() {
        let ground = Architecture::open_ground(10.0, 8.0);
        assert_eq!(
            pieces(&ground, &SceneLook::default())[0].material,
            ground_material()
        );
        let mut look = SceneLook::default();
        let sand = scenethesis_materials::by_id("sand").unwrap().material();
        look.surfaces
            .insert(scenethesis_materials::GROUND_SURFACE.into(), sand.clone());
        assert_eq!(pieces(&ground, &look)[0].material, sand);
        // Indoors the ground is not a floor.
        let room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        assert_eq!(pieces(&room, &look)[0].material, floor_material());
    }
}
