//! Rendering one view of a prepared scene: the camera checked, the uniform block for it, the
//! scene pass into three targets (lit colour, linear depth, instance), the ambient-occlusion
//! pass from the lit colour and the depth into the final colour, and the read-back.

use std::sync::mpsc;
use std::time::Instant;

use image::RgbaImage;
use nalgebra::Vector3;
use scenethesis_imagery::{Camera, DepthMap};

use super::{mat, palette, Globals, PreparedScene, Renderer, SUN_DIRECTION};
use super::{COLOR_FORMAT, DEPTH_FORMAT, VALUE_FORMAT};
use crate::geometry::WallRange;
use crate::{Frame, RenderError};

/// How far around a point the ambient occlusion looks for occluders, metres.
const OCCLUSION_RADIUS_M: f32 = 0.35;
/// How strongly occluders darken the ambient light (1 = a fully closed hemisphere is black).
const OCCLUSION_STRENGTH: f32 = 1.4;
/// The widest the occlusion's search disc gets on screen, pixels (near surfaces).
const OCCLUSION_MAX_PIXELS: f32 = 48.0;

impl Renderer {
    /// Renders a prepared scene from `camera` and reads the three images back.
    pub fn render_prepared(
        &self,
        scene: &PreparedScene,
        camera: &Camera,
    ) -> Result<Frame, RenderError> {
        let planes = self.render_planes(scene, camera, 1)?;
        let [color, depth, instance]: [Vec<u8>; 3] = planes
            .try_into()
            .map_err(|_| RenderError::Readback("expected three planes".into()))?;
        let (width, height) = (camera.intrinsics.width, camera.intrinsics.height);
        let depth = depth
            .chunks_exact(4)
            .map(|b| f32::from_le_bytes([b[0], b[1], b[2], b[3]]))
            .collect();
        // The depth target holds distances ≥ 0 (0 = background), so the map always builds.
        let depth = DepthMap::new(width, height, depth).map_err(|e| {
            RenderError::Readback(format!("the depth buffer read back malformed: {e}"))
        })?;
        Ok(Frame {
            color: RgbaImage::from_raw(width, height, color).expect("4 bytes per pixel"),
            depth,
            instance: instance
                .chunks_exact(4)
                .map(|b| u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
                .collect(),
            ids: scene.ids.clone(),
        })
    }

    /// Renders `camera`'s view (whose size must be a multiple of `factor`) and reads back the
    /// final colour at 1 / `factor` of its size per side — each output pixel the average of
    /// the `factor`² scene-pass pixels it covers, with ambient occlusion looked up once per
    /// output pixel — plus, for `factor` 1, the depth and instance planes.
    pub(super) fn render_planes(
        &self,
        scene: &PreparedScene,
        camera: &Camera,
        factor: u32,
    ) -> Result<Vec<Vec<u8>>, RenderError> {
        self.check_camera(camera)?;
        let started = Instant::now();
        let mut globals = self.view_globals(scene, camera);
        globals.occlusion[3] = factor as f32;
        let uniform = self.uniform(&globals);
        let k = camera.intrinsics;
        let targets = ViewTargets::new(&self.device, k.width, k.height, factor);
        let mut encoder = self.device.create_command_encoder(&Default::default());
        self.draw_view(&mut encoder, scene, camera, &uniform, &targets);
        self.draw_occlusion(&mut encoder, &uniform, &targets);
        targets.copy_out(&mut encoder);
        let queue = self.queue_guard();
        self.queue.submit([encoder.finish()]);
        drop(queue);
        let planes = targets.read_back(&self.device)?;
        let ms = started.elapsed().as_secs_f64() * 1e3;
        tracing::debug!(
            width = k.width,
            height = k.height,
            factor,
            ms,
            "view rendered"
        );
        Ok(planes)
    }

    /// Refuses an image size the device cannot hold and a camera with non-finite values or
    /// non-positive focal lengths.
    fn check_camera(&self, camera: &Camera) -> Result<(), RenderError> {
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
        Ok(())
    }

    /// The uniform block of `camera`'s view: projection with a depth range fitted to the
    /// scene's extent as seen from the camera, the sun and the backdrop's colours.
    fn view_globals(&self, scene: &PreparedScene, camera: &Camera) -> Globals {
        let k = camera.intrinsics;
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
        let shadows = if self.options.shadows { 1.0 } else { 0.0 };
        Globals {
            clip_from_world: mat(&clip_from_world),
            light_from_world: mat(&scene.light_from_world),
            view_z: [0, 1, 2, 3].map(|c| view[(2, c)] as f32),
            light_dir: [
                sun.x as f32,
                sun.y as f32,
                sun.z as f32,
                scene.shadow_texel as f32,
            ],
            sun: [colors.sun[0], colors.sun[1], colors.sun[2], shadows],
            sky_ambient: rgb(colors.sky_ambient),
            ground_ambient: rgb(colors.ground_ambient),
            cam_right: column(0),
            cam_up: column(1),
            cam_back: column(2),
            intrinsics: [k.fx as f32, k.fy as f32, k.cx as f32, k.cy as f32],
            bg_top: rgb(colors.top),
            bg_horizon: rgb(colors.horizon),
            bg_bottom: rgb(colors.bottom),
            eye: [
                camera.position.x as f32,
                camera.position.y as f32,
                camera.position.z as f32,
                1.0,
            ],
            occlusion: [
                OCCLUSION_RADIUS_M,
                if self.options.ambient_occlusion {
                    OCCLUSION_STRENGTH
                } else {
                    0.0
                },
                OCCLUSION_MAX_PIXELS,
                0.0,
            ],
        }
    }

    /// The scene pass: the backdrop; the objects and floor, then each wall unless the scene
    /// cuts away walls the camera stands behind, drawn three times: their opaque surfaces'
    /// depth, those surfaces shaded (each pixel once), and their see-through surfaces blended
    /// over the rest.
    fn draw_view(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        scene: &PreparedScene,
        camera: &Camera,
        uniform: &wgpu::BindGroup,
        targets: &ViewTargets,
    ) {
        let attachments = targets.views.each_ref().map(|view| {
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
                view: &targets.zbuffer,
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
        pass.set_bind_group(0, uniform, &[]);
        pass.set_pipeline(&self.pipelines.background);
        pass.draw(0..3, 0..1);
        if let Some(buffer) = &scene.vertices {
            pass.set_bind_group(1, &scene.shadow_group, &[]);
            pass.set_bind_group(2, &self.textures.group(), &[]);
            pass.set_vertex_buffer(0, buffer.slice(..));
            let pipelines = &self.pipelines;
            for pipeline in [&pipelines.prepass, &pipelines.scene, &pipelines.glass] {
                pass.set_pipeline(pipeline);
                pass.draw(scene.always.clone(), 0..1);
                for wall in &scene.walls {
                    if !(scene.cut_away_walls && cut_away(camera, wall)) {
                        pass.draw(wall.vertices.clone(), 0..1);
                    }
                }
            }
        }
    }
}

impl Renderer {
    /// The ambient-occlusion pass: the lit colour, its ambient share darkened where the
    /// depth around a pixel rises in front of it, into the final colour target.
    fn draw_occlusion(
        &self,
        encoder: &mut wgpu::CommandEncoder,
        uniform: &wgpu::BindGroup,
        targets: &ViewTargets,
    ) {
        let inputs = self.device.create_bind_group(&wgpu::BindGroupDescriptor {
            label: Some("ambient occlusion"),
            layout: &self.pipelines.occlusion_layout,
            entries: &[
                wgpu::BindGroupEntry {
                    binding: 0,
                    resource: wgpu::BindingResource::TextureView(&targets.views[0]),
                },
                wgpu::BindGroupEntry {
                    binding: 1,
                    resource: wgpu::BindingResource::TextureView(&targets.views[1]),
                },
            ],
        });
        let mut pass = encoder.begin_render_pass(&wgpu::RenderPassDescriptor {
            label: Some("ambient occlusion"),
            color_attachments: &[Some(wgpu::RenderPassColorAttachment {
                view: &targets.shaded_view,
                depth_slice: None,
                resolve_target: None,
                ops: wgpu::Operations {
                    load: wgpu::LoadOp::Clear(wgpu::Color::TRANSPARENT),
                    store: wgpu::StoreOp::Store,
                },
            })],
            depth_stencil_attachment: None,
            timestamp_writes: None,
            occlusion_query_set: None,
            multiview_mask: None,
        });
        pass.set_pipeline(&self.pipelines.occlusion);
        pass.set_bind_group(0, uniform, &[]);
        pass.set_bind_group(1, &inputs, &[]);
        pass.draw(0..3, 0..1);
    }
}

/// Whether a wall is cut away for this camera: the camera stands on its outer side (so the wall
/// would hide the room) and, for an interior wall of a house, the floor the camera looks at lies
/// on its inner side (the wall stands in front of what the camera looks at).
fn cut_away(camera: &Camera, wall: &WallRange) -> bool {
    camera_behind_wall(camera, wall) && (!wall.interior || looks_past(camera, wall))
}

/// Whether the camera stands on the outer side of a wall.
fn camera_behind_wall(camera: &Camera, wall: &WallRange) -> bool {
    let c = nalgebra::Vector2::new(camera.position.x, camera.position.z);
    (c - wall.start.coords).dot(&wall.inward) < -wall.thickness / 2.0
}

/// Whether the point where the camera's optical axis meets the floor lies on the wall's inner
/// side (a camera that does not look down counts as looking past every wall it stands behind).
fn looks_past(camera: &Camera, wall: &WallRange) -> bool {
    let forward = camera.forward();
    if forward.y > -1e-6 {
        return true;
    }
    let hit = camera.position + forward * (-camera.position.y / forward.y);
    let floor = nalgebra::Vector2::new(hit.x, hit.z);
    (floor - wall.start.coords).dot(&wall.inward) > 0.0
}

/// The targets of one view (lit colour, linear depth bits, instance; all 4 bytes a pixel),
/// the final colour the ambient-occlusion pass writes (1 / `factor` of their size per side),
/// the z-buffer, and the buffer the final colour (and, unsupersampled, the depth and instance
/// targets) are copied into for reading back.
struct ViewTargets {
    /// Size of the final colour (and of every plane read back).
    width: u32,
    height: u32,
    /// Planes read back: 3 (colour, depth, instance) unsupersampled, else the colour alone.
    planes: u64,
    textures: [wgpu::Texture; 3],
    views: [wgpu::TextureView; 3],
    shaded: wgpu::Texture,
    shaded_view: wgpu::TextureView,
    zbuffer: wgpu::TextureView,
    readback: wgpu::Buffer,
}

impl ViewTargets {
    /// Scene-pass targets of `width` × `height` pixels on `device`, the final colour
    /// `factor` times smaller per side.
    fn new(device: &wgpu::Device, width: u32, height: u32, factor: u32) -> Self {
        let factor = factor.max(1);
        let (out_width, out_height) = (width / factor, height / factor);
        let planes = if factor == 1 { 3 } else { 1 };
        let target = |label, format, usage, size| {
            device.create_texture(&wgpu::TextureDescriptor {
                label: Some(label),
                size,
                mip_level_count: 1,
                sample_count: 1,
                dimension: wgpu::TextureDimension::D2,
                format,
                usage,
                view_formats: &[],
            })
        };
        let readable = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::COPY_SRC;
        let sampled = wgpu::TextureUsages::RENDER_ATTACHMENT | wgpu::TextureUsages::TEXTURE_BINDING;
        let big = extent(width, height);
        let textures = [
            target("lit colour", COLOR_FORMAT, sampled, big),
            target("linear depth", VALUE_FORMAT, readable | sampled, big),
            target("instance", VALUE_FORMAT, readable, big),
        ];
        let shaded = target(
            "colour",
            COLOR_FORMAT,
            readable,
            extent(out_width, out_height),
        );
        let zbuffer = target(
            "z-buffer",
            DEPTH_FORMAT,
            wgpu::TextureUsages::RENDER_ATTACHMENT,
            big,
        );
        let views = textures
            .each_ref()
            .map(|t| t.create_view(&Default::default()));
        let readback = device.create_buffer(&wgpu::BufferDescriptor {
            label: Some("read-back"),
            size: plane_size(out_width, out_height) * planes,
            usage: wgpu::BufferUsages::COPY_DST | wgpu::BufferUsages::MAP_READ,
            mapped_at_creation: false,
        });
        Self {
            width: out_width,
            height: out_height,
            planes,
            textures,
            views,
            shaded_view: shaded.create_view(&Default::default()),
            shaded,
            zbuffer: zbuffer.create_view(&Default::default()),
            readback,
        }
    }

    /// Copies the final colour (and, unsupersampled, the depth and the instance targets) into
    /// the read-back buffer, one padded plane each.
    fn copy_out(&self, encoder: &mut wgpu::CommandEncoder) {
        let plane = plane_size(self.width, self.height);
        let sources = [&self.shaded, &self.textures[1], &self.textures[2]];
        for (i, texture) in sources.into_iter().take(self.planes as usize).enumerate() {
            encoder.copy_texture_to_buffer(
                texture.as_image_copy(),
                wgpu::TexelCopyBufferInfo {
                    buffer: &self.readback,
                    layout: wgpu::TexelCopyBufferLayout {
                        offset: plane * i as u64,
                        bytes_per_row: Some(padded_row(self.width) as u32),
                        rows_per_image: Some(self.height),
                    },
                },
                extent(self.width, self.height),
            );
        }
    }

    /// Waits for the copies and returns the planes' pixels with the row padding removed.
    fn read_back(&self, device: &wgpu::Device) -> Result<Vec<Vec<u8>>, RenderError> {
        let (sender, receiver) = mpsc::channel();
        self.readback
            .map_async(wgpu::MapMode::Read, .., move |result| {
                // The receiver outlives the poll below; a failed send only means it was dropped.
                let _ = sender.send(result);
            });
        let failed = |e: &dyn std::fmt::Display| RenderError::Readback(e.to_string());
        device
            .poll(wgpu::PollType::wait_indefinitely())
            .map_err(|e| failed(&e))?;
        receiver
            .recv()
            .map_err(|e| failed(&e))?
            .map_err(|e| failed(&e))?;
        let mapped = self.readback.get_mapped_range(..).map_err(|e| failed(&e))?;
        let (row, padded) = (self.width as u64 * 4, padded_row(self.width));
        let plane = plane_size(self.width, self.height);
        let unpad = |plane_index: u64| -> Vec<u8> {
            let base = plane * plane_index;
            let mut out = Vec::with_capacity((row * self.height as u64) as usize);
            for y in 0..self.height as u64 {
                let start = (base + y * padded) as usize;
                out.extend_from_slice(&mapped[start..start + row as usize]);
            }
            out
        };
        let planes = (0..self.planes).map(unpad).collect();
        drop(mapped);
        self.readback.unmap();
        Ok(planes)
    }
}

/// A `width` × `height` single-layer extent.
fn extent(width: u32, height: u32) -> wgpu::Extent3d {
    wgpu::Extent3d {
        width,
        height,
        depth_or_array_layers: 1,
    }
}

/// Bytes of a row of 4-byte pixels, padded to the 256 bytes a texture copy needs.
fn padded_row(width: u32) -> u64 {
    (width as u64 * 4).div_ceil(256) * 256
}

/// Bytes of one padded plane.
fn plane_size(width: u32, height: u32) -> u64 {
    padded_row(width) * height as u64
}
