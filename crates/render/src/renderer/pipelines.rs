//! What a device renders with, built once: the bind group layouts, the seven pipelines
//! (depth pre-pass, scene, glass, background, shadow, shadow tint, ambient occlusion) sharing
//! one shader, the shadow map's samplers and the material textures' sampler.

use super::{COLOR_FORMAT, DEPTH_FORMAT, TINT_FORMAT, VALUE_FORMAT};
use crate::geometry::Vertex;

/// The layouts, pipelines and sampler of a [`Renderer`](super::Renderer).
pub(super) struct Pipelines {
    /// Group 0 of every pass: the uniform block.
    pub(super) globals_layout: wgpu::BindGroupLayout,
    /// Group 1 of the scene pass: the shadow map's depth and tint and their samplers.
    pub(super) shadow_layout: wgpu::BindGroupLayout,
    /// Group 2 of the scene pass: the material texture arrays and their sampler.
    pub(super) textures_layout: wgpu::BindGroupLayout,
    /// Group 1 of the ambient-occlusion pass: the lit colour and the linear depth.
    pub(super) occlusion_layout: wgpu::BindGroupLayout,
    /// Lit, shadowed geometry into the colour, linear-depth and instance targets.
    pub(super) scene: wgpu::RenderPipeline,
    /// The opaque surfaces' depth only, before the scene pass.
    pub(super) prepass: wgpu::RenderPipeline,
    /// See-through surfaces blended over the scene pass's colour, after it.
    pub(super) glass: wgpu::RenderPipeline,
    /// The backdrop's gradient, drawn first as one full-screen triangle.
    pub(super) background: wgpu::RenderPipeline,
    /// Depth only, from the sun: the opaque casters.
    pub(super) shadow: wgpu::RenderPipeline,
    /// The see-through casters into the shadow tint: the light they let through and their
    /// depth, each kept as the minimum over the casters.
    pub(super) shadow_tint: wgpu::RenderPipeline,
    /// Screen-space ambient occlusion applied to the lit colour, into the final colour.
    pub(super) occlusion: wgpu::RenderPipeline,
    /// Bilinear depth comparison for soft shadow edges.
    pub(super) shadow_sampler: wgpu::Sampler,
    /// Clamped bilinear filtering of the shadow tint.
    pub(super) tint_sampler: wgpu::Sampler,
    /// Repeating trilinear filtering of the material maps.
    pub(super) texture_sampler: wgpu::Sampler,
}

/// What differs between the pipelines; they share the shader.
struct PipelineSpec<'a> {
    label: &'a str,
    layout: &'a wgpu::PipelineLayout,
    vertex_entry: &'a str,
    buffers: &'a [Option<wgpu::VertexBufferLayout<'a>>],
    cull_mode: Option<wgpu::Face>,
    depth: Option<wgpu::DepthStencilState>,
    fragment_entry: Option<&'a str>,
    targets: &'a [Option<wgpu::ColorTargetState>],
}

impl Pipelines {
    /// Compiles the shader and builds everything on `device`.
    pub(super) fn build(device: &wgpu::Device) -> Self {
        let shader = device.create_shader_module(wgpu::include_wgsl!("../shader.wgsl"));
        let globals_layout = globals_layout(device);
        let shadow_layout = shadow_layout(device);
        let textures_layout = textures_layout(device);
        let occlusion_layout = occlusion_layout(device);
        let layout = |label, groups: &[Option<&wgpu::BindGroupLayout>]| {
            device.create_pipeline_layout(&wgpu::PipelineLayoutDescriptor {
                label: Some(label),
                bind_group_layouts: groups,
                immediate_size: 0,
            })
        };
        let scene_layout = layout(
            "scene",
            &[
                Some(&globals_layout),
                Some(&shadow_layout),
                Some(&textures_layout),
            ],
        );
        let globals_only = layout("globals only", &[Some(&globals_layout)]);
        let occlusion_pass = layout(
            "ambient occlusion",
            &[Some(&globals_layout), Some(&occlusion_layout)],
        );
        let vertices = [Some(vertex_layout())];
        let targets = [
            Some(wgpu::ColorTargetState::from(COLOR_FORMAT)),
            Some(wgpu::ColorTargetState::from(VALUE_FORMAT)),
            Some(wgpu::ColorTargetState::from(VALUE_FORMAT)),
        ];
        let scene = pipeline(
            device,
            &shader,
            PipelineSpec {
                label: "scene",
                layout: &scene_layout,
                vertex_entry: "vs_scene",
                buffers: &vertices,
                cull_mode: Some(wgpu::Face::Back),
                depth: Some(depth_state(
                    false,
                    wgpu::CompareFunction::LessEqual,
                    Default::default(),
                )),
                fragment_entry: Some("fs_scene"),
                targets: &targets,
            },
        );
        let untouched = glass_targets().map(|t| {
            t.map(|t| wgpu::ColorTargetState {
                blend: None,
                write_mask: wgpu::ColorWrites::empty(),
                ..t
            })
        });
        let prepass = pipeline(
            device,
            &shader,
            PipelineSpec {
                label: "depth pre-pass",
                layout: &scene_layout,
                vertex_entry: "vs_prepass",
                buffers: &vertices,
                cull_mode: Some(wgpu::Face::Back),
                depth: Some(depth_state(
                    true,
                    wgpu::CompareFunction::Less,
                    Default::default(),
                )),
                fragment_entry: Some("fs_prepass"),
                targets: &untouched,
            },
        );
        let glass_targets = glass_targets();
        let glass = pipeline(
            device,
            &shader,
            PipelineSpec {
                label: "glass",
                layout: &scene_layout,
                vertex_entry: "vs_glass",
                buffers: &vertices,
                cull_mode: Some(wgpu::Face::Back),
                depth: Some(depth_state(
                    false,
                    wgpu::CompareFunction::Less,
                    Default::default(),
                )),
                fragment_entry: Some("fs_glass"),
                targets: &glass_targets,
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
                depth: Some(depth_state(
                    false,
                    wgpu::CompareFunction::Always,
                    Default::default(),
                )),
                fragment_entry: Some("fs_background"),
                targets: &targets,
            },
        );
        let shadow = pipeline(
            device,
            &shader,
            PipelineSpec {
                label: "shadow",
                layout: &globals_only,
                vertex_entry: "vs_shadow",
                buffers: &vertices,
                cull_mode: None,
                depth: Some(depth_state(
                    true,
                    wgpu::CompareFunction::Less,
                    wgpu::DepthBiasState {
                        constant: 2,
                        slope_scale: 2.0,
                        clamp: 0.0,
                    },
                )),
                fragment_entry: None,
                targets: &[],
            },
        );
        let tint_target = [Some(wgpu::ColorTargetState {
            format: TINT_FORMAT,
            blend: Some(wgpu::BlendState {
                color: wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::One,
                    dst_factor: wgpu::BlendFactor::One,
                    operation: wgpu::BlendOperation::Min,
                },
                alpha: wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::One,
                    dst_factor: wgpu::BlendFactor::One,
                    operation: wgpu::BlendOperation::Min,
                },
            }),
            write_mask: wgpu::ColorWrites::ALL,
        })];
        let shadow_tint = pipeline(
            device,
            &shader,
            PipelineSpec {
                label: "shadow tint",
                layout: &globals_only,
                vertex_entry: "vs_shadow_glass",
                buffers: &vertices,
                cull_mode: None,
                depth: None,
                fragment_entry: Some("fs_shadow_tint"),
                targets: &tint_target,
            },
        );
        let occlusion = pipeline(
            device,
            &shader,
            PipelineSpec {
                label: "ambient occlusion",
                layout: &occlusion_pass,
                vertex_entry: "vs_background",
                buffers: &[],
                cull_mode: None,
                depth: None,
                fragment_entry: Some("fs_occlusion"),
                targets: &targets[..1],
            },
        );
        Self {
            globals_layout,
            shadow_layout,
            textures_layout,
            occlusion_layout,
            scene,
            prepass,
            glass,
            background,
            shadow,
            shadow_tint,
            occlusion,
            shadow_sampler: shadow_sampler(device),
            tint_sampler: tint_sampler(device),
            texture_sampler: texture_sampler(device),
        }
    }
}

/// A render pipeline of `shader` after `spec`, writing its colour targets when it has a
/// fragment stage.
fn pipeline(
    device: &wgpu::Device,
    shader: &wgpu::ShaderModule,
    spec: PipelineSpec<'_>,
) -> wgpu::RenderPipeline {
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
        depth_stencil: spec.depth,
        multisample: wgpu::MultisampleState::default(),
        fragment: spec.fragment_entry.map(|entry| wgpu::FragmentState {
            module: shader,
            entry_point: Some(entry),
            compilation_options: Default::default(),
            targets: spec.targets,
        }),
        multiview_mask: None,
        cache: None,
    })
}

/// The glass pass's targets: colour blended by the fragment's opacity (the ambient share in
/// alpha kept from the surface behind), depth and instance left untouched.
fn glass_targets() -> [Option<wgpu::ColorTargetState>; 3] {
    let keep = |format| {
        Some(wgpu::ColorTargetState {
            format,
            blend: None,
            write_mask: wgpu::ColorWrites::empty(),
        })
    };
    [
        Some(wgpu::ColorTargetState {
            format: COLOR_FORMAT,
            blend: Some(wgpu::BlendState {
                color: wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::SrcAlpha,
                    dst_factor: wgpu::BlendFactor::OneMinusSrcAlpha,
                    operation: wgpu::BlendOperation::Add,
                },
                alpha: wgpu::BlendComponent {
                    src_factor: wgpu::BlendFactor::Zero,
                    dst_factor: wgpu::BlendFactor::One,
                    operation: wgpu::BlendOperation::Add,
                },
            }),
            write_mask: wgpu::ColorWrites::ALL,
        }),
        keep(VALUE_FORMAT),
        keep(VALUE_FORMAT),
    ]
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

/// A [`Vertex`]: position, normal, albedo, instance index, texture coordinates, tangent,
/// roughness and metalness, texture layer.
fn vertex_layout() -> wgpu::VertexBufferLayout<'static> {
    wgpu::VertexBufferLayout {
        array_stride: std::mem::size_of::<Vertex>() as u64,
        step_mode: wgpu::VertexStepMode::Vertex,
        attributes: &VERTEX_ATTRIBUTES,
    }
}

/// The attributes of a [`Vertex`], in shader locations 0–7.
const VERTEX_ATTRIBUTES: [wgpu::VertexAttribute; 8] = wgpu::vertex_attr_array![
    0 => Float32x3,
    1 => Float32x3,
    2 => Float32x4,
    3 => Uint32,
    4 => Float32x2,
    5 => Float32x4,
    6 => Float32x2,
    7 => Uint32,
];

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

/// Group 1 of the scene pass: the depth texture of the shadow map with a comparison sampler,
/// and its tint with a filtering one.
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
            texture_entry(
                2,
                wgpu::TextureSampleType::Float { filterable: true },
                wgpu::TextureViewDimension::D2,
            ),
            wgpu::BindGroupLayoutEntry {
                binding: 3,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
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

/// Clamped and bilinear: the shadow tint blends across its texels like the depth comparison.
fn tint_sampler(device: &wgpu::Device) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("shadow tint"),
        address_mode_u: wgpu::AddressMode::ClampToEdge,
        address_mode_v: wgpu::AddressMode::ClampToEdge,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        ..Default::default()
    })
}

/// A fragment-stage texture binding of `sample_type` and `view_dimension`.
fn texture_entry(
    binding: u32,
    sample_type: wgpu::TextureSampleType,
    view_dimension: wgpu::TextureViewDimension,
) -> wgpu::BindGroupLayoutEntry {
    wgpu::BindGroupLayoutEntry {
        binding,
        visibility: wgpu::ShaderStages::FRAGMENT,
        ty: wgpu::BindingType::Texture {
            sample_type,
            view_dimension,
            multisampled: false,
        },
        count: None,
    }
}

/// Group 2 of the scene pass: base-colour, normal and metallic-roughness arrays (one layer
/// per library material) and a filtering sampler.
fn textures_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    let array = |binding| {
        texture_entry(
            binding,
            wgpu::TextureSampleType::Float { filterable: true },
            wgpu::TextureViewDimension::D2Array,
        )
    };
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("material textures"),
        entries: &[
            array(0),
            array(1),
            array(2),
            wgpu::BindGroupLayoutEntry {
                binding: 3,
                visibility: wgpu::ShaderStages::FRAGMENT,
                ty: wgpu::BindingType::Sampler(wgpu::SamplerBindingType::Filtering),
                count: None,
            },
        ],
    })
}

/// Group 1 of the ambient-occlusion pass: the lit colour (read texel by texel) and the
/// linear-depth bits.
fn occlusion_layout(device: &wgpu::Device) -> wgpu::BindGroupLayout {
    device.create_bind_group_layout(&wgpu::BindGroupLayoutDescriptor {
        label: Some("ambient occlusion"),
        entries: &[
            texture_entry(
                0,
                wgpu::TextureSampleType::Float { filterable: false },
                wgpu::TextureViewDimension::D2,
            ),
            texture_entry(
                1,
                wgpu::TextureSampleType::Uint,
                wgpu::TextureViewDimension::D2,
            ),
        ],
    })
}

/// Repeating (the maps tile), bilinear within the nearest mip level: textures stay calm where
/// they shrink, at half the texel reads of trilinear filtering (the previews' supersampling
/// hides the steps between levels).
fn texture_sampler(device: &wgpu::Device) -> wgpu::Sampler {
    device.create_sampler(&wgpu::SamplerDescriptor {
        label: Some("material maps"),
        address_mode_u: wgpu::AddressMode::Repeat,
        address_mode_v: wgpu::AddressMode::Repeat,
        mag_filter: wgpu::FilterMode::Linear,
        min_filter: wgpu::FilterMode::Linear,
        mipmap_filter: wgpu::MipmapFilterMode::Nearest,
        ..Default::default()
    })
}
