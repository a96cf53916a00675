//! Signed distance to a whole scene of posed objects.

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use rayon::prelude::*;
use scenethesis_scene_graph::Pose;

use crate::geometry::distance2_to_box;
use crate::{SdfError, SignedDistance};

/// One posed object: its field and the cached transform.
struct Entry {
    id: String,
    field: Arc<dyn SignedDistance>,
    pose: Pose,
    cos: f32,
    sin: f32,
    scale: f32,
    translation: Vector3<f32>,
    /// World box of the surface; distances outside it are at least the distance to it.
    world_min: [f32; 3],
    world_max: [f32; 3],
    valid: bool,
}

impl Entry {
    fn new(id: String, field: Arc<dyn SignedDistance>, pose: Pose) -> Self {
        let mut e = Entry {
            id,
            field,
            pose,
            cos: 1.0,
            sin: 0.0,
            scale: 1.0,
            translation: Vector3::zeros(),
            world_min: [0.0; 3],
            world_max: [0.0; 3],
            valid: false,
        };
        e.set_pose(pose);
        e
    }

    fn set_pose(&mut self, pose: Pose) {
        self.pose = pose;
        self.valid = pose.is_finite() && pose.scale > 0.0;
        self.cos = pose.yaw.cos() as f32;
        self.sin = pose.yaw.sin() as f32;
        self.scale = pose.scale as f32;
        self.translation = pose.translation.cast::<f32>();
        let (lo, hi) = self.field.local_bounds();
        let s = self.scale;
        let t = self.translation;
        // Yaw turns about +Y, so the y range is exact.
        self.world_min[1] = t.y + s * lo.y;
        self.world_max[1] = t.y + s * hi.y;
        let finite = [lo.x, lo.z, hi.x, hi.z].iter().all(|v| v.is_finite());
        if finite {
            let mut min = [f32::INFINITY; 2];
            let mut max = [f32::NEG_INFINITY; 2];
            for x in [lo.x, hi.x] {
                for z in [lo.z, hi.z] {
                    let w = self.to_world_vector(&Vector3::new(x, 0.0, z)) * s + t;
                    min = [min[0].min(w.x), min[1].min(w.z)];
                    max = [max[0].max(w.x), max[1].max(w.z)];
                }
            }
            // Pad by a relative epsilon so rounding never culls a touching object.
            let pad = 1e-5 * (1.0 + (max[0] - min[0]).max(max[1] - min[1]));
            self.world_min[0] = min[0] - pad;
            self.world_min[2] = min[1] - pad;
            self.world_max[0] = max[0] + pad;
            self.world_max[2] = max[1] + pad;
        } else {
            self.world_min[0] = f32::NEG_INFINITY;
            self.world_min[2] = f32::NEG_INFINITY;
            self.world_max[0] = f32::INFINITY;
            self.world_max[2] = f32::INFINITY;
        }
    }

    /// R_y(yaw) · v.
    #[inline]
    fn to_world_vector(&self, v: &Vector3<f32>) -> Vector3<f32> {
        Vector3::new(
            self.cos * v.x + self.sin * v.z,
            v.y,
            -self.sin * v.x + self.cos * v.z,
        )
    }

    /// The world point in the object's frame.
    #[inline]
    fn to_local(&self, p: &Point3<f32>) -> Point3<f32> {
        let d = p.coords - self.translation;
        let inv = 1.0 / self.scale;
        Point3::new(
            (self.cos * d.x - self.sin * d.z) * inv,
            d.y * inv,
            (self.sin * d.x + self.cos * d.z) * inv,
        )
    }

    #[inline]
    fn box_distance2(&self, p: &Point3<f32>) -> f32 {
        distance2_to_box(&[p.x, p.y, p.z], &self.world_min, &self.world_max)
    }

    #[inline]
    fn distance(&self, p: &Point3<f32>) -> f32 {
        self.field.distance(&self.to_local(p)) * self.scale
    }

    fn surface_within(&self, p: &Point3<f32>, radius: f32) -> Option<bool> {
        self.field
            .surface_within(&self.to_local(p), radius / self.scale)
    }

    #[inline]
    fn distance_and_gradient(&self, p: &Point3<f32>) -> (f32, Vector3<f32>) {
        let (d, g) = self.field.distance_and_gradient(&self.to_local(p));
        (d * self.scale, self.to_world_vector(&g))
    }
}

/// The nearest object to a point and the field there.
#[derive(Debug, Clone, PartialEq)]
pub struct SceneQuery<'a> {
    /// Id of the object with the smallest signed distance.
    pub id: &'a str,
    /// Its signed distance in world metres (negative inside it).
    pub distance: f32,
    /// Unit world-space gradient of that object's field.
    pub gradient: Vector3<f32>,
}

/// Signed distance to a scene: the union of many objects, each a field in its own frame placed
/// with a 5-DoF [`Pose`] (uniform scale, yaw, translation).
///
/// World distance is `scale ×` the local distance at the inverse-posed point, so moving an
/// object only updates its transform ([`SceneSdf::set_pose`]) and never rebakes its field.
/// Queries can exclude objects (an object must not collide with itself). Each object's world
/// box culls it when it cannot beat the best distance found so far, so far objects cost one box
/// test. Objects are kept in id order, so ties resolve to the smallest id.
#[derive(Default)]
pub struct SceneSdf {
    entries: Vec<Entry>,
}

impl std::fmt::Debug for SceneSdf {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_map()
            .entries(self.entries.iter().map(|e| (&e.id, &e.pose)))
            .finish()
    }
}

impl SceneSdf {
    /// An empty scene.
    pub fn new() -> Self {
        Self::default()
    }

    fn position(&self, id: &str) -> Result<usize, usize> {
        self.entries.binary_search_by(|e| e.id.as_str().cmp(id))
    }

    /// Adds an object (or replaces the one with the same id). An object whose pose is not
    /// finite with positive scale is kept but ignored by queries until [`SceneSdf::set_pose`]
    /// gives it a valid pose.
    pub fn insert(&mut self, id: impl Into<String>, field: Arc<dyn SignedDistance>, pose: Pose) {
        let id = id.into();
        match self.position(&id) {
            Ok(i) => self.entries[i] = Entry::new(id, field, pose),
            Err(i) => self.entries.insert(i, Entry::new(id, field, pose)),
        }
    }

    /// Moves an object; its field is reused as is.
    pub fn set_pose(&mut self, id: &str, pose: Pose) -> Result<(), SdfError> {
        if !(pose.is_finite() && pose.scale > 0.0) {
            return Err(SdfError::InvalidPose {
                id: id.to_string(),
                pose,
            });
        }
        let i = self
            .position(id)
            .map_err(|_| SdfError::UnknownObject(id.to_string()))?;
        self.entries[i].set_pose(pose);
        Ok(())
    }

    /// Removes an object (no effect if absent).
    pub fn remove(&mut self, id: &str) {
        if let Ok(i) = self.position(id) {
            self.entries.remove(i);
        }
    }

    /// The pose of an object.
    pub fn pose(&self, id: &str) -> Option<Pose> {
        self.position(id).ok().map(|i| self.entries[i].pose)
    }

    /// The field of an object.
    pub fn field(&self, id: &str) -> Option<&Arc<dyn SignedDistance>> {
        self.position(id).ok().map(|i| &self.entries[i].field)
    }

    /// Object ids in order.
    pub fn ids(&self) -> impl Iterator<Item = &str> {
        self.entries.iter().map(|e| e.id.as_str())
    }

    /// Number of objects.
    pub fn len(&self) -> usize {
        self.entries.len()
    }

    /// Whether the scene holds no object.
    pub fn is_empty(&self) -> bool {
        self.entries.is_empty()
    }

    /// The world box `(min, max)` of an object's surface.
    pub fn world_bounds(&self, id: &str) -> Option<(Point3<f32>, Point3<f32>)> {
        self.position(id).ok().map(|i| {
            let e = &self.entries[i];
            (Point3::from(e.world_min), Point3::from(e.world_max))
        })
    }

    /// Signed distance from `p` to the union of all objects not in `exclude`
    /// (`f32::INFINITY` when none is left).
    pub fn distance(&self, p: &Point3<f32>, exclude: &[&str]) -> f32 {
        let mask = self.mask(exclude);
        self.nearest_masked(p, &mask)
            .map_or(f32::INFINITY, |(_, d)| d)
    }

    /// The object closest to `p` (smallest signed distance) among those not excluded, with its
    /// distance.
    pub fn nearest(&self, p: &Point3<f32>, exclude: &[&str]) -> Option<(&str, f32)> {
        let mask = self.mask(exclude);
        self.nearest_masked(p, &mask)
            .map(|(i, d)| (self.entries[i].id.as_str(), d))
    }

    /// Nearest object, its distance and the world gradient of its field at `p`.
    pub fn query(&self, p: &Point3<f32>, exclude: &[&str]) -> Option<SceneQuery<'_>> {
        let mask = self.mask(exclude);
        let (i, _) = self.nearest_masked(p, &mask)?;
        let e = &self.entries[i];
        let (distance, gradient) = e.distance_and_gradient(p);
        Some(SceneQuery {
            id: &e.id,
            distance,
            gradient,
        })
    }

    /// Signed distance from `p` to one object (ignoring all others).
    pub fn distance_to(&self, id: &str, p: &Point3<f32>) -> Option<f32> {
        let e = &self.entries[self.position(id).ok()?];
        e.valid.then(|| e.distance(p))
    }

    /// Whether one object's surface comes within `radius` (world metres) of `p`, when its
    /// field answers that cheaply ([`SignedDistance::surface_within`]); `None` when it cannot
    /// or when the scene has no valid object `id`.
    pub fn surface_within(&self, id: &str, p: &Point3<f32>, radius: f32) -> Option<bool> {
        let e = &self.entries[self.position(id).ok()?];
        e.valid.then(|| e.surface_within(p, radius)).flatten()
    }

    /// Signed distance and unit world gradient of one object's field at `p`.
    pub fn distance_and_gradient_to(
        &self,
        id: &str,
        p: &Point3<f32>,
    ) -> Option<(f32, Vector3<f32>)> {
        let e = &self.entries[self.position(id).ok()?];
        e.valid.then(|| e.distance_and_gradient(p))
    }

    /// Signed distances of many points to the scene minus `exclude`, in parallel (rayon).
    pub fn distances(&self, points: &[Point3<f32>], exclude: &[&str]) -> Vec<f32> {
        let mask = self.mask(exclude);
        points
            .par_iter()
            .with_min_len(256)
            .map(|p| {
                self.nearest_masked(p, &mask)
                    .map_or(f32::INFINITY, |(_, d)| d)
            })
            .collect()
    }

    /// Per entry: whether it takes part in queries.
    fn mask(&self, exclude: &[&str]) -> Vec<bool> {
        self.entries
            .iter()
            .map(|e| e.valid && !exclude.contains(&e.id.as_str()))
            .collect()
    }

    fn nearest_masked(&self, p: &Point3<f32>, mask: &[bool]) -> Option<(usize, f32)> {
        // Start with the object whose box is nearest, then cull the rest by box distance.
        let mut first: Option<(usize, f32)> = None;
        for (i, e) in self.entries.iter().enumerate() {
            if !mask[i] {
                continue;
            }
            let b = e.box_distance2(p);
            if first.is_none_or(|(_, fb)| b < fb) {
                first = Some((i, b));
            }
        }
        let (fi, _) = first?;
        let mut best = (fi, self.entries[fi].distance(p));
        for (i, e) in self.entries.iter().enumerate() {
            if !mask[i] || i == fi {
                continue;
            }
            let b2 = e.box_distance2(p);
            if b2 > 0.0 && b2 >= best.1 * best.1.abs() {
                continue;
            }
            let d = e.distance(p);
            if d < best.1 || (d == best.1 && i < best.0) {
                best = (i, d);
            }
        }
        Some(best)
    }
}
