//! The wgpu renderer: adapter selection, pipelines, the shadow pass and frame read-back.

use std::ops::Range;
use std::sync::mpsc;

use bytemuck::{Pod, Zeroable};
use image::RgbaImage;
use nalgebra::{Matrix4, Point3, Vector3};
use scenethesis_imagery::{Camera, DepthMap};
use scenethesis_scene_graph::Aabb;
use wgpu::util::DeviceExt;

use crate::backend::{adapter_rank, backend_names};
use crate::geometry::{SceneGeometry, Vertex, WallRange};
use crate::{Backdrop, BackendChoice, Frame, RenderError, RenderScene};

const COLOR_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Rgba8UnormSrgb;
const VALUE_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::R32Uint;
const DEPTH_FORMAT: wgpu::TextureFormat = wgpu::TextureFormat::Depth32Float;
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
}

impl Default for RendererOptions {
    fn default() -> Self {
        Self {
            backend: BackendChoice::Auto,
            shadows: true,
            shadow_map_size: 2048,
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
        Backdrop::Interior => Palette {
            sun: [0.74, 0.72, 0.68],
            sky_ambient: [0.44, 0.44, 0.47],
            ground_ambient: [0.22, 0.20, 0.18],
            top: [0.10, 0.10, 0.12],
            horizon: [0.22, 0.22, 0.24],
            bottom: [0.08, 0.08, 0.08],
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
    globals_layout: wgpu::BindGroupLayout,
    shadow_layout: wgpu::BindGroupLayout,
    scene_pipeline: wgpu::RenderPipeline,
    background_pipeline: wgpu::RenderPipeline,
    shadow_pipeline: wgpu::RenderPipeline,
    shadow_sampler: wgpu::Sampler,
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
        let backends = options.backend.backends();
        let instance = wgpu::Instance::new(wgpu::InstanceDescriptor {
            backends,
            ..wgpu::InstanceDescriptor::new_without_display_handle()
        });
        let adapters = pollster::block_on(instance.enumerate_adapters(backends));
        let no_adapter = |reason: String| RenderError::NoAdapter {
            backends: backend_names(backends),
            reason,
        };
        // The best-ranked adapter; among equals, the first one enumerated.
        let mut best: Option<(u32, wgpu::Adapter)> = None;
        for adapter in adapters {
            let info = adapter.get_info();
            let rank = adapter_rank(info.device_type, info.backend);
            if best.as_ref().is_none_or(|(r, _)| rank > *r) {
                best = Some((rank, adapter));
            }
        }
        let (_, adapter) = best.ok_or_else(|| no_adapter("none was found".into()))?;
        let info = adapter.get_info();
        // Everything the adapter offers: large images, three colour targets.
        let limits = adapter.limits();
        let (device, queue) = pollster::block_on(adapter.request_device(&wgpu::DeviceDescriptor {
            label: Some("scenethesis-render"),
            required_limits: limits,
            ..Default::default()
        }))
        .map_err(|source| RenderError::Device {
            adapter: format!("{} ({:?})", info.name, info.backend),
            source,
        })?;
        tracing::info!(adapter = %info.name, backend = ?info.backend, "renderer ready");

        let shader = device.create_shader_module(wgpu::include_wgsl!("shader.wgsl"));
        let globals_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("globals"),
            entries: &[wgpu::BindGroupLayoutEntry {
                binding: 0,
                visibility: wgpu::ShaderStages::VERTEX_FRAGMENT,
                ty: wgpu::BindingType::Buffer {
                    ty: wgpu::BufferBindingType::Uniform,
                    has_dynamic_offset: false,
                    min_binding_size: None,
                },
                count: None,
            }],
        });
        let shadow_layout = device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
            label: Some("shadow map"),
            entries: &[
                wgpu::BindGroupLayoutEntry {
                    binding: 0,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Texture {
                        sample_type: wgpu::TextureSampleType::Depth,
                        view_dimension: wgpu::TextureViewDimension::D2,
                        multisampled: false,
                    },
                    count: None,
                },
                wgpu::BindGroupLayoutEntry {
                    binding: 1,
                    visibility: wgpu::ShaderStages::FRAGMENT,
                    ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Comparison),
                    count: None,
                },
            ],
        });
        let scene_layout = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("scene"),
            bind_group_layouts: &[Some(&globals_layout), Some(&shadow_layout)],
            immediate_size: 0,
        });
        let globals_only = device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
            label: Some("globals only"),
            bind_group_layouts: &[Some(&globals_layout)],
            immediate_size: 0,
        });
        let vertex_layout = wgpu::VertexBufferLayout {
            array_stride: std::mem::size_of::<Vertex>() as u64,
            step_mode: wgpu::VertexStepMode::Vertex,
            attributes: &wgpu::vertex_attr_array![
                0 => Float32x3, 1 => Float32x3, 2 => Float32x3, 3 => Uint32
            ],
        };
        let targets = [
            Some(wgpu::ColorTargetState::from(COLOR_FORMAT)),
            Some(wgpu::ColorTargetState::from(VALUE_FORMAT)),
            Some(wgpu::ColorTargetState::from(VALUE_FORMAT)),
        ];
        let depth_state = |write: bool, compare, bias| wgpu::DepthStencilState {
            format: DEPTH_FORMAT,
            depth_write_enabled: Some(write),
            depth_compare: Some(compare),
            stencil: wgpu::StencilState::default(),
            bias,
        };
        // The three pipelines share the shader, the colour targets and everything but these.
        let pipeline = |label: &str,
                        layout: &wgpu::PipelineLayout,
                        vertex_entry: &str,
                        buffers: &[Option<wgpu::VertexBufferLayout>],
                        cull_mode: Option<wgpu::Face>,
                        depth_stencil: wgpu::DepthStencilState,
                        fragment_entry: Option<&str>| {
            device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
                label: Some(label),
                layout: Some(layout),
                vertex: wgpu::VertexState {
                    module: &shader,
                    entry_point: Some(vertex_entry),
                    compilation_options: Default::default(),
                    buffers,
                },
                primitive: wgpu::PrimitiveState {
                    cull_mode,
                    ..Default::default()
                },
                depth_stencil: Some(depth_stencil),
                multisample: wgpu::MultisampleState::default(),
                fragment: fragment_entry.map(|entry| wgpu::FragmentState {
                    module: &shader,
                    entry_point: Some(entry),
                    compilation_options: Default::default(),
                    targets: &targets,
                }),
                multiview_mask: None,
                cache: None,
            })
        };
        let scene_pipeline = pipeline(
            "scene",
            &scene_layout,
            "vs_scene",
            &[Some(vertex_layout.clone())],
            Some(wgpu::Face::Back),
            depth_state(
                true,
                wgpu::CompareFunction::Less,
                wgpu::DepthBiasState::default(),
            ),
            Some("fs_scene"),
        );
        let background_pipeline = pipeline(
            "background",
            &globals_only,
            "vs_background",
            &[],
            None,
            depth_state(
                false,
                wgpu::CompareFunction::Always,
                wgpu::DepthBiasState::default(),
            ),
            Some("fs_background"),
        );
        let shadow_pipeline = pipeline(
            "shadow",
            &globals_only,
            "vs_shadow",
            &[Some(vertex_layout)],
            None,
            depth_state(
                true,
                wgpu::CompareFunction::Less,
                wgpu::DepthBiasState {
                    constant: 2,
                    slope_scale: 2.0,
                    clamp: 0.0,
                },
            ),
            None,
        );
        let shadow_sampler = device.create_sampler(&wgpu::SamplerDescriptor {
            label: Some("shadow"),
            address_mode_u: wgpu::AddressMode::ClampToEdge,
            address_mode_v: wgpu::AddressMode::ClampToEdge,
            mag_filter: wgpu::FilterMode::Linear,
            min_filter: wgpu::FilterMode::Linear,
            compare: Some(wgpu::CompareFunction::LessEqual),
            ..Default::default()
        });
        Ok(Self {
            device,
            queue,
            info,
            options,
            globals_layout,
            shadow_layout,
            scene_pipeline,
            background_pipeline,
            shadow_pipeline,
            shadow_sampler,
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

    /// Uploads a scene's geometry and renders its shadow map, for rendering many views.
    pub fn prepare(&self, scene: &RenderScene) -> Result<PreparedScene, RenderError> {
        let geometry = SceneGeometry::build(scene)?;
        let bounds = scene.bounds();
        let center = bounds.center();
        let reach = geometry
            .vertices
            .iter()
            .map(|v| (Point3::from(v.position).cast::<f64>() - center).norm())
            .fold(bounds.size().norm() / 2.0, f64::max);
        let vertices = (!geometry.vertices.is_empty()).then(|| {
            self.device
                .create_buffer_init(&wgpu::util::BufferInitDescriptor {
                    label: Some("scene vertices"),
                    contents: bytemuck::cast_slice(&geometry.vertices),
                    usage: wgpu::BufferUsages::VERTEX,
                })
        });

        // The sun's orthographic frustum: a cube around the objects' and room's bounding sphere.
        let radius = (bounds.size().norm() / 2.0).max(0.5);
        let light_from_world = light_matrix(&bounds, radius);
        let size = self.options.shadow_map_size.max(1);
        let shadow_texel = 2.0 * radius / size as f64;
        let shadow_texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some("shadow map"),
            size: wgpu::Extent3d {
                width: size,
                height: size,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: DEPTH_FORMAT,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        let shadow_view = shadow_texture.create_view(&Default::default());
        if let (Some(buffer), true) = (&vertices, self.options.shadows) {
            let mut globals = Globals::zeroed();
            globals.light_from_world = mat(&light_from_world);
            let uniform = self.uniform(&globals);
            let mut encoder = self.device.create_command_encoder(&Default::default());
            {
                let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                    label: Some("shadow"),
                    depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                        view: &shadow_view,
                        depth_ops: Some(wgpu::Operations {
                            load: wgpu::LoadOp::Clear(1.0),
                            store: wgpu::StoreOp::Store,
                        }),
                        stencil_ops: None,
                    }),
                    ..Default::default()
                });
                pass.set_pipeline(&self.shadow_pipeline);
                pass.set_bind_group(0, &uniform, &[]);
                pass.set_vertex_buffer(0, buffer.slice(..));
                pass.draw(geometry.objects.clone(), 0..1);
            }
            self.queue.submit([encoder.finish()]);
        } else {
            // No casters: clear the map so every lookup reads "lit".
            let mut encoder = self.device.create_command_encoder(&Default::default());
            encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow clear"),
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &shadow_view,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            self.queue.submit([encoder.finish()]);
        }
        let shadow_group = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shadow map"),
            layout: &self.shadow_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&shadow_view),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&self.shadow_sampler),
                },
            ],
        });
        Ok(PreparedScene {
            vertices,
            always: geometry.always,
            walls: geometry.walls,
            ids: geometry.ids,
            backdrop: scene.backdrop,
            cut_away_walls: scene.cut_away_walls,
            bounds,
            reach,
            light_from_world,
            shadow_texel,
            shadow_group,
        })
    }

    /// Renders a prepared scene from `camera` and reads the three images back.
    pub fn render_prepared(
        &self,
        scene: &PreparedScene,
        camera: &Camera,
    ) -> Result<Frame, RenderError> {
        let k = camera.intrinsics;
        let max = self.device.limits().max_texture_dimension_2d;
        if k.width == 0 || k.height == 0 || k.width > max || k.height > max {
            return Err(RenderError::InvalidSize {
                width: k.width,
                height: k.height,
                max,
            });
        }
        let finite = [k.fx, k.fy, k.cx, k.cy]
            .iter()
            .chain(camera.position.iter())
            .chain(camera.rotation.coords.iter())
            .all(|v| v.is_finite());
        if !finite || k.fx <= 0.0 || k.fy <= 0.0 {
            return Err(RenderError::InvalidCamera(format!("{camera:?}")));
        }

        // Depth range from the scene's extent as seen from this camera.
        let distance = (camera.position - scene.bounds.center()).norm();
        let far = distance + scene.reach + 1.0;
        let near = ((distance - scene.reach) * 0.5).clamp(0.01, far * 0.01);
        let view = camera.view_matrix();
        let clip_from_world = camera.clip_from_camera(near, far) * view;
        let rotation = camera.rotation.to_rotation_matrix();
        let column = |i: usize| {
            let c = rotation.matrix().column(i);
            [c[0] as f32, c[1] as f32, c[2] as f32, 0.0]
        };
        let sun = Vector3::from(SUN_DIRECTION).normalize();
        let colors = palette(scene.backdrop);
        let rgb = |c: [f32; 3]| [c[0], c[1], c[2], 1.0];
        let globals = Globals {
            clip_from_world: mat(&clip_from_world),
            light_from_world: mat(&scene.light_from_world),
            view_z: [
                view[(2, 0)] as f32,
                view[(2, 1)] as f32,
                view[(2, 2)] as f32,
                view[(2, 3)] as f32,
            ],
            light_dir: [
                sun.x as f32,
                sun.y as f32,
                sun.z as f32,
                scene.shadow_texel as f32,
            ],
            sun: [
                colors.sun[0],
                colors.sun[1],
                colors.sun[2],
                if self.options.shadows { 1.0 } else { 0.0 },
            ],
            sky_ambient: rgb(colors.sky_ambient),
            ground_ambient: rgb(colors.ground_ambient),
            cam_right: column(0),
            cam_up: column(1),
            cam_back: column(2),
            intrinsics: [k.fx as f32, k.fy as f32, k.cx as f32, k.cy as f32],
            bg_top: rgb(colors.top),
            bg_horizon: rgb(colors.horizon),
            bg_bottom: rgb(colors.bottom),
        };
        let uniform = self.uniform(&globals);

        let (width, height) = (k.width, k.height);
        let extent = wgpu::Extent3d {
            width,
            height,
            depth_or_array_layers: 1,
        };
        let target = |label, format, usage| {
            self.device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size: extent,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let readable = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let color = target("colour", COLOR_FORMAT, readable);
        let depth_bits = target("linear depth", VALUE_FORMAT, readable);
        let instance = target("instance", VALUE_FORMAT, readable);
        let zbuffer = target(
            "z-buffer",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
        );
        let views = [&color, &depth_bits, &instance].map(|t| t.create_view(&Default::default()));
        let zview = zbuffer.create_view(&Default::default());

        // All three targets are 4 bytes per pixel; rows are padded to 256 bytes for the copy.
        let row = width as u64 * 4;
        let padded = row.div_ceil(256) * 256;
        let plane = padded * height as u64;
        let readback = self.device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read-back"),
            size: plane * 3,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });

        let mut encoder = self.device.create_command_encoder(&Default::default());
        {
            let attachments = views.each_ref().map(|view| {
                Some(wgpu::RenderPassColorAttachment {
                    view,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                        store: wgpu::StoreOp::Store,
                    },
                })
            });
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("scene"),
                color_attachments: &attachments,
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: &zview,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Discard,
                    }),
                    stencil_ops: None,
                }),
                timestamp_writes: None,
                occlusion_query_set: None,
                multiview_mask: None,
            });
            pass.set_bind_group(0, &uniform, &[]);
            pass.set_pipeline(&self.background_pipeline);
            pass.draw(0..3, 0..1);
            if let Some(buffer) = &scene.vertices {
                pass.set_pipeline(&self.scene_pipeline);
                pass.set_bind_group(1, &scene.shadow_group, &[]);
                pass.set_vertex_buffer(0, buffer.slice(..));
                pass.draw(scene.always.clone(), 0..1);
                for wall in &scene.walls {
                    if !(scene.cut_away_walls && camera_behind_wall(camera, wall)) {
                        pass.draw(wall.vertices.clone(), 0..1);
                    }
                }
            }
        }
        for (i, texture) in [&color, &depth_bits, &instance].into_iter().enumerate() {
            encoder.copy_texture_to_buffer(
                texture.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &readback,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: plane * i as u64,
                        bytes_per_row: Some(padded as u32),
                        rows_per_image: Some(height),
                    },
                },
                extent,
            );
        }
        self.queue.submit([encoder.finish()]);

        let (sender, receiver) = mpsc::channel();
        readback.map_async(wgpu::MapMode::Read, .., move |result| {
            // The receiver outlives the poll below; a failed send only means it was dropped.
            let _ = sender.send(result);
        });
        self.device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        receiver
            .recv()
            .map_err(|e| RenderError::Readback(e.to_string()))?
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let mapped = readback
            .get_mapped_range(..)
            .map_err(|e| RenderError::Readback(e.to_string()))?;
        let unpad = |plane_index: u64| -> Vec<u8> {
            let base = plane * plane_index;
            let mut out = Vec::with_capacity((row * height as u64) as usize);
            for y in 0..height as u64 {
                let start = (base + y * padded) as usize;
                out.extend_from_slice(&mapped[start..start + row as usize]);
            }
            out
        };
        let color_bytes = unpad(0);
        let depth: Vec<f32> = unpad(1)
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        // The depth target holds distances ≥ 0 (0 = background), so the map always builds.
        let depth = DepthMap::new(width, height, depth).map_err(|e| {
            RenderError::Readback(format!("the depth buffer read back malformed: {e}"))
        })?;
        let instance: Vec<u32> = unpad(2)
            .chunks_exact(4)
            .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        drop(mapped);
        readback.unmap();
        Ok(Frame {
            color: RgbaImage::from_raw(width, height, color_bytes).expect("4 bytes per pixel"),
            depth,
            instance,
            ids: scene.ids.clone(),
        })
    }

    /// The colour image of `camera`'s view rendered at `factor` × its resolution and averaged
    /// down (in linear light) to the camera's size: anti-aliased previews. `factor` 1 is a
    /// plain render.
    pub fn render_color_supersampled(
        &self,
        scene: &PreparedScene,
        camera: &Camera,
        factor: u32,
    ) -> Result<RgbaImage, RenderError> {
        let factor = factor.max(1);
        let k = camera.intrinsics;
        let mut big = *camera;
        big.intrinsics = k.resized(k.width * factor, k.height * factor);
        let frame = self.render_prepared(scene, &big)?;
        if factor == 1 {
            return Ok(frame.color);
        }
        let to_linear: Vec<f32> = (0..256)
            .map(|v| {
                let c = v as f32 / 255.0;
                if c <= 0.04045 {
                    c / 12.92
                } else {
                    ((c + 0.055) / 1.055).powf(2.4)
                }
            })
            .collect();
        let to_srgb = |l: f32| {
            let c = if l <= 0.003_130_8 {
                l * 12.92
            } else {
                1.055 * l.powf(1.0 / 2.4) - 0.055
            };
            (c * 255.0).round().clamp(0.0, 255.0) as u8
        };
        let n = (factor * factor) as f32;
        Ok(RgbaImage::from_fn(k.width, k.height, |x, y| {
            let mut sum = [0.0f32; 3];
            for dy in 0..factor {
                for dx in 0..factor {
                    let p = frame.color.get_pixel(x * factor + dx, y * factor + dy).0;
                    for c in 0..3 {
                        sum[c] += to_linear[p[c] as usize];
                    }
                }
            }
            image::Rgba([
                to_srgb(sum[0] / n),
                to_srgb(sum[1] / n),
                to_srgb(sum[2] / n),
                255,
            ])
        }))
    }

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
            layout: &self.globals_layout,
            entries: &[wgpu::BindGroupEntry {
                binding: 0,
                resource: buffer.as_entire_binding(),
            }],
        })
    }
}

/// Whether the camera stands on the outer side of a wall (so the wall would hide the room).
fn camera_behind_wall(camera: &Camera, wall: &WallRange) -> bool {
    let c = nalgebra::Vector2::new(camera.position.x, camera.position.z);
    (c - wall.start.coords).dot(&wall.inward) < -wall.thickness / 2.0
}

/// The sun's orthographic clip-from-world matrix for a sphere of `radius` around the box's
/// centre: x, y in [−1, 1] across the sun's view, depth in [0, 1] along its rays.
fn light_matrix(bounds: &Aabb, radius: f64) -> Matrix4<f64> {
    let toward_sun = Vector3::from(SUN_DIRECTION).normalize();
    let forward = -toward_sun;
    let reference = if forward.y.abs() > 0.99 {
        Vector3::z()
    } else {
        Vector3::y()
    };
    let right = forward.cross(&reference).normalize();
    let up = right.cross(&forward);
    let c = bounds.center().coords;
    let r = radius;
    Matrix4::new(
        right.x / r,
        right.y / r,
        right.z / r,
        -right.dot(&c) / r,
        up.x / r,
        up.y / r,
        up.z / r,
        -up.dot(&c) / r,
        forward.x / (2.0 * r),
        forward.y / (2.0 * r),
        forward.z / (2.0 * r),
        (r - forward.dot(&c)) / (2.0 * r),
        0.0,
        0.0,
        0.0,
        1.0,
    )
}

/// A column-major f32 matrix for WGSL.
fn mat(m: &Matrix4<f64>) -> [[f32; 4]; 4] {
    let m = m.cast::<f32>();
    [0, 1, 2, 3].map(|c| [m[(0, c)], m[(1, c)], m[(2, c)], m[(3, c)]])
}
