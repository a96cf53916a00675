//! Uploading a scene: its vertices, the maps of the materials it wears (once per renderer),
//! the sun's orthographic frustum around it, and the shadow map rendered once for every view
//! of the scene.

use std::collections::{BTreeMap, BTreeSet};
use std::ops::Range;
use std::time::Instant;

use bytemuck::Zeroable;
use nalgebra::{Matrix4, Point3, Vector3};
use scenethesis_scene_graph::{Aabb, TextureImage};
use wgpu::util::DeviceExt;

use super::{mat, Globals, PreparedScene, Renderer, DEPTH_FORMAT, SUN_DIRECTION, TINT_FORMAT};
use crate::geometry::SceneGeometry;
use crate::{RenderError, RenderScene};

impl Renderer {
    /// Uploads a scene's geometry and renders its shadow map, for rendering many views.
    pub fn prepare(&self, scene: &RenderScene) -> Result<PreparedScene, RenderError> {
        let started = Instant::now();
        let mut shown: BTreeMap<u64, &TextureImage> = BTreeMap::new();
        for inst in &scene.instances {
            for part in &inst.mesh.parts {
                let material = inst.mesh.materials.get(part.material);
                if let Some((_, image)) = material.and_then(|m| part.textured_uvs(m)) {
                    shown.entry(image.digest()).or_insert(image);
                }
            }
        }
        let images = if shown.is_empty() {
            BTreeMap::new()
        } else {
            let shown: Vec<&TextureImage> = shown.into_values().collect();
            let _queue = self.queue_guard();
            self.textures
                .ensure_images(&self.device, &self.queue, &shown)
        };
        let geometry = SceneGeometry::build(scene, &images)?;
        let built = started.elapsed();
        let library_layers = scenethesis_materials::library().len() as u32;
        let layers: BTreeSet<u32> = geometry
            .vertices
            .iter()
            .map(|v| v.layer)
            .filter(|&l| l <= library_layers)
            .collect();
        let queue = self.queue_guard();
        self.textures.ensure(
            &self.queue,
            layers
                .into_iter()
                .filter_map(|l| l.checked_sub(1))
                .map(|l| l as usize),
        );
        drop(queue);
        let textured = started.elapsed();
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
        let shadow_view = self.shadow_texture("shadow map", size, DEPTH_FORMAT);
        let tint_view = self.shadow_texture("shadow tint", tint_size(size), TINT_FORMAT);
        let casters = vertices.as_ref().filter(|_| self.options.shadows);
        self.draw_shadow_map(
            (&shadow_view, &tint_view),
            casters.map(|b| (b, geometry.objects.clone())),
            &light_from_world,
        );
        tracing::debug!(
            vertices = geometry.vertices.len(),
            geometry_ms = built.as_secs_f64() * 1e3,
            textures_ms = (textured - built).as_secs_f64() * 1e3,
            total_ms = started.elapsed().as_secs_f64() * 1e3,
            "scene prepared"
        );
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
            shadow_texel: 2.0 * radius / size as f64,
            shadow_group: self.shadow_group(&shadow_view, &tint_view),
        })
    }

    /// A square texture of `size` texels a side in `format`, to render into from the sun and
    /// sample: the shadow map's depth or its tint.
    fn shadow_texture(
        &self,
        label: &str,
        size: u32,
        format: wgpu::TextureFormat,
    ) -> wgpu::TextureView {
        let texture = self.device.create_texture(&wgpu::TextureDescriptor {
            label: Some(label),
            size: wgpu::Extent3d {
                width: size,
                height: size,
                depth_or_array_layers: 1,
            },
            mip_level_count: 1,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format,
            usage: wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING,
            view_formats: &[],
        });
        texture.create_view(&Default::default())
    }

    /// Renders the `casters` (a vertex buffer and the range of object vertices in it) from
    /// the sun: the opaque ones into the shadow map's depth, the see-through ones (glass) into
    /// its tint (the light they let through and the nearest pane's depth). With none, only
    /// clears both, so every lookup reads "lit".
    fn draw_shadow_map(
        &self,
        (depth, tint): (&wgpu::TextureView, &wgpu::TextureView),
        casters: Option<(&wgpu::Buffer, Range<u32>)>,
        light_from_world: &Matrix4<f64>,
    ) {
        let mut encoder = self.device.create_command_encoder(&Default::default());
        let drawn = casters.map(|(buffer, objects)| {
            let mut globals = Globals::zeroed();
            globals.light_from_world = mat(light_from_world);
            (self.uniform(&globals), buffer, objects)
        });
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow"),
                depth_stencil_attachment: Some(wgpu::RenderPassDepthStencilAttachment {
                    view: depth,
                    depth_ops: Some(wgpu::Operations {
                        load: wgpu::LoadOp::Clear(1.0),
                        store: wgpu::StoreOp::Store,
                    }),
                    stencil_ops: None,
                }),
                ..Default::default()
            });
            if let Some((uniform, buffer, objects)) = &drawn {
                pass.set_bind_group(0, uniform, &[]);
                pass.set_vertex_buffer(0, buffer.slice(..));
                pass.set_pipeline(&self.pipelines.shadow);
                pass.draw(objects.clone(), 0..1);
            }
        }
        {
            let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
                label: Some("shadow tint"),
                color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                    view: tint,
                    depth_slice: None,
                    resolve_target: None,
                    ops: wgpu::Operations {
                        load: wgpu::LoadOp::Clear(wgpu::Color::WHITE),
                        store: wgpu::StoreOp::Store,
                    },
                })],
                ..Default::default()
            });
            if let Some((uniform, buffer, objects)) = &drawn {
                pass.set_bind_group(0, uniform, &[]);
                pass.set_vertex_buffer(0, buffer.slice(..));
                pass.set_pipeline(&self.pipelines.shadow_tint);
                pass.draw(objects.clone(), 0..1);
            }
        }
        let queue = self.queue_guard();
        self.queue.submit([encoder.finish()]);
        drop(queue);
    }

    /// Group 1 of the scene pass: the shadow map's `depth` with the comparison sampler and
    /// its `tint` with a filtering one.
    fn shadow_group(&self, depth: &wgpu::TextureView, tint: &wgpu::TextureView) -> wgpu::BindGroup {
        self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("shadow map"),
            layout: &self.pipelines.shadow_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(depth),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::Sampler(&self.pipelines.shadow_sampler),
                },
                wgpu::BindGroupEntry {
                    binding: 2,
                    resource: wgpu::BindingResource::TextureView(tint),
                },
                wgpu::BindGroupEntry {
                    binding: 3,
                    resource: wgpu::BindingResource::Sampler(&self.pipelines.tint_sampler),
                },
            ],
        })
    }
}

/// Side of the shadow tint in texels: half the depth map's (a tint has no sharp edges to
/// keep, and a quarter of the texels to clear and blend).
fn tint_size(shadow_map_size: u32) -> u32 {
    (shadow_map_size / 2).max(1)
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
