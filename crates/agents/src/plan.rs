//! The plan: what a [`Planner`] makes of a prompt, and what a [`crate::Guide`] lays out.

use std::collections::{BTreeMap, BTreeSet};

use scenethesis_scene_graph::{
    AssetLook, Environment, LookAttribute, ParentRef, Relation, RelationKind,
};
use serde::{Deserialize, Serialize};

/// Id of the back wall of a planned room (−z); the anchor's wall by default.
pub const BACK_WALL: &str = "wall_0";
/// Id of the left wall (−x, seen from the door looking at the back wall).
pub const LEFT_WALL: &str = "wall_1";
/// Id of the front wall (+z), which holds the door.
pub const FRONT_WALL: &str = "wall_2";
/// Id of the right wall (+x, seen from the door looking at the back wall).
pub const RIGHT_WALL: &str = "wall_3";

/// The longest prompt the offline planner reads, in characters; a longer prompt is cut at a
/// word boundary before this limit and the plan's `limits` say so.
pub const MAX_PROMPT_CHARS: usize = 2000;

/// `prompt` cut to at most [`MAX_PROMPT_CHARS`] characters at the last word boundary within the
/// limit, with a note saying so when it was cut (the note `report.json` lists under `limits`).
///
/// ```
/// use scenethesis_agents::{cut_prompt, MAX_PROMPT_CHARS};
/// assert_eq!(cut_prompt("a kitchen"), ("a kitchen", None));
/// let long = "a kitchen ".repeat(300);
/// let (cut, note) = cut_prompt(&long);
/// assert!(cut.chars().count() <= MAX_PROMPT_CHARS && note.is_some());
/// ```
pub fn cut_prompt(prompt: &str) -> (&str, Option<String>) {
    let length = prompt.chars().count();
    if length <= MAX_PROMPT_CHARS {
        return (prompt, None);
    }
    let end = prompt
        .char_indices()
        .nth(MAX_PROMPT_CHARS)
        .map_or(prompt.len(), |(i, _)| i);
    let cut = prompt[..end]
        .rfind(|c: char| !c.is_alphanumeric())
        .filter(|&i| i > 0)
        .unwrap_or(end);
    let kept = prompt[..cut].trim_end();
    let note = format!(
        "the prompt is {length} characters long; only its first {} were read (the limit is {MAX_PROMPT_CHARS})",
        kept.chars().count()
    );
    (kept, Some(note))
}
/// The most instances of one requested object ("500 chairs" plans this many, and the plan's
/// `limits` say so).
pub const MAX_COUNT_PER_OBJECT: u32 = 50;
/// The most objects one plan holds; objects the prompt names come first, and the plan's
/// `limits` say what was left out.
pub const MAX_PLANNED_OBJECTS: usize = 250;
/// The longest side of a planned room in metres, however the plan arrives (the offline planner
/// stays well below it; a model's answer is clamped to it; a plan file beyond it is refused).
pub const MAX_ROOM_SIDE: f64 = 40.0;
/// The shortest side a model's answer may give a room, in metres (shorter answers are raised).
pub const MIN_ROOM_SIDE: f64 = 2.0;
/// The widest walkway (`aisle`) a plan may ask for, in metres.
pub const MAX_AISLE: f64 = 5.0;
/// The deepest free space in front of the door (`door_clearance`) a plan may ask for, in metres.
pub const MAX_DOOR_CLEARANCE: f64 = 5.0;
/// The most hard constraints one plan holds.
pub const MAX_PLAN_CONSTRAINTS: usize = 1000;

/// What a planner is asked for.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct PlanRequest {
    /// The user's text prompt, simple ("a gym room") or detailed.
    pub prompt: String,
    /// The categories the asset library can provide; the plan uses only these.
    pub available_categories: BTreeSet<String>,
    /// Seed for every choice the planner makes.
    pub seed: u64,
}

impl PlanRequest {
    /// A request for `prompt` over the given categories.
    pub fn new<I, S>(prompt: impl Into<String>, available_categories: I, seed: u64) -> Self
    where
        I: IntoIterator<Item = S>,
        S: Into<String>,
    {
        Self {
            prompt: prompt.into(),
            available_categories: available_categories.into_iter().map(Into::into).collect(),
            seed,
        }
    }
}

/// Depth layer of an object in the scene's spatial hierarchy.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Layer {
    /// Against the walls, behind everything else (shelves, cabinets).
    Background,
    /// The anchor and its group.
    Middle,
    /// Nearest the viewer (seats facing the anchor, free-standing small things).
    Foreground,
}

/// Where on the floor a ground object goes, before any exact pose exists.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "zone", rename_all = "kebab-case")]
pub enum Zone {
    /// Back against a wall; `wall` names one (`wall_0` …) or `None` for any wall.
    Wall {
        /// A particular wall id, or any wall.
        wall: Option<String>,
    },
    /// In a corner, back against one of its walls.
    Corner,
    /// Near the middle of the room.
    Center,
    /// In a grid of rows in the middle of the room, facing the back wall.
    Rows,
    /// Anywhere with clearance.
    Free,
    /// Hanging on a wall, above free floor.
    WallMounted,
    /// Positioned by its spatial relations (in front of, beside, around, facing …).
    Relative,
    /// Resting on, in or under its parent object (not on the floor).
    Supported,
}

/// One object of the plan.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PlannedObject {
    /// Stable id, e.g. `sofa_0`, `book_3`.
    pub id: String,
    /// Category name from the available categories.
    pub category: String,
    /// Depth layer.
    pub layer: Layer,
    /// How the object rests on its parent (`on-floor`, `against-wall`, `on`, `inside`, `under`).
    pub support: RelationKind,
    /// The ground or the supporting object's id.
    pub parent: ParentRef,
    /// Where a ground object goes.
    pub zone: Zone,
    /// Further relations to other planned objects or walls (in-front-of, beside, facing, …).
    pub relations: Vec<Relation>,
    /// Whether the prompt stated this object's support or relations (hard constraints).
    pub hard: bool,
    /// The colours and materials the prompt asks this object to have; its asset wears them.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub attributes: Vec<Attribute>,
}

/// Whether an attribute is a colour or a material.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AttributeKind {
    /// A colour ("red", "dark grey").
    Color,
    /// A material ("leather", "oak", "glass").
    Material,
}

/// A colour or material the prompt asks an object or a room surface to have, and what it does.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub struct Attribute {
    /// The prompt's words for it (stems): `red`, `dark grey`, `leather`.
    pub words: String,
    /// Colour or material.
    pub kind: AttributeKind,
    /// What it does to the asset or surface: the parts it qualifies, the named material
    /// they become, the colour they take.
    #[serde(flatten)]
    pub look: LookAttribute,
}

/// Where the room's style came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum StyleSource {
    /// A style word of the prompt.
    Prompt,
    /// Drawn with the seed (the prompt names none).
    #[default]
    Seed,
}

/// One room surface's look: the palette entry it is made of and the prompt's attributes.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct SurfaceLook {
    /// The palette entry the surface is made of before its attributes (`oak`, `white_paint`).
    pub base: String,
    /// The colours and materials the prompt asks the surface to have.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub attributes: Vec<Attribute>,
}

/// A look word of the prompt the library cannot do.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct UnavailableAttribute {
    /// The prompt's words for it (`plaid`, `mauve coloured`).
    pub words: String,
    /// What it qualifies: the object's words or the surface (`sofa`, `walls`).
    pub target: String,
}

/// The room's look: a coherent style (one entry per material family), its surfaces and the
/// look words the library cannot do.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct RoomLook {
    /// The style's name (`scandinavian`, …; see `knowledge/looks.toml`).
    pub style: String,
    /// Whether the prompt named the style or the seed drew it.
    #[serde(default)]
    pub style_source: StyleSource,
    /// The prompt's words for the style, when it named one.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub style_words: Option<String>,
    /// Per palette family, the entry every object's material of that family becomes.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub families: BTreeMap<String, String>,
    /// The room surfaces (`floor`, `walls`, `ceiling`).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub surfaces: BTreeMap<String, SurfaceLook>,
    /// Look words the library cannot do, reported, never silently dropped.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub unavailable: Vec<UnavailableAttribute>,
}

impl RoomLook {
    /// The look object `object`'s asset is generated with: the room's families and the
    /// object's own attributes.
    pub fn asset_look(&self, object: &PlannedObject) -> AssetLook {
        AssetLook {
            families: self.families.clone(),
            attributes: object.attributes.iter().map(|a| a.look.clone()).collect(),
        }
    }
}

/// What a hard constraint refers to.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
#[serde(tag = "kind", content = "id", rename_all = "kebab-case")]
pub enum ConstraintTarget {
    /// A planned object.
    Object(String),
    /// A particular wall.
    Wall(String),
    /// Any wall.
    AnyWall,
    /// A corner of the room.
    Corner,
}

/// A relation the prompt states explicitly; the layout must satisfy it.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct PlanConstraint {
    /// The planned object it constrains.
    pub subject: String,
    /// The relation kind (`against-wall` for walls and corners).
    pub kind: RelationKind,
    /// What it relates to.
    pub target: ConstraintTarget,
    /// The prompt words that stated it.
    pub phrase: String,
}

/// A scene plan: objects, anchor, hierarchy and relations.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Plan {
    /// The prompt the plan was made from.
    pub prompt: String,
    /// The detected scene type (an archetype name), or `custom` for a blend of archetypes.
    pub scene_type: String,
    /// The archetypes the plan draws on, best match first.
    pub archetypes: Vec<String>,
    /// Indoor room or outdoor ground.
    pub environment: Environment,
    /// What an outdoor scene's open ground is made of: a library material id from the
    /// place's knowledge (`sand` on a beach, `grass` in a park); `None` indoors and in plans
    /// that name none (their ground is the library's soil).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub ground: Option<String>,
    /// Room (or ground) size [x, z] in metres.
    pub room_size: [f64; 2],
    /// Wall height in metres (indoor).
    pub wall_height: f64,
    /// Minimum walkway width in metres (≥ 0.6).
    pub aisle: f64,
    /// Free depth in front of the door in metres.
    pub door_clearance: f64,
    /// Id of the anchor object (always a ground object of the plan).
    pub anchor: String,
    /// The objects: ground objects first (anchor first), then supported ones, parents before
    /// children.
    pub objects: Vec<PlannedObject>,
    /// The relations the prompt states, as hard constraints.
    pub constraints: Vec<PlanConstraint>,
    /// The up-sampled prompt: the scene's background, middle ground and foreground in words.
    pub description: String,
    /// What the planner substituted or left out, and why.
    pub notes: Vec<String>,
    /// What the planner assumed to read the prompt: the kind of place an unknown scene type
    /// was read as, or the generic room it fell back to (empty when the prompt names a known
    /// scene type).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub assumptions: Vec<String>,
    /// The place the planner read the prompt as, how sure it is and why (`None` in plans
    /// written before readings were recorded, or by hand).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub reading: Option<PlaceReading>,
    /// Limits that cut the request: prompt length, instances per object, objects per plan.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub limits: Vec<String>,
    /// Every object the prompt names, with how many were asked for and the planned ids (or why
    /// none could be planned).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub requested: Vec<RequestedObject>,
    /// The room's style, surfaces and unavailable look words (`None`: every asset wears its
    /// generator's own materials).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub look: Option<RoomLook>,
    /// Floor areas the guide keeps clear (a house room's doors and windows; empty for a
    /// single room, whose one door's clearance is `door_clearance`).
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub keep_clear: Vec<KeepClear>,
}

/// A rectangle of the room's floor, in the room's frame (the floor centred on the origin), that
/// no floor object may take — or, with `below`, none taller than that (the floor under a
/// window).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct KeepClear {
    /// What the area serves, e.g. `door_2 swing and approach` or `window_1`.
    pub why: String,
    /// Corner with the smallest (x, z), m.
    pub min: [f64; 2],
    /// Corner with the largest (x, z), m.
    pub max: [f64; 2],
    /// The height (m) an object's top may reach inside the area (a window's sill); `None`:
    /// nothing may stand in it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub below: Option<f64>,
    /// Whether the area lies before the door the room is entered by, in its front wall (+z):
    /// the guide keeps it as the room's door clearance and roots its walkway there, rather
    /// than at the front wall's middle.
    #[serde(default, skip_serializing_if = "std::ops::Not::not")]
    pub entrance: bool,
}

/// Below this confidence a reading of the place is reported as a guess (in `report.json`
/// and the summary line).
pub const LOW_CONFIDENCE: f64 = 0.6;

/// Who read the place of a prompt.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum ReadingSource {
    /// The offline planner's knowledge.
    #[default]
    Knowledge,
    /// A language model (its scene type, completed from the same knowledge).
    Model,
}

/// The place a prompt was read as, how sure the reading is and what it rests on.
///
/// ```
/// use scenethesis_agents::{KnowledgePlanner, PlanRequest, Planner};
///
/// let planner = KnowledgePlanner::new();
/// let request = PlanRequest::new("a kitchen", planner.known_categories(), 0);
/// let reading = planner.plan(&request).unwrap().reading.unwrap();
/// assert_eq!(reading.place, "kitchen");
/// assert!(!reading.is_low());
/// ```
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct PlaceReading {
    /// The place read: an archetype or a place of the thesaurus (the primary one of a blend).
    pub place: String,
    /// From 0 (a guess) to 1 (the prompt names the place outright).
    pub confidence: f64,
    /// What the reading rests on, in words ("\"home cinema\" names the place `home_cinema`").
    pub basis: String,
    /// Who read it.
    #[serde(default)]
    pub source: ReadingSource,
}

impl PlaceReading {
    /// Whether the reading is a guess ([`LOW_CONFIDENCE`]).
    pub fn is_low(&self) -> bool {
        self.confidence < LOW_CONFIDENCE
    }
}

/// An object the prompt names, as planned.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct RequestedObject {
    /// The prompt's words for it (singular stems), e.g. `office chair`.
    pub words: String,
    /// The category planned for it, or `None` when the library has nothing close.
    pub category: Option<String>,
    /// How many the prompt asks for (0 for "without …" / "no …" / "0 …"), after the
    /// [`MAX_COUNT_PER_OBJECT`] cap.
    pub count: u32,
    /// The planned objects' ids (empty when none were asked for or none is available).
    pub ids: Vec<String>,
    /// Why the plan differs from the words (substituted, unavailable, capped), if it does.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub note: Option<String>,
}

impl RequestedObject {
    /// Whether the prompt asked for at least one instance that the plan could hold.
    pub fn expected(&self) -> bool {
        self.count > 0 && self.category.is_some()
    }
}

impl Plan {
    /// Whether the room's walls are given rather than sized to the plan: a house room, whose
    /// walls are the floor plan's (it carries the areas its doors and windows keep clear). A
    /// guide may not grow such a room to fit what it could not place.
    pub fn room_is_fixed(&self) -> bool {
        !self.keep_clear.is_empty()
    }

    /// The planned object with this id.
    pub fn object(&self, id: &str) -> Option<&PlannedObject> {
        self.objects.iter().find(|o| o.id == id)
    }

    /// The distinct categories of the plan, sorted.
    pub fn categories(&self) -> BTreeSet<&str> {
        self.objects.iter().map(|o| o.category.as_str()).collect()
    }

    /// The distinct relation kinds used (supports other than `on-floor`, and relations).
    pub fn relation_kinds(&self) -> BTreeSet<RelationKind> {
        self.objects
            .iter()
            .flat_map(|o| {
                std::iter::once(o.support)
                    .filter(|k| *k != RelationKind::OnFloor)
                    .chain(o.relations.iter().map(|r| r.kind))
            })
            .collect()
    }

    /// The objects of one layer.
    pub fn layer(&self, layer: Layer) -> impl Iterator<Item = &PlannedObject> {
        self.objects.iter().filter(move |o| o.layer == layer)
    }

    /// The plan with each object's support as `scene` holds it wherever `scene` rests it on
    /// another parent than planned, for every object the prompt did not pin down
    /// ([`PlannedObject::hard`]): when an image leads the layout, what it shows an object
    /// resting on (a bucket on the floor beside a crate, not in it) replaces the planner's
    /// default, and the judge holds the scene to the image. Objects the prompt stated keep
    /// their planned support, as do objects on their planned parent (on the floor, whether
    /// against a wall is the plan's to say) and objects `scene` lacks.
    ///
    /// ```
    /// use scenethesis_agents::{KnowledgePlanner, PlanRequest, Planner};
    /// use scenethesis_scene_graph::{nalgebra::Point3, Aabb, Architecture, ParentRef, RelationKind,
    ///     Scene, SceneObject};
    ///
    /// let request = PlanRequest::new("a cozy living room", ["sofa", "cushion", "coffee_table"], 0);
    /// let plan = KnowledgePlanner::new().plan(&request).unwrap();
    /// // Something the planner rests on another object, and the prompt did not place.
    /// let held = plan.objects.iter().find(|o| o.parent != ParentRef::Ground && !o.hard);
    /// let held = held.expect("the living room's plan rests things on others");
    /// // The image shows it standing on the floor.
    /// let bounds = Aabb::new(Point3::new(-0.1, 0.0, -0.1), Point3::new(0.1, 0.5, 0.1));
    /// let mut scene = Scene::new(Architecture::default());
    /// scene.objects.push(SceneObject::standing_box(&held.id, bounds, 0.0, 0.0));
    /// let placed = plan.with_supports_of(&scene);
    /// let as_seen = placed.object(&held.id).unwrap();
    /// assert_eq!((as_seen.support, &as_seen.parent), (RelationKind::OnFloor, &ParentRef::Ground));
    /// assert_eq!(placed.objects.len(), plan.objects.len());
    /// // Had the prompt placed it, the plan would keep its word.
    /// let mut pinned = plan.clone();
    /// pinned.objects.iter_mut().find(|o| o.id == held.id).unwrap().hard = true;
    /// assert_eq!(pinned.with_supports_of(&scene).object(&held.id), pinned.object(&held.id));
    /// ```
    pub fn with_supports_of(&self, scene: &scenethesis_scene_graph::Scene) -> Plan {
        let mut plan = self.clone();
        for planned in plan.objects.iter_mut().filter(|o| !o.hard) {
            if let Some(placed) = scene
                .object(&planned.id)
                .filter(|p| p.parent != planned.parent)
            {
                planned.support = placed.support;
                planned.parent = placed.parent.clone();
            }
        }
        plan
    }
}

/// Why a prompt could not be planned.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum PlanError {
    /// The prompt is empty or only whitespace and punctuation.
    #[error("the prompt is empty: describe a scene, e.g. \"a cozy living room\"")]
    EmptyPrompt,
    /// No word of the prompt names a scene type, an object or a setting.
    #[error("the prompt \"{prompt}\" names no known scene type, object or setting; try e.g. \"a garage\" or \"a bedroom with a desk\"")]
    Unintelligible {
        /// The prompt.
        prompt: String,
    },
    /// The request offers no categories the plan could use.
    #[error("none of the {available} available categories fits \"{prompt}\"; the plan needs at least one floor object")]
    NothingAvailable {
        /// The prompt.
        prompt: String,
        /// How many categories were offered.
        available: usize,
    },
    /// A model provider failed (online planners).
    #[error("planner provider `{provider}` failed: {message}")]
    Provider {
        /// The provider's name.
        provider: String,
        /// What went wrong.
        message: String,
    },
    /// A provider's answer is not a usable plan (online planners).
    #[error("planner provider `{provider}` returned an unusable plan: {message}")]
    InvalidPlan {
        /// The provider's name.
        provider: String,
        /// What is wrong with it.
        message: String,
    },
}

/// Stage 1 of the method: a prompt becomes a [`Plan`].
///
/// The offline [`crate::KnowledgePlanner`] reads archetype knowledge; an LLM-backed planner
/// implements the same trait by prompting a model with the request (prompt and available
/// categories) and parsing its answer into a [`Plan`] (which is serde-serializable for that
/// purpose). Implementations must be deterministic for a fixed request and provider.
///
/// [`crate::FixedPlanner`] is the second implementation: it returns a plan read from a file.
///
/// Calling the seam with the offline planner:
///
/// ```
/// use scenethesis_agents::{KnowledgePlanner, PlanRequest, Planner};
///
/// let planner: &dyn Planner = &KnowledgePlanner::new();
/// let request = PlanRequest::new("a bedroom with a bed", ["bed", "nightstand", "lamp"], 0);
/// let plan = planner.plan(&request).unwrap();
/// assert!(plan.objects.iter().any(|object| object.category == "bed"));
/// assert!(plan.objects.iter().all(|o| request.available_categories.contains(&o.category)));
/// ```
pub trait Planner: Send + Sync {
    /// A short name for reports (`report.json` records it).
    fn name(&self) -> &str;

    /// Plans the scene for `request`.
    fn plan(&self, request: &PlanRequest) -> Result<Plan, PlanError>;
}
