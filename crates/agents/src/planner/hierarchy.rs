//! Phase 4, hierarchy: the anchor, the support tree (no loops), stable ids, depth layers, and
//! the planned objects with their relations and hard constraints.

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_scene_graph::{Environment, ParentRef, Relation, RelationKind};

use crate::knowledge::{AnchorPlace, Mount};
use crate::plan::{
    ConstraintTarget, Layer, PlanConstraint, PlanError, PlanRequest, PlannedObject, Zone, BACK_WALL,
};

use super::interpret::Reading;
use super::room::footprint;
use super::{Draft, DraftPlace, KnowledgePlanner};

/// The plan's object tree.
#[derive(Debug, Clone)]
pub(super) struct Tree {
    /// The anchor's id.
    pub anchor: String,
    /// Ground objects first (anchor first), then supported ones, parents before children.
    pub objects: Vec<PlannedObject>,
    /// The stated relations, by object id.
    pub constraints: Vec<PlanConstraint>,
    /// Each draft's id, by draft index.
    pub ids: Vec<String>,
}

/// Chooses the anchor, breaks relation and support loops, orders and names the drafts and
/// turns them into planned objects.
pub(super) fn build(
    planner: &KnowledgePlanner,
    reading: &Reading,
    request: &PlanRequest,
    mut drafts: Vec<Draft>,
) -> Result<Tree, PlanError> {
    let primary = &reading.archetypes[0];
    // The anchor.
    let anchor = choose_anchor(planner, &drafts).ok_or_else(|| PlanError::NothingAvailable {
        prompt: reading.prompt.clone(),
        available: request.available_categories.len(),
    })?;
    if drafts[anchor].place != DraftPlace::Anchor {
        drafts[anchor].place = DraftPlace::Anchor;
    }
    // A relative place must not point at itself or form loops: fall back to free.
    for d in 0..drafts.len() {
        if let DraftPlace::Relative(_, t) | DraftPlace::Opposite(t) = drafts[d].place {
            if t == d || matches!(drafts[t].place, DraftPlace::Support(..)) {
                drafts[d].place = DraftPlace::Zone(Zone::Free);
            }
        }
    }
    break_support_cycles(&mut drafts);

    // Order: anchor, other ground objects, then supported objects by depth.
    let order = ground_first(&drafts, anchor);
    let mut ids = vec![String::new(); drafts.len()];
    let mut counters: BTreeMap<&str, usize> = BTreeMap::new();
    for &d in &order {
        let n = counters.entry(drafts[d].category.as_str()).or_default();
        ids[d] = format!("{}_{}", drafts[d].category, n);
        *n += 1;
    }

    let indoor = primary.environment == Environment::Indoor;
    let mut objects: Vec<PlannedObject> = Vec::with_capacity(drafts.len());
    let mut layers: BTreeMap<usize, Layer> = BTreeMap::new();
    let mut constraints = Vec::new();
    for &d in &order {
        let draft = &drafts[d];
        let (zone, support, parent, mut relations) =
            placement(draft, primary.anchor_place, indoor, &ids);
        for (kind, t) in &draft.extra {
            let r = Relation::new(*kind, ids[*t].clone());
            if !relations.contains(&r) && *t != d {
                relations.push(r);
            }
        }
        let layer = layer_of(&draft.place, &zone, &layers, primary.anchor_place);
        layers.insert(d, layer);
        constraints.extend(stated_constraints(draft, &ids[d], &ids));
        objects.push(PlannedObject {
            id: ids[d].clone(),
            category: draft.category.clone(),
            layer,
            support,
            parent,
            zone,
            relations,
            hard: draft.hard,
            attributes: Vec::new(),
        });
    }
    Ok(Tree {
        anchor: ids[anchor].clone(),
        objects,
        constraints,
        ids,
    })
}

/// The anchor: the draft placed as one, else the largest floor object standing in a zone or
/// next to another.
fn choose_anchor(planner: &KnowledgePlanner, drafts: &[Draft]) -> Option<usize> {
    let knowledge = &planner.knowledge;
    drafts
        .iter()
        .position(|d| d.place == DraftPlace::Anchor)
        .or_else(|| {
            // The largest floor object.
            drafts
                .iter()
                .enumerate()
                .filter(|(_, d)| matches!(d.place, DraftPlace::Zone(_) | DraftPlace::Relative(..)))
                .filter(|(_, d)| {
                    knowledge
                        .prior(&d.category)
                        .is_some_and(|p| p.mount == Mount::Floor)
                })
                .max_by(|a, b| {
                    footprint(knowledge, &a.1.category)
                        .total_cmp(&footprint(knowledge, &b.1.category))
                        .then(b.0.cmp(&a.0))
                })
                .map(|(i, _)| i)
        })
}

/// The drafts in plan order: the anchor, other ground objects, then supported objects by
/// depth (ties in drafting order).
fn ground_first(drafts: &[Draft], anchor: usize) -> Vec<usize> {
    let depth = |mut d: usize| {
        let mut n = 0;
        while let DraftPlace::Support(_, p) = drafts[d].place {
            d = p;
            n += 1;
            if n > drafts.len() {
                break;
            }
        }
        n
    };
    let mut order: Vec<usize> = (0..drafts.len()).collect();
    order.sort_by_key(|&d| (d != anchor, depth(d), d));
    order
}

/// A draft's zone, support, parent and relations, from its place (`ids`: every draft's id).
fn placement(
    draft: &Draft,
    anchor_place: AnchorPlace,
    indoor: bool,
    ids: &[String],
) -> (Zone, RelationKind, ParentRef, Vec<Relation>) {
    match &draft.place {
        DraftPlace::Anchor => {
            let wall = draft.wall.clone().or_else(|| {
                (anchor_place == AnchorPlace::Wall && indoor).then(|| BACK_WALL.to_owned())
            });
            match wall {
                Some(w) if indoor => (
                    Zone::Wall {
                        wall: Some(w.clone()),
                    },
                    RelationKind::AgainstWall,
                    ParentRef::Ground,
                    vec![Relation::new(RelationKind::AgainstWall, w)],
                ),
                _ => (
                    Zone::Center,
                    RelationKind::OnFloor,
                    ParentRef::Ground,
                    vec![],
                ),
            }
        }
        DraftPlace::Zone(zone) => {
            let against =
                indoor && matches!(zone, Zone::Wall { .. } | Zone::Corner | Zone::WallMounted);
            let mut rel = vec![];
            if let (true, Zone::Wall { wall: Some(w) }) = (indoor, zone) {
                rel.push(Relation::new(RelationKind::AgainstWall, w.clone()));
            }
            let zone = if indoor || !matches!(zone, Zone::WallMounted) {
                zone.clone()
            } else {
                Zone::Free
            };
            (
                zone,
                if against {
                    RelationKind::AgainstWall
                } else {
                    RelationKind::OnFloor
                },
                ParentRef::Ground,
                rel,
            )
        }
        DraftPlace::Relative(kind, t) => {
            let mut rel = vec![Relation::new(*kind, ids[*t].clone())];
            if *kind == RelationKind::Around {
                rel.push(Relation::new(RelationKind::Facing, ids[*t].clone()));
            }
            (
                Zone::Relative,
                RelationKind::OnFloor,
                ParentRef::Ground,
                rel,
            )
        }
        DraftPlace::Opposite(t) => {
            let support = if indoor {
                RelationKind::AgainstWall
            } else {
                RelationKind::OnFloor
            };
            (
                Zone::Wall { wall: None },
                support,
                ParentRef::Ground,
                vec![Relation::new(RelationKind::Facing, ids[*t].clone())],
            )
        }
        DraftPlace::Support(kind, p) => (
            Zone::Supported,
            *kind,
            ParentRef::Object(ids[*p].clone()),
            vec![],
        ),
    }
}

/// The depth layer of a draft at `place` in `zone` (`layers`: those of the drafts before it).
fn layer_of(
    place: &DraftPlace,
    zone: &Zone,
    layers: &BTreeMap<usize, Layer>,
    anchor_place: AnchorPlace,
) -> Layer {
    match (place, zone) {
        (DraftPlace::Anchor, _) => Layer::Middle,
        // Small things on the anchor group come forward; on storage they stay back.
        (DraftPlace::Support(_, p), _) => match layers.get(p).copied().unwrap_or(Layer::Middle) {
            Layer::Background => Layer::Background,
            _ => Layer::Foreground,
        },
        (_, Zone::Center) if !matches!(anchor_place, AnchorPlace::Center) => Layer::Foreground,
        (_, Zone::Wall { .. } | Zone::Corner | Zone::WallMounted) => Layer::Background,
        (DraftPlace::Relative(RelationKind::InFrontOf | RelationKind::Facing, _), _) => {
            Layer::Foreground
        }
        (_, Zone::Free) => Layer::Foreground,
        _ => Layer::Middle,
    }
}

/// The hard constraints the prompt stated on `draft` (whose id is `subject`), with object
/// targets named by their ids.
fn stated_constraints<'a>(
    draft: &'a Draft,
    subject: &'a str,
    ids: &'a [String],
) -> impl Iterator<Item = PlanConstraint> + 'a {
    draft.constraints.iter().map(move |(kind, target, words)| {
        let (target, phrase) = match target {
            ConstraintTarget::Object(_) => {
                let (words, t) = words.rsplit_once('#').unwrap_or((words, "0"));
                let t: usize = t.parse().unwrap_or(0);
                (ConstraintTarget::Object(ids[t].clone()), words.to_owned())
            }
            other => (other.clone(), words.clone()),
        };
        PlanConstraint {
            subject: subject.to_owned(),
            kind: *kind,
            target,
            phrase,
        }
    })
}

/// Turns support loops ("A on B", "B on A") into floor placements.
fn break_support_cycles(drafts: &mut [Draft]) {
    for start in 0..drafts.len() {
        let mut seen = BTreeSet::new();
        let mut d = start;
        while let DraftPlace::Support(_, p) = drafts[d].place {
            if !seen.insert(d) {
                drafts[start].place = DraftPlace::Zone(Zone::Free);
                break;
            }
            d = p;
        }
    }
}
