//! The per-object optimization problem and the paper's losses: translation and scale collision
//! losses over penetrating surface points, the stability loss over bottom points, and the
//! pose-alignment loss over correspondences.

use std::time::Instant;

use nalgebra::{Point2, Point3, Vector3};
use scenethesis_scene_graph::{Aabb, Architecture, Pose};
use serde::{Deserialize, Serialize};

use crate::contact::{cluster_contacts, CollisionState, Contact};
use crate::memo::{self, Clearance, ContactMemo, MemoState};
use crate::obstacles::box_distance;
use crate::obstacles::Obstacles;
use crate::prepare::PreparedAsset;
use crate::support::Support;
use scenethesis_correspondence::params::{
    rotate_y, unrotate_y, world_point, PoseVector, SCALE, TX, TY, TZ,
};
use scenethesis_correspondence::PoseAlignment;

/// Tolerances and weights of the losses.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LossSettings {
    /// A surface point closer than this to another object or the architecture counts as
    /// colliding (the paper's threshold is 0; a small positive margin leaves a visible gap that
    /// survives rounding), in metres.
    pub collision_margin: f64,
    /// The gap the stability loss aims for between an object's bottom and its support, in
    /// metres; kept above `collision_margin` so the two terms never fight.
    pub support_clearance: f64,
    /// Length scale σ of the stability loss `1 − exp(−(d/σ)²)`, in metres (the paper's
    /// formula is σ = 1 m; metres make that nearly quadratic, so a shorter scale is used).
    pub stability_length: f64,
    /// Weight λ_p of the pose-alignment loss.
    pub weight_pose: f64,
    /// Weight λ_cT of the translation collision loss.
    pub weight_translation: f64,
    /// Weight λ_cS of the scale collision loss.
    pub weight_scale: f64,
    /// Weight λ_s of the stability loss; the default σ² makes a unit learning rate move a
    /// resting object by about its gap, whatever σ is.
    pub weight_stability: f64,
    /// Two penetrating points belong to the same cluster when they are closer than this many
    /// mean sample spacings on the asset surface.
    pub cluster_link_spacings: f64,
}

impl Default for LossSettings {
    fn default() -> Self {
        Self {
            collision_margin: 0.001,
            support_clearance: 0.00125,
            stability_length: 0.1,
            weight_pose: 1.0,
            weight_translation: 1.0,
            weight_scale: 1.0,
            weight_stability: 0.01,
            cluster_link_spacings: 2.5,
        }
    }
}

/// The largest relative change of scale by which [`ObjectProblem::rest_by_scale`] brings an
/// object onto its support.
pub const REST_BY_SCALE_LIMIT: f64 = 0.2;
/// A gap (metres) between an object's bottom and its resting height below which
/// [`ObjectProblem::rest_by_scale`] leaves it to the physics stage: the fit's own noise, not
/// worth a change of size (and of where the things on the object stand).
pub const REST_BY_SCALE_GAP: f64 = 0.01;

/// The floor rectangle an object must stay inside, in world (x, z).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RoomBounds {
    /// Smallest x and z.
    pub min: Point2<f64>,
    /// Largest x and z.
    pub max: Point2<f64>,
}

impl RoomBounds {
    /// The floor rectangle of an architecture.
    pub fn of(architecture: &Architecture) -> Self {
        Self {
            min: architecture.floor.min,
            max: architecture.floor.max,
        }
    }

    /// The rectangle an object of house room `room` must stay inside: the bounds of that
    /// room's outline (its walls' inner faces), or the whole floor's ([`RoomBounds::of`]) for
    /// no room or one the architecture does not hold. A house's interior walls are thin:
    /// started deeper than half a wall into one, an object's push out of it would lead
    /// through it into the next room.
    ///
    /// ```
    /// use scenethesis_physics_opt::RoomBounds;
    /// use scenethesis_scene_graph::{Architecture, RoomArea};
    ///
    /// let mut house = Architecture::rectangular_room(8.0, 4.0, 2.8, 0.9);
    /// house.rooms.push(RoomArea::rectangle("bathroom", "bathroom", [0.0, -2.0], [3.0, 2.0]));
    /// let bounds = RoomBounds::of_room(&house, Some("bathroom"));
    /// assert_eq!((bounds.min.x, bounds.max.x), (0.0, 3.0));
    /// assert_eq!(RoomBounds::of_room(&house, None), RoomBounds::of(&house));
    /// ```
    pub fn of_room(architecture: &Architecture, room: Option<&str>) -> Self {
        match room.and_then(|id| architecture.room(id)?.bounds()) {
            Some((min, max)) => Self { min, max },
            None => Self::of(architecture),
        }
    }

    /// How far a world box sticks out of the rectangle (0 when inside).
    pub fn overhang(&self, b: &Aabb) -> f64 {
        [
            self.min.x - b.min.x,
            b.max.x - self.max.x,
            self.min.y - b.min.z,
            b.max.z - self.max.y,
        ]
        .into_iter()
        .fold(0.0, f64::max)
    }

    /// The shift in (x, z) that moves a world box inside the rectangle (centring it on an axis
    /// where it is wider than the room).
    pub fn shift_inside(&self, b: &Aabb) -> Vector3<f64> {
        let axis = |lo: f64, hi: f64, rmin: f64, rmax: f64| {
            if hi - lo > rmax - rmin {
                (rmin + rmax) / 2.0 - (lo + hi) / 2.0
            } else if lo < rmin {
                rmin - lo
            } else if hi > rmax {
                rmax - hi
            } else {
                0.0
            }
        };
        Vector3::new(
            axis(b.min.x, b.max.x, self.min.x, self.max.x),
            0.0,
            axis(b.min.z, b.max.z, self.min.y, self.max.y),
        )
    }
}

/// Which part of the optimization is running.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stage {
    /// Stage 1: pose alignment to the guidance image only.
    Alignment,
    /// Stage 2: collision and stability.
    Physics,
}

/// The loss terms at one pose.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct Losses {
    /// `L_pose` (0 without correspondences).
    pub pose: f64,
    /// `L_translation`: mean squared push over the penetrating points.
    pub translation: f64,
    /// `L_scale`: mean squared scale pull when the penetration forms two or more clusters.
    pub scale: f64,
    /// `L_stability`: mean `1 − exp(−(d/σ)²)` over the bottom points.
    pub stability: f64,
}

impl Losses {
    /// The weighted total of the terms that belong to `stage`.
    pub fn total(&self, stage: Stage, s: &LossSettings) -> f64 {
        match stage {
            Stage::Alignment => s.weight_pose * self.pose,
            Stage::Physics => {
                s.weight_translation * self.translation
                    + s.weight_scale * self.scale
                    + s.weight_stability * self.stability
            }
        }
    }
}

/// Everything an [`crate::Optimizer`] needs to place one object: its geometry, the scene it is
/// placed into, what it rests on, the room, its correspondences and the loss settings.
#[derive(Clone, Copy)]
pub struct ObjectProblem<'a> {
    /// The object's id.
    pub id: &'a str,
    /// Its prepared geometry.
    pub asset: &'a PreparedAsset,
    /// The objects placed before it and the architecture.
    pub obstacles: &'a Obstacles,
    /// What it rests on.
    pub support: &'a Support,
    /// The floor rectangle it must stay inside, if any.
    pub room: Option<RoomBounds>,
    /// Its correspondences with the guidance image, if any.
    pub alignment: Option<&'a PoseAlignment>,
    /// Loss tolerances and weights.
    pub settings: &'a LossSettings,
    /// When set, optimizers stop iterating once this instant has passed and return the pose
    /// reached (the stage's time budget; see [`crate::OptimizeSettings::time_budget`]).
    pub deadline: Option<Instant>,
    /// Distances remembered between this problem's contact checks
    /// ([`ObjectProblem::contacts`]), when its obstacles stay put while it is solved.
    pub memo: Option<&'a ContactMemo>,
    /// When set, optimizers take at most this many iterations in a stage, fewer than their
    /// own budget allows ([`ObjectProblem::iteration_budget`]): the final pass probes further
    /// starts this way, since a start that frees the object does so within a few.
    pub iteration_limit: Option<usize>,
}

impl<'a> ObjectProblem<'a> {
    /// The problem of object `id` (of `asset`) among `obstacles`, resting as `support` says,
    /// with `settings`: no room to stay inside, no correspondences, deadline, memo or
    /// iteration limit (set those fields on the value to have them).
    ///
    /// ```
    /// use scenethesis_physics_opt::{
    ///     LossSettings, ObjectProblem, Obstacles, PrepareSettings, PreparedAsset, Support,
    /// };
    /// use scenethesis_scene_graph::{Material, Mesh, Placement, Pose};
    ///
    /// let oak = Material::new("oak", [0.6, 0.4, 0.2], 0.7);
    /// let mesh = Mesh::cuboid("crate", oak, [-0.2, 0.0, -0.2], [0.2, 0.4, 0.2]);
    /// let prepare = PrepareSettings::default();
    /// let asset =
    ///     PreparedAsset::new("crate", &mesh, Vec::new(), [0.9, 1.1], Placement::Floor, &prepare)
    ///         .unwrap();
    /// let (obstacles, settings) = (Obstacles::new(true), LossSettings::default());
    /// let problem = ObjectProblem::new("crate_0", &asset, &obstacles, &Support::Free, &settings);
    /// assert!(problem.room.is_none() && problem.iteration_limit.is_none());
    /// // Nothing to collide with.
    /// assert!(problem.contacts(&Pose::default()).is_free());
    /// ```
    pub fn new(
        id: &'a str,
        asset: &'a PreparedAsset,
        obstacles: &'a Obstacles,
        support: &'a Support,
        settings: &'a LossSettings,
    ) -> Self {
        Self {
            id,
            asset,
            obstacles,
            support,
            room: None,
            alignment: None,
            settings,
            deadline: None,
            memo: None,
            iteration_limit: None,
        }
    }

    /// Whether the [`ObjectProblem::deadline`] has passed: optimizers check it before each
    /// iteration (it only ever stops work early; a deadline not reached changes nothing).
    pub fn out_of_time(&self) -> bool {
        scenethesis_correspondence::deadline::past(self.deadline)
    }

    /// The iterations an optimizer whose own budget is `own` may take in a stage of this
    /// problem: `own`, or the [`ObjectProblem::iteration_limit`] when lower.
    pub fn iteration_budget(&self, own: usize) -> usize {
        self.iteration_limit.map_or(own, |limit| limit.min(own))
    }

    /// The allowed scale interval.
    pub fn scale_range(&self) -> [f64; 2] {
        self.asset.scale_range()
    }

    /// The world box of the object at `pose`.
    pub fn world_box(&self, pose: &Pose) -> Aabb {
        self.asset.bounds().transformed(pose)
    }

    /// The object's centroid in world coordinates.
    pub fn world_centroid(&self, pose: &Pose) -> Point3<f64> {
        world_point(pose, &self.asset.centroid())
    }

    /// The contacts closer than the collision margin, checked in both directions (the
    /// object's samples against the obstacles, and nearby obstacles' samples against the
    /// object's own field), clustered ([`ObjectProblem::cluster`]).
    pub fn collision(&self, pose: &Pose) -> CollisionState {
        let mut state = self.contacts(pose);
        self.cluster(&mut state);
        state
    }

    /// [`ObjectProblem::collision`] without the clusters (`clusters` is left empty): for the
    /// callers that only ask whether and where the object collides. Clustering is the costly
    /// part of a colliding pose's check, and most checks never look at the clusters. With a
    /// [`ObjectProblem::memo`], points its bounds prove clear of the margin are not queried
    /// (the contacts are the same).
    pub fn contacts(&self, pose: &Pose) -> CollisionState {
        let region = self.world_box(pose);
        // Only obstacles near the object's box can matter.
        let near = self
            .obstacles
            .near_box(&region, self.settings.collision_margin);
        if near.is_empty() {
            return CollisionState::default();
        }
        let mut forgetful = MemoState::default();
        let mut kept = self.memo.map(ContactMemo::lock);
        let memo = kept.as_deref_mut().unwrap_or(&mut forgetful);
        if self.memo.is_some() {
            let own = self.asset.surface_points().len();
            memo.hold_for(&near, own, |index| self.obstacles.samples(index).len());
        }
        let mut contacts = self.own_contacts(pose, &near, memo);
        contacts.extend(self.foreign_contacts(pose, &region, &near, memo));
        CollisionState {
            contacts,
            clusters: Vec::new(),
        }
    }

    /// The object's surface points within the margin of a `near` obstacle, each with its
    /// nearest such obstacle.
    fn own_contacts(&self, pose: &Pose, near: &[usize], memo: &mut MemoState) -> Vec<Contact> {
        let margin = self.settings.collision_margin;
        let reach = memo::reach(margin);
        let obstacles = self.obstacles;
        let mut contacts = Vec::new();
        for (k, local) in self.asset.surface_points().iter().enumerate() {
            let world = world_point(pose, local);
            let known = memo.own(k);
            let proven = known.clear_of(&world, margin);
            let outside = known.outside_unless_within(&world, reach);
            let mut best: Option<(usize, f64)> = None;
            let mut clearance = f64::INFINITY;
            for &index in near {
                let lipschitz = obstacles.is_lipschitz(index);
                if proven && lipschitz {
                    continue;
                }
                let gap = box_distance(obstacles.bounds(index), &world);
                let d = if gap >= margin {
                    gap
                } else if lipschitz
                    && outside
                    && obstacles.surface_within(index, &world, reach) == Some(false)
                {
                    reach
                } else {
                    obstacles.distance_to(index, &world)
                };
                if lipschitz {
                    clearance = clearance.min(d);
                }
                if d < margin && best.is_none_or(|(_, bd)| d < bd) {
                    best = Some((index, d));
                }
            }
            if !proven {
                memo.set_own(k, Clearance::new(world, clearance));
            }
            if let Some((obstacle, distance)) = best {
                contacts.push(Contact {
                    local: *local,
                    world,
                    distance,
                    violation: margin - distance,
                    obstacle,
                    push: obstacles.gradient_of(obstacle, &world),
                    foreign: false,
                });
            }
        }
        contacts
    }

    /// The `near` obstacles' samples inside (or within the margin of) the object's own field.
    fn foreign_contacts(
        &self,
        pose: &Pose,
        region: &Aabb,
        near: &[usize],
        memo: &mut MemoState,
    ) -> Vec<Contact> {
        let margin = self.settings.collision_margin;
        let own = if self.obstacles.is_exact() {
            self.asset.exact_field()
        } else {
            self.asset.grid_field()
        };
        let remember = own.is_lipschitz();
        // The margin in the asset's own units, where its field measures.
        let local_margin = margin / pose.scale;
        let local_reach = memo::reach(local_margin);
        let grown = Aabb::new(
            region.min - Vector3::repeat(margin),
            region.max + Vector3::repeat(margin),
        );
        let mut contacts = Vec::new();
        for (slot, &index) in near.iter().enumerate() {
            for (k, world) in self.obstacles.samples(index).iter().enumerate() {
                if !grown.contains_point(world) {
                    continue;
                }
                let local_scaled = unrotate_y(pose.yaw, &(world.coords - pose.translation));
                let local = Point3::from(local_scaled / pose.scale);
                let point = local.cast::<f32>();
                if remember {
                    let known = memo.foreign(slot, k);
                    if known.clear_of(&local, local_margin) {
                        continue;
                    }
                    if known.outside_unless_within(&local, local_reach)
                        && own.surface_within(&point, local_reach as f32) == Some(false)
                    {
                        memo.set_foreign(slot, k, Clearance::new(local, local_reach));
                        continue;
                    }
                }
                let (d, g) = own.distance_and_gradient(&point);
                if remember {
                    memo.set_foreign(slot, k, Clearance::new(local, f64::from(d)));
                }
                let distance = d as f64 * pose.scale;
                if distance >= margin {
                    continue;
                }
                let push = -rotate_y(pose.yaw, &g.cast::<f64>());
                contacts.push(Contact {
                    local,
                    world: *world,
                    distance,
                    violation: margin - distance,
                    obstacle: index,
                    push: push.try_normalize(1e-12).unwrap_or_else(Vector3::y),
                    foreign: true,
                });
            }
        }
        contacts
    }

    /// Groups `state`'s contacts into clusters of nearby points (indices into its contacts).
    /// Contacts of the bottom with the support surface are left out of the clusters: the
    /// stability term, not the scale, answers them.
    pub fn cluster(&self, state: &mut CollisionState) {
        let margin = self.settings.collision_margin;
        let contacts = &state.contacts;
        let band = self
            .support
            .plane()
            .map(|plane| plane.height + self.settings.support_clearance + 2.0 * margin + 0.005);
        let clustered: Vec<Contact> = contacts
            .iter()
            .filter(|c| band.is_none_or(|top| c.world.y > top))
            .copied()
            .collect();
        let mut clusters = cluster_contacts(
            &clustered,
            self.asset.sample_spacing(),
            self.settings.cluster_link_spacings,
        );
        // Map cluster members back to indices into `contacts`.
        if clustered.len() != contacts.len() {
            let index: Vec<usize> = contacts
                .iter()
                .enumerate()
                .filter(|(_, c)| band.is_none_or(|top| c.world.y > top))
                .map(|(i, _)| i)
                .collect();
            for cluster in &mut clusters {
                for member in cluster.iter_mut() {
                    *member = index[*member];
                }
            }
        }
        state.clusters = clusters;
    }

    /// The direction in which moving the object separates a contact fastest.
    pub fn obstacle_normal(&self, contact: &Contact) -> Vector3<f64> {
        contact.push
    }

    /// The stability residuals `d_i − clearance` of the bottom points, with the vertical
    /// derivative of each `d_i` (1 for a surface, the parent's gradient's y for a parent's
    /// geometry). Empty for a free object.
    pub fn stability_residuals(&self, pose: &Pose) -> Vec<(f64, f64)> {
        let clearance = self.settings.support_clearance;
        match self.support {
            Support::Free => Vec::new(),
            Support::Surface(plane) => self
                .asset
                .bottom_points()
                .iter()
                .map(|p| (world_point(pose, p).y - plane.height - clearance, 1.0))
                .collect(),
            Support::ParentGeometry { parent } => {
                let Some(index) = self.obstacles.index_of(parent) else {
                    return Vec::new();
                };
                self.asset
                    .bottom_points()
                    .iter()
                    .map(|p| {
                        let w = world_point(pose, p);
                        let d = self.obstacles.distance_to(index, &w);
                        let g = self.obstacles.gradient_of(index, &w);
                        (d - clearance, g.y)
                    })
                    .collect()
            }
        }
    }

    /// The loss terms at `pose` and the paper's descent direction for `stage`: the gradient of
    /// the weighted total, where the collision targets `T + u·|d|` and `g(|d|, u)·S` are held
    /// fixed (as in an autodiff graph that detaches them).
    pub fn losses_and_gradient(&self, pose: &Pose, stage: Stage) -> (Losses, PoseVector) {
        let (losses, grad, _) = self.losses_gradient_and_state(pose, stage);
        (losses, grad)
    }

    /// [`ObjectProblem::losses_and_gradient`] plus, in the physics stage, the collision state
    /// it was computed from.
    pub fn losses_gradient_and_state(
        &self,
        pose: &Pose,
        stage: Stage,
    ) -> (Losses, PoseVector, Option<CollisionState>) {
        let mut collision = None;
        let s = self.settings;
        let mut losses = Losses::default();
        let mut grad = PoseVector::zeros();
        match stage {
            Stage::Alignment => {
                if let Some(align) = self.alignment {
                    let (l, g) = align.loss_and_gradient(pose);
                    losses.pose = l;
                    grad += g * s.weight_pose;
                }
            }
            Stage::Physics => {
                let state = self.collision(pose);
                let free = state.is_free();
                collision = Some(state);
                let state = collision.as_ref().expect("just set");
                if !free {
                    let centroid = self.world_centroid(pose);
                    let n = state.contacts.len() as f64;
                    let mut push = Vector3::zeros();
                    for c in &state.contacts {
                        let u = centroid - c.world;
                        let dir = if u.norm() > 1e-9 {
                            u.normalize()
                        } else {
                            Vector3::y()
                        };
                        push += dir * c.violation;
                        losses.translation += c.violation * c.violation / n;
                    }
                    // ∂/∂T Σ‖(T + u|d|) − T‖² with the target detached: −2 Σ u|d| (mean).
                    let g = push * (-2.0 / n) * s.weight_translation;
                    grad[TX] += g.x;
                    grad[TY] += g.y;
                    grad[TZ] += g.z;
                    if state.clusters.len() > 1 {
                        let mut pull = 0.0;
                        for c in &state.contacts {
                            let arm = (centroid - c.world).norm().max(1e-6);
                            let target = pose.scale * ((arm - c.violation) / arm).max(0.0);
                            losses.scale += (target - pose.scale).powi(2) / n;
                            pull += target - pose.scale;
                        }
                        grad[SCALE] += -2.0 * pull / n * s.weight_scale;
                    }
                }
                let residuals = self.stability_residuals(pose);
                if !residuals.is_empty() {
                    let sigma2 = s.stability_length * s.stability_length;
                    let n = residuals.len() as f64;
                    let mut dy = 0.0;
                    for (r, dr_dy) in &residuals {
                        let e = (-(r * r) / sigma2).exp();
                        losses.stability += (1.0 - e) / n;
                        dy += 2.0 * r / sigma2 * e * dr_dy / n;
                    }
                    // Gravity acts vertically: the stability term moves the object up or down.
                    grad[TY] += dy * s.weight_stability;
                }
            }
        }
        (losses, grad, collision)
    }

    /// The loss terms at `pose`.
    pub fn losses(&self, pose: &Pose, stage: Stage) -> Losses {
        self.losses_and_gradient(pose, stage).0
    }

    /// The nearest feasible pose: scale inside its range (and below a compartment's clearance),
    /// the footprint centre over the support region, and the object's footprint inside the
    /// room ([`PreparedAsset::footprint_box`]).
    pub fn project(&self, pose: &Pose) -> Pose {
        let mut p = *pose;
        let [lo, hi] = self.feasible_scales();
        p.scale = p.scale.clamp(lo, hi);
        if !p.yaw.is_finite() {
            p.yaw = pose.yaw;
        }
        if let Some(plane) = self.support.plane() {
            let c = plane.clamp(p.translation.x, p.translation.z);
            p.translation.x = c.x;
            p.translation.z = c.y;
        }
        if let Some(room) = self.room {
            p.translation += room.shift_inside(&self.asset.footprint_box(&p));
        }
        p
    }

    /// The scales [`ObjectProblem::project`] allows: the asset's scale range, its top lowered
    /// to the largest scale that fits under the support's clearance (never below the bottom).
    fn feasible_scales(&self) -> [f64; 2] {
        let [lo, hi] = self.scale_range();
        match self.clearance_scale_limit() {
            Some(limit) => [lo, hi.min(limit).max(lo)],
            None => [lo, hi],
        }
    }

    /// The largest scale at which the object fits under its support's clearance, if the
    /// support is enclosed above.
    pub fn clearance_scale_limit(&self) -> Option<f64> {
        let plane = self.support.plane()?;
        let clearance = plane.clearance?;
        let height = self.asset.bounds().max.y.max(1e-6);
        Some(
            (clearance - self.settings.support_clearance - 2.0 * self.settings.collision_margin)
                / height,
        )
    }

    /// The pose that rests the object on its surface support by a change of scale that keeps
    /// its top where it is. A guidance image sees an object's top; where its bottom meets the
    /// support is hidden, or the least certain part of the fit: a bed fitted 8 % too small
    /// floats 3 cm so that its mattress meets the image, and put down as it is, the mattress
    /// and the cushions on it would sink by as much. The scale stays within its range (the
    /// physics stage then closes what is left of the gap). `None` without a surface support,
    /// for a gap under [`REST_BY_SCALE_GAP`], or when resting would change the scale by more
    /// than [`REST_BY_SCALE_LIMIT`]: that object is misplaced, not misjudged in size.
    pub fn rest_by_scale(&self, pose: &Pose) -> Option<Pose> {
        let resting = self.resting_height(pose)?;
        if (pose.translation.y - resting).abs() < REST_BY_SCALE_GAP {
            return None;
        }
        let bounds = self.asset.bounds();
        let height = (bounds.max.y - bounds.min.y).max(1e-6);
        let base = resting + pose.scale * bounds.min.y;
        let top = pose.translation.y + pose.scale * bounds.max.y;
        let wanted = (top - base) / height;
        if (wanted / pose.scale - 1.0).abs() > REST_BY_SCALE_LIMIT {
            return None;
        }
        let [lo, hi] = self.feasible_scales();
        let mut rested = *pose;
        rested.scale = wanted.clamp(lo, hi);
        rested.translation.y = top - rested.scale * bounds.max.y;
        Some(self.project(&rested))
    }

    /// The translation height that puts the object's bottom at its support plus clearance
    /// (only for surface supports).
    pub fn resting_height(&self, pose: &Pose) -> Option<f64> {
        let plane = self.support.plane()?;
        Some(
            plane.height + self.settings.support_clearance - pose.scale * self.asset.bounds().min.y,
        )
    }
}

#[cfg(test)]
mod tests {
    use std::sync::Arc;

    use scenethesis_scene_graph::Placement;
    use scenethesis_scene_graph::{Material, Mesh};
    use scenethesis_sdf::BoxSdf;

    use super::*;
    use crate::prepare::PrepareSettings;
    use crate::support::SupportPlane;

    fn cube(half: f32) -> PreparedAsset {
        let m = Material::new("m", [0.5; 3], 0.5);
        let mesh = Mesh::cuboid("c", m, [-half, 0.0, -half], [half, 2.0 * half, half]);
        PreparedAsset::new(
            "cube",
            &mesh,
            Vec::new(),
            [0.5, 1.5],
            Placement::Floor,
            &PrepareSettings::default(),
        )
        .unwrap()
    }

    /// A 1 m wall slab whose face is at x = `face`, extending toward +x when `positive`.
    fn slab(obstacles: &mut Obstacles, id: &str, face: f64, positive: bool) {
        let centre = if positive { face + 0.5 } else { face - 0.5 };
        obstacles.insert(
            id,
            Arc::new(BoxSdf::new(Vector3::new(0.5, 2.0, 2.0))),
            Pose::new(1.0, 0.0, Vector3::new(centre, 0.0, 0.0)),
            true,
            &[],
        );
    }

    /// A table top at 0.75 m, unbounded.
    fn table_top() -> Support {
        Support::Surface(SupportPlane {
            owner: "table".into(),
            surface: "top".into(),
            height: 0.75,
            region: None,
            clearance: None,
        })
    }

    fn problem<'a>(
        asset: &'a PreparedAsset,
        obstacles: &'a Obstacles,
        support: &'a Support,
        settings: &'a LossSettings,
    ) -> ObjectProblem<'a> {
        ObjectProblem::new("cube", asset, obstacles, support, settings)
    }

    #[test]
    fn translation_loss_pushes_from_the_penetration_toward_the_centroid() {
        let asset = cube(0.2);
        let mut obstacles = Obstacles::new(true);
        slab(&mut obstacles, "wall", 0.5, true);
        let settings = LossSettings::default();
        let support = Support::Free;
        let p = problem(&asset, &obstacles, &support, &settings);
        // The cube spans x in [0.2, 0.6]: 10 cm inside the wall.
        let pose = Pose::new(1.0, 0.0, Vector3::new(0.4, 0.5, 0.0));
        let (losses, grad, state) = p.losses_gradient_and_state(&pose, Stage::Physics);
        let state = state.unwrap();
        assert_eq!(state.clusters.len(), 1);
        assert!(losses.translation > 0.0 && losses.scale == 0.0);
        // Descent (−grad) moves the cube toward −x, away from the wall, and not vertically.
        assert!(grad[TX] > 0.0, "{grad:?}");
        assert!(grad[TY].abs() < 0.2 * grad[TX] && grad[TZ].abs() < 0.2 * grad[TX]);
        assert_eq!(grad[SCALE], 0.0);
        // Out of the wall (and beyond the margin) nothing pushes.
        let free = Pose::new(1.0, 0.0, Vector3::new(0.29, 0.5, 0.0));
        assert!(p.collision(&free).is_free());
    }

    #[test]
    fn scale_loss_acts_only_when_the_penetration_forms_two_clusters() {
        let asset = cube(0.2);
        let mut obstacles = Obstacles::new(true);
        // A 0.36 m gap between two walls for a 0.4 m cube: penetration on both sides.
        slab(&mut obstacles, "right", 0.18, true);
        slab(&mut obstacles, "left", -0.18, false);
        let settings = LossSettings::default();
        let support = Support::Free;
        let p = problem(&asset, &obstacles, &support, &settings);
        let pose = Pose::new(1.0, 0.0, Vector3::new(0.0, 0.5, 0.0));
        let (losses, grad, state) = p.losses_gradient_and_state(&pose, Stage::Physics);
        assert_eq!(state.unwrap().clusters.len(), 2);
        assert!(losses.scale > 0.0);
        // Descent shrinks the cube; the two pushes cancel along x.
        assert!(grad[SCALE] > 0.0, "{grad:?}");
        assert!(
            grad[TX].abs() < 0.05 * grad[SCALE].abs().max(1e-3),
            "{grad:?}"
        );
    }

    #[test]
    fn stability_loss_pulls_a_floating_object_down_to_its_support() {
        let asset = cube(0.1);
        let obstacles = Obstacles::new(true);
        let settings = LossSettings::default();
        let support = table_top();
        let p = problem(&asset, &obstacles, &support, &settings);
        let pose = Pose::new(1.0, 0.0, Vector3::new(0.0, 0.80, 0.0));
        let (losses, grad) = p.losses_and_gradient(&pose, Stage::Physics);
        let r = 0.05 - settings.support_clearance;
        let sigma = settings.stability_length;
        assert!((losses.stability - (1.0 - (-(r / sigma).powi(2)).exp())).abs() < 1e-9);
        assert!(grad[TY] > 0.0 && grad[TX] == 0.0 && grad[TZ] == 0.0);
        assert_eq!(
            p.resting_height(&pose),
            Some(0.75 + settings.support_clearance)
        );
    }

    #[test]
    fn resting_by_scale_keeps_the_top_the_image_sees() {
        // A 1 m cube (scale range 0.5–1.5) on a table top at 0.75 m.
        let asset = cube(0.5);
        let obstacles = Obstacles::new(true);
        let settings = LossSettings::default();
        let support = table_top();
        let p = problem(&asset, &obstacles, &support, &settings);
        let rest = 0.75 + settings.support_clearance;
        for (bottom, top) in [(0.80, 1.70), (0.70, 1.80)] {
            // Floating 5 cm (it grows) or sunk 5 cm (it shrinks): the top stays, the bottom
            // rests.
            let pose = Pose::new(top - bottom, 0.3, Vector3::new(0.2, bottom, -0.1));
            let rested = p.rest_by_scale(&pose).expect("a gap within the limit");
            assert!((rested.translation.y - rest).abs() < 1e-12, "{rested:?}");
            assert!((rested.translation.y + rested.scale - top).abs() < 1e-12);
            assert_eq!((rested.yaw, rested.translation.x), (0.3, 0.2));
        }
        // Within the fit's noise of rest (under 1 cm), or 40 cm off (a misplaced object, not a
        // misjudged size): no change.
        let resting = Pose::new(0.9, 0.0, Vector3::new(0.0, rest + 0.008, 0.0));
        assert_eq!(p.rest_by_scale(&resting), None);
        let far = Pose::new(0.9, 0.0, Vector3::new(0.0, 1.15, 0.0));
        assert_eq!(p.rest_by_scale(&far), None);
        // Without a surface to rest on there is nothing to do.
        let free = problem(&asset, &obstacles, &Support::Free, &settings);
        assert_eq!(free.rest_by_scale(&resting), None);
    }
}
