//! CPU-side geometry: posed meshes, floors, walls with door and window gaps, window panes and
//! ground planes flattened
//! into one vertex list with per-corner normals, linear albedo and instance index.

use std::collections::BTreeSet;
use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use nalgebra::{Point2, Point3, Vector2, Vector3};
use scenethesis_scene_graph::{
    leaf_material, Architecture, Environment, MeshPart, Wall, GROUND_ID,
};

use crate::{Backdrop, RenderError, RenderScene};

/// Linear albedo of a room's floor (light oak).
const FLOOR_ALBEDO: [f32; 3] = [0.50, 0.36, 0.22];
/// Linear albedo of a room's walls (warm off-white).
const WALL_ALBEDO: [f32; 3] = [0.72, 0.70, 0.66];
/// Linear albedo of a window's glass pane (a pale sky blue: the renderer draws no
/// transparency, so the pane shows as daylit glass).
const GLASS_ALBEDO: [f32; 3] = [0.55, 0.72, 0.86];
/// Linear albedo of the studio floor (neutral grey).
const STUDIO_ALBEDO: [f32; 3] = [0.55, 0.55, 0.55];
/// Linear albedo of outdoor ground (dry grass).
const GROUND_ALBEDO: [f32; 3] = [0.30, 0.34, 0.18];
/// Faces meeting at less than this angle share a smoothed normal (cos 35°).
const CREASE_COS: f32 = 0.819;

/// One vertex as the GPU sees it.
#[repr(C)]
#[derive(Debug, Clone, Copy, PartialEq, Pod, Zeroable)]
pub(crate) struct Vertex {
    /// World position in metres.
    pub position: [f32; 3],
    /// Unit world normal.
    pub normal: [f32; 3],
    /// Linear RGB albedo.
    pub albedo: [f32; 3],
    /// Instance index: 1-based index into the id table.
    pub instance: u32,
}

/// The vertex range of one wall, kept apart so walls can be cut away per camera.
#[derive(Debug, Clone)]
pub(crate) struct WallRange {
    /// Vertices of the wall's boxes.
    pub vertices: Range<u32>,
    /// A point on the wall's centre line, in (x, z).
    pub start: Point2<f64>,
    /// Unit normal pointing into the room, in (x, z).
    pub inward: Vector2<f64>,
    /// Wall thickness in metres.
    pub thickness: f64,
}

/// A whole scene flattened for drawing.
#[derive(Debug, Clone, Default)]
pub(crate) struct SceneGeometry {
    /// Non-indexed triangle list.
    pub vertices: Vec<Vertex>,
    /// Vertices of the objects (the shadow casters), first in the list.
    pub objects: Range<u32>,
    /// Vertices drawn from every camera: objects, floor, ground.
    pub always: Range<u32>,
    /// One entry per wall, after `always`.
    pub walls: Vec<WallRange>,
    /// Instance index `k` (1-based) names `ids[k - 1]`.
    pub ids: Vec<String>,
}

impl SceneGeometry {
    /// Flattens `scene`; fails on duplicate ids or invalid poses.
    pub fn build(scene: &RenderScene) -> Result<Self, RenderError> {
        let mut geo = SceneGeometry::default();
        let mut seen = BTreeSet::new();
        for inst in &scene.instances {
            if !seen.insert(inst.id.as_str()) {
                return Err(RenderError::DuplicateId(inst.id.clone()));
            }
            let pose = &inst.pose;
            if !pose.is_finite() || pose.scale <= 0.0 {
                return Err(RenderError::InvalidPose {
                    id: inst.id.clone(),
                });
            }
            let index = geo.push_id(&inst.id);
            let rotation = pose.rotation();
            for part in &inst.mesh.parts {
                let albedo = inst
                    .mesh
                    .materials
                    .get(part.material)
                    .map_or([0.6; 3], |m| {
                        [m.base_color[0], m.base_color[1], m.base_color[2]]
                    });
                let world: Vec<[f32; 3]> = part
                    .positions
                    .iter()
                    .map(|p| {
                        let w = pose.transform_point(&Point3::from(*p).cast::<f64>());
                        [w.x as f32, w.y as f32, w.z as f32]
                    })
                    .collect();
                let normals = corner_normals(part);
                for (t, tri) in part.triangles.iter().enumerate() {
                    for (k, &v) in tri.iter().enumerate() {
                        let n = rotation * Vector3::from(normals[3 * t + k]).cast::<f64>();
                        geo.vertices.push(Vertex {
                            position: world[v as usize],
                            normal: [n.x as f32, n.y as f32, n.z as f32],
                            albedo,
                            instance: index,
                        });
                    }
                }
            }
        }
        geo.objects = 0..geo.vertices.len() as u32;
        let arch = scene.architecture.as_ref();
        let bounds = scene.bounds();
        let ground_plane = matches!(scene.backdrop, Backdrop::Studio | Backdrop::Sky);
        if let Some(arch) = arch {
            let outdoor = arch.environment == Environment::Outdoor;
            if !(ground_plane && outdoor) {
                let index = geo.push_id(&arch.floor.id);
                geo.push_quad_y(
                    0.0,
                    [arch.floor.min.x, arch.floor.min.y],
                    [arch.floor.max.x, arch.floor.max.y],
                    if outdoor {
                        GROUND_ALBEDO
                    } else {
                        scene
                            .surface_albedo
                            .get("floor")
                            .copied()
                            .unwrap_or(FLOOR_ALBEDO)
                    },
                    index,
                );
            }
        }
        if ground_plane {
            let (id, albedo, half) = match scene.backdrop {
                Backdrop::Sky => (
                    arch.filter(|a| a.environment == Environment::Outdoor)
                        .map_or(GROUND_ID, |a| a.floor.id.as_str()),
                    GROUND_ALBEDO,
                    500.0,
                ),
                _ => (
                    GROUND_ID,
                    STUDIO_ALBEDO,
                    (bounds.size().x.max(bounds.size().z) * 10.0).max(20.0),
                ),
            };
            // Under a room's own floor, sink the plane a little to avoid depth fighting.
            let y = if arch.is_some_and(|a| a.environment == Environment::Indoor) {
                -0.002
            } else {
                0.0
            };
            let c = bounds.center();
            let index = geo.push_id(id);
            geo.push_quad_y(
                y,
                [c.x - half, c.z - half],
                [c.x + half, c.z + half],
                albedo,
                index,
            );
        }
        geo.always = 0..geo.vertices.len() as u32;
        if let Some(arch) = arch {
            let wall_albedo = scene
                .surface_albedo
                .get("walls")
                .copied()
                .unwrap_or(WALL_ALBEDO);
            for wall in &arch.walls {
                let start = geo.vertices.len() as u32;
                let index = geo.push_id(&wall.id);
                for (center, half) in wall_boxes(arch, wall) {
                    geo.push_box(wall, center, half, wall_albedo, index);
                }
                geo.push_leaves(arch, wall);
                geo.push_panes(arch, wall);
                geo.walls.push(WallRange {
                    vertices: start..geo.vertices.len() as u32,
                    start: wall.start,
                    inward: wall.inward_normal(),
                    thickness: wall.thickness,
                });
            }
        }
        Ok(geo)
    }

    fn push_id(&mut self, id: &str) -> u32 {
        self.ids.push(id.to_owned());
        self.ids.len() as u32
    }

    fn push_triangle(&mut self, corners: [Point3<f64>; 3], albedo: [f32; 3], instance: u32) {
        let n = (corners[1] - corners[0])
            .cross(&(corners[2] - corners[0]))
            .normalize();
        for c in corners {
            self.vertices.push(Vertex {
                position: [c.x as f32, c.y as f32, c.z as f32],
                normal: [n.x as f32, n.y as f32, n.z as f32],
                albedo,
                instance,
            });
        }
    }

    /// An upward-facing rectangle at height `y` spanning (x, z) from `min` to `max`.
    fn push_quad_y(&mut self, y: f64, min: [f64; 2], max: [f64; 2], albedo: [f32; 3], id: u32) {
        let p = |x: f64, z: f64| Point3::new(x, y, z);
        let (a, b, c, d) = (
            p(min[0], min[1]),
            p(max[0], min[1]),
            p(max[0], max[1]),
            p(min[0], max[1]),
        );
        // Counter-clockwise seen from above (+Y): a → d → c, a → c → b.
        self.push_triangle([a, d, c], albedo, id);
        self.push_triangle([a, c, b], albedo, id);
    }

    /// The leaves hung in `wall`'s doors, at their states: drawn, and cut away, with the wall,
    /// each under its door's id.
    fn push_leaves(&mut self, arch: &Architecture, wall: &Wall) {
        for door in arch.doors.iter().filter(|d| d.wall == wall.id) {
            let Some(leaf) = arch.door_leaf(door) else {
                continue;
            };
            let index = self.push_id(&door.id);
            let albedo = leaf_material().base_color;
            let albedo = [albedo[0], albedo[1], albedo[2]];
            for part in &leaf.posed_mesh().parts {
                for t in &part.triangles {
                    let corner = |k: usize| Point3::from(part.positions[t[k] as usize]).cast();
                    self.push_triangle([corner(0), corner(1), corner(2)], albedo, index);
                }
            }
        }
    }

    /// The glass panes of `wall`'s windows ([`Architecture::window_pane`]) in
    /// [`GLASS_ALBEDO`]: drawn, and cut away, with the wall, each under its window's id.
    fn push_panes(&mut self, arch: &Architecture, wall: &Wall) {
        for window in arch.windows.iter().filter(|w| w.wall == wall.id) {
            if let Some((wall, pane)) = arch.window_pane(window) {
                let index = self.push_id(&window.id);
                let (center, half) = (pane.center(wall), pane.half_extents());
                self.push_box(wall, center, half, GLASS_ALBEDO, index);
            }
        }
    }

    /// A box aligned with `wall`, centred at `center` (x, y, z) with half extents along the
    /// wall, up and across.
    fn push_box(
        &mut self,
        wall: &Wall,
        center: Point3<f64>,
        half: Vector3<f64>,
        albedo: [f32; 3],
        id: u32,
    ) {
        let d = wall.direction();
        let along = Vector3::new(d.x, 0.0, d.y) * half.x;
        let up = Vector3::y() * half.y;
        let n = wall.inward_normal();
        let across = Vector3::new(n.x, 0.0, n.y) * half.z;
        let axes = [along, up, across];
        // Each face: the axis it faces along and its sign.
        for axis in 0..3 {
            for sign in [-1.0, 1.0] {
                let normal = axes[axis] * sign;
                let (u, v) = (axes[(axis + 1) % 3], axes[(axis + 2) % 3]);
                let fc = center + normal;
                let q = [fc - u - v, fc + u - v, fc + u + v, fc - u + v];
                let mut tris = [[q[0], q[1], q[2]], [q[0], q[2], q[3]]];
                let facing = (q[1] - q[0]).cross(&(q[2] - q[0])).dot(&normal);
                if facing < 0.0 {
                    for t in &mut tris {
                        t.swap(1, 2);
                    }
                }
                for t in tris {
                    self.push_triangle(t, albedo, id);
                }
            }
        }
    }
}

/// The boxes (centre, half extents along / up / across the wall) that make up a wall with its
/// door and window openings cut out ([`Architecture::wall_spans`], as every exporter cuts it).
fn wall_boxes(arch: &Architecture, wall: &Wall) -> Vec<(Point3<f64>, Vector3<f64>)> {
    arch.wall_spans(wall)
        .iter()
        .map(|span| (span.center(wall), span.half_extents()))
        .collect()
}

/// Per-corner normals of a part (three per triangle): each corner averages the area-weighted
/// normals of the triangles around its vertex that meet its own face at less than 35°, so
/// curved surfaces look smooth and box edges stay sharp.
fn corner_normals(part: &MeshPart) -> Vec<[f32; 3]> {
    let faces: Vec<Vector3<f32>> = (0..part.triangles.len())
        .map(|t| {
            let [a, b, c] = part.triangle(t);
            (b - a).cross(&(c - a))
        })
        .collect();
    let unit: Vec<Vector3<f32>> = faces
        .iter()
        .map(|f| f.try_normalize(1e-20).unwrap_or_else(Vector3::y))
        .collect();
    // Compressed adjacency: the triangles around each vertex.
    let n = part.positions.len();
    let mut start = vec![0u32; n + 1];
    for tri in &part.triangles {
        for &v in tri {
            start[v as usize + 1] += 1;
        }
    }
    for i in 0..n {
        start[i + 1] += start[i];
    }
    let mut fill = start.clone();
    let mut around = vec![0u32; start[n] as usize];
    for (t, tri) in part.triangles.iter().enumerate() {
        for &v in tri {
            around[fill[v as usize] as usize] = t as u32;
            fill[v as usize] += 1;
        }
    }
    let mut out = Vec::with_capacity(part.triangles.len() * 3);
    for (t, tri) in part.triangles.iter().enumerate() {
        for &v in tri {
            let range = start[v as usize] as usize..start[v as usize + 1] as usize;
            let sum: Vector3<f32> = around[range]
                .iter()
                .filter(|&&o| unit[o as usize].dot(&unit[t]) > CREASE_COS)
                .map(|&o| faces[o as usize])
                .sum();
            let normal = sum.try_normalize(1e-20).unwrap_or(unit[t]);
            out.push([normal.x, normal.y, normal.z]);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::{Architecture, WindowOpening};

    #[test]
    fn door_leaves_a_gap_in_its_wall() {
        let room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let front = room.wall("wall_2").unwrap();
        let boxes = wall_boxes(&room, front);
        assert_eq!(boxes.len(), 3, "two side pieces and a lintel: {boxes:?}");
        let lintel = boxes
            .iter()
            .find(|(c, _)| c.y > 2.0)
            .expect("a lintel above the door");
        assert!((lintel.1.x - 0.45).abs() < 1e-9);
        // No full-height piece covers the door's centre (x = 0 on the front wall).
        for (c, h) in &boxes {
            if h.y * 2.0 > 2.7 {
                assert!((c.x.abs() - h.x) >= 0.45 - 1e-9, "{c:?} {h:?}");
            }
        }
        let back = room.wall("wall_0").unwrap();
        assert_eq!(wall_boxes(&room, back).len(), 1);
    }

    #[test]
    fn a_window_shows_as_a_hole_with_a_pane() {
        let mut room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let back = room.wall("wall_0").unwrap().clone();
        let window = WindowOpening::centred("window_0", &back, 1.2, 1.2, 0.9);
        room.windows.push(window);
        let back = &back;
        let boxes = wall_boxes(&room, back);
        assert_eq!(boxes.len(), 4, "piers, the wall below the sill, a lintel");
        // Nothing of the wall at the window's centre (x = 0, y = 1.5).
        for (c, h) in &boxes {
            let covers = (c.x.abs() <= h.x) && (c.y - 1.5).abs() <= h.y;
            assert!(!covers, "{c:?} {h:?}");
        }
        let mut geo = SceneGeometry::default();
        geo.push_panes(&room, back);
        assert_eq!(geo.vertices.len(), 36, "one box");
        assert_eq!(geo.ids, ["window_0"]);
        assert!(geo.vertices.iter().all(|v| v.albedo == GLASS_ALBEDO));
    }

    #[test]
    fn box_edges_stay_sharp_and_normals_point_out() {
        let part = MeshPart::cuboid("cube", 0, [0.0; 3], [1.0; 3]);
        let normals = corner_normals(&part);
        assert_eq!(normals[0], [0.0, 0.0, -1.0]);
        assert_eq!(normals[3 * 4], [0.0, -1.0, 0.0]);
        assert_eq!(normals[3 * 11 + 2], [1.0, 0.0, 0.0]);
    }
}
