//! What a device renders with, built once: the bind group layouts, the three pipelines
//! (scene, background, shadow) sharing one shader, and the shadow map's comparison sampler.

use super::{COLOR_FORMAT, DEPTH_FORMAT, VALUE_FORMAT};
use crate::geometry::Vertex;

/// The layouts, pipelines and sampler of a [`Renderer`](super::Renderer).
pub(super) struct Pipelines {
    /// Group 0 of every pass: the uniform block.
    pub(super) globals_layout: wgpu::BindGroupLayout,
    /// Group 1 of the scene pass: the shadow map and its sampler.
    pub(super) shadow_layout: wgpu::BindGroupLayout,
    /// Lit, shadowed geometry into the colour, linear-depth and instance targets.
    pub(super) scene: wgpu::RenderPipeline,
    /// The backdrop's gradient, drawn first as one full-screen triangle.
    pub(super) background: wgpu::RenderPipeline,
    /// Depth only, from the sun.
    pub(super) shadow: wgpu::RenderPipeline,
    /// Bilinear depth comparison for soft shadow edges.
    pub(super) shadow_sampler: wgpu::Sampler,
}

/// What differs between the three pipelines; they share the shader and the colour targets.
struct PipelineSpec<'a> {
    label: &'a str,
    layout: &'a wgpu::PipelineLayout,
    vertex_entry: &'a str,
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    cull_mode: Option<wgpu::Face>,
    depth: wgpu::DepthStencilState,
    fragment_entry: Option<&'a str>,
}

impl Pipelines {
    /// Compiles the shader and builds everything on `device`.
    pub(super) fn build(device: &wgpu::Device) -> Self {
        let shader = device.create_shader_module(wgpu::include_wgsl!("../shader.wgsl"));
        let globals_layout = globals_layout(device);
        let shadow_layout = shadow_layout(device);
        let layout = |label, groups: &[Option<&wgpu::BindGroupLayout>]| {
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: groups,
                immediate_size: 0,
            })
        };
        let scene_layout = layout("scene", &[Some(&globals_layout), Some(&shadow_layout)]);
        let globals_only = layout("globals only", &[Some(&globals_layout)]);
        let vertices = [Some(vertex_layout())];
        let scene = pipeline(
            device,
            &shader,
            PipelineSpec {
                label: "scene",
                layout: &scene_layout,
                vertex_entry: "vs_scene",
                buffers: &vertices,
                cull_mode: Some(wgpu::Face::Back),
                depth: depth_state(true, wgpu::CompareFunction::Less, Default::default()),
                fragment_entry: Some("fs_scene"),
            },
        );
        let background = pipeline(
            device,
            &shader,
            PipelineSpec {
                label: "background",
                layout: &globals_only,
                vertex_entry: "vs_background",
                buffers: &[],
                cull_mode: None,
                depth: depth_state(false, wgpu::CompareFunction::Always, Default::default()),
                fragment_entry: Some("fs_background"),
            },
        );
        let shadow = pipeline(device, &shader, shadow_spec(&globals_only, &vertices));
        Self {
            globals_layout,
            shadow_layout,
            scene,
            background,
            shadow,
            shadow_sampler: shadow_sampler(device),
        }
    }
}

/// The shadow pipeline: depth only, biased against acne.
fn shadow_spec<'a>(
    layout: &'a wgpu::PipelineLayout,
    vertices: &'a [Option<wgpu::VertexBufferLayout<'a>>],
) -> PipelineSpec<'a> {
    PipelineSpec {
        label: "shadow",
        layout,
        vertex_entry: "vs_shadow",
        buffers: vertices,
        cull_mode: None,
        depth: depth_state(
            true,
            wgpu::CompareFunction::Less,
            wgpu::DepthBiasState {
                constant: 2,
                slope_scale: 2.0,
                clamp: 0.0,
            },
        ),
        fragment_entry: None,
    }
}

/// A render pipeline of `shader` after `spec`, writing the three colour targets when it has
/// a fragment stage.
fn pipeline(
    device: &wgpu::Device,
    shader: &wgpu::ShaderModule,
    spec: PipelineSpec<'_>,
) -> wgpu::RenderPipeline {
    let targets = [
        Some(wgpu::ColorTargetState::from(COLOR_FORMAT)),
        Some(wgpu::ColorTargetState::from(VALUE_FORMAT)),
        Some(wgpu::ColorTargetState::from(VALUE_FORMAT)),
    ];
    device.create_render_pipeline(&wgpu::RenderPipelineDescriptor {
        label: Some(spec.label),
        layout: Some(spec.layout),
        vertex: wgpu::VertexState {
            module: shader,
            entry_point: Some(spec.vertex_entry),
            compilation_options: Default::default(),
            buffers: spec.buffers,
        },
        primitive: wgpu::PrimitiveState {
            cull_mode: spec.cull_mode,
            ..Default::default()
        },
        depth_stencil: Some(spec.depth),
        multisample: wgpu::MultisampleState::default(),
        fragment: spec.fragment_entry.map(|entry| wgpu::FragmentState {
            module: shader,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            targets: &targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// Depth testing with `compare`, writing depth when `write`, with `bias`.
fn depth_state(
    write: bool,
    compare: wgpu::CompareFunction,
    bias: wgpu::DepthBiasState,
) -> wgpu::DepthStencilState {
    wgpu::DepthStencilState {
        format: DEPTH_FORMAT,
        depth_write_enabled: Some(write),
        depth_compare: Some(compare),
        stencil: wgpu::StencilState::default(),
        bias,
    }
}

/// A [`Vertex`]: position, normal, albedo and instance index.
fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &VERTEX_ATTRIBUTES,
    }
}

/// The attributes of a [`Vertex`], in shader locations 0–3.
const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 4] =
    wgpu::vertex_attr_array![0 => Float32x3, 1 => Float32x3, 2 => Float32x3, 3 => Uint32];

/// Group 0: one uniform buffer seen by vertex and fragment stages.
fn globals_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
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
    })
}

/// Group 1 of the scene pass: the depth texture of the shadow map and a comparison sampler.
fn shadow_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
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
    })
}

/// Clamped, bilinear, `LessEqual` comparison: soft shadow edges.
fn shadow_sampler(device: &wgpu::Device) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("shadow"),
        address_mode_u: wgpu::AddressMode::ClampToEdge,
        address_mode_v: wgpu::AddressMode::ClampToEdge,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        compare: Some(wgpu::CompareFunction::LessEqual),
        ..Default::default()
    })
}
