//! Phase 2, select: which objects the scene holds, how many of each and roughly where — the
//! archetypes' object groups, merged with every object the prompt mentions.

use std::collections::BTreeSet;

use rand::Rng;
use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::RelationKind;

use crate::knowledge::{
    Archetype, CategoryPrior, Mount, NominalShape, ObjectGroup, Place, Sparsity,
};
use crate::plan::Zone;
use crate::prompt::Analysis;

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
    let analysis = &reading.analysis;
    let primary = &reading.archetypes[0];
    let mut out = Drafting {
        mention_drafts: vec![Vec::new(); analysis.mentions.len()],
        // Room for every object the prompt names before the archetypes' own.
        reserve: analysis.mentions.iter().map(|m| m.count as usize).sum(),
        ..Drafting::default()
    };
    let selector = Selector {
        planner,
        analysis,
        available,
        groups: merged_groups(&reading.archetypes, reading.modifier_blend),
        sparsity: reading.sparsity.as_ref().map(|(level, _)| *level),
        core: &primary.core,
    };
    let mentions = selector.assign_mentions(&mut out);
    selector.draft_groups(&mentions, &primary.anchor, &mut out, rng);
    selector.draft_other_mentions(&mentions, &mut out, rng);
    super::needs::complete_needs(planner, available, &mentions.excluded, &mut out);
    out.mention_category = mentions.category;
    out
}

/// Groups: the primary archetype's, then the others' new categories (at most one more than
/// their least). With `with_anchors` (a modifier names the other archetype: "an *alchemy*
/// workshop") the others' anchors come too, against a wall.
fn merged_groups(archetypes: &[Archetype], with_anchors: bool) -> Vec<ObjectGroup> {
    let mut groups: Vec<ObjectGroup> = archetypes[0].objects.clone();
    for other in &archetypes[1..] {
        let have: BTreeSet<String> = groups.iter().map(|g| g.category.clone()).collect();
        for g in &other.objects {
            if have.contains(&g.category) {
                continue;
            }
            if g.place == Place::Anchor {
                if with_anchors {
                    groups.push(ObjectGroup {
                        place: Place::Wall,
                        min: 1,
                        max: 1,
                        ..g.clone()
                    });
                }
                continue;
            }
            let mut g = g.clone();
            g.max = g.max.min(g.min.max(1) + 1);
            groups.push(g);
        }
    }
    groups
}

/// What the prompt's mentions make of the archetype groups.
struct MentionGroups {
    /// The archetype group each mention takes over.
    group: Vec<Option<usize>>,
    /// The category planned for each mention (`None`: not available).
    category: Vec<Option<String>>,
    /// Categories the prompt rules out ("without chairs").
    excluded: BTreeSet<String>,
    /// Categories whose count the prompt gives as the scene's total ("three chairs").
    totals: BTreeSet<String>,
}

/// The selection's inputs: the planner, the prompt's reading, the available categories and
/// the merged archetype groups.
struct Selector<'a> {
    planner: &'a KnowledgePlanner,
    analysis: &'a Analysis,
    available: &'a BTreeSet<String>,
    groups: Vec<ObjectGroup>,
    /// How sparse the prompt asks the room to be.
    sparsity: Option<Sparsity>,
    /// The primary place's core categories.
    core: &'a [String],
}

impl Selector<'_> {
    /// Whether the room keeps archetype group `group` (planned as `category`; `anchor`: it is
    /// the place's anchor group) when no mention takes it over: every group in a full room;
    /// in a sparse one the anchor and the required groups of the core (every required group
    /// when the place lists no core); in an empty one the anchor alone.
    fn keeps(&self, group: &ObjectGroup, category: &str, anchor: bool) -> bool {
        let core = || {
            group.min >= 1
                && (self.core.is_empty()
                    || self
                        .core
                        .iter()
                        .any(|c| *c == group.category || c == category))
        };
        match self.sparsity {
            None => true,
            Some(Sparsity::Core) => anchor || core(),
            Some(Sparsity::Empty) => anchor,
        }
    }

    fn substitute(&self, category: &str) -> Option<String> {
        self.planner.substitute(category, self.available)
    }

    /// Whether the prompt states a relation of mention `mi`.
    fn stated(&self, mi: usize) -> bool {
        self.analysis.stated.iter().any(|s| s.subject == mi)
    }

    /// Mentions take over the first archetype group of their category.
    fn assign_mentions(&self, out: &mut Drafting) -> MentionGroups {
        let mentions = &self.analysis.mentions;
        let mut assigned = MentionGroups {
            group: vec![None; mentions.len()],
            category: vec![None; mentions.len()],
            excluded: BTreeSet::new(),
            totals: BTreeSet::new(),
        };
        for (mi, m) in mentions.iter().enumerate() {
            let Some(c) = self.substitute(&m.category) else {
                out.notes.push(format!(
                    "\"{}\": `{}` is not available and has no substitute; left out",
                    m.words, m.category
                ));
                continue;
            };
            if c != m.category {
                out.notes.push(format!(
                    "\"{}\": `{}` is not available, using `{c}`",
                    m.words, m.category
                ));
            }
            let g = self
                .groups
                .iter()
                .enumerate()
                .position(|(gi, g)| g.category == c && !assigned.group.contains(&Some(gi)));
            if m.count == 0 {
                // "without chairs": no group of the category is planned.
                assigned.excluded.insert(c.clone());
            } else if m.zone.is_none() {
                assigned.group[mi] = g;
            }
            if m.numbered && m.zone.is_none() {
                // "three chairs" is the scene's total: no other group adds to it.
                assigned.totals.insert(c.clone());
            }
            assigned.category[mi] = Some(c);
        }
        assigned
    }

    /// Walks the groups in order; a mention's objects appear where its group is (or at the
    /// end, for categories the archetype lacks).
    fn draft_groups(
        &self,
        mentions: &MentionGroups,
        anchor: &str,
        out: &mut Drafting,
        rng: &mut ChaCha8Rng,
    ) {
        let anchor_category = self.substitute(anchor);
        for (gi, group) in self.groups.iter().enumerate() {
            let Some(category) = self.substitute(&group.category) else {
                out.notes
                    .push(format!("`{}` is not available; left out", group.category));
                continue;
            };
            let mention = mentions.group.iter().position(|g| *g == Some(gi));
            let anchor_group =
                group.place == Place::Anchor && Some(&category) == anchor_category.as_ref();
            if mentions.excluded.contains(&category)
                || (mention.is_none() && mentions.totals.contains(&category))
                || (mention.is_none() && !self.keeps(group, &category, anchor_group))
            {
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
            let drafted = GroupDraft {
                group,
                category: &category,
                mention,
                least: self.sparsity.is_some(),
            };
            match &group.place {
                Place::Support(kind, target) => {
                    self.draft_supported(&drafted, *kind, target, out, rng)
                }
                place => {
                    let anchor = Some(&category) == anchor_category.as_ref();
                    self.draft_placed(&drafted, place, anchor, out, rng)
                }
            }
        }
    }

    /// A group resting on (or inside) its target's instances: a mention's objects spread over
    /// them, an optional extra drawn once for the room, otherwise a count per parent.
    fn draft_supported(
        &self,
        drafted: &GroupDraft<'_>,
        kind: RelationKind,
        target: &str,
        out: &mut Drafting,
        rng: &mut ChaCha8Rng,
    ) {
        let (group, category) = (drafted.group, drafted.category);
        let parents: Vec<usize> = self
            .substitute(target)
            .and_then(|t| out.by_category.get(&t).cloned())
            .unwrap_or_default();
        if parents.is_empty() && drafted.mention.is_none() {
            return;
        }
        if let Some(mi) = drafted.mention {
            if self.stated(mi) || parents.is_empty() {
                return; // placed from the prompt's own relations later
            }
            let m = &self.analysis.mentions[mi];
            let total = if m.explicit_count {
                m.count
            } else {
                drafted.count(rng).max(m.count) * parents.len() as u32
            };
            for k in 0..total as usize {
                let place = DraftPlace::Support(kind, parents[k % parents.len()]);
                if let Some(d) = out.add(category, place, false, true) {
                    out.mention_drafts[mi].push(d);
                }
            }
            return;
        }
        if group.min == 0 {
            // An optional extra is drawn once for the room, not once per parent: with
            // four shelves a per-shelf draw would put it in almost every seed.
            let count = drafted.count(rng) as usize;
            let first = if parents.len() > 1 {
                rng.random_range(0..parents.len())
            } else {
                0
            };
            for k in 0..count {
                let p = parents[(first + k) % parents.len()];
                out.add(category, DraftPlace::Support(kind, p), false, false);
            }
        } else {
            for &p in &parents {
                for _ in 0..drafted.count(rng) {
                    out.add(category, DraftPlace::Support(kind, p), false, false);
                }
            }
        }
    }

    /// A group placed on the floor (or a wall): its count, then its place — the anchor, a
    /// zone, next to its target's instances (spread over them) or opposite its target.
    /// `anchor`: whether the group's category is the archetype's anchor.
    fn draft_placed(
        &self,
        drafted: &GroupDraft<'_>,
        place: &Place,
        anchor: bool,
        out: &mut Drafting,
        rng: &mut ChaCha8Rng,
    ) {
        let (category, mention) = (drafted.category, drafted.mention);
        let hard = mention.is_some_and(|mi| self.stated(mi));
        let count = match mention {
            Some(mi) => {
                let m = &self.analysis.mentions[mi];
                if m.explicit_count {
                    m.count
                } else {
                    drafted.count(rng).max(m.count)
                }
            }
            None => drafted.count(rng),
        };
        let place = match place {
            Place::Anchor if anchor && !out.by_category.contains_key(category) => {
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
                    .substitute(t)
                    .and_then(|t| out.by_category.get(&t).cloned())
                {
                    Some(targets) => {
                        // Spread over the target's instances.
                        for k in 0..count as usize {
                            let place = DraftPlace::Relative(*kind, targets[k % targets.len()]);
                            let d = out.add(category, place, hard, mention.is_some());
                            if let (Some(mi), Some(d)) = (mention, d) {
                                out.mention_drafts[mi].push(d);
                            }
                        }
                        return;
                    }
                    None => DraftPlace::Zone(Zone::Free),
                }
            }
            Place::Opposite(t) => match self
                .substitute(t)
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
            let d = out.add(category, p, hard, mention.is_some());
            if let (Some(mi), Some(d)) = (mention, d) {
                out.mention_drafts[mi].push(d);
            }
        }
    }

    /// Mentions without an archetype group, or whose stated relations place them: drafted
    /// free, then given a stand-in's own zone or the default place of their category's kind
    /// (unless the prompt states their place).
    fn draft_other_mentions(
        &self,
        mentions: &MentionGroups,
        out: &mut Drafting,
        rng: &mut ChaCha8Rng,
    ) {
        for (mi, m) in self.analysis.mentions.iter().enumerate() {
            if !out.mention_drafts[mi].is_empty() {
                continue;
            }
            let Some(category) = mentions.category[mi].clone() else {
                continue;
            };
            let prior = self.planner.knowledge.prior(&category);
            let count = if m.explicit_count {
                m.count
            } else if let Some(g) = mentions.group[mi] {
                let group = &self.groups[g];
                rng.random_range(group.min.max(1)..=group.max.max(1))
                    .max(m.count)
            } else {
                m.count.max(3)
            };
            for _ in 0..count {
                if let Some(d) = out.add(&category, DraftPlace::Zone(Zone::Free), false, true) {
                    out.mention_drafts[mi].push(d);
                }
            }
            if let (false, Some(zone)) = (self.stated(mi), &m.zone) {
                // A stand-in's own place ("an island" stands free in the middle).
                for &d in &out.mention_drafts[mi] {
                    out.drafts[d].place = DraftPlace::Zone(zone.clone());
                }
            } else if !self.stated(mi) {
                for &d in &out.mention_drafts[mi] {
                    out.drafts[d].place = default_place(self.planner, prior, &out.drafts, d);
                }
            }
        }
    }
}

/// One archetype group being drafted: the group, the category planned for it, the mention
/// that took it over and whether the room is sparse (each group at its least count).
struct GroupDraft<'a> {
    group: &'a ObjectGroup,
    category: &'a str,
    mention: Option<usize>,
    least: bool,
}

impl GroupDraft<'_> {
    /// A count drawn from the group's range (its least in a sparse room).
    fn count(&self, rng: &mut ChaCha8Rng) -> u32 {
        if self.least {
            self.group.min
        } else {
            rng.random_range(self.group.min..=self.group.max)
        }
    }
}

/// The default place of draft `d`, by its category's kind (`prior`): an item on (or inside)
/// a fitting floor object, a wall mount, shelves against a wall, a seat facing the anchor,
/// otherwise free.
fn default_place(
    planner: &KnowledgePlanner,
    prior: Option<&CategoryPrior>,
    drafts: &[Draft],
    d: usize,
) -> DraftPlace {
    let mount = prior.map(|p| p.mount).unwrap_or_default();
    let shape = prior.map(|p| p.shape).unwrap_or(NominalShape::None);
    match (mount, shape) {
        (Mount::Surface, _) => {
            let inside = prior.and_then(|p| p.rests) == Some(crate::knowledge::ItemRest::Inside);
            match default_parent(planner, drafts, inside) {
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
    }
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
