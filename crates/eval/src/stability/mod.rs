//! Stability: the scene simulated with rapier, each object one free rigid body made of convex
//! pieces, and the objects that move or turn reported. Groups of bodies that cannot reach
//! each other are simulated in worlds of their own, side by side ([`WORLD_GAP`]).

use std::collections::HashMap;
use std::hash::{Hash, Hasher};
use std::sync::{Arc, Mutex};

use rapier3d::glamx::{Pose3, Quat, Vec3};
use rapier3d::parry::transformation::vhacd::VHACDParameters;
use rapier3d::prelude::*;
use rayon::prelude::*;
use scenethesis_scene_graph::{Aabb, MeshPart};
use serde::{Deserialize, Serialize};

use crate::raster::{wall_pieces, WallPiece};
use crate::scene::EvalScene;

mod worlds;
use worlds::{worlds, FreeBody};
pub use worlds::{MAX_EXCURSION, MAX_WORLDS, WORLD_GAP};

/// Simulated time in seconds.
pub const SIM_DURATION: f64 = 2.0;
/// Time step in seconds.
pub const SIM_STEP: f64 = 0.001;
/// Gravity in m/s² (pointing down, −Y).
pub const GRAVITY: f64 = 9.81;
/// Density of every object in kg/m³.
pub const DENSITY: f64 = 1000.0;
/// Friction coefficient of every surface.
pub const FRICTION: f64 = 0.5;
/// An object is unstable if its centre of mass moves more than this (m).
pub const MAX_DISPLACEMENT: f64 = 0.01;
/// An object is unstable if it turns by more than this (rad).
pub const MAX_ROTATION: f64 = 0.1;
/// A colliding pair keeps its contact points from the last step they were computed at while
/// its relative pose has drifted less than this since (m): 1/500 of [`MAX_DISPLACEMENT`].
/// Resting pairs, most of a settled scene, then skip contact determination on most steps
/// (the simulation costs about 40 % less) while every object's end pose stays within a few
/// hundredths of a millimetre of recomputing contacts every step.
pub const CONTACT_RECYCLE_DRIFT: f64 = 2e-5;

/// An object that moved, turned or blew up during the simulation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct UnstableObject {
    /// Object id.
    pub id: String,
    /// Distance its centre of mass moved (m); 0 when `non_finite`.
    pub displacement: f64,
    /// Angle it turned by (rad); 0 when `non_finite`.
    pub rotation: f64,
    /// Its state became NaN or infinite.
    pub non_finite: bool,
}

/// The stability results of one scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize, Default)]
pub struct StabilityReport {
    /// Objects simulated as free bodies (the denominator of Inst-O).
    pub tested: usize,
    /// Objects mounted on a wall (support `mounted`), welded in place and excluded.
    pub welded: Vec<String>,
    /// Objects without any volume to simulate (no triangles or a flat mesh), excluded.
    pub skipped: Vec<String>,
    /// The unstable objects, in scene order.
    pub unstable: Vec<UnstableObject>,
    /// Simulated time (s): [`SIM_DURATION`], or less when every body fell asleep earlier
    /// (nothing moves any more, so the rest of the run would change nothing); the longest
    /// of the worlds when the bodies were simulated in several.
    #[serde(default)]
    pub simulated_seconds: f64,
    /// The worlds the free bodies were simulated in: 1, or up to [`MAX_WORLDS`] when they
    /// form groups that cannot reach each other ([`WORLD_GAP`]).
    #[serde(default)]
    pub worlds: usize,
}

/// Convex collision pieces of one mesh part, each with its pose in the part's frame.
type Pieces = Arc<Vec<(Pose3, SharedShape)>>;

/// Convex decompositions already computed, keyed by the part's exact geometry. Keep one across
/// evaluations of similar scenes to decompose each non-convex part once.
#[derive(Debug, Default, Clone)]
pub struct DecompositionCache {
    map: Arc<Mutex<HashMap<u64, Pieces>>>,
}

impl DecompositionCache {
    /// An empty cache.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of decompositions held.
    pub fn len(&self) -> usize {
        self.map.lock().map(|m| m.len()).unwrap_or(0)
    }

    /// Whether the cache is empty.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The convex collision pieces of a part: a rapier cylinder or cone for a finely segmented
    /// vertical cylinder or cone (see [`round_solid`]), the convex hull of the part when the part
    /// is convex (procedural parts are), otherwise its VHACD decomposition (computed once per
    /// distinct geometry), so that cavities stay open. Empty for a flat or empty part.
    pub fn pieces(&self, part: &MeshPart) -> Pieces {
        if let Some(round) = round_solid(part) {
            return Arc::new(vec![round]);
        }
        let points: Vec<Vec3> = part.positions.iter().map(|&p| Vec3::from(p)).collect();
        if is_convex(part) {
            return Arc::new(
                SharedShape::convex_hull(&points)
                    .map(|s| vec![(Pose3::IDENTITY, s)])
                    .unwrap_or_default(),
            );
        }
        let key = geometry_hash(part);
        if let Some(found) = self.map.lock().ok().and_then(|m| m.get(&key).cloned()) {
            return found;
        }
        let params = VHACDParameters {
            resolution: 32,
            ..Default::default()
        };
        let pieces = if part.triangles.is_empty() || points.len() < 4 {
            Vec::new()
        } else {
            let compound =
                SharedShape::convex_decomposition_with_params(&points, &part.triangles, &params);
            compound
                .as_compound()
                .map(|c| c.shapes().to_vec())
                .unwrap_or_default()
        };
        let pieces = Arc::new(pieces);
        if let Ok(mut m) = self.map.lock() {
            m.insert(key, pieces.clone());
        }
        pieces
    }
}

/// Rings with at least this many vertices are simulated as round primitives.
const MIN_ROUND_SEGMENTS: usize = 12;

/// A vertical cylinder or cone given as a mesh with at least `MIN_ROUND_SEGMENTS` (12) sides, as
/// the matching rapier primitive with its pose.
///
/// A convex hull with many vertices around its base keeps rocking on a dynamic support in
/// rapier (a 24-sided cup on a table tilts by 0.05 rad and slides by 1 cm, never sleeping), so a
/// settle check would wrongly call it unstable; the round primitives rest still. Recognised
/// shapes: every vertex lies on one of two horizontal planes, and on each plane the vertices
/// are a ring at one radius about a common vertical axis, optionally with the ring's centre
/// (cap centres); a plane holding only the centre is a cone's apex.
pub fn round_solid(part: &MeshPart) -> Option<(Pose3, SharedShape)> {
    let pts: Vec<Vec3> = part.positions.iter().map(|&p| Vec3::from(p)).collect();
    let (mut y0, mut y1) = (f32::INFINITY, f32::NEG_INFINITY);
    for p in &pts {
        y0 = y0.min(p.y);
        y1 = y1.max(p.y);
    }
    let height = y1 - y0;
    if height.is_nan() || height <= 1e-4 {
        return None;
    }
    let eps = 1e-5 + 1e-4 * height;
    if pts
        .iter()
        .any(|p| (p.y - y0).abs() > eps && (p.y - y1).abs() > eps)
    {
        return None;
    }
    // Ring points of a level: (centre, radius, count); `None` radius when only the centre.
    let level = |y: f32| -> Option<(Vec3, f32, usize)> {
        let ring: Vec<Vec3> = pts
            .iter()
            .filter(|p| (p.y - y).abs() <= eps)
            .copied()
            .collect();
        let (mut lo, mut hi) = (Vec3::splat(f32::INFINITY), Vec3::splat(f32::NEG_INFINITY));
        for p in &ring {
            lo = lo.min(*p);
            hi = hi.max(*p);
        }
        let rough = (lo + hi) / 2.0;
        let reach = ring
            .iter()
            .map(|p| (*p - rough).with_y(0.0).length())
            .fold(0.0f32, f32::max);
        let outer: Vec<Vec3> = ring
            .iter()
            .filter(|p| (**p - rough).with_y(0.0).length() > 0.5 * reach)
            .copied()
            .collect();
        if outer.is_empty() {
            return Some((rough.with_y(y), 0.0, 0));
        }
        let centre = outer.iter().copied().sum::<Vec3>() / outer.len() as f32;
        let radius = outer
            .iter()
            .map(|p| (*p - centre).with_y(0.0).length())
            .sum::<f32>()
            / outer.len() as f32;
        let tolerance = 1e-5 + 0.005 * radius;
        let round = ring.iter().all(|p| {
            let d = (*p - centre).with_y(0.0).length();
            (d - radius).abs() <= tolerance || d <= tolerance
        });
        round.then_some((centre.with_y(y), radius, outer.len()))
    };
    let (c0, r0, n0) = level(y0)?;
    let (c1, r1, n1) = level(y1)?;
    if (c0 - c1).with_y(0.0).length() > 1e-4 + 0.005 * r0.max(r1) {
        return None;
    }
    let centre = Vec3::new(c0.x, (y0 + y1) / 2.0, c0.z);
    let half = height / 2.0;
    if n0 >= MIN_ROUND_SEGMENTS && n1 >= MIN_ROUND_SEGMENTS && (r0 - r1).abs() <= 0.005 * r0 {
        return Some((
            Pose3::from_translation(centre),
            SharedShape::cylinder(half, (r0 + r1) / 2.0),
        ));
    }
    if n0 >= MIN_ROUND_SEGMENTS && n1 == 0 {
        return Some((Pose3::from_translation(centre), SharedShape::cone(half, r0)));
    }
    if n1 >= MIN_ROUND_SEGMENTS && n0 == 0 {
        // rapier's cone points up; turn it upside down for an apex at the bottom.
        return Some((
            Pose3::from_parts(centre, Quat::from_rotation_x(std::f32::consts::PI)),
            SharedShape::cone(half, r1),
        ));
    }
    None
}

/// Massless contact feet of a convex piece: for every face with more than four corners, the
/// pyramid from the widest quadrilateral of its corners to the piece's centroid.
///
/// Contacts between convex polyhedra are generated from each one's support face, which parry
/// cuts to the face's first four corners in contour order: on a 24-sided base that is a sliver
/// on one side, so the piece has support on that side only and rocks (a can on a shelf never
/// settles, and keeps its whole island awake for the full simulation). A foot lies inside the
/// piece (all its corners are points of the piece), so the collision shape stays exactly the
/// piece; the foot's quadrilateral face is coplanar with the wide face and spans it, so resting
/// on that face gives contacts on every side.
pub fn face_feet(shape: &SharedShape) -> Vec<SharedShape> {
    let Some(hull) = shape.as_convex_polyhedron() else {
        return Vec::new();
    };
    let points = hull.points();
    if points.is_empty() {
        return Vec::new();
    }
    let centroid = points.iter().copied().sum::<Vec3>() / points.len() as f32;
    let corners = hull.vertices_adj_to_face();
    hull.faces()
        .iter()
        .filter(|f| f.num_vertices_or_edges > 4)
        .filter_map(|f| {
            let start = f.first_vertex_or_edge as usize;
            let ring: Vec<Vec3> = corners[start..start + f.num_vertices_or_edges as usize]
                .iter()
                .map(|&v| points[v as usize])
                .collect();
            let quad = widest_quad(&ring, f.normal)?;
            // The apex must stand off the face, else the pyramid is flat.
            if f.normal.dot(quad[0] - centroid) <= 1e-4 {
                return None;
            }
            SharedShape::convex_hull(&[quad[0], quad[1], quad[2], quad[3], centroid])
        })
        .collect()
}

/// Four corners of a convex polygon spanning it widely: its two farthest corners and, on each
/// side of the line through them, the corner farthest from it (`normal`: the polygon's).
fn widest_quad(ring: &[Vec3], normal: Vec3) -> Option<[Vec3; 4]> {
    let (mut a, mut c, mut far) = (0, 0, 0.0f32);
    for i in 0..ring.len() {
        for j in i + 1..ring.len() {
            let d = (ring[i] - ring[j]).length_squared();
            if d > far {
                (a, c, far) = (i, j, d);
            }
        }
    }
    let axis = ring[c] - ring[a];
    // Signed distance from the diagonal, in the polygon's plane.
    let side = |p: Vec3| normal.dot(axis.cross(p - ring[a]));
    let mut best = [(0.0f32, None), (0.0f32, None)];
    for (k, p) in ring.iter().enumerate() {
        let s = side(*p);
        let (slot, mag) = if s > 0.0 { (0, s) } else { (1, -s) };
        if mag > best[slot].0 {
            best[slot] = (mag, Some(k));
        }
    }
    let (b, d) = (best[0].1?, best[1].1?);
    Some([ring[a], ring[b], ring[c], ring[d]])
}

fn geometry_hash(part: &MeshPart) -> u64 {
    let mut h = std::collections::hash_map::DefaultHasher::new();
    for p in &part.positions {
        p.map(f32::to_bits).hash(&mut h);
    }
    part.triangles.hash(&mut h);
    h.finish()
}

/// Whether every vertex lies on the inner side of every face plane (within 0.1 mm), i.e. the
/// part is a convex solid (with outward faces).
pub fn is_convex(part: &MeshPart) -> bool {
    let pts: Vec<Vec3> = part.positions.iter().map(|&p| Vec3::from(p)).collect();
    if pts.len() < 4 {
        return false;
    }
    part.triangles.iter().all(|t| {
        let [a, b, c] = t.map(|i| pts[i as usize]);
        let n = (b - a).cross(c - a);
        let len = n.length();
        if len < 1e-12 {
            return true;
        }
        let n = n / len;
        pts.iter().all(|p| n.dot(*p - a) <= 1e-4)
    })
}

/// Simulates the scene for [`SIM_DURATION`] and reports which objects are unstable.
pub fn simulate(scene: &EvalScene, cache: &DecompositionCache) -> StabilityReport {
    simulate_with(scene, cache, &Simulation::default()).0
}

/// How the simulation computes contacts. [`Simulation::default`] is the metric's;
/// [`Simulation::recomputing_contacts`] is the reference it is checked against.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Simulation {
    /// Relative-pose drift (m) under which a colliding pair keeps its last contact points;
    /// 0 recomputes every pair's contacts at every step.
    pub contact_recycle_drift: f64,
    /// Free bodies that cannot reach each other are simulated in separate worlds
    /// ([`WORLD_GAP`]); `false` simulates every body in one world.
    pub separate_worlds: bool,
    /// The separate worlds run side by side on rayon's workers; `false` runs them one after
    /// another on the calling thread, for a caller that keeps the other cores busy. Each
    /// world's result is the same either way.
    pub worlds_in_parallel: bool,
}

impl Default for Simulation {
    fn default() -> Self {
        Simulation {
            contact_recycle_drift: CONTACT_RECYCLE_DRIFT,
            separate_worlds: true,
            worlds_in_parallel: true,
        }
    }
}

impl Simulation {
    /// Every pair's contacts recomputed at every step: slower, and no contact is stale.
    pub fn recomputing_contacts() -> Self {
        Simulation {
            contact_recycle_drift: 0.0,
            ..Simulation::default()
        }
    }

    /// Every free body in one world, the way a single simulation of the scene goes.
    pub fn one_world() -> Self {
        Simulation {
            separate_worlds: false,
            ..Simulation::default()
        }
    }

    /// The metric's simulation on the calling thread alone: the same separate worlds, one
    /// after another, with the same results as [`Simulation::default`].
    pub fn on_one_core() -> Self {
        Simulation {
            worlds_in_parallel: false,
            ..Simulation::default()
        }
    }
}

/// How far one free body moved and turned over the simulation.
#[derive(Debug, Clone, PartialEq)]
pub struct BodyMotion {
    /// Object id.
    pub id: String,
    /// Distance its centre of mass moved (m); NaN or infinite when `non_finite`.
    pub displacement: f64,
    /// Angle it turned by (rad); NaN or infinite when `non_finite`.
    pub rotation: f64,
    /// Its state became NaN or infinite.
    pub non_finite: bool,
}

impl BodyMotion {
    /// Whether the metric calls this motion unstable: moved more than [`MAX_DISPLACEMENT`],
    /// turned more than [`MAX_ROTATION`] or blew up.
    pub fn is_unstable(&self) -> bool {
        self.non_finite || self.displacement > MAX_DISPLACEMENT || self.rotation > MAX_ROTATION
    }
}

/// Simulates the scene as [`simulate`] does with `settings`, and also returns every free
/// body's motion, in scene order.
pub fn simulate_with(
    scene: &EvalScene,
    cache: &DecompositionCache,
    settings: &Simulation,
) -> (StabilityReport, Vec<BodyMotion>) {
    let mut report = StabilityReport::default();
    let objects = collision_shapes(scene, cache, &mut report);
    let free: Vec<usize> = (0..objects.len()).filter(|&i| !objects[i].welded).collect();
    report.tested = free.len();
    let mut runs = if settings.separate_worlds {
        separate_worlds(scene, &objects, &free, settings)
    } else {
        None
    }
    .unwrap_or_else(|| vec![run_world(scene, &objects, &free, settings)]);
    report.simulated_seconds = runs.iter().map(|r| r.steps).max().unwrap_or(0) as f64 * SIM_STEP;
    report.worlds = runs.len();
    let mut motions: Vec<(usize, BodyMotion)> =
        runs.iter_mut().flat_map(|r| r.motions.drain(..)).collect();
    motions.sort_by_key(|(index, _)| *index);
    let motions: Vec<BodyMotion> = motions.into_iter().map(|(_, m)| m).collect();
    report.unstable = motions
        .iter()
        .filter(|m| m.is_unstable())
        .map(|m| UnstableObject {
            id: m.id.clone(),
            displacement: if m.non_finite { 0.0 } else { m.displacement },
            rotation: if m.non_finite { 0.0 } else { m.rotation },
            non_finite: m.non_finite,
        })
        .collect();
    (report, motions)
}

/// The free bodies simulated in up to [`MAX_WORLDS`] worlds side by side (`worlds::worlds`), or
/// `None` when they make one world, or when a body travelled farther than [`MAX_EXCURSION`]
/// (it could have reached a body of another world).
fn separate_worlds(
    scene: &EvalScene,
    objects: &[ObjectShapes],
    free: &[usize],
    settings: &Simulation,
) -> Option<Vec<WorldRun>> {
    let bodies: Vec<FreeBody> = free
        .iter()
        .map(|&i| FreeBody {
            bounds: objects[i].bounds,
            weight: objects[i].colliders.len(),
        })
        .collect();
    let split = worlds(&bodies);
    if split.len() < 2 {
        return None;
    }
    let run = |members: &Vec<usize>| {
        let members: Vec<usize> = members.iter().map(|&k| free[k]).collect();
        run_world(scene, objects, &members, settings)
    };
    let runs: Vec<WorldRun> = if settings.worlds_in_parallel {
        split.par_iter().map(run).collect()
    } else {
        split.iter().map(run).collect()
    };
    runs.iter()
        .all(|r| r.excursion <= MAX_EXCURSION)
        .then_some(runs)
}

/// The collision shapes of one object, ready to become a body in any world.
struct ObjectShapes {
    /// Object id.
    id: String,
    /// Its colliders, each a convex piece or a massless contact foot, with its pose.
    colliders: Vec<Collider>,
    /// Welded to a wall: a fixed body in every world.
    welded: bool,
    /// Its mesh's box (world frame).
    bounds: Aabb,
}

/// Every object with something to simulate, in scene order; the others are noted as
/// skipped, the welded ones as welded, in `report`.
fn collision_shapes(
    scene: &EvalScene,
    cache: &DecompositionCache,
    report: &mut StabilityReport,
) -> Vec<ObjectShapes> {
    let mut out = Vec::new();
    for object in &scene.objects {
        let mut colliders = Vec::new();
        for part in &object.mesh.parts {
            for (pose, shape) in cache.pieces(part).iter() {
                // Feet first: massless, they only add contact points where the piece's own
                // contact generation leaves a wide face with too few.
                for foot in face_feet(shape) {
                    colliders.push(
                        material(ColliderBuilder::new(foot).position(*pose))
                            .density(0.0)
                            .build(),
                    );
                }
                colliders
                    .push(material(ColliderBuilder::new(shape.clone()).position(*pose)).build());
            }
        }
        if colliders.is_empty() {
            report.skipped.push(object.id.clone());
            continue;
        }
        if object.welded() {
            report.welded.push(object.id.clone());
        }
        out.push(ObjectShapes {
            id: object.id.clone(),
            colliders,
            welded: object.welded(),
            bounds: object
                .mesh
                .bounds()
                .expect("a mesh with collision pieces has vertices"),
        });
    }
    out
}

/// What one world's simulation found.
struct WorldRun {
    /// Steps run.
    steps: usize,
    /// Each free body's motion, with the index of its object in the shapes list.
    motions: Vec<(usize, BodyMotion)>,
    /// The farthest any point of a free body travelled at any step (m), bounded above.
    excursion: f64,
}

/// Simulates the room, every welded object and the free objects `members` (indices into
/// `objects`) in one world, objects inserted in scene order.
fn run_world(
    scene: &EvalScene,
    objects: &[ObjectShapes],
    members: &[usize],
    settings: &Simulation,
) -> WorldRun {
    let mut world = new_world(settings);
    add_architecture(&mut world, scene);
    let mut bodies = Vec::new();
    let mut next_member = members.iter().peekable();
    for (index, object) in objects.iter().enumerate() {
        let member = next_member.peek() == Some(&&index);
        if member {
            next_member.next();
        }
        if !(member || object.welded) {
            continue;
        }
        let handle = add_object(&mut world, object);
        if member && !object.welded {
            bodies.push((
                index,
                handle,
                reach_from_centre(&world.bodies[handle], object),
            ));
        }
    }
    let (steps, excursion) = run(&mut world, &bodies);
    let motions = bodies
        .into_iter()
        .map(|(index, handle, _)| {
            (
                index,
                motion(objects[index].id.clone(), &world.bodies[handle]),
            )
        })
        .collect();
    WorldRun {
        steps,
        motions,
        excursion,
    }
}

/// One body made of an object's colliders: fixed when it is welded, free otherwise.
fn add_object(world: &mut PhysicsWorld, object: &ObjectShapes) -> RigidBodyHandle {
    let builder = if object.welded {
        RigidBodyBuilder::fixed()
    } else {
        RigidBodyBuilder::dynamic()
    };
    let handle = world.bodies.insert(builder);
    for collider in &object.colliders {
        world
            .colliders
            .insert_with_parent(collider.clone(), handle, &mut world.bodies);
    }
    handle
}

/// The farthest corner of an object's box from its body's centre of mass (m).
fn reach_from_centre(body: &RigidBody, object: &ObjectShapes) -> f64 {
    let com = body.local_center_of_mass();
    let com = ::nalgebra::Point3::new(com.x as f64, com.y as f64, com.z as f64);
    object
        .bounds
        .corners()
        .iter()
        .map(|corner| (corner - com).norm())
        .fold(0.0, f64::max)
}

/// An empty world with the metric's gravity and time step, computing contacts as `settings`
/// says.
fn new_world(settings: &Simulation) -> PhysicsWorld {
    let mut world = PhysicsWorld::new();
    world.gravity = Vec3::new(0.0, -GRAVITY as f32, 0.0);
    world.integration_parameters.dt = SIM_STEP as f32;
    // Rapier reuses a pair's contact points while the pair's relative pose drifts less than
    // the recycle distance since they were computed. Its default (5 cm, for games) made tall,
    // symmetric objects (lamps, plants, umbrellas) creep and tilt past the metric's thresholds
    // while standing still; at [`CONTACT_RECYCLE_DRIFT`] a resting pair skips contact
    // determination on most steps, and no contact is staler than a fiftieth of a millimetre.
    let drift = settings.contact_recycle_drift;
    world.integration_parameters.contact_recycling = drift > 0.0;
    world
        .integration_parameters
        .normalized_contact_recycle_distance = drift as f32;
    world
}

/// The metric's surface: [`FRICTION`], no bounce, [`DENSITY`].
fn material(b: ColliderBuilder) -> ColliderBuilder {
    b.friction(FRICTION as f32)
        .restitution(0.0)
        .density(DENSITY as f32)
}

/// The static floor (a slab whose top is y = 0, well beyond the floor rectangle) and walls.
fn add_architecture(world: &mut PhysicsWorld, scene: &EvalScene) {
    let floor = &scene.architecture.floor;
    let floor_center = [
        (floor.min.x + floor.max.x) / 2.0,
        (floor.min.y + floor.max.y) / 2.0,
    ];
    // Half extents of the slab: the floor rectangle plus 10 m on every side.
    let floor_half = [
        (floor.max.x - floor.min.x) / 2.0 + 10.0,
        (floor.max.y - floor.min.y) / 2.0 + 10.0,
    ];
    world.insert(
        RigidBodyBuilder::fixed().translation(Vec3::new(
            floor_center[0] as f32,
            -1.0,
            floor_center[1] as f32,
        )),
        material(ColliderBuilder::cuboid(
            floor_half[0] as f32,
            1.0,
            floor_half[1] as f32,
        )),
    );
    for WallPiece {
        rect: piece,
        bottom,
        height,
        ..
    } in wall_pieces(scene)
    {
        let angle = (-piece.axis[1]).atan2(piece.axis[0]) as f32;
        let half_height = (height - bottom) as f32 / 2.0;
        let pose = Pose3::from_parts(
            Vec3::new(
                piece.center[0] as f32,
                (bottom + height) as f32 / 2.0,
                piece.center[1] as f32,
            ),
            Quat::from_rotation_y(angle),
        );
        world.insert(
            RigidBodyBuilder::fixed().pose(pose),
            material(ColliderBuilder::cuboid(
                piece.half[0] as f32,
                half_height,
                piece.half[1] as f32,
            )),
        );
    }
}

/// Steps the world for [`SIM_DURATION`], or until every body sleeps. Returns the steps run
/// and the farthest any point of the free `bodies` (handle, and the reach of its box from
/// its centre of mass) travelled at any step: the centre's travel plus the angle turned times
/// the reach bounds every point's.
fn run(world: &mut PhysicsWorld, bodies: &[(usize, RigidBodyHandle, f64)]) -> (usize, f64) {
    let steps = (SIM_DURATION / SIM_STEP).round() as usize;
    let mut ran = 0;
    let mut excursion = 0.0f64;
    while ran < steps {
        world.step();
        ran += 1;
        for (_, handle, reach) in bodies {
            let (moved, turned) = moved_and_turned(&world.bodies[*handle]);
            let travel = moved.length() as f64 + turned as f64 * reach;
            // NaN counts as far.
            excursion = if travel.is_nan() {
                f64::INFINITY
            } else {
                excursion.max(travel)
            };
        }
        if world.islands.active_bodies().next().is_none() {
            break;
        }
    }
    (ran, excursion)
}

/// The motion of object `id`'s body since it was placed.
fn motion(id: String, body: &RigidBody) -> BodyMotion {
    let (moved, rotation) = moved_and_turned(body);
    BodyMotion {
        id,
        displacement: moved.length() as f64,
        rotation: rotation as f64,
        non_finite: !body.position().is_finite() || !moved.is_finite() || !rotation.is_finite(),
    }
}

/// How far a body's centre of mass has moved since it was placed, and the angle it turned.
fn moved_and_turned(body: &RigidBody) -> (Vec3, f32) {
    let local_com = body.local_center_of_mass();
    let pose = body.position();
    (
        pose.transform_point(local_com) - local_com,
        quat_angle(pose.rotation),
    )
}

/// The rotation angle of a unit quaternion, in [0, π].
fn quat_angle(q: Quat) -> f32 {
    2.0 * q.w.abs().min(1.0).acos()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scene::EvalObject;
    use scenethesis_primitives::{cuboid, cylinder, frustum};

    #[test]
    fn finely_segmented_cylinders_and_cones_become_round_primitives() {
        let cyl = cylinder("c", 0, [0.3, -0.2], 0.04, 0.75, 0.85, 24);
        let (pose, shape) = round_solid(&cyl).expect("a 24-sided cylinder");
        let c = shape.as_cylinder().expect("cylinder primitive");
        assert!((c.radius - 0.04).abs() < 1e-5 && (c.half_height - 0.05).abs() < 1e-5);
        assert!((pose.translation - Vec3::new(0.3, 0.8, -0.2)).length() < 1e-5);
        let cone = frustum("k", 0, [0.0, 0.0], 0.2, 0.0, 0.0, 0.5, 32);
        assert!(round_solid(&cone).unwrap().1.as_cone().is_some());
        let down = frustum("k", 0, [0.0, 0.0], 0.0, 0.2, 0.0, 0.5, 32);
        let (pose, shape) = round_solid(&down).unwrap();
        assert!(shape.as_cone().is_some());
        assert!(pose.rotation.angle_between(Quat::IDENTITY) > 3.0);
        // Coarse rings, frusta and boxes stay convex hulls.
        assert!(round_solid(&cylinder("c", 0, [0.0, 0.0], 0.04, 0.0, 0.1, 8)).is_none());
        assert!(round_solid(&frustum("f", 0, [0.0, 0.0], 0.2, 0.1, 0.0, 0.5, 32)).is_none());
        assert!(round_solid(&cuboid("b", 0, [0.0; 3], [1.0; 3])).is_none());
    }

    #[test]
    fn wide_faces_get_a_spanning_foot_inside_the_piece() {
        // A can's bottom: a 24-sided frustum, narrower at the base.
        let part = frustum("bottom", 0, [0.0, 0.0], 0.028, 0.033, 0.0, 0.008, 24);
        let points: Vec<Vec3> = part.positions.iter().map(|&p| Vec3::from(p)).collect();
        let hull = SharedShape::convex_hull(&points).unwrap();
        let feet = face_feet(&hull);
        // One per 24-gon cap; the 24 side quads need none.
        assert_eq!(feet.len(), 2);
        for foot in &feet {
            let poly = foot.as_convex_polyhedron().unwrap();
            // Every corner is in the piece (tested a little towards its middle).
            let middle = Vec3::new(0.0, 0.004, 0.0);
            for p in poly.points() {
                let q = middle + (*p - middle) * 0.95;
                assert!(hull.contains_local_point(q), "{p:?} outside the piece");
            }
            // Its face on the cap is a quadrilateral spanning the cap (diagonals ≈ diameter).
            let cap = poly
                .faces()
                .iter()
                .find(|f| f.normal.y.abs() > 0.999)
                .expect("a face on the cap");
            assert_eq!(cap.num_vertices_or_edges, 4);
            let start = cap.first_vertex_or_edge as usize;
            let corners: Vec<Vec3> = poly.vertices_adj_to_face()[start..start + 4]
                .iter()
                .map(|&v| poly.points()[v as usize])
                .collect();
            let r = if cap.normal.y < 0.0 { 0.028 } else { 0.033 };
            for k in 0..2 {
                let diagonal = (corners[k] - corners[k + 2]).length();
                assert!((diagonal - 2.0 * r).abs() < 0.002 * r, "{diagonal} vs {r}");
            }
        }
        // Boxes have no wide faces; round primitives are not polyhedra.
        let block = SharedShape::cuboid(0.1, 0.1, 0.1);
        assert!(face_feet(&block).is_empty());
        let box_hull = cuboid("b", 0, [0.0; 3], [1.0; 3]);
        let box_points: Vec<Vec3> = box_hull.positions.iter().map(|&p| Vec3::from(p)).collect();
        assert!(face_feet(&SharedShape::convex_hull(&box_points).unwrap()).is_empty());
    }

    #[test]
    fn a_can_on_a_shelf_board_settles_and_the_simulation_ends_early() {
        use scenethesis_scene_graph::{Architecture, Material, Mesh, Pose, RelationKind};
        let mesh = |parts| Mesh {
            parts,
            materials: vec![Material::new("grey", [0.5, 0.5, 0.5], 0.8)],
        };
        // A free board on two blocks, and on it a can: 24-sided frustum base, body, neck.
        let board = mesh(vec![
            cuboid("block_l", 0, [-0.4, 0.0, -0.15], [-0.3, 0.3, 0.15]),
            cuboid("block_r", 0, [0.3, 0.0, -0.15], [0.4, 0.3, 0.15]),
            cuboid("board", 0, [-0.45, 0.3, -0.2], [0.45, 0.32, 0.2]),
        ]);
        let can = mesh(vec![
            frustum("bottom", 0, [0.0, 0.0], 0.028, 0.033, 0.0, 0.008, 24),
            cylinder("body", 0, [0.0, 0.0], 0.033, 0.008, 0.11, 24),
            frustum("neck", 0, [0.0, 0.0], 0.033, 0.028, 0.11, 0.122, 24),
        ]);
        let object = |id: &str, m: &Mesh, y: f64, parent: Option<&str>| EvalObject {
            id: id.into(),
            category: id.into(),
            mesh: m.transformed(&Pose::new(1.0, 0.0, ::nalgebra::Vector3::new(0.1, y, 0.05))),
            yaw: 0.0,
            parent: parent.map(str::to_owned),
            support: Some(RelationKind::On),
            relations: Vec::new(),
            joints: Vec::new(),
            parent_link: None,
        };
        let scene = EvalScene {
            objects: vec![
                object("board", &board, 0.00125, None),
                object("can", &can, 0.32 + 0.0025, Some("board")),
            ],
            architecture: Architecture::open_ground(10.0, 10.0),
        };
        let report = simulate(&scene, &DecompositionCache::new());
        assert!(report.unstable.is_empty(), "{:?}", report.unstable);
        // Everything sleeps after half a second at rest (rapier's default); a can without
        // feet keeps rocking past 1 s.
        assert!(
            report.simulated_seconds < 0.75,
            "still moving after {} s",
            report.simulated_seconds
        );
    }

    #[test]
    fn convexity_test_tells_boxes_from_an_l_shape() {
        let mut part = cuboid("b", 0, [0.0; 3], [1.0; 3]);
        assert!(is_convex(&part));
        // Push one corner inward: a dent makes it non-convex.
        part.positions[7] = [0.6, 0.6, 0.6];
        assert!(!is_convex(&part));
    }
}
