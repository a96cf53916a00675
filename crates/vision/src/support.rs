//! Phase 5: what holds each lifted box up.
//!
//! Boxes are visited lowest first. A box whose bottom is at the floor stands on the ground; one
//! whose bottom meets another box's top within a gap tolerance, with most of its footprint over
//! that box, stands on it; one whose bottom lies between another box's bottom and top, with its
//! footprint inside, sits inside it (a shelf, a cabinet). A box held by nothing whose bottom
//! is too low to hang on a wall stands on the ground (its bottom was lifted wrongly); anything
//! else is reported as unsupported so the caller can decide (a wall-mounted object, or a
//! lifting error). A box at the floor lying mostly over a larger low one (a mat, a towel, a
//! pallet) rests on it.

use std::collections::BTreeMap;

use serde::{Deserialize, Serialize};

use crate::footprint::FloorRectangle;
use crate::lifted_box::LiftedBox;
use scenethesis_scene_graph::{hangs_on_wall, Wall};

/// How a lifted box is held up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SupportKind {
    /// Stands on the floor.
    Ground,
    /// Rests on top of its parent.
    On,
    /// Rests inside its parent (on a shelf or an inner floor).
    Inside,
    /// Stands on the floor under its parent (a basket under a table): the parent's footprint
    /// covers it and the parent's top is above it.
    Under,
    /// Nothing below it: mounted on a wall, or lifted wrongly.
    Unsupported,
    /// Hangs on the wall named as its parent: its back touches the wall and its bottom is well
    /// above the floor ([`mount_on_walls`] turns unsupported boxes into mounted ones when the
    /// room's walls are known). In `scene.json` this is parent = the wall id, support `mounted`.
    Mounted,
}

/// The inferred support of one box.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SupportGuess {
    /// The supported box's object id.
    pub id: String,
    /// The supporting object's id, or the wall's id when mounted; `None` for the ground or when
    /// unsupported.
    pub parent: Option<String>,
    /// How it is supported.
    pub kind: SupportKind,
}

/// The box a floor-standing box `i` stands under: among the boxes taller than it whose
/// footprint covers at least 60 % of its own, the one standing lowest (its bottom may be on
/// the floor, as table legs are), then the lowest-topped: a toolbox on a workbench covers the
/// paint can under the workbench too, and a workbench with a pegboard tops out above it.
fn under(boxes: &[LiftedBox], i: usize) -> Option<usize> {
    let b = &boxes[i];
    let foot = b.footprint();
    let mut best: Option<usize> = None;
    for (j, a) in boxes.iter().enumerate() {
        if j == i || a.top() <= b.top() + 0.02 || foot.fraction_inside(&a.footprint(), 0.0) < 0.6 {
            continue;
        }
        // The covering box must be wider than the one under it.
        if a.footprint().area() <= foot.area() {
            continue;
        }
        let lower = |k: usize| {
            let c = &boxes[k];
            a.bottom() < c.bottom() - UNDER_BAND
                || (a.bottom() <= c.bottom() + UNDER_BAND && a.top() < c.top())
        };
        if best.is_none_or(lower) {
            best = Some(j);
        }
    }
    best
}

/// Covering boxes whose bottoms lie this close (metres) stand at one height for [`under`].
const UNDER_BAND: f64 = 0.02;

/// The low box (a mat, a towel, a rug: its top within `gap` of the floor; or a pallet: its
/// top within `reach` of the floor and more than `gap` below box `i`'s) a floor-level box `i` lies on: larger than it and under at
/// least half of its footprint; the largest such. Both bottoms were found at the floor (a low
/// parent's top is within noise of it, and a box over a pallet has its bottom hidden), so the
/// height order cannot tell which holds which; two boxes cannot both stand on the same floor.
fn lying_on(boxes: &[LiftedBox], i: usize, gap: f64, reach: f64) -> Option<usize> {
    let foot = boxes[i].footprint();
    let top = boxes[i].top();
    boxes
        .iter()
        .enumerate()
        .filter(|(j, a)| {
            *j != i
                && a.top() <= reach
                && (a.top() <= gap || a.top() < top - gap)
                && a.footprint().area() > foot.area()
                && foot.fraction_inside(&a.footprint(), 0.0) >= 0.5
        })
        .max_by(|(_, a), (_, c)| a.footprint().area().total_cmp(&c.footprint().area()))
        .map(|(j, _)| j)
}

/// Infers the support of every box. `gap` is the largest vertical gap in metres between a
/// child's bottom and its parent's top (or the floor) that still counts as contact.
pub fn infer_supports(boxes: &[LiftedBox], gap: f64) -> Vec<SupportGuess> {
    infer_supports_within(boxes, gap, gap)
}

/// [`infer_supports`] with a second chance: a box that neither stands on the floor nor meets a
/// top within `gap` rests on the box below it whose top is nearest its bottom, within `reach`
/// metres either way, when at least 30 % of its footprint lies over that box (noisy depth
/// scatters bottoms and tops by more than a contact gap); failing that (when `reach` exceeds
/// `gap`), inside the box its bottom lies within by the same 30 % (a lower tier of a rack).
/// What is left is unsupported when its bottom is above [`MOUNT_MIN_BOTTOM`] and on the ground
/// otherwise (nothing holds it and nothing hangs that low: its bottom was lifted wrongly).
pub fn infer_supports_within(boxes: &[LiftedBox], gap: f64, reach: f64) -> Vec<SupportGuess> {
    let mut order: Vec<usize> = (0..boxes.len()).collect();
    order.sort_by(|&a, &b| {
        boxes[a]
            .bottom()
            .total_cmp(&boxes[b].bottom())
            .then(boxes[a].id.cmp(&boxes[b].id))
    });
    let mut out = Vec::with_capacity(boxes.len());
    for &i in &order {
        let b = &boxes[i];
        let bottom = b.bottom();
        let foot = b.footprint();
        // (score, parent index, kind): smaller score wins.
        let mut best: Option<(f64, usize, SupportKind)> = None;
        for (j, a) in boxes.iter().enumerate() {
            // A parent starts clearly lower (2 cm): side-by-side objects do not hold each other.
            if j == i || a.bottom() >= bottom - 0.02 {
                continue;
            }
            let cover = foot.fraction_inside(&a.footprint(), 0.05);
            let top_gap = (bottom - a.top()).abs();
            let candidate = if top_gap <= gap && cover >= 0.5 {
                Some((top_gap, SupportKind::On))
            } else if bottom > a.bottom() + 1e-3
                && bottom < a.top() - gap
                && b.top() <= a.top() + gap
                && cover >= 0.6
            {
                // Inside: rank by how close the bottom is to the parent's inner floor.
                Some((gap + (bottom - a.bottom()), SupportKind::Inside))
            } else {
                None
            };
            if let Some((score, kind)) = candidate {
                if best.is_none_or(|(s, _, _)| score < s) {
                    best = Some((score, j, kind));
                }
            }
        }
        if best.is_none() && bottom > gap {
            for (j, a) in boxes.iter().enumerate() {
                if j == i || a.bottom() >= bottom - 0.02 {
                    continue;
                }
                let top_gap = (bottom - a.top()).abs();
                if top_gap <= reach
                    && foot.fraction_inside(&a.footprint(), 0.05) >= 0.3
                    && best.is_none_or(|(s, _, _)| top_gap < s)
                {
                    best = Some((top_gap, j, SupportKind::On));
                }
            }
        }
        if best.is_none() && bottom > gap && reach > gap {
            // Nor near any top: inside the box it sits within (a lower tier of a rack), by the
            // same looser footprint test, nearest its inner floor.
            for (j, a) in boxes.iter().enumerate() {
                if j == i || a.bottom() >= bottom - 0.02 {
                    continue;
                }
                let depth = bottom - a.bottom();
                if bottom < a.top() - gap
                    && b.top() <= a.top() + gap
                    && foot.fraction_inside(&a.footprint(), 0.05) >= 0.3
                    && best.is_none_or(|(s, _, _)| depth < s)
                {
                    best = Some((depth, j, SupportKind::Inside));
                }
            }
        }
        let guess = match best {
            _ if bottom <= gap && lying_on(boxes, i, gap, reach).is_some() => SupportGuess {
                id: b.id.clone(),
                parent: lying_on(boxes, i, gap, reach).map(|j| boxes[j].id.clone()),
                kind: SupportKind::On,
            },
            _ if bottom <= gap => match under(boxes, i) {
                Some(j) => SupportGuess {
                    id: b.id.clone(),
                    parent: Some(boxes[j].id.clone()),
                    kind: SupportKind::Under,
                },
                None => SupportGuess {
                    id: b.id.clone(),
                    parent: None,
                    kind: SupportKind::Ground,
                },
            },
            Some((_, j, kind)) => SupportGuess {
                id: b.id.clone(),
                parent: Some(boxes[j].id.clone()),
                kind,
            },
            // Nothing holds up a box this low and nothing hangs this low on a wall: a floor
            // object whose bottom was lifted wrongly.
            None if bottom <= MOUNT_MIN_BOTTOM => SupportGuess {
                id: b.id.clone(),
                parent: None,
                kind: SupportKind::Ground,
            },
            None => SupportGuess {
                id: b.id.clone(),
                parent: None,
                kind: SupportKind::Unsupported,
            },
        };
        out.push(guess);
    }
    out.sort_by(|a, b| a.id.cmp(&b.id));
    out
}

/// Boxes held by the floor (beside a container or lifted *under* it), or *on* another box,
/// instead: `tiers` holds each container's shelf and inner-floor heights as fractions of its
/// height, by id (boards spanning most of its footprint). A box whose footprint lies mostly
/// inside a container's moves onto the tier nearest its bottom among those at or above what
/// holds it now and below its top, when that tier is nearer its bottom than its holder, or
/// above its bottom (the board would cut through it). The boxes alone cannot see the boards,
/// the container's asset can: a box that fills a shelf bay reaches up to the board above it,
/// so a toy on that board is within the contact gap of both; a bottle on a bottom shelf whose
/// lip hides its foot is lifted down to the floor under the shelf.
pub fn prefer_tiers(
    boxes: &[LiftedBox],
    supports: &mut [SupportGuess],
    tiers: &BTreeMap<String, Vec<f64>>,
) {
    if tiers.is_empty() {
        return;
    }
    let by_id: BTreeMap<&str, &LiftedBox> = boxes.iter().map(|b| (b.id.as_str(), b)).collect();
    for guess in supports.iter_mut() {
        let Some(b) = by_id.get(guess.id.as_str()) else {
            continue;
        };
        let held_at = match (guess.kind, guess.parent.as_deref()) {
            (SupportKind::Ground | SupportKind::Under, _) => 0.0,
            (SupportKind::On, Some(p)) => match by_id.get(p) {
                Some(p) => p.top(),
                None => continue,
            },
            _ => continue,
        };
        let holder_gap = (b.bottom() - held_at).abs();
        let mut best: Option<(f64, &str)> = None;
        for (id, levels) in tiers {
            let Some(c) = by_id.get(id.as_str()).filter(|c| c.id != b.id) else {
                continue;
            };
            let on_it =
                guess.kind == SupportKind::On && guess.parent.as_deref() == Some(id.as_str());
            if on_it || b.footprint().fraction_inside(&c.footprint(), 0.05) < 0.6 {
                continue;
            }
            for f in levels {
                let t = c.bottom() + f * (c.top() - c.bottom());
                let gap = (b.bottom() - t).abs();
                let holds = t >= held_at - 1e-3 && t < b.top();
                if holds
                    && (gap < holder_gap || t > b.bottom())
                    && best.is_none_or(|(g, _)| gap < g)
                {
                    best = Some((gap, id.as_str()));
                }
            }
        }
        if let Some((_, id)) = best {
            guess.parent = Some(id.to_owned());
            guess.kind = SupportKind::Inside;
        }
    }
}

/// The wall-mounting thresholds, whose one home is the scene graph's [`hangs_on_wall`] rule.
pub use scenethesis_scene_graph::{MOUNT_MIN_BOTTOM, MOUNT_WALL_REACH};

/// How far (metres) the corner of `footprint` nearest `wall`'s inner face lies in front of it
/// (negative: behind it, inside the wall).
pub fn wall_offset(wall: &Wall, footprint: &FloorRectangle) -> f64 {
    let n = wall.inward_normal();
    let face = wall.start + n * (wall.thickness / 2.0);
    footprint
        .corners()
        .iter()
        .map(|p| (p - face).dot(&n))
        .fold(f64::MAX, f64::min)
}

/// Turns every [`SupportKind::Unsupported`] guess whose box backs onto one of `walls` (the
/// box overlapping the wall along its length) and hangs on it by [`hangs_on_wall`] (the bottom
/// above [`MOUNT_MIN_BOTTOM`], the footprint corner nearest the wall within
/// [`MOUNT_WALL_REACH`] of its inner face) into
/// [`SupportKind::Mounted`] with that wall as parent (the nearest wall when several qualify).
/// Other guesses are left as they are.
pub fn mount_on_walls(guesses: &mut [SupportGuess], boxes: &[LiftedBox], walls: &[Wall]) {
    for guess in guesses
        .iter_mut()
        .filter(|g| g.kind == SupportKind::Unsupported)
    {
        let Some(b) = boxes.iter().find(|b| b.id == guess.id) else {
            continue;
        };
        let corners = b.footprint().corners();
        let mut best: Option<(f64, &Wall)> = None;
        for wall in walls.iter().filter(|w| w.length() > 0.0) {
            let d = wall.direction();
            let along = |p: &nalgebra::Point2<f64>| (p - wall.start).dot(&d);
            let nearest = wall_offset(wall, &b.footprint());
            let (lo, hi) = corners
                .iter()
                .map(along)
                .fold((f64::MAX, f64::MIN), |(lo, hi), a| (lo.min(a), hi.max(a)));
            let overlaps = hi > 0.0 && lo < wall.length();
            if overlaps
                && hangs_on_wall(b.bottom(), nearest)
                && best.is_none_or(|(e, _)| nearest.abs() < e)
            {
                best = Some((nearest.abs(), wall));
            }
        }
        if let Some((_, wall)) = best {
            guess.kind = SupportKind::Mounted;
            guess.parent = Some(wall.id.clone());
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::Architecture;

    /// The support kind and parent inferred for `id`.
    fn of(supports: &[SupportGuess], id: &str) -> (SupportKind, Option<String>) {
        let g = supports.iter().find(|g| g.id == id).unwrap();
        (g.kind, g.parent.clone())
    }

    #[test]
    fn a_high_box_against_a_wall_hangs_on_it_and_others_do_not() {
        // 6 × 4 m room: the back wall `wall_0` has its inner face at z = −2.
        let room = Architecture::rectangular_room(6.0, 4.0, 2.8, 0.9);
        let boxes = vec![
            // A painting 1.3–1.9 m up, its back 1 cm off the back wall.
            LiftedBox::axis_aligned("painting", [0.5, 1.6, -1.97], [0.4, 0.3, 0.02]),
            // The same 1 m out into the room: floating, a lifting error.
            LiftedBox::axis_aligned("ghost", [0.5, 1.6, -0.97], [0.4, 0.3, 0.02]),
            // Against the wall but only 10 cm up: not mounted, a floor object lifted wrongly.
            LiftedBox::axis_aligned("low", [-1.5, 0.3, -1.9], [0.3, 0.2, 0.1]),
            // On the floor against the wall: stands on the ground.
            LiftedBox::axis_aligned("cabinet", [2.0, 0.5, -1.8], [0.4, 0.5, 0.2]),
        ];
        let mut guesses = infer_supports(&boxes, 0.06);
        mount_on_walls(&mut guesses, &boxes, &room.walls);
        let kind = |id: &str| {
            let g = guesses.iter().find(|g| g.id == id).unwrap();
            (g.kind, g.parent.clone())
        };
        assert_eq!(
            kind("painting"),
            (SupportKind::Mounted, Some("wall_0".into()))
        );
        assert_eq!(kind("ghost"), (SupportKind::Unsupported, None));
        assert_eq!(kind("low"), (SupportKind::Ground, None));
        assert_eq!(kind("cabinet"), (SupportKind::Ground, None));
    }

    #[test]
    fn a_bottom_noise_lifted_off_its_table_still_rests_on_it() {
        // Table top at 0.75; the vase's bottom came out 0.2 m above it.
        let boxes = [
            LiftedBox::axis_aligned("table", [0.0, 0.375, 0.0], [0.6, 0.375, 0.4]),
            LiftedBox::axis_aligned("vase", [0.1, 1.05, 0.0], [0.08, 0.1, 0.08]),
            LiftedBox::axis_aligned("painting", [0.0, 1.6, -0.38], [0.4, 0.3, 0.02]),
        ];
        let strict = infer_supports(&boxes, 0.06);
        let vase = strict.iter().find(|s| s.id == "vase").unwrap();
        assert_eq!(vase.kind, SupportKind::Unsupported);
        let reaching = infer_supports_within(&boxes, 0.06, 0.3);
        let vase = reaching.iter().find(|s| s.id == "vase").unwrap();
        assert_eq!(
            (vase.kind, vase.parent.as_deref()),
            (SupportKind::On, Some("table"))
        );
        // A painting 0.55 m above the table stays mounted.
        let painting = reaching.iter().find(|s| s.id == "painting").unwrap();
        assert_eq!(painting.kind, SupportKind::Unsupported);
    }

    #[test]
    fn a_can_under_a_workbench_is_under_it_not_under_the_toolbox_on_it() {
        let boxes = [
            // A workbench with a pegboard: 0–1.8 m, its top board at 0.9 m.
            LiftedBox::axis_aligned("workbench", [0.0, 0.9, 0.0], [0.8, 0.9, 0.3]),
            // A toolbox on the board, over the can; its top (1.1 m) below the pegboard's.
            LiftedBox::axis_aligned("toolbox", [0.1, 1.0, 0.0], [0.25, 0.1, 0.15]),
            LiftedBox::axis_aligned("paint_can", [0.1, 0.09, 0.0], [0.06, 0.09, 0.06]),
        ];
        let s = infer_supports(&boxes, 0.06);
        assert_eq!(
            of(&s, "paint_can"),
            (SupportKind::Under, Some("workbench".into()))
        );
    }

    #[test]
    fn objects_at_the_floor_over_a_towel_lie_on_it() {
        let boxes = [
            LiftedBox::axis_aligned("towel", [0.0, 0.005, 0.0], [0.9, 0.005, 0.5]),
            LiftedBox::axis_aligned("ball", [0.3, 0.11, 0.1], [0.1, 0.1, 0.1]),
            LiftedBox::axis_aligned("keys", [-0.2, 0.015, 0.0], [0.04, 0.005, 0.03]),
            // Mostly off the towel: on the floor.
            LiftedBox::axis_aligned("bag", [0.95, 0.2, 0.0], [0.2, 0.2, 0.15]),
        ];
        let s = infer_supports(&boxes, 0.06);
        assert_eq!(of(&s, "ball"), (SupportKind::On, Some("towel".into())));
        assert_eq!(of(&s, "keys"), (SupportKind::On, Some("towel".into())));
        assert_eq!(of(&s, "bag"), (SupportKind::Ground, None));
        assert_eq!(of(&s, "towel"), (SupportKind::Ground, None));
    }

    #[test]
    fn a_crate_found_at_the_floor_over_a_pallet_rests_on_it() {
        let boxes = [
            LiftedBox::axis_aligned("pallet", [0.0, 0.07, 0.0], [0.6, 0.07, 0.5]),
            // Its bottom hidden behind the pallet, the crate came out standing on the floor.
            LiftedBox::axis_aligned("crate", [0.1, 0.2, 0.0], [0.3, 0.2, 0.2]),
            // A low stool beside the pallet stays on the floor.
            LiftedBox::axis_aligned("stool", [1.2, 0.2, 0.0], [0.2, 0.2, 0.2]),
        ];
        let s = infer_supports_within(&boxes, 0.06, 0.3);
        assert_eq!(of(&s, "crate"), (SupportKind::On, Some("pallet".into())));
        assert_eq!(of(&s, "stool"), (SupportKind::Ground, None));
        assert_eq!(of(&s, "pallet"), (SupportKind::Ground, None));
    }

    #[test]
    fn a_box_within_a_rack_a_noisy_footprint_half_out_sits_inside_it() {
        let boxes = [
            LiftedBox::axis_aligned("rack", [0.0, 0.4, 0.0], [0.8, 0.4, 0.25]),
            // A dumbbell on the lower tier, 15 cm up, its footprint 60 % in front of the rack.
            LiftedBox::axis_aligned("dumbbell", [0.0, 0.23, 0.3], [0.15, 0.08, 0.125]),
        ];
        let s = infer_supports_within(&boxes, 0.06, 0.3);
        let dumbbell = s.iter().find(|g| g.id == "dumbbell").unwrap();
        assert_eq!(
            (dumbbell.kind, dumbbell.parent.as_deref()),
            (SupportKind::Inside, Some("rack"))
        );
        // The strict rule alone (60 % inside) finds nothing holding it.
        let strict = infer_supports(&boxes, 0.06);
        let dumbbell = strict.iter().find(|g| g.id == "dumbbell").unwrap();
        assert_ne!(dumbbell.kind, SupportKind::Inside);
    }
}
