//! Reading a prompt: which archetypes it names, which objects it mentions (with counts) and
//! which spatial relations it states.

use std::collections::BTreeSet;

use crate::knowledge::{Knowledge, RelationPhrase};
use crate::looks::{read_looks, Looks, ReadLooks};
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
    /// Where each mention's noun stands: (first token, tokens, mention), once per time the
    /// prompt names it ("the sofa is red" names an earlier sofa again).
    pub noun_spans: Vec<(usize, usize, usize)>,
    /// The colours, materials and style the prompt asks for.
    pub looks: ReadLooks,
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

/// Reads `prompt`. `available` restricts how generic nouns resolve. `naming` marks the tokens
/// that name the place (one per token; they are not read as objects).
pub(crate) fn analyze(
    prompt: &str,
    knowledge: &Knowledge,
    nouns: &[NounAlias],
    available: &BTreeSet<String>,
    naming: &[bool],
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
    match_scenes(&stems, knowledge, &mut out);
    let scene_categories = scene_categories(&out, knowledge);

    // 2. Items: mentions, relation phrases, pronouns and joints.
    let reader = ItemReader {
        tokens: &tokens,
        stems: &stems,
        knowledge,
        nouns,
        available,
        scene_categories: &scene_categories,
        consumed: naming,
    };
    let items = reader.read(&mut out);

    // 3. Relations from the item stream.
    read_relations(&mut out, &items, knowledge);

    // 4. Colours, materials and the style, on the nouns they qualify.
    out.looks = read_looks(Looks::builtin(), &stems, &out.noun_spans);
    out
}

/// Whether the stems from `i` on spell `phrase`.
fn matches_at(stems: &[Option<&str>], i: usize, phrase: &[String]) -> bool {
    phrase.len() <= stems.len() - i
        && phrase
            .iter()
            .enumerate()
            .all(|(k, w)| stems[i + k] == Some(w.as_str()))
}

/// Phase 1, the scene type: scores every archetype by its whole phrases, then by the words it
/// shares with the prompt, into `out.scenes` (best first); generic nouns prefer the best
/// archetypes' categories.
fn match_scenes(stems: &[Option<&str>], knowledge: &Knowledge, out: &mut Analysis) {
    let voc = &knowledge.vocabulary;
    for (ai, arch) in knowledge.archetypes.iter().enumerate() {
        let mut score = 0.0;
        let mut phrase_hit = false;
        let mut best_len = 0;
        for phrase in &arch.phrases {
            for i in 0..stems.len() {
                if matches_at(stems, i, phrase) {
                    phrase_hit = true;
                    best_len = best_len.max(phrase.len());
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
}

/// The categories of the two best-matching archetypes (generic nouns prefer them).
fn scene_categories<'k>(out: &Analysis, knowledge: &'k Knowledge) -> BTreeSet<&'k str> {
    out.scenes
        .iter()
        .take(2)
        .flat_map(|m| {
            knowledge.archetypes[m.archetype]
                .objects
                .iter()
                .map(|g| g.category.as_str())
        })
        .collect()
}

/// What the item reader carries from one word to the next.
#[derive(Debug, Default)]
struct Pending {
    /// The count read last ("three", "a", "no"), for the next mention.
    count: Option<u32>,
    /// Whether "the" came before the next noun.
    definite: bool,
    /// "without" negates the mentions up to the next clause or "with"; "no" the next one.
    negated: bool,
    /// Whether the pending count came from an article ("a chair": one, but not a total).
    article: bool,
    /// After "its" / "their" the next noun names a part of the target ("its shelves").
    possessive: bool,
}

impl Pending {
    /// Forgets the count and "the" once a word has used them.
    fn used(&mut self) {
        self.count = None;
        self.definite = false;
    }

    /// The count a mention gets: none when negated.
    fn mention_count(&self) -> Option<u32> {
        if self.negated {
            Some(0)
        } else {
            self.count
        }
    }
}

/// Phase 2: reads the prompt's tokens into items (mentions, relation phrases, pronouns and
/// joints), the mentions into `Analysis::mentions`.
struct ItemReader<'a> {
    tokens: &'a [Token],
    stems: &'a [Option<&'a str>],
    knowledge: &'a Knowledge,
    nouns: &'a [NounAlias],
    available: &'a BTreeSet<String>,
    /// The categories of the best-matching scenes.
    scene_categories: &'a BTreeSet<&'a str>,
    /// Tokens that named the scene.
    consumed: &'a [bool],
}

impl ItemReader<'_> {
    /// The item stream of the prompt; mentions are added to `out`.
    fn read(&self, out: &mut Analysis) -> Vec<Item> {
        let voc = &self.knowledge.vocabulary;
        let mut items: Vec<Item> = Vec::new();
        let mut pending = Pending::default();
        let mut i = 0;
        while i < self.tokens.len() {
            let Some(word) = self.stems[i] else {
                items.push(Item::Break);
                pending = Pending {
                    article: pending.article,
                    ..Pending::default()
                };
                i += 1;
                continue;
            };
            if self.consumed[i] {
                pending.used();
                i += 1;
                continue;
            }
            if let Some((phrase, rel)) = voc.relations.iter().find(|(p, _)| self.matches_at(i, p)) {
                let words = phrase.join(" ");
                items.push(Item::Rel(rel.clone(), words));
                pending.possessive = false;
                pending.used();
                i += phrase.len();
                continue;
            }
            let noun_len = self
                .knowledge
                .category_phrases()
                .iter()
                .find(|(p, _)| self.matches_at(i, p))
                .map(|(p, _)| p.len())
                .or(voc.generic.contains_key(word).then_some(1));
            if noun_len.is_none_or(|n| n == 1) && self.qualifies_next(i) {
                // A look word before a noun ("a *glass* coffee table", "a *light* blue rug")
                // is no object of its own.
                i += 1;
                continue;
            }
            if let (true, Some(len)) = (pending.possessive, noun_len) {
                pending.possessive = false;
                i += len;
                continue;
            }
            let before = items.len();
            let read = self
                .read_alias(i, noun_len, &pending, out, &mut items)
                .or_else(|| self.read_category(i, &pending, out, &mut items))
                .or_else(|| self.read_generic(i, word, &pending, out, &mut items));
            if let Some(len) = read {
                for item in &items[before..] {
                    if let Item::Mention(m) = item {
                        out.noun_spans.push((i, len, *m));
                    }
                }
                pending.used();
                i += len;
                continue;
            }
            self.read_word(word, &mut pending, &mut items);
            i += 1;
        }
        items
    }

    fn matches_at(&self, i: usize, phrase: &[String]) -> bool {
        matches_at(self.stems, i, phrase)
    }

    /// Whether the word at `i` is a look word (colour, material, modifier) that qualifies
    /// what follows it: another look word, a surface or a noun.
    fn qualifies_next(&self, i: usize) -> bool {
        let looks = Looks::builtin();
        let is_look = |k: usize| {
            self.stems
                .get(k)
                .copied()
                .flatten()
                .is_some_and(|w| looks.is_look_word(w))
        };
        if !is_look(i) {
            return false;
        }
        let mut k = i + 1;
        while is_look(k) {
            k += 1;
        }
        let Some(next) = self.stems.get(k).copied().flatten() else {
            return false;
        };
        looks.surfaces.contains_key(next)
            || self.knowledge.vocabulary.generic.contains_key(next)
            || self
                .knowledge
                .category_phrases()
                .iter()
                .any(|(p, _)| self.matches_at(k, p))
    }

    /// Whether the phrase ending at token `last` was written in the plural.
    fn plural_at(&self, last: usize) -> bool {
        matches!(&self.tokens[last], Token::Word { plural: true, .. })
    }

    /// A noun the library lacks at token `i`, when its phrase is longer than any category
    /// phrase here: its stand-in's mention, or a note that it is unavailable. Returns how many
    /// tokens it read.
    fn read_alias(
        &self,
        i: usize,
        noun_len: Option<usize>,
        pending: &Pending,
        out: &mut Analysis,
        items: &mut Vec<Item>,
    ) -> Option<usize> {
        let alias = self.nouns.iter().find(|a| {
            self.matches_at(i, &a.phrase)
                && a.phrase.len() > noun_len.unwrap_or(0)
                && a.only_with
                    .as_ref()
                    .is_none_or(|c| self.scene_categories.contains(c.as_str()))
        })?;
        let plural = self.plural_at(i + alias.phrase.len() - 1);
        let words = alias.phrase.join(" ");
        match alias.category.as_deref() {
            Some(category) => {
                let m = push_mention(
                    out,
                    items,
                    category,
                    pending.mention_count(),
                    pending.negated || !pending.article,
                    plural,
                    pending.definite,
                    words.clone(),
                );
                if out.mentions[m].words == words {
                    out.mentions[m].zone = alias.zone.clone();
                    out.mentions[m].stand_in = true;
                }
            }
            None if !pending.negated && pending.count != Some(0) => out.unavailable.push(words),
            None => {}
        }
        Some(alias.phrase.len())
    }

    /// Whether the word at `i`, one that is also an adjective (`knowledge/vocabulary.toml`
    /// `[adjective_nouns]`: "a *safe* room"), names the object here: after an article, a count
    /// or "the", and not before another meaningful word ("a safe and cozy nursery" is an
    /// adjective, "a safe and a desk" a noun). Any other word always does.
    fn names_the_object(&self, i: usize, pending: &Pending) -> bool {
        let voc = &self.knowledge.vocabulary;
        let Some(word) = self.stems[i] else {
            return false;
        };
        if !voc.adjective_nouns.contains(word) {
            return true;
        }
        let determined = pending.count.is_some() || pending.definite;
        let content = |w: &str| !voc.filler.contains(w) && !voc.counts.contains_key(w);
        let next = self.stems.get(i + 1).copied().flatten();
        let after = self.stems.get(i + 2).copied().flatten();
        let adjective = match next {
            Some("and" | "or") => after.is_some_and(content),
            Some(w) => content(w),
            None => false,
        };
        determined && !adjective
    }

    /// A category's phrase at token `i`: its mention. Returns how many tokens it read.
    fn read_category(
        &self,
        i: usize,
        pending: &Pending,
        out: &mut Analysis,
        items: &mut Vec<Item>,
    ) -> Option<usize> {
        let (phrase, category) = self
            .knowledge
            .category_phrases()
            .iter()
            .find(|(p, _)| self.matches_at(i, p))?;
        if phrase.len() == 1 && !self.names_the_object(i, pending) {
            return None;
        }
        let plural = self.plural_at(i + phrase.len() - 1);
        let words = phrase.join(" ");
        push_mention(
            out,
            items,
            category,
            pending.mention_count(),
            pending.negated || !pending.article,
            plural,
            pending.definite,
            words,
        );
        Some(phrase.len())
    }

    /// A generic noun at token `i` ("toys", "a plant"): an earlier mention it refers to, several
    /// categories of its list for a bare plural, or the one that fits the scene best. Returns
    /// how many tokens it read.
    fn read_generic(
        &self,
        i: usize,
        word: &str,
        pending: &Pending,
        out: &mut Analysis,
        items: &mut Vec<Item>,
    ) -> Option<usize> {
        let list = self.knowledge.vocabulary.generic.get(word)?;
        let (count, negated) = (pending.count, pending.negated);
        let plural = self.plural_at(i);
        let usable: Vec<&String> = list
            .iter()
            .filter(|c| self.available.contains(*c))
            .collect();
        let earlier = out
            .mentions
            .iter()
            .rposition(|m| list.contains(&m.category));
        if pending.definite && earlier.is_some() {
            items.push(Item::Mention(earlier.unwrap_or_default()));
        } else if plural && count.is_none_or(|n| n == 0) && usable.len() > 1 {
            // "toys": several categories of the list, preferring the scene's own.
            let mut chosen: Vec<&String> = usable
                .iter()
                .copied()
                .filter(|c| self.scene_categories.contains(c.as_str()))
                .collect();
            chosen.extend(
                usable
                    .iter()
                    .copied()
                    .filter(|c| !self.scene_categories.contains(c.as_str())),
            );
            chosen.truncate(3);
            for (k, c) in chosen.into_iter().enumerate() {
                if k > 0 {
                    items.push(Item::And);
                }
                push_mention(
                    out,
                    items,
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
            .find(|c| self.scene_categories.contains(c.as_str()))
            .or(usable.first())
        {
            let c = (*c).clone();
            push_mention(
                out,
                items,
                &c,
                pending.mention_count(),
                negated || !pending.article,
                plural,
                pending.definite,
                word.to_owned(),
            );
        }
        Some(1)
    }

    /// Any other word: articles, pronouns, joints, negations and counts.
    fn read_word(&self, word: &str, pending: &mut Pending, items: &mut Vec<Item>) {
        match word {
            "the" => pending.definite = true,
            "it" | "them" => items.push(Item::Pronoun { possessive: false }),
            "its" | "their" => {
                items.push(Item::Pronoun { possessive: true });
                pending.possessive = true;
            }
            "with" | "holding" | "containing" | "featuring" | "including" => {
                pending.negated = false;
                items.push(Item::With);
            }
            "without" | "minus" | "lacking" => pending.negated = true,
            "but" => pending.negated = false,
            "no" | "zero" | "none" => {
                pending.count = Some(0);
                pending.article = false;
            }
            "and" | "plus" => items.push(Item::And),
            _ => {
                if let Some(n) = self.knowledge.vocabulary.counts.get(word) {
                    // "a few" → few wins over a; "a couple" → couple wins.
                    pending.count = Some(*n);
                    pending.article = matches!(word, "a" | "an");
                } else if let Ok(n) = word.parse::<u32>() {
                    pending.count = Some(n);
                    pending.article = false;
                } else if word.chars().all(|c| c.is_ascii_digit()) {
                    // More digits than a u32 holds.
                    pending.count = Some(u32::MAX);
                    pending.article = false;
                } else if word == "lot" {
                    pending.count = Some(6);
                }
            }
        }
    }
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

/// Phase 3: the stated relations of the item stream, into `out.stated`.
fn read_relations(out: &mut Analysis, items: &[Item], knowledge: &Knowledge) {
    let mut reader = RelationReader::default();
    for item in items.iter().chain(std::iter::once(&Item::Break)) {
        match item {
            Item::Mention(m) => reader.mention(out, *m),
            Item::And => reader.group_open = true,
            Item::With => reader.with(),
            Item::Rel(phrase, words) => reader.relation(out, phrase, words),
            Item::Pronoun { possessive } => {
                // A possessive pronoun reads like any other here (the item reader skipped
                // the part it names).
                let _ = possessive;
                reader.pronoun(out)
            }
            Item::Break => reader.clause_break(out, knowledge),
        }
    }
}

/// States `phrase` of every subject toward `target` (a mention is never related to itself).
fn emit(
    out: &mut Analysis,
    subjects: &[usize],
    phrase: &RelationPhrase,
    target: StatedTarget,
    words: &str,
) {
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
}

/// What the relation reader carries from item to item within a clause.
#[derive(Debug)]
struct RelationReader {
    /// The mentions joined by "and" so far (the subjects of the next relation phrase).
    group: Vec<usize>,
    /// Whether the next mention joins `group` rather than starting a new one.
    group_open: bool,
    /// The subjects of the clause's last relation phrase.
    last_subjects: Vec<usize>,
    /// The clause's first mention.
    head: Option<usize>,
    /// What "with" follows ("a desk with a lamp": the desk).
    with_parent: Option<usize>,
    /// The mentions after "with".
    with_members: Vec<usize>,
    in_with: bool,
    /// Whether a relation phrase already placed the "with" members.
    with_related: bool,
    /// A relation phrase waiting for its target: phrase, words and subjects.
    pending: Option<(RelationPhrase, String, Vec<usize>)>,
    /// Every mention read so far.
    seen: Vec<usize>,
}

impl Default for RelationReader {
    fn default() -> Self {
        Self {
            group: Vec::new(),
            group_open: true,
            last_subjects: Vec::new(),
            head: None,
            with_parent: None,
            with_members: Vec::new(),
            in_with: false,
            with_related: false,
            pending: None,
            seen: Vec::new(),
        }
    }
}

impl RelationReader {
    /// Whether every one of `subjects` came after "with".
    fn all_with_members(&self, subjects: &[usize]) -> bool {
        subjects.iter().all(|s| self.with_members.contains(s))
    }

    /// Mention `m`: the target of a pending phrase, or a subject of the next one.
    fn mention(&mut self, out: &mut Analysis, m: usize) {
        if let Some((phrase, words, subjects)) = self.pending.take() {
            emit(out, &subjects, &phrase, StatedTarget::Mention(m), &words);
            if self.all_with_members(&subjects) && self.in_with {
                self.with_related = true;
            }
            self.last_subjects = subjects;
            self.group.clear();
            self.group_open = false;
            self.seen.push(m);
            return;
        }
        if !self.group_open {
            self.group.clear();
        }
        self.group.push(m);
        self.group_open = false;
        self.head.get_or_insert(m);
        if self.in_with {
            self.with_members.push(m);
        }
        self.seen.push(m);
    }

    /// "with": the mentions that follow belong to the one before.
    fn with(&mut self) {
        self.with_parent = self.head.or(self.seen.last().copied());
        self.in_with = true;
        self.with_related = false;
        self.with_members.clear();
        self.group.clear();
        self.group_open = true;
        self.pending = None;
    }

    /// A relation phrase: stated at once toward a corner, a wall or the clause's head, or
    /// pending until its target is read.
    fn relation(&mut self, out: &mut Analysis, phrase: &RelationPhrase, words: &str) {
        let subjects = if self.group.is_empty() {
            self.last_subjects.clone()
        } else {
            self.group.clone()
        };
        if subjects.is_empty() {
            return;
        }
        let direct = if phrase.corner {
            Some(StatedTarget::Corner)
        } else if let Some(w) = &phrase.wall {
            Some(StatedTarget::Wall(w.clone()))
        } else if phrase.head {
            self.with_parent
                .or(self.head)
                .filter(|h| !subjects.contains(h))
                .map(StatedTarget::Mention)
        } else {
            None
        };
        match direct {
            Some(target) => {
                emit(out, &subjects, phrase, target, words);
                if self.in_with && self.all_with_members(&subjects) {
                    self.with_related = true;
                }
            }
            None if phrase.head => {}
            None => self.pending = Some((phrase.clone(), words.to_owned(), subjects.clone())),
        }
        self.last_subjects = subjects;
        self.group.clear();
        self.group_open = false;
    }

    /// A pronoun: the target of a pending phrase.
    fn pronoun(&mut self, out: &mut Analysis) {
        let Some((phrase, words, subjects)) = self.pending.take() else {
            return;
        };
        // In "X with Y inside it", "it" is X; elsewhere the latest other mention.
        let with_target = self
            .with_parent
            .filter(|p| self.in_with && !subjects.contains(p) && self.all_with_members(&subjects));
        let target = with_target.or_else(|| {
            self.seen
                .iter()
                .rev()
                .find(|m| !subjects.contains(m))
                .copied()
        });
        if let Some(target) = target {
            emit(
                out,
                &subjects,
                &phrase,
                StatedTarget::Mention(target),
                &words,
            );
            if self.in_with && self.all_with_members(&subjects) {
                self.with_related = true;
            }
        }
        self.last_subjects = subjects;
    }

    /// A clause break: the "with" members no phrase placed go on (or inside) their parent,
    /// and the clause's state is forgotten (the mentions seen are kept).
    fn clause_break(&mut self, out: &mut Analysis, knowledge: &Knowledge) {
        self.finish_with(out, knowledge);
        *self = RelationReader {
            seen: std::mem::take(&mut self.seen),
            ..RelationReader::default()
        };
    }

    /// "A desk with a lamp and books": the small members after "with" that no relation phrase
    /// placed rest on (or inside, for shelves and containers) the parent.
    fn finish_with(&self, out: &mut Analysis, knowledge: &Knowledge) {
        if !self.in_with || self.with_related {
            return;
        }
        let Some(parent) = self.with_parent else {
            return;
        };
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
        for &m in &self.with_members {
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
    }
}
