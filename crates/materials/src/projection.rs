//! Texture coordinates in metres by box projection: each triangle is projected along the axis
//! its normal points most along (in the asset's own frame), onto the other two axes, and
//! divided by the material's tile size, so a 0.8 m wood tile repeats every 0.8 m on every
//! face. On each face u runs along the part's longer extent of the two axes (wood grain along
//! a leg, along a table top's length). A vertex shared by faces projected along different
//! axes needs one copy per axis ([`FaceProjection::axis`] tells which).

/// The projection of one part: its tile size and its extent per axis.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BoxProjection {
    tile_size_m: f32,
    extent: [f32; 3],
}

/// How one face is projected.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FaceProjection {
    /// The axis projected along (0 x, 1 y, 2 z): the one the face's normal points most along.
    pub axis: usize,
    /// The axis u runs along.
    pub u_axis: usize,
    /// The axis that runs toward the image's top (v decreases along it).
    pub v_axis: usize,
    tile_bits: u32,
}

impl BoxProjection {
    /// The projection of a part with these vertex positions for a tile of `tile_size_m`.
    pub fn new(tile_size_m: f32, positions: &[[f32; 3]]) -> Self {
        let mut min = [f32::INFINITY; 3];
        let mut max = [f32::NEG_INFINITY; 3];
        for p in positions {
            for k in 0..3 {
                min[k] = min[k].min(p[k]);
                max[k] = max[k].max(p[k]);
            }
        }
        let extent = std::array::from_fn(|k| (max[k] - min[k]).max(0.0));
        Self {
            tile_size_m: tile_size_m.max(1e-3),
            extent,
        }
    }

    /// How a face with this (unnormalised) normal is projected.
    pub fn face(&self, normal: [f32; 3]) -> FaceProjection {
        let a = normal.map(f32::abs);
        let axis = if a[0] >= a[1] && a[0] >= a[2] {
            0
        } else if a[1] >= a[2] {
            1
        } else {
            2
        };
        let (p, q) = match axis {
            0 => (2, 1),
            1 => (0, 2),
            _ => (0, 1),
        };
        let (u_axis, v_axis) = if self.extent[q] > self.extent[p] {
            (q, p)
        } else {
            (p, q)
        };
        FaceProjection {
            axis,
            u_axis,
            v_axis,
            tile_bits: self.tile_size_m.to_bits(),
        }
    }
}

impl FaceProjection {
    /// Texture coordinates of a point: metres along u and against v, in tiles.
    pub fn uv(&self, p: [f32; 3]) -> [f32; 2] {
        let tile = f32::from_bits(self.tile_bits);
        [p[self.u_axis] / tile, -p[self.v_axis] / tile]
    }

    /// The glTF tangent at a vertex of unit normal `n`: the u axis made perpendicular to `n`,
    /// and `w` = ±1 so that `cross(n, tangent) · w` points toward the image's top.
    pub fn tangent(&self, n: [f32; 3]) -> [f32; 4] {
        let mut t = [0.0f32; 3];
        t[self.u_axis] = 1.0;
        let d = dot(n, t);
        let t = [t[0] - n[0] * d, t[1] - n[1] * d, t[2] - n[2] * d];
        let len = dot(t, t).sqrt();
        let t = if len > 1e-6 {
            t.map(|c| c / len)
        } else {
            let mut fallback = [0.0; 3];
            fallback[self.v_axis] = 1.0;
            fallback
        };
        let b = cross(n, t);
        let w = if b[self.v_axis] >= 0.0 { 1.0 } else { -1.0 };
        [t[0], t[1], t[2], w]
    }
}

fn dot(a: [f32; 3], b: [f32; 3]) -> f32 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: [f32; 3], b: [f32; 3]) -> [f32; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn faces_project_in_metres_along_the_longer_extent() {
        // A table leg: 0.05 × 0.7 × 0.05 m.
        let leg = BoxProjection::new(0.5, &[[0.0, 0.0, 0.0], [0.05, 0.7, 0.05]]);
        let front = leg.face([0.0, 0.0, 1.0]);
        assert_eq!((front.axis, front.u_axis, front.v_axis), (2, 1, 0));
        assert_eq!(front.uv([0.05, 0.7, 0.05]), [1.4, -0.1]);
        // A top: 1.6 × 0.03 × 0.8 m, u along the length.
        let top = BoxProjection::new(0.8, &[[-0.8, 0.7, -0.4], [0.8, 0.73, 0.4]]);
        let up = top.face([0.0, 2.0, 0.1]);
        assert_eq!((up.axis, up.u_axis, up.v_axis), (1, 0, 2));
        let t = up.tangent([0.0, 1.0, 0.0]);
        assert_eq!(&t[..3], &[1.0, 0.0, 0.0]);
        // cross(+y, +x) = −z, and the image's top runs along +z: w = −1.
        assert_eq!(t[3], -1.0);
    }
}
