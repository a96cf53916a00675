//! Collision: penetration depths between objects' real triangle meshes, both directions, and
//! penetration of the floor and walls.

use std::sync::OnceLock;

use nalgebra::Point3;
use rayon::prelude::*;
use scenethesis_scene_graph::{Aabb, Mesh, MeshPart};
use scenethesis_sdf::{MeshSdf, SignRule};
use serde::{Deserialize, Serialize};

use crate::raster::{wall_pieces, WallPiece};
use crate::scene::EvalScene;

/// A pair (or an object and the architecture) collides when the penetration exceeds this (m).
pub const PENETRATION_TOLERANCE: f64 = 0.001;
/// Minimum number of area-uniform surface samples per object.
pub const MIN_SAMPLES: usize = 2000;
/// Surface samples per square metre (one per cm²).
pub const SAMPLES_PER_M2: f64 = 10_000.0;

/// Two objects that interpenetrate by more than [`PENETRATION_TOLERANCE`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CollidingPair {
    /// First object id (earlier in scene order).
    pub a: String,
    /// Second object id.
    pub b: String,
    /// Penetration depth (m): the deepest point of either surface inside the other mesh.
    pub depth: f64,
}

/// An object that sinks into the floor or a wall by more than [`PENETRATION_TOLERANCE`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ArchPenetration {
    /// Object id.
    pub object: String,
    /// Id of the floor or wall it penetrates.
    pub architecture: String,
    /// Penetration depth (m).
    pub depth: f64,
}

/// The collision results of one scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct CollisionReport {
    /// Colliding pairs, in scene order of (a, b).
    pub pairs: Vec<CollidingPair>,
    /// Objects in at least one colliding pair, in scene order.
    pub colliding_objects: Vec<String>,
    /// Penetrations of the floor and walls, in scene order.
    pub architecture: Vec<ArchPenetration>,
    /// Object pairs whose boxes overlap and were tested with the meshes.
    pub pairs_tested: usize,
}

/// One part of an object: its box, and its exact signed distance field, built the first time
/// a test point falls in the box (most parts of a large object are never reached).
pub(crate) struct PartField<'a> {
    bounds: Aabb,
    part: &'a MeshPart,
    sdf: OnceLock<Option<BuiltField>>,
}

/// A part's exact field, and whether every solid of it is closed.
struct BuiltField {
    sdf: MeshSdf,
    closed: bool,
}

impl PartField<'_> {
    /// The part's field; `None` for a part without a usable (non-degenerate) triangle, which
    /// has no inside to penetrate.
    fn built(&self) -> Option<&BuiltField> {
        self.sdf
            .get_or_init(|| {
                let sdf = MeshSdf::new(&self.part.positions, &self.part.triangles).ok()?;
                let closed = sdf
                    .sign_rules()
                    .iter()
                    .all(|r| *r == SignRule::PseudoNormal);
                Some(BuiltField { sdf, closed })
            })
            .as_ref()
    }
}

/// Slack (m) for the `f32` rounding of a field's distances when they are bounded by a box
/// depth computed in `f64`.
const BOX_DEPTH_SLACK: f64 = 1e-4;

/// How deep `q` lies inside `bounds` (its distance to the nearest face; `q` is inside).
fn box_depth(bounds: &Aabb, q: &Point3<f64>) -> f64 {
    (0..3)
        .map(|k| (q[k] - bounds.min[k]).min(bounds.max[k] - q[k]))
        .fold(f64::INFINITY, f64::min)
}

/// The part fields of every object of a scene, each object's made on first use and then shared
/// by every test of one evaluation (the collision pairs and the opening sweeps).
pub(crate) struct SceneFields<'a> {
    scene: &'a EvalScene,
    objects: Vec<OnceLock<Vec<PartField<'a>>>>,
}

impl<'a> SceneFields<'a> {
    /// No field of `scene` built yet.
    pub(crate) fn new(scene: &'a EvalScene) -> Self {
        Self {
            scene,
            objects: scene.objects.iter().map(|_| OnceLock::new()).collect(),
        }
    }

    /// The part fields of object `k` of the scene.
    pub(crate) fn of(&self, k: usize) -> &[PartField<'a>] {
        self.objects[k].get_or_init(|| part_fields(&self.scene.objects[k].mesh))
    }
}

/// What the collision test needs of one object.
struct Prepared {
    bounds: Option<Aabb>,
    /// Vertices plus area-uniform surface samples, world coordinates.
    points: Vec<Point3<f32>>,
}

/// Surface area of a mesh in m².
pub fn surface_area(mesh: &Mesh) -> f64 {
    mesh.parts
        .iter()
        .flat_map(|p| {
            p.triangles.iter().map(move |t| {
                let [a, b, c] = p.triangle_f64(t);
                (b - a).cross(&(c - a)).norm() / 2.0
            })
        })
        .sum()
}

trait TriangleF64 {
    fn triangle_f64(&self, t: &[u32; 3]) -> [nalgebra::Point3<f64>; 3];
}

impl TriangleF64 for scenethesis_scene_graph::MeshPart {
    fn triangle_f64(&self, t: &[u32; 3]) -> [nalgebra::Point3<f64>; 3] {
        t.map(|i| Point3::from(self.positions[i as usize]).cast::<f64>())
    }
}

/// The number of surface samples for a mesh: one per cm², at least [`MIN_SAMPLES`] and at most
/// [`crate::limits::MAX_SAMPLES_PER_OBJECT`].
pub fn sample_count(mesh: &Mesh) -> usize {
    let wanted = surface_area(mesh) * SAMPLES_PER_M2;
    if wanted.is_finite() {
        (wanted.ceil() as usize).clamp(MIN_SAMPLES, crate::limits::MAX_SAMPLES_PER_OBJECT)
    } else {
        crate::limits::MAX_SAMPLES_PER_OBJECT
    }
}

/// The test points of a mesh: its vertices and area-uniform surface samples.
pub fn test_points(mesh: &Mesh, seed: u64) -> Vec<Point3<f32>> {
    let mut points: Vec<Point3<f32>> = mesh
        .parts
        .iter()
        .flat_map(|p| p.positions.iter().map(|&v| Point3::from(v)))
        .collect();
    if mesh.triangle_count() > 0 {
        points.extend(scenethesis_sdf::sampling::surface_points(
            mesh,
            sample_count(mesh),
            seed,
        ));
    }
    points
}

/// The parts of `mesh` with triangles, each with its box (fields not built yet).
fn part_fields(mesh: &Mesh) -> Vec<PartField<'_>> {
    mesh.parts
        .iter()
        .filter(|p| !p.triangles.is_empty())
        .filter_map(|p| {
            let corners: Vec<Point3<f64>> = p
                .positions
                .iter()
                .map(|&v| Point3::from(v).cast::<f64>())
                .collect();
            Some(PartField {
                bounds: Aabb::from_points(corners.iter())?,
                part: p,
                sdf: OnceLock::new(),
            })
        })
        .collect()
}

fn boxes_touch(a: &Aabb, b: &Aabb) -> bool {
    (0..3).all(|i| a.min[i] <= b.max[i] && b.min[i] <= a.max[i])
}

/// The deepest penetration (m, ≥ 0) of any of `points` inside the parts of another object,
/// whose whole box is `bounds` (a point outside it is outside every part: skipped at once),
/// when it is deeper than [`PENETRATION_TOLERANCE`]; otherwise some depth no deeper than that
/// (callers only compare it with the tolerance).
///
/// A closed solid lies inside its part's box, so a point is no deeper in the solid than in the
/// box: a point whose box depth cannot beat both the deepest found so far and the tolerance
/// is not queried. That skips the many surface samples of a resting contact, which lie in the
/// supporting part's box only by a hair.
pub(crate) fn penetration(points: &[Point3<f32>], bounds: &Aabb, fields: &[PartField<'_>]) -> f64 {
    let mut near: Vec<(Point3<f32>, Point3<f64>)> = points
        .iter()
        .map(|p| (*p, p.cast::<f64>()))
        .filter(|(_, q)| bounds.contains_point(q))
        .collect();
    // Sorted by x, each part looks only at the points within its x range.
    near.sort_by(|a, b| a.1.x.total_cmp(&b.1.x));
    let mut deepest = 0.0f64;
    for field in fields {
        let from = near.partition_point(|(_, q)| q.x < field.bounds.min.x);
        let to = near.partition_point(|(_, q)| q.x <= field.bounds.max.x);
        let mut inside = near[from..to.max(from)]
            .iter()
            .filter(|(_, q)| field.bounds.contains_point(q))
            .peekable();
        if inside.peek().is_none() {
            continue;
        }
        let Some(built) = field.built() else {
            continue;
        };
        for (p, q) in inside {
            let bound = deepest.max(PENETRATION_TOLERANCE);
            if built.closed && box_depth(&field.bounds, q) + BOX_DEPTH_SLACK <= bound {
                continue;
            }
            let depth = -(built.sdf.signed_distance(p) as f64);
            if depth > deepest {
                deepest = depth;
            }
        }
    }
    deepest
}

/// Tests every pair of objects whose boxes touch with their real meshes (both directions) and
/// every object against the floor and walls.
pub fn collisions(scene: &EvalScene) -> CollisionReport {
    collisions_with(scene, &SceneFields::new(scene))
}

/// [`collisions`] with the part fields of `fields` (shared with other tests of the scene).
pub(crate) fn collisions_with(scene: &EvalScene, fields: &SceneFields<'_>) -> CollisionReport {
    let objects = &scene.objects;
    let prepared: Vec<Prepared> = objects
        .par_iter()
        .enumerate()
        .map(|(k, o)| Prepared {
            bounds: o.mesh.bounds(),
            points: test_points(&o.mesh, 0x5eed_0000 + k as u64),
        })
        .collect();
    let candidates = candidate_pairs(&prepared);
    let depths = pair_depths(fields, &prepared, &candidates);
    let mut report = CollisionReport {
        pairs_tested: candidates.len(),
        ..Default::default()
    };
    let mut colliding = vec![false; objects.len()];
    for (&(i, j), &depth) in candidates.iter().zip(&depths) {
        if depth > PENETRATION_TOLERANCE {
            colliding[i] = true;
            colliding[j] = true;
            report.pairs.push(CollidingPair {
                a: objects[i].id.clone(),
                b: objects[j].id.clone(),
                depth,
            });
        }
    }
    report.colliding_objects = objects
        .iter()
        .zip(&colliding)
        .filter(|(_, &c)| c)
        .map(|(o, _)| o.id.clone())
        .collect();
    report.architecture = architecture_penetrations(scene, &prepared);
    report
}

/// The pairs `(i, j)`, `i < j`, whose bounding boxes touch.
fn candidate_pairs(prepared: &[Prepared]) -> Vec<(usize, usize)> {
    let mut candidates = Vec::new();
    for i in 0..prepared.len() {
        for j in i + 1..prepared.len() {
            if let (Some(a), Some(b)) = (&prepared[i].bounds, &prepared[j].bounds) {
                if boxes_touch(a, b) {
                    candidates.push((i, j));
                }
            }
        }
    }
    candidates
}

/// Each candidate pair's deepest penetration, either way round, against the exact fields of
/// the parts of the other object.
fn pair_depths(
    fields: &SceneFields<'_>,
    prepared: &[Prepared],
    candidates: &[(usize, usize)],
) -> Vec<f64> {
    candidates
        .par_iter()
        .map(|&(i, j)| match (&prepared[i].bounds, &prepared[j].bounds) {
            (Some(bi), Some(bj)) => {
                let ab = penetration(&prepared[i].points, bj, fields.of(j));
                let ba = penetration(&prepared[j].points, bi, fields.of(i));
                ab.max(ba)
            }
            // Candidates are pairs with both boxes.
            _ => 0.0,
        })
        .collect()
}

/// Every object's penetration of the floor and of each wall (the deepest over the wall's
/// pieces), where deeper than [`PENETRATION_TOLERANCE`].
fn architecture_penetrations(scene: &EvalScene, prepared: &[Prepared]) -> Vec<ArchPenetration> {
    let walls = wall_pieces(scene);
    let mut found = Vec::new();
    for (object, prep) in scene.objects.iter().zip(prepared) {
        let floor_depth = prep
            .points
            .iter()
            .map(|p| -(p.y as f64))
            .fold(0.0, f64::max);
        if floor_depth > PENETRATION_TOLERANCE {
            found.push(ArchPenetration {
                object: object.id.clone(),
                architecture: scene.architecture.floor.id.clone(),
                depth: floor_depth,
            });
        }
        let mut per_wall: Vec<(&str, f64)> = Vec::new();
        for piece in &walls {
            let deepest = piece_depth(piece, &prep.points);
            if deepest > PENETRATION_TOLERANCE {
                let id = piece.wall.as_str();
                match per_wall.iter_mut().find(|(w, _)| *w == id) {
                    Some(entry) => entry.1 = entry.1.max(deepest),
                    None => per_wall.push((id, deepest)),
                }
            }
        }
        for (id, depth) in per_wall {
            found.push(ArchPenetration {
                object: object.id.clone(),
                architecture: id.to_owned(),
                depth,
            });
        }
    }
    found
}

/// How deep the deepest of `points` lies inside the wall piece's box (0 when none is inside).
pub(crate) fn piece_depth(piece: &WallPiece, points: &[Point3<f32>]) -> f64 {
    let (rect, bottom, height) = (&piece.rect, piece.bottom, piece.height);
    let mut deepest = 0.0f64;
    for p in points {
        let (x, y, z) = (p.x as f64, p.y as f64, p.z as f64);
        if y <= bottom || y >= height {
            continue;
        }
        let (dx, dz) = (x - rect.center[0], z - rect.center[1]);
        let u = dx * rect.axis[0] + dz * rect.axis[1];
        let v = -dx * rect.axis[1] + dz * rect.axis[0];
        let inside = (rect.half[0] - u.abs())
            .min(rect.half[1] - v.abs())
            .min(y - bottom)
            .min(height - y);
        deepest = deepest.max(inside);
    }
    deepest
}
