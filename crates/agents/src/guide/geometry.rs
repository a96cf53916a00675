//! Floor-plane geometry of the guide: oriented footprints and a coarse occupancy raster.

/// An oriented rectangle on the floor plane (x, z): centre, yaw and half extents along the
/// object's own x (width) and z (depth) axes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Footprint {
    pub cx: f64,
    pub cz: f64,
    pub yaw: f64,
    pub hx: f64,
    pub hz: f64,
}

impl Footprint {
    /// The floor rectangle in front of this footprint that `info`'s moving parts sweep while
    /// opening ([`AssetInfo::opening_bounds`]), across the object's width; `None` when nothing
    /// opens past its front (lids, or no joints). The footprint's centre is the asset's origin.
    pub fn opening(&self, info: &scenethesis_scene_graph::AssetInfo) -> Option<Footprint> {
        let swept = info.opening_bounds.as_ref()?;
        let reach = swept.max.z.min(2.5) - self.hz;
        if reach <= 0.02 {
            return None;
        }
        let centre = self.to_world(0.0, self.hz + reach / 2.0);
        Some(Footprint {
            cx: centre[0],
            cz: centre[1],
            yaw: self.yaw,
            hx: (swept.max.x.max(-swept.min.x)).clamp(0.05, self.hx),
            hz: reach / 2.0,
        })
    }

    /// The object's local +X (right-hand side axis) and +Z (front) in world (x, z).
    pub fn axes(&self) -> ([f64; 2], [f64; 2]) {
        let (s, c) = self.yaw.sin_cos();
        ([c, -s], [s, c])
    }

    /// World (x, z) of a point given in the footprint's local frame.
    pub fn to_world(self, lx: f64, lz: f64) -> [f64; 2] {
        let (r, f) = self.axes();
        [
            self.cx + r[0] * lx + f[0] * lz,
            self.cz + r[1] * lx + f[1] * lz,
        ]
    }

    /// Local coordinates of a world (x, z) point.
    pub fn to_local(self, x: f64, z: f64) -> [f64; 2] {
        let (r, f) = self.axes();
        let (dx, dz) = (x - self.cx, z - self.cz);
        [dx * r[0] + dz * r[1], dx * f[0] + dz * f[1]]
    }

    /// The four corners in world (x, z).
    pub fn corners(&self) -> [[f64; 2]; 4] {
        [
            self.to_world(-self.hx, -self.hz),
            self.to_world(self.hx, -self.hz),
            self.to_world(self.hx, self.hz),
            self.to_world(-self.hx, self.hz),
        ]
    }

    /// Half extent of the footprint along a world unit direction.
    pub fn extent_along(&self, dir: [f64; 2]) -> f64 {
        let (r, f) = self.axes();
        self.hx * (r[0] * dir[0] + r[1] * dir[1]).abs()
            + self.hz * (f[0] * dir[0] + f[1] * dir[1]).abs()
    }

    /// Whether the two rectangles, each grown by `gap / 2`, overlap (separating axes).
    pub fn overlaps(&self, other: &Footprint, gap: f64) -> bool {
        let (r1, f1) = self.axes();
        let (r2, f2) = other.axes();
        let d = [other.cx - self.cx, other.cz - self.cz];
        for axis in [r1, f1, r2, f2] {
            let dist = (d[0] * axis[0] + d[1] * axis[1]).abs();
            if dist >= self.extent_along(axis) + other.extent_along(axis) + gap - 1e-9 {
                return false;
            }
        }
        true
    }

    /// Whether a world point lies inside the rectangle grown by `grow` on every side.
    pub fn contains(&self, x: f64, z: f64, grow: f64) -> bool {
        let [lx, lz] = self.to_local(x, z);
        lx.abs() <= self.hx + grow && lz.abs() <= self.hz + grow
    }

    /// World bounding box [min_x, min_z, max_x, max_z] grown by `grow`.
    pub fn bounds(&self, grow: f64) -> [f64; 4] {
        let ex = self.extent_along([1.0, 0.0]) + grow;
        let ez = self.extent_along([0.0, 1.0]) + grow;
        [self.cx - ex, self.cz - ez, self.cx + ex, self.cz + ez]
    }
}

/// The shared floor raster of the scene graph, used for the guide's walkway checks.
pub(crate) use scenethesis_scene_graph::FloorRaster as Raster;

/// The guide's footprint-based operations on the shared floor raster.
pub(crate) trait RasterExt {
    /// Free cells of the raster's rectangle eroded by `inset` (true inside, false near the
    /// border).
    fn floor_mask(&self, inset: f64) -> Vec<bool>;
    /// Clears the cells whose centres lie in `fp` grown by `grow`.
    fn stamp(&self, mask: &mut [bool], fp: &Footprint, grow: f64);
    /// Calls `f` with the index of every cell whose centre lies in `fp` grown by `grow`.
    fn for_cells_in(&self, fp: &Footprint, grow: f64, f: impl FnMut(usize));
}

impl RasterExt for Raster {
    fn floor_mask(&self, inset: f64) -> Vec<bool> {
        let (x1, z1) = (
            self.x0 + self.nx as f64 * self.cell,
            self.z0 + self.nz as f64 * self.cell,
        );
        let mut mask = vec![false; self.nx * self.nz];
        for j in 0..self.nz {
            for i in 0..self.nx {
                let [x, z] = self.center(i, j);
                mask[j * self.nx + i] = x >= self.x0 + inset
                    && x <= x1 - inset
                    && z >= self.z0 + inset
                    && z <= z1 - inset;
            }
        }
        mask
    }

    fn stamp(&self, mask: &mut [bool], fp: &Footprint, grow: f64) {
        self.for_cells_in(fp, grow, |idx| mask[idx] = false);
    }

    fn for_cells_in(&self, fp: &Footprint, grow: f64, f: impl FnMut(usize)) {
        self.for_cells_where(fp.bounds(grow), |x, z| fp.contains(x, z, grow), f);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rotated_rectangles_overlap_by_separating_axes() {
        let a = Footprint {
            cx: 0.0,
            cz: 0.0,
            yaw: 0.0,
            hx: 1.0,
            hz: 0.5,
        };
        let b = Footprint {
            cx: 1.6,
            cz: 0.0,
            yaw: std::f64::consts::FRAC_PI_4,
            hx: 0.5,
            hz: 0.5,
        };
        assert!(a.overlaps(&b, 0.0), "diamond corner reaches x = 0.89 < 1");
        let c = Footprint { cx: 1.8, ..b };
        assert!(!c.overlaps(&a, 0.0));
        assert!(c.overlaps(&a, 0.2));
        assert!((a.extent_along([0.0, 1.0]) - 0.5).abs() < 1e-12);
    }

    #[test]
    fn components_split_by_a_wall_of_cells() {
        let r = Raster::new(0.0, 0.0, 1.0, 1.0, 0.1);
        let mut mask = r.floor_mask(0.0);
        let wall = Footprint {
            cx: 0.5,
            cz: 0.5,
            yaw: 0.0,
            hx: 0.05,
            hz: 0.6,
        };
        r.stamp(&mut mask, &wall, 0.0);
        let sizes = r.components4(&mask).sizes;
        assert_eq!(sizes.len(), 3, "two components: {sizes:?}");
    }
}
