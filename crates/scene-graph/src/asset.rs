use crate::{Aabb, AssetRef, Joint, Mesh, RelationKind};
use serde::{Deserialize, Serialize};

/// Where an asset is normally placed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Placement {
    /// Stands on the floor (furniture, appliances, plants in pots).
    Floor,
    /// Hangs on a wall (paintings, whiteboards, wall shelves).
    Wall,
    /// Rests on another object's support surface (books, mugs, lamps on tables).
    Surface,
    /// Hangs from the ceiling (pendant lamps).
    Ceiling,
}

/// What kind of place a support surface is.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SurfaceKind {
    /// An upward face open above: a table top, a counter, a bed.
    Top,
    /// The floor of a compartment enclosed above: a shelf board, a cabinet or locker bay.
    Shelf,
    /// The inside bottom of a container open on top: a crate, a basket, a bowl, a mug.
    Interior,
    /// Floor space beneath the asset: under a table, a desk's knee hole, under a bench.
    Under,
}

impl SurfaceKind {
    /// The kinds of surface a child held by `support` may rest on, best first: *on* a top,
    /// else a shelf or an interior; *inside* a shelf bay or an interior; *under* the floor
    /// space beneath. Empty for the relations that do not rest on a parent's surface (the
    /// floor, a wall and the spatial relations). The layout fills surfaces in this order and
    /// the optimizer chooses among the same kinds, so a mug the layout puts on a cabinet's
    /// shelf because its top is full stays on that shelf.
    ///
    /// ```
    /// use scenethesis_scene_graph::{RelationKind, SurfaceKind};
    /// assert_eq!(SurfaceKind::for_support(RelationKind::On)[0], SurfaceKind::Top);
    /// assert!(SurfaceKind::for_support(RelationKind::On).contains(&SurfaceKind::Shelf));
    /// assert!(SurfaceKind::for_support(RelationKind::Beside).is_empty());
    /// ```
    pub fn for_support(support: RelationKind) -> &'static [SurfaceKind] {
        match support {
            RelationKind::On => &[SurfaceKind::Top, SurfaceKind::Shelf, SurfaceKind::Interior],
            RelationKind::Inside => &[SurfaceKind::Shelf, SurfaceKind::Interior],
            RelationKind::Under => &[SurfaceKind::Under],
            _ => &[],
        }
    }
}

/// How low is low, as a share of a height: a shelf at most this share of a top's height
/// beneath that top (of the same asset) is a *low shelf*, which holds what is *under* the top
/// (a basket on a coffee table's lower shelf); and an object *under* a target starts within
/// this share of the target's height from its bottom ([`relation_holds`](crate::relation_holds)).
/// The layout, the optimizer's surface choice and the relation check all read it from here.
pub const LOW_SHELF_SHARE: f64 = 0.35;

/// Whether `shelf` is a low shelf beneath a top of the same asset (`surfaces`): at most
/// [`LOW_SHELF_SHARE`] of the top's height.
pub fn is_low_shelf(shelf: &SupportSurface, surfaces: &[SupportSurface]) -> bool {
    shelf.kind == SurfaceKind::Shelf
        && surfaces.iter().any(|t| {
            t.kind == SurfaceKind::Top
                && t.height > shelf.height
                && shelf.height <= LOW_SHELF_SHARE as f32 * t.height
        })
}

/// Whether an asset with `surfaces` holds anything *under* it: a floor space beneath it or a
/// low shelf ([`is_low_shelf`]).
pub fn holds_under(surfaces: &[SupportSurface]) -> bool {
    surfaces
        .iter()
        .any(|s| s.kind == SurfaceKind::Under || is_low_shelf(s, surfaces))
}

/// A place where something can rest, in the asset's own frame.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SupportSurface {
    /// Name unique within the asset, e.g. `top`, `shelf_2`, `under`.
    pub name: String,
    /// The kind of place.
    pub kind: SurfaceKind,
    /// The usable region as a convex polygon in (x, z), counter-clockwise seen from above
    /// (+Y toward the viewer); already shrunk by walls and rims so anything inside it is free.
    pub polygon: Vec<[f32; 2]>,
    /// Height of the surface (y) in the asset frame; 0 for `Under`.
    pub height: f32,
    /// Free height above the surface before hitting the asset again; `None` when open above.
    pub clearance: Option<f32>,
}

impl SupportSurface {
    /// The (x, z) centroid of the polygon's vertices.
    pub fn center(&self) -> [f32; 2] {
        let n = self.polygon.len().max(1) as f32;
        let (sx, sz) = self
            .polygon
            .iter()
            .fold((0.0, 0.0), |(x, z), p| (x + p[0], z + p[1]));
        [sx / n, sz / n]
    }

    /// Area of the polygon in square metres.
    pub fn area(&self) -> f32 {
        let n = self.polygon.len();
        let twice: f32 = (0..n)
            .map(|i| {
                let (a, b) = (self.polygon[i], self.polygon[(i + 1) % n]);
                a[0] * b[1] - b[0] * a[1]
            })
            .sum();
        twice.abs() / 2.0
    }

    /// Whether the (x, z) point lies inside the convex polygon (or on its border).
    pub fn contains(&self, x: f32, z: f32) -> bool {
        let n = self.polygon.len();
        if n < 3 {
            return false;
        }
        let mut sign = 0.0f32;
        for i in 0..n {
            let (a, b) = (self.polygon[i], self.polygon[(i + 1) % n]);
            let cross = (b[0] - a[0]) * (z - a[1]) - (b[1] - a[1]) * (x - a[0]);
            if cross.abs() > 1e-7 {
                if sign != 0.0 && cross.signum() != sign {
                    return false;
                }
                sign = cross.signum();
            }
        }
        true
    }
}

/// Everything the planner, guide and optimizer need to know about one asset.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AssetInfo {
    /// Where the mesh comes from (generator and seed, or imported file).
    pub source: AssetRef,
    /// Category, e.g. `bookshelf`.
    pub category: String,
    /// Other names for the category (`bookcase`), used by retrieval.
    pub synonyms: Vec<String>,
    /// Extent of the mesh along x, y and z in metres (at scale 1).
    pub size: [f32; 3],
    /// Where the asset is normally placed.
    pub placement: Placement,
    /// Canonical front in the asset frame; always +Z (`[0, 0, 1]`) after normalisation.
    pub front: [f32; 3],
    /// Every place something can rest on, in, or under the asset.
    pub support_surfaces: Vec<SupportSurface>,
    /// The range of uniform scale the optimizer may apply and still look plausible.
    pub scale_range: [f32; 2],
    /// The moving parts' joints (doors, drawers, lids), parents before children; empty for a
    /// rigid asset.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub joints: Vec<Joint>,
    /// The box the moving parts sweep while opening ([`opening_sweep`](crate::opening_sweep)),
    /// in the asset frame: space a layout keeps free of other objects. `None` when nothing
    /// moves.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub opening_bounds: Option<Aabb>,
}

/// An asset: its mesh and its metadata.
#[derive(Debug, Clone, PartialEq)]
pub struct Asset {
    /// Metadata.
    pub info: AssetInfo,
    /// Geometry and materials in the asset's own frame.
    pub mesh: Mesh,
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn polygon_area_center_and_containment() {
        let s = SupportSurface {
            name: "top".into(),
            kind: SurfaceKind::Top,
            polygon: vec![[-1.0, -0.5], [-1.0, 0.5], [1.0, 0.5], [1.0, -0.5]],
            height: 0.75,
            clearance: None,
        };
        assert!((s.area() - 2.0).abs() < 1e-6);
        assert_eq!(s.center(), [0.0, 0.0]);
        assert!(s.contains(0.9, 0.4));
        assert!(!s.contains(1.1, 0.0));
    }
}
