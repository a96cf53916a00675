//! A square-cell raster over the floor plane (x, z) and its connected components: the one
//! routine behind the guide's walkway checks and the Walk and Reach metrics.

use std::ops::Range;

/// Label of a blocked cell in [`Components::labels`].
pub const BLOCKED_CELL: u32 = 0;

/// A raster of `nx` × `nz` square cells of side `cell` (m) whose corner is (`x0`, `z0`) on the
/// floor plane. Cell (i, j) has the flat index `j * nx + i`; masks are `Vec<bool>` in that
/// order with `true` meaning free.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FloorRaster {
    /// World x (m) of the raster's low edge.
    pub x0: f64,
    /// World z (m) of the raster's low edge.
    pub z0: f64,
    /// Side of a cell (m).
    pub cell: f64,
    /// Cells along x.
    pub nx: usize,
    /// Cells along z.
    pub nz: usize,
}

/// Connected components of a mask: a label per cell ([`BLOCKED_CELL`] for blocked cells, labels
/// from 1 in the order their first cell appears in the flat index) and the cell count of each
/// label (`sizes[0]` is always 0).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Components {
    /// The label of each cell, in flat index order.
    pub labels: Vec<u32>,
    /// Cell count per label; index 0 (blocked) is 0.
    pub sizes: Vec<usize>,
}

impl Components {
    /// Number of components (labels other than [`BLOCKED_CELL`]).
    pub fn count(&self) -> usize {
        self.sizes.len() - 1
    }

    /// Free cells over all components.
    pub fn total(&self) -> usize {
        self.sizes.iter().sum()
    }
}

impl FloorRaster {
    /// A raster of `cell`-sized cells covering [x0, x1] × [z0, z1] (at least one cell each way).
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

    /// An `n` × `n` raster over the square of side `side` whose low corner is (`x0`, `z0`).
    pub fn square(x0: f64, z0: f64, side: f64, n: usize) -> Self {
        Self {
            x0,
            z0,
            cell: side / n as f64,
            nx: n,
            nz: n,
        }
    }

    /// Number of cells.
    pub fn len(&self) -> usize {
        self.nx * self.nz
    }

    /// Whether the raster has no cells.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// World (x, z) of the centre of cell (i, j).
    pub fn center(&self, i: usize, j: usize) -> [f64; 2] {
        [
            self.x0 + (i as f64 + 0.5) * self.cell,
            self.z0 + (j as f64 + 0.5) * self.cell,
        ]
    }

    /// The cell holding a world point, if it is on the raster.
    pub fn cell_of(&self, x: f64, z: f64) -> Option<(usize, usize)> {
        let i = ((x - self.x0) / self.cell).floor();
        let j = ((z - self.z0) / self.cell).floor();
        (i >= 0.0 && j >= 0.0 && (i as usize) < self.nx && (j as usize) < self.nz)
            .then_some((i as usize, j as usize))
    }

    /// The cell index ranges (i, j) of every cell that may hold a point of the world box
    /// `[min x, min z, max x, max z]`, clamped to the raster (a superset: callers test the
    /// cell centres themselves).
    pub fn cell_range(&self, b: [f64; 4]) -> (Range<usize>, Range<usize>) {
        let to = |v: f64, o: f64| ((v - o) / self.cell).floor();
        let clamp = |v: f64, n: usize| v.clamp(0.0, n as f64) as usize;
        let i0 = clamp(to(b[0], self.x0), self.nx);
        let i1 = clamp(to(b[2], self.x0) + 1.0, self.nx);
        let j0 = clamp(to(b[1], self.z0), self.nz);
        let j1 = clamp(to(b[3], self.z0) + 1.0, self.nz);
        (i0..i1, j0..j1)
    }

    /// Calls `f` with the flat index of every cell in the box `b` (see
    /// [`FloorRaster::cell_range`]) whose centre passes `inside`.
    pub fn for_cells_where(
        &self,
        b: [f64; 4],
        mut inside: impl FnMut(f64, f64) -> bool,
        mut f: impl FnMut(usize),
    ) {
        let (is, js) = self.cell_range(b);
        for j in js {
            for i in is.clone() {
                let [x, z] = self.center(i, j);
                if inside(x, z) {
                    f(j * self.nx + i);
                }
            }
        }
    }

    /// 8-connected components of the free cells of `mask`.
    pub fn components8(&self, mask: &[bool]) -> Components {
        self.label(mask, true)
    }

    /// 4-connected components of the free cells of `mask`.
    pub fn components4(&self, mask: &[bool]) -> Components {
        self.label(mask, false)
    }

    /// Labels the components by depth-first flood fill from each unlabelled free cell in flat
    /// index order. The neighbours are visited with plain index arithmetic (no iterator
    /// chain): this runs twice per candidate pose the guide tries, and the labels and sizes
    /// do not depend on the order a component's cells are visited in.
    fn label(&self, mask: &[bool], diagonal: bool) -> Components {
        assert_eq!(mask.len(), self.len(), "mask size must match the raster");
        let (nx, nz) = (self.nx, self.nz);
        let mut labels = vec![BLOCKED_CELL; mask.len()];
        let mut sizes = vec![0usize];
        let mut stack = Vec::new();
        for start in 0..mask.len() {
            if !mask[start] || labels[start] != BLOCKED_CELL {
                continue;
            }
            let label = sizes.len() as u32;
            let mut size = 0;
            labels[start] = label;
            stack.push(start);
            while let Some(idx) = stack.pop() {
                size += 1;
                let (i, j) = (idx % nx, idx / nx);
                let (left, right) = (i > 0, i + 1 < nx);
                let (down, up) = (j > 0, j + 1 < nz);
                let mut visit = |n: usize| {
                    if mask[n] && labels[n] == BLOCKED_CELL {
                        labels[n] = label;
                        stack.push(n);
                    }
                };
                if down {
                    if diagonal && left {
                        visit(idx - nx - 1);
                    }
                    visit(idx - nx);
                    if diagonal && right {
                        visit(idx - nx + 1);
                    }
                }
                if left {
                    visit(idx - 1);
                }
                if right {
                    visit(idx + 1);
                }
                if up {
                    if diagonal && left {
                        visit(idx + nx - 1);
                    }
                    visit(idx + nx);
                    if diagonal && right {
                        visit(idx + nx + 1);
                    }
                }
            }
            sizes.push(size);
        }
        Components { labels, sizes }
    }

    /// Flat indices of the cells next to `idx` (4- or 8-neighbourhood), on the raster.
    fn neighbours(&self, idx: usize, diagonal: bool) -> impl Iterator<Item = usize> + '_ {
        let (i, j) = ((idx % self.nx) as i64, (idx / self.nx) as i64);
        (-1i64..=1)
            .flat_map(|dj| (-1i64..=1).map(move |di| (di, dj)))
            .filter(move |&(di, dj)| (di, dj) != (0, 0) && (diagonal || di == 0 || dj == 0))
            .map(move |(di, dj)| (i + di, j + dj))
            .filter(|&(a, b)| a >= 0 && b >= 0 && a < self.nx as i64 && b < self.nz as i64)
            .map(|(a, b)| b as usize * self.nx + a as usize)
    }

    /// The labels (other than [`BLOCKED_CELL`]) of the cells a set of cells touches once dilated by
    /// one cell (8-neighbourhood), sorted and without repeats.
    pub fn touched_labels(&self, cells: &[usize], labels: &[u32]) -> Vec<u32> {
        let mut out = std::collections::BTreeSet::new();
        for &c in cells {
            for n in std::iter::once(c).chain(self.neighbours(c, true)) {
                if labels[n] != BLOCKED_CELL {
                    out.insert(labels[n]);
                }
            }
        }
        out.into_iter().collect()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 10 × 10 raster over the unit square with a one-cell column blocked at i = 5.
    fn split() -> (FloorRaster, Vec<bool>) {
        let r = FloorRaster::new(0.0, 0.0, 1.0, 1.0, 0.1);
        let mut mask = vec![true; r.len()];
        r.for_cells_where(
            [0.45, -1.0, 0.55, 2.0],
            |x, _| (x - 0.55).abs() < 0.01,
            |i| mask[i] = false,
        );
        (r, mask)
    }

    #[test]
    fn a_blocked_column_splits_the_floor_in_two() {
        let (r, mask) = split();
        assert_eq!((r.nx, r.nz), (10, 10));
        assert_eq!(mask.iter().filter(|m| !**m).count(), 10);
        for c in [r.components4(&mask), r.components8(&mask)] {
            assert_eq!(c.sizes, vec![0, 50, 40], "left then right: {:?}", c.sizes);
            assert_eq!(c.count(), 2);
            assert_eq!(c.total(), 90);
            assert_eq!(c.labels[0], 1);
            assert_eq!(c.labels[5], BLOCKED_CELL);
            assert_eq!(c.labels[9], 2);
        }
    }

    #[test]
    fn diagonal_steps_join_only_eight_connected_components() {
        let r = FloorRaster::square(0.0, 0.0, 2.0, 2);
        let mask = [true, false, false, true];
        assert_eq!(r.components4(&mask).count(), 2);
        assert_eq!(r.components8(&mask).count(), 1);
        assert_eq!(r.cell, 1.0);
        assert_eq!(r.cell_of(1.5, 0.2), Some((1, 0)));
        assert_eq!(r.cell_of(2.5, 0.2), None);
    }

    #[test]
    fn touched_labels_see_the_neighbouring_components() {
        let (r, mask) = split();
        let c = r.components8(&mask);
        // The blocked cell (5, 3) touches both sides; cell (1, 1) only the left one.
        assert_eq!(r.touched_labels(&[3 * 10 + 5], &c.labels), vec![1, 2]);
        assert_eq!(r.touched_labels(&[11], &c.labels), vec![1]);
        assert!(r.touched_labels(&[], &c.labels).is_empty());
    }

    #[test]
    fn cell_range_is_clamped_and_covers_the_box() {
        let r = FloorRaster::new(0.0, 0.0, 1.0, 1.0, 0.1);
        assert_eq!(r.cell_range([-5.0, -5.0, 5.0, 5.0]), (0..10, 0..10));
        assert_eq!(r.cell_range([0.25, 0.31, 0.35, 0.39]), (2..4, 3..4));
    }
}
