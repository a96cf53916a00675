//! Language agents over any [`scenethesis_models::ChatModel`]: [`LlmPlanner`] turns a prompt
//! into the same [`scenethesis_agents::Plan`] the offline planner makes, following the paper's
//! coarse planning (interpret the prompt, review the library's categories, select objects and
//! an anchor, cross-check each against the library, lay out a background / middle /
//! foreground hierarchy with relations, write the up-sampled prompt).
//!
//! This crate has no HTTP of its own: give it an `scenethesis-openai` client, a cached one, or
//! any other implementation of the trait.
#![warn(missing_docs)]

mod convert;
mod planner;
mod schema;

pub use planner::{LlmPlanner, MIN_OBJECTS};
pub use schema::plan_schema;
