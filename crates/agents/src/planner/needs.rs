//! Phase 2b, needs: what serves what. A plan holding a subject of a `needs` rule
//! (`knowledge/arrangement.toml`: dining chairs, a monitor, a projector) that no target
//! serves gets the rule's first target and its subjects drawn up to it, or loses the
//! subjects the prompt did not ask for when it rules every target out.

use std::collections::BTreeSet;

use scenethesis_scene_graph::RelationKind;

use crate::arrangement::{ArrangementRules, NeedsRule};
use crate::knowledge::{Mount, NominalShape};
use crate::plan::Zone;

use super::{DraftPlace, Drafting, KnowledgePlanner};

/// Completes the plan's `needs` rules (`knowledge/arrangement.toml`): subjects that no target
/// serves are drawn up to one (dining chairs around a table, a monitor onto a desk; seats
/// facing a television's stand), the rule's first target added when the plan lacks it, and
/// left out when the prompt rules every target out ("a classroom without desks" has no
/// teacher's chair). Each change is noted in the plan.
pub(super) fn complete_needs(
    planner: &KnowledgePlanner,
    available: &BTreeSet<String>,
    excluded: &BTreeSet<String>,
    out: &mut Drafting,
) {
    for rule in &ArrangementRules::builtin().needs {
        if !rule.applies(out.drafts.iter().map(|d| d.category.as_str())) {
            continue;
        }
        let unserved = unserved(rule, out);
        let Some(&first) = unserved.first() else {
            continue;
        };
        let subject = out.drafts[first].category.clone();
        // The rule's first target may be added; the others serve only when planned already.
        let allowed = rule.target.iter().enumerate().find(|(i, c)| {
            available.contains(*c)
                && !excluded.contains(*c)
                && (*i == 0 || out.by_category.contains_key(*c))
        });
        let allowed = allowed.map(|(_, c)| c);
        let Some(target) = allowed else {
            // What the prompt itself names stays, served or not.
            let named: BTreeSet<usize> = out.mention_drafts.iter().flatten().copied().collect();
            let gone: Vec<usize> = unserved
                .into_iter()
                .filter(|d| !named.contains(d))
                .collect();
            if !gone.is_empty() {
                out.notes.push(format!(
                    "left out {} {subject}: {} (the prompt rules out {})",
                    gone.len(),
                    rule.rule,
                    rule.target.join(", ")
                ));
                out.remove(&gone);
            }
            continue;
        };
        let existing = out.by_category.get(target).and_then(|v| {
            v.iter()
                .copied()
                .find(|&d| !matches!(out.drafts[d].place, DraftPlace::Support(..)))
        });
        let t = match existing {
            Some(t) => t,
            None => {
                let zone = match planner.knowledge.prior(target).map(|p| p.mount) {
                    Some(Mount::Wall) => Zone::WallMounted,
                    _ => Zone::Free,
                };
                let Some(t) = out.add(target, DraftPlace::Zone(zone), false, false) else {
                    continue;
                };
                out.notes.push(format!(
                    "added a {target}: {} (the plan held {subject} but none it serves)",
                    rule.rule
                ));
                t
            }
        };
        draw_up(planner, &unserved, t, out);
    }
}

/// The subjects of `rule` no target serves: floor ones not placed relative to a target,
/// carried ones with no target under them when the rule asks for one (`within` 0), or with
/// no target in the plan at all.
fn unserved(rule: &NeedsRule, out: &Drafting) -> Vec<usize> {
    let is_target = |d: usize| rule.target.contains(&out.drafts[d].category);
    let any_target = (0..out.drafts.len()).any(is_target);
    let carried_by_target = |mut d: usize| {
        while let DraftPlace::Support(_, p) = out.drafts[d].place {
            if is_target(p) {
                return true;
            }
            d = p;
        }
        false
    };
    rule.subject
        .iter()
        .filter_map(|c| out.by_category.get(c))
        .flatten()
        .copied()
        .filter(|&s| match out.drafts[s].place {
            DraftPlace::Relative(_, t) | DraftPlace::Opposite(t) => !is_target(t),
            DraftPlace::Support(..) if rule.within <= 0.0 => !carried_by_target(s),
            DraftPlace::Support(..) => !any_target,
            DraftPlace::Anchor => false,
            DraftPlace::Zone(_) => true,
        })
        .collect()
}

/// Puts the `subjects` of a `needs` rule by their target draft `t`: carried ones on it when
/// it has a top, else the target facing the floor object carrying the first; floor ones
/// around a table (several) or in front of it (one), beside a bed.
fn draw_up(planner: &KnowledgePlanner, subjects: &[usize], t: usize, out: &mut Drafting) {
    let target_shape = planner
        .knowledge
        .prior(&out.drafts[t].category)
        .map(|p| p.shape);
    let has_top = matches!(
        target_shape,
        Some(NominalShape::Table | NominalShape::Cabinet | NominalShape::Solid)
    );
    let (carried, floor): (Vec<usize>, Vec<usize>) = subjects
        .iter()
        .partition(|&&s| matches!(out.drafts[s].place, DraftPlace::Support(..)));
    if let Some(&s) = carried.first() {
        if has_top {
            for &s in &carried {
                out.drafts[s].place = DraftPlace::Support(RelationKind::On, t);
            }
        } else if !matches!(out.drafts[t].place, DraftPlace::Anchor)
            && planner
                .knowledge
                .prior(&out.drafts[t].category)
                .map(|p| p.mount)
                == Some(Mount::Floor)
        {
            let mut root = s;
            while let DraftPlace::Support(_, p) = out.drafts[root].place {
                root = p;
            }
            out.drafts[t].place = DraftPlace::Relative(RelationKind::Facing, root);
        }
    }
    let kind = match target_shape {
        Some(NominalShape::Bed) => RelationKind::Beside,
        Some(NominalShape::Table) if floor.len() > 1 => RelationKind::Around,
        _ => RelationKind::InFrontOf,
    };
    for s in floor {
        out.drafts[s].place = DraftPlace::Relative(kind, t);
    }
}
