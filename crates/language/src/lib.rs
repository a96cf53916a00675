//! Language agents over any [`scenethesis_models::ChatModel`]: [`LlmPlanner`] turns a prompt
//! into the same [`scenethesis_agents::Plan`] the offline planner makes, following the paper's
//! coarse planning (interpret the prompt, review the library's categories, select objects and
//! an anchor, cross-check each against the library, lay out a background / middle /
//! foreground hierarchy with relations, write the up-sampled prompt).
//!
//! This crate has no HTTP of its own: give it an `scenethesis-openai` client, a cached one, or
//! any other implementation of the trait.
//!
//! ```
//! use scenethesis_agents::{KnowledgePlanner, PlanRequest, Planner};
//! use scenethesis_language::LlmPlanner;
//! use scenethesis_models::{ChatModel, ChatRequest, ChatResponse, ProviderError, TokenUsage};
//! use serde_json::json;
//!
//! /// Stands in for a served model: answers every request with one plan.
//! struct Answering(serde_json::Value);
//!
//! impl ChatModel for Answering {
//!     fn name(&self) -> String {
//!         "example/fixed".into()
//!     }
//!     fn chat(&self, _: &ChatRequest) -> Result<ChatResponse, ProviderError> {
//!         Ok(ChatResponse {
//!             text: self.0.to_string(),
//!             json: Some(self.0.clone()),
//!             model: "fixed".into(),
//!             usage: TokenUsage::default(),
//!             notes: vec![],
//!         })
//!     }
//! }
//!
//! let object = |id: &str, category: &str, support: &str, parent: &str, zone: &str| json!({
//!     "id": id, "category": category, "layer": "middle", "support": support,
//!     "parent": parent, "zone": zone, "wall": "wall_0", "relations": [], "stated": true
//! });
//! let answer = json!({
//!     "interpretation": "a desk with a lamp on it", "detailed": true, "scene_type": "study",
//!     "environment": "indoor", "room_width": 3.5, "room_depth": 3.0, "anchor": "desk_0",
//!     "objects": [
//!         object("lamp_0", "table lamp", "on", "desk_0", "supported"),
//!         object("desk_0", "desk", "against-wall", "ground", "wall"),
//!     ],
//!     "unavailable": [], "description": "a desk against the back wall with a lamp on it"
//! });
//! let prompt = "a desk against the back wall with a table lamp on it";
//! let request = PlanRequest::new(prompt, KnowledgePlanner::new().known_categories(), 1);
//! let plan = LlmPlanner::new(Answering(answer)).plan(&request)?;
//! assert_eq!(plan.anchor, "desk_0");
//! assert_eq!(plan.objects[0].id, "desk_0", "floor objects first, parents before children");
//! assert_eq!(plan.object("lamp_0").unwrap().category, "table_lamp");
//! assert_eq!(plan.description, prompt, "a detailed prompt is kept as written");
//! # Ok::<(), scenethesis_agents::PlanError>(())
//! ```
//!
//! [`VlmJudge`] (a `scenethesis_judge::Judge`) runs the geometric judge first, then shows a
//! vision-language model previews drawn by any renderer of the seam in
//! `scenethesis-render-api` and rejects scenes it scores below
//! [`VlmThresholds`], with per-object reasons the pipeline's re-plan acts on.
#![warn(missing_docs)]

mod convert;
mod planner;
mod review;
mod salvage;
mod schema;
mod vlm_judge;

pub use planner::{LlmPlanner, MIN_OBJECTS};
pub use review::{ObjectReason, MAX_REVIEW_OBJECTS, MAX_REVIEW_TEXT_CHARS};
pub use schema::{
    plan_max_tokens, plan_schema, MAX_ANSWER_OBJECTS, PLAN_OVERHEAD_TOKENS, TOKENS_PER_OBJECT,
};
pub use vlm_judge::{review_max_tokens, review_schema, VlmJudge, VlmReview, VlmThresholds};
