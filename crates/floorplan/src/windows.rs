//! Windows of a generated plan: on exterior walls only, sized and set at the sill height of
//! the room type, clear of doors.

use crate::knowledge::{Knowledge, WindowSpec};
use crate::plan::{FloorPlan, Window};
use crate::walls::Wall;

/// Free wall kept between a window and a wall's end, m.
pub const WINDOW_END_CLEARANCE: f64 = 0.3;
/// Free wall kept between a window and a door on the same wall, m.
pub const WINDOW_DOOR_CLEARANCE: f64 = 0.2;
/// A window is dropped rather than narrowed below this fraction of its type's width.
const MIN_WIDTH_FRACTION: f64 = 0.6;

/// The windows of a plan whose doors are placed and whose walls (without openings) are
/// `walls`: each room with a window type gets one on its longest exterior wall, and rooms with
/// windows of a metre or more a second on their next exterior wall.
pub fn place_windows(knowledge: &Knowledge, plan: &FloorPlan, walls: &[Wall]) -> Vec<Window> {
    let mut out = Vec::new();
    for room in &plan.rooms {
        let Some(spec) = knowledge.room(&room.room_type).and_then(|r| r.window) else {
            continue;
        };
        let mut outside: Vec<&Wall> = walls
            .iter()
            .filter(|w| w.rooms[0] == room.id && w.is_exterior())
            .collect();
        outside.sort_by(|a, b| b.length().total_cmp(&a.length()).then(a.id.cmp(&b.id)));
        let wanted = if spec.width >= 1.0 { 2 } else { 1 };
        for wall in outside.into_iter().take(wanted) {
            if let Some((t, width)) = free_span(plan, wall, &spec) {
                out.push(Window {
                    id: format!("window_{}", out.len()),
                    room: room.id.clone(),
                    centre: wall.segment().point(t),
                    width,
                    height: spec.height,
                    sill: spec.sill,
                });
            }
        }
    }
    out
}

/// The centre and width of the window on the widest stretch of `wall` clear of its ends and
/// of doors.
fn free_span(plan: &FloorPlan, wall: &Wall, spec: &WindowSpec) -> Option<(f64, f64)> {
    let seg = wall.segment();
    let mut blocked: Vec<(f64, f64)> = plan
        .doors
        .iter()
        .filter_map(|d| {
            seg.along(&d.centre)
                .map(|t| (t - d.width / 2.0, t + d.width / 2.0))
        })
        .filter(|(a, b)| *b > seg.lo && *a < seg.hi)
        .map(|(a, b)| (a - WINDOW_DOOR_CLEARANCE, b + WINDOW_DOOR_CLEARANCE))
        .collect();
    blocked.sort_by(|a, b| a.0.total_cmp(&b.0));
    let mut free = Vec::new();
    let mut from = seg.lo + WINDOW_END_CLEARANCE;
    for (a, b) in blocked {
        free.push((from, a));
        from = from.max(b);
    }
    free.push((from, seg.hi - WINDOW_END_CLEARANCE));
    let (a, b) = free
        .into_iter()
        .max_by(|x, y| (x.1 - x.0).total_cmp(&(y.1 - y.0)))?;
    let width = (((b - a).min(spec.width)) * 100.0).floor() / 100.0;
    if width < spec.width * MIN_WIDTH_FRACTION {
        return None;
    }
    Some((((a + b) / 2.0 * 100.0).round() / 100.0, width))
}
