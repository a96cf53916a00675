//! The wgpu renderer, one file a phase: opening the device ([`device`]), building the
//! pipelines ([`pipelines`]), the material maps kept on the device ([`textures`]), uploading a
//! scene with its shadow map ([`prepare`]), rendering a view with its ambient occlusion and
//! reading it back ([`view`]), and anti-aliased previews ([`supersample`]).

mod device;
mod pipelines;
mod prepare;
mod supersample;
mod textures;
mod view;

use std::ops::Range;

use bytemuck::{Pod, Zeroable};
use nalgebra::Matrix4;
use scenethesis_imagery::Camera;
use scenethesis_scene_graph::Aabb;
use wgpu::util::DeviceExt;

use crate::geometry::WallRange;
use crate::{Backdrop, BackendChoice, Frame, RenderError, RenderScene};
use pipelines::Pipelines;
use textures::MaterialTextures;

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
const VALUE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
/// The shadow tint: the light see-through casters let pass (rgb) and the nearest one's depth
/// from the sun (alpha), both kept as the minimum over the casters.
const TINT_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba16Float;
/// Unit direction toward the sun (from the front right, high up).
const SUN_DIRECTION: [f64; 3] = [0.4, 1.0, 0.6];

/// How to set up a [`Renderer`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RendererOptions {
    /// Which backend to open.
    pub backend: BackendChoice,
    /// Soft shadows from the sun (objects shadow the floor and each other).
    pub shadows: bool,
    /// Side of the square shadow map in texels.
    pub shadow_map_size: u32,
    /// Screen-space ambient occlusion: creases, corners and contact under objects darken
    /// their ambient light.
    pub ambient_occlusion: bool,
}

impl Default for RendererOptions {
    fn default() -> Self {
        Self {
            backend: BackendChoice::Auto,
            shadows: true,
            shadow_map_size: 2048,
            ambient_occlusion: true,
        }
    }
}

impl RendererOptions {
    /// The defaults, with the backend taken from `WGPU_BACKEND` when it is set.
    pub fn from_env() -> Result<Self, RenderError> {
        Ok(Self {
            backend: BackendChoice::from_env()?,
            ..Self::default()
        })
    }
}

/// The uniform block shared by every pass (see `shader.wgsl`).
#[repr(C)]
#[derive(Debug, Clone, Copy, Pod, Zeroable)]
struct Globals {
    clip_from_world: [[f32; 4]; 4],
    light_from_world: [[f32; 4]; 4],
    view_z: [f32; 4],
    light_dir: [f32; 4],
    sun: [f32; 4],
    sky_ambient: [f32; 4],
    ground_ambient: [f32; 4],
    cam_right: [f32; 4],
    cam_up: [f32; 4],
    cam_back: [f32; 4],
    intrinsics: [f32; 4],
    bg_top: [f32; 4],
    bg_horizon: [f32; 4],
    bg_bottom: [f32; 4],
    eye: [f32; 4],
    occlusion: [f32; 4],
}

/// Light and background colours of a backdrop (linear RGB).
struct Palette {
    sun: [f32; 3],
    sky_ambient: [f32; 3],
    ground_ambient: [f32; 3],
    top: [f32; 3],
    horizon: [f32; 3],
    bottom: [f32; 3],
}

fn palette(backdrop: Backdrop) -> Palette {
    match backdrop {
        Backdrop::Studio => Palette {
            sun: [0.78, 0.76, 0.72],
            sky_ambient: [0.42, 0.43, 0.46],
            ground_ambient: [0.20, 0.19, 0.18],
            top: [0.62, 0.63, 0.66],
            horizon: [0.80, 0.80, 0.81],
            bottom: [0.55, 0.55, 0.55],
        },
        // Daylight through the windows as the key light, the ceiling's and the floor's
        // bounce as the fill, and a clear sky beyond the room.
        Backdrop::Interior => Palette {
            sun: [0.78, 0.74, 0.66],
            sky_ambient: [0.46, 0.46, 0.48],
            ground_ambient: [0.24, 0.21, 0.18],
            top: [0.22, 0.40, 0.74],
            horizon: [0.70, 0.79, 0.90],
            bottom: [0.34, 0.33, 0.31],
        },
        Backdrop::Sky => Palette {
            sun: [0.95, 0.90, 0.80],
            sky_ambient: [0.34, 0.40, 0.52],
            ground_ambient: [0.20, 0.18, 0.14],
            top: [0.16, 0.32, 0.72],
            horizon: [0.68, 0.78, 0.90],
            bottom: [0.40, 0.42, 0.36],
        },
    }
}

/// An open GPU device with the pipelines to render scenes. Creating one takes tens to
/// hundreds of milliseconds (adapter, shader compilation); keep it for many renders.
pub struct Renderer {
    device: wgpu::Device,
    queue: wgpu::Queue,
    info: wgpu::AdapterInfo,
    options: RendererOptions,
    pipelines: Pipelines,
    textures: MaterialTextures,
    /// Held while textures are written and while commands are submitted: wgpu-core can
    /// deadlock when one thread writes a texture as another submits (two test threads sharing
    /// a renderer on llvmpipe did).
    queue_lock: std::sync::Mutex<()>,
}

impl Renderer {
    /// The queue's lock ([`Renderer::queue_lock`]), taken even if a panicking thread held it.
    fn queue_guard(&self) -> std::sync::MutexGuard<'_, ()> {
        self.queue_lock
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }
}

impl std::fmt::Debug for Renderer {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Renderer")
            .field("adapter", &self.adapter_description())
            .field("options", &self.options)
            .finish()
    }
}

/// A scene uploaded to the GPU with its shadow map, ready to be rendered from many cameras.
pub struct PreparedScene {
    vertices: Option<wgpu::Buffer>,
    always: Range<u32>,
    walls: Vec<WallRange>,
    ids: Vec<String>,
    backdrop: Backdrop,
    cut_away_walls: bool,
    bounds: Aabb,
    reach: f64,
    light_from_world: Matrix4<f64>,
    shadow_texel: f64,
    shadow_group: wgpu::BindGroup,
}

impl std::fmt::Debug for PreparedScene {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("PreparedScene")
            .field("ids", &self.ids)
            .field("bounds", &self.bounds)
            .finish_non_exhaustive()
    }
}

impl PreparedScene {
    /// The id table of frames rendered from this scene (see [`Frame::ids`]).
    pub fn ids(&self) -> &[String] {
        &self.ids
    }
}

impl Renderer {
    /// Opens the adapter chosen by `options.backend` and builds the pipelines.
    pub fn new(options: RendererOptions) -> Result<Self, RenderError> {
        let (device, queue, info) = device::open(options.backend.backends())?;
        let pipelines = Pipelines::build(&device);
        let textures = MaterialTextures::new(
            &device,
            &pipelines.textures_layout,
            &pipelines.texture_sampler,
        );
        Ok(Self {
            device,
            queue,
            info,
            options,
            pipelines,
            textures,
            queue_lock: std::sync::Mutex::new(()),
        })
    }

    /// A renderer with [`RendererOptions::from_env`].
    pub fn from_env() -> Result<Self, RenderError> {
        Self::new(RendererOptions::from_env()?)
    }

    /// The adapter in use, e.g. `llvmpipe (LLVM 15.0.6, 256 bits) on Gl (Cpu)`.
    pub fn adapter_description(&self) -> String {
        format!(
            "{} on {:?} ({:?})",
            self.info.name, self.info.backend, self.info.device_type
        )
    }

    /// The backend of the adapter in use.
    pub fn backend(&self) -> wgpu::Backend {
        self.info.backend
    }

    /// Renders `scene` as seen by `camera` (uploads the scene, then [`Renderer::render_prepared`]).
    pub fn render(&self, scene: &RenderScene, camera: &Camera) -> Result<Frame, RenderError> {
        let prepared = self.prepare(scene)?;
        self.render_prepared(&prepared, camera)
    }

    /// A bind group holding `globals` as the uniform block of every pass.
    fn uniform(&self, globals: &Globals) -> wgpu::BindGroup {
        let buffer = self
            .device
            .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                label: Some("globals"),
                contents: bytemuck::bytes_of(globals),
                usage: wgpu::BufferUsages::UNIFORM,
            });
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("globals"),
            layout: &self.pipelines.globals_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }],
        })
    }
}

/// A column-major f32 matrix for WGSL.
fn mat(m: &Matrix4<f64>) -> [[f32; 4]; 4] {
    let m = m.cast::<f32>();
    [0, 1, 2, 3].map(|c| [m[(0, c)], m[(1, c)], m[(2, c)], m[(3, c)]])
}
