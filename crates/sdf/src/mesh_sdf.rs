//! Exact signed distance to a triangle mesh.

use std::collections::HashMap;

use nalgebra::{Point3, Vector3};
use rayon::prelude::*;

use crate::bvh::{self, Node, Node4, Packets};
use crate::geometry::{closest_on_triangle, distance2_to_box, solid_angle, Feature, F4};
use crate::{SdfError, SdfQuery, SignedDistance};

type V3 = Vector3<f32>;

const NO_TRIANGLE: u32 = u32::MAX;
/// Far-field acceptance ratio of the hierarchical winding number: a node whose triangles all lie
/// within `radius` of its centre is replaced by its dipole when the query is farther than
/// `WINDING_BETA * radius`.
const WINDING_BETA: f32 = 3.0;

/// How the sign of one solid of a [`MeshSdf`] is decided.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum SignRule {
    /// A closed, consistently oriented component: the sign comes from the angle-weighted
    /// pseudo-normal of the closest feature (face, edge or vertex). Exact for closed manifolds
    /// that do not intersect themselves.
    PseudoNormal,
    /// All open (holed) components together: a point is inside where the generalized winding
    /// number is at least ½, computed hierarchically (exact solid angles near the query,
    /// first-order dipoles for far BVH nodes). Robust to small holes and cracks; for large
    /// holes "inside" degrades gracefully toward "mostly enclosed", and meshes that are not
    /// outward-oriented (CCW seen from outside) come out inside-out.
    WindingNumber,
}

#[derive(Debug, Clone, Copy)]
struct Group {
    root: u32,
    /// Entry of the 4-wide tree: (4-wide node, 0) or, for a one-leaf group, (first packet,
    /// packet count).
    wide_root: (u32, u32),
    first_tri: u32,
    end_tri: u32,
    min: [f32; 3],
    max: [f32; 3],
    rule: SignRule,
}

impl Group {
    #[inline]
    fn contains(&self, p: &[f32; 3]) -> bool {
        (0..3).all(|i| self.min[i] <= p[i] && p[i] <= self.max[i])
    }
    #[inline]
    fn holds(&self, tri: u32) -> bool {
        self.first_tri <= tri && tri < self.end_tri
    }
}

/// Angle-weighted pseudo-normals of one triangle: face, edges (ab, bc, ca), vertices (a, b, c).
#[derive(Debug, Clone, Copy, Default)]
struct PseudoNormals([V3; 7]);

/// First-order far-field summary of a BVH node's triangles for the winding number.
#[derive(Debug, Clone, Copy, Default)]
struct Dipole {
    center: V3,
    area_normal: V3,
    radius: f32,
}

/// The nearest triangle found so far: squared distance, triangle, and its packet lane
/// (`4 · packet + lane`) whose cached corners and face normal can sign it without touching the
/// per-triangle arrays.
#[derive(Debug, Clone, Copy)]
struct Nearest {
    d2: f32,
    tri: u32,
    slot: u32,
}

impl Nearest {
    const NONE: Nearest = Nearest {
        d2: f32::INFINITY,
        tri: NO_TRIANGLE,
        slot: NO_TRIANGLE,
    };
}

/// The closest triangle found by a search, and whether the query point is inside.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Hit {
    pub tri: u32,
    /// The triangle's packet lane (`4 · packet + lane`): the hint for a later search.
    pub slot: u32,
    pub distance2: f32,
    pub inside: bool,
}

impl Hit {
    #[inline]
    pub fn signed_distance(&self) -> f32 {
        let d = self.distance2.sqrt();
        if self.inside {
            -d
        } else {
            d
        }
    }
}

/// Exact signed distance field of a triangle mesh, accelerated by a BVH.
///
/// The mesh is split into *solids*: every connected, closed and consistently oriented component
/// (after welding vertices with identical positions) is a solid signed by pseudo-normals
/// ([`SignRule::PseudoNormal`]); all remaining open components together form one solid signed by
/// the generalized winding number ([`SignRule::WindingNumber`]). Solids combine as a union: a
/// point inside any solid is inside, and the field is the minimum of the solids' signed
/// distances. Outside every solid that is the exact distance to the union's surface; inside, it
/// is minus the depth within the deepest containing solid (a lower bound on the depth in the
/// union, exact wherever the nearest surface point is not buried inside another solid).
///
/// Queries are `f32`; `MeshSdf` is `Send + Sync` and cheap to share through an `Arc`. A query
/// searches a 4-wide BVH (box and slab bounds per child) whose leaves hold triangles packed four
/// at a time for branch-free distance tests; queries in a box around the mesh start from the
/// triangle a coarse seed grid (built with the field) stores for their cell, whose distance is a
/// tight upper bound from the first step.
#[derive(Debug, Clone)]
pub struct MeshSdf {
    tris: Vec<[V3; 3]>,
    nodes: Vec<Node>,
    wide: Vec<Node4>,
    packets: Packets,
    groups: Vec<Group>,
    normals: Vec<PseudoNormals>,
    dipoles: Vec<Dipole>,
    min: Point3<f32>,
    max: Point3<f32>,
    grad_epsilon: f32,
    /// Starting triangles for unhinted searches.
    seeds: SeedGrid,
}

/// Fewest triangles for which a [`SeedGrid`] is built.
const SEED_MIN_TRIANGLES: usize = 256;
/// Largest number of cells of a [`SeedGrid`].
const SEED_MAX_CELLS: usize = 4096;

/// A coarse grid over the mesh's bounds, padded by a quarter of the longest side, holding per
/// cell the packet slot of the triangle nearest to the cell's centre. An unhinted query inside
/// it starts from that triangle: its distance is a valid (and usually tight) upper bound, so the
/// tree search prunes from the start. Empty for small meshes.
#[derive(Debug, Clone, Default)]
struct SeedGrid {
    origin: [f32; 3],
    cell: f32,
    dims: [usize; 3],
    slots: Vec<u32>,
}

impl SeedGrid {
    /// The seed slot of the cell holding `p` ([`NO_TRIANGLE`] outside the grid).
    #[inline]
    fn slot(&self, p: &V3) -> u32 {
        let mut index = 0;
        let mut stride = 1;
        for axis in 0..3 {
            let u = (p[axis] - self.origin[axis]) / self.cell;
            // Also false for NaN.
            if !(u >= 0.0 && u < self.dims[axis] as f32) {
                return NO_TRIANGLE;
            }
            index += (u as usize).min(self.dims[axis] - 1) * stride;
            stride *= self.dims[axis];
        }
        self.slots[index]
    }
}

struct PartInput<'a> {
    name: String,
    positions: &'a [[f32; 3]],
    triangles: &'a [[u32; 3]],
}

/// A solid before BVH construction: triangle corners plus (for closed solids) pseudo-normals.
struct SolidInput {
    tris: Vec<[V3; 3]>,
    normals: Vec<PseudoNormals>,
    rule: SignRule,
}

impl MeshSdf {
    /// Builds the field of one triangle list: a closed solid, several closed (possibly
    /// overlapping) components, or an open soup with holes. Triangles are counter-clockwise
    /// seen from outside.
    pub fn new(positions: &[[f32; 3]], triangles: &[[u32; 3]]) -> Result<Self, SdfError> {
        Self::build(&[PartInput {
            name: "mesh".into(),
            positions,
            triangles,
        }])
    }

    /// Builds the field of a multi-part asset mesh. Parts may overlap (a table top and its
    /// legs); the result is their union.
    pub fn from_mesh(mesh: &scenethesis_scene_graph::Mesh) -> Result<Self, SdfError> {
        let parts: Vec<PartInput> = mesh
            .parts
            .iter()
            .map(|p| PartInput {
                name: format!("part `{}`", p.name),
                positions: &p.positions,
                triangles: &p.triangles,
            })
            .collect();
        if parts.is_empty() {
            return Err(SdfError::EmptyMesh {
                mesh: "mesh with no parts".into(),
            });
        }
        Self::build(&parts)
    }

    fn build(parts: &[PartInput]) -> Result<Self, SdfError> {
        let mut solids = Vec::new();
        let mut soup: Vec<[V3; 3]> = Vec::new();
        for part in parts {
            validate(part)?;
            split_part(part, &mut solids, &mut soup);
        }
        if !soup.is_empty() {
            let normals = soup
                .iter()
                .map(|t| {
                    let mut pn = PseudoNormals::default();
                    pn.0[0] = face_normal(t);
                    pn
                })
                .collect();
            solids.push(SolidInput {
                tris: soup,
                normals,
                rule: SignRule::WindingNumber,
            });
        }
        if solids.is_empty() {
            let name = if parts.len() == 1 {
                parts[0].name.clone()
            } else {
                "mesh".into()
            };
            return Err(SdfError::EmptyMesh { mesh: name });
        }

        let total: usize = solids.iter().map(|s| s.tris.len()).sum();
        let mut tris = Vec::with_capacity(total);
        let mut normals = Vec::with_capacity(total);
        let mut nodes = Vec::with_capacity(2 * total / 3 + solids.len());
        let mut groups = Vec::with_capacity(solids.len());
        let mut wide = Vec::new();
        let mut packets = Packets::default();
        for solid in &solids {
            let boxes: Vec<([f32; 3], [f32; 3])> = solid.tris.iter().map(tri_box).collect();
            let mut order: Vec<u32> = (0..solid.tris.len() as u32).collect();
            let first = tris.len() as u32;
            let root = bvh::build(&mut nodes, &mut order, first, &boxes);
            for &i in &order {
                tris.push(solid.tris[i as usize]);
                normals.push(solid.normals[i as usize]);
            }
            let r = &nodes[root as usize];
            let wide_root = if r.count > 0 {
                packets.add_leaf(&tris, r.index, r.count)
            } else {
                (
                    bvh::collapse(&nodes, root, &tris, &mut wide, &mut packets),
                    0,
                )
            };
            let r = &nodes[root as usize];
            groups.push(Group {
                root,
                wide_root,
                first_tri: first,
                end_tri: tris.len() as u32,
                min: r.min,
                max: r.max,
                rule: solid.rule,
            });
        }
        let mut min = Point3::from([f32::INFINITY; 3]);
        let mut max = Point3::from([f32::NEG_INFINITY; 3]);
        for g in &groups {
            min = min.inf(&Point3::from(g.min));
            max = max.sup(&Point3::from(g.max));
        }
        let extent = (max - min).amax().max(1e-6);
        let mut sdf = MeshSdf {
            tris,
            nodes,
            wide,
            packets,
            groups,
            normals,
            dipoles: Vec::new(),
            min,
            max,
            grad_epsilon: extent * 1e-6,
            seeds: SeedGrid::default(),
        };
        if sdf.groups.iter().any(|g| g.rule == SignRule::WindingNumber) {
            sdf.dipoles = vec![Dipole::default(); sdf.nodes.len()];
            let roots: Vec<u32> = sdf
                .groups
                .iter()
                .filter(|g| g.rule == SignRule::WindingNumber)
                .map(|g| g.root)
                .collect();
            for root in roots {
                sdf.fill_dipoles(root);
            }
        }
        sdf.seeds = sdf.seed_grid();
        Ok(sdf)
    }

    /// Builds the [`SeedGrid`] (empty below [`SEED_MIN_TRIANGLES`] triangles), walking each x
    /// row with the previous cell's triangle as the hint.
    fn seed_grid(&self) -> SeedGrid {
        let count = self.tris.len();
        if count < SEED_MIN_TRIANGLES {
            return SeedGrid::default();
        }
        let pad = 0.25 * (self.max - self.min).amax();
        let lo = self.min.coords.add_scalar(-pad);
        let side = (self.max - self.min).add_scalar(2.0 * pad);
        let cells = (count / 4).min(SEED_MAX_CELLS) as f32;
        let cell = (side.x * side.y * side.z / cells).cbrt().max(1e-6);
        let dims = [0, 1, 2].map(|a| ((side[a] / cell).ceil() as usize).clamp(1, 64));
        let mut slots = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                let mut hint = NO_TRIANGLE;
                for i in 0..dims[0] {
                    let centre =
                        lo + V3::new(i as f32 + 0.5, j as f32 + 0.5, k as f32 + 0.5) * cell;
                    hint = self.nearest(centre, hint).slot;
                    slots.push(hint);
                }
            }
        }
        SeedGrid {
            origin: [lo.x, lo.y, lo.z],
            cell,
            dims,
            slots,
        }
    }

    /// The nearest triangle of any solid (unsigned), starting from the hint slot.
    fn nearest(&self, p: V3, hint_slot: u32) -> Nearest {
        let hint = self.hint_packet(hint_slot);
        let mut best = Nearest::NONE;
        for g in &self.groups {
            let seed = self.seed(g, p, hint);
            if seed.d2 < best.d2 {
                best = seed;
            }
            self.closest_in(g, p, &mut best);
        }
        best
    }

    /// Computes dipoles for the subtree at `node`; returns its triangle range.
    fn fill_dipoles(&mut self, node: u32) -> (u32, u32) {
        let n = self.nodes[node as usize];
        let (first, end) = if n.count > 0 {
            (n.index, n.index + n.count)
        } else {
            let (a, _) = self.fill_dipoles(n.index);
            let (_, b) = self.fill_dipoles(n.index + 1);
            (a, b)
        };
        let mut area_normal = V3::zeros();
        let mut weighted = V3::zeros();
        let mut area_sum = 0.0f32;
        for t in &self.tris[first as usize..end as usize] {
            let an = (t[1] - t[0]).cross(&(t[2] - t[0])) * 0.5;
            let area = an.norm();
            area_normal += an;
            weighted += (t[0] + t[1] + t[2]) * (area / 3.0);
            area_sum += area;
        }
        let center = if area_sum > 0.0 {
            weighted / area_sum
        } else {
            (V3::from(n.min) + V3::from(n.max)) * 0.5
        };
        let mut radius = 0.0f32;
        for t in &self.tris[first as usize..end as usize] {
            for v in t {
                radius = radius.max((v - center).norm());
            }
        }
        self.dipoles[node as usize] = Dipole {
            center,
            area_normal,
            radius,
        };
        (first, end)
    }

    /// Number of triangles used (degenerate ones are dropped).
    pub fn triangle_count(&self) -> usize {
        self.tris.len()
    }

    /// The sign rule of each solid, closed solids first, then the open soup if any.
    pub fn sign_rules(&self) -> Vec<SignRule> {
        self.groups.iter().map(|g| g.rule).collect()
    }

    /// Exact signed distance, closest surface point and gradient at `p`.
    pub fn query(&self, p: &Point3<f32>) -> SdfQuery {
        let hit = self.search(p.coords, NO_TRIANGLE);
        self.finish(p.coords, &hit)
    }

    /// Exact signed distance at `p` (negative inside).
    #[inline]
    pub fn signed_distance(&self, p: &Point3<f32>) -> f32 {
        self.search(p.coords, NO_TRIANGLE).signed_distance()
    }

    /// Whether `p` is inside the solid (inside any of its parts).
    pub fn contains(&self, p: &Point3<f32>) -> bool {
        self.search(p.coords, NO_TRIANGLE).inside
    }

    /// Signed distances of many points, in parallel (rayon).
    pub fn distances(&self, points: &[Point3<f32>]) -> Vec<f32> {
        points.par_iter().map(|p| self.signed_distance(p)).collect()
    }

    /// Generalized winding number of the whole mesh at `p` (about 1 inside a closed outward
    /// surface, 0 outside; overlapping parts add up), computed hierarchically.
    pub fn winding_number(&self, p: &Point3<f32>) -> f32 {
        let mut total = 0.0;
        for g in &self.groups {
            total += match g.rule {
                SignRule::WindingNumber => self.winding(g.root, p.coords),
                SignRule::PseudoNormal => self.exact_winding(g, p.coords),
            };
        }
        total
    }

    fn exact_winding(&self, g: &Group, p: V3) -> f32 {
        let sum: f32 = self.tris[g.first_tri as usize..g.end_tri as usize]
            .iter()
            .map(|t| solid_angle(p, t[0], t[1], t[2]))
            .sum();
        sum / (4.0 * std::f32::consts::PI)
    }

    /// Signed distance with an optional hint, the `slot` of an earlier hit near `p` (speeds up
    /// coherent queries); returns the hit so the caller can pass its slot as the next hint.
    #[inline]
    pub(crate) fn search_hinted(&self, p: &Point3<f32>, hint: Option<u32>) -> Hit {
        self.search(p.coords, hint.unwrap_or(NO_TRIANGLE))
    }

    /// Nearest triangle, its squared distance and whether `p` is inside, starting from the
    /// hint slot `hint_slot` (any value; out-of-range ones are ignored) or, without one
    /// ([`NO_TRIANGLE`]), from the seed grid.
    fn search(&self, p: V3, hint_slot: u32) -> Hit {
        let hint_slot = if hint_slot == NO_TRIANGLE {
            self.seeds.slot(&p)
        } else {
            hint_slot
        };
        let hint = self.hint_packet(hint_slot);
        let pa = [p.x, p.y, p.z];
        if self.groups.len() == 1 {
            let g = &self.groups[0];
            let mut best = self.seed(g, p, hint);
            self.closest_in(g, p, &mut best);
            let inside = g.contains(&pa) && self.inside_group(g, p, &best);
            return Hit {
                tri: best.tri,
                slot: best.slot,
                distance2: best.d2,
                inside,
            };
        }
        // Solids whose box holds p may contain it: search each fully and sign it.
        let mut best = Nearest::NONE;
        let mut deepest: Option<Nearest> = None;
        for g in &self.groups {
            if !g.contains(&pa) {
                continue;
            }
            let mut near = self.seed(g, p, hint);
            self.closest_in(g, p, &mut near);
            if self.inside_group(g, p, &near) && deepest.is_none_or(|dd| near.d2 > dd.d2) {
                deepest = Some(near);
            }
            if near.d2 < best.d2 {
                best = near;
            }
        }
        if let Some(near) = deepest {
            return Hit {
                tri: near.tri,
                slot: near.slot,
                distance2: near.d2,
                inside: true,
            };
        }
        // Outside every solid: the nearest triangle of any solid decides.
        for g in &self.groups {
            if g.contains(&pa) || distance2_to_box(&pa, &g.min, &g.max) >= best.d2 {
                continue;
            }
            if best.tri == NO_TRIANGLE && hint.is_some_and(|(_, first)| g.holds(first)) {
                best = self.seed(g, p, hint);
            }
            self.closest_in(g, p, &mut best);
        }
        Hit {
            tri: best.tri,
            slot: best.slot,
            distance2: best.d2,
            inside: false,
        }
    }

    /// The hint's packet and its first triangle (all its triangles share a leaf), if the slot
    /// names a packet.
    #[inline]
    fn hint_packet(&self, slot: u32) -> Option<(usize, u32)> {
        let packet = (slot / 4) as usize;
        self.packets
            .first_tri
            .get(packet)
            .map(|&first| (packet, first))
    }

    /// The starting bound of a search in `g`: the nearest triangle of the hint's packet
    /// `(packet, its first triangle)` if that packet belongs to `g`.
    #[inline]
    fn seed(&self, g: &Group, p: V3, hint: Option<(usize, u32)>) -> Nearest {
        if let Some((packet, first)) = hint.filter(|&(_, first)| g.holds(first)) {
            // The whole packet of the hint (its leaf neighbours) in one go; padding lanes are
            // infinitely far, so the nearest lane is a real triangle.
            let ds = self.packets.packets[packet].distances2(&[
                F4::splat(p.x),
                F4::splat(p.y),
                F4::splat(p.z),
            ]);
            let d2 = ds.min_lane();
            let lane = ds.0.iter().position(|&d| d == d2).unwrap_or(0) as u32;
            Nearest {
                d2,
                tri: first + lane,
                slot: 4 * packet as u32 + lane,
            }
        } else {
            Nearest::NONE
        }
    }

    /// Whether `p`, whose nearest triangle of solid `g` is `near`, is inside that solid.
    #[inline]
    fn inside_group(&self, g: &Group, p: V3, near: &Nearest) -> bool {
        match g.rule {
            SignRule::PseudoNormal => {
                let tri = near.tri;
                // Corners from the packet the search just read (in cache).
                let packet = self.packets.packets.get((near.slot / 4) as usize);
                let lane = (near.slot % 4) as usize;
                let t = match packet {
                    Some(packet) => packet.triangle(lane),
                    None => self.tris[tri as usize],
                };
                let (q, feature) = closest_on_triangle(p, t[0], t[1], t[2]);
                let normal = match (feature, packet) {
                    (Feature::Face, Some(packet)) => packet.face_normal(lane),
                    _ => self.pseudo_normal(tri, feature),
                };
                (p - q).dot(&normal) < 0.0
            }
            SignRule::WindingNumber => self.winding(g.root, p) >= 0.5,
        }
    }

    #[inline]
    fn pseudo_normal(&self, tri: u32, feature: Feature) -> V3 {
        let pn = &self.normals[tri as usize].0;
        match feature {
            Feature::Face => pn[0],
            Feature::Edge(e) => pn[1 + e as usize],
            Feature::Vertex(v) => pn[4 + v as usize],
        }
    }

    /// Nearest triangle of group `g`, improving `best`.
    #[inline]
    fn closest_in(&self, g: &Group, p: V3, best: &mut Nearest) {
        let pa = [p.x, p.y, p.z];
        let d = distance2_to_box(&pa, &g.min, &g.max);
        if d < best.d2 {
            self.closest_from(g.wide_root, d, p, best);
        }
    }

    /// Depth-first, nearest-first search of the 4-wide tree from `entry` (node, 0) or
    /// (first packet, packet count).
    fn closest_from(&self, entry: (u32, u32), d: f32, p: V3, best: &mut Nearest) {
        const CAP: usize = 64;
        let pa = [p.x, p.y, p.z];
        let p4 = pa.map(F4::splat);
        let mut stack: [(f32, u32, u32); CAP] = [(0.0, 0, 0); CAP];
        stack[0] = (d, entry.0, entry.1);
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let (d, index, count) = stack[sp];
            if d >= best.d2 {
                continue;
            }
            if count > 0 {
                let start = index as usize;
                let end = start + count as usize;
                for (k, (packet, &first)) in self.packets.packets[start..end]
                    .iter()
                    .zip(&self.packets.first_tri[start..end])
                    .enumerate()
                {
                    let ds = packet.distances2(&p4);
                    let nearest = ds.min_lane();
                    if nearest < best.d2 {
                        let lane = ds.0.iter().position(|&d| d == nearest).unwrap_or(0) as u32;
                        *best = Nearest {
                            d2: nearest,
                            tri: first + lane,
                            slot: 4 * (start + k) as u32 + lane,
                        };
                    }
                }
                continue;
            }
            let n = &self.wide[index as usize];
            let ds = n.distances2(&p4).0;
            // Push farthest first so the nearest child is searched next.
            let mut order = [0usize, 1, 2, 3];
            for i in 1..4 {
                let mut j = i;
                while j > 0 && ds[order[j - 1]] < ds[order[j]] {
                    order.swap(j - 1, j);
                    j -= 1;
                }
            }
            for &lane in &order {
                if ds[lane] < best.d2 {
                    if sp == CAP {
                        // Pathologically deep tree: search this child recursively.
                        self.closest_from(n.entry(lane), ds[lane], p, best);
                    } else {
                        let (index, count) = n.entry(lane);
                        stack[sp] = (ds[lane], index, count);
                        sp += 1;
                    }
                }
            }
        }
    }

    /// Whether any triangle lies closer than `radius` to `p` (unsigned): a depth-first search
    /// that prunes every node and packet at least `radius` away and stops at the first triangle
    /// inside it. Far cheaper than [`MeshSdf::search`] when nothing is that near.
    fn any_within(&self, p: V3, radius: f32) -> bool {
        let r2 = radius * radius;
        let pa = [p.x, p.y, p.z];
        let p4 = pa.map(F4::splat);
        self.groups.iter().any(|g| {
            distance2_to_box(&pa, &g.min, &g.max) < r2 && self.any_from(g.wide_root, &p4, r2)
        })
    }

    /// [`MeshSdf::any_within`] below the 4-wide tree's `entry` (node, 0) or (first packet,
    /// packet count), for the squared radius `r2`.
    fn any_from(&self, entry: (u32, u32), p4: &[F4; 3], r2: f32) -> bool {
        const CAP: usize = 64;
        let mut stack = [(0u32, 0u32); CAP];
        stack[0] = entry;
        let mut sp = 1usize;
        while sp > 0 {
            sp -= 1;
            let (index, count) = stack[sp];
            if count > 0 {
                let start = index as usize;
                let packets = &self.packets.packets[start..start + count as usize];
                if packets.iter().any(|q| q.distances2(p4).min_lane() < r2) {
                    return true;
                }
                continue;
            }
            let n = &self.wide[index as usize];
            let ds = n.distances2(p4).0;
            for (lane, &d) in ds.iter().enumerate() {
                if d >= r2 {
                    continue;
                }
                if sp == CAP {
                    // Pathologically deep tree: search this child recursively.
                    if self.any_from(n.entry(lane), p4, r2) {
                        return true;
                    }
                } else {
                    stack[sp] = n.entry(lane);
                    sp += 1;
                }
            }
        }
        false
    }

    /// Hierarchical generalized winding number of the subtree at `root`.
    fn winding(&self, root: u32, p: V3) -> f32 {
        let mut stack: Vec<u32> = Vec::with_capacity(64);
        stack.push(root);
        let mut omega = 0.0f32;
        while let Some(node) = stack.pop() {
            let dip = &self.dipoles[node as usize];
            let r = dip.center - p;
            let dist = r.norm();
            if dist > WINDING_BETA * dip.radius {
                omega += dip.area_normal.dot(&r) / (dist * dist * dist);
                continue;
            }
            let n = &self.nodes[node as usize];
            if n.count > 0 {
                let start = n.index as usize;
                for t in &self.tris[start..start + n.count as usize] {
                    omega += solid_angle(p, t[0], t[1], t[2]);
                }
            } else {
                stack.push(n.index);
                stack.push(n.index + 1);
            }
        }
        omega / (4.0 * std::f32::consts::PI)
    }

    /// Turns a search hit into a full query result.
    pub(crate) fn finish(&self, p: V3, hit: &Hit) -> SdfQuery {
        let Some(t) = self.tris.get(hit.tri as usize) else {
            // Only a non-finite query point finds no triangle.
            return SdfQuery {
                distance: f32::NAN,
                closest_point: Point3::from(p),
                gradient: V3::y(),
            };
        };
        let (q, feature) = closest_on_triangle(p, t[0], t[1], t[2]);
        let diff = p - q;
        let len = diff.norm();
        let sign = if hit.inside { -1.0 } else { 1.0 };
        let gradient = if len > self.grad_epsilon {
            diff * (sign / len)
        } else {
            let n = self.pseudo_normal(hit.tri, feature);
            let n = if n.norm_squared() > 0.0 {
                n
            } else {
                self.normals[hit.tri as usize].0[0]
            };
            n.try_normalize(0.0).unwrap_or_else(V3::y)
        };
        SdfQuery {
            distance: sign * len,
            closest_point: Point3::from(q),
            gradient,
        }
    }
}

impl SignedDistance for MeshSdf {
    #[inline]
    fn distance(&self, p: &Point3<f32>) -> f32 {
        self.signed_distance(p)
    }

    fn gradient(&self, p: &Point3<f32>) -> Vector3<f32> {
        self.query(p).gradient
    }

    fn local_bounds(&self) -> (Point3<f32>, Point3<f32>) {
        (self.min, self.max)
    }

    fn surface_within(&self, p: &Point3<f32>, radius: f32) -> Option<bool> {
        Some(self.any_within(p.coords, radius))
    }

    /// Closed solids signed by pseudo-normals give a true signed distance (the union's is
    /// their minimum); an open soup's winding-number sign may flip away from its surface.
    fn is_lipschitz(&self) -> bool {
        self.groups.iter().all(|g| g.rule == SignRule::PseudoNormal)
    }

    fn distance_and_gradient(&self, p: &Point3<f32>) -> (f32, Vector3<f32>) {
        let q = self.query(p);
        (q.distance, q.gradient)
    }
}

fn validate(part: &PartInput) -> Result<(), SdfError> {
    for (index, p) in part.positions.iter().enumerate() {
        if !p.iter().all(|v| v.is_finite()) {
            return Err(SdfError::NonFiniteVertex {
                mesh: part.name.clone(),
                index,
                position: *p,
            });
        }
    }
    let n = part.positions.len();
    for (triangle, t) in part.triangles.iter().enumerate() {
        if let Some(&index) = t.iter().find(|&&i| i as usize >= n) {
            return Err(SdfError::IndexOutOfRange {
                mesh: part.name.clone(),
                triangle,
                index,
                vertex_count: n,
            });
        }
    }
    Ok(())
}

fn face_normal(t: &[V3; 3]) -> V3 {
    (t[1] - t[0])
        .cross(&(t[2] - t[0]))
        .try_normalize(0.0)
        .unwrap_or_else(V3::zeros)
}

fn tri_box(t: &[V3; 3]) -> ([f32; 3], [f32; 3]) {
    let min = t[0].inf(&t[1]).inf(&t[2]);
    let max = t[0].sup(&t[1]).sup(&t[2]);
    ([min.x, min.y, min.z], [max.x, max.y, max.z])
}

fn find(parent: &mut [usize], mut x: usize) -> usize {
    while parent[x] != x {
        parent[x] = parent[parent[x]];
        x = parent[x];
    }
    x
}

/// Welds a part's vertices by position, splits it into edge-connected components and sorts
/// them into closed solids and open soup.
fn split_part(part: &PartInput, solids: &mut Vec<SolidInput>, soup: &mut Vec<[V3; 3]>) {
    let key = |p: &[f32; 3]| p.map(|v| if v == 0.0 { 0u32 } else { v.to_bits() });
    let mut weld: HashMap<[u32; 3], u32> = HashMap::with_capacity(part.positions.len());
    let mut welded_pos: Vec<V3> = Vec::with_capacity(part.positions.len());
    let remap: Vec<u32> = part
        .positions
        .iter()
        .map(|p| {
            *weld.entry(key(p)).or_insert_with(|| {
                welded_pos.push(V3::from(*p));
                welded_pos.len() as u32 - 1
            })
        })
        .collect();
    let tris: Vec<[u32; 3]> = part
        .triangles
        .iter()
        .map(|t| t.map(|i| remap[i as usize]))
        .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
        .collect();
    if tris.is_empty() {
        return;
    }
    // Components over shared undirected edges.
    let mut parent: Vec<usize> = (0..tris.len()).collect();
    let mut first_with_edge: HashMap<(u32, u32), usize> = HashMap::with_capacity(tris.len() * 2);
    for (ti, t) in tris.iter().enumerate() {
        for k in 0..3 {
            let (a, b) = (t[k], t[(k + 1) % 3]);
            let e = (a.min(b), a.max(b));
            match first_with_edge.get(&e) {
                Some(&other) => {
                    let (ra, rb) = (find(&mut parent, ti), find(&mut parent, other));
                    if ra != rb {
                        parent[ra.max(rb)] = ra.min(rb);
                    }
                }
                None => {
                    first_with_edge.insert(e, ti);
                }
            }
        }
    }
    let mut components: Vec<Vec<usize>> = Vec::new();
    let mut slot_of_root: HashMap<usize, usize> = HashMap::new();
    for ti in 0..tris.len() {
        let r = find(&mut parent, ti);
        let slot = *slot_of_root.entry(r).or_insert_with(|| {
            components.push(Vec::new());
            components.len() - 1
        });
        components[slot].push(ti);
    }
    let corners = |t: &[u32; 3]| t.map(|i| welded_pos[i as usize]);
    for comp in components {
        let mut directed: HashMap<(u32, u32), u32> = HashMap::with_capacity(comp.len() * 3);
        for &ti in &comp {
            let t = tris[ti];
            for k in 0..3 {
                *directed.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
            }
        }
        let closed = directed
            .iter()
            .all(|(&(a, b), &c)| c == 1 && directed.get(&(b, a)) == Some(&1));
        if !closed {
            soup.extend(comp.iter().map(|&ti| corners(&tris[ti])));
            continue;
        }
        // Angle-weighted pseudo-normals.
        let mut vertex_n: HashMap<u32, V3> = HashMap::new();
        let mut edge_n: HashMap<(u32, u32), V3> = HashMap::new();
        let face_ns: Vec<V3> = comp
            .iter()
            .map(|&ti| face_normal(&corners(&tris[ti])))
            .collect();
        for (&ti, n) in comp.iter().zip(&face_ns) {
            let t = tris[ti];
            let c = corners(&t);
            for k in 0..3 {
                let e0 = c[(k + 1) % 3] - c[k];
                let e1 = c[(k + 2) % 3] - c[k];
                let angle = e0.angle(&e1);
                let angle = if angle.is_finite() { angle } else { 0.0 };
                *vertex_n.entry(t[k]).or_insert_with(V3::zeros) += n * angle;
                let (a, b) = (t[k], t[(k + 1) % 3]);
                *edge_n.entry((a.min(b), a.max(b))).or_insert_with(V3::zeros) += n;
            }
        }
        let mut solid = SolidInput {
            tris: Vec::with_capacity(comp.len()),
            normals: Vec::with_capacity(comp.len()),
            rule: SignRule::PseudoNormal,
        };
        for (&ti, n) in comp.iter().zip(&face_ns) {
            let t = tris[ti];
            let e = |k: usize| {
                let (a, b) = (t[k], t[(k + 1) % 3]);
                edge_n[&(a.min(b), a.max(b))]
            };
            solid.tris.push(corners(&t));
            solid.normals.push(PseudoNormals([
                *n,
                e(0),
                e(1),
                e(2),
                vertex_n[&t[0]],
                vertex_n[&t[1]],
                vertex_n[&t[2]],
            ]));
        }
        solids.push(solid);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::{Rng, SeedableRng};

    /// Two overlapping boxes (two closed solids) and an open square (winding-number soup).
    fn several_solids() -> MeshSdf {
        let (mut positions, mut triangles) = crate::shapes::cuboid(V3::new(0.3, 0.2, 0.25));
        let (more, tris) = crate::shapes::cuboid(V3::new(0.1, 0.4, 0.1));
        let base = positions.len() as u32;
        positions.extend(more.iter().map(|p| [p[0] + 0.25, p[1] + 0.1, p[2]]));
        triangles.extend(tris.iter().map(|t| t.map(|i| i + base)));
        let base = positions.len() as u32;
        positions.extend([
            [-0.5, -0.5, 0.5],
            [0.5, -0.5, 0.5],
            [0.5, 0.5, 0.5],
            [-0.5, 0.5, 0.5],
        ]);
        triangles.extend([[base, base + 1, base + 2], [base, base + 2, base + 3]]);
        MeshSdf::new(&positions, &triangles).unwrap()
    }

    #[test]
    fn seed_grid_holds_the_nearest_triangle_of_each_cell_centre() {
        let (positions, triangles) = crate::shapes::bumpy_sphere(0.5, 0.15, 40, 21);
        let sdf = MeshSdf::new(&positions, &triangles).unwrap();
        let seeds = &sdf.seeds;
        assert_eq!(seeds.slots.len(), seeds.dims.iter().product::<usize>());
        assert!(seeds.slots.len() >= 64, "{:?}", seeds.dims);
        for (index, &slot) in seeds.slots.iter().enumerate() {
            let (i, j, k) = (
                index % seeds.dims[0],
                index / seeds.dims[0] % seeds.dims[1],
                index / (seeds.dims[0] * seeds.dims[1]),
            );
            let centre = V3::from(seeds.origin)
                + V3::new(i as f32 + 0.5, j as f32 + 0.5, k as f32 + 0.5) * seeds.cell;
            assert_eq!(seeds.slot(&centre), slot);
            let (packet, lane) = ((slot / 4) as usize, slot % 4);
            let t = &sdf.tris[(sdf.packets.first_tri[packet] + lane) as usize];
            let seeded = (closest_on_triangle(centre, t[0], t[1], t[2]).0 - centre).norm_squared();
            let exact = sdf.search_hinted(&Point3::from(centre), None).distance2;
            assert!(
                (seeded - exact).abs() <= 1e-6 * exact + 1e-9,
                "{seeded} vs {exact}"
            );
        }
        // Outside the grid and for NaN there is no seed.
        assert_eq!(seeds.slot(&V3::new(10.0, 0.0, 0.0)), NO_TRIANGLE);
        assert_eq!(seeds.slot(&V3::new(f32::NAN, 0.0, 0.0)), NO_TRIANGLE);
        // Small meshes have none.
        let (p, t) = crate::shapes::cuboid(V3::new(0.5, 0.5, 0.5));
        assert!(MeshSdf::new(&p, &t).unwrap().seeds.slots.is_empty());
    }

    #[test]
    fn hinted_searches_agree_with_unhinted_ones() {
        let (positions, triangles) = crate::shapes::bumpy_sphere(0.5, 0.15, 40, 21);
        let bumpy = MeshSdf::new(&positions, &triangles).unwrap();
        let several = several_solids();
        assert_eq!(several.sign_rules().len(), 3);
        let mut rng = rand_chacha::ChaCha8Rng::seed_from_u64(3);
        for sdf in [&bumpy, &several] {
            let slots = 4 * sdf.packets.packets.len() as u32;
            for _ in 0..2000 {
                let p = Point3::new(
                    rng.random_range(-0.8f32..0.8),
                    rng.random_range(-0.8f32..0.8),
                    rng.random_range(-0.8f32..0.8),
                );
                let plain = sdf.search_hinted(&p, None);
                // Any slot may serve as a hint, even padding lanes and invalid ones.
                let hint = rng.random_range(0..slots + 8);
                let hinted = sdf.search_hinted(&p, Some(hint));
                // Equal up to rounding: bounds and triangle distances round differently where
                // they coincide (axis-aligned faces), which may prune a tied triangle.
                assert!(
                    (plain.distance2 - hinted.distance2).abs() <= 1e-6 * plain.distance2,
                    "at {p:?} with hint {hint}: {} vs {}",
                    plain.distance2,
                    hinted.distance2
                );
                assert_eq!(plain.inside, hinted.inside, "at {p:?} with hint {hint}");
                // The hit's slot names its triangle, at the reported distance.
                let (packet, lane) = ((plain.slot / 4) as usize, plain.slot % 4);
                assert_eq!(sdf.packets.first_tri[packet] + lane, plain.tri);
                let t = &sdf.tris[plain.tri as usize];
                let q = closest_on_triangle(p.coords, t[0], t[1], t[2]).0;
                assert!(((q - p.coords).norm_squared() - plain.distance2).abs() <= 1e-6);
            }
        }
    }
}
