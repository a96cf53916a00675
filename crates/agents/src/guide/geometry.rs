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

/// A square-cell raster over the floor rectangle.
#[derive(Debug, Clone)]
pub(crate) struct Raster {
    pub x0: f64,
    pub z0: f64,
    pub cell: f64,
    pub nx: usize,
    pub nz: usize,
}

impl Raster {
    /// A raster of `cell`-sized cells over [x0, x1] × [z0, z1].
    pub fn new(x0: f64, z0: f64, x1: f64, z1: f64, cell: f64) -> Self {
        let nx = ((x1 - x0) / cell).ceil().max(1.0) as usize;
        let nz = ((z1 - z0) / cell).ceil().max(1.0) as usize;
        Self {
            x0,
            z0,
            cell,
            nx,
            nz,
        }
    }

    /// Centre of cell (i, j).
    pub fn center(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.x0 + (i as f64 + 0.5) * self.cell,
            self.z0 + (j as f64 + 0.5) * self.cell,
        ]
    }

    /// The cell holding a world point, if on the raster.
    pub fn cell_of(&self, x: f64, z: f64) -> Option<(usize, usize)> {
        let i = ((x - self.x0) / self.cell).floor();
        let j = ((z - self.z0) / self.cell).floor();
        (i >= 0.0 && j >= 0.0 && (i as usize) < self.nx && (j as usize) < self.nz)
            .then_some((i as usize, j as usize))
    }

    /// Free cells of the floor eroded by `inset` (all true inside, false near the border).
    pub fn floor_mask(&self, inset: f64) -> Vec<bool> {
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

    /// Clears the cells whose centres lie in `fp` grown by `grow`.
    pub fn stamp(&self, mask: &mut [bool], fp: &Footprint, grow: f64) {
        self.for_cells_in(fp, grow, |idx| mask[idx] = false);
    }

    /// Calls `f` with the index of every cell whose centre lies in `fp` grown by `grow`.
    pub fn for_cells_in(&self, fp: &Footprint, grow: f64, mut f: impl FnMut(usize)) {
        let [bx0, bz0, bx1, bz1] = fp.bounds(grow);
        let i0 = (((bx0 - self.x0) / self.cell).floor().max(0.0)) as usize;
        let j0 = (((bz0 - self.z0) / self.cell).floor().max(0.0)) as usize;
        let i1 = ((((bx1 - self.x0) / self.cell).ceil()).max(0.0) as usize).min(self.nx);
        let j1 = ((((bz1 - self.z0) / self.cell).ceil()).max(0.0) as usize).min(self.nz);
        for j in j0..j1 {
            for i in i0..i1 {
                let [x, z] = self.center(i, j);
                if fp.contains(x, z, grow) {
                    f(j * self.nx + i);
                }
            }
        }
    }

    /// 8-connected components of the free cells, labelled like [`Raster::components`].
    pub fn components8(&self, mask: &[bool]) -> (Vec<u32>, Vec<usize>) {
        let mut labels = vec![0u32; mask.len()];
        let mut sizes = vec![0usize];
        let mut stack = Vec::new();
        for start in 0..mask.len() {
            if !mask[start] || labels[start] != 0 {
                continue;
            }
            let label = sizes.len() as u32;
            let mut size = 0;
            labels[start] = label;
            stack.push(start);
            while let Some(idx) = stack.pop() {
                size += 1;
                let (i, j) = ((idx % self.nx) as i64, (idx / self.nx) as i64);
                for dj in -1..=1 {
                    for di in -1..=1 {
                        let (a, b) = (i + di, j + dj);
                        if a < 0 || b < 0 || a >= self.nx as i64 || b >= self.nz as i64 {
                            continue;
                        }
                        let n = b as usize * self.nx + a as usize;
                        if mask[n] && labels[n] == 0 {
                            labels[n] = label;
                            stack.push(n);
                        }
                    }
                }
            }
            sizes.push(size);
        }
        (labels, sizes)
    }

    /// 4-connected components of the free cells: a label per cell (0 = blocked) and the size
    /// of each label (index 0 unused).
    pub fn components(&self, mask: &[bool]) -> (Vec<u32>, Vec<usize>) {
        let mut labels = vec![0u32; mask.len()];
        let mut sizes = vec![0usize];
        let mut stack = Vec::new();
        for start in 0..mask.len() {
            if !mask[start] || labels[start] != 0 {
                continue;
            }
            let label = sizes.len() as u32;
            let mut size = 0;
            labels[start] = label;
            stack.push(start);
            while let Some(idx) = stack.pop() {
                size += 1;
                let (i, j) = (idx % self.nx, idx / self.nx);
                let mut visit = |n: usize| {
                    if mask[n] && labels[n] == 0 {
                        labels[n] = label;
                        stack.push(n);
                    }
                };
                if i > 0 {
                    visit(idx - 1);
                }
                if i + 1 < self.nx {
                    visit(idx + 1);
                }
                if j > 0 {
                    visit(idx - self.nx);
                }
                if j + 1 < self.nz {
                    visit(idx + self.nx);
                }
            }
            sizes.push(size);
        }
        (labels, sizes)
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
        let (_, sizes) = r.components(&mask);
        assert_eq!(sizes.len(), 3, "two components: {sizes:?}");
    }
}
