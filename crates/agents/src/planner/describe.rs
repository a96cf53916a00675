//! The up-sampled prompt: the plan's background, middle ground and foreground in words.

use std::collections::BTreeMap;

use scenethesis_scene_graph::{ParentRef, RelationKind};

use crate::plan::{Layer, PlannedObject, Zone};

/// The up-sampled prompt: each layer in words.
pub(super) fn describe(objects: &[PlannedObject], anchor: &str) -> String {
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

/// An object id without its `_N` index.
fn strip_index(id: &str) -> String {
    match id.rsplit_once('_') {
        Some((head, tail)) if tail.chars().all(|c| c.is_ascii_digit()) => head.to_owned(),
        _ => id.to_owned(),
    }
}
