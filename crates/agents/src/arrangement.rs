//! Functional arrangement: whether a scene's furniture is turned and grouped the way people use
//! it (seating faces what it serves, a bed's head is against a wall with nightstands at its
//! sides, kitchen work runs along walls, …). The rules are knowledge data
//! (`knowledge/arrangement.toml`); each is checked with the judge's relation code,
//! [`relation_holds`].

use std::sync::OnceLock;

use nalgebra::Vector2;
use scenethesis_scene_graph::{
    floor_centre, floor_gap, front_dir, relation_holds, right_dir, ParentRef, Relation,
    RelationKind, Scene, SceneObject, GROUND_ID,
};
use serde::{Deserialize, Serialize};

/// The built-in arrangement rules (TOML).
pub const ARRANGEMENT_TOML: &str = include_str!("../knowledge/arrangement.toml");

/// Seating (or a screen) faces at least one of its targets within reach.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct FacesRule {
    rule: String,
    /// `reject` (default): a broken instance fails the judge; `report`: only reported.
    #[serde(default)]
    judge: Severity,
    subject: Vec<String>,
    target: Vec<String>,
    within: f64,
}

/// The subject's back is against a wall.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct AgainstRule {
    rule: String,
    /// `reject` (default): a broken instance fails the judge; `report`: only reported.
    #[serde(default)]
    judge: Severity,
    subject: Vec<String>,
}

/// The subject stands at a side of its target.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct FlanksRule {
    rule: String,
    /// `reject` (default): a broken instance fails the judge; `report`: only reported.
    #[serde(default)]
    judge: Severity,
    subject: Vec<String>,
    target: Vec<String>,
    within: f64,
}

/// Members along walls, each touching another; also what the procedural guide builds runs
/// from (`crate::guide`).
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RunsRule {
    pub(crate) rule: String,
    /// `reject` (default): a broken instance fails the judge; `report`: only reported.
    #[serde(default)]
    judge: Severity,
    /// The categories that form the runs.
    pub(crate) members: Vec<String>,
    /// The rule applies only to scenes with one of these on the floor (empty: always).
    #[serde(default)]
    pub(crate) with: Vec<String>,
    /// Largest box gap between touching members, in metres.
    pub(crate) gap: f64,
    /// Members that stand at the ends of a run (tall units that would break the worktop).
    #[serde(default)]
    pub(crate) ends: Vec<String>,
    /// Wall-mounted categories that hang above the run.
    #[serde(default)]
    pub(crate) above: Vec<String>,
    /// Free-standing categories that stand in front of the run, facing it.
    #[serde(default)]
    pub(crate) island: Vec<String>,
    /// Run shapes a prompt may name: `one-wall`, `l-shaped`, `u-shaped`, `galley`, each with
    /// the phrases that name it.
    #[serde(default)]
    pub(crate) shapes: std::collections::BTreeMap<String, Vec<String>>,
}

impl RunsRule {
    /// Whether the rule applies to a scene holding `categories` on the floor: two or more
    /// members and one of the `with` categories.
    pub(crate) fn applies<'a>(
        &self,
        categories: impl IntoIterator<Item = &'a str> + Clone,
    ) -> bool {
        let members = categories
            .clone()
            .into_iter()
            .filter(|c| self.members.iter().any(|m| m == c))
            .count();
        members >= 2
            && (self.with.is_empty()
                || categories
                    .into_iter()
                    .any(|c| self.with.iter().any(|w| w == c)))
    }
}

/// The categories any of which stands for a room's anchor of category `anchor` (the object
/// its room type is built around: a bedroom's bed): the anchor's own, and, when it is a member
/// of a built-in `[[runs]]` rule (a kitchen's counter), every member of those runs, as the
/// runs are the room's core and the guide may leave out a counter to fit the others.
///
/// ```
/// let core = scenethesis_agents::core_categories("kitchen_counter");
/// assert!(core.iter().any(|c| c == "stove") && core[0] == "kitchen_counter");
/// assert_eq!(scenethesis_agents::core_categories("bed"), ["bed"]);
/// ```
pub fn core_categories(anchor: &str) -> Vec<String> {
    let mut out = vec![anchor.to_owned()];
    for r in &ArrangementRules::builtin().runs {
        if r.members.iter().any(|m| m == anchor) {
            out.extend(r.members.iter().filter(|m| *m != anchor).cloned());
        }
    }
    out
}

/// The subject faces the room or stands against a wall.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
struct OrientedRule {
    rule: String,
    /// `reject` (default): a broken instance fails the judge; `report`: only reported.
    #[serde(default)]
    judge: Severity,
    subject: Vec<String>,
}

/// The subject is of use only with one of its targets: a dining chair with a table it serves,
/// a monitor on a desk, a television with seating before it. Unlike the other rules it also
/// applies to supported objects; the planner adds a missing target to a plan
/// (`crate::planner`), and the judge rejects a scene where a subject has none.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct NeedsRule {
    pub(crate) rule: String,
    /// `reject` (default): a broken instance fails the judge; `report`: only reported.
    #[serde(default)]
    judge: Severity,
    /// The categories that need a target.
    pub(crate) subject: Vec<String>,
    /// The categories that serve them, the planner's choice first.
    pub(crate) target: Vec<String>,
    /// Largest box gap on the floor between the subject (or the floor object carrying it) and
    /// a target, in metres; a target carrying the subject always serves it.
    pub(crate) within: f64,
    /// The rule does not apply to scenes holding one of these (a shop, where a television is
    /// goods for sale).
    #[serde(default)]
    pub(crate) except_with: Vec<String>,
}

impl NeedsRule {
    /// Whether the rule applies to a scene (or plan) holding `categories`.
    pub(crate) fn applies<'a>(&self, mut categories: impl Iterator<Item = &'a str>) -> bool {
        !categories.any(|c| self.except_with.iter().any(|e| e == c))
    }
}

/// What a broken instance of a rule means for the judge.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
#[serde(rename_all = "kebab-case")]
enum Severity {
    /// The judge rejects the scene (and the pipeline re-plans).
    #[default]
    Reject,
    /// Reported in the verdict only.
    Report,
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
    pub(crate) runs: Vec<RunsRule>,
    #[serde(default)]
    oriented: Vec<OrientedRule>,
    #[serde(default)]
    pub(crate) needs: Vec<NeedsRule>,
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

    /// The judged `faces` rules `category` is a subject of, as (targets, within metres): the
    /// procedural guide puts such an object where it faces a target near it, and the vision
    /// guide turns a recovered one toward the nearest target it sees.
    ///
    /// ```
    /// use scenethesis_agents::arrangement::ArrangementRules;
    /// let rules = ArrangementRules::builtin().faces_of("bar_stool");
    /// assert!(rules.iter().any(|(targets, _)| targets.iter().any(|t| t == "bar_counter")));
    /// ```
    pub fn faces_of(&self, category: &str) -> Vec<(&[String], f64)> {
        self.faces
            .iter()
            .filter(|r| r.judge == Severity::Reject && r.subject.iter().any(|c| c == category))
            .map(|r| (r.target.as_slice(), r.within))
            .collect()
    }

    /// The judged `faces` rules `category` is a target of: each rule's subjects and reach.
    pub(crate) fn served_by(&self, category: &str) -> Vec<(&[String], f64)> {
        self.faces
            .iter()
            .filter(|r| r.judge == Severity::Reject && r.target.iter().any(|c| c == category))
            .map(|r| (r.subject.as_slice(), r.within))
            .collect()
    }

    /// Whether a judged `flanks` rule makes `subject` stand at a side of `target` (a
    /// nightstand off a bed's long side): the procedural guide then tries no spot before
    /// the target's foot or behind its head in a house room (a room with fixed walls).
    pub(crate) fn must_flank(&self, subject: &str, target: &str) -> bool {
        self.flanks.iter().any(|r| {
            r.judge == Severity::Reject
                && r.subject.iter().any(|c| c == subject)
                && r.target.iter().any(|c| c == target)
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
            names.extend(
                r.members
                    .iter()
                    .chain(&r.with)
                    .chain(&r.ends)
                    .chain(&r.above)
                    .chain(&r.island)
                    .map(String::as_str),
            );
        }
        for r in &self.oriented {
            names.extend(r.subject.iter().map(String::as_str));
        }
        for r in &self.needs {
            names.extend(
                r.subject
                    .iter()
                    .chain(&r.target)
                    .chain(&r.except_with)
                    .map(String::as_str),
            );
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
    /// Whether the judge rejects a scene for it (`false`: the rule is only reported, see
    /// `knowledge/arrangement.toml`).
    #[serde(default = "yes")]
    pub rejects: bool,
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
    /// The layout of the scene's runs ([`run_layout`]: `one-wall`, `l-shaped`, `u-shaped`,
    /// `galley`), when a run rule applies.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub layout: Option<String>,
}

impl ArrangementCheck {
    /// `held / checked`, or `None` when no rule applied.
    pub fn share(&self) -> Option<f64> {
        (self.checked > 0).then(|| f64::from(self.held) / f64::from(self.checked))
    }

    fn record(&mut self, rule: &str, judge: Severity, subject: &str, failure: Option<String>) {
        self.checked += 1;
        match failure {
            None => self.held += 1,
            Some(reason) => self.broken.push(BrokenRule {
                rule: rule.to_owned(),
                rejects: judge == Severity::Reject,
                subject: subject.to_owned(),
                reason,
            }),
        }
    }
}

/// The layout of a scene's runs (`[[runs]]` rules that apply), named by the walls their members
/// stand against: `one-wall` (the back wall), `l-shaped` (the back wall and a side wall),
/// `u-shaped` (the back wall and both side walls), `galley` (the back wall and the door wall),
/// else the list of walls; `None` when no run rule applies.
pub fn run_layout(scene: &Scene) -> Option<String> {
    let floor: Vec<&SceneObject> = scene
        .objects
        .iter()
        .filter(|o| o.parent == ParentRef::Ground)
        .collect();
    let rule = ArrangementRules::builtin()
        .runs
        .iter()
        .find(|r| r.applies(floor.iter().map(|o| o.category.as_str())))?;
    let walls: std::collections::BTreeSet<&str> = floor
        .iter()
        .filter(|o| rule.members.contains(&o.category))
        .filter_map(|o| {
            o.relations
                .iter()
                .find(|r| r.kind == RelationKind::AgainstWall)
                .map(|r| r.target.as_str())
        })
        .collect();
    let walls: Vec<&str> = walls.into_iter().collect();
    Some(match walls.as_slice() {
        ["wall_0"] => "one-wall".to_owned(),
        ["wall_0", "wall_1"] | ["wall_0", "wall_3"] => "l-shaped".to_owned(),
        ["wall_0", "wall_1", "wall_3"] => "u-shaped".to_owned(),
        ["wall_0", "wall_2"] => "galley".to_owned(),
        other => other.join("+"),
    })
}

fn yes() -> bool {
    true
}

/// Checks the built-in arrangement rules on a scene.
pub fn check_arrangement(scene: &Scene) -> ArrangementCheck {
    check_arrangement_with(ArrangementRules::builtin(), scene)
}

/// Checks `rules` on a scene. Only floor objects (parent: the ground) take part, but for
/// `needs` rules, whose subjects may stand on others; a rule with no subject in the scene adds
/// nothing.
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
                .filter(|t| t.id != s.id && floor_gap(s, t) <= r.within)
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
            check.record(&r.rule, r.judge, &s.id, failure);
        }
    }
    for r in &rules.against {
        for s in of(&r.subject) {
            let failure = (!holds(s, RelationKind::AgainstWall, GROUND_ID))
                .then(|| "its back is not against a wall".to_owned());
            check.record(&r.rule, r.judge, &s.id, failure);
        }
    }
    for r in &rules.flanks {
        let targets = of(&r.target);
        for s in of(&r.subject) {
            let near: Vec<&SceneObject> = targets
                .iter()
                .copied()
                .filter(|t| floor_gap(s, t) <= r.within)
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
            check.record(&r.rule, r.judge, &s.id, failure);
        }
    }
    for r in &rules.runs {
        if !r.applies(floor.iter().map(|o| o.category.as_str())) {
            continue;
        }
        let members = of(&r.members);
        for s in &members {
            let failure = if !holds(s, RelationKind::AgainstWall, GROUND_ID) {
                Some("not against a wall".to_owned())
            } else if !members
                .iter()
                .any(|t| t.id != s.id && floor_gap(s, t) <= r.gap)
            {
                Some(format!("touches no other member within {} m", r.gap))
            } else {
                None
            };
            check.record(&r.rule, r.judge, &s.id, failure);
        }
    }
    for r in &rules.oriented {
        let centre = room_centre(scene);
        let front = room_front(scene);
        for s in of(&r.subject) {
            let to_centre = centre - floor_centre(s);
            let faces_room = to_centre.norm() < 1e-6 || front_dir(s).dot(&to_centre) > 0.0;
            let failure = (!faces_room
                && !holds(s, RelationKind::AgainstWall, GROUND_ID)
                && !front.as_ref().is_some_and(|f| f.rows_toward(s)))
            .then(|| {
                "turned away from the room, not against a wall and not in a row facing the \
                 room's front"
                    .to_owned()
            });
            check.record(&r.rule, r.judge, &s.id, failure);
        }
    }
    check_needs(rules, scene, &mut check);
    check.layout = run_layout(scene);
    check
}

/// Checks the `needs` rules: every subject, on the floor or carried, has a target carrying it,
/// or on the floor or a wall within the rule's reach of the floor object it stands on.
fn check_needs(rules: &ArrangementRules, scene: &Scene, check: &mut ArrangementCheck) {
    let categories = || scene.objects.iter().map(|o| o.category.as_str());
    for r in rules.needs.iter().filter(|r| r.applies(categories())) {
        let targets: Vec<&SceneObject> = scene
            .objects
            .iter()
            .filter(|o| matches!(o.parent, ParentRef::Ground | ParentRef::Wall(_)))
            .filter(|o| r.target.contains(&o.category))
            .collect();
        for s in scene
            .objects
            .iter()
            .filter(|o| r.subject.contains(&o.category))
        {
            let chain = support_chain(scene, s);
            let carried = chain.iter().any(|o| r.target.contains(&o.category));
            let root = chain.last().copied().unwrap_or(s);
            let near = targets
                .iter()
                .any(|t| t.id != root.id && floor_gap(root, t) <= r.within);
            let failure = (!carried && !near).then(|| {
                if targets.is_empty() {
                    format!("the scene has none of {}", r.target.join(", "))
                } else {
                    format!("no {} within {} m", r.target.join(" or "), r.within)
                }
            });
            check.record(&r.rule, r.judge, &s.id, failure);
        }
    }
}

/// The objects carrying `o`, nearest first, up to the floor object (empty for a floor
/// object).
fn support_chain<'s>(scene: &'s Scene, o: &SceneObject) -> Vec<&'s SceneObject> {
    let mut chain = Vec::new();
    let mut parent = o.parent.object_id();
    while let Some(id) = parent {
        let Some(p) = scene.objects.iter().find(|x| x.id == id) else {
            break;
        };
        if chain.iter().any(|c: &&SceneObject| c.id == p.id) {
            break;
        }
        chain.push(p);
        parent = p.parent.object_id();
    }
    chain
}

/// `s` is turned within 50° of straight at `t`'s front face (its front opposite `t`'s).
fn squarely_toward(s: &SceneObject, t: &SceneObject) -> bool {
    -front_dir(s).dot(&front_dir(t)) >= 50f64.to_radians().cos()
}

/// `s` is beside `t` (the relation code's *beside*), off its long side rather than before its
/// foot or behind its head: across the target's width it lies outside the target's half
/// width, along its length within the target's half length.
fn flanks(scene: &Scene, s: &SceneObject, t: &SceneObject) -> bool {
    let beside = Relation::new(RelationKind::Beside, t.id.clone());
    if relation_holds(scene, &s.id, &beside) != Some(true) {
        return false;
    }
    let d = floor_centre(s) - floor_centre(t);
    let size = t.local_bounds.size() * t.pose.scale;
    let (half_w, half_l) = (size.x / 2.0, size.z / 2.0);
    d.dot(&right_dir(t)).abs() >= half_w && d.dot(&front_dir(t)).abs() <= half_l
}

/// The front of a room whose anchor stands with its back against a wall (a teacher's desk, a
/// judge's bench): the anchor's floor centre and the direction it faces, into the room.
struct RoomFront {
    at: Vector2<f64>,
    into_room: Vector2<f64>,
}

impl RoomFront {
    /// `s` stands in the room before the front and is turned like the anchor (within 50°):
    /// whoever sits at it, on its front side, looks toward the front of the room (a desk in
    /// a classroom's rows).
    fn rows_toward(&self, s: &SceneObject) -> bool {
        (floor_centre(s) - self.at).dot(&self.into_room) > 0.0
            && front_dir(s).dot(&self.into_room) >= 50f64.to_radians().cos()
    }
}

/// The room's front, when its anchor is a floor object with its back against a wall.
fn room_front(scene: &Scene) -> Option<RoomFront> {
    let id = scene.anchor.as_deref()?;
    let a = scene.objects.iter().find(|o| o.id == id)?;
    let against = Relation::new(RelationKind::AgainstWall, GROUND_ID.to_owned());
    (a.parent == ParentRef::Ground && relation_holds(scene, &a.id, &against) == Some(true)).then(
        || RoomFront {
            at: floor_centre(a),
            into_room: front_dir(a),
        },
    )
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
        let known: Vec<&str> = scenethesis_procedural::catalog::categories()
            .map(|c| c.name)
            .collect();
        for name in rules.categories() {
            assert!(known.contains(&name), "arrangement.toml names `{name}`");
        }
    }
}
