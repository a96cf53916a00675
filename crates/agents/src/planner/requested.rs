//! Phase 6, requested: every object the prompt names, with how many were asked for and the
//! planned ids, and the limits that cut the plan.

use std::collections::BTreeSet;

use crate::plan::{Plan, RequestedObject, MAX_COUNT_PER_OBJECT, MAX_PLANNED_OBJECTS};
use crate::prompt::analyze;

use super::interpret::Reading;
use super::Drafting;

/// The requested objects of the plan and the limits applied to it (besides the prompt's
/// length).
pub(super) fn requested(
    reading: &Reading,
    drafting: &Drafting,
    ids: &[String],
) -> (Vec<RequestedObject>, Vec<String>) {
    let mut limits = Vec::new();
    let mut out = Vec::new();
    for (mi, m) in reading.analysis.mentions.iter().enumerate() {
        let category = drafting.mention_category.get(mi).cloned().flatten();
        let planned: Vec<String> = drafting.mention_drafts[mi]
            .iter()
            .map(|&d| ids[d].clone())
            .collect();
        let mut notes = Vec::new();
        match &category {
            None => notes.push(format!(
                "the library has no `{}` and nothing close enough",
                m.category
            )),
            Some(c) if *c != m.category => {
                notes.push(format!("`{}` is not available; using `{c}`", m.category))
            }
            Some(c) if m.stand_in => {
                notes.push(format!("the library has no \"{}\"; using `{c}`", m.words))
            }
            Some(_) => {}
        }
        if let Some(asked) = m.capped_from {
            notes.push(format!(
                "asked for {asked}; capped at {MAX_COUNT_PER_OBJECT} (the most instances of one object)"
            ));
            limits.push(format!(
                "\"{}\": {asked} asked for, {MAX_COUNT_PER_OBJECT} planned (the most instances of one object)",
                m.words
            ));
        }
        out.push(RequestedObject {
            words: m.words.clone(),
            category,
            count: m.count,
            ids: planned,
            note: (!notes.is_empty()).then(|| notes.join("; ")),
        });
    }
    out.extend(reading.analysis.unavailable.iter().map(|w| unavailable(w)));
    for (category, n) in &drafting.cut {
        limits.push(format!(
            "{n} × `{category}` left out: a plan holds at most {MAX_PLANNED_OBJECTS} objects"
        ));
    }
    (out, limits)
}

impl super::KnowledgePlanner {
    /// What `plan`'s prompt names, read by this planner and matched to `plan`'s objects by
    /// category: for a plan written by someone else (a model, a person), so the judge and the
    /// report can tell whether every requested object made it into the scene. Each mention takes
    /// up to its count of not yet taken objects of its category (or of the category standing in
    /// for it under `available`), then of its kinds (`office_chair` for "chair", the members of
    /// a generic noun such as "lamp"); fewer than asked for is reported in the mention's note.
    pub fn requested_in(&self, plan: &Plan, available: &BTreeSet<String>) -> Vec<RequestedObject> {
        let naming = super::interpret::naming_tokens(self, &plan.prompt);
        let analysis = analyze(
            &plan.prompt,
            &self.knowledge,
            &self.thesaurus.nouns,
            available,
            &naming,
        );
        let mut taken: BTreeSet<String> = BTreeSet::new();
        let mut out = Vec::new();
        for m in &analysis.mentions {
            let category = self.substitute(&m.category, available);
            let mut notes = Vec::new();
            let ids: Vec<String> = match &category {
                None => {
                    notes.push(format!(
                        "the library has no `{}` and nothing close enough",
                        m.category
                    ));
                    Vec::new()
                }
                Some(c) => {
                    if *c != m.category {
                        notes.push(format!("`{}` is not available; using `{c}`", m.category));
                    }
                    // The category itself first, then its kinds (`office_chair` for `chair`,
                    // a generic noun's list).
                    let generic = &self.knowledge.vocabulary.generic;
                    let kind_of = |category: &str| {
                        category.ends_with(&format!("_{c}"))
                            || [&m.category, c].iter().any(|g| {
                                generic
                                    .get(*g)
                                    .is_some_and(|l| l.iter().any(|x| x == category))
                            })
                    };
                    let free = |o: &&crate::plan::PlannedObject| !taken.contains(&o.id);
                    let ids: Vec<String> = plan
                        .objects
                        .iter()
                        .filter(free)
                        .filter(|o| o.category == *c)
                        .chain(
                            plan.objects
                                .iter()
                                .filter(free)
                                .filter(|o| o.category != *c && kind_of(&o.category)),
                        )
                        .take(m.count as usize)
                        .map(|o| o.id.clone())
                        .collect();
                    taken.extend(ids.iter().cloned());
                    if ids.len() < m.count as usize {
                        notes.push(format!(
                            "the plan holds {} of the {} asked for",
                            ids.len(),
                            m.count
                        ));
                    }
                    ids
                }
            };
            out.push(RequestedObject {
                words: m.words.clone(),
                category,
                count: m.count,
                ids,
                note: (!notes.is_empty()).then(|| notes.join("; ")),
            });
        }
        out.extend(analysis.unavailable.iter().map(|w| unavailable(w)));
        out
    }
}

/// A noun of the prompt the library has nothing close to.
fn unavailable(words: &str) -> RequestedObject {
    RequestedObject {
        words: words.to_owned(),
        category: None,
        count: 1,
        ids: Vec::new(),
        note: Some(format!(
            "the library has nothing close to \"{words}\"; left out"
        )),
    }
}
