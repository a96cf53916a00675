//! Phase 5: what holds each lifted box up.
//!
//! Boxes are visited lowest first. A box whose bottom is at the floor stands on the ground; one
//! whose bottom meets another box's top within a gap tolerance, with most of its footprint over
//! that box, stands on it; one whose bottom lies between another box's bottom and top, with its
//! footprint inside, sits inside it (a shelf, a cabinet). Anything else is reported as
//! unsupported so the caller can decide (a wall-mounted object, or a lifting error).

use serde::{Deserialize, Serialize};

use crate::lifted_box::LiftedBox;

/// How a lifted box is held up.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SupportKind {
    /// Stands on the floor.
    Ground,
    /// Rests on top of its parent.
    On,
    /// Rests inside its parent (on a shelf or an inner floor).
    Inside,
    /// Stands on the floor under its parent (a basket under a table): the parent's footprint
    /// covers it and the parent's top is above it.
    Under,
    /// Nothing below it: mounted on a wall, or lifted wrongly.
    Unsupported,
}

/// The inferred support of one box.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SupportGuess {
    /// The supported box's object id.
    pub id: String,
    /// The supporting object's id; `None` for the ground or when unsupported.
    pub parent: Option<String>,
    /// How it is supported.
    pub kind: SupportKind,
}

/// The box a floor-standing box `i` stands under: the lowest-topped box taller than it whose
/// footprint covers at least 60 % of its own and that does not itself reach down around it
/// (its bottom may be on the floor, as table legs are).
fn under(boxes: &[LiftedBox], i: usize) -> Option<usize> {
    let b = &boxes[i];
    let foot = b.footprint();
    let mut best: Option<usize> = None;
    for (j, a) in boxes.iter().enumerate() {
        if j == i || a.top() <= b.top() + 0.02 || foot.fraction_inside(&a.footprint(), 0.0) < 0.6 {
            continue;
        }
        // The covering box must be wider than the one under it.
        if a.footprint().area() <= foot.area() {
            continue;
        }
        if best.is_none_or(|k| a.top() < boxes[k].top()) {
            best = Some(j);
        }
    }
    best
}

/// Infers the support of every box. `gap` is the largest vertical gap in metres between a
/// child's bottom and its parent's top (or the floor) that still counts as contact.
pub fn infer_supports(boxes: &[LiftedBox], gap: f64) -> Vec<SupportGuess> {
    let mut order: Vec<usize> = (0..boxes.len()).collect();
    order.sort_by(|&a, &b| {
        boxes[a]
            .bottom()
            .total_cmp(&boxes[b].bottom())
            .then(boxes[a].id.cmp(&boxes[b].id))
    });
    let mut out = Vec::with_capacity(boxes.len());
    for &i in &order {
        let b = &boxes[i];
        let bottom = b.bottom();
        let foot = b.footprint();
        // (score, parent index, kind): smaller score wins.
        let mut best: Option<(f64, usize, SupportKind)> = None;
        for (j, a) in boxes.iter().enumerate() {
            // A parent starts clearly lower (2 cm): side-by-side objects do not hold each other.
            if j == i || a.bottom() >= bottom - 0.02 {
                continue;
            }
            let cover = foot.fraction_inside(&a.footprint(), 0.05);
            let top_gap = (bottom - a.top()).abs();
            let candidate = if top_gap <= gap && cover >= 0.5 {
                Some((top_gap, SupportKind::On))
            } else if bottom > a.bottom() + 1e-3
                && bottom < a.top() - gap
                && b.top() <= a.top() + gap
                && cover >= 0.6
            {
                // Inside: rank by how close the bottom is to the parent's inner floor.
                Some((gap + (bottom - a.bottom()), SupportKind::Inside))
            } else {
                None
            };
            if let Some((score, kind)) = candidate {
                if best.is_none_or(|(s, _, _)| score < s) {
                    best = Some((score, j, kind));
                }
            }
        }
        let guess = match best {
            _ if bottom <= gap => match under(boxes, i) {
                Some(j) => SupportGuess {
                    id: b.id.clone(),
                    parent: Some(boxes[j].id.clone()),
                    kind: SupportKind::Under,
                },
                None => SupportGuess {
                    id: b.id.clone(),
                    parent: None,
                    kind: SupportKind::Ground,
                },
            },
            Some((_, j, kind)) => SupportGuess {
                id: b.id.clone(),
                parent: Some(boxes[j].id.clone()),
                kind,
            },
            None => SupportGuess {
                id: b.id.clone(),
                parent: None,
                kind: SupportKind::Unsupported,
            },
        };
        out.push(guess);
    }
    out.sort_by(|a, b| a.id.cmp(&b.id));
    out
}
