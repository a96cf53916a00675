//! The asset builder: parts, materials and support surfaces normalised into an asset.

use scenethesis_scene_graph::{
    Asset, AssetInfo, AssetRef, Material, Mesh, MeshPart, Placement, SupportSurface, SurfaceKind,
};

use crate::{cuboid, rect_surface};

/// Collects parts, materials and support surfaces, then normalises them into an [`Asset`]
/// whose origin is the centre of its footprint at its lowest point.
#[derive(Debug, Default, Clone)]
pub struct AssetBuilder {
    mesh: Mesh,
    surfaces: Vec<SupportSurface>,
}

impl AssetBuilder {
    /// An empty builder.
    pub fn new() -> Self {
        Self::default()
    }

    /// Flattens the underside into a contact patch: every vertex lower than `depth` above the
    /// parts' lowest point is raised onto that plane. A tessellated sphere or a cylinder lying
    /// on its side otherwise rests on one vertex or edge and rolls off it in simulation (a real
    /// ball or fruit flattens into its contact patch the same way). Convex parts stay convex
    /// while `depth` is below their second ring of vertices.
    pub fn flatten_base(&mut self, depth: f32) {
        let lowest = self
            .mesh
            .parts
            .iter()
            .flat_map(|p| p.positions.iter().map(|v| v[1]))
            .fold(f32::INFINITY, f32::min);
        if !lowest.is_finite() {
            return;
        }
        let plane = lowest + depth;
        for part in &mut self.mesh.parts {
            for v in &mut part.positions {
                v[1] = v[1].max(plane);
            }
        }
    }

    /// Adds `material` (or finds an identical one) and returns its index.
    pub fn material(&mut self, material: Material) -> usize {
        if let Some(i) = self.mesh.materials.iter().position(|m| *m == material) {
            return i;
        }
        self.mesh.materials.push(material);
        self.mesh.materials.len() - 1
    }

    /// Adds a part (its material index must come from [`AssetBuilder::material`]).
    pub fn part(&mut self, part: MeshPart) -> &mut Self {
        self.mesh.parts.push(part);
        self
    }

    /// Adds an axis-aligned box part.
    pub fn cuboid(&mut self, name: &str, material: usize, min: [f32; 3], max: [f32; 3]) {
        self.mesh.parts.push(cuboid(name, material, min, max));
    }

    /// Adds a support surface (in the same frame as the parts).
    pub fn surface(&mut self, surface: SupportSurface) -> &mut Self {
        self.surfaces.push(surface);
        self
    }

    /// Adds an upward-facing support surface open above (a table top, a seat, a counter) over
    /// the axis-aligned rectangle `min`..`max` in (x, z), shrunk by `margin` as in
    /// [`rect_surface`].
    pub fn top_surface(
        &mut self,
        name: &str,
        min: [f32; 2],
        max: [f32; 2],
        height: f32,
        margin: f32,
    ) -> &mut Self {
        self.surface(rect_surface(
            name,
            SurfaceKind::Top,
            min,
            max,
            height,
            None,
            margin,
        ))
    }

    /// The support surfaces added so far, to adjust them after later parts.
    pub fn surfaces_mut(&mut self) -> &mut Vec<SupportSurface> {
        &mut self.surfaces
    }

    /// Turns everything added so far by half a turn about the vertical axis through `pivot`
    /// = (x, z), e.g. to make compartments built facing +Z open toward −Z.
    pub fn turn_around(&mut self, pivot: [f32; 2]) {
        for part in &mut self.mesh.parts {
            for p in &mut part.positions {
                p[0] = 2.0 * pivot[0] - p[0];
                p[2] = 2.0 * pivot[1] - p[2];
            }
        }
        for s in &mut self.surfaces {
            for p in &mut s.polygon {
                p[0] = 2.0 * pivot[0] - p[0];
                p[1] = 2.0 * pivot[1] - p[1];
            }
        }
    }

    /// The parts added so far.
    pub fn parts(&self) -> &[MeshPart] {
        &self.mesh.parts
    }

    /// Moves everything so that the footprint centre at the lowest point is the origin, and
    /// returns the asset with its size from the mesh bounds. `source`, `category` and
    /// `synonyms` are left for the registry that calls the generator to fill in
    /// (`scenethesis_procedural::catalog::generate`).
    ///
    /// # Panics
    /// When no part was added.
    pub fn finish(mut self, placement: Placement, scale_range: [f32; 2]) -> Asset {
        let bounds = self
            .mesh
            .bounds()
            .expect("an asset needs at least one part");
        let (min, max) = (bounds.min.cast::<f32>(), bounds.max.cast::<f32>());
        let shift = [-0.5 * (min.x + max.x), -min.y, -0.5 * (min.z + max.z)];
        for part in &mut self.mesh.parts {
            for p in &mut part.positions {
                for k in 0..3 {
                    p[k] += shift[k];
                }
            }
        }
        for s in &mut self.surfaces {
            for p in &mut s.polygon {
                p[0] += shift[0];
                p[1] += shift[2];
            }
            s.height += shift[1];
        }
        let size = max - min;
        Asset {
            info: AssetInfo {
                source: AssetRef::Procedural {
                    generator: String::new(),
                    seed: 0,
                },
                category: String::new(),
                synonyms: Vec::new(),
                size: [size.x, size.y, size.z],
                placement,
                front: [0.0, 0.0, 1.0],
                support_surfaces: self.surfaces,
                scale_range,
                joints: Vec::new(),
                opening_bounds: None,
            },
            mesh: self.mesh,
        }
    }
}
