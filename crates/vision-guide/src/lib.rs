//! The vision guide: a guidance image and the plan's objects become the initial scene graph.
//!
//! [`VisionGuide`] is a [`scenethesis_agents::Guide`], the second one beside the procedural
//! guide. It reads an image — the user's own photo or RGB-D capture (given files,
//! [`GivenGuidance`]), or an image model's edit of our render of the plan's empty room (so the
//! camera and the room are known) — finds one mask per planned object (given instance masks,
//! or a vision-language model's boxes refined by a segmenter or used as they are), takes depth
//! from a file, a depth model or nobody (single-view metrology under the known camera), lifts
//! every mask to a gravity-aligned box with `scenethesis-vision` and assembles the scene graph
//! (ground → anchor → parents → children) with 5-DoF poses of the retrieved assets. It hands the
//! optimizer what it saw ([`scenethesis_imagery::Guidance`]) through
//! [`scenethesis_agents::GuidedLayout::guidance`].
//!
//! Models are reached only through the provider traits of `scenethesis-models`; the empty
//! room is rendered through the renderer seam,
//! [`SceneRenderer`](scenethesis_render_api::SceneRenderer), which `scenethesis-render`
//! implements with the GPU. This crate has no HTTP, GPU or model runtime.
//!
//! Modules, one phase each: [`source`] (where the image comes from, and file checks),
//! [`camera`] (a camera estimated from the floor), [`adopt`] (labelled objects the plan lacks
//! become planned objects), [`detect`] (masks for the planned objects),
//! [`photo`] (a photo alone: the prompt read from its masks, the floor checked), [`keep`] (`--keep-plan`: planned objects the image
//! does not show, placed offline around it), [`relations`] (the support relations a vision-language model states, cross-checked with the
//! lift), [`assemble`] (boxes → scene graph), and the guide itself.
#![warn(missing_docs)]

pub mod adopt;
pub mod assemble;
pub mod camera;
pub mod detect;
mod guide;
pub mod keep;
pub mod photo;
pub mod relations;
pub mod source;

pub use guide::{edit_prompt, VisionGuide};
pub use photo::{photo_scene, PhotoError, PhotoScene};
pub use source::{GivenGuidance, GuidanceFileError, GuidanceFiles};
