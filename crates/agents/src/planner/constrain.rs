//! Phase 3, constrain: the relations the prompt states ("on", "under", "in front of",
//! "against the back wall", "in the corner" …) move their subjects and become hard
//! constraints of the plan.

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_scene_graph::RelationKind;

use crate::knowledge::Mount;
use crate::plan::{ConstraintTarget, Zone};
use crate::prompt::StatedTarget;

use super::interpret::Reading;
use super::{DraftPlace, Drafting, KnowledgePlanner};

/// Applies every stated relation of the prompt to the drafts of its subject mention.
pub(super) fn apply_stated(
    planner: &KnowledgePlanner,
    reading: &Reading,
    available: &BTreeSet<String>,
    out: &mut Drafting,
) {
    let knowledge = &planner.knowledge;
    let analysis = &reading.analysis;
    // Stated relations become hard constraints.
    let mut split_seen: BTreeMap<(usize, usize), usize> = BTreeMap::new();
    // The stated relation that last moved each draft (by its words), to report conflicts.
    let mut moved_by: BTreeMap<usize, String> = BTreeMap::new();
    for s in &analysis.stated {
        let subjects = out.mention_drafts[s.subject].clone();
        for (k, &d) in subjects.iter().enumerate() {
            out.drafts[d].hard = true;
            let before = out.drafts[d].place.clone();
            let kind = s.phrase.kind;
            match &s.target {
                StatedTarget::Corner => {
                    out.drafts[d].place = DraftPlace::Zone(Zone::Corner);
                    out.drafts[d].constraints.push((
                        RelationKind::AgainstWall,
                        ConstraintTarget::Corner,
                        s.words.clone(),
                    ));
                }
                StatedTarget::Wall(w) => {
                    let wall = (!w.is_empty()).then(|| w.clone());
                    if out.drafts[d].place != DraftPlace::Anchor {
                        out.drafts[d].place = DraftPlace::Zone(Zone::Wall { wall: wall.clone() });
                    }
                    out.drafts[d].wall = wall.clone();
                    let target = wall
                        .map(ConstraintTarget::Wall)
                        .unwrap_or(ConstraintTarget::AnyWall);
                    out.drafts[d].constraints.push((
                        RelationKind::AgainstWall,
                        target,
                        s.words.clone(),
                    ));
                }
                StatedTarget::Mention(t) => {
                    let targets = &out.mention_drafts[*t];
                    if targets.is_empty() {
                        if k == 0 {
                            out.notes.push(format!(
                                "\"{}\" {} \"{}\": the target is not planned (not asked for, or not available); the relation cannot hold",
                                analysis.mentions[s.subject].words,
                                s.words,
                                analysis.mentions[*t].words
                            ));
                        }
                        continue;
                    }
                    let target = targets[k % targets.len()];
                    if target == d {
                        continue;
                    }
                    let target_is_anchor_like = out.drafts[target].place == DraftPlace::Anchor;
                    let _ = target_is_anchor_like;
                    match kind {
                        RelationKind::On | RelationKind::Inside | RelationKind::Under => {
                            let prior = knowledge.prior(&out.drafts[d].category);
                            let small = prior
                                .filter(|p| p.mount == Mount::Floor && kind != RelationKind::Under)
                                .and_then(|p| p.small.clone())
                                .filter(|c| available.contains(c));
                            if let Some(small) = small {
                                if k == 0 {
                                    out.notes.push(format!("\"{}\" {} \"{}\": a `{}` does not fit there, using the smaller `{small}`", analysis.mentions[s.subject].words, s.words, analysis.mentions[*t].words, out.drafts[d].category));
                                }
                                out.drafts[d].category = small;
                            }
                            out.drafts[d].place = DraftPlace::Support(kind, target);
                        }
                        RelationKind::Facing => {
                            if matches!(out.drafts[d].place, DraftPlace::Relative(..)) {
                                out.drafts[d].extra.push((kind, target));
                            } else if !matches!(
                                out.drafts[d].place,
                                DraftPlace::Anchor
                                    | DraftPlace::Zone(Zone::Wall { .. })
                                    | DraftPlace::Zone(Zone::Corner)
                            ) {
                                out.drafts[d].place = DraftPlace::Relative(kind, target);
                            } else {
                                out.drafts[d].extra.push((kind, target));
                            }
                        }
                        _ => {
                            let mut kind = kind;
                            if s.phrase.split {
                                let n = split_seen.entry((s.subject, target)).or_default();
                                out.drafts[d].extra.push((
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
                            if out.drafts[d].place != DraftPlace::Anchor {
                                out.drafts[d].place = DraftPlace::Relative(kind, target);
                            } else {
                                out.drafts[d].extra.push((kind, target));
                            }
                        }
                    }
                    out.drafts[d].constraints.push((
                        kind,
                        ConstraintTarget::Object(String::new()),
                        format!("{}#{target}", s.words),
                    ));
                }
            }
            if out.drafts[d].place != before {
                if let (0, Some(earlier)) = (k, moved_by.get(&d)) {
                    out.notes.push(format!(
                        "\"{}\": \"{}\" conflicts with the earlier \"{earlier}\", which moved it first; the later one places it and both are checked",
                        analysis.mentions[s.subject].words, s.words
                    ));
                }
                moved_by.insert(d, s.words.clone());
            }
        }
    }
}
