//! Reading a prompt: which archetypes it names, which objects it mentions (with counts) and
//! which spatial relations it states.

use std::collections::BTreeSet;

use crate::knowledge::{Knowledge, RelationPhrase};
use crate::places::NounAlias;
use crate::plan::{Zone, MAX_COUNT_PER_OBJECT};
use crate::text::{tokenize, Token};

/// An archetype's match against the prompt.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct SceneMatch {
    /// Index into `Knowledge::archetypes`.
    pub archetype: usize,
    /// Score: whole phrases weigh by length, shared single words less.
    pub score: f64,
    /// Whether a whole phrase of the archetype occurs in the prompt.
    pub phrase: bool,
    /// Word count of the longest phrase of the archetype found in the prompt.
    pub phrase_len: usize,
}

/// An object the prompt mentions.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Mention {
    /// The category.
    pub category: String,
    /// How many (1 for a singular without a count word; 0 for "no …", "without …", "0 …"),
    /// at most [`MAX_COUNT_PER_OBJECT`].
    pub count: u32,
    /// The count the prompt asked for when it was above [`MAX_COUNT_PER_OBJECT`].
    pub capped_from: Option<u32>,
    /// Where a noun the library lacks puts its stand-in ("an island": a kitchen counter in
    /// the middle), if the noun table says.
    pub zone: Option<Zone>,
    /// Whether the words name a noun the library lacks and the category stands in for it.
    pub stand_in: bool,
    /// Whether a count word or a singular article fixed the count.
    pub explicit_count: bool,
    /// Whether a number or count word other than "a"/"an" fixed the count ("three chairs",
    /// "no chairs"): the count is then the scene's total for the category.
    pub numbered: bool,
    /// The words of the mention as written (stems).
    pub words: String,
}

/// What a stated relation points at.
#[derive(Debug, Clone, PartialEq, Eq)]
pub(crate) enum StatedTarget {
    /// Another mention (by index).
    Mention(usize),
    /// A wall id, or `""` for any wall.
    Wall(String),
    /// A corner.
    Corner,
}

/// A relation the prompt states for a mention.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Stated {
    /// The subject mention.
    pub subject: usize,
    /// The phrase's meaning.
    pub phrase: RelationPhrase,
    /// The target.
    pub target: StatedTarget,
    /// The prompt words.
    pub words: String,
}

/// Everything read from a prompt.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct Analysis {
    /// Archetype matches with a positive score, best first.
    pub scenes: Vec<SceneMatch>,
    /// Mentioned objects, in prompt order.
    pub mentions: Vec<Mention>,
    /// Stated relations.
    pub stated: Vec<Stated>,
    /// Whether any word is a known scene word (setting, mood).
    pub scene_words: bool,
    /// Whether the prompt holds any word at all.
    pub any_word: bool,
    /// Nouns the prompt names that the library has nothing close to (prompt words).
    pub unavailable: Vec<String>,
}

#[derive(Debug, Clone)]
enum Item {
    Mention(usize),
    Rel(RelationPhrase, String),
    Pronoun { possessive: bool },
    With,
    And,
    Break,
}

/// Reads `prompt`. `available` restricts how generic nouns resolve.
pub(crate) fn analyze(
    prompt: &str,
    knowledge: &Knowledge,
    nouns: &[NounAlias],
    available: &BTreeSet<String>,
) -> Analysis {
    let tokens = tokenize(prompt);
    let stems: Vec<Option<&str>> = tokens.iter().map(Token::stem).collect();
    let mut out = Analysis {
        any_word: stems
            .iter()
            .any(|s| s.is_some_and(|w| w.chars().any(char::is_alphabetic))),
        ..Analysis::default()
    };
    let voc = &knowledge.vocabulary;
    out.scene_words = stems.iter().flatten().any(|w| voc.scene_words.contains(*w));

    // 1. Scene type: whole phrases, then shared words.
    let matches_at = |i: usize, phrase: &[String]| {
        phrase.len() <= stems.len() - i
            && phrase
                .iter()
                .enumerate()
                .all(|(k, w)| stems[i + k] == Some(w.as_str()))
    };
    let mut consumed = vec![false; tokens.len()];
    let mut phrase_spans: Vec<(usize, usize, usize)> = Vec::new(); // (archetype, start, len)
    for (ai, arch) in knowledge.archetypes.iter().enumerate() {
        let mut score = 0.0;
        let mut phrase_hit = false;
        let mut best_len = 0;
        for phrase in &arch.phrases {
            for i in 0..stems.len() {
                if matches_at(i, phrase) {
                    phrase_hit = true;
                    best_len = best_len.max(phrase.len());
                    phrase_spans.push((ai, i, phrase.len()));
                }
            }
        }
        if phrase_hit {
            score += 10.0 * best_len as f64;
        }
        let words: BTreeSet<&str> = arch.phrases.iter().flatten().map(String::as_str).collect();
        let shared = stems
            .iter()
            .flatten()
            .filter(|w| !voc.filler.contains(**w) && words.contains(**w))
            .count();
        score += 3.0 * shared as f64;
        if score > 0.0 {
            out.scenes.push(SceneMatch {
                archetype: ai,
                score,
                phrase: phrase_hit,
                phrase_len: best_len,
            });
        }
    }
    out.scenes.sort_by(|a, b| {
        b.score
            .total_cmp(&a.score)
            .then(a.archetype.cmp(&b.archetype))
    });
    if let Some(best) = out.scenes.first() {
        for &(ai, start, len) in &phrase_spans {
            if ai == best.archetype {
                consumed[start..start + len]
                    .iter_mut()
                    .for_each(|c| *c = true);
            }
        }
    }
    let scene_categories: BTreeSet<&str> = out
        .scenes
        .iter()
        .take(2)
        .flat_map(|m| {
            knowledge.archetypes[m.archetype]
                .objects
                .iter()
                .map(|g| g.category.as_str())
        })
        .collect();

    // 2. Items: mentions, relation phrases, pronouns and joints.
    let category_phrases = knowledge.category_phrases();
    let mut items: Vec<Item> = Vec::new();
    let mut count: Option<u32> = None;
    let mut definite = false;
    // "without" negates the mentions up to the next clause or "with"; "no" the next one.
    let mut negated = false;
    // Whether the pending count came from an article ("a chair": one, but not a total).
    let mut article = false;
    // After "its" / "their" the next noun names a part of the target ("its shelves").
    let mut possessive = false;
    let mut i = 0;
    while i < tokens.len() {
        let Some(word) = stems[i] else {
            items.push(Item::Break);
            count = None;
            definite = false;
            possessive = false;
            negated = false;
            i += 1;
            continue;
        };
        if consumed[i] {
            count = None;
            definite = false;
            i += 1;
            continue;
        }
        if let Some((phrase, rel)) = voc.relations.iter().find(|(p, _)| matches_at(i, p)) {
            let words = phrase.join(" ");
            items.push(Item::Rel(rel.clone(), words));
            possessive = false;
            count = None;
            definite = false;
            i += phrase.len();
            continue;
        }
        let noun_len = category_phrases
            .iter()
            .find(|(p, _)| matches_at(i, p))
            .map(|(p, _)| p.len())
            .or(voc.generic.contains_key(word).then_some(1));
        if let (true, Some(len)) = (possessive, noun_len) {
            possessive = false;
            i += len;
            continue;
        }
        // A noun the library lacks, when its phrase is longer than any category phrase here.
        let alias = nouns.iter().find(|a| {
            matches_at(i, &a.phrase)
                && a.phrase.len() > noun_len.unwrap_or(0)
                && a.only_with
                    .as_ref()
                    .is_none_or(|c| scene_categories.contains(c.as_str()))
        });
        if let Some(alias) = alias {
            let last = i + alias.phrase.len() - 1;
            let plural = matches!(&tokens[last], Token::Word { plural: true, .. });
            let words = alias.phrase.join(" ");
            match alias.category.as_deref() {
                Some(category) => {
                    let m = push_mention(
                        &mut out,
                        &mut items,
                        category,
                        if negated { Some(0) } else { count },
                        negated || !article,
                        plural,
                        definite,
                        words.clone(),
                    );
                    if out.mentions[m].words == words {
                        out.mentions[m].zone = alias.zone.clone();
                        out.mentions[m].stand_in = true;
                    }
                }
                None if !negated && count != Some(0) => out.unavailable.push(words),
                None => {}
            }
            count = None;
            definite = false;
            i += alias.phrase.len();
            continue;
        }
        if let Some((phrase, category)) = category_phrases.iter().find(|(p, _)| matches_at(i, p)) {
            let last = i + phrase.len() - 1;
            let plural = matches!(&tokens[last], Token::Word { plural: true, .. });
            let words = phrase.join(" ");
            let n = if negated { Some(0) } else { count };
            push_mention(
                &mut out,
                &mut items,
                category,
                n,
                negated || !article,
                plural,
                definite,
                words,
            );
            count = None;
            definite = false;
            i += phrase.len();
            continue;
        }
        if let Some(list) = voc.generic.get(word) {
            let plural = matches!(&tokens[i], Token::Word { plural: true, .. });
            let usable: Vec<&String> = list.iter().filter(|c| available.contains(*c)).collect();
            let earlier = out
                .mentions
                .iter()
                .rposition(|m| list.contains(&m.category));
            if definite && earlier.is_some() {
                items.push(Item::Mention(earlier.unwrap_or_default()));
            } else if plural && count.is_none_or(|n| n == 0) && usable.len() > 1 {
                // "toys": several categories of the list, preferring the scene's own.
                let mut chosen: Vec<&String> = usable
                    .iter()
                    .copied()
                    .filter(|c| scene_categories.contains(c.as_str()))
                    .collect();
                chosen.extend(
                    usable
                        .iter()
                        .copied()
                        .filter(|c| !scene_categories.contains(c.as_str())),
                );
                chosen.truncate(3);
                for (k, c) in chosen.into_iter().enumerate() {
                    if k > 0 {
                        items.push(Item::And);
                    }
                    push_mention(
                        &mut out,
                        &mut items,
                        c,
                        Some(if negated || count == Some(0) { 0 } else { 2 }),
                        negated || count == Some(0),
                        true,
                        false,
                        word.to_owned(),
                    );
                }
            } else if let Some(c) = usable
                .iter()
                .find(|c| scene_categories.contains(c.as_str()))
                .or(usable.first())
            {
                let c = (*c).clone();
                push_mention(
                    &mut out,
                    &mut items,
                    &c,
                    if negated { Some(0) } else { count },
                    negated || !article,
                    plural,
                    definite,
                    word.to_owned(),
                );
            }
            count = None;
            definite = false;
            i += 1;
            continue;
        }
        match word {
            "the" => definite = true,
            "it" | "them" => items.push(Item::Pronoun { possessive: false }),
            "its" | "their" => {
                items.push(Item::Pronoun { possessive: true });
                possessive = true;
            }
            "with" | "holding" | "containing" | "featuring" | "including" => {
                negated = false;
                items.push(Item::With);
            }
            "without" | "minus" | "lacking" => negated = true,
            "but" => negated = false,
            "no" | "zero" | "none" => {
                count = Some(0);
                article = false;
            }
            "and" | "plus" => items.push(Item::And),
            _ => {
                if let Some(n) = voc.counts.get(word) {
                    // "a few" → few wins over a; "a couple" → couple wins.
                    count = Some(*n);
                    article = matches!(word, "a" | "an");
                } else if let Ok(n) = word.parse::<u32>() {
                    count = Some(n);
                    article = false;
                } else if word.chars().all(|c| c.is_ascii_digit()) {
                    // More digits than a u32 holds.
                    count = Some(u32::MAX);
                    article = false;
                } else if word == "lot" {
                    count = Some(6);
                }
            }
        }
        i += 1;
    }

    // 3. Relations from the item stream.
    read_relations(&mut out, &items, knowledge);
    out
}

#[allow(clippy::too_many_arguments)]
fn push_mention(
    out: &mut Analysis,
    items: &mut Vec<Item>,
    category: &str,
    count: Option<u32>,
    numbered: bool,
    plural: bool,
    definite: bool,
    words: String,
) -> usize {
    if definite {
        if let Some(earlier) = out.mentions.iter().rposition(|m| m.category == category) {
            items.push(Item::Mention(earlier));
            return earlier;
        }
    }
    let idx = out.mentions.len();
    let explicit = count.is_some() || !plural;
    let n = count.unwrap_or(if plural { 3 } else { 1 });
    let capped_from = (n > MAX_COUNT_PER_OBJECT).then_some(n);
    let n = n.min(MAX_COUNT_PER_OBJECT);
    // "a few books" keeps the count; "an armchair" is one; "no chairs" is none.
    out.mentions.push(Mention {
        category: category.to_owned(),
        count: match (n, plural) {
            (0, _) => 0,
            (n, true) => n.max(2),
            (n, false) => n.max(1),
        },
        explicit_count: explicit,
        numbered: numbered && count.is_some(),
        words,
        capped_from,
        zone: None,
        stand_in: false,
    });
    items.push(Item::Mention(idx));
    idx
}

fn read_relations(out: &mut Analysis, items: &[Item], knowledge: &Knowledge) {
    let mut group: Vec<usize> = Vec::new();
    let mut group_open = true;
    let mut last_subjects: Vec<usize> = Vec::new();
    let mut head: Option<usize> = None;
    let mut with_parent: Option<usize> = None;
    let mut with_members: Vec<usize> = Vec::new();
    let mut in_with = false;
    let mut with_related = false;
    let mut pending: Option<(RelationPhrase, String, Vec<usize>)> = None;
    let mut seen: Vec<usize> = Vec::new();

    let emit = |out: &mut Analysis,
                subjects: &[usize],
                phrase: &RelationPhrase,
                target: StatedTarget,
                words: &str| {
        for &s in subjects {
            if StatedTarget::Mention(s) == target {
                continue;
            }
            out.stated.push(Stated {
                subject: s,
                phrase: phrase.clone(),
                target: target.clone(),
                words: words.to_owned(),
            });
        }
    };

    let finish_clause = |out: &mut Analysis,
                         in_with: bool,
                         with_related: bool,
                         with_parent: Option<usize>,
                         with_members: &[usize]| {
        if !in_with || with_related {
            return;
        }
        let Some(parent) = with_parent else { return };
        let parent_cat = out.mentions[parent].category.clone();
        let Some(prior) = knowledge.prior(&parent_cat) else {
            return;
        };
        use crate::knowledge::{Mount, NominalShape};
        let kind = match prior.shape {
            NominalShape::Shelves | NominalShape::Container => {
                scenethesis_scene_graph::RelationKind::Inside
            }
            NominalShape::None => return,
            _ => scenethesis_scene_graph::RelationKind::On,
        };
        for &m in with_members {
            let small = knowledge
                .prior(&out.mentions[m].category)
                .is_some_and(|p| p.mount == Mount::Surface);
            if small && m != parent {
                let phrase = RelationPhrase {
                    kind,
                    corner: false,
                    head: false,
                    split: false,
                    wall: None,
                };
                out.stated.push(Stated {
                    subject: m,
                    phrase,
                    target: StatedTarget::Mention(parent),
                    words: "with".into(),
                });
            }
        }
    };

    for item in items.iter().chain(std::iter::once(&Item::Break)) {
        match item {
            Item::Mention(m) => {
                let m = *m;
                if let Some((phrase, words, subjects)) = pending.take() {
                    emit(out, &subjects, &phrase, StatedTarget::Mention(m), &words);
                    if subjects.iter().all(|s| with_members.contains(s)) && in_with {
                        with_related = true;
                    }
                    last_subjects = subjects;
                    group.clear();
                    group_open = false;
                    seen.push(m);
                    continue;
                }
                if !group_open {
                    group.clear();
                }
                group.push(m);
                group_open = false;
                head.get_or_insert(m);
                if in_with {
                    with_members.push(m);
                }
                seen.push(m);
            }
            Item::And => group_open = true,
            Item::With => {
                with_parent = head.or(seen.last().copied());
                in_with = true;
                with_related = false;
                with_members.clear();
                group.clear();
                group_open = true;
                pending = None;
            }
            Item::Rel(phrase, words) => {
                let subjects = if group.is_empty() {
                    last_subjects.clone()
                } else {
                    group.clone()
                };
                if subjects.is_empty() {
                    continue;
                }
                let direct = if phrase.corner {
                    Some(StatedTarget::Corner)
                } else if let Some(w) = &phrase.wall {
                    Some(StatedTarget::Wall(w.clone()))
                } else if phrase.head {
                    with_parent
                        .or(head)
                        .filter(|h| !subjects.contains(h))
                        .map(StatedTarget::Mention)
                } else {
                    None
                };
                match direct {
                    Some(target) => {
                        emit(out, &subjects, phrase, target, words);
                        if in_with && subjects.iter().all(|s| with_members.contains(s)) {
                            with_related = true;
                        }
                    }
                    None if phrase.head => {}
                    None => pending = Some((phrase.clone(), words.clone(), subjects.clone())),
                }
                last_subjects = subjects;
                group.clear();
                group_open = false;
            }
            Item::Pronoun { possessive } => {
                if let Some((phrase, words, subjects)) = pending.take() {
                    // In "X with Y inside it", "it" is X; elsewhere the latest other mention.
                    let with_target = with_parent.filter(|p| {
                        in_with
                            && !subjects.contains(p)
                            && subjects.iter().all(|s| with_members.contains(s))
                    });
                    let target = with_target
                        .or_else(|| seen.iter().rev().find(|m| !subjects.contains(m)).copied());
                    if let Some(target) = target {
                        emit(
                            out,
                            &subjects,
                            &phrase,
                            StatedTarget::Mention(target),
                            &words,
                        );
                        if in_with && subjects.iter().all(|s| with_members.contains(s)) {
                            with_related = true;
                        }
                    }
                    last_subjects = subjects;
                    let _ = possessive;
                }
            }
            Item::Break => {
                finish_clause(out, in_with, with_related, with_parent, &with_members);
                group.clear();
                group_open = true;
                last_subjects.clear();
                head = None;
                with_parent = None;
                with_members.clear();
                in_with = false;
                with_related = false;
                pending = None;
            }
        }
    }
}
