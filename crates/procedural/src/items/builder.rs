//! The asset builder of the item and outdoor generators: [`AssetBuilder`] with shorthands for
//! the materials and part families small items are made of.

use rand_chacha::ChaCha8Rng;
use scenethesis_scene_graph::{Joint, Material, MeshPart};

use crate::materials::{fixed_material, pick_material, Palette};
use scenethesis_primitives::{ellipsoid, frustum, polyline, ring_slab, tube, AssetBuilder};
use scenethesis_scene_graph::{Asset, Placement, SupportSurface, SurfaceKind};

/// Collects parts, materials and support surfaces in an [`AssetBuilder`], then normalises them
/// into an [`Asset`].
#[derive(Default)]
pub(crate) struct Builder {
    inner: AssetBuilder,
}

impl Builder {
    /// An empty builder.
    pub(crate) fn new() -> Self {
        Self::default()
    }

    /// Adds a dielectric material and returns its index.
    pub(crate) fn material(&mut self, name: &str, rgb: [f32; 3], roughness: f32) -> usize {
        self.inner.material(Material::new(name, rgb, roughness))
    }

    /// Adds a metallic material and returns its index.
    pub(crate) fn metal(&mut self, name: &str, rgb: [f32; 3], roughness: f32) -> usize {
        let mut m = Material::new(name, rgb, roughness);
        m.metallic = 1.0;
        self.inner.material(m)
    }

    /// Adds a translucent material (alpha < 1) and returns its index.
    pub(crate) fn glass(&mut self, name: &str, rgb: [f32; 3], alpha: f32) -> usize {
        let mut m = Material::new(name, rgb, 0.05);
        m.base_color[3] = alpha;
        self.inner.material(m)
    }

    /// Draws a material from `palette` and returns its index.
    pub(crate) fn palette(&mut self, palette: Palette, rng: &mut ChaCha8Rng) -> usize {
        self.inner.material(pick_material(palette, rng))
    }

    /// Adds a material given in sRGB bytes (see [`fixed_material`]) and returns its index.
    pub(crate) fn fixed(
        &mut self,
        name: &str,
        srgb: [u8; 3],
        roughness: f32,
        metallic: f32,
    ) -> usize {
        self.inner
            .material(fixed_material(name, srgb, roughness, metallic))
    }

    /// Flattens the underside into a contact patch `depth` high (see
    /// [`AssetBuilder::flatten_base`]).
    pub(crate) fn flatten_base(&mut self, depth: f32) {
        self.inner.flatten_base(depth);
    }

    /// Adds a joint (see [`AssetBuilder::joint`]).
    pub(crate) fn joint(&mut self, joint: Joint) {
        self.inner.joint(joint);
    }

    /// Opens the link of the joint named `joint`, so that the parts added next move with it,
    /// or closes it with `None` (see [`AssetBuilder::link`]).
    pub(crate) fn link(&mut self, joint: Option<&str>) {
        self.inner.link(joint);
    }

    /// Adds a finished part.
    pub(crate) fn add(&mut self, part: MeshPart) {
        self.inner.part(part);
    }

    /// Adds an axis-aligned box.
    pub(crate) fn cuboid(&mut self, name: &str, material: usize, min: [f32; 3], max: [f32; 3]) {
        self.inner.cuboid(name, material, min, max);
    }

    /// Adds a vertical frustum (a cylinder when `r0 == r1`).
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn frustum(
        &mut self,
        name: &str,
        material: usize,
        center: [f32; 2],
        r0: f32,
        r1: f32,
        y0: f32,
        y1: f32,
        segments: u32,
    ) {
        self.add(frustum(name, material, center, r0, r1, y0, y1, segments));
    }

    /// Adds an axis-aligned ellipsoid.
    pub(crate) fn ellipsoid(
        &mut self,
        name: &str,
        material: usize,
        center: [f32; 3],
        radii: [f32; 3],
    ) {
        self.add(ellipsoid(name, material, center, radii, 10, 16));
    }

    /// Adds tubes joining consecutive points.
    pub(crate) fn polyline(
        &mut self,
        name: &str,
        material: usize,
        points: &[[f32; 3]],
        radius: f32,
    ) {
        for part in polyline(name, material, points, radius) {
            self.add(part);
        }
    }

    /// Adds a tube (frustum) between two points.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn tube(
        &mut self,
        name: &str,
        material: usize,
        a: [f32; 3],
        b: [f32; 3],
        r0: f32,
        r1: f32,
        segments: u32,
    ) {
        self.add(tube(name, material, a, b, r0, r1, segments));
    }

    /// Adds a ring of `segments` convex wall slabs around a vertical axis, inner and outer radii
    /// `(r_in, r_out)` at `y0` and at `y1`: the wall of a mug, bowl, bucket or barrel.
    #[allow(clippy::too_many_arguments)]
    pub(crate) fn ring(
        &mut self,
        name: &str,
        material: usize,
        center: [f32; 2],
        bottom: (f32, f32, f32),
        top: (f32, f32, f32),
        segments: u32,
    ) {
        let n = segments.max(3);
        for k in 0..n {
            let a0 = std::f32::consts::TAU * k as f32 / n as f32;
            let a1 = std::f32::consts::TAU * (k + 1) as f32 / n as f32;
            self.add(ring_slab(
                &format!("{name}_{k}"),
                material,
                center,
                a0,
                a1,
                bottom,
                top,
            ));
        }
    }

    /// Adds an open-top rectangular tub: a floor of thickness `floor` and four walls of thickness
    /// `wall` around the outer box `min`..`max`. Returns the inner floor's height.
    pub(crate) fn open_box(
        &mut self,
        name: &str,
        material: usize,
        min: [f32; 3],
        max: [f32; 3],
        wall: f32,
        floor: f32,
    ) -> f32 {
        let inner_y = min[1] + floor;
        self.cuboid(
            &format!("{name}_floor"),
            material,
            min,
            [max[0], inner_y, max[2]],
        );
        let y0 = inner_y - floor * 0.5;
        self.cuboid(
            &format!("{name}_wall_back"),
            material,
            [min[0], y0, min[2]],
            [max[0], max[1], min[2] + wall],
        );
        self.cuboid(
            &format!("{name}_wall_front"),
            material,
            [min[0], y0, max[2] - wall],
            [max[0], max[1], max[2]],
        );
        self.cuboid(
            &format!("{name}_wall_left"),
            material,
            [min[0], y0, min[2]],
            [min[0] + wall, max[1], max[2]],
        );
        self.cuboid(
            &format!("{name}_wall_right"),
            material,
            [max[0] - wall, y0, min[2]],
            [max[0], max[1], max[2]],
        );
        inner_y
    }

    /// Adds a support surface.
    pub(crate) fn surface(
        &mut self,
        name: &str,
        kind: SurfaceKind,
        polygon: Vec<[f32; 2]>,
        height: f32,
        clearance: Option<f32>,
    ) {
        self.inner.surface(SupportSurface {
            name: name.into(),
            kind,
            polygon,
            height,
            clearance,
        });
    }

    /// Adds the `interior` support surface of a container open on top: the inside bottom at
    /// `height`, free above.
    pub(crate) fn interior(&mut self, polygon: Vec<[f32; 2]>, height: f32) {
        self.surface("interior", SurfaceKind::Interior, polygon, height, None);
    }

    /// Adds an upward-facing support surface open above (a top, a lid, a plate's flat).
    pub(crate) fn top(&mut self, name: &str, polygon: Vec<[f32; 2]>, height: f32) {
        self.surface(name, SurfaceKind::Top, polygon, height, None);
    }

    /// Moves everything so that the origin is the footprint centre at the lowest point, and
    /// returns the asset with its size measured from the mesh.
    pub(crate) fn finish(self, placement: Placement, scale_range: [f32; 2]) -> Asset {
        self.inner.finish(placement, scale_range)
    }
}
