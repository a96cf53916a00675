//! Phase 1, interpret: read the prompt and choose the archetypes the scene draws on.

use std::collections::BTreeSet;

use crate::knowledge::Archetype;
use crate::plan::{PlanError, PlanRequest};
use crate::prompt::{analyze, Analysis};

use super::KnowledgePlanner;

/// What the planner made of a prompt before drafting any object.
#[derive(Debug, Clone)]
pub(super) struct Reading {
    /// The prompt, trimmed.
    pub prompt: String,
    /// Mentions, stated relations and archetype matches.
    pub analysis: Analysis,
    /// The archetypes the plan draws on, primary first.
    pub archetypes: Vec<Archetype>,
    /// The plan's scene type: the primary archetype's name, or `custom` for a blend.
    pub scene_type: String,
}

/// Reads `request.prompt` and chooses its archetypes.
pub(super) fn interpret(
    planner: &KnowledgePlanner,
    request: &PlanRequest,
) -> Result<Reading, PlanError> {
    let prompt = request.prompt.trim();
    let knowledge = &planner.knowledge;
    if !prompt.chars().any(char::is_alphanumeric) {
        return Err(PlanError::EmptyPrompt);
    }
    let analysis = analyze(prompt, knowledge, &request.available_categories);
    let choice =
        choose_archetypes(planner, &analysis).ok_or_else(|| PlanError::Unintelligible {
            prompt: prompt.to_owned(),
        })?;
    let scene_type = if choice.blended {
        "custom".to_owned()
    } else {
        choice.archetypes[0].name.clone()
    };
    Ok(Reading {
        prompt: prompt.to_owned(),
        analysis,
        archetypes: choice.archetypes,
        scene_type,
    })
}

/// The archetypes chosen for a prompt.
struct Choice {
    archetypes: Vec<Archetype>,
    blended: bool,
}

/// The archetypes best matching the analysis (best first) and whether they blend.
fn choose_archetypes(planner: &KnowledgePlanner, analysis: &Analysis) -> Option<Choice> {
    let knowledge = &planner.knowledge;
    let by_index = |chosen: &[usize], blended: bool| Choice {
        archetypes: chosen
            .iter()
            .map(|&i| knowledge.archetypes[i].clone())
            .collect(),
        blended,
    };
    let scenes = &analysis.scenes;
    if let Some(best) = scenes.first() {
        let ties = scenes
            .iter()
            .take_while(|m| (m.score - best.score).abs() < 1e-9)
            .count();
        // Two archetypes named equally strongly ("an alchemy workshop") blend.
        let rival = scenes
            .get(1)
            .is_some_and(|m| m.phrase && m.phrase_len == best.phrase_len);
        if best.phrase && ties == 1 && !rival {
            return Some(by_index(&[best.archetype], false));
        }
        let mut chosen: Vec<usize> = scenes.iter().take(2).map(|m| m.archetype).collect();
        chosen.dedup();
        return Some(by_index(&chosen, true));
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
            let chosen: Vec<usize> = ranked.iter().take(2).map(|r| r.1).collect();
            return Some(by_index(&chosen, true));
        }
    }
    if analysis.scene_words || !analysis.mentions.is_empty() {
        let default = knowledge
            .archetypes
            .iter()
            .position(|a| a.name == knowledge.vocabulary.default_archetype)?;
        return Some(by_index(&[default], !analysis.mentions.is_empty()));
    }
    None
}
