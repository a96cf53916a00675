//! Building an [`EvalScene`] from files: our output folders and any glTF / GLB scene.

use std::path::Path;

use nalgebra::Point2;
use scenethesis_scene_graph::{
    hangs_on_wall, Aabb, Architecture, Environment, Floor, Mesh, Scene, Wall,
};

use crate::glb::GlbScene;
use crate::scene::{EvalObject, EvalScene};
use crate::EvalError;

/// Gap (m) under which an object counts as resting on the floor or on the object below it when
/// a foreign scene states no support links.
const SUPPORT_GAP: f64 = 0.02;

/// Loads whatever `path` is: an output folder (holding `scene.json`), a `scene.json` file, or a
/// `.glb` / `.gltf` scene.
///
/// The scene is checked against [`crate::limits`] ([`EvalScene::check_limits`]) before it is
/// returned, as are the scenes of [`load_folder`] and [`load_glb`].
pub fn load_path(path: &Path) -> Result<EvalScene, EvalError> {
    if path.is_dir() {
        return load_folder(path);
    }
    let ext = path
        .extension()
        .and_then(|e| e.to_str())
        .map(str::to_ascii_lowercase);
    match ext.as_deref() {
        Some("glb") | Some("gltf") => load_glb(path),
        Some("json") => load_scene_file(path, path.parent().map(|p| p.join("scene.glb"))),
        _ => Err(EvalError::UnsupportedInput {
            path: path.to_owned(),
        }),
    }
}

/// Loads an output folder: `scene.json` for objects, links and room, and meshes from the nodes
/// of `scene.glb` named by object id; without `scene.glb`, procedural assets are regenerated
/// from their generator and seed.
pub fn load_folder(dir: &Path) -> Result<EvalScene, EvalError> {
    let json = dir.join("scene.json");
    if !json.is_file() {
        return Err(EvalError::NotAScene {
            path: dir.to_owned(),
        });
    }
    load_scene_file(&json, Some(dir.join("scene.glb")))
}

fn load_scene_file(json: &Path, glb: Option<std::path::PathBuf>) -> Result<EvalScene, EvalError> {
    let scene = load_scene_file_unchecked(json, glb)?;
    scene.check_limits()?;
    Ok(scene)
}

fn load_scene_file_unchecked(
    json: &Path,
    glb: Option<std::path::PathBuf>,
) -> Result<EvalScene, EvalError> {
    let scene = Scene::read_json(json)?;
    match glb.filter(|g| g.is_file()) {
        Some(glb_path) => {
            let glb = GlbScene::read(&glb_path)?;
            let objects = scene
                .objects
                .iter()
                .map(|o| {
                    let node = glb.find(&o.id).ok_or_else(|| EvalError::MissingMesh {
                        object: o.id.clone(),
                        reason: format!("no node named {} in {}", o.id, glb_path.display()),
                    })?;
                    Ok(EvalObject::from_scene_object_world(o, node.subtree_mesh()))
                })
                .collect::<Result<Vec<_>, EvalError>>()?;
            Ok(EvalScene {
                objects,
                architecture: scene.architecture.clone(),
            })
        }
        None => EvalScene::from_scene_procedural(&scene),
    }
}

/// Loads any glTF / GLB scene that has no `scene.json`: every top-level node is an object (its
/// subtree's meshes merged; a single mesh-less wrapper root is looked through, and so is a
/// house's room node, `extras` `{"room": type}`, whose children are its objects) except nodes
/// named like architecture (`floor`, `ground`, `wall_3`,
/// `Ceiling.001`, `door`, …). The floor rectangle is the floor nodes' box (or the objects' box
/// when there is none); each connected piece of a wall node becomes a wall box. Support links
/// are inferred: an object whose bottom is within 2 cm of the floor stands on the ground,
/// otherwise on the highest object below it.
pub fn load_glb(path: &Path) -> Result<EvalScene, EvalError> {
    let scene = load_glb_unchecked(path)?;
    scene.check_limits()?;
    Ok(scene)
}

fn load_glb_unchecked(path: &Path) -> Result<EvalScene, EvalError> {
    let glb = GlbScene::read(path)?;
    // Exporters often wrap a whole scene in one mesh-less root node: look through it.
    let mut roots = &glb.roots;
    while roots.len() == 1 && roots[0].mesh.parts.is_empty() && !roots[0].children.is_empty() {
        roots = &roots[0].children;
    }
    // A house's room nodes group its objects: read them as if at the root.
    let roots = roots.iter().flat_map(|node| {
        if node.is_room {
            node.children.iter().collect::<Vec<_>>()
        } else {
            vec![node]
        }
    });
    let mut floor_box: Option<Aabb> = None;
    let mut walls = Vec::new();
    let mut objects = Vec::new();
    for node in roots {
        let mesh = node.subtree_mesh();
        match architecture_kind(&node.name) {
            Some(ArchKind::Floor) => {
                if let Some(b) = mesh.bounds() {
                    floor_box = Some(floor_box.map_or(b, |f| f.union(&b)));
                }
            }
            Some(ArchKind::Wall) => {
                for (k, piece) in connected_pieces(&mesh).into_iter().enumerate() {
                    walls.push(wall_from_box(&format!("{}#{k}", node.name), &piece));
                }
            }
            Some(ArchKind::Other) => {}
            None => {
                if mesh.triangle_count() == 0 {
                    continue;
                }
                objects.push(EvalObject {
                    id: node.name.clone(),
                    category: category_of(&node.name),
                    mesh,
                    yaw: node.yaw(),
                    parent: None,
                    support: None,
                    relations: Vec::new(),
                    joints: Vec::new(),
                    parent_link: None,
                });
            }
        }
    }
    let floor_box = floor_box
        .or_else(|| {
            objects
                .iter()
                .map(EvalObject::aabb)
                .reduce(|a, b| a.union(&b))
        })
        .ok_or_else(|| EvalError::BadGltf {
            path: path.to_owned(),
            reason: "no floor node and no objects".into(),
        })?;
    // Support inference compares every pair of objects: check the counts first.
    if objects.len() > crate::limits::MAX_OBJECTS || walls.len() > crate::limits::MAX_WALLS {
        return Err(EvalError::OverLimit {
            what: path.display().to_string(),
            reason: format!(
                "{} objects and {} wall pieces, limits {} and {}",
                objects.len(),
                walls.len(),
                crate::limits::MAX_OBJECTS,
                crate::limits::MAX_WALLS
            ),
        });
    }
    infer_support(&mut objects, &walls);
    Ok(EvalScene {
        objects,
        architecture: Architecture {
            environment: if walls.is_empty() {
                Environment::Outdoor
            } else {
                Environment::Indoor
            },
            floor: Floor {
                id: "floor".into(),
                min: Point2::new(floor_box.min.x, floor_box.min.z),
                max: Point2::new(floor_box.max.x, floor_box.max.z),
            },
            walls,
            doors: Vec::new(),
            windows: Vec::new(),
            rooms: Vec::new(),
        },
    })
}

#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum ArchKind {
    Floor,
    Wall,
    Other,
}

/// Whether a node name denotes architecture: its first word is an architecture word and every
/// other word is a number or a neutral qualifier (`wall_0`, `Floor.001`, `ground_plane`; but
/// not `floor_lamp` or `wall_shelf`).
fn architecture_kind(name: &str) -> Option<ArchKind> {
    const NEUTRAL: &[&str] = &[
        "plane", "mesh", "geo", "geometry", "left", "right", "front", "back", "north", "south",
        "east", "west", "frame", "opening", "inner", "outer", "main",
    ];
    let lower = name.to_ascii_lowercase();
    let mut words = lower
        .split(|c: char| !c.is_ascii_alphanumeric())
        .filter(|w| !w.is_empty());
    let kind = match words.next()? {
        "floor" | "ground" | "floors" => ArchKind::Floor,
        "wall" | "walls" => ArchKind::Wall,
        "ceiling" | "door" | "doors" | "roof" | "doorframe" | "window" => ArchKind::Other,
        _ => return None,
    };
    words
        .all(|w| w.chars().all(|c| c.is_ascii_digit()) || NEUTRAL.contains(&w))
        .then_some(kind)
}

/// The category of a foreign node: its name lower-cased without a trailing number
/// (`Chair.001` → `chair`, `table_2` → `table`).
fn category_of(name: &str) -> String {
    let lower = name.to_ascii_lowercase();
    let trimmed = lower.trim_end_matches(|c: char| c.is_ascii_digit());
    let trimmed = trimmed.trim_end_matches(['_', '.', '-', ' ']);
    if trimmed.is_empty() {
        lower
    } else {
        trimmed.to_owned()
    }
}

/// The boxes of the connected pieces of a mesh (triangles sharing vertex positions).
fn connected_pieces(mesh: &Mesh) -> Vec<Aabb> {
    let mut boxes = Vec::new();
    for part in &mesh.parts {
        let n = part.positions.len();
        let mut parent: Vec<usize> = (0..n).collect();
        fn root(p: &mut [usize], mut i: usize) -> usize {
            while p[i] != i {
                p[i] = p[p[i]];
                i = p[i];
            }
            i
        }
        // Weld vertices at the same position (exporters split them for normals).
        let mut by_pos: std::collections::BTreeMap<[u32; 3], usize> = Default::default();
        for (i, p) in part.positions.iter().enumerate() {
            let key = p.map(f32::to_bits);
            let first = *by_pos.entry(key).or_insert(i);
            let (a, b) = (root(&mut parent, first), root(&mut parent, i));
            parent[a] = b;
        }
        for t in &part.triangles {
            for k in 1..3 {
                let (a, b) = (
                    root(&mut parent, t[0] as usize),
                    root(&mut parent, t[k] as usize),
                );
                parent[a] = b;
            }
        }
        let mut piece_boxes: std::collections::BTreeMap<usize, Aabb> = Default::default();
        for t in &part.triangles {
            let r = root(&mut parent, t[0] as usize);
            for &i in t {
                let p = nalgebra::Point3::from(part.positions[i as usize]).cast::<f64>();
                piece_boxes
                    .entry(r)
                    .and_modify(|b| *b = b.including(&p))
                    .or_insert(Aabb::new(p, p));
            }
        }
        boxes.extend(piece_boxes.into_values());
    }
    boxes
}

/// A wall along the longer horizontal side of a box.
fn wall_from_box(id: &str, b: &Aabb) -> Wall {
    let size = b.size();
    let c = b.center();
    let (start, end, thickness) = if size.x >= size.z {
        (Point2::new(b.min.x, c.z), Point2::new(b.max.x, c.z), size.z)
    } else {
        (Point2::new(c.x, b.min.z), Point2::new(c.x, b.max.z), size.x)
    };
    Wall {
        id: id.to_owned(),
        start,
        end,
        height: b.max.y.max(0.0),
        thickness: thickness.max(1e-3),
    }
}

/// Fills parents and wall mounting for objects of a scene that states neither: an object with
/// nothing beneath it that hangs on a wall by the scene graph's [`hangs_on_wall`] rule (its
/// bottom above `MOUNT_MIN_BOTTOM`, its box within `MOUNT_WALL_REACH` of the wall's) hangs
/// on that wall (support `mounted`, so welded); anything else off the floor and
/// unsupported stays without a support and is simulated, so it falls.
fn infer_support(objects: &mut [EvalObject], walls: &[Wall]) {
    use scenethesis_scene_graph::RelationKind;
    let boxes: Vec<Aabb> = objects.iter().map(EvalObject::aabb).collect();
    let ids: Vec<String> = objects.iter().map(|o| o.id.clone()).collect();
    for (i, object) in objects.iter_mut().enumerate() {
        let b = &boxes[i];
        if b.min.y <= SUPPORT_GAP {
            object.support = Some(RelationKind::OnFloor);
            continue;
        }
        let c = b.center();
        let below = boxes
            .iter()
            .enumerate()
            .filter(|&(j, o)| {
                j != i
                    && o.min.x <= c.x
                    && c.x <= o.max.x
                    && o.min.z <= c.z
                    && c.z <= o.max.z
                    && o.min.y < b.min.y
                    && o.max.y <= b.max.y
            })
            .max_by(|a, b| a.1.max.y.total_cmp(&b.1.max.y));
        match below {
            Some((j, _)) => {
                object.parent = Some(ids[j].clone());
                object.support = Some(RelationKind::On);
            }
            None => {
                // A foreign wall has no known inner side: the gap is the distance between the
                // boxes on the floor plane, along the axis that parts them most.
                let hangs = walls.iter().any(|w| {
                    let wb = w.aabb();
                    let dx = (wb.min.x - b.max.x).max(b.min.x - wb.max.x).max(0.0);
                    let dz = (wb.min.z - b.max.z).max(b.min.z - wb.max.z).max(0.0);
                    hangs_on_wall(b.min.y, dx.max(dz))
                });
                if hangs {
                    object.support = Some(RelationKind::Mounted);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn architecture_names_are_told_from_objects() {
        assert_eq!(architecture_kind("floor"), Some(ArchKind::Floor));
        assert_eq!(architecture_kind("Wall.003"), Some(ArchKind::Wall));
        assert_eq!(architecture_kind("wall_0"), Some(ArchKind::Wall));
        assert_eq!(architecture_kind("ground_plane"), Some(ArchKind::Floor));
        assert_eq!(architecture_kind("door_0"), Some(ArchKind::Other));
        assert_eq!(architecture_kind("floor_lamp_0"), None);
        assert_eq!(architecture_kind("wall_shelf"), None);
        assert_eq!(architecture_kind("chair"), None);
        assert_eq!(category_of("Chair.001"), "chair");
        assert_eq!(category_of("dining_table_12"), "dining_table");
    }

    #[test]
    fn an_object_hangs_on_a_foreign_wall_by_the_scene_graph_rule() {
        // A wall along x whose room-side face is at z = -1.95, and boxes 0.3 m deep.
        let wall = wall_from_box(
            "wall_0",
            &Aabb::new(
                nalgebra::Point3::new(-2.0, 0.0, -2.1),
                nalgebra::Point3::new(2.0, 2.5, -1.95),
            ),
        );
        let object = |id: &str, x: f32, gap: f64, bottom: f64| EvalObject {
            id: id.into(),
            category: "frame".into(),
            mesh: Mesh::cuboid(
                "body",
                scenethesis_scene_graph::Material::new("m", [0.5; 3], 0.5),
                [x - 0.2, bottom as f32, (-1.95 + gap) as f32],
                [x + 0.2, bottom as f32 + 0.3, (-1.65 + gap) as f32],
            ),
            yaw: 0.0,
            parent: None,
            support: None,
            relations: Vec::new(),
            joints: Vec::new(),
            parent_link: None,
        };
        let mut objects = vec![
            object("close", -1.5, 0.0, 1.2),
            object("proud", -0.5, 0.1, 1.2),
            object("far", 0.5, 0.2, 1.2),
            object("low", 1.5, 0.0, 0.2),
        ];
        infer_support(&mut objects, &[wall]);
        let mounted: Vec<&str> = objects
            .iter()
            .filter(|o| o.support == Some(scenethesis_scene_graph::RelationKind::Mounted))
            .map(|o| o.id.as_str())
            .collect();
        assert_eq!(mounted, ["close", "proud"]);
    }
}
