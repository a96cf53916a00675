//! Looks in prompts: the colour, material and style words of `knowledge/looks.toml`, and
//! reading them off a prompt — which object or room surface each colour or material word
//! qualifies ("a red leather sofa", "the sofa is red", "with oak floors", "walls painted
//! white"), which style the room has, and which look words the library cannot do.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::OnceLock;

use scenethesis_procedural::looks::{named_material, Palette};
use scenethesis_scene_graph::{LookScope, Srgb};
use serde::Deserialize;

use crate::knowledge::KnowledgeError;
use crate::text::phrase_stems;

/// The embedded looks file.
pub const LOOKS_TOML: &str = include_str!("../knowledge/looks.toml");
const LOOKS_FILE: &str = "knowledge/looks.toml";

/// The room surfaces a prompt can qualify.
pub const SURFACES: [&str; 3] = ["floor", "walls", "ceiling"];

/// What a material word makes the parts it qualifies.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct MaterialWord {
    /// The entry's name in the file (`oak`, `leather`, `velvet`).
    pub name: String,
    /// A palette entry the parts become.
    pub entry: Option<String>,
    /// A palette family whose entry the room's style (or `default`) chooses.
    pub family: Option<String>,
    /// The family's entry when the style has none.
    pub default: Option<String>,
    /// A fabric token the parts take on in their own colour.
    pub token: Option<String>,
    /// Which parts it qualifies.
    pub scope: LookScope,
}

/// One style: its words and the palette entries its rooms choose from.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Style {
    /// The style's name (`scandinavian`).
    pub name: String,
    /// The words naming it, as stems.
    pub words: Vec<Vec<String>>,
    /// Per palette family, the entries a room of the style chooses one of.
    pub families: BTreeMap<String, Vec<String>>,
    /// Per surface (`floor`, `walls`, `ceiling`), the entries a room chooses one of.
    pub surfaces: BTreeMap<String, Vec<String>>,
}

/// The look vocabulary.
#[derive(Debug, Clone, PartialEq)]
pub struct Looks {
    /// Colour words (stems) and their colours.
    pub colors: BTreeMap<String, Srgb>,
    /// Words that lighten (positive share of white) or darken (negative: black) a colour.
    pub modifiers: BTreeMap<String, f32>,
    /// Material phrases (stems), longest first, and what each does.
    pub materials: Vec<(Vec<String>, MaterialWord)>,
    /// Look words the library cannot do.
    pub unavailable: BTreeSet<String>,
    /// Surface words (stems) and the surface each names.
    pub surfaces: BTreeMap<String, String>,
    /// Each surface's material without a style or a prompt word.
    pub surface_defaults: BTreeMap<String, String>,
    /// The styles, in name order.
    pub styles: Vec<Style>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct LooksFile {
    colors: BTreeMap<String, String>,
    color_modifiers: BTreeMap<String, f32>,
    materials: BTreeMap<String, RawMaterial>,
    unavailable: RawWords,
    surfaces: BTreeMap<String, Vec<String>>,
    surface_defaults: BTreeMap<String, String>,
    styles: BTreeMap<String, BTreeMap<String, Vec<String>>>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawWords {
    words: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    words: Vec<String>,
    #[serde(default)]
    entry: Option<String>,
    #[serde(default)]
    family: Option<String>,
    #[serde(default)]
    default: Option<String>,
    #[serde(default)]
    token: Option<String>,
    scope: LookScope,
}

fn invalid(entry: impl Into<String>, message: impl Into<String>) -> KnowledgeError {
    KnowledgeError::Invalid {
        file: LOOKS_FILE,
        entry: entry.into(),
        message: message.into(),
    }
}

/// Checks that `entry` is a palette entry, of `family` when given.
fn check_entry(at: &str, entry: &str, family: Option<&str>) -> Result<(), KnowledgeError> {
    let (palette, _) = named_material(entry).ok_or_else(|| {
        invalid(
            at,
            format!("`{entry}` is no palette entry of the procedural library"),
        )
    })?;
    match family {
        Some(f) if palette.name() != f => Err(invalid(
            at,
            format!("`{entry}` is a `{}` entry, not `{f}`", palette.name()),
        )),
        _ => Ok(()),
    }
}

fn single_stem(word: &str) -> String {
    phrase_stems(word).join(" ")
}

impl Looks {
    /// The vocabulary embedded in this build (parsed once).
    ///
    /// # Panics
    /// Never in a released build: the embedded file is checked by this crate's tests.
    pub fn builtin() -> &'static Looks {
        static BUILTIN: OnceLock<Looks> = OnceLock::new();
        BUILTIN.get_or_init(|| {
            Looks::from_toml(LOOKS_TOML)
                .unwrap_or_else(|e| panic!("embedded looks knowledge is broken: {e}"))
        })
    }

    /// Reads and checks a looks file: colours are `#rrggbb`, every material named is a
    /// palette entry (of its family), every style's entries belong to the family or surface
    /// they are listed under.
    pub fn from_toml(text: &str) -> Result<Looks, KnowledgeError> {
        let file: LooksFile = toml::from_str(text).map_err(|e| KnowledgeError::Parse {
            file: LOOKS_FILE,
            message: e.to_string(),
        })?;
        let mut colors = BTreeMap::new();
        for (word, hex) in &file.colors {
            let colour = Srgb::parse(hex)
                .ok_or_else(|| invalid(format!("colors.{word}"), "expected \"#rrggbb\""))?;
            colors.insert(single_stem(word), colour);
        }
        let modifiers = file
            .color_modifiers
            .iter()
            .map(|(w, s)| (single_stem(w), *s))
            .collect();
        let mut materials = Vec::new();
        for (name, raw) in file.materials {
            let at = format!("materials.{name}");
            materials.extend(Self::material(&at, &name, raw)?);
        }
        materials.sort_by(|a, b| b.0.len().cmp(&a.0.len()).then(a.0.cmp(&b.0)));
        let mut surfaces = BTreeMap::new();
        for (surface, words) in &file.surfaces {
            if !SURFACES.contains(&surface.as_str()) {
                return Err(invalid(
                    format!("surfaces.{surface}"),
                    "expected floor, walls or ceiling",
                ));
            }
            for w in words {
                surfaces.insert(single_stem(w), surface.clone());
            }
        }
        for (surface, entry) in &file.surface_defaults {
            check_entry(&format!("surface_defaults.{surface}"), entry, None)?;
        }
        let mut styles = Vec::new();
        for (name, mut table) in file.styles {
            styles.push(Self::style(&name, &mut table)?);
        }
        Ok(Looks {
            colors,
            modifiers,
            materials,
            unavailable: file
                .unavailable
                .words
                .iter()
                .map(|w| single_stem(w))
                .collect(),
            surfaces,
            surface_defaults: file.surface_defaults,
            styles,
        })
    }

    fn material(
        at: &str,
        name: &str,
        raw: RawMaterial,
    ) -> Result<Vec<(Vec<String>, MaterialWord)>, KnowledgeError> {
        if let Some(entry) = &raw.entry {
            check_entry(at, entry, None)?;
        }
        if let Some(family) = &raw.family {
            if Palette::from_name(family).is_none() {
                return Err(invalid(at, format!("`{family}` is no palette family")));
            }
            let default = raw.default.as_deref().ok_or_else(|| {
                invalid(
                    at,
                    "a `family` needs a `default` entry for rooms without a style",
                )
            })?;
            check_entry(at, default, Some(family))?;
        }
        if [
            raw.entry.is_some(),
            raw.family.is_some(),
            raw.token.is_some(),
        ]
        .iter()
        .filter(|b| **b)
        .count()
            != 1
        {
            return Err(invalid(
                at,
                "give exactly one of `entry`, `family`, `token`",
            ));
        }
        let word = MaterialWord {
            name: name.to_owned(),
            entry: raw.entry,
            family: raw.family,
            default: raw.default,
            token: raw.token,
            scope: raw.scope,
        };
        Ok(raw
            .words
            .iter()
            .map(|w| (phrase_stems(w), word.clone()))
            .collect())
    }

    fn style(
        name: &str,
        table: &mut BTreeMap<String, Vec<String>>,
    ) -> Result<Style, KnowledgeError> {
        let at = format!("styles.{name}");
        let words = table
            .remove("words")
            .ok_or_else(|| invalid(&at, "a style needs `words`"))?;
        let mut style = Style {
            name: name.to_owned(),
            words: words.iter().map(|w| phrase_stems(w)).collect(),
            families: BTreeMap::new(),
            surfaces: BTreeMap::new(),
        };
        for (key, entries) in std::mem::take(table) {
            let key_at = format!("{at}.{key}");
            if entries.is_empty() {
                return Err(invalid(&key_at, "an empty list"));
            }
            if SURFACES.contains(&key.as_str()) {
                for e in &entries {
                    check_entry(&key_at, e, None)?;
                }
                style.surfaces.insert(key, entries);
            } else if Palette::from_name(&key).is_some() {
                for e in &entries {
                    check_entry(&key_at, e, Some(&key))?;
                }
                style.families.insert(key, entries);
            } else {
                return Err(invalid(
                    &key_at,
                    "expected `words`, a palette family or floor / walls / ceiling",
                ));
            }
        }
        Ok(style)
    }

    /// The style named `name`.
    pub fn style_named(&self, name: &str) -> Option<&Style> {
        self.styles.iter().find(|s| s.name == name)
    }

    /// Whether the stem is a look word of any kind (colour, modifier, material word,
    /// unavailable look word).
    pub fn is_look_word(&self, stem: &str) -> bool {
        self.colors.contains_key(stem)
            || self.modifiers.contains_key(stem)
            || self.unavailable.contains(stem)
            || self
                .materials
                .iter()
                .any(|(p, _)| p.len() == 1 && p[0] == stem)
    }
}

/// What a look word of the prompt is.
#[derive(Debug, Clone, PartialEq)]
pub(crate) enum LookWord {
    /// A colour (modifiers applied) and its name (`dark_grey`).
    Color(Srgb, String),
    /// A material word.
    Material(MaterialWord),
    /// A look word the library cannot do.
    Unavailable,
}

/// One look word read off the prompt, with its words.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ReadWord {
    /// The prompt's words (stems joined by spaces).
    pub words: String,
    /// What it is.
    pub word: LookWord,
}

/// What an attribute qualifies.
#[derive(Debug, Clone, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) enum LookTarget {
    /// A mention of the prompt, by index.
    Mention(usize),
    /// A room surface (`floor`, `walls`, `ceiling`).
    Surface(String),
}

/// Everything the prompt says about looks.
#[derive(Debug, Clone, PartialEq, Default)]
pub(crate) struct ReadLooks {
    /// The look words of each target, in prompt order.
    pub attributes: Vec<(LookTarget, ReadWord)>,
    /// The style the prompt names and its words.
    pub style: Option<(String, String)>,
}

/// Mixes a colour with white (`share > 0`) or black (`share < 0`).
fn modified(colour: Srgb, share: f32) -> Srgb {
    let towards = if share > 0.0 { 255.0 } else { 0.0 };
    let t = share.abs().clamp(0.0, 1.0);
    Srgb(
        colour
            .0
            .map(|c| (c as f32 + t * (towards - c as f32)).round() as u8),
    )
}

/// Reads looks off a prompt's stems (`None` for a clause break), given the token spans of
/// its object nouns (start, length, mention).
pub(crate) fn read_looks(
    looks: &Looks,
    stems: &[Option<&str>],
    nouns: &[(usize, usize, usize)],
) -> ReadLooks {
    let mut out = ReadLooks::default();
    let mut spans: Vec<(usize, usize, LookTarget)> = nouns
        .iter()
        .map(|&(s, l, m)| (s, l, LookTarget::Mention(m)))
        .collect();
    for (i, stem) in stems.iter().enumerate() {
        let Some(stem) = stem else { continue };
        let inside = nouns.iter().any(|&(s, l, _)| i >= s && i < s + l);
        if let (Some(surface), false) = (looks.surfaces.get(*stem), inside) {
            spans.push((i, 1, LookTarget::Surface(surface.clone())));
        }
    }
    spans.sort_by_key(|s| s.0);
    let mut used = vec![false; stems.len()];
    for (start, len, target) in &spans {
        // Words inside the noun's own phrase ("*wooden* chair"), then before it, then a
        // predicate after it ("the sofa is red", "walls painted white").
        let mut words = Vec::new();
        let mut before = *start;
        while before > 0 {
            match look_before(looks, stems, before, &used) {
                Some((from, word)) => {
                    words.push((from, before - from, word));
                    before = from;
                }
                None => break,
            }
        }
        words.reverse();
        let mut i = *start;
        while i + 1 < start + len {
            match look_at(looks, stems, i) {
                Some((n, word)) => {
                    words.push((i, n, word));
                    i += n;
                }
                None => i += 1,
            }
        }
        words.extend(predicate(looks, stems, start + len, &used));
        for (at, n, word) in words {
            if used[at..at + n].iter().any(|u| *u) {
                continue;
            }
            used[at..at + n].iter_mut().for_each(|u| *u = true);
            out.attributes.push((target.clone(), word));
        }
    }
    out.style = read_style(looks, stems);
    out
}

/// The look word ending just before token `end` (a colour with its modifier, a material
/// phrase, an unavailable word, or an unknown word written `<word>-coloured`).
fn look_before(
    looks: &Looks,
    stems: &[Option<&str>],
    end: usize,
    used: &[bool],
) -> Option<(usize, ReadWord)> {
    for from in end.saturating_sub(3)..end {
        if used[from..end].iter().any(|u| *u) {
            continue;
        }
        if let Some((n, word)) = look_at(looks, stems, from) {
            if from + n == end {
                return Some((from, word));
            }
        }
    }
    // "<word>-coloured" (or "-colored"): a colour word, known or not.
    let last = stems[end - 1]?;
    if matches!(last, "coloured" | "colored" | "colour" | "color") && end >= 2 {
        let colour = stems[end - 2]?;
        return Some((
            end - 2,
            ReadWord {
                words: format!("{colour} {last}"),
                word: match looks.colors.get(colour) {
                    Some(c) => LookWord::Color(*c, colour.to_owned()),
                    None => LookWord::Unavailable,
                },
            },
        ));
    }
    None
}

/// The look word starting at token `i` and its length in tokens.
fn look_at(looks: &Looks, stems: &[Option<&str>], i: usize) -> Option<(usize, ReadWord)> {
    let word = stems.get(i).copied().flatten()?;
    if let Some(share) = looks.modifiers.get(word) {
        let next = stems.get(i + 1).copied().flatten()?;
        let colour = looks.colors.get(next)?;
        return Some((
            2,
            ReadWord {
                words: format!("{word} {next}"),
                word: LookWord::Color(modified(*colour, *share), format!("{word}_{next}")),
            },
        ));
    }
    let material = looks.materials.iter().find(|(phrase, _)| {
        phrase
            .iter()
            .enumerate()
            .all(|(k, w)| stems.get(i + k).copied().flatten() == Some(w.as_str()))
    });
    if let Some((phrase, m)) = material {
        return Some((
            phrase.len(),
            ReadWord {
                words: phrase.join(" "),
                word: LookWord::Material(m.clone()),
            },
        ));
    }
    if let Some(colour) = looks.colors.get(word) {
        return Some((
            1,
            ReadWord {
                words: word.to_owned(),
                word: LookWord::Color(*colour, word.to_owned()),
            },
        ));
    }
    looks.unavailable.contains(word).then(|| {
        (
            1,
            ReadWord {
                words: word.to_owned(),
                word: LookWord::Unavailable,
            },
        )
    })
}

/// The look words of a predicate starting at token `i`: "is / are [painted | made of | in]
/// <look words>", "painted <colour>", "made of <material>", up to the clause's end.
fn predicate(
    looks: &Looks,
    stems: &[Option<&str>],
    mut i: usize,
    used: &[bool],
) -> Vec<(usize, usize, ReadWord)> {
    let at = |k: usize| stems.get(k).copied().flatten();
    let mut linked = false;
    if matches!(at(i), Some("is" | "are" | "was" | "were")) {
        i += 1;
        linked = true;
    }
    let mut open_material = false;
    match (at(i), at(i + 1)) {
        (Some("painted" | "finished" | "done" | "in"), _) => {
            i += 1;
            linked = true;
        }
        (Some("made"), Some("of" | "from")) => {
            i += 2;
            linked = true;
            open_material = true;
        }
        _ => {}
    }
    if !linked {
        return Vec::new();
    }
    let mut out = Vec::new();
    while i < stems.len() && !used[i] {
        if matches!(at(i), Some("and" | "all" | "entirely" | "fully")) && !out.is_empty() {
            i += 1;
            continue;
        }
        match look_at(looks, stems, i) {
            Some((n, word)) => {
                out.push((i, n, word));
                i += n;
            }
            None if open_material && out.is_empty() => {
                // "made of bamboo": a material word the vocabulary does not know.
                if let Some(w) = at(i) {
                    out.push((
                        i,
                        1,
                        ReadWord {
                            words: w.to_owned(),
                            word: LookWord::Unavailable,
                        },
                    ));
                }
                break;
            }
            None => break,
        }
    }
    out
}

/// The first style word of the prompt.
fn read_style(looks: &Looks, stems: &[Option<&str>]) -> Option<(String, String)> {
    (0..stems.len()).find_map(|i| {
        looks.styles.iter().find_map(|style| {
            style
                .words
                .iter()
                .find(|phrase| {
                    phrase
                        .iter()
                        .enumerate()
                        .all(|(k, w)| stems.get(i + k).copied().flatten() == Some(w.as_str()))
                })
                .map(|phrase| (style.name.clone(), phrase.join(" ")))
        })
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_embedded_looks_parse_and_name_palette_entries() {
        let looks = Looks::builtin();
        assert!(looks.colors.len() >= 40);
        assert!(looks.styles.len() >= 6);
        assert!(looks.style_named("scandinavian").is_some());
        assert!(looks.is_look_word("leather"));
        assert!(!looks.is_look_word("sofa"));
    }

    #[test]
    fn a_bad_entry_is_refused_naming_it() {
        let text = LOOKS_TOML.replace("entry = \"oak\"", "entry = \"unobtainium\"");
        let e = Looks::from_toml(&text).unwrap_err().to_string();
        assert!(
            e.contains("materials.oak") && e.contains("unobtainium"),
            "{e}"
        );
        let text = LOOKS_TOML.replace(
            "wood = [\"ash\", \"pine\", \"maple\"]",
            "wood = [\"white_paint\"]",
        );
        let e = Looks::from_toml(&text).unwrap_err().to_string();
        assert!(e.contains("styles.scandinavian.wood"), "{e}");
    }

    #[test]
    fn modifiers_darken_and_lighten() {
        let grey = Srgb([0x80, 0x80, 0x80]);
        assert!(modified(grey, -0.5).0[0] < 0x80);
        assert!(modified(grey, 0.5).0[0] > 0x80);
    }
}
