//! Cross-checking the lifted supports with the relations a model states.
//!
//! Geometry decides what holds each box up ([`crate::support`]), but a footprint half over a
//! table and a bottom a few centimetres off its top can be read either way. A vision-language
//! model looking at the image says what each object stands on, is inside or hangs on. The two
//! are reconciled per object:
//!
//! - they agree: nothing changes;
//! - geometry is ambiguous (its own relation's footprint overlap and height gap are both short of
//!   clear) and the stated relation is geometrically possible: the model's answer decides;
//! - otherwise (geometry is clear, or the stated relation is impossible: the parent is not
//!   below, the footprints do not overlap, the gap is far beyond reach) geometry wins and the
//!   disagreement is recorded.

use serde::{Deserialize, Serialize};

use crate::lifted_box::LiftedBox;
use crate::support::{SupportGuess, SupportKind, MOUNT_MIN_BOTTOM};

/// How well the lifted boxes bear out one support relation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Evidence {
    /// Footprint overlap and height gap both say so plainly.
    Clear,
    /// Possible, but overlap or gap is marginal: either reading fits the boxes.
    Marginal,
    /// Impossible for these boxes (parent not below, no overlap, a gap beyond reach).
    Contradicted,
}

/// Footprint overlap (fraction of the child's footprint over the parent's) from which an
/// `on` or `inside` relation counts as clear.
pub const CLEAR_COVER: f64 = 0.7;

/// Footprint overlap below which a box cannot rest on or in another.
pub const MIN_COVER: f64 = 0.15;

/// Who settled one object's support when the model and the geometry disagreed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Decision {
    /// The geometry was ambiguous and the model's relation is possible: the model's answer is
    /// taken.
    Model,
    /// The geometry was clear or the model's relation impossible: the geometry's is kept.
    Geometry,
}

/// One object on which the model and the geometry disagreed.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SupportCheck {
    /// The object.
    pub id: String,
    /// What the geometry inferred.
    pub geometry: SupportGuess,
    /// How well the boxes bear the geometry's relation out.
    pub geometry_evidence: Evidence,
    /// What the model stated.
    pub stated: SupportGuess,
    /// How well the boxes bear the model's relation out.
    pub stated_evidence: Evidence,
    /// Which one was kept.
    pub decision: Decision,
}

impl SupportCheck {
    /// One line for a report: the object, both relations, their evidence and who decided.
    pub fn note(&self) -> String {
        let rel = |g: &SupportGuess| match (&g.kind, &g.parent) {
            (SupportKind::Ground, _) => "on the floor".to_string(),
            (SupportKind::Unsupported, _) => "unsupported".to_string(),
            (SupportKind::Mounted, Some(w)) => format!("mounted on {w}"),
            (SupportKind::Mounted, None) => "mounted".to_string(),
            (k, Some(p)) => format!("{} {p}", kind_word(*k)),
            (k, None) => kind_word(*k).to_string(),
        };
        let ev = |e: Evidence| match e {
            Evidence::Clear => "clear",
            Evidence::Marginal => "marginal",
            Evidence::Contradicted => "contradicted",
        };
        match self.decision {
            Decision::Model => format!(
                "support of `{}`: the geometry reads `{}` ({}), the model says `{}` ({}); ambiguous geometry, the model's answer is taken",
                self.id,
                rel(&self.geometry),
                ev(self.geometry_evidence),
                rel(&self.stated),
                ev(self.stated_evidence)
            ),
            Decision::Geometry => format!(
                "support of `{}`: the model says `{}` ({}), the geometry reads `{}` ({}); the geometry is kept",
                self.id,
                rel(&self.stated),
                ev(self.stated_evidence),
                rel(&self.geometry),
                ev(self.geometry_evidence)
            ),
        }
    }
}

fn kind_word(kind: SupportKind) -> &'static str {
    match kind {
        SupportKind::Ground => "on the floor",
        SupportKind::On => "on",
        SupportKind::Inside => "inside",
        SupportKind::Under => "under",
        SupportKind::Unsupported => "unsupported",
        SupportKind::Mounted => "mounted on",
    }
}

/// Whether a stated relation says the same as the geometry's: the same parent object (on or
/// inside alike: a shelf's board is both), the floor for a box on or under something standing
/// on the floor, or a wall for one the geometry found unsupported or mounted.
pub fn agrees(geometry: &SupportGuess, stated: &SupportGuess) -> bool {
    use SupportKind::*;
    match (geometry.kind, stated.kind) {
        (Ground | Under, Ground) => true,
        (Unsupported | Mounted, Mounted) => true,
        (On | Inside, On | Inside) => geometry.parent == stated.parent,
        _ => false,
    }
}

/// How well `boxes` bear out `claim`. `gap` is the contact gap, `reach` the farthest a bottom
/// may be from a supporting top ([`crate::LiftOptions::contact_gap`],
/// [`crate::LiftOptions::support_reach`]).
pub fn evidence(boxes: &[LiftedBox], claim: &SupportGuess, gap: f64, reach: f64) -> Evidence {
    let Some(b) = boxes.iter().find(|b| b.id == claim.id) else {
        return Evidence::Contradicted;
    };
    let bottom = b.bottom();
    let foot = b.footprint();
    // Something below within reach that the box could rest on instead.
    let rest_below = || {
        boxes.iter().any(|a| {
            a.id != b.id
                && a.bottom() < bottom - 0.02
                && (bottom - a.top()).abs() <= reach
                && foot.fraction_inside(&a.footprint(), 0.05) >= 0.3
        })
    };
    match claim.kind {
        SupportKind::Ground | SupportKind::Under => {
            if bottom > reach {
                Evidence::Contradicted
            } else if bottom <= gap && !rest_below() {
                Evidence::Clear
            } else {
                Evidence::Marginal
            }
        }
        SupportKind::On | SupportKind::Inside => {
            let Some(p) = claim
                .parent
                .as_ref()
                .and_then(|p| boxes.iter().find(|a| &a.id == p))
            else {
                return Evidence::Contradicted;
            };
            if p.id == b.id || p.bottom() >= bottom - 0.02 {
                return Evidence::Contradicted;
            }
            let cover = foot.fraction_inside(&p.footprint(), 0.05);
            if cover < MIN_COVER {
                return Evidence::Contradicted;
            }
            if claim.kind == SupportKind::On {
                let top_gap = (bottom - p.top()).abs();
                if top_gap > reach {
                    Evidence::Contradicted
                } else if cover >= CLEAR_COVER && top_gap <= gap {
                    Evidence::Clear
                } else {
                    Evidence::Marginal
                }
            } else if bottom > p.top() + gap {
                Evidence::Contradicted
            } else if cover >= CLEAR_COVER && bottom < p.top() - gap && b.top() <= p.top() + gap {
                Evidence::Clear
            } else {
                Evidence::Marginal
            }
        }
        SupportKind::Mounted | SupportKind::Unsupported => {
            if bottom <= gap {
                Evidence::Contradicted
            } else if bottom > MOUNT_MIN_BOTTOM && !rest_below() {
                Evidence::Clear
            } else {
                Evidence::Marginal
            }
        }
    }
}

/// Reconciles `supports` (the geometry's, one per box) with `stated` (the model's, any subset
/// of the boxes; relations naming unknown objects are contradicted and ignored). Where geometry
/// is not clear and the stated relation is possible, the stated one replaces it in `supports`
/// (a stated wall mount without a wall id becomes [`SupportKind::Unsupported`], for the caller's
/// wall check to name the wall). Returns every disagreement, in `supports`' order.
pub fn cross_check(
    boxes: &[LiftedBox],
    supports: &mut [SupportGuess],
    stated: &[SupportGuess],
    gap: f64,
    reach: f64,
) -> Vec<SupportCheck> {
    let mut out = Vec::new();
    for guess in supports.iter_mut() {
        let Some(claim) = stated.iter().find(|s| s.id == guess.id) else {
            continue;
        };
        if agrees(guess, claim) {
            continue;
        }
        let geometry_evidence = evidence(boxes, guess, gap, reach);
        let stated_evidence = evidence(boxes, claim, gap, reach);
        let decision =
            if stated_evidence != Evidence::Contradicted && geometry_evidence != Evidence::Clear {
                Decision::Model
            } else {
                Decision::Geometry
            };
        out.push(SupportCheck {
            id: guess.id.clone(),
            geometry: guess.clone(),
            geometry_evidence,
            stated: claim.clone(),
            stated_evidence,
            decision,
        });
        if decision == Decision::Model {
            *guess = match claim.kind {
                SupportKind::Mounted if claim.parent.is_none() => SupportGuess {
                    id: claim.id.clone(),
                    parent: None,
                    kind: SupportKind::Unsupported,
                },
                SupportKind::Ground => SupportGuess {
                    id: claim.id.clone(),
                    parent: None,
                    kind: SupportKind::Ground,
                },
                _ => claim.clone(),
            };
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::support::infer_supports_within;

    fn said(id: &str, kind: SupportKind, parent: Option<&str>) -> SupportGuess {
        SupportGuess {
            id: id.into(),
            parent: parent.map(str::to_owned),
            kind,
        }
    }

    /// A table (top 0.75 m) and a cabinet beside it (top 0.9 m). A lamp is clearly on the
    /// table; a box straddles the table's edge, 40 % of its footprint over the table and 10 cm
    /// above its top: geometry reaches for the table, marginally.
    fn scene() -> (Vec<LiftedBox>, Vec<SupportGuess>) {
        let boxes = vec![
            LiftedBox::axis_aligned("table", [0.0, 0.375, 0.0], [0.6, 0.375, 0.4]),
            LiftedBox::axis_aligned("cabinet", [1.5, 0.45, 0.0], [0.3, 0.45, 0.3]),
            LiftedBox::axis_aligned("lamp", [0.1, 0.95, 0.0], [0.1, 0.2, 0.1]),
            LiftedBox::axis_aligned("box", [0.65, 0.95, 0.0], [0.125, 0.1, 0.1]),
        ];
        let supports = infer_supports_within(&boxes, 0.06, 0.3);
        (boxes, supports)
    }

    fn of<'a>(s: &'a [SupportGuess], id: &str) -> &'a SupportGuess {
        s.iter().find(|g| g.id == id).unwrap()
    }

    #[test]
    fn the_model_decides_an_ambiguous_support() {
        let (boxes, mut supports) = scene();
        assert_eq!(of(&supports, "box").parent.as_deref(), Some("table"));
        assert_eq!(
            evidence(&boxes, of(&supports, "box"), 0.06, 0.3),
            Evidence::Marginal
        );
        let stated = [said("box", SupportKind::Ground, None)];
        // Standing on the floor is impossible for a box 0.85 m up: geometry keeps the table.
        let checks = cross_check(&boxes, &mut supports, &stated, 0.06, 0.3);
        assert_eq!(checks[0].decision, Decision::Geometry);
        assert_eq!(checks[0].stated_evidence, Evidence::Contradicted);
        // Hanging on the wall is possible: the model's answer decides.
        let stated = [said("box", SupportKind::Mounted, None)];
        let checks = cross_check(&boxes, &mut supports, &stated, 0.06, 0.3);
        assert_eq!(checks.len(), 1);
        assert_eq!(checks[0].decision, Decision::Model);
        assert_eq!(of(&supports, "box").kind, SupportKind::Unsupported);
        assert!(
            checks[0].note().contains("the model's answer is taken"),
            "{}",
            checks[0].note()
        );
    }

    #[test]
    fn geometry_wins_a_clear_case_and_the_disagreement_is_recorded() {
        let (boxes, mut supports) = scene();
        let before = supports.clone();
        assert_eq!(
            evidence(&boxes, of(&supports, "lamp"), 0.06, 0.3),
            Evidence::Clear
        );
        let stated = [
            // Contradicts a clear case: the lamp is plainly on the table.
            said("lamp", SupportKind::On, Some("cabinet")),
            // Agrees: no record.
            said("table", SupportKind::Ground, None),
            // Unknown objects are ignored.
            said("ghost", SupportKind::Ground, None),
        ];
        let checks = cross_check(&boxes, &mut supports, &stated, 0.06, 0.3);
        assert_eq!(supports, before);
        assert_eq!(checks.len(), 1);
        assert_eq!(checks[0].id, "lamp");
        assert_eq!(checks[0].decision, Decision::Geometry);
        assert_eq!(checks[0].geometry_evidence, Evidence::Clear);
        let note = checks[0].note();
        assert!(
            note.contains("on cabinet") && note.contains("the geometry is kept"),
            "{note}"
        );
    }
}
