//! The offline planner: archetype knowledge plus prompt reading, no model and no network.

use std::collections::{BTreeMap, BTreeSet};

use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::{Environment, ParentRef, Relation, RelationKind};

use crate::knowledge::{
    AnchorPlace, Archetype, Knowledge, Mount, NominalShape, ObjectGroup, Place,
};
use crate::plan::*;
use crate::prompt::{analyze, Analysis, StatedTarget};

/// Plans scenes from the embedded (or a supplied) archetype knowledge, with no API key.
///
/// A prompt is matched to scene archetypes by their names and synonyms (whole phrases first,
/// then shared words); an unknown scene type blends the nearest archetypes, and every object
/// the prompt mentions joins the plan with its count. Spatial phrases of a detailed prompt
/// ("on", "inside", "under", "in front of", "facing", "beside", "left of", "against the back
/// wall", "in the corner") become hard constraints.
#[derive(Debug, Clone)]
pub struct KnowledgePlanner {
    knowledge: Knowledge,
}

impl Default for KnowledgePlanner {
    fn default() -> Self {
        Self::new()
    }
}

/// One object instance being drafted.
#[derive(Debug, Clone)]
struct Draft {
    category: String,
    place: DraftPlace,
    hard: bool,
    /// Extra relations: kind and target draft.
    extra: Vec<(RelationKind, usize)>,
    /// Relations to walls (kind against-wall) stated by the prompt.
    wall: Option<String>,
    /// Hard constraints: (kind, target, phrase).
    constraints: Vec<(RelationKind, ConstraintTarget, String)>,
}

#[derive(Debug, Clone, PartialEq)]
enum DraftPlace {
    Anchor,
    Zone(Zone),
    Relative(RelationKind, usize),
    Opposite(usize),
    Support(RelationKind, usize),
}

impl KnowledgePlanner {
    /// A planner over the embedded knowledge files.
    pub fn new() -> Self {
        Self {
            knowledge: Knowledge::builtin().clone(),
        }
    }

    /// A planner over caller-supplied knowledge.
    pub fn with_knowledge(knowledge: Knowledge) -> Self {
        Self { knowledge }
    }

    /// The planner's knowledge.
    pub fn knowledge(&self) -> &Knowledge {
        &self.knowledge
    }

    /// Every category the knowledge files name (the built-in library's categories).
    pub fn known_categories(&self) -> BTreeSet<String> {
        self.knowledge.category_names().map(str::to_owned).collect()
    }

    /// A category usable under `available`: itself, or the first available category of a
    /// generic noun's list that contains it.
    fn substitute(&self, category: &str, available: &BTreeSet<String>) -> Option<String> {
        if available.contains(category) {
            return Some(category.to_owned());
        }
        let shape = self.knowledge.prior(category).map(|p| p.shape);
        self.knowledge
            .vocabulary
            .generic
            .values()
            .filter(|list| list.iter().any(|c| c == category))
            .flatten()
            .find(|c| available.contains(*c) && self.knowledge.prior(c).map(|p| p.shape) == shape)
            .cloned()
    }

    fn choose_archetypes(&self, analysis: &Analysis) -> Option<(Vec<usize>, bool)> {
        let knowledge = &self.knowledge;
        let scenes = &analysis.scenes;
        if let Some(best) = scenes.first() {
            let ties: Vec<usize> = scenes
                .iter()
                .take_while(|m| (m.score - best.score).abs() < 1e-9)
                .map(|m| m.archetype)
                .collect();
            // Two archetypes named equally strongly ("an alchemy workshop") blend.
            let rival = scenes
                .get(1)
                .is_some_and(|m| m.phrase && m.phrase_len == best.phrase_len);
            if best.phrase && ties.len() == 1 && !rival {
                return Some((vec![best.archetype], false));
            }
            let mut chosen: Vec<usize> = scenes.iter().take(2).map(|m| m.archetype).collect();
            chosen.dedup();
            return Some((chosen, true));
        }
        // No scene words: the archetypes holding most of the mentioned categories.
        let mentioned: BTreeSet<&str> = analysis
            .mentions
            .iter()
            .map(|m| m.category.as_str())
            .collect();
        if !mentioned.is_empty() {
            let mut ranked: Vec<(usize, usize)> = knowledge
                .archetypes
                .iter()
                .enumerate()
                .map(|(i, a)| {
                    let held = a
                        .objects
                        .iter()
                        .filter(|g| mentioned.contains(g.category.as_str()))
                        .map(|g| &g.category)
                        .collect::<BTreeSet<_>>()
                        .len();
                    // An archetype anchored on a mentioned object fits best.
                    let anchored = held > 0 && mentioned.contains(a.anchor.as_str());
                    (2 * held + usize::from(anchored), i)
                })
                .filter(|(n, _)| *n > 0)
                .collect();
            ranked.sort_by(|a, b| b.0.cmp(&a.0).then(a.1.cmp(&b.1)));
            if !ranked.is_empty() {
                return Some((ranked.iter().take(2).map(|r| r.1).collect(), true));
            }
        }
        if analysis.scene_words || !analysis.mentions.is_empty() {
            let default = knowledge
                .archetypes
                .iter()
                .position(|a| a.name == knowledge.vocabulary.default_archetype)?;
            return Some((vec![default], !analysis.mentions.is_empty()));
        }
        None
    }
}

impl Planner for KnowledgePlanner {
    fn name(&self) -> &str {
        "knowledge"
    }

    fn plan(&self, request: &PlanRequest) -> Result<Plan, PlanError> {
        let prompt = request.prompt.trim();
        let knowledge = &self.knowledge;
        let available = &request.available_categories;
        if !prompt.chars().any(char::is_alphanumeric) {
            return Err(PlanError::EmptyPrompt);
        }
        let analysis = analyze(prompt, knowledge, available);
        let (chosen, blended) =
            self.choose_archetypes(&analysis)
                .ok_or_else(|| PlanError::Unintelligible {
                    prompt: prompt.to_owned(),
                })?;
        let archetypes: Vec<&Archetype> =
            chosen.iter().map(|&i| &knowledge.archetypes[i]).collect();
        let primary = archetypes[0];
        let mut rng = ChaCha8Rng::seed_from_u64(request.seed ^ 0x5ce7_e515_9a11_0001);
        let mut notes = Vec::new();

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

        let mut drafts: Vec<Draft> = Vec::new();
        let mut by_category: BTreeMap<String, Vec<usize>> = BTreeMap::new();
        let mut mention_drafts: Vec<Vec<usize>> = vec![Vec::new(); analysis.mentions.len()];
        let mut group_consumed = vec![false; groups.len()];

        // Mentions take over the first archetype group of their category.
        let mut mention_group: Vec<Option<usize>> = vec![None; analysis.mentions.len()];
        let mut mention_category: Vec<Option<String>> = vec![None; analysis.mentions.len()];
        for (mi, m) in analysis.mentions.iter().enumerate() {
            match self.substitute(&m.category, available) {
                Some(c) => {
                    if c != m.category {
                        notes.push(format!(
                            "\"{}\": `{}` is not available, using `{c}`",
                            m.words, m.category
                        ));
                    }
                    let g = groups.iter().enumerate().position(|(gi, g)| {
                        g.category == c && !group_consumed[gi] && !mention_group.contains(&Some(gi))
                    });
                    mention_group[mi] = g;
                    mention_category[mi] = Some(c);
                }
                None => notes.push(format!(
                    "\"{}\": `{}` is not available and has no substitute; left out",
                    m.words, m.category
                )),
            }
        }

        let add = |drafts: &mut Vec<Draft>,
                   by_category: &mut BTreeMap<String, Vec<usize>>,
                   category: &str,
                   place: DraftPlace,
                   hard: bool| {
            let idx = drafts.len();
            drafts.push(Draft {
                category: category.to_owned(),
                place,
                hard,
                extra: Vec::new(),
                wall: None,
                constraints: Vec::new(),
            });
            by_category
                .entry(category.to_owned())
                .or_default()
                .push(idx);
            idx
        };

        // Walk the groups in order; a mention's objects appear where its group is (or at the
        // end, for categories the archetype lacks).
        let anchor_category = self.substitute(&primary.anchor, available);
        let stated_for = |mi: usize| analysis.stated.iter().filter(move |s| s.subject == mi);
        for (gi, group) in groups.iter().enumerate() {
            let Some(category) = self.substitute(&group.category, available) else {
                notes.push(format!("`{}` is not available; left out", group.category));
                continue;
            };
            if category != group.category
                && !notes
                    .iter()
                    .any(|n| n.starts_with(&format!("`{}`", group.category)))
            {
                notes.push(format!(
                    "`{}` is not available, using `{category}`",
                    group.category
                ));
            }
            let mention = mention_group.iter().position(|g| *g == Some(gi));
            let count_for = |rng: &mut ChaCha8Rng| rng.random_range(group.min..=group.max);
            let hard = mention.is_some_and(|mi| stated_for(mi).next().is_some());
            match &group.place {
                Place::Support(kind, target) => {
                    let parents: Vec<usize> = self
                        .substitute(target, available)
                        .and_then(|t| by_category.get(&t).cloned())
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
                            count_for(&mut rng).max(m.count) * parents.len() as u32
                        };
                        for k in 0..total as usize {
                            let d = add(
                                &mut drafts,
                                &mut by_category,
                                &category,
                                DraftPlace::Support(*kind, parents[k % parents.len()]),
                                false,
                            );
                            mention_drafts[mi].push(d);
                        }
                        group_consumed[gi] = true;
                        continue;
                    }
                    for &p in &parents {
                        for _ in 0..count_for(&mut rng) {
                            add(
                                &mut drafts,
                                &mut by_category,
                                &category,
                                DraftPlace::Support(*kind, p),
                                false,
                            );
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
                                count_for(&mut rng).max(m.count)
                            }
                        }
                        None => count_for(&mut rng),
                    };
                    let place = match place {
                        Place::Anchor
                            if Some(&category) == anchor_category.as_ref()
                                && !by_category.contains_key(&category) =>
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
                            match self
                                .substitute(t, available)
                                .and_then(|t| by_category.get(&t).cloned())
                            {
                                Some(targets) => {
                                    // Spread over the target's instances.
                                    for k in 0..count as usize {
                                        let d = add(
                                            &mut drafts,
                                            &mut by_category,
                                            &category,
                                            DraftPlace::Relative(*kind, targets[k % targets.len()]),
                                            hard,
                                        );
                                        if let Some(mi) = mention {
                                            mention_drafts[mi].push(d);
                                        }
                                    }
                                    group_consumed[gi] = true;
                                    continue;
                                }
                                None => DraftPlace::Zone(Zone::Free),
                            }
                        }
                        Place::Opposite(t) => match self
                            .substitute(t, available)
                            .and_then(|t| by_category.get(&t).and_then(|v| v.first().copied()))
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
                        let d = add(&mut drafts, &mut by_category, &category, p, hard);
                        if let Some(mi) = mention {
                            mention_drafts[mi].push(d);
                        }
                    }
                }
            }
            group_consumed[gi] = true;
        }

        // Mentions without an archetype group, or whose stated relations place them.
        for (mi, m) in analysis.mentions.iter().enumerate() {
            if !mention_drafts[mi].is_empty() {
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
                let d = add(
                    &mut drafts,
                    &mut by_category,
                    &category,
                    DraftPlace::Zone(Zone::Free),
                    false,
                );
                mention_drafts[mi].push(d);
            }
            if stated_for(mi).next().is_none() {
                // Default place by the category's kind.
                let mount = prior.map(|p| p.mount).unwrap_or_default();
                let shape = prior.map(|p| p.shape).unwrap_or(NominalShape::None);
                for &d in &mention_drafts[mi] {
                    drafts[d].place = match (mount, shape) {
                        (Mount::Surface, _) => {
                            let inside = prior.and_then(|p| p.rests)
                                == Some(crate::knowledge::ItemRest::Inside);
                            match self.default_parent(&drafts, inside) {
                                Some((kind, p)) => DraftPlace::Support(kind, p),
                                None => DraftPlace::Zone(Zone::Free),
                            }
                        }
                        (Mount::Wall, _) => DraftPlace::Zone(Zone::WallMounted),
                        (_, NominalShape::Shelves | NominalShape::Cabinet) => {
                            DraftPlace::Zone(Zone::Wall { wall: None })
                        }
                        (_, NominalShape::Seat) => {
                            match drafts.iter().position(|d| d.place == DraftPlace::Anchor) {
                                Some(a) if a != d => DraftPlace::Relative(RelationKind::Facing, a),
                                _ => DraftPlace::Zone(Zone::Free),
                            }
                        }
                        _ => DraftPlace::Zone(Zone::Free),
                    };
                }
            }
        }

        // Stated relations become hard constraints.
        let mut split_seen: BTreeMap<(usize, usize), usize> = BTreeMap::new();
        for s in &analysis.stated {
            let subjects = mention_drafts[s.subject].clone();
            for (k, &d) in subjects.iter().enumerate() {
                drafts[d].hard = true;
                let kind = s.phrase.kind;
                match &s.target {
                    StatedTarget::Corner => {
                        drafts[d].place = DraftPlace::Zone(Zone::Corner);
                        drafts[d].constraints.push((
                            RelationKind::AgainstWall,
                            ConstraintTarget::Corner,
                            s.words.clone(),
                        ));
                    }
                    StatedTarget::Wall(w) => {
                        let wall = (!w.is_empty()).then(|| w.clone());
                        if drafts[d].place != DraftPlace::Anchor {
                            drafts[d].place = DraftPlace::Zone(Zone::Wall { wall: wall.clone() });
                        }
                        drafts[d].wall = wall.clone();
                        let target = wall
                            .map(ConstraintTarget::Wall)
                            .unwrap_or(ConstraintTarget::AnyWall);
                        drafts[d].constraints.push((
                            RelationKind::AgainstWall,
                            target,
                            s.words.clone(),
                        ));
                    }
                    StatedTarget::Mention(t) => {
                        let targets = &mention_drafts[*t];
                        if targets.is_empty() {
                            continue;
                        }
                        let target = targets[k % targets.len()];
                        if target == d {
                            continue;
                        }
                        let target_is_anchor_like = drafts[target].place == DraftPlace::Anchor;
                        let _ = target_is_anchor_like;
                        match kind {
                            RelationKind::On | RelationKind::Inside | RelationKind::Under => {
                                let prior = knowledge.prior(&drafts[d].category);
                                let small = prior
                                    .filter(|p| {
                                        p.mount == Mount::Floor && kind != RelationKind::Under
                                    })
                                    .and_then(|p| p.small.clone())
                                    .filter(|c| available.contains(c));
                                if let Some(small) = small {
                                    if k == 0 {
                                        notes.push(format!("\"{}\" {} \"{}\": a `{}` does not fit there, using the smaller `{small}`", analysis.mentions[s.subject].words, s.words, analysis.mentions[*t].words, drafts[d].category));
                                    }
                                    drafts[d].category = small;
                                }
                                drafts[d].place = DraftPlace::Support(kind, target);
                            }
                            RelationKind::Facing => {
                                if matches!(drafts[d].place, DraftPlace::Relative(..)) {
                                    drafts[d].extra.push((kind, target));
                                } else if !matches!(
                                    drafts[d].place,
                                    DraftPlace::Anchor
                                        | DraftPlace::Zone(Zone::Wall { .. })
                                        | DraftPlace::Zone(Zone::Corner)
                                ) {
                                    drafts[d].place = DraftPlace::Relative(kind, target);
                                } else {
                                    drafts[d].extra.push((kind, target));
                                }
                            }
                            _ => {
                                let mut kind = kind;
                                if s.phrase.split {
                                    let n = split_seen.entry((s.subject, target)).or_default();
                                    drafts[d].extra.push((
                                        if *n % 2 == 0 {
                                            RelationKind::LeftOf
                                        } else {
                                            RelationKind::RightOf
                                        },
                                        target,
                                    ));
                                    *n += 1;
                                    kind = RelationKind::Beside;
                                }
                                if drafts[d].place != DraftPlace::Anchor {
                                    drafts[d].place = DraftPlace::Relative(kind, target);
                                } else {
                                    drafts[d].extra.push((kind, target));
                                }
                            }
                        }
                        drafts[d].constraints.push((
                            kind,
                            ConstraintTarget::Object(String::new()),
                            format!("{}#{target}", s.words),
                        ));
                    }
                }
            }
        }

        // The anchor.
        let anchor = drafts
            .iter()
            .position(|d| d.place == DraftPlace::Anchor)
            .or_else(|| {
                // The largest floor object.
                drafts
                    .iter()
                    .enumerate()
                    .filter(|(_, d)| {
                        matches!(d.place, DraftPlace::Zone(_) | DraftPlace::Relative(..))
                    })
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
            .ok_or_else(|| PlanError::NothingAvailable {
                prompt: prompt.to_owned(),
                available: available.len(),
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
        let mut ids = vec![String::new(); drafts.len()];
        let mut counters: BTreeMap<&str, usize> = BTreeMap::new();
        for &d in &order {
            let n = counters.entry(drafts[d].category.as_str()).or_default();
            ids[d] = format!("{}_{}", drafts[d].category, n);
            *n += 1;
        }

        let environment = primary.environment;
        let indoor = environment == Environment::Indoor;
        let mut objects: Vec<PlannedObject> = Vec::with_capacity(drafts.len());
        let mut layers: BTreeMap<usize, Layer> = BTreeMap::new();
        let mut constraints = Vec::new();
        for &d in &order {
            let draft = &drafts[d];
            let (zone, support, parent, mut relations) = match &draft.place {
                DraftPlace::Anchor => {
                    let wall = draft.wall.clone().or_else(|| {
                        (primary.anchor_place == AnchorPlace::Wall && indoor)
                            .then(|| BACK_WALL.to_owned())
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
                    let against = indoor
                        && matches!(zone, Zone::Wall { .. } | Zone::Corner | Zone::WallMounted);
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
            };
            for (kind, t) in &draft.extra {
                let r = Relation::new(*kind, ids[*t].clone());
                if !relations.contains(&r) && *t != d {
                    relations.push(r);
                }
            }
            let layer = match (&draft.place, &zone) {
                (DraftPlace::Anchor, _) => Layer::Middle,
                // Small things on the anchor group come forward; on storage they stay back.
                (DraftPlace::Support(_, p), _) => {
                    match layers.get(p).copied().unwrap_or(Layer::Middle) {
                        Layer::Background => Layer::Background,
                        _ => Layer::Foreground,
                    }
                }
                (_, Zone::Center) if !matches!(primary.anchor_place, AnchorPlace::Center) => {
                    Layer::Foreground
                }
                (_, Zone::Wall { .. } | Zone::Corner | Zone::WallMounted) => Layer::Background,
                (DraftPlace::Relative(RelationKind::InFrontOf | RelationKind::Facing, _), _) => {
                    Layer::Foreground
                }
                (_, Zone::Free) => Layer::Foreground,
                _ => Layer::Middle,
            };
            layers.insert(d, layer);
            for (kind, target, words) in &draft.constraints {
                let (target, phrase) = match target {
                    ConstraintTarget::Object(_) => {
                        let (words, t) = words.rsplit_once('#').unwrap_or((words, "0"));
                        let t: usize = t.parse().unwrap_or(0);
                        (ConstraintTarget::Object(ids[t].clone()), words.to_owned())
                    }
                    other => (other.clone(), words.clone()),
                };
                constraints.push(PlanConstraint {
                    subject: ids[d].clone(),
                    kind: *kind,
                    target,
                    phrase,
                });
            }
            objects.push(PlannedObject {
                id: ids[d].clone(),
                category: draft.category.clone(),
                layer,
                support,
                parent,
                zone,
                relations,
                hard: draft.hard,
            });
        }

        // Room size: the archetype's range, grown when the floor objects need more room.
        let size_range = archetypes.iter().fold(primary.size, |acc, a| {
            [
                acc[0].max(a.size[0]),
                acc[1].max(a.size[1]),
                acc[2].max(a.size[2]),
                acc[3].max(a.size[3]),
            ]
        });
        let mut x = rng.random_range(size_range[0]..=size_range[1]);
        let mut z = rng.random_range(size_range[2]..=size_range[3]);
        let need: f64 = objects
            .iter()
            .filter(|o| o.parent == ParentRef::Ground && o.zone != Zone::WallMounted)
            .map(|o| footprint(knowledge, &o.category) * 2.4)
            .sum::<f64>()
            + 5.0;
        if x * z < need {
            let grow = (need / (x * z)).sqrt().min(1.5);
            x *= grow;
            z *= grow;
        }
        let tallest = objects
            .iter()
            .filter_map(|o| knowledge.prior(&o.category))
            .map(|p| p.size[1])
            .filter(|h| *h < 4.0)
            .fold(0.0, f64::max);
        let wall_height = if tallest > 2.3 { 3.4 } else { 2.8 };
        let aisle = archetypes.iter().map(|a| a.aisle).fold(0.6, f64::max);
        let door_clearance = archetypes
            .iter()
            .map(|a| a.door_clearance)
            .fold(0.6, f64::max);

        let description = describe(&objects, &ids[anchor], knowledge);
        Ok(Plan {
            prompt: prompt.to_owned(),
            scene_type: if blended {
                "custom".into()
            } else {
                primary.name.clone()
            },
            archetypes: archetypes.iter().map(|a| a.name.clone()).collect(),
            environment,
            room_size: [round_cm(x), round_cm(z)],
            wall_height,
            aisle,
            door_clearance,
            anchor: ids[anchor].clone(),
            objects,
            constraints,
            description,
            notes,
        })
    }
}

impl KnowledgePlanner {
    /// A default support for a small item: the first planned floor object with a fitting shape.
    fn default_parent(&self, drafts: &[Draft], inside: bool) -> Option<(RelationKind, usize)> {
        let shape_of = |d: &Draft| self.knowledge.prior(&d.category).map(|p| p.shape);
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

fn footprint(knowledge: &Knowledge, category: &str) -> f64 {
    knowledge
        .prior(category)
        .map(|p| p.size[0] * p.size[2])
        .unwrap_or(0.25)
}

fn round_cm(v: f64) -> f64 {
    (v * 100.0).round() / 100.0
}

/// The up-sampled prompt: each layer in words.
fn describe(objects: &[PlannedObject], anchor: &str, knowledge: &Knowledge) -> String {
    let _ = knowledge;
    let mut parts = Vec::new();
    for (layer, title) in [
        (Layer::Background, "Background"),
        (Layer::Middle, "Middle ground"),
        (Layer::Foreground, "Foreground"),
    ] {
        let mut phrases: BTreeMap<String, usize> = BTreeMap::new();
        let mut order: Vec<String> = Vec::new();
        for o in objects.iter().filter(|o| o.layer == layer) {
            let how = if o.id == anchor {
                format!(
                    "{} (the anchor{})",
                    o.category,
                    if matches!(o.zone, Zone::Wall { .. }) {
                        ", against the back wall"
                    } else {
                        ", in the middle"
                    }
                )
            } else {
                match (&o.parent, o.support, o.relations.first()) {
                    (ParentRef::Object(p), kind, _) => {
                        format!("{} {} {}", o.category, kind, strip_index(p))
                    }
                    (_, _, Some(r)) if r.kind != RelationKind::AgainstWall => {
                        format!("{} {} {}", o.category, r.kind, strip_index(&r.target))
                    }
                    _ => match &o.zone {
                        Zone::Wall { .. } => format!("{} against a wall", o.category),
                        Zone::Corner => format!("{} in a corner", o.category),
                        Zone::WallMounted => format!("{} on a wall", o.category),
                        Zone::Rows => format!("{} in rows", o.category),
                        Zone::Center => format!("{} near the middle", o.category),
                        _ => format!("{} in the open", o.category),
                    },
                }
            };
            if !phrases.contains_key(&how) {
                order.push(how.clone());
            }
            *phrases.entry(how).or_default() += 1;
        }
        if order.is_empty() {
            continue;
        }
        let text: Vec<String> = order
            .iter()
            .map(|p| match phrases[p] {
                1 => p.replace('_', " "),
                n => format!("{n} × {}", p.replace('_', " ")),
            })
            .collect();
        parts.push(format!("{title}: {}.", text.join("; ")));
    }
    parts.join(" ")
}

fn strip_index(id: &str) -> String {
    match id.rsplit_once('_') {
        Some((head, tail)) if tail.chars().all(|c| c.is_ascii_digit()) => head.to_owned(),
        _ => id.to_owned(),
    }
}
