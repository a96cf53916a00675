//! Parents grown within their scale range so the children the prompt puts on, in or under them
//! fit: a stated vase taller than every compartment of a bookshelf at its smallest plausible
//! size is not dropped while a slightly larger bookshelf would hold it.

use scenethesis_scene_graph::{AssetInfo, ParentRef, SurfaceKind};

use super::surfaces::{asked, FIT_SHARE, HEADROOM};
use crate::plan::Plan;

/// The uniform scale each planned object is laid out at, by plan index: 1 except for a floor
/// object whose support surfaces are too small for a stated child even at the child's smallest
/// scale, which grows (up to the top of its own scale range) just enough for the most
/// demanding such child that then fits. A child that would not fit even then grows nothing.
pub(super) fn layout_scales(plan: &Plan, infos: &[AssetInfo]) -> Vec<f64> {
    let mut scales = vec![1.0f64; plan.objects.len()];
    for (c, child) in plan.objects.iter().enumerate() {
        let ParentRef::Object(parent_id) = &child.parent else {
            continue;
        };
        let Some(p) = plan.objects.iter().position(|o| &o.id == parent_id) else {
            continue;
        };
        if plan.objects[p].parent != ParentRef::Ground || !asked(plan, c) {
            continue;
        }
        let need = needed_scale(&infos[p], &infos[c], child.support);
        // A hair above the exact ratio, so the packer's own comparisons pass.
        let grown = need * 1.001;
        if need > 1.0 && grown > scales[p] && grown <= infos[p].scale_range[1] as f64 {
            scales[p] = grown;
        }
    }
    scales
}

/// The smallest uniform scale of `parent` at which `child`, at the smallest scale of its
/// range, fits one of the surfaces `support` may use (their clearance and their extent, as
/// the packer measures them); infinite when it uses none.
fn needed_scale(
    parent: &AssetInfo,
    child: &AssetInfo,
    support: scenethesis_scene_graph::RelationKind,
) -> f64 {
    let smallest = child.scale_range[0] as f64;
    let [w, h, d] = child.size.map(|v| v as f64 * smallest);
    let kinds = SurfaceKind::for_support(support);
    parent
        .support_surfaces
        .iter()
        .filter(|s| kinds.contains(&s.kind))
        .map(|s| {
            let (x0, z0, x1, z1) = s.polygon.iter().fold(
                (f64::MAX, f64::MAX, f64::MIN, f64::MIN),
                |(a, b, c, e), q| {
                    let (x, z) = (q[0] as f64, q[1] as f64);
                    (a.min(x), b.min(z), c.max(x), e.max(z))
                },
            );
            let (sw, sd) = ((x1 - x0) * FIT_SHARE, (z1 - z0) * FIT_SHARE);
            let footprint = (w / sw).max(d / sd).min((d / sw).max(w / sd));
            let height = s.clearance.map_or(0.0, |c| (h + HEADROOM) / c as f64);
            footprint.max(height)
        })
        .fold(f64::INFINITY, f64::min)
}

/// `info` at uniform scale `k`: its size and every support surface (outline, height,
/// clearance) scaled about the asset origin.
pub(super) fn scaled(info: &AssetInfo, k: f64) -> AssetInfo {
    if k == 1.0 {
        return info.clone();
    }
    let k32 = k as f32;
    let mut out = info.clone();
    out.size = info.size.map(|v| v * k32);
    for s in &mut out.support_surfaces {
        s.polygon = s.polygon.iter().map(|q| [q[0] * k32, q[1] * k32]).collect();
        s.height *= k32;
        s.clearance = s.clearance.map(|c| c * k32);
    }
    out
}
