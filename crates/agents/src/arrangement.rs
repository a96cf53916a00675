//! Functional arrangement: whether a scene's furniture is turned and grouped the way people use
//! it (seating faces what it serves, a bed's head is against a wall with nightstands at its
//! sides, kitchen work runs along walls, …). The rules are knowledge data
//! (`knowledge/arrangement.toml`); each is checked with the judge's relation code,
//! [`relation_holds`].

use std::sync::OnceLock;

use nalgebra::Vector2;
use scenethesis_scene_graph::{
    relation_holds, ParentRef, Relation, RelationKind, Scene, SceneObject, GROUND_ID,
};
use serde::{Deserialize, Serialize};

/// The built-in arrangement rules (TOML).
pub const ARRANGEMENT_TOML: &str = include_str!("../knowledge/arrangement.toml");

/// Seating (or a screen) faces at least one of its targets within reach.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct FacesRule {
    rule: String,
    subject: Vec<String>,
    target: Vec<String>,
    within: f64,
}

/// The subject's back is against a wall.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct AgainstRule {
    rule: String,
    subject: Vec<String>,
}

/// The subject stands at a side of its target.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct FlanksRule {
    rule: String,
    subject: Vec<String>,
    target: Vec<String>,
    within: f64,
}

/// Members along walls, each touching another.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct RunsRule {
    rule: String,
    members: Vec<String>,
    gap: f64,
}

/// The subject faces the room or stands against a wall.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct OrientedRule {
    rule: String,
    subject: Vec<String>,
}

/// The arrangement rules, as read from TOML.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ArrangementRules {
    #[serde(default)]
    faces: Vec<FacesRule>,
    #[serde(default)]
    against: Vec<AgainstRule>,
    #[serde(default)]
    flanks: Vec<FlanksRule>,
    #[serde(default)]
    runs: Vec<RunsRule>,
    #[serde(default)]
    oriented: Vec<OrientedRule>,
}

impl ArrangementRules {
    /// Parses rules from TOML (the format of `knowledge/arrangement.toml`).
    pub fn from_toml(text: &str) -> Result<Self, toml::de::Error> {
        toml::from_str(text)
    }

    /// The built-in rules.
    pub fn builtin() -> &'static Self {
        static BUILTIN: OnceLock<ArrangementRules> = OnceLock::new();
        BUILTIN.get_or_init(|| {
            Self::from_toml(ARRANGEMENT_TOML).expect("built-in arrangement.toml parses")
        })
    }

    /// Every category the rules name (for checking them against the library).
    pub fn categories(&self) -> Vec<&str> {
        let mut names: Vec<&str> = Vec::new();
        for r in &self.faces {
            names.extend(r.subject.iter().chain(&r.target).map(String::as_str));
        }
        for r in &self.against {
            names.extend(r.subject.iter().map(String::as_str));
        }
        for r in &self.flanks {
            names.extend(r.subject.iter().chain(&r.target).map(String::as_str));
        }
        for r in &self.runs {
            names.extend(r.members.iter().map(String::as_str));
        }
        for r in &self.oriented {
            names.extend(r.subject.iter().map(String::as_str));
        }
        names.sort_unstable();
        names.dedup();
        names
    }
}

/// One rule instance that does not hold.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct BrokenRule {
    /// The rule, in words.
    pub rule: String,
    /// The object it was checked on.
    pub subject: String,
    /// What was measured.
    pub reason: String,
}

/// How far a scene follows the arrangement rules; part of the judge's verdict.
#[derive(Debug, Clone, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct ArrangementCheck {
    /// Rule instances checked (one per subject object a rule applies to).
    pub checked: u32,
    /// Of those, instances that hold.
    pub held: u32,
    /// The instances that do not hold.
    pub broken: Vec<BrokenRule>,
}

impl ArrangementCheck {
    /// `held / checked`, or `None` when no rule applied.
    pub fn share(&self) -> Option<f64> {
        (self.checked > 0).then(|| f64::from(self.held) / f64::from(self.checked))
    }

    fn record(&mut self, rule: &str, subject: &str, failure: Option<String>) {
        self.checked += 1;
        match failure {
            None => self.held += 1,
            Some(reason) => self.broken.push(BrokenRule {
                rule: rule.to_owned(),
                subject: subject.to_owned(),
                reason,
            }),
        }
    }
}

/// Checks the built-in arrangement rules on a scene.
pub fn check_arrangement(scene: &Scene) -> ArrangementCheck {
    check_arrangement_with(ArrangementRules::builtin(), scene)
}

/// Checks `rules` on a scene. Only floor objects (parent: the ground) take part; a rule with
/// no subject in the scene adds nothing.
pub fn check_arrangement_with(rules: &ArrangementRules, scene: &Scene) -> ArrangementCheck {
    let floor: Vec<&SceneObject> = scene
        .objects
        .iter()
        .filter(|o| o.parent == ParentRef::Ground)
        .collect();
    let of = |names: &[String]| -> Vec<&SceneObject> {
        floor
            .iter()
            .copied()
            .filter(|o| names.contains(&o.category))
            .collect()
    };
    let holds = |o: &SceneObject, kind: RelationKind, target: &str| {
        relation_holds(scene, &o.id, &Relation::new(kind, target.to_owned())) == Some(true)
    };
    let mut check = ArrangementCheck::default();
    for r in &rules.faces {
        let targets = of(&r.target);
        for s in of(&r.subject) {
            let near: Vec<&SceneObject> = targets
                .iter()
                .copied()
                .filter(|t| t.id != s.id && gap_xz(s, t) <= r.within)
                .collect();
            if near.is_empty() {
                continue;
            }
            let failure = (!near.iter().any(|t| {
                holds(s, RelationKind::Facing, &t.id)
                    || (holds(s, RelationKind::InFrontOf, &t.id) && squarely_toward(s, t))
            }))
            .then(|| {
                format!(
                    "faces none of {}",
                    near.iter()
                        .map(|t| format!("`{}`", t.id))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            });
            check.record(&r.rule, &s.id, failure);
        }
    }
    for r in &rules.against {
        for s in of(&r.subject) {
            let failure = (!holds(s, RelationKind::AgainstWall, GROUND_ID))
                .then(|| "its back is not against a wall".to_owned());
            check.record(&r.rule, &s.id, failure);
        }
    }
    for r in &rules.flanks {
        let targets = of(&r.target);
        for s in of(&r.subject) {
            let near: Vec<&SceneObject> = targets
                .iter()
                .copied()
                .filter(|t| gap_xz(s, t) <= r.within)
                .collect();
            if near.is_empty() {
                continue;
            }
            let failure = (!near.iter().any(|t| flanks(scene, s, t))).then(|| {
                format!(
                    "stands at no side of {}",
                    near.iter()
                        .map(|t| format!("`{}`", t.id))
                        .collect::<Vec<_>>()
                        .join(", ")
                )
            });
            check.record(&r.rule, &s.id, failure);
        }
    }
    for r in &rules.runs {
        let members = of(&r.members);
        if members.len() < 2 {
            continue;
        }
        for s in &members {
            let failure = if !holds(s, RelationKind::AgainstWall, GROUND_ID) {
                Some("not against a wall".to_owned())
            } else if !members
                .iter()
                .any(|t| t.id != s.id && gap_xz(s, t) <= r.gap)
            {
                Some(format!("touches no other member within {} m", r.gap))
            } else {
                None
            };
            check.record(&r.rule, &s.id, failure);
        }
    }
    for r in &rules.oriented {
        let centre = room_centre(scene);
        for s in of(&r.subject) {
            let to_centre = centre - xz(s);
            let faces_room = to_centre.norm() < 1e-6 || front(s).dot(&to_centre) > 0.0;
            let failure = (!faces_room && !holds(s, RelationKind::AgainstWall, GROUND_ID))
                .then(|| "turned away from the room and not against a wall".to_owned());
            check.record(&r.rule, &s.id, failure);
        }
    }
    check
}

fn xz(o: &SceneObject) -> Vector2<f64> {
    let c = o.world_aabb().center();
    Vector2::new(c.x, c.z)
}

fn front(o: &SceneObject) -> Vector2<f64> {
    Vector2::new(o.pose.yaw.sin(), o.pose.yaw.cos())
}

fn right(o: &SceneObject) -> Vector2<f64> {
    Vector2::new(o.pose.yaw.cos(), -o.pose.yaw.sin())
}

/// `s` is turned within 50° of straight at `t`'s front face (its front opposite `t`'s).
fn squarely_toward(s: &SceneObject, t: &SceneObject) -> bool {
    -front(s).dot(&front(t)) >= 50f64.to_radians().cos()
}

fn gap_xz(a: &SceneObject, b: &SceneObject) -> f64 {
    let (a, b) = (a.world_aabb(), b.world_aabb());
    let dx = (b.min.x - a.max.x).max(a.min.x - b.max.x).max(0.0);
    let dz = (b.min.z - a.max.z).max(a.min.z - b.max.z).max(0.0);
    (dx * dx + dz * dz).sqrt()
}

/// `s` is beside `t` (the relation code's *beside*), off its long side rather than before its
/// foot or behind its head: across the target's width it lies outside the target's half
/// width, along its length within the target's half length.
fn flanks(scene: &Scene, s: &SceneObject, t: &SceneObject) -> bool {
    let beside = Relation::new(RelationKind::Beside, t.id.clone());
    if relation_holds(scene, &s.id, &beside) != Some(true) {
        return false;
    }
    let d = xz(s) - xz(t);
    let size = t.local_bounds.size() * t.pose.scale;
    let (half_w, half_l) = (size.x / 2.0, size.z / 2.0);
    d.dot(&right(t)).abs() >= half_w && d.dot(&front(t)).abs() <= half_l
}

/// The centre of the floor rectangle (the origin when there is no floor).
fn room_centre(scene: &Scene) -> Vector2<f64> {
    let f = &scene.architecture.floor;
    Vector2::new((f.min.x + f.max.x) / 2.0, (f.min.y + f.max.y) / 2.0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn builtin_rules_parse_and_name_known_categories() {
        let rules = ArrangementRules::builtin();
        assert!(!rules.faces.is_empty() && !rules.runs.is_empty());
        let known: Vec<&str> = scenethesis_assets::catalog::categories()
            .map(|c| c.name)
            .collect();
        for name in rules.categories() {
            assert!(known.contains(&name), "arrangement.toml names `{name}`");
        }
    }
}
