//! Placing the floor objects: the order they are tried in (anchor, relative, corner, wall,
//! centre, rows, free, mounted; each relative object right after its target) and the first
//! candidate spot of each that keeps the walkway open.

use std::collections::{BTreeMap, BTreeSet};

use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::AssetInfo;
use scenethesis_scene_graph::ParentRef;

use super::candidates::{candidates, free_candidates, mount_ok};
use super::room::Side;
use super::runs::{above_run_spots, PlacedRuns, ABOVE_RUN_BOTTOM};
use super::shared::positional_target;
use super::shared::Placed;
use super::walkway::FloorState;
use super::DroppedObject;
use crate::arrangement::ArrangementRules;
use crate::plan::{Plan, Zone};

/// The plan indices of the floor objects in the order they are placed.
pub(super) fn placement_order(plan: &Plan) -> Vec<usize> {
    let class = |i: usize| -> u8 {
        let o = &plan.objects[i];
        if o.id == plan.anchor {
            return 0;
        }
        match &o.zone {
            Zone::Relative => 1,
            Zone::Corner => 2,
            Zone::Wall { wall: Some(_) } => 3,
            Zone::Wall { wall: None } => 4,
            Zone::Center => 5,
            Zone::Rows => 6,
            Zone::Free => 7,
            Zone::WallMounted => 8,
            Zone::Supported => 9,
        }
    };
    let mut order: Vec<usize> = (0..plan.objects.len())
        .filter(|&i| plan.objects[i].parent == ParentRef::Ground)
        .collect();
    order.sort_by_key(|&i| (class(i), !plan.objects[i].hard, i));
    chain_dependents(plan, order)
}

/// Places the floor objects of `order` one by one at their first candidate that fits and
/// keeps the walkway open; returns the objects that found no spot.
pub(super) fn place_floor_objects(
    state: &mut FloorState<'_>,
    order: Vec<usize>,
    infos: &[AssetInfo],
    sides: &[Side],
    runs: Option<&PlacedRuns>,
    rng: &mut ChaCha8Rng,
) -> Vec<DroppedObject> {
    let plan = state.plan;
    let mut dropped: Vec<DroppedObject> = Vec::new();
    let mut attempted = vec![false; plan.objects.len()];
    let mut pending = order;
    while !pending.is_empty() {
        let mut next = Vec::new();
        let mut progress = false;
        for &i in &pending {
            let o = &plan.objects[i];
            // A relative object waits for its target (placed already when it is in a run).
            if let Some(target) = positional_target(o) {
                if let Some(t) = state.index_of(target) {
                    if !attempted[t]
                        && state.placed_of(t).is_none()
                        && plan.objects[t].parent == ParentRef::Ground
                    {
                        next.push(i);
                        continue;
                    }
                }
            }
            attempted[i] = true;
            progress = true;
            if let Some(reason) = target_left_out(state, i, &attempted) {
                dropped.push(DroppedObject {
                    id: o.id.clone(),
                    reason,
                });
                continue;
            }
            let mounted = o.zone == Zone::WallMounted;
            if mounted && hang_above_run(state, runs, i, &infos[i], sides, rng) {
                continue;
            }
            let candidates = candidates(state, o, &infos[i], sides, infos, rng);
            let (hx, hz) = (infos[i].size[0] as f64 / 2.0, infos[i].size[2] as f64 / 2.0);
            let mut accepted = None;
            let mut tried = 0;
            for c in candidates {
                let p = Placed {
                    front_access: c.wall.is_some()
                        || matches!(o.zone, Zone::Wall { .. } | Zone::Corner | Zone::WallMounted),
                    wall: c.wall.clone(),
                    mounted,
                    ..Placed::standing(i, c.fp, &infos[i])
                };
                if !mounted {
                    if !state.fits(&p, 0.02) {
                        continue;
                    }
                } else if !mount_ok(state, &p) {
                    continue;
                }
                tried += 1;
                if tried > 160 {
                    break;
                }
                if state.evaluate(Some(&p)).0 {
                    accepted = Some(p);
                    break;
                }
            }
            let _ = (hx, hz);
            match accepted {
                Some(p) => state.commit(p),
                None => dropped.push(DroppedObject {
                    id: o.id.clone(),
                    reason: if tried == 0 {
                        "no free spot for its footprint".into()
                    } else {
                        "every free spot would block the walkway, the door or another object's access".into()
                    },
                }),
            }
        }
        if !progress {
            // Targets that never get placed: place the waiting ones without them.
            for &i in &next {
                attempted[i] = true;
            }
            for &i in &next {
                let o = &plan.objects[i];
                let candidates = free_candidates(state, &infos[i], rng, None);
                let mut ok = false;
                for c in candidates.into_iter().take(200) {
                    let p = Placed::standing(i, c.fp, &infos[i]);
                    if !state.fits(&p, 0.02) {
                        continue;
                    }
                    if state.evaluate(Some(&p)).0 {
                        state.commit(p);
                        ok = true;
                        break;
                    }
                }
                if !ok {
                    dropped.push(DroppedObject {
                        id: o.id.clone(),
                        reason: "its target was not placed and no free spot remained".into(),
                    });
                }
            }
            break;
        }
        pending = next;
    }
    dropped
}

/// Why relative object `i` is left out: its target was tried and found no spot, and it
/// only serves such a target (a `needs` rule: a dining chair whose table found no room, with
/// no other table standing), unless the prompt asked for it. `None` when it is placed.
fn target_left_out(state: &FloorState<'_>, i: usize, attempted: &[bool]) -> Option<String> {
    let plan = state.plan;
    let o = &plan.objects[i];
    if o.hard {
        return None;
    }
    let t = state.index_of(positional_target(o)?)?;
    let target = &plan.objects[t];
    if !attempted[t] || state.placed_of(t).is_some() || target.parent != ParentRef::Ground {
        return None;
    }
    let rule = ArrangementRules::builtin()
        .needs
        .iter()
        .find(|r| r.subject.contains(&o.category) && r.target.contains(&target.category))?;
    let served = state
        .placed
        .iter()
        .any(|p| !p.mounted && rule.target.contains(&plan.objects[p.plan_index].category));
    (!served).then(|| {
        format!(
            "its target `{}` found no spot and nothing else it serves stands here ({})",
            target.id, rule.rule
        )
    })
}

/// Hangs wall-mounted object `i` above a run (a wall cabinet over the counters) at the first
/// spot no other mounted object takes; returns whether it was hung.
fn hang_above_run(
    state: &mut FloorState<'_>,
    runs: Option<&PlacedRuns>,
    i: usize,
    info: &AssetInfo,
    sides: &[Side],
    rng: &mut ChaCha8Rng,
) -> bool {
    let Some(runs) = runs else { return false };
    let size = info.size.map(f64::from);
    let spots = above_run_spots(
        state,
        runs,
        &state.plan.objects[i].category,
        size,
        sides,
        rng,
    );
    for (fp, wall) in spots {
        if state
            .placed
            .iter()
            .filter(|p| p.mounted)
            .any(|p| p.fp.overlaps(&fp, 0.05))
            || state.in_a_swing(&fp, ABOVE_RUN_BOTTOM)
        {
            continue;
        }
        // Reached from the free floor beside the run's end, not from its front.
        let p = Placed {
            wall: Some(wall),
            mounted: true,
            bottom: Some(ABOVE_RUN_BOTTOM),
            ..Placed::standing(i, fp, info)
        };
        if !state.in_a_hung_swing(&p)
            && !state.hangs_in_keep_clear(&p)
            && state.evaluate(Some(&p)).0
        {
            state.commit(p);
            return true;
        }
    }
    false
}

/// Reorders floor objects so each object placed relative to another comes right after its
/// target (depth first), dependents whose chain holds a prompt-requested (hard) object first.
/// Otherwise objects placed in between take the spots around a target before a requested
/// object that is waiting for it ("an armchair next to the floor lamp") gets its turn.
fn chain_dependents(plan: &Plan, order: Vec<usize>) -> Vec<usize> {
    let in_order: BTreeSet<usize> = order.iter().copied().collect();
    let index_of: BTreeMap<&str, usize> = plan
        .objects
        .iter()
        .enumerate()
        .map(|(i, o)| (o.id.as_str(), i))
        .collect();
    // Each object's target among the floor objects being ordered, by plan index.
    let target: Vec<Option<usize>> = (0..plan.objects.len())
        .map(|i| {
            positional_target(&plan.objects[i])
                .and_then(|t| index_of.get(t).copied())
                .filter(|t| in_order.contains(t) && *t != i)
        })
        .collect();
    let mut dependents: BTreeMap<usize, Vec<usize>> = BTreeMap::new();
    for &i in &order {
        if let Some(t) = target[i] {
            dependents.entry(t).or_default().push(i);
        }
    }
    fn holds_hard(
        plan: &Plan,
        dependents: &BTreeMap<usize, Vec<usize>>,
        i: usize,
        depth: usize,
    ) -> bool {
        plan.objects[i].hard
            || (depth < 16
                && dependents.get(&i).is_some_and(|d| {
                    d.iter()
                        .any(|&j| holds_hard(plan, dependents, j, depth + 1))
                }))
    }
    let hard: Vec<bool> = (0..plan.objects.len())
        .map(|i| holds_hard(plan, &dependents, i, 0))
        .collect();
    for list in dependents.values_mut() {
        // A stable sort keeps the class/hard/index order among equals.
        list.sort_by_key(|&j| !hard[j]);
    }
    let mut out = Vec::with_capacity(order.len());
    let mut emitted = vec![false; plan.objects.len()];
    fn emit(
        i: usize,
        dependents: &BTreeMap<usize, Vec<usize>>,
        emitted: &mut [bool],
        out: &mut Vec<usize>,
    ) {
        if emitted[i] {
            return;
        }
        emitted[i] = true;
        out.push(i);
        if let Some(list) = dependents.get(&i) {
            for &j in list {
                emit(j, dependents, emitted, out);
            }
        }
    }
    for &i in &order {
        // Roots first; a dependent is emitted with its target (cycles fall back to order).
        if target[i].is_none() {
            emit(i, &dependents, &mut emitted, &mut out);
        }
    }
    for &i in &order {
        emit(i, &dependents, &mut emitted, &mut out);
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{KnowledgePlanner, PlanRequest, Planner};

    fn plan(prompt: &str) -> Plan {
        let available: Vec<String> = scenethesis_procedural::catalog::categories()
            .map(|c| c.name.to_owned())
            .collect();
        KnowledgePlanner::new()
            .plan(&PlanRequest::new(prompt, available, 0))
            .unwrap_or_else(|e| panic!("{prompt}: {e}"))
    }

    #[test]
    fn anchor_first_each_floor_object_once_and_relative_ones_after_their_target() {
        for prompt in [
            "a cozy living room with reading materials",
            "a kitchen",
            "a garage",
        ] {
            let plan = plan(prompt);
            let order = placement_order(&plan);
            let floor: BTreeSet<usize> = (0..plan.objects.len())
                .filter(|&i| plan.objects[i].parent == ParentRef::Ground)
                .collect();
            assert_eq!(order.len(), floor.len(), "{prompt}: {order:?}");
            assert_eq!(order.iter().copied().collect::<BTreeSet<_>>(), floor);
            assert_eq!(plan.objects[order[0]].id, plan.anchor, "{prompt}");
            for (k, &i) in order.iter().enumerate() {
                let Some(t) = positional_target(&plan.objects[i]) else {
                    continue;
                };
                if let Some(pos) = order.iter().position(|&j| plan.objects[j].id == t) {
                    assert!(
                        pos < k,
                        "{prompt}: `{}` before its target `{t}`",
                        plan.objects[i].id
                    );
                }
            }
        }
    }
}
