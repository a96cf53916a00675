//! The pinhole camera: intrinsics in pixels, the pose in the world, projection and its inverse.

use nalgebra::{Matrix3, Matrix4, Point2, Point3, Rotation3, UnitQuaternion, Vector3};
use serde::{Deserialize, Serialize};

/// Vertical field of view of the renderer's view presets and of a guidance image that comes
/// without intrinsics (radians; 50°).
pub const DEFAULT_VERTICAL_FOV: f64 = 50.0 * std::f64::consts::PI / 180.0;

/// Pinhole intrinsics in pixels. Pixel (0, 0) is the top-left corner of the image; the centre
/// of the top-left pixel is (0.5, 0.5); `u` grows to the right and `v` downward.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Intrinsics {
    /// Image width in pixels.
    pub width: u32,
    /// Image height in pixels.
    pub height: u32,
    /// Focal length along `u`, in pixels.
    pub fx: f64,
    /// Focal length along `v`, in pixels.
    pub fy: f64,
    /// Principal point `u`, in pixels.
    pub cx: f64,
    /// Principal point `v`, in pixels.
    pub cy: f64,
}

impl Intrinsics {
    /// Square-pixel intrinsics with the principal point at the image centre and the given
    /// vertical field of view in radians.
    pub fn from_vertical_fov(width: u32, height: u32, vertical_fov: f64) -> Self {
        let f = height as f64 / 2.0 / (vertical_fov / 2.0).tan();
        Self {
            width,
            height,
            fx: f,
            fy: f,
            cx: width as f64 / 2.0,
            cy: height as f64 / 2.0,
        }
    }

    /// The vertical field of view in radians.
    pub fn vertical_fov(&self) -> f64 {
        2.0 * (self.height as f64 / 2.0 / self.fy).atan()
    }

    /// The same camera model for an image resized to `width × height` pixels.
    pub fn resized(&self, width: u32, height: u32) -> Self {
        let (sx, sy) = (
            width as f64 / self.width as f64,
            height as f64 / self.height as f64,
        );
        Self {
            width,
            height,
            fx: self.fx * sx,
            fy: self.fy * sy,
            cx: self.cx * sx,
            cy: self.cy * sy,
        }
    }
}

/// A point projected into an image.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Projection {
    /// Image position in pixels (`u` right, `v` down).
    pub pixel: Point2<f64>,
    /// Distance along the optical axis, in metres (positive in front of the camera).
    pub depth: f64,
}

/// A pinhole camera: intrinsics plus its pose in the world.
///
/// The camera frame follows glTF: +X right, +Y up, looking along −Z. `rotation` maps camera
/// directions to world directions and `position` is the optical centre in the world.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Camera {
    /// Pixel-space projection parameters.
    pub intrinsics: Intrinsics,
    /// Optical centre in world coordinates.
    pub position: Point3<f64>,
    /// World-from-camera rotation.
    pub rotation: UnitQuaternion<f64>,
}

impl Camera {
    /// A camera at `eye` looking at `target`, with `up` giving the image's upward direction.
    /// Falls back to +Z as the reference when `up` is parallel to the view direction.
    pub fn look_at(
        intrinsics: Intrinsics,
        eye: Point3<f64>,
        target: Point3<f64>,
        up: Vector3<f64>,
    ) -> Self {
        let forward = (target - eye).normalize();
        let mut right = forward.cross(&up);
        if right.norm() < 1e-9 {
            right = forward.cross(&Vector3::z());
        }
        let right = right.normalize();
        let true_up = right.cross(&forward);
        let m = Matrix3::from_columns(&[right, true_up, -forward]);
        Self {
            intrinsics,
            position: eye,
            rotation: UnitQuaternion::from_rotation_matrix(&Rotation3::from_matrix_unchecked(m)),
        }
    }

    /// The unit viewing direction (the camera's −Z axis) in world coordinates.
    pub fn forward(&self) -> Vector3<f64> {
        self.rotation * -Vector3::z()
    }

    /// A world point expressed in the camera frame.
    pub fn world_to_camera(&self, world: &Point3<f64>) -> Point3<f64> {
        Point3::from(self.rotation.inverse() * (world - self.position))
    }

    /// Projects a world point; `None` when it is not in front of the camera.
    pub fn project(&self, world: &Point3<f64>) -> Option<Projection> {
        let c = self.world_to_camera(world);
        let depth = -c.z;
        if depth <= 0.0 || !depth.is_finite() {
            return None;
        }
        let k = &self.intrinsics;
        Some(Projection {
            pixel: Point2::new(k.cx + k.fx * c.x / depth, k.cy - k.fy * c.y / depth),
            depth,
        })
    }

    /// The world point seen at `pixel` at the given depth along the optical axis.
    pub fn unproject(&self, pixel: &Point2<f64>, depth: f64) -> Point3<f64> {
        let k = &self.intrinsics;
        let c = Vector3::new(
            (pixel.x - k.cx) / k.fx * depth,
            -(pixel.y - k.cy) / k.fy * depth,
            -depth,
        );
        self.position + self.rotation * c
    }

    /// The 4×4 camera-from-world (view) matrix.
    pub fn view_matrix(&self) -> Matrix4<f64> {
        let r = self.rotation.inverse().to_rotation_matrix();
        let t = -(r * self.position.coords);
        let mut m = r.to_homogeneous();
        m.fixed_view_mut::<3, 1>(0, 3).copy_from(&t);
        m
    }

    /// The 4×4 clip-from-camera matrix for wgpu/WebGPU conventions (NDC x, y in [−1, 1] with y
    /// up, depth in [0, 1] from `near` to `far`) that reproduces [`Camera::project`] exactly,
    /// including an off-centre principal point.
    pub fn clip_from_camera(&self, near: f64, far: f64) -> Matrix4<f64> {
        let k = &self.intrinsics;
        let (w, h) = (k.width as f64, k.height as f64);
        let a = -far / (far - near);
        let b = -far * near / (far - near);
        Matrix4::new(
            2.0 * k.fx / w,
            0.0,
            1.0 - 2.0 * k.cx / w,
            0.0,
            0.0,
            2.0 * k.fy / h,
            2.0 * k.cy / h - 1.0,
            0.0,
            0.0,
            0.0,
            a,
            b,
            0.0,
            0.0,
            -1.0,
            0.0,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn camera() -> Camera {
        let k = Intrinsics {
            width: 640,
            height: 480,
            fx: 500.0,
            fy: 510.0,
            cx: 300.0,
            cy: 250.0,
        };
        Camera::look_at(
            k,
            Point3::new(3.0, 2.0, 4.0),
            Point3::new(0.0, 0.5, 0.0),
            Vector3::y(),
        )
    }

    #[test]
    fn project_then_unproject_is_identity() {
        let cam = camera();
        let p = Point3::new(0.3, 0.9, -0.4);
        let proj = cam.project(&p).unwrap();
        assert!((cam.unproject(&proj.pixel, proj.depth) - p).norm() < 1e-9);
    }

    #[test]
    fn target_projects_to_principal_point_and_up_is_up() {
        let cam = camera();
        let proj = cam.project(&Point3::new(0.0, 0.5, 0.0)).unwrap();
        assert!((proj.pixel - Point2::new(300.0, 250.0)).norm() < 1e-9);
        let above = cam.project(&Point3::new(0.0, 1.5, 0.0)).unwrap();
        assert!(
            above.pixel.y < 250.0,
            "higher points must appear higher in the image"
        );
        assert!(
            cam.project(&Point3::new(6.0, 3.5, 8.0)).is_none(),
            "behind the camera"
        );
    }

    #[test]
    fn clip_matrix_matches_projection() {
        let cam = camera();
        let (near, far) = (0.1, 50.0);
        let p = Point3::new(-0.5, 1.2, 0.7);
        let proj = cam.project(&p).unwrap();
        let clip = cam.clip_from_camera(near, far) * cam.view_matrix() * p.to_homogeneous();
        let ndc = clip.xyz() / clip.w;
        let k = cam.intrinsics;
        let u = (ndc.x + 1.0) / 2.0 * k.width as f64;
        let v = (1.0 - ndc.y) / 2.0 * k.height as f64;
        assert!((u - proj.pixel.x).abs() < 1e-9 && (v - proj.pixel.y).abs() < 1e-9);
        assert!((clip.w - proj.depth).abs() < 1e-9);
        assert!(ndc.z > 0.0 && ndc.z < 1.0);
    }
}
