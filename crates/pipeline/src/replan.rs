//! The re-plan policy: what the pipeline does with the objects a judge blamed. A pure function
//! of the plan, the offenders and the round, so it can be tested without running a pipeline.

use std::collections::BTreeSet;

use scenethesis_agents::Plan;
use scenethesis_scene_graph::ParentRef;

use crate::report::ReplanAction;

/// Decides the re-plan after a rejected attempt of round `round` (0-based) out of
/// `max_replans` re-plans: which action, and which objects to drop.
///
/// The first re-plan moves the offenders (new asset variants, a new layout seed). From the
/// second re-plan on it drops them (never the anchor) with everything they hold. Objects the
/// prompt asked for (`hard`, or listed in the plan's `requested`) are never dropped: while
/// they are the only offenders they are moved again, and the final re-plan makes room for them
/// by dropping up to three optional floor objects instead (the last in plan order that hold
/// nothing the prompt asked for). With nothing to drop the action is [`ReplanAction::Move`].
pub fn replan_action(
    plan: &Plan,
    offenders: &[String],
    round: usize,
    max_replans: usize,
) -> (ReplanAction, Vec<String>) {
    let movable: Vec<String> = offenders
        .iter()
        .filter(|id| **id != plan.anchor)
        .cloned()
        .collect();
    let requested = |id: &String| {
        plan.object(id).is_some_and(|o| o.hard) || plan.requested.iter().any(|r| r.ids.contains(id))
    };
    let (asked_for, optional): (Vec<String>, Vec<String>) =
        movable.iter().cloned().partition(requested);
    let last_chance = round + 1 == max_replans;
    let to_drop: Vec<String> = if round == 0 || movable.is_empty() {
        Vec::new()
    } else if !optional.is_empty() {
        optional
    } else if last_chance && !asked_for.is_empty() {
        room_for_requested(plan, &requested)
    } else {
        Vec::new()
    };
    let action = if to_drop.is_empty() {
        ReplanAction::Move
    } else {
        ReplanAction::Drop
    };
    (action, to_drop)
}

/// Up to three optional floor objects to drop so that the objects the prompt asked for find
/// room: the last in plan order that are not the anchor, not asked for and hold nothing that
/// is.
fn room_for_requested(plan: &Plan, requested: &dyn Fn(&String) -> bool) -> Vec<String> {
    let holds_requested = |id: &str| {
        plan.objects
            .iter()
            .any(|o| o.parent.object_id() == Some(id) && requested(&o.id))
    };
    plan.objects
        .iter()
        .rev()
        .filter(|o| o.parent == ParentRef::Ground && o.id != plan.anchor)
        .filter(|o| !requested(&o.id) && !holds_requested(&o.id))
        .take(3)
        .map(|o| o.id.clone())
        .collect()
}

/// Removes `ids` and every object resting on them (recursively) from the plan, with the
/// relations and constraints that mention them; returns what was removed.
pub(crate) fn drop_objects(plan: &mut Plan, ids: &[String]) -> BTreeSet<String> {
    let mut gone: BTreeSet<String> = ids.iter().cloned().collect();
    loop {
        let more: Vec<String> = plan
            .objects
            .iter()
            .filter(|o| !gone.contains(&o.id))
            .filter(|o| matches!(&o.parent, ParentRef::Object(p) if gone.contains(p)))
            .map(|o| o.id.clone())
            .collect();
        if more.is_empty() {
            break;
        }
        gone.extend(more);
    }
    plan.objects.retain(|o| !gone.contains(&o.id));
    for object in &mut plan.objects {
        object.relations.retain(|r| !gone.contains(&r.target));
    }
    plan.constraints.retain(|c| {
        !gone.contains(&c.subject)
            && !matches!(&c.target, scenethesis_agents::ConstraintTarget::Object(t) if gone.contains(t))
    });
    gone
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_agents::{KnowledgePlanner, PlanRequest, Planner};

    fn plan() -> Plan {
        let categories = scenethesis_procedural::catalog::categories().map(|c| c.name.to_owned());
        KnowledgePlanner::new()
            .plan(&PlanRequest::new(
                "a bedroom with a desk and a lamp on the desk",
                categories,
                0,
            ))
            .unwrap()
    }

    fn ids(plan: &Plan, hard: bool) -> Vec<String> {
        plan.objects
            .iter()
            .filter(|o| o.hard == hard && o.id != plan.anchor)
            .map(|o| o.id.clone())
            .collect()
    }

    #[test]
    fn the_first_replan_only_moves() {
        let p = plan();
        let optional = ids(&p, false);
        assert_eq!(
            replan_action(&p, &optional, 0, 3),
            (ReplanAction::Move, Vec::new())
        );
    }

    #[test]
    fn later_replans_drop_optional_offenders_but_never_the_anchor() {
        let p = plan();
        let optional = ids(&p, false);
        let mut offenders = vec![p.anchor.clone()];
        offenders.extend(optional.iter().take(2).cloned());
        let (action, dropped) = replan_action(&p, &offenders, 1, 3);
        assert_eq!(action, ReplanAction::Drop);
        assert_eq!(dropped, optional[..2].to_vec());
        // Only the anchor at fault: nothing can be dropped, so it moves.
        assert_eq!(
            replan_action(&p, std::slice::from_ref(&p.anchor), 2, 3),
            (ReplanAction::Move, Vec::new())
        );
    }

    #[test]
    fn requested_objects_are_never_dropped_the_last_chance_makes_room() {
        let p = plan();
        let hard = ids(&p, true);
        assert!(!hard.is_empty(), "the prompt asks for a desk and a lamp");
        let optional = ids(&p, false);
        let mixed: Vec<String> = hard
            .iter()
            .chain(optional.iter().take(1))
            .cloned()
            .collect();
        // Others remain: only they go.
        assert_eq!(
            replan_action(&p, &mixed, 1, 3),
            (ReplanAction::Drop, optional[..1].to_vec())
        );
        // Only requested objects: moved until the last re-plan, which drops optional floor
        // objects to make room for them; never the requested objects themselves.
        assert_eq!(
            replan_action(&p, &hard, 1, 3),
            (ReplanAction::Move, Vec::new())
        );
        let (action, freed) = replan_action(&p, &hard, 2, 3);
        assert_eq!(action, ReplanAction::Drop);
        assert!(!freed.is_empty() && freed.len() <= 3, "{freed:?}");
        for id in &freed {
            let o = p.object(id).unwrap();
            assert!(
                !o.hard && o.parent == ParentRef::Ground && *id != p.anchor,
                "{id}"
            );
            assert!(!hard.contains(id));
            assert!(p
                .objects
                .iter()
                .all(|c| c.parent.object_id() != Some(id.as_str()) || !c.hard));
        }
    }

    #[test]
    fn dropping_removes_children_and_relations_to_them() {
        let mut p = plan();
        let parent = p
            .objects
            .iter()
            .find_map(|o| o.parent.object_id().map(str::to_owned))
            .expect("something rests on something");
        let children: Vec<String> = p
            .objects
            .iter()
            .filter(|o| o.parent.object_id() == Some(parent.as_str()))
            .map(|o| o.id.clone())
            .collect();
        let gone = drop_objects(&mut p, std::slice::from_ref(&parent));
        assert!(gone.contains(&parent));
        for child in &children {
            assert!(gone.contains(child), "{child} rested on {parent}");
            assert!(p.object(child).is_none());
        }
        for o in &p.objects {
            assert!(o.relations.iter().all(|r| !gone.contains(&r.target)));
        }
    }
}
