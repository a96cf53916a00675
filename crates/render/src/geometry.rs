//! CPU-side geometry: posed meshes, floors, walls with door and window gaps, window panes and
//! ground planes flattened into one vertex list with per-corner normals, surface parameters,
//! texture coordinates in metres with tangents (the library's box projection, as the exporters
//! use it) or a part's own texture coordinates into its imported image, and instance index.

use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use nalgebra::{Point2, Point3, Vector2, Vector3};
use scenethesis_materials::{
    floor_material, glass_material, maps, outdoor_ground, resolve, surface_or, wall_material,
    BoxProjection,
};
use scenethesis_scene_graph::{
    leaf_material, Architecture, Environment, Material, MeshPart, Wall, GROUND_ID,
};

use crate::{Backdrop, RenderError, RenderScene};

/// Linear albedo of the studio floor (neutral grey).
const STUDIO_ALBEDO: [f32; 3] = [0.55, 0.55, 0.55];
/// Roughness of the studio floor.
const STUDIO_ROUGHNESS: f32 = 0.8;
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
    /// Linear RGB albedo (with a texture, the factor its base-colour map is multiplied by)
    /// and opacity: below 1 the surface is see-through glass, drawn after the opaque ones.
    pub albedo: [f32; 4],
    /// Instance index: 1-based index into the id table.
    pub instance: u32,
    /// Texture coordinates in tiles of the material (0 without a texture).
    pub uv: [f32; 2],
    /// World tangent along u; `w` the sign of the bitangent (toward the image's top).
    pub tangent: [f32; 4],
    /// Roughness and metalness factors (the metallic-roughness map multiplies them).
    pub roughness_metallic: [f32; 2],
    /// Texture layer: 1 + the layer of the material's maps (a library material's index, or an
    /// imported image's layer after the library's), 0 for a plain colour.
    pub layer: u32,
}

/// How a surface is shaded: a material's colour, roughness and metalness and, when its name
/// resolves to a library material, that material's texture layer and tile size.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Surface {
    albedo: [f32; 4],
    roughness_metallic: [f32; 2],
    layer: u32,
    tile_size_m: Option<f32>,
}

impl Surface {
    /// The surface of a scene material: textured with its library material when its name
    /// resolves to one, the colour and roughness then turned into factors of the maps (so the
    /// surface averages its own colour), else the plain colour.
    pub fn of(material: &Material) -> Self {
        match resolve(&material.name) {
            Some(library) => {
                let maps = maps(library);
                Self {
                    albedo: maps.color_factor(material.base_color),
                    roughness_metallic: [
                        maps.roughness_factor(material.roughness),
                        material.metallic,
                    ],
                    layer: library.index() as u32 + 1,
                    tile_size_m: Some(library.tile_size_m),
                }
            }
            None => Self {
                albedo: material.base_color.map(|c| c.clamp(0.0, 1.0)),
                roughness_metallic: [material.roughness, material.metallic],
                layer: 0,
                tile_size_m: None,
            },
        }
    }

    /// The surface of a material showing its imported image from texture layer `layer`: the
    /// base colour multiplies the image, roughness and metalness as they are.
    fn image(material: &Material, layer: u32) -> Self {
        Self {
            albedo: material.base_color.map(|c| c.clamp(0.0, 1.0)),
            roughness_metallic: [material.roughness, material.metallic],
            layer: layer + 1,
            tile_size_m: None,
        }
    }

    /// An untextured opaque dielectric of linear colour `albedo`.
    pub fn plain(albedo: [f32; 3], roughness: f32) -> Self {
        Self {
            albedo: [albedo[0], albedo[1], albedo[2], 1.0],
            roughness_metallic: [roughness, 0.0],
            layer: 0,
            tile_size_m: None,
        }
    }

    /// The box projection of a part with these positions, when the surface is textured.
    fn projection(&self, positions: &[[f32; 3]]) -> Option<BoxProjection> {
        self.tile_size_m
            .map(|tile| BoxProjection::new(tile, positions))
    }

    /// A vertex of this surface at world `position` with world `normal`; `texture` is the
    /// texture coordinates and world tangent of the corner, when textured.
    fn vertex(
        &self,
        position: [f32; 3],
        normal: [f32; 3],
        texture: Option<([f32; 2], [f32; 4])>,
        instance: u32,
    ) -> Vertex {
        let (uv, tangent) = texture.unwrap_or(([0.0; 2], [1.0, 0.0, 0.0, 1.0]));
        Vertex {
            position,
            normal,
            albedo: self.albedo,
            instance,
            uv,
            tangent,
            roughness_metallic: self.roughness_metallic,
            layer: self.layer,
        }
    }
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
    /// Whether a house has a room on its outer side too (an interior wall): it is cut away only
    /// where it stands between the camera and the floor the camera looks at.
    pub interior: bool,
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
    /// Flattens `scene`; fails on duplicate ids or invalid poses. `images` gives the texture
    /// layer of each imported image on the device, by digest: a part showing one of them is
    /// drawn with it at its own texture coordinates, any other part of a material with an
    /// image in the material's flat colour.
    pub fn build(scene: &RenderScene, images: &BTreeMap<u64, u32>) -> Result<Self, RenderError> {
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
                let material = inst.mesh.materials.get(part.material);
                let image = material.and_then(|m| {
                    let (uvs, image) = part.textured_uvs(m)?;
                    Some((uvs, Surface::image(m, *images.get(&image.digest())?)))
                });
                let surface = match (&image, material) {
                    (Some((_, surface)), _) => *surface,
                    (None, Some(m)) if m.texture.is_some() => Surface::of(&m.without_image()),
                    (None, m) => m.map_or(Surface::plain([0.6; 3], 0.6), Surface::of),
                };
                let own_uvs = image.map(|(uvs, _)| uvs);
                let projection = surface.projection(&part.positions);
                let world: Vec<[f32; 3]> = part
                    .positions
                    .iter()
                    .map(|p| {
                        let w = pose.transform_point(&Point3::from(*p).cast::<f64>());
                        [w.x as f32, w.y as f32, w.z as f32]
                    })
                    .collect();
                let normals = corner_normals(part);
                let to_world = |v: [f32; 3]| {
                    let w = rotation * Vector3::from(v).cast::<f64>();
                    [w.x as f32, w.y as f32, w.z as f32]
                };
                for (t, tri) in part.triangles.iter().enumerate() {
                    // Texture coordinates and tangents in the asset's frame, as exported.
                    let [a, b, c] = part.triangle(t);
                    let face_normal = (b - a).cross(&(c - a));
                    let face = projection.map(|p| p.face(face_normal.into()));
                    for (k, &v) in tri.iter().enumerate() {
                        let local_normal = normals[3 * t + k];
                        let texture = face
                            .map(|f| {
                                let local = f.tangent(local_normal);
                                let [x, y, z] = to_world([local[0], local[1], local[2]]);
                                (f.uv(part.positions[v as usize]), [x, y, z, local[3]])
                            })
                            .or_else(|| {
                                // The image's flat normal map leaves the tangent unused; it
                                // only has to stay off the normal.
                                let uv = own_uvs?[v as usize];
                                let [x, y, z] = to_world(perpendicular(local_normal));
                                Some((uv, [x, y, z, 1.0]))
                            });
                        geo.vertices.push(surface.vertex(
                            world[v as usize],
                            to_world(local_normal),
                            texture,
                            index,
                        ));
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
                let material = if outdoor {
                    outdoor_ground(&scene.surfaces)
                } else {
                    surface_or(&scene.surfaces, "floor", floor_material)
                };
                geo.push_quad_y(
                    0.0,
                    [arch.floor.min.x, arch.floor.min.y],
                    [arch.floor.max.x, arch.floor.max.y],
                    &Surface::of(&material),
                    index,
                );
            }
        }
        if ground_plane {
            let (id, surface, half) = match scene.backdrop {
                Backdrop::Sky => (
                    arch.filter(|a| a.environment == Environment::Outdoor)
                        .map_or(GROUND_ID, |a| a.floor.id.as_str()),
                    Surface::of(&outdoor_ground(&scene.surfaces)),
                    500.0,
                ),
                _ => (
                    GROUND_ID,
                    Surface::plain(STUDIO_ALBEDO, STUDIO_ROUGHNESS),
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
                &surface,
                index,
            );
        }
        geo.always = 0..geo.vertices.len() as u32;
        if let Some(arch) = arch {
            let wall_surface = Surface::of(&surface_or(&scene.surfaces, "walls", wall_material));
            for wall in &arch.walls {
                let start = geo.vertices.len() as u32;
                let index = geo.push_id(&wall.id);
                for (center, half) in wall_boxes(arch, wall) {
                    geo.push_box(wall, center, half, &wall_surface, index);
                }
                geo.push_leaves(arch, wall);
                geo.push_panes(arch, wall);
                geo.walls.push(WallRange {
                    vertices: start..geo.vertices.len() as u32,
                    start: wall.start,
                    inward: wall.inward_normal(),
                    thickness: wall.thickness,
                    interior: is_interior(arch, wall),
                });
            }
        }
        Ok(geo)
    }

    fn push_id(&mut self, id: &str) -> u32 {
        self.ids.push(id.to_owned());
        self.ids.len() as u32
    }

    /// A flat-shaded world-space triangle of `surface`, its texture coordinates projected by
    /// `projection` (the box projection of the piece it belongs to).
    fn push_triangle(
        &mut self,
        corners: [Point3<f64>; 3],
        surface: &Surface,
        projection: Option<&BoxProjection>,
        instance: u32,
    ) {
        let n = (corners[1] - corners[0])
            .cross(&(corners[2] - corners[0]))
            .normalize();
        let normal = [n.x as f32, n.y as f32, n.z as f32];
        let face = projection.map(|p| p.face(normal));
        for c in corners {
            let position = [c.x as f32, c.y as f32, c.z as f32];
            let texture = face.map(|f| (f.uv(position), f.tangent(normal)));
            self.vertices
                .push(surface.vertex(position, normal, texture, instance));
        }
    }

    /// An upward-facing rectangle at height `y` spanning (x, z) from `min` to `max`.
    fn push_quad_y(&mut self, y: f64, min: [f64; 2], max: [f64; 2], surface: &Surface, id: u32) {
        let p = |x: f64, z: f64| Point3::new(x, y, z);
        let (a, b, c, d) = (
            p(min[0], min[1]),
            p(max[0], min[1]),
            p(max[0], max[1]),
            p(min[0], max[1]),
        );
        let projection =
            surface.projection(&[a, b, c, d].map(|p| [p.x as f32, p.y as f32, p.z as f32]));
        // Counter-clockwise seen from above (+Y): a → d → c, a → c → b.
        self.push_triangle([a, d, c], surface, projection.as_ref(), id);
        self.push_triangle([a, c, b], surface, projection.as_ref(), id);
    }

    /// The leaves hung in `wall`'s doors (both of a double door), at their states: drawn, and
    /// cut away, with the wall, each under its door's id.
    fn push_leaves(&mut self, arch: &Architecture, wall: &Wall) {
        for door in arch.doors.iter().filter(|d| d.wall == wall.id) {
            let leaves = arch.door_leaves(door);
            if leaves.is_empty() {
                continue;
            }
            let index = self.push_id(&door.id);
            let surface = Surface::of(&leaf_material());
            let posed: Vec<_> = leaves.iter().map(|l| l.posed_mesh()).collect();
            for part in posed.iter().flat_map(|m| &m.parts) {
                let projection = surface.projection(&part.positions);
                for t in &part.triangles {
                    let corner = |k: usize| Point3::from(part.positions[t[k] as usize]).cast();
                    let corners = [corner(0), corner(1), corner(2)];
                    self.push_triangle(corners, &surface, projection.as_ref(), index);
                }
            }
        }
    }

    /// The glass panes of `wall`'s windows ([`Architecture::window_pane`]) in the library's
    /// glass ([`glass_material`]): drawn, and cut away, with the wall, each under its window's
    /// id.
    fn push_panes(&mut self, arch: &Architecture, wall: &Wall) {
        for window in arch.windows.iter().filter(|w| w.wall == wall.id) {
            if let Some((wall, pane)) = arch.window_pane(window) {
                let index = self.push_id(&window.id);
                let (center, half) = (pane.center(wall), pane.half_extents());
                self.push_box(wall, center, half, &Surface::of(&glass_material()), index);
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
        surface: &Surface,
        id: u32,
    ) {
        let d = wall.direction();
        let along = Vector3::new(d.x, 0.0, d.y) * half.x;
        let up = Vector3::y() * half.y;
        let n = wall.inward_normal();
        let across = Vector3::new(n.x, 0.0, n.y) * half.z;
        let axes = [along, up, across];
        let corners: Vec<[f32; 3]> = (0..8)
            .map(|i| {
                let s = |bit: usize| if (i >> bit) & 1 == 1 { 1.0 } else { -1.0 };
                let p = center + along * s(0) + up * s(1) + across * s(2);
                [p.x as f32, p.y as f32, p.z as f32]
            })
            .collect();
        let projection = surface.projection(&corners);
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
                    self.push_triangle(t, surface, projection.as_ref(), id);
                }
            }
        }
    }
}

/// Whether a house has a room on the outer side of `wall` (an interior wall between two rooms);
/// never for a single room, whose architecture lists no rooms.
fn is_interior(arch: &Architecture, wall: &Wall) -> bool {
    let mid = nalgebra::center(&wall.start, &wall.end);
    let behind = mid - wall.inward_normal() * wall.thickness;
    arch.room_at(behind.x, behind.y).is_some()
}

/// The boxes (centre, half extents along / up / across the wall) that make up a wall with its
/// door and window openings cut out ([`Architecture::wall_spans`], as every exporter cuts it).
fn wall_boxes(arch: &Architecture, wall: &Wall) -> Vec<(Point3<f64>, Vector3<f64>)> {
    arch.wall_spans(wall)
        .iter()
        .map(|span| (span.center(wall), span.half_extents()))
        .collect()
}

/// A unit vector perpendicular to the unit vector `n`.
fn perpendicular(n: [f32; 3]) -> [f32; 3] {
    let n = Vector3::from(n);
    let axis = if n.x.abs() < 0.9 {
        Vector3::x()
    } else {
        Vector3::y()
    };
    let t = (axis - n * n.dot(&axis))
        .try_normalize(1e-12)
        .unwrap_or(Vector3::z());
    [t.x, t.y, t.z]
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
    fn only_a_wall_between_two_rooms_of_a_house_is_interior() {
        use scenethesis_scene_graph::RoomArea;
        let mut house = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let room =
            |id: &str, x0: f64, x1: f64| RoomArea::rectangle(id, "bedroom", [x0, -2.0], [x1, 2.0]);
        house.rooms = vec![room("west", -3.0, -0.05), room("east", 0.05, 3.0)];
        let partition = Wall {
            id: "partition".into(),
            start: Point2::new(0.0, -2.0),
            end: Point2::new(0.0, 2.0),
            height: 2.8,
            thickness: 0.1,
        };
        assert!(is_interior(&house, &partition));
        for wall in &house.walls {
            assert!(!is_interior(&house, wall), "{} is an outer wall", wall.id);
        }
        let single = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        assert!(
            !is_interior(&single, &partition),
            "a single room has no rooms"
        );
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
        let glass = Surface::of(&glass_material());
        assert!(glass.layer > 0, "the pane wears the library's glass");
        assert!(geo.vertices.iter().all(|v| v.layer == glass.layer));
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
