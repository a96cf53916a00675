//! A small CPU depth rasterizer: an asset's triangle mesh at a pose, seen by a camera, inside a
//! pixel window of that camera's image. It is what the shape matcher compares with a guidance
//! mask and depth, many times per object (one render per yaw candidate and per match refresh),
//! so it renders only the object's region and only depth (no colour, no lighting). It also
//! draws a whole scene's guidance ([`rasterized_guidance`]) for tests and benchmarks of the
//! stage without a GPU.

use std::collections::BTreeMap;

use nalgebra::{Point2, Point3, Vector3};
use scenethesis_imagery::{Camera, DepthMap, Guidance, Intrinsics, Mask, RgbImage};
use scenethesis_scene_graph::{Mesh, MeshPart, Pose, Scene};

/// A rectangle of pixels of a camera's image: columns `x0 .. x0 + width`, rows
/// `y0 .. y0 + height`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Window {
    /// First column.
    pub x0: u32,
    /// First row.
    pub y0: u32,
    /// Width in pixels.
    pub width: u32,
    /// Height in pixels.
    pub height: u32,
}

impl Window {
    /// The whole image of `camera`.
    pub fn full(camera: &Camera) -> Self {
        Self {
            x0: 0,
            y0: 0,
            width: camera.intrinsics.width,
            height: camera.intrinsics.height,
        }
    }

    /// The window spanning pixel box `(x0, y0, x1, y1)` (exclusive ends) grown by `margin`
    /// pixels on every side and clipped to a `width × height` image; `None` when empty.
    pub fn around(
        bbox: (u32, u32, u32, u32),
        margin: u32,
        width: u32,
        height: u32,
    ) -> Option<Self> {
        let (x0, y0, x1, y1) = bbox;
        let x0 = x0.saturating_sub(margin);
        let y0 = y0.saturating_sub(margin);
        let x1 = x1.saturating_add(margin).min(width);
        let y1 = y1.saturating_add(margin).min(height);
        (x1 > x0 && y1 > y0).then_some(Self {
            x0,
            y0,
            width: x1 - x0,
            height: y1 - y0,
        })
    }

    /// The smallest window holding both.
    pub fn union(&self, other: &Window) -> Window {
        let x0 = self.x0.min(other.x0);
        let y0 = self.y0.min(other.y0);
        let x1 = (self.x0 + self.width).max(other.x0 + other.width);
        let y1 = (self.y0 + self.height).max(other.y0 + other.height);
        Window {
            x0,
            y0,
            width: x1 - x0,
            height: y1 - y0,
        }
    }

    /// `camera` cropped to this window: the same pose and focal lengths, the principal point
    /// shifted so that pixel (0, 0) of the crop is pixel (x0, y0) of the original.
    pub fn crop(&self, camera: &Camera) -> Camera {
        let k = &camera.intrinsics;
        Camera {
            intrinsics: Intrinsics {
                width: self.width,
                height: self.height,
                fx: k.fx,
                fy: k.fy,
                cx: k.cx - self.x0 as f64,
                cy: k.cy - self.y0 as f64,
            },
            position: camera.position,
            rotation: camera.rotation,
        }
    }
}

/// An asset rendered at a pose: what a [`Matcher`](crate::Matcher) compares with the guidance.
/// Its camera is the guidance camera cropped to the rendered window (and, for a coarse view,
/// subsampled by `stride`), so view pixel `(x, y)` is guidance pixel
/// `(offset[0] + stride·x + stride/2, offset[1] + stride·y + stride/2)` (for the usual stride 1,
/// `(x + offset[0], y + offset[1])`).
#[derive(Debug, Clone, PartialEq)]
pub struct RenderedView {
    /// The camera of the view (the guidance camera cropped to the window).
    pub camera: Camera,
    /// Where the view's pixel (0, 0) lies in the guidance image.
    pub offset: [u32; 2],
    /// Guidance pixels per view pixel along each axis (1: full resolution).
    pub stride: u32,
    /// The asset's pose the view was rendered at.
    pub pose: Pose,
    /// Depth of the asset along the optical axis, metres (unknown = not covered).
    pub depth: DepthMap,
    /// The asset's colour, when the renderer produced one (the CPU rasterizer does not).
    pub color: Option<RgbImage>,
}

impl RenderedView {
    /// The asset-frame point (scale 1) seen at view pixel `(x, y)`, lifted from the view's
    /// depth at the pixel centre; `None` where the asset does not cover the pixel.
    pub fn asset_point(&self, x: u32, y: u32) -> Option<Point3<f64>> {
        let d = self.depth.get(x, y)? as f64;
        let world = self
            .camera
            .unproject(&Point2::new(x as f64 + 0.5, y as f64 + 0.5), d);
        Some(self.pose.inverse_transform_point(&world))
    }

    /// The guidance pixel of view pixel `(x, y)` (the one under its centre).
    pub fn to_guidance(&self, x: u32, y: u32) -> (u32, u32) {
        let s = self.stride.max(1);
        (
            x * s + s / 2 + self.offset[0],
            y * s + s / 2 + self.offset[1],
        )
    }

    /// Number of covered pixels.
    pub fn coverage(&self) -> usize {
        self.depth
            .values()
            .iter()
            .filter(|d| d.is_finite() && **d > 0.0)
            .count()
    }
}

/// The pixel box `(x0, y0, x1, y1)` (exclusive ends) that the asset's bounding box covers in
/// `camera`'s image at `pose`, clipped to the image; `None` when it is behind the camera or
/// outside the image.
pub fn projected_bbox(mesh: &Mesh, pose: &Pose, camera: &Camera) -> Option<(u32, u32, u32, u32)> {
    let b = mesh.bounds()?;
    let (w, h) = (
        camera.intrinsics.width as f64,
        camera.intrinsics.height as f64,
    );
    let (mut x0, mut y0, mut x1, mut y1) = (f64::MAX, f64::MAX, f64::MIN, f64::MIN);
    for i in 0..8 {
        let p = Point3::new(
            if i & 1 == 0 { b.min.x } else { b.max.x },
            if i & 2 == 0 { b.min.y } else { b.max.y },
            if i & 4 == 0 { b.min.z } else { b.max.z },
        );
        let q = camera.project(&pose.transform_point(&p))?;
        x0 = x0.min(q.pixel.x);
        y0 = y0.min(q.pixel.y);
        x1 = x1.max(q.pixel.x);
        y1 = y1.max(q.pixel.y);
    }
    let x0 = x0.floor().clamp(0.0, w) as u32;
    let y0 = y0.floor().clamp(0.0, h) as u32;
    let x1 = x1.ceil().clamp(0.0, w) as u32;
    let y1 = y1.ceil().clamp(0.0, h) as u32;
    (x1 > x0 && y1 > y0).then_some((x0, y0, x1, y1))
}

/// Renders the depth of `mesh` at `pose` seen by `camera`, inside `window` of the camera's
/// image. Triangles with a vertex closer than 1 cm to the camera plane are skipped (objects
/// are in front of the camera); both faces are drawn; see-through parts
/// ([`scenethesis_scene_graph::Material::is_see_through`]) are not.
pub fn rasterize(mesh: &Mesh, pose: &Pose, camera: &Camera, window: Window) -> RenderedView {
    rasterize_coarse(mesh, pose, camera, window, 1)
}

/// [`rasterize`] at a coarser resolution: one view pixel per `stride × stride` block of the
/// window (stride 0 counts as 1). Cheaper by about `stride²`, for ranking hypotheses before
/// the full-resolution passes.
pub fn rasterize_coarse(
    mesh: &Mesh,
    pose: &Pose,
    camera: &Camera,
    window: Window,
    stride: u32,
) -> RenderedView {
    let stride = stride.max(1);
    let mut view_camera = window.crop(camera);
    if stride > 1 {
        let k = &mut view_camera.intrinsics;
        let f = stride as f64;
        k.width = window.width.div_ceil(stride);
        k.height = window.height.div_ceil(stride);
        k.fx /= f;
        k.fy /= f;
        k.cx /= f;
        k.cy /= f;
    }
    let (vw, vh) = (view_camera.intrinsics.width, view_camera.intrinsics.height);
    let (w, h) = (vw as usize, vh as usize);
    let mut depth = vec![f32::INFINITY; w * h];
    let k = &view_camera.intrinsics;
    let cam_from_world = camera.rotation.inverse();
    let (s, c) = pose.yaw.sin_cos();
    // See-through parts (glass) leave the depth to what lies behind them, as in the guidance
    // the renderer draws and as depth sensors measure it.
    let opaque = |part: &&MeshPart| {
        mesh.materials
            .get(part.material)
            .is_none_or(|m| !m.is_see_through())
    };
    for part in mesh.parts.iter().filter(opaque) {
        // Vertices in the camera frame: (u, v, depth).
        let projected: Vec<Option<(f64, f64, f64)>> = part
            .positions
            .iter()
            .map(|p| {
                let l = Vector3::new(p[0] as f64, p[1] as f64, p[2] as f64) * pose.scale;
                let world =
                    pose.translation + Vector3::new(c * l.x + s * l.z, l.y, -s * l.x + c * l.z);
                let cam = cam_from_world * (Point3::from(world) - camera.position);
                let d = -cam.z;
                (d > 0.01).then(|| (k.cx + k.fx * cam.x / d, k.cy - k.fy * cam.y / d, d))
            })
            .collect();
        for t in &part.triangles {
            let (Some(a), Some(b), Some(cc)) = (
                projected[t[0] as usize],
                projected[t[1] as usize],
                projected[t[2] as usize],
            ) else {
                continue;
            };
            fill_triangle(a, b, cc, w, h, &mut depth);
        }
    }
    for d in &mut depth {
        if !d.is_finite() {
            *d = f32::NAN;
        }
    }
    RenderedView {
        camera: view_camera,
        offset: [window.x0, window.y0],
        stride,
        pose: *pose,
        depth: DepthMap::new(vw, vh, depth)
            .unwrap_or_else(|_| DepthMap::from_fn(vw, vh, |_, _| f32::NAN)),
        color: None,
    }
}

/// Fills one projected triangle into a depth buffer (nearest wins), interpolating inverse
/// depth linearly in screen space (perspective-correct depth) at pixel centres.
fn fill_triangle(
    a: (f64, f64, f64),
    b: (f64, f64, f64),
    c: (f64, f64, f64),
    w: usize,
    h: usize,
    depth: &mut [f32],
) {
    let area = (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0);
    if area.abs() < 1e-12 {
        return;
    }
    let xmin = a.0.min(b.0).min(c.0).floor().max(0.0);
    let ymin = a.1.min(b.1).min(c.1).floor().max(0.0);
    let xmax = a.0.max(b.0).max(c.0).ceil().min(w as f64);
    let ymax = a.1.max(b.1).max(c.1).ceil().min(h as f64);
    if xmin >= xmax || ymin >= ymax {
        return;
    }
    let (ia, ib, ic) = (1.0 / a.2, 1.0 / b.2, 1.0 / c.2);
    let inv_area = 1.0 / area;
    for y in ymin as usize..ymax as usize {
        let py = y as f64 + 0.5;
        for x in xmin as usize..xmax as usize {
            let px = x as f64 + 0.5;
            let w0 = ((b.0 - px) * (c.1 - py) - (b.1 - py) * (c.0 - px)) * inv_area;
            let w1 = ((c.0 - px) * (a.1 - py) - (c.1 - py) * (a.0 - px)) * inv_area;
            let w2 = 1.0 - w0 - w1;
            if w0 < 0.0 || w1 < 0.0 || w2 < 0.0 {
                continue;
            }
            let z = (1.0 / (w0 * ia + w1 * ib + w2 * ic)) as f32;
            let slot = &mut depth[y * w + x];
            if z < *slot {
                *slot = z;
            }
        }
    }
}

/// Guidance of `scene` seen by `camera`, drawn by the CPU rasterizer: each pixel belongs to the
/// nearest object's mask and holds its depth (0 where no object is; no architecture, a grey
/// image). For tests and benchmarks of the correspond stage without a GPU.
pub fn rasterized_guidance(
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    camera: &Camera,
) -> Guidance {
    let (w, h) = (camera.intrinsics.width, camera.intrinsics.height);
    let window = Window::full(camera);
    let views: Vec<(&str, RenderedView)> = scene
        .objects
        .iter()
        .filter_map(|o| {
            Some((
                o.id.as_str(),
                rasterize(meshes.get(&o.id)?, &o.pose, camera, window),
            ))
        })
        .collect();
    let mut masks: BTreeMap<String, Mask> = views
        .iter()
        .map(|(id, _)| (id.to_string(), Mask::new(w, h)))
        .collect();
    let depth = DepthMap::from_fn(w, h, |x, y| {
        let nearest = views
            .iter()
            .filter_map(|(id, v)| v.depth.get(x, y).map(|d| (d, *id)))
            .min_by(|a, b| a.0.total_cmp(&b.0));
        match nearest {
            Some((d, id)) => {
                if let Some(m) = masks.get_mut(id) {
                    m.set(x, y, true);
                }
                d
            }
            None => 0.0,
        }
    });
    let image = RgbImage::new(w, h, vec![128; w as usize * h as usize * 3])
        .expect("the image has the camera's size");
    Guidance::new(*camera, image, Some(depth), masks).expect("every buffer has the camera's size")
}

#[cfg(test)]
mod tests {
    use super::*;
    use scenethesis_scene_graph::Material;

    /// A 64 × 64 camera 4 m in front of the origin (+Z), at half a metre's height, looking
    /// along −Z.
    fn camera_in_front() -> Camera {
        let k = Intrinsics::from_vertical_fov(64, 64, 1.0);
        Camera::look_at(
            k,
            Point3::new(0.0, 0.5, 4.0),
            Point3::new(0.0, 0.5, 0.0),
            Vector3::y(),
        )
    }

    #[test]
    fn a_box_seen_head_on_fills_its_projection_at_its_front_depth() {
        let camera = camera_in_front();
        let k = camera.intrinsics;
        let grey = Material::new("grey", [0.5; 3], 0.8);
        let mesh = Mesh::cuboid("box", grey, [-0.5, 0.0, -0.5], [0.5, 1.0, 0.5]);
        let pose = Pose::new(1.0, 0.0, Vector3::zeros());
        let view = rasterize(&mesh, &pose, &camera, Window::full(&camera));
        // The centre pixel sees the front face at 3.5 m.
        let d = view.depth.get(32, 32).unwrap();
        assert!((d - 3.5).abs() < 1e-4, "{d}");
        // The face spans ±0.5 m at 3.5 m: ±0.5 / 3.5 · f pixels around the centre.
        let half = 0.5 / 3.5 * k.fx;
        let covered = view.coverage() as f64;
        assert!(
            ((covered - (2.0 * half).powi(2)) / covered).abs() < 0.1,
            "{covered}"
        );
        let p = view.asset_point(32, 32).unwrap();
        assert!((p.z - 0.5).abs() < 1e-4 && p.x.abs() < 0.05, "{p:?}");
        // A cropped window sees the same depths at shifted pixels.
        let win = Window {
            x0: 20,
            y0: 24,
            width: 20,
            height: 16,
        };
        let crop = rasterize(&mesh, &pose, &camera, win);
        assert_eq!(crop.depth.get(12, 8), view.depth.get(32, 32));
        assert_eq!(crop.to_guidance(12, 8), (32, 32));
        let bbox = projected_bbox(&mesh, &pose, &camera).unwrap();
        assert!(
            bbox.0 <= 32 - half as u32 && bbox.2 >= 32 + half as u32,
            "{bbox:?}"
        );
    }

    #[test]
    fn glass_leaves_the_depth_to_what_lies_behind_it() {
        let camera = camera_in_front();
        // A cabinet's back panel, and a glass front 40 cm nearer the camera.
        let grey = Material::new("grey", [0.5; 3], 0.8);
        let mut cabinet = Mesh::cuboid("back", grey, [-0.5, 0.0, -0.5], [0.5, 1.0, -0.45]);
        let mut glass = Material::new("glass", [0.9; 3], 0.05);
        glass.base_color[3] = 0.25;
        cabinet.append(&Mesh::cuboid(
            "front",
            glass,
            [-0.5, 0.0, -0.1],
            [0.5, 1.0, -0.09],
        ));
        let pose = Pose::new(1.0, 0.0, Vector3::zeros());
        let view = rasterize(&cabinet, &pose, &camera, Window::full(&camera));
        let d = view.depth.get(32, 32).unwrap();
        assert!(
            (d - 4.45).abs() < 1e-3,
            "the back panel is at 4.45 m, not the glass: {d}"
        );
        // Made opaque, the front hides the panel.
        cabinet.materials[1].base_color[3] = 1.0;
        let view = rasterize(&cabinet, &pose, &camera, Window::full(&camera));
        let d = view.depth.get(32, 32).unwrap();
        assert!((d - 4.09).abs() < 1e-3, "{d}");
    }
}
