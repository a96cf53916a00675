//! [`LlmPlanner`]: the paper's coarse planning by a chat model, completed from offline
//! knowledge when the model's plan is weak.

use std::collections::BTreeSet;

use scenethesis_agents::{
    KnowledgePlanner, PlaceReading, Plan, PlanError, PlanRequest, PlannedObject, Planner,
    ReadingSource, Zone, MAX_PLANNED_OBJECTS,
};
use scenethesis_models::{ChatModel, ChatRequest, Message};
use scenethesis_scene_graph::ParentRef;

use crate::convert::{convert, fresh_id, order, Answer, Converted};
use crate::salvage::close_truncated;
use crate::schema::{plan_max_tokens, plan_schema};

/// Objects a plan for a simple prompt must have.
pub const MIN_OBJECTS: usize = 15;

const INSTRUCTIONS: &str = "You plan 3D scenes for a physics simulator. Work in these steps:
1. Interpret the user's prompt: the kind of place, its size and style. Decide whether the prompt is
   detailed (it names several objects and where they go) or simple.
2. Review the categories the asset library offers; every object must use one of them exactly.
3. Select the objects: for a simple prompt at least 15 (counting each instance), with the
   supporting objects and the small things on them that make the place believable; for a
   detailed prompt every object the user named with the stated counts, plus fitting extras.
   Choose one large floor-standing object as the anchor that the layout is organised around.
4. Cross-check every object against the library: use the nearest category, and list what has no
   fitting category under `unavailable` with the reason.
5. Lay out a spatial hierarchy: `background` (against the walls), `middle` (the anchor and its
   group) and `foreground` (nearest the viewer). Give each object its support: `on-floor` or
   `against-wall` with parent `ground`, or `on`/`inside`/`under` with the supporting object's id
   as parent. Zones: `wall` (with `wall`: wall_0 back, wall_1 left, wall_2 front with the door,
   wall_3 right, or any), `corner`, `center`, `rows`, `free`, `wall-mounted`, `relative` (placed
   by its relations), `supported` (for on/inside/under). Relations (`beside`, `in-front-of`,
   `behind`, `left-of`, `right-of`, `facing`, `around`) target other object ids. Mark `stated`
   true for objects whose placement the prompt itself states.
6. Write `description`: the scene in words, background, then middle ground, then foreground
   (the up-sampled prompt an image model will draw from). Room width and depth are in metres.
Ids are the category with a number: shelf_0, shelf_1, ...";

/// A [`Planner`] that asks a [`ChatModel`] for the plan, as the paper's LLM planner does.
///
/// The answer is requested under [`plan_schema`] and converted into the offline planner's
/// [`Plan`] type. A weak answer (too few objects for a simple prompt, categories the library
/// lacks, no usable anchor) is re-asked once with the problems listed; if it is still weak,
/// the plan is completed from the offline [`KnowledgePlanner`] (missing anchor, objects up to
/// [`MIN_OBJECTS`]) with a note, so a run does not fail because the model is small.
///
/// Every request states `max_tokens` ([`crate::plan_max_tokens`]: what the schema's largest
/// answer needs). An answer that still breaks the schema after the client's repair round, or
/// is cut off mid-object, is salvaged rather than refused: the complete objects are kept (at
/// most [`crate::MAX_ANSWER_OBJECTS`]), the open brackets closed, unknown categories and
/// unusable ids dropped or renamed with a note, self-parents and support loops put on the
/// floor; the plan is then completed from offline knowledge without re-asking. Only transport
/// failures (unreachable, timeouts, HTTP errors) are errors naming the endpoint and model; an
/// answer with no JSON object at all is re-asked once, then planned offline with a note.
#[derive(Debug)]
pub struct LlmPlanner<M> {
    model: M,
    label: String,
    fallback: KnowledgePlanner,
    min_objects: usize,
}

/// What one model round gave.
enum Round {
    /// A plan, maybe with issues, the answer text, and whether the plan was salvaged from an
    /// answer that breaks the schema (cut off, not JSON, too many objects) after the client's
    /// repair round.
    Plan(Box<Converted>, String, bool),
    /// No usable plan (not JSON, schema violated after repair); why.
    Unusable(String),
}

impl<M: ChatModel> LlmPlanner<M> {
    /// A planner asking `model`, completing weak plans from the built-in knowledge.
    pub fn new(model: M) -> Self {
        Self {
            label: format!("llm:{}", model.name()),
            model,
            fallback: KnowledgePlanner::new(),
            min_objects: MIN_OBJECTS,
        }
    }

    /// Completes weak plans from `fallback` instead.
    pub fn with_fallback(mut self, fallback: KnowledgePlanner) -> Self {
        self.fallback = fallback;
        self
    }

    /// Sets the object count a simple prompt's plan needs (default [`MIN_OBJECTS`]).
    pub fn with_min_objects(mut self, n: usize) -> Self {
        self.min_objects = n;
        self
    }

    /// The model.
    pub fn model(&self) -> &M {
        &self.model
    }

    fn round(&self, messages: Vec<Message>, request: &PlanRequest) -> Result<Round, PlanError> {
        let mut chat = ChatRequest::structured(messages, plan_schema());
        chat.seed = Some(request.seed);
        chat.max_tokens = Some(plan_max_tokens());
        chat.lenient = true;
        let response = self.model.chat(&chat).map_err(|e| PlanError::Provider {
            provider: self.label.clone(),
            message: e.to_string(),
        })?;
        let (value, salvaged) = match response.json {
            Some(v) => {
                let invalid = !plan_schema().violations(&v).is_empty();
                (v, invalid)
            }
            None => match close_truncated(&response.text) {
                Some(v) => (v, true),
                None => {
                    return Ok(Round::Unusable(format!(
                        "the answer holds no JSON object ({})",
                        response.notes.join("; ")
                    )))
                }
            },
        };
        let (answer, read_notes) = Answer::read(&value);
        let mut converted = convert(
            &answer,
            &request.prompt,
            &request.available_categories,
            self.min_objects,
        );
        converted.plan.notes.extend(response.notes);
        converted.plan.notes.extend(read_notes);
        if salvaged {
            converted.plan.notes.push(format!(
                "salvaged from an answer that does not fit the plan schema: {} usable objects kept",
                converted.plan.objects.len()
            ));
        }
        Ok(Round::Plan(Box::new(converted), response.text, salvaged))
    }

    /// Fills a weak plan from the offline planner: the anchor when missing, then objects up
    /// to the minimum count.
    fn complete(&self, mut converted: Converted, request: &PlanRequest) -> Result<Plan, PlanError> {
        let reasons = converted.issues.join("; ");
        let offline = match self.fallback.plan(request) {
            Ok(p) => p,
            Err(e) => {
                if converted.plan.anchor.is_empty() || converted.plan.objects.is_empty() {
                    return Err(PlanError::InvalidPlan {
                        provider: self.label.clone(),
                        message: format!(
                            "{reasons}; the offline knowledge cannot complete it either: {e}"
                        ),
                    });
                }
                converted.plan.notes.push(format!(
                    "weak plan kept as is ({reasons}); offline knowledge: {e}"
                ));
                return Ok(converted.plan);
            }
        };
        let plan = &mut converted.plan;
        let mut taken: BTreeSet<String> = plan.objects.iter().map(|o| o.id.clone()).collect();
        let mut renamed: Vec<(String, String)> = Vec::new();
        let mut added = 0usize;
        if plan.anchor.is_empty() {
            if let Some(a) = offline.object(&offline.anchor) {
                let id = fresh_id(&a.category, &mut taken);
                renamed.push((a.id.clone(), id.clone()));
                let mut a = a.clone();
                a.id = id.clone();
                a.relations.retain(|r| r.target.starts_with("wall_"));
                plan.objects.push(a);
                plan.anchor = id;
                added += 1;
            }
        }
        let needed = if converted.detailed {
            0
        } else {
            self.min_objects
        };
        for o in &offline.objects {
            if plan.objects.len() >= needed {
                break;
            }
            if o.id == offline.anchor {
                continue;
            }
            let parent = match &o.parent {
                ParentRef::Ground => Some(ParentRef::Ground),
                ParentRef::Wall(w) => Some(ParentRef::Wall(w.clone())),
                ParentRef::Object(p) => renamed
                    .iter()
                    .find(|(from, _)| from == p)
                    .map(|(_, to)| ParentRef::Object(to.clone())),
            };
            let Some(parent) = parent else { continue };
            let id = fresh_id(&o.category, &mut taken);
            renamed.push((o.id.clone(), id.clone()));
            let mut copy: PlannedObject = o.clone();
            copy.id = id;
            copy.parent = parent;
            copy.hard = false;
            copy.relations = o
                .relations
                .iter()
                .filter_map(|r| {
                    if r.target.starts_with("wall_") {
                        return Some(r.clone());
                    }
                    renamed
                        .iter()
                        .find(|(from, _)| *from == r.target)
                        .map(|(_, to)| scenethesis_scene_graph::Relation::new(r.kind, to.clone()))
                })
                .collect();
            if copy.zone == Zone::Relative && copy.relations.is_empty() {
                copy.zone = Zone::Free;
            }
            plan.objects.push(copy);
            added += 1;
        }
        plan.objects = order(std::mem::take(&mut plan.objects), &plan.anchor.clone());
        if added > 0 {
            plan.archetypes = offline.archetypes.clone();
        }
        plan.notes.push(format!(
            "completed from offline knowledge ({}): {added} objects added because {reasons}",
            offline.scene_type
        ));
        if plan.anchor.is_empty() {
            return Err(PlanError::InvalidPlan {
                provider: self.label.clone(),
                message: format!("{reasons}; no anchor could be found"),
            });
        }
        Ok(converted.plan)
    }
}

fn user_message(request: &PlanRequest) -> String {
    let categories: Vec<&str> = request
        .available_categories
        .iter()
        .map(String::as_str)
        .collect();
    format!(
        "Prompt: {}\n\nAvailable categories ({}): {}",
        request.prompt.trim(),
        categories.len(),
        categories.join(", ")
    )
}

impl<M: ChatModel> Planner for LlmPlanner<M> {
    /// `llm:<model name>`, for reports.
    fn name(&self) -> &str {
        &self.label
    }

    /// The model's plan (re-asked once, completed from offline knowledge when weak), with the
    /// objects its prompt names read by the offline planner (`requested`), so a requested
    /// object the model left out is reported, and judged, as missing; the model's reading of
    /// the place is kept and completed from the same knowledge (its place's core contents).
    fn plan(&self, request: &PlanRequest) -> Result<Plan, PlanError> {
        let (mut plan, detailed) = self.model_plan(request)?;
        if plan.requested.is_empty() {
            plan.requested = self
                .fallback
                .requested_in(&plan, &request.available_categories);
            self.add_left_out(&mut plan, request);
            // A detailed prompt is kept as the user stated it.
            if !detailed {
                self.complete_reading(&mut plan, request);
            }
        }
        Ok(plan)
    }
}

/// Adds a copy of `source`, an object of the offline plan `offline`, to `plan` under a fresh
/// id: on the floor or wall it stands on, or on an object of `plan` of its parent's category
/// (`None`, and nothing added, when `plan` has none); relations to objects are dropped.
fn adopt(
    plan: &mut Plan,
    source: &PlannedObject,
    offline: &Plan,
    taken: &mut BTreeSet<String>,
) -> Option<String> {
    let parent = match &source.parent {
        ParentRef::Ground => ParentRef::Ground,
        ParentRef::Wall(w) => ParentRef::Wall(w.clone()),
        ParentRef::Object(p) => {
            let p = offline.object(p)?;
            let host = plan.objects.iter().find(|o| o.category == p.category)?;
            ParentRef::Object(host.id.clone())
        }
    };
    let id = fresh_id(&source.category, taken);
    let mut copy = source.clone();
    copy.id = id.clone();
    copy.parent = parent;
    copy.relations.retain(|r| r.target.starts_with("wall_"));
    if copy.zone == Zone::Relative && copy.relations.is_empty() {
        copy.zone = Zone::Free;
    }
    plan.objects.push(copy);
    Some(id)
}

impl<M: ChatModel> LlmPlanner<M> {
    /// Completes the model's reading from the offline knowledge: the offline planner reads
    /// the model's scene type ("home_cinema" as "home cinema"), and every category of that
    /// place's `core` (what any real room of the kind holds) the model left out, and the
    /// prompt does not rule out, is added as the offline planner plans it, with a note. The
    /// plan's `reading` names the model's place, and how sure the knowledge is of it.
    fn complete_reading(&self, plan: &mut Plan, request: &PlanRequest) {
        let words = plan.scene_type.replace('_', " ");
        let typed = PlanRequest {
            prompt: words.clone(),
            ..request.clone()
        };
        let Ok(offline) = self.fallback.plan(&typed) else {
            return;
        };
        let Some(known) = offline.reading.clone() else {
            return;
        };
        plan.reading = Some(PlaceReading {
            place: plan.scene_type.clone(),
            confidence: known.confidence,
            basis: format!(
                "the model read the prompt as `{}`; the knowledge reads that as `{}` ({})",
                plan.scene_type, known.place, known.basis
            ),
            source: ReadingSource::Model,
        });
        if known.is_low() {
            return;
        }
        let ruled_out = |c: &str| {
            plan.requested
                .iter()
                .any(|r| r.count == 0 && r.category.as_deref() == Some(c))
        };
        let missing: Vec<String> = self
            .fallback
            .core_of(&known.place)
            .into_iter()
            .filter(|c| request.available_categories.contains(c) && !ruled_out(c))
            .filter(|c| !plan.objects.iter().any(|o| &o.category == c))
            .collect();
        let mut taken: BTreeSet<String> = plan.objects.iter().map(|o| o.id.clone()).collect();
        let mut added = Vec::new();
        for c in &missing {
            let Some(source) = offline.objects.iter().find(|o| &o.category == c) else {
                continue;
            };
            if plan.objects.len() >= MAX_PLANNED_OBJECTS {
                break;
            }
            added.extend(adopt(plan, source, &offline, &mut taken));
        }
        if !added.is_empty() {
            plan.objects = order(std::mem::take(&mut plan.objects), &plan.anchor.clone());
            plan.notes.push(format!(
                "completed the model's `{}` from the offline knowledge of `{}`, whose core the model left out: {}",
                plan.scene_type,
                known.place,
                added.join(", ")
            ));
        }
    }

    /// Adds the instances of requested objects the model left out, as the offline planner
    /// plans them for the same prompt (on a parent of the same category when they stand on
    /// one; one the model's plan lacks leaves them out), and notes what was added.
    fn add_left_out(&self, plan: &mut Plan, request: &PlanRequest) {
        let short: Vec<usize> = (0..plan.requested.len())
            .filter(|&i| {
                let r = &plan.requested[i];
                r.category.is_some() && (r.ids.len() as u32) < r.count
            })
            .collect();
        if short.is_empty() {
            return;
        }
        let Ok(offline) = self.fallback.plan(request) else {
            return;
        };
        let mut taken: BTreeSet<String> = plan.objects.iter().map(|o| o.id.clone()).collect();
        let mut added = Vec::new();
        for i in short {
            let words = plan.requested[i].words.clone();
            let Some(model) = offline.requested.iter().find(|r| r.words == words) else {
                continue;
            };
            let missing = plan.requested[i].count as usize - plan.requested[i].ids.len();
            for source in model
                .ids
                .iter()
                .filter_map(|id| offline.object(id))
                .take(missing)
            {
                if plan.objects.len() >= MAX_PLANNED_OBJECTS {
                    break;
                }
                let Some(id) = adopt(plan, source, &offline, &mut taken) else {
                    continue;
                };
                plan.requested[i].ids.push(id.clone());
                added.push(id);
            }
            let r = &mut plan.requested[i];
            if r.ids.len() as u32 == r.count {
                let kept: Vec<&str> = r
                    .note
                    .as_deref()
                    .unwrap_or("")
                    .split("; ")
                    .filter(|part| !part.is_empty() && !part.starts_with("the plan holds"))
                    .collect();
                r.note = (!kept.is_empty()).then(|| kept.join("; "));
            }
        }
        if !added.is_empty() {
            plan.objects = order(std::mem::take(&mut plan.objects), &plan.anchor.clone());
            plan.notes.push(format!(
                "added what the prompt names and the model left out, as the offline knowledge plans it: {}",
                added.join(", ")
            ));
        }
    }
}

impl<M: ChatModel> LlmPlanner<M> {
    fn model_plan(&self, request: &PlanRequest) -> Result<(Plan, bool), PlanError> {
        if !request.prompt.chars().any(char::is_alphanumeric) {
            return Err(PlanError::EmptyPrompt);
        }
        if request.available_categories.is_empty() {
            return Err(PlanError::NothingAvailable {
                prompt: request.prompt.clone(),
                available: 0,
            });
        }
        let messages = vec![
            Message::system(INSTRUCTIONS),
            Message::user(user_message(request)),
        ];
        let first = self.round(messages.clone(), request)?;
        let critique = match first {
            Round::Plan(c, _, _) if c.issues.is_empty() => return Ok((c.plan, c.detailed)),
            // The client has re-asked once already; another round would end the same way.
            Round::Plan(c, _, true) => {
                let detailed = c.detailed;
                return self.complete(*c, request).map(|p| (p, detailed));
            }
            Round::Plan(ref c, _, false) => c.issues.join("; "),
            Round::Unusable(ref why) => why.clone(),
        };
        tracing::info!(planner = %self.name(), "re-asking once: {critique}");
        let mut again = messages;
        if let Round::Plan(_, text, _) = &first {
            again.push(Message::assistant(text.clone()));
        }
        again.push(Message::user(format!(
            "Your plan has these problems: {critique}. Answer again with the complete, corrected \
             plan."
        )));
        let second = self.round(again, request)?;
        let best = match (second, first) {
            (Round::Plan(c, _, _), _) if c.issues.is_empty() => {
                let mut plan = c.plan;
                plan.notes.push(format!("re-asked once: {critique}"));
                return Ok((plan, c.detailed));
            }
            (Round::Plan(c, _, _), _) | (Round::Unusable(_), Round::Plan(c, _, _)) => Some(c),
            (Round::Unusable(_), Round::Unusable(_)) => None,
        };
        match best {
            Some(mut c) => {
                c.plan.notes.push(format!("re-asked once: {critique}"));
                let detailed = c.detailed;
                self.complete(*c, request).map(|p| (p, detailed))
            }
            None => {
                let mut plan = self
                    .fallback
                    .plan(request)
                    .map_err(|e| PlanError::InvalidPlan {
                        provider: self.label.clone(),
                        message: format!(
                            "{critique}; the offline knowledge cannot plan it either: {e}"
                        ),
                    })?;
                plan.notes.push(format!(
                    "the model's answers were unusable twice ({critique}); planned from offline knowledge"
                ));
                Ok((plan, false))
            }
        }
    }
}
