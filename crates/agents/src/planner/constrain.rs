//! Phase 3, constrain: the relations the prompt states ("on", "under", "in front of",
//! "against the back wall", "in the corner" …) move their subjects and become hard
//! constraints of the plan.

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_scene_graph::RelationKind;

use crate::knowledge::Mount;
use crate::plan::{ConstraintTarget, Zone};
use crate::prompt::{Stated, StatedTarget};

use super::interpret::Reading;
use super::{DraftPlace, Drafting, KnowledgePlanner};

/// Applies every stated relation of the prompt to the drafts of its subject mention.
pub(super) fn apply_stated(
    planner: &KnowledgePlanner,
    reading: &Reading,
    available: &BTreeSet<String>,
    out: &mut Drafting,
) {
    let mut stating = Stating {
        planner,
        reading,
        available,
        out,
        split_seen: BTreeMap::new(),
        moved_by: BTreeMap::new(),
    };
    for s in &reading.analysis.stated {
        let subjects = stating.out.mention_drafts[s.subject].clone();
        for (k, &d) in subjects.iter().enumerate() {
            stating.apply(s, k, d);
        }
    }
}

/// The state of applying the stated relations, one subject draft at a time.
struct Stating<'a> {
    planner: &'a KnowledgePlanner,
    reading: &'a Reading,
    available: &'a BTreeSet<String>,
    out: &'a mut Drafting,
    /// Per (subject mention, target draft), how many split relations ("on either side of")
    /// were applied: they alternate left and right.
    split_seen: BTreeMap<(usize, usize), usize>,
    /// The stated relation that last moved each draft (by its words), to report conflicts.
    moved_by: BTreeMap<usize, String>,
}

impl Stating<'_> {
    /// Applies `s` to draft `d`, the `k`-th draft of its subject mention: the draft becomes
    /// hard, moves where the relation says and gains the relation as a constraint; a move
    /// that overrides an earlier relation's is noted.
    fn apply(&mut self, s: &Stated, k: usize, d: usize) {
        self.out.drafts[d].hard = true;
        let before = self.out.drafts[d].place.clone();
        match &s.target {
            StatedTarget::Corner => {
                let draft = &mut self.out.drafts[d];
                draft.place = DraftPlace::Zone(Zone::Corner);
                draft.constraints.push((
                    RelationKind::AgainstWall,
                    ConstraintTarget::Corner,
                    s.words.clone(),
                ));
            }
            StatedTarget::Wall(w) => self.against_wall(s, d, w),
            StatedTarget::Mention(t) => {
                if !self.relate_to_mention(s, k, d, *t) {
                    return;
                }
            }
        }
        if self.out.drafts[d].place != before {
            if let (0, Some(earlier)) = (k, self.moved_by.get(&d)) {
                self.out.notes.push(format!(
                    "\"{}\": \"{}\" conflicts with the earlier \"{earlier}\", which moved it first; the later one places it and both are checked",
                    self.reading.analysis.mentions[s.subject].words, s.words
                ));
            }
            self.moved_by.insert(d, s.words.clone());
        }
    }

    /// Against wall `w` (any wall when empty): a zone along it, unless the draft is the anchor.
    fn against_wall(&mut self, s: &Stated, d: usize, w: &str) {
        let draft = &mut self.out.drafts[d];
        let wall = (!w.is_empty()).then(|| w.to_owned());
        if draft.place != DraftPlace::Anchor {
            draft.place = DraftPlace::Zone(Zone::Wall { wall: wall.clone() });
        }
        draft.wall = wall.clone();
        let target = wall
            .map(ConstraintTarget::Wall)
            .unwrap_or(ConstraintTarget::AnyWall);
        draft
            .constraints
            .push((RelationKind::AgainstWall, target, s.words.clone()));
    }

    /// Relative to the drafts of mention `t` (the `k`-th subject draft takes the `k`-th
    /// target, round robin). Returns false when nothing applies: the target is not planned
    /// (noted once) or is the draft itself.
    fn relate_to_mention(&mut self, s: &Stated, k: usize, d: usize, t: usize) -> bool {
        let targets = &self.out.mention_drafts[t];
        if targets.is_empty() {
            if k == 0 {
                let mentions = &self.reading.analysis.mentions;
                self.out.notes.push(format!(
                    "\"{}\" {} \"{}\": the target is not planned (not asked for, or not available); the relation cannot hold",
                    mentions[s.subject].words, s.words, mentions[t].words
                ));
            }
            return false;
        }
        let target = targets[k % targets.len()];
        if target == d {
            return false;
        }
        let kind = s.phrase.kind;
        match kind {
            RelationKind::On | RelationKind::Inside | RelationKind::Under => {
                self.support(s, k, d, t, target)
            }
            RelationKind::Facing => self.facing(d, target),
            _ => self.relative(s, d, target),
        }
        self.out.drafts[d].constraints.push((
            kind,
            ConstraintTarget::Object(String::new()),
            format!("{}#{target}", s.words),
        ));
        true
    }

    /// On, inside or under draft `target`; a floor object too big to sit on or in something
    /// becomes its smaller kind when the library has it (noted once).
    fn support(&mut self, s: &Stated, k: usize, d: usize, t: usize, target: usize) {
        let kind = s.phrase.kind;
        let prior = self.planner.knowledge.prior(&self.out.drafts[d].category);
        let small = prior
            .filter(|p| p.mount == Mount::Floor && kind != RelationKind::Under)
            .and_then(|p| p.small.clone())
            .filter(|c| self.available.contains(c));
        if let Some(small) = small {
            if k == 0 {
                let mentions = &self.reading.analysis.mentions;
                self.out.notes.push(format!(
                    "\"{}\" {} \"{}\": a `{}` does not fit there, using the smaller `{small}`",
                    mentions[s.subject].words,
                    s.words,
                    mentions[t].words,
                    self.out.drafts[d].category
                ));
            }
            self.out.drafts[d].category = small;
        }
        self.out.drafts[d].place = DraftPlace::Support(kind, target);
    }

    /// Facing draft `target`: the draft's placement when it has none of its own (a relative
    /// one, the anchor's, a wall or corner zone), else an extra relation.
    fn facing(&mut self, d: usize, target: usize) {
        let draft = &mut self.out.drafts[d];
        let kind = RelationKind::Facing;
        if matches!(draft.place, DraftPlace::Relative(..)) {
            draft.extra.push((kind, target));
        } else if !matches!(
            draft.place,
            DraftPlace::Anchor
                | DraftPlace::Zone(Zone::Wall { .. })
                | DraftPlace::Zone(Zone::Corner)
        ) {
            draft.place = DraftPlace::Relative(kind, target);
        } else {
            draft.extra.push((kind, target));
        }
    }

    /// Any other relation to draft `target` places the draft (the anchor keeps its place and
    /// gains it as an extra); a split relation ("on either side of") alternates left and
    /// right and places it beside the target.
    fn relative(&mut self, s: &Stated, d: usize, target: usize) {
        let mut kind = s.phrase.kind;
        let draft = &mut self.out.drafts[d];
        if s.phrase.split {
            let n = self.split_seen.entry((s.subject, target)).or_default();
            let side = if *n % 2 == 0 {
                RelationKind::LeftOf
            } else {
                RelationKind::RightOf
            };
            draft.extra.push((side, target));
            *n += 1;
            kind = RelationKind::Beside;
        }
        if draft.place != DraftPlace::Anchor {
            draft.place = DraftPlace::Relative(kind, target);
        } else {
            draft.extra.push((kind, target));
        }
    }
}
