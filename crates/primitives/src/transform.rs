//! Moving, turning and tidying parts, and the rotations and frames the other builders share.

use nalgebra::{Point3, Rotation3, Unit, Vector3};
use scenethesis_scene_graph::MeshPart;

/// Drops unused vertices (and their texture coordinates) and renumbers the triangles.
pub fn compact(part: &mut MeshPart) {
    let mut map = vec![u32::MAX; part.positions.len()];
    let mut positions = Vec::new();
    let mut uvs = Vec::new();
    for t in &mut part.triangles {
        for i in t.iter_mut() {
            if map[*i as usize] == u32::MAX {
                map[*i as usize] = positions.len() as u32;
                positions.push(part.positions[*i as usize]);
                if let Some(uv) = part.uvs.as_ref().and_then(|u| u.get(*i as usize)) {
                    uvs.push(*uv);
                }
            }
            *i = map[*i as usize];
        }
    }
    part.positions = positions;
    if part.uvs.is_some() {
        part.uvs = (uvs.len() == part.positions.len()).then_some(uvs);
    }
}

/// Flips every triangle of `part` when its signed volume is negative, so faces point outward.
pub fn orient_outward(part: &mut MeshPart) {
    if part.signed_volume() < 0.0 {
        for t in &mut part.triangles {
            t.swap(1, 2);
        }
    }
}

/// Two unit vectors perpendicular to `axis` and to each other, (u, v) with u × v along `axis`.
pub(crate) fn frame(axis: [f32; 3]) -> ([f32; 3], [f32; 3]) {
    let w = normalized(axis);
    let reference = if w[1].abs() < 0.9 {
        [0.0, 1.0, 0.0]
    } else {
        [1.0, 0.0, 0.0]
    };
    let u = normalized(cross(reference, w));
    let v = cross(w, u);
    (u, v)
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalized(a: [f32; 3]) -> [f32; 3] {
    let n = (a[0] * a[0] + a[1] * a[1] + a[2] * a[2]).sqrt().max(1e-12);
    [a[0] / n, a[1] / n, a[2] / n]
}

/// The part moved by `offset`.
pub fn translated(mut part: MeshPart, offset: [f32; 3]) -> MeshPart {
    for p in &mut part.positions {
        for k in 0..3 {
            p[k] += offset[k];
        }
    }
    part
}

/// The part turned by `yaw` radians about the vertical axis through `pivot` = (x, z), in the
/// same sense as a pose's yaw.
pub fn rotated_y(mut part: MeshPart, yaw: f32, pivot: [f32; 2]) -> MeshPart {
    let (s, c) = yaw.sin_cos();
    for p in &mut part.positions {
        let (x, z) = (p[0] - pivot[0], p[2] - pivot[1]);
        p[0] = pivot[0] + c * x + s * z;
        p[2] = pivot[1] - s * x + c * z;
    }
    part
}

/// The rotation taking +Y onto `direction`.
pub fn rotation_from_y(direction: &Vector3<f32>) -> Rotation3<f32> {
    let y = Vector3::y();
    Rotation3::rotation_between(&y, direction)
        .unwrap_or_else(|| Rotation3::from_axis_angle(&Vector3::x_axis(), std::f32::consts::PI))
}

/// A rotation by `angle` radians about `axis`.
pub fn rotation(axis: [f32; 3], angle: f32) -> Rotation3<f32> {
    Rotation3::from_axis_angle(&Unit::new_normalize(Vector3::from(axis)), angle)
}

/// `part` rotated about the origin, then moved by `offset` (a proper rotation keeps orientation).
pub fn transformed(mut part: MeshPart, rot: &Rotation3<f32>, offset: [f32; 3]) -> MeshPart {
    for p in &mut part.positions {
        let q = rot * Point3::from(*p);
        *p = [q.x + offset[0], q.y + offset[1], q.z + offset[2]];
    }
    part
}
