//! What an object rests on: a horizontal support surface in world coordinates (the floor, a
//! table top, a shelf board, a crate's interior) or, without surface metadata, its parent's
//! geometry.

use nalgebra::{Point2, Point3, Vector3};
use scenethesis_scene_graph::{Architecture, Pose, RelationKind};
use scenethesis_scene_graph::{SupportSurface, SurfaceKind};
use serde::{Deserialize, Serialize};

use scenethesis_correspondence::params::world_point;

/// A horizontal support surface placed in the world.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SupportPlane {
    /// Id of what holds the surface: an object id, or the floor's id.
    pub owner: String,
    /// Name of the surface on its owner (e.g. `top`, `shelf_1`, or `floor`).
    pub surface: String,
    /// World height of the surface.
    pub height: f64,
    /// The usable region as a convex polygon in world (x, z), counter-clockwise seen from
    /// above; `None` for the whole floor (the room bounds limit it instead).
    pub region: Option<Vec<Point2<f64>>>,
    /// Free height above the surface in metres, if it is enclosed above (a shelf compartment).
    pub clearance: Option<f64>,
}

impl SupportPlane {
    /// The floor of a scene at y = 0.
    pub fn floor(architecture: &Architecture) -> Self {
        Self {
            owner: architecture.floor.id.clone(),
            surface: architecture.floor.id.clone(),
            height: 0.0,
            region: None,
            clearance: None,
        }
    }

    /// An asset's support surface placed with its owner's pose.
    pub fn placed(owner: &str, surface: &SupportSurface, owner_pose: &Pose) -> Self {
        let region = surface
            .polygon
            .iter()
            .map(|p| {
                let w = world_point(
                    owner_pose,
                    &Point3::new(p[0] as f64, surface.height as f64, p[1] as f64),
                );
                Point2::new(w.x, w.z)
            })
            .collect();
        Self {
            owner: owner.to_owned(),
            surface: surface.name.clone(),
            height: owner_pose.translation.y + owner_pose.scale * surface.height as f64,
            region: Some(region),
            clearance: surface.clearance.map(|c| c as f64 * owner_pose.scale),
        }
    }

    /// Whether the world (x, z) point lies over the surface (always true without a region).
    pub fn contains(&self, x: f64, z: f64) -> bool {
        self.region
            .as_ref()
            .is_none_or(|poly| polygon_contains(poly, &Point2::new(x, z)))
    }

    /// The point of the region closest to (x, z) (the point itself when it is inside).
    pub fn clamp(&self, x: f64, z: f64) -> Point2<f64> {
        let p = Point2::new(x, z);
        match &self.region {
            Some(poly) if !polygon_contains(poly, &p) => closest_on_polygon(poly, &p),
            _ => p,
        }
    }

    /// Horizontal distance from (x, z) to the region (0 inside).
    pub fn horizontal_distance(&self, x: f64, z: f64) -> f64 {
        (self.clamp(x, z) - Point2::new(x, z)).norm()
    }
}

/// How an object rests under gravity.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "kebab-case")]
pub enum Support {
    /// On a horizontal surface: its bottom should touch the plane.
    Surface(SupportPlane),
    /// On its parent's geometry, which has no surface metadata: its bottom points should have
    /// zero signed distance to the parent (the paper's literal stability term).
    ParentGeometry {
        /// The parent's id.
        parent: String,
    },
    /// Not resting on anything (wall-mounted or hanging): no stability term.
    Free,
}

impl Support {
    /// The surface plane, if this is a surface support.
    pub fn plane(&self) -> Option<&SupportPlane> {
        match self {
            Support::Surface(p) => Some(p),
            _ => None,
        }
    }
}

/// How much closer in height (metres) a surface of a less preferred kind must be to a child's
/// foot, per place down the relation's order ([`SurfaceKind::for_support`]), to hold it
/// instead: a mug *on* a cabinet stands on its top unless it stands at the height of one of
/// its shelves (where the layout put it because the top was full).
const KIND_RANK_COST: f64 = 0.05;

/// Picks the parent's support surface for a child standing at `foot` (world position of its
/// asset origin, i.e. the centre of its footprint at its lowest point) with relation `relation`:
/// among the surfaces of the kinds the relation allows ([`SurfaceKind::for_support`]), a
/// surface under the foot before one beside it, then the nearest in height, a less preferred
/// kind counting `KIND_RANK_COST` farther per rank. For `under`, the low shelves beneath a
/// top ([`is_low_shelf`]) fit as well as the floor beneath it. `None` when the parent has no
/// surfaces of a fitting kind.
pub fn choose_surface(
    parent_id: &str,
    parent_pose: &Pose,
    surfaces: &[SupportSurface],
    relation: RelationKind,
    foot: &Point3<f64>,
) -> Option<SupportPlane> {
    let mut best: Option<(f64, SupportPlane)> = None;
    for (rank, kind) in SurfaceKind::for_support(relation).iter().enumerate() {
        let fits = |s: &&SupportSurface| {
            s.kind == *kind || (*kind == SurfaceKind::Under && is_low_shelf(s, surfaces))
        };
        for s in surfaces.iter().filter(fits) {
            let plane = SupportPlane::placed(parent_id, s, parent_pose);
            let horizontal = plane.horizontal_distance(foot.x, foot.z);
            let vertical = (plane.height - foot.y).abs();
            let beside = if horizontal > 0.0 { 100.0 } else { 0.0 };
            let cost = beside + vertical + horizontal * 4.0 + rank as f64 * KIND_RANK_COST;
            if best.as_ref().is_none_or(|(c, _)| cost < *c) {
                best = Some((cost, plane));
            }
        }
    }
    best.map(|(_, p)| p)
}

pub use scenethesis_scene_graph::is_low_shelf;

/// Whether `p` is inside the convex polygon (either winding) or on its border.
pub fn polygon_contains(poly: &[Point2<f64>], p: &Point2<f64>) -> bool {
    let n = poly.len();
    if n < 3 {
        return false;
    }
    let mut sign = 0.0f64;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let cross = (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x);
        if cross.abs() > 1e-12 {
            if sign != 0.0 && cross.signum() != sign {
                return false;
            }
            sign = cross.signum();
        }
    }
    true
}

/// The closest point to `p` on the polygon's boundary.
pub fn closest_on_polygon(poly: &[Point2<f64>], p: &Point2<f64>) -> Point2<f64> {
    let n = poly.len();
    if n == 0 {
        return *p;
    }
    let mut best = poly[0];
    let mut best_d = f64::INFINITY;
    for i in 0..n {
        let (a, b) = (poly[i], poly[(i + 1) % n]);
        let ab = b - a;
        let t = if ab.norm_squared() > 0.0 {
            ((p - a).dot(&ab) / ab.norm_squared()).clamp(0.0, 1.0)
        } else {
            0.0
        };
        let q = a + ab * t;
        let d = (q - p).norm_squared();
        if d < best_d {
            best_d = d;
            best = q;
        }
    }
    best
}

/// The horizontal (x, z) part of a vector.
pub fn horizontal(v: &Vector3<f64>) -> Vector3<f64> {
    Vector3::new(v.x, 0.0, v.z)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn shelf_surfaces() -> Vec<SupportSurface> {
        let poly = vec![[-0.4, -0.15], [-0.4, 0.15], [0.4, 0.15], [0.4, -0.15]];
        (0..3)
            .map(|i| SupportSurface {
                name: format!("shelf_{i}"),
                kind: SurfaceKind::Shelf,
                polygon: poly.clone(),
                height: 0.05 + 0.4 * i as f32,
                clearance: Some(0.35),
            })
            .collect()
    }

    #[test]
    fn picks_the_compartment_nearest_in_height_and_places_it() {
        let pose = Pose::new(
            1.0,
            std::f64::consts::FRAC_PI_2,
            Vector3::new(1.0, 0.0, 0.0),
        );
        let s = shelf_surfaces();
        let foot = Point3::new(1.0, 0.47, 0.1);
        let plane = choose_surface("shelf", &pose, &s, RelationKind::Inside, &foot).unwrap();
        assert_eq!(plane.surface, "shelf_1");
        assert!((plane.height - 0.45).abs() < 1e-6);
        // Rotated a quarter turn, the 0.8 m wide board runs along z.
        assert!(plane.contains(1.1, 0.35) && !plane.contains(1.3, 0.0));
        assert!(choose_surface("shelf", &pose, &s, RelationKind::Under, &foot).is_none());
        let c = plane.clamp(1.3, 0.0);
        assert!((c - Point2::new(1.15, 0.0)).norm() < 1e-6, "{c:?}");
    }

    #[test]
    fn under_a_table_is_its_floor_space_or_its_low_shelf_whichever_holds_the_foot() {
        let poly = vec![[-0.4, -0.25], [-0.4, 0.25], [0.4, 0.25], [0.4, -0.25]];
        let surface = |name: &str, kind, height| SupportSurface {
            name: name.into(),
            kind,
            polygon: poly.clone(),
            height,
            clearance: None,
        };
        let pose = Pose::new(1.0, 0.0, Vector3::zeros());
        // A coffee table whose lower shelf leaves no room beneath it: the shelf is "under".
        let table = vec![
            surface("top", SurfaceKind::Top, 0.45),
            surface("lower_shelf", SurfaceKind::Shelf, 0.12),
        ];
        let on_shelf = Point3::new(0.1, 0.12, 0.0);
        let plane = choose_surface("t", &pose, &table, RelationKind::Under, &on_shelf).unwrap();
        assert_eq!(plane.surface, "lower_shelf");
        // With floor space under it too, the surface nearest the foot wins.
        let mut both = table.clone();
        both.push(surface("under", SurfaceKind::Under, 0.0));
        let on_floor = Point3::new(0.1, 0.0, 0.0);
        let pick = |foot| choose_surface("t", &pose, &both, RelationKind::Under, foot).unwrap();
        assert_eq!(pick(&on_shelf).surface, "lower_shelf");
        assert_eq!(pick(&on_floor).surface, "under");
        // A shelf high in a bookcase is not under anything.
        let tall = vec![
            surface("top", SurfaceKind::Top, 1.8),
            surface("shelf_3", SurfaceKind::Shelf, 1.2),
        ];
        assert!(choose_surface("b", &pose, &tall, RelationKind::Under, &on_shelf).is_none());
    }

    #[test]
    fn on_a_cabinet_is_its_top_unless_the_foot_stands_at_a_shelf() {
        // A bathroom cabinet: a top at 1 m and a bay floor behind its doors at 0.1 m. The
        // layout puts a bottle "on" it on the bay floor once the top is full; the optimizer
        // must keep it there, not lift it onto the top into the towels.
        let mut cabinet = shelf_surfaces();
        cabinet.truncate(1);
        cabinet.push(SupportSurface {
            name: "top".into(),
            kind: SurfaceKind::Top,
            polygon: vec![[-0.4, -0.15], [-0.4, 0.15], [0.4, 0.15], [0.4, -0.15]],
            height: 1.0,
            clearance: None,
        });
        let pose = Pose::new(1.0, 0.0, Vector3::zeros());
        let pick = |y: f64| {
            let foot = Point3::new(0.1, y, 0.0);
            choose_surface("c", &pose, &cabinet, RelationKind::On, &foot)
                .unwrap()
                .surface
        };
        assert_eq!(pick(0.05), "shelf_0");
        assert_eq!(pick(1.0), "top");
        // A foot lifted from an image a few centimetres off the top is still on the top;
        // between the two, the top is preferred until the shelf is clearly nearer.
        assert_eq!(pick(0.97), "top");
        assert_eq!(pick(0.55), "top");
        assert_eq!(pick(0.45), "shelf_0");
    }
}
