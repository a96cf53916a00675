//! Support surfaces over a rectangle or a regular polygon.

use scenethesis_scene_graph::{SupportSurface, SurfaceKind};

use crate::{rect, regular_polygon};

/// A support surface over the axis-aligned rectangle `min`..`max` in (x, z), shrunk by `margin`
/// on every side (never below a 1 cm square around the centre).
pub fn rect_surface(
    name: &str,
    kind: SurfaceKind,
    min: [f32; 2],
    max: [f32; 2],
    height: f32,
    clearance: Option<f32>,
    margin: f32,
) -> SupportSurface {
    let shrink = |lo: f32, hi: f32| {
        let m = margin.min(0.5 * (hi - lo) - 0.005).max(0.0);
        (lo + m, hi - m)
    };
    let (x0, x1) = shrink(min[0], max[0]);
    let (z0, z1) = shrink(min[1], max[1]);
    SupportSurface {
        name: name.into(),
        kind,
        polygon: rect(x0, z0, x1, z1),
        height,
        clearance,
    }
}

/// A support surface over a regular `sides`-gon inscribed in the circle of `radius` (already
/// shrunk by the caller) around `center` in (x, z).
pub fn disc_surface(
    name: &str,
    kind: SurfaceKind,
    center: [f32; 2],
    radius: f32,
    height: f32,
    clearance: Option<f32>,
    sides: u32,
) -> SupportSurface {
    SupportSurface {
        name: name.into(),
        kind,
        polygon: regular_polygon(center, radius, sides),
        height,
        clearance,
    }
}
