//! Headless rendering of posed meshes with wgpu: colour, metric depth and instance-id images
//! from a pinhole [`Camera`](scenethesis_imagery::Camera), on real GPUs or Mesa's
//! software drivers (GL llvmpipe through EGL, Vulkan lavapipe).
//!
//! A [`RenderScene`] holds [`Instance`]s (an id, a shared [`Mesh`](scenethesis_scene_graph::Mesh)
//! and a 5-DoF [`Pose`](scenethesis_scene_graph::Pose)), optionally the room's
//! [`Architecture`](scenethesis_scene_graph::Architecture) — its floor, and walls with their
//! door openings cut out — and a [`Backdrop`]. A [`Renderer`] turns it into a [`Frame`]:
//!
//! - `color`: sRGB; every part and room surface whose material resolves to the procedural
//!   library ([`scenethesis_materials`]) wears its base-colour, normal and metallic-roughness
//!   maps (texture coordinates in metres by the library's box projection, each material's maps
//!   uploaded once per renderer), lit by a key light (the sun, or daylight through a room's
//!   windows) with soft percentage-closer filtered shadows cast by the objects, a hemisphere
//!   fill (ceiling and floor bounce) with its reflection, and screen-space ambient occlusion;
//!   behind the scene, a sky gradient (rooms and outdoors) or a studio grey;
//! - `depth`: metres along the optical axis, exactly what [`Camera::project`] returns;
//! - `instance`: which object (or floor / wall) each pixel shows, with an id table.
//!
//! The projection is the camera's own [`Camera::clip_from_camera`], so renders and
//! correspondence agree to the pixel. Walls whose outer side faces the camera are cut away so
//! that views from outside see into the room. [`views`] computes photo, top and orbit cameras.
//!
//! [`Renderer`] implements the workspace's renderer seam,
//! [`SceneRenderer`](scenethesis_render_api::SceneRenderer): a scene graph goes in through
//! [`RenderScene::from_scene`], standard views ([`view_camera`]) come out as images.
//!
//! ```no_run
//! use scenethesis_render::{views, Renderer, RendererOptions, RenderScene};
//! # fn main() -> Result<(), Box<dyn std::error::Error>> {
//! let renderer = Renderer::new(RendererOptions::from_env()?)?;
//! let scene = RenderScene::studio(Vec::new());
//! let frame = renderer.render(&scene, &views::photo_view(&scene, 512, 384))?;
//! std::fs::write("preview.png", frame.color_png()?)?;
//! # Ok(()) }
//! ```
//!
//! [`Camera::project`]: scenethesis_imagery::Camera::project
//! [`Camera::clip_from_camera`]: scenethesis_imagery::Camera::clip_from_camera
#![warn(missing_docs)]

mod backend;
mod error;
mod frame;
mod geometry;
mod guidance;
pub mod labels;
mod renderer;
mod scene;
mod seam;
pub mod views;

pub use backend::BackendChoice;
pub use error::RenderError;
pub use frame::Frame;
pub use renderer::{PreparedScene, Renderer, RendererOptions};
pub use scene::{Backdrop, Instance, RenderScene};
pub use seam::view_camera;
