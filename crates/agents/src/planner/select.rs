//! Phase 2, select: which objects the scene holds, how many of each and roughly where — the
//! archetypes' object groups, merged with every object the prompt mentions.

use std::collections::BTreeSet;

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::RelationKind;

use crate::knowledge::{Mount, NominalShape, ObjectGroup, Place};
use crate::plan::Zone;

use super::interpret::Reading;
use super::{Draft, DraftPlace, Drafting, KnowledgePlanner};

/// Drafts the objects of the archetypes' groups and of the prompt's mentions, with counts and
/// default places (the prompt's stated relations are applied later, by `constrain`).
pub(super) fn select(
    planner: &KnowledgePlanner,
    reading: &Reading,
    available: &BTreeSet<String>,
    rng: &mut ChaCha8Rng,
) -> Drafting {
    let knowledge = &planner.knowledge;
    let analysis = &reading.analysis;
    let archetypes = &reading.archetypes;
    let primary = &archetypes[0];
    let mut out = Drafting {
        mention_drafts: vec![Vec::new(); analysis.mentions.len()],
        // Room for every object the prompt names before the archetypes' own.
        reserve: analysis.mentions.iter().map(|m| m.count as usize).sum(),
        ..Drafting::default()
    };

    // Groups: the primary archetype's, then the others' new categories.
    let mut groups: Vec<ObjectGroup> = primary.objects.clone();
    for other in &archetypes[1..] {
        let have: BTreeSet<String> = groups.iter().map(|g| g.category.clone()).collect();
        for g in &other.objects {
            if g.place == Place::Anchor || have.contains(&g.category) {
                continue;
            }
            let mut g = g.clone();
            g.max = g.max.min(g.min.max(1) + 1);
            groups.push(g);
        }
    }

    let mut group_consumed = vec![false; groups.len()];

    // Mentions take over the first archetype group of their category.
    let mut mention_group: Vec<Option<usize>> = vec![None; analysis.mentions.len()];
    let mut mention_category: Vec<Option<String>> = vec![None; analysis.mentions.len()];
    let mut excluded: BTreeSet<String> = BTreeSet::new();
    let mut totals: BTreeSet<String> = BTreeSet::new();
    for (mi, m) in analysis.mentions.iter().enumerate() {
        match planner.substitute(&m.category, available) {
            Some(c) => {
                if c != m.category {
                    out.notes.push(format!(
                        "\"{}\": `{}` is not available, using `{c}`",
                        m.words, m.category
                    ));
                }
                let g = groups.iter().enumerate().position(|(gi, g)| {
                    g.category == c && !group_consumed[gi] && !mention_group.contains(&Some(gi))
                });
                if m.count == 0 {
                    // "without chairs": no group of the category is planned.
                    excluded.insert(c.clone());
                } else if m.zone.is_none() {
                    mention_group[mi] = g;
                }
                if m.numbered && m.zone.is_none() {
                    // "three chairs" is the scene's total: no other group adds to it.
                    totals.insert(c.clone());
                }
                mention_category[mi] = Some(c);
            }
            None => out.notes.push(format!(
                "\"{}\": `{}` is not available and has no substitute; left out",
                m.words, m.category
            )),
        }
    }

    // Walk the groups in order; a mention's objects appear where its group is (or at the
    // end, for categories the archetype lacks).
    let anchor_category = planner.substitute(&primary.anchor, available);
    let stated_for = |mi: usize| analysis.stated.iter().filter(move |s| s.subject == mi);
    for (gi, group) in groups.iter().enumerate() {
        let Some(category) = planner.substitute(&group.category, available) else {
            out.notes
                .push(format!("`{}` is not available; left out", group.category));
            continue;
        };
        let mention = mention_group.iter().position(|g| *g == Some(gi));
        if excluded.contains(&category) || (mention.is_none() && totals.contains(&category)) {
            group_consumed[gi] = true;
            continue;
        }
        if category != group.category
            && !out
                .notes
                .iter()
                .any(|n| n.starts_with(&format!("`{}`", group.category)))
        {
            out.notes.push(format!(
                "`{}` is not available, using `{category}`",
                group.category
            ));
        }
        let count_for = |rng: &mut ChaCha8Rng| rng.random_range(group.min..=group.max);
        let hard = mention.is_some_and(|mi| stated_for(mi).next().is_some());
        match &group.place {
            Place::Support(kind, target) => {
                let parents: Vec<usize> = planner
                    .substitute(target, available)
                    .and_then(|t| out.by_category.get(&t).cloned())
                    .unwrap_or_default();
                if parents.is_empty() && mention.is_none() {
                    continue;
                }
                if let Some(mi) = mention {
                    if stated_for(mi).next().is_some() || parents.is_empty() {
                        continue; // placed from the prompt's own relations below
                    }
                    let m = &analysis.mentions[mi];
                    let total = if m.explicit_count {
                        m.count
                    } else {
                        count_for(rng).max(m.count) * parents.len() as u32
                    };
                    for k in 0..total as usize {
                        let place = DraftPlace::Support(*kind, parents[k % parents.len()]);
                        if let Some(d) = out.add(&category, place, false, true) {
                            out.mention_drafts[mi].push(d);
                        }
                    }
                    group_consumed[gi] = true;
                    continue;
                }
                if group.min == 0 {
                    // An optional extra is drawn once for the room, not once per parent: with
                    // four shelves a per-shelf draw would put it in almost every seed.
                    let count = count_for(rng) as usize;
                    let first = if parents.len() > 1 {
                        rng.random_range(0..parents.len())
                    } else {
                        0
                    };
                    for k in 0..count {
                        let p = parents[(first + k) % parents.len()];
                        out.add(&category, DraftPlace::Support(*kind, p), false, false);
                    }
                } else {
                    for &p in &parents {
                        for _ in 0..count_for(rng) {
                            out.add(&category, DraftPlace::Support(*kind, p), false, false);
                        }
                    }
                }
            }
            place => {
                let count = match mention {
                    Some(mi) => {
                        let m = &analysis.mentions[mi];
                        if m.explicit_count {
                            m.count
                        } else {
                            count_for(rng).max(m.count)
                        }
                    }
                    None => count_for(rng),
                };
                let place = match place {
                    Place::Anchor
                        if Some(&category) == anchor_category.as_ref()
                            && !out.by_category.contains_key(&category) =>
                    {
                        DraftPlace::Anchor
                    }
                    Place::Anchor => DraftPlace::Zone(Zone::Center),
                    Place::Wall => DraftPlace::Zone(Zone::Wall { wall: None }),
                    Place::Corner => DraftPlace::Zone(Zone::Corner),
                    Place::Center => DraftPlace::Zone(Zone::Center),
                    Place::Rows => DraftPlace::Zone(Zone::Rows),
                    Place::Free => DraftPlace::Zone(Zone::Free),
                    Place::WallMounted => DraftPlace::Zone(Zone::WallMounted),
                    Place::Relative(kind, t) | Place::Support(kind, t) => {
                        match planner
                            .substitute(t, available)
                            .and_then(|t| out.by_category.get(&t).cloned())
                        {
                            Some(targets) => {
                                // Spread over the target's instances.
                                for k in 0..count as usize {
                                    let place =
                                        DraftPlace::Relative(*kind, targets[k % targets.len()]);
                                    let d = out.add(&category, place, hard, mention.is_some());
                                    if let (Some(mi), Some(d)) = (mention, d) {
                                        out.mention_drafts[mi].push(d);
                                    }
                                }
                                group_consumed[gi] = true;
                                continue;
                            }
                            None => DraftPlace::Zone(Zone::Free),
                        }
                    }
                    Place::Opposite(t) => match planner
                        .substitute(t, available)
                        .and_then(|t| out.by_category.get(&t).and_then(|v| v.first().copied()))
                    {
                        Some(target) => DraftPlace::Opposite(target),
                        None => DraftPlace::Zone(Zone::Wall { wall: None }),
                    },
                };
                for k in 0..count {
                    let p = if k > 0 && place == DraftPlace::Anchor {
                        DraftPlace::Zone(Zone::Center)
                    } else {
                        place.clone()
                    };
                    let d = out.add(&category, p, hard, mention.is_some());
                    if let (Some(mi), Some(d)) = (mention, d) {
                        out.mention_drafts[mi].push(d);
                    }
                }
            }
        }
        group_consumed[gi] = true;
    }

    // Mentions without an archetype group, or whose stated relations place them.
    for (mi, m) in analysis.mentions.iter().enumerate() {
        if !out.mention_drafts[mi].is_empty() {
            continue;
        }
        let Some(category) = mention_category[mi].clone() else {
            continue;
        };
        let prior = knowledge.prior(&category);
        let count = if m.explicit_count {
            m.count
        } else if let Some(g) = mention_group[mi] {
            rng.random_range(groups[g].min.max(1)..=groups[g].max.max(1))
                .max(m.count)
        } else {
            m.count.max(3)
        };
        for _ in 0..count {
            if let Some(d) = out.add(&category, DraftPlace::Zone(Zone::Free), false, true) {
                out.mention_drafts[mi].push(d);
            }
        }
        if let (None, Some(zone)) = (stated_for(mi).next(), &m.zone) {
            // A stand-in's own place ("an island" stands free in the middle).
            for &d in &out.mention_drafts[mi] {
                out.drafts[d].place = DraftPlace::Zone(zone.clone());
            }
        } else if stated_for(mi).next().is_none() {
            // Default place by the category's kind.
            let mount = prior.map(|p| p.mount).unwrap_or_default();
            let shape = prior.map(|p| p.shape).unwrap_or(NominalShape::None);
            for &d in &out.mention_drafts[mi] {
                out.drafts[d].place = match (mount, shape) {
                    (Mount::Surface, _) => {
                        let inside =
                            prior.and_then(|p| p.rests) == Some(crate::knowledge::ItemRest::Inside);
                        match default_parent(planner, &out.drafts, inside) {
                            Some((kind, p)) => DraftPlace::Support(kind, p),
                            None => DraftPlace::Zone(Zone::Free),
                        }
                    }
                    (Mount::Wall, _) => DraftPlace::Zone(Zone::WallMounted),
                    (_, NominalShape::Shelves | NominalShape::Cabinet) => {
                        DraftPlace::Zone(Zone::Wall { wall: None })
                    }
                    (_, NominalShape::Seat) => {
                        match out
                            .drafts
                            .iter()
                            .position(|d| d.place == DraftPlace::Anchor)
                        {
                            Some(a) if a != d => DraftPlace::Relative(RelationKind::Facing, a),
                            _ => DraftPlace::Zone(Zone::Free),
                        }
                    }
                    _ => DraftPlace::Zone(Zone::Free),
                };
            }
        }
    }
    out.mention_category = mention_category;
    out
}

/// A default support for a small item: the first planned floor object with a fitting shape.
fn default_parent(
    planner: &KnowledgePlanner,
    drafts: &[Draft],
    inside: bool,
) -> Option<(RelationKind, usize)> {
    let shape_of = |d: &Draft| planner.knowledge.prior(&d.category).map(|p| p.shape);
    let floor = |d: &Draft| !matches!(d.place, DraftPlace::Support(..));
    if inside {
        if let Some(i) = drafts.iter().position(|d| {
            floor(d)
                && matches!(
                    shape_of(d),
                    Some(NominalShape::Shelves | NominalShape::Cabinet)
                )
        }) {
            return Some((RelationKind::Inside, i));
        }
    }
    drafts
        .iter()
        .position(|d| floor(d) && matches!(shape_of(d), Some(NominalShape::Table)))
        .or_else(|| {
            drafts.iter().position(|d| {
                floor(d)
                    && matches!(
                        shape_of(d),
                        Some(NominalShape::Solid | NominalShape::Cabinet | NominalShape::Bed)
                    )
            })
        })
        .map(|i| (RelationKind::On, i))
        .or_else(|| {
            drafts
                .iter()
                .position(|d| floor(d) && matches!(shape_of(d), Some(NominalShape::Shelves)))
                .map(|i| (RelationKind::Inside, i))
        })
}
