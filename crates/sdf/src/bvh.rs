//! Bounding volume hierarchies over triangles.
//!
//! A binary tree is built with binned SAH (32-byte nodes; an inner node's two children sit
//! next to each other at `index` and `index + 1`; a leaf holds `count > 0` consecutive
//! triangles starting at `index`). It serves the winding-number traversal, and is collapsed
//! into a 4-wide tree ([`Node4`]) with box and slab bounds per child for closest-point queries,
//! whose leaves hold their triangles packed four at a time ([`Packets`]).

// Per-axis loops over small fixed arrays read best with indices.
#![allow(clippy::needless_range_loop)]

use crate::geometry::{TriPacket, F4};

/// One BVH node (32 bytes).
#[derive(Debug, Clone, Copy)]
#[repr(C, align(32))]
pub(crate) struct Node {
    /// Box minimum.
    pub min: [f32; 3],
    /// Number of triangles for a leaf, 0 for an inner node.
    pub count: u32,
    /// Box maximum.
    pub max: [f32; 3],
    /// First triangle (leaf) or left child (inner node; right child is `index + 1`).
    pub index: u32,
}

impl Node {
    const EMPTY: Node = Node {
        min: [f32::INFINITY; 3],
        count: 0,
        max: [f32::NEG_INFINITY; 3],
        index: 0,
    };
}

#[derive(Clone, Copy)]
struct Bounds {
    min: [f32; 3],
    max: [f32; 3],
}

impl Bounds {
    const EMPTY: Bounds = Bounds {
        min: [f32::INFINITY; 3],
        max: [f32::NEG_INFINITY; 3],
    };
    fn grow(&mut self, o: &Bounds) {
        for i in 0..3 {
            self.min[i] = self.min[i].min(o.min[i]);
            self.max[i] = self.max[i].max(o.max[i]);
        }
    }
    fn grow_point(&mut self, p: &[f32; 3]) {
        for i in 0..3 {
            self.min[i] = self.min[i].min(p[i]);
            self.max[i] = self.max[i].max(p[i]);
        }
    }
    fn half_area(&self) -> f32 {
        let d = [
            (self.max[0] - self.min[0]).max(0.0),
            (self.max[1] - self.min[1]).max(0.0),
            (self.max[2] - self.min[2]).max(0.0),
        ];
        d[0] * d[1] + d[1] * d[2] + d[2] * d[0]
    }
}

const LEAF_SIZE: usize = 12;
const BINS: usize = 16;

/// Builds a subtree over `items` (triangle ids; reordered in place) whose triangle boxes are
/// `boxes[id]`, appending nodes to `nodes`. `offset` is where `items[0]` will sit in the final
/// triangle array. Returns the root's node index.
pub(crate) fn build(
    nodes: &mut Vec<Node>,
    items: &mut [u32],
    offset: u32,
    boxes: &[([f32; 3], [f32; 3])],
) -> u32 {
    let root = nodes.len() as u32;
    nodes.push(Node::EMPTY);
    let centroids: Vec<[f32; 3]> = boxes
        .iter()
        .map(|(a, b)| {
            [
                0.5 * (a[0] + b[0]),
                0.5 * (a[1] + b[1]),
                0.5 * (a[2] + b[2]),
            ]
        })
        .collect();
    let mut builder = Builder {
        nodes,
        boxes,
        centroids: &centroids,
    };
    builder.split(root as usize, items, offset);
    root
}

struct Builder<'a> {
    nodes: &'a mut Vec<Node>,
    boxes: &'a [([f32; 3], [f32; 3])],
    centroids: &'a [[f32; 3]],
}

impl Builder<'_> {
    fn item_bounds(&self, id: u32) -> Bounds {
        let (min, max) = self.boxes[id as usize];
        Bounds { min, max }
    }

    fn split(&mut self, node: usize, items: &mut [u32], offset: u32) {
        let mut bounds = Bounds::EMPTY;
        let mut cbounds = Bounds::EMPTY;
        for &id in items.iter() {
            bounds.grow(&self.item_bounds(id));
            cbounds.grow_point(&self.centroids[id as usize]);
        }
        self.nodes[node].min = bounds.min;
        self.nodes[node].max = bounds.max;
        let n = items.len();
        if n <= LEAF_SIZE {
            self.make_leaf(node, n, offset);
            return;
        }
        // Longest centroid axis.
        let ext = [
            cbounds.max[0] - cbounds.min[0],
            cbounds.max[1] - cbounds.min[1],
            cbounds.max[2] - cbounds.min[2],
        ];
        let axis = if ext[0] >= ext[1] && ext[0] >= ext[2] {
            0
        } else if ext[1] >= ext[2] {
            1
        } else {
            2
        };
        let mid = if ext[axis] <= 0.0 {
            n / 2
        } else {
            // Binned SAH along `axis`.
            let scale = BINS as f32 / ext[axis];
            let bin_of = |c: &[f32; 3]| -> usize {
                (((c[axis] - cbounds.min[axis]) * scale) as usize).min(BINS - 1)
            };
            let mut bin_bounds = [Bounds::EMPTY; BINS];
            let mut bin_count = [0usize; BINS];
            for &id in items.iter() {
                let b = bin_of(&self.centroids[id as usize]);
                bin_bounds[b].grow(&self.item_bounds(id));
                bin_count[b] += 1;
            }
            let mut right_area = [0.0f32; BINS];
            let mut acc = Bounds::EMPTY;
            let mut cnt = 0;
            let mut right_count = [0usize; BINS];
            for b in (1..BINS).rev() {
                acc.grow(&bin_bounds[b]);
                cnt += bin_count[b];
                right_area[b] = acc.half_area();
                right_count[b] = cnt;
            }
            let mut best_cost = f32::INFINITY;
            let mut best_split = 0;
            let mut left = Bounds::EMPTY;
            let mut left_count = 0;
            for b in 0..BINS - 1 {
                left.grow(&bin_bounds[b]);
                left_count += bin_count[b];
                if left_count == 0 || right_count[b + 1] == 0 {
                    continue;
                }
                let cost = left.half_area() * left_count as f32
                    + right_area[b + 1] * right_count[b + 1] as f32;
                if cost < best_cost {
                    best_cost = cost;
                    best_split = b + 1;
                }
            }
            if best_split == 0 {
                n / 2
            } else {
                // Partition items by bin.
                let mut i = 0;
                let mut j = n;
                while i < j {
                    if bin_of(&self.centroids[items[i] as usize]) < best_split {
                        i += 1;
                    } else {
                        j -= 1;
                        items.swap(i, j);
                    }
                }
                i
            }
        };
        let mid = if mid == 0 || mid == n {
            // Fall back to a median split by centroid.
            items.sort_unstable_by(|a, b| {
                self.centroids[*a as usize][axis].total_cmp(&self.centroids[*b as usize][axis])
            });
            n / 2
        } else {
            mid
        };
        let left = self.nodes.len();
        self.nodes.push(Node::EMPTY);
        self.nodes.push(Node::EMPTY);
        self.nodes[node].count = 0;
        self.nodes[node].index = left as u32;
        let (l, r) = items.split_at_mut(mid);
        self.split(left, l, offset);
        self.split(left + 1, r, offset + mid as u32);
    }

    fn make_leaf(&mut self, node: usize, n: usize, offset: u32) {
        self.nodes[node].count = n as u32;
        self.nodes[node].index = offset;
    }
}

/// A 4-wide node for closest-point queries: the bounds of up to four children side by side
/// (structure of arrays, 192 bytes = three cache lines), so one node visit tests four children
/// at once. Each child
/// has a box and a slab (unit axis `normal`, every point of its triangles has
/// `normal · x ∈ [low, high]`); the larger of the two distances is the lower bound used to
/// prune. Slabs are much tighter than boxes for flat, tilted surface patches.
#[derive(Debug, Clone, Copy)]
#[repr(C, align(64))]
pub(crate) struct Node4 {
    pub min: [F4; 3],
    pub max: [F4; 3],
    pub normal: [F4; 3],
    pub low: F4,
    pub high: F4,
    /// Inner child: its index in the 4-wide node array (top bit clear). Leaf child: top bit
    /// set, then its first [`TriPacket`] and, in the two low bits, its packet count minus one.
    child: [u32; 4],
}

/// Marks a leaf child in [`Node4::child`].
const LEAF_BIT: u32 = 1 << 31;
// A leaf's packet count minus one must fit in two bits.
const _: () = assert!(LEAF_SIZE <= 16);
const _: () = assert!(std::mem::size_of::<Node4>() == 192);

impl Node4 {
    const EMPTY: Node4 = Node4 {
        min: [F4([f32::INFINITY; 4]); 3],
        max: [F4([f32::NEG_INFINITY; 4]); 3],
        normal: [F4([0.0; 4]); 3],
        low: F4([f32::NEG_INFINITY; 4]),
        high: F4([f32::INFINITY; 4]),
        child: [0; 4],
    };

    /// Child `lane` as `(4-wide node, 0)` for an inner child or `(first packet, packet count)`
    /// for a leaf.
    #[inline(always)]
    pub fn entry(&self, lane: usize) -> (u32, u32) {
        let c = self.child[lane];
        if c & LEAF_BIT == 0 {
            (c, 0)
        } else {
            ((c & !LEAF_BIT) >> 2, (c & 3) + 1)
        }
    }

    /// Squared lower bounds on the distance from `p` (splatted) to the four children's
    /// triangles (infinite for empty lanes).
    #[inline(always)]
    pub fn distances2(&self, p: &[F4; 3]) -> F4 {
        let zero = F4::splat(0.0);
        let mut d2 = zero;
        let mut proj = zero;
        for axis in 0..3 {
            let d = (self.min[axis] - p[axis])
                .max(p[axis] - self.max[axis])
                .max(zero);
            d2 = d2 + d * d;
            proj = proj + self.normal[axis] * p[axis];
        }
        let s = (self.low - proj).max(proj - self.high).max(zero);
        d2.max(s * s)
    }
}

/// The leaves' triangles packed four at a time for closest-point queries.
#[derive(Debug, Clone, Default)]
pub(crate) struct Packets {
    /// The packets; a leaf's packets are consecutive.
    pub packets: Vec<TriPacket>,
    /// Index (in the triangle array) of each packet's lane-0 triangle; lane `k` is `first + k`.
    pub first_tri: Vec<u32>,
}

impl Packets {
    /// Packs the `count` triangles from `first`; returns `(first packet, packet count)`.
    pub fn add_leaf(
        &mut self,
        tris: &[[nalgebra::Vector3<f32>; 3]],
        first: u32,
        count: u32,
    ) -> (u32, u32) {
        let start = self.packets.len() as u32;
        let range = &tris[first as usize..(first + count) as usize];
        for (k, chunk) in range.chunks(4).enumerate() {
            self.packets.push(TriPacket::new(chunk));
            self.first_tri.push(first + 4 * k as u32);
        }
        (start, self.packets.len() as u32 - start)
    }
}

/// Collapses the binary subtree at `node` (an inner node) into 4-wide nodes appended to
/// `out`, packing its leaves into `packets`; returns the index of its 4-wide root.
pub(crate) fn collapse(
    bin: &[Node],
    node: u32,
    tris: &[[nalgebra::Vector3<f32>; 3]],
    out: &mut Vec<Node4>,
    packets: &mut Packets,
) -> u32 {
    let n = &bin[node as usize];
    debug_assert_eq!(n.count, 0);
    let mut kids: Vec<u32> = vec![n.index, n.index + 1];
    while kids.len() < 4 {
        let area = |k: u32| {
            let b = &bin[k as usize];
            Bounds {
                min: b.min,
                max: b.max,
            }
            .half_area()
        };
        let pick = kids
            .iter()
            .enumerate()
            .filter(|(_, &k)| bin[k as usize].count == 0)
            .max_by(|a, b| area(*a.1).total_cmp(&area(*b.1)))
            .map(|(i, &k)| (i, k));
        let Some((i, k)) = pick else { break };
        kids.remove(i);
        let inner = &bin[k as usize];
        kids.push(inner.index);
        kids.push(inner.index + 1);
    }
    let me = out.len();
    out.push(Node4::EMPTY);
    let mut wide = Node4::EMPTY;
    for (lane, &k) in kids.iter().enumerate() {
        let b = &bin[k as usize];
        for axis in 0..3 {
            wide.min[axis].0[lane] = b.min[axis];
            wide.max[axis].0[lane] = b.max[axis];
        }
        let (normal, low, high) = slab(&tris[triangle_range(bin, k)]);
        for axis in 0..3 {
            wide.normal[axis].0[lane] = normal[axis];
        }
        wide.low.0[lane] = low;
        wide.high.0[lane] = high;
        if b.count > 0 {
            let (first, count) = packets.add_leaf(tris, b.index, b.count);
            assert!(first < LEAF_BIT >> 2, "too many triangle packets");
            wide.child[lane] = LEAF_BIT | (first << 2) | (count - 1);
        } else {
            wide.child[lane] = collapse(bin, k, tris, out, packets);
        }
    }
    out[me] = wide;
    me as u32
}

/// The triangles under binary node `k` (subtrees are contiguous in triangle order).
fn triangle_range(bin: &[Node], k: u32) -> std::ops::Range<usize> {
    let mut first = k;
    while bin[first as usize].count == 0 {
        first = bin[first as usize].index;
    }
    let mut last = k;
    while bin[last as usize].count == 0 {
        last = bin[last as usize].index + 1;
    }
    let (f, l) = (&bin[first as usize], &bin[last as usize]);
    f.index as usize..(l.index + l.count) as usize
}

/// The slab of a set of triangles along their area-weighted mean normal: `(axis, low, high)`,
/// slightly widened so rounding never makes it exclude a triangle.
fn slab(tris: &[[nalgebra::Vector3<f32>; 3]]) -> ([f32; 3], f32, f32) {
    let sum: nalgebra::Vector3<f32> = tris
        .iter()
        .map(|t| (t[1] - t[0]).cross(&(t[2] - t[0])))
        .sum();
    let Some(n) = sum.try_normalize(1e-20) else {
        return ([0.0; 3], f32::NEG_INFINITY, f32::INFINITY);
    };
    let mut low = f32::INFINITY;
    let mut high = f32::NEG_INFINITY;
    let mut scale = 0.0f32;
    for t in tris {
        for v in t {
            let d = n.dot(v);
            low = low.min(d);
            high = high.max(d);
            scale = scale.max(v.amax());
        }
    }
    let eps = (scale + (high - low).abs()) * 1e-6;
    ([n.x, n.y, n.z], low - eps, high + eps)
}
