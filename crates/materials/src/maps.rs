//! The texture maps of a library material: its pattern sampled over one tile at
//! [`TEXTURE_SIZE`]² texels, as PNG files in glTF's channel layout (generated here; made once
//! per process and kept between processes by [`maps`](crate::maps)).

use std::sync::OnceLock;

use image::ImageEncoder;

use crate::color::linear_to_srgb_byte;
use crate::library::LibraryMaterial;
use crate::pattern::Texel;

/// Width and height of every map, texels.
pub const TEXTURE_SIZE: u32 = 256;

/// Which map of a material.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MapKind {
    /// sRGB albedo multiplier (the surface's colour multiplies it).
    BaseColor,
    /// Tangent-space normal, +X along u, +Y toward the image's top (the OpenGL convention
    /// glTF uses), linear.
    Normal,
    /// glTF metallic-roughness: G roughness, B metalness (R unused, 255), linear.
    MetallicRoughness,
}

impl MapKind {
    /// Every map, in a stable order.
    pub const ALL: [MapKind; 3] = [
        MapKind::BaseColor,
        MapKind::Normal,
        MapKind::MetallicRoughness,
    ];

    /// The suffix of its file name: `color`, `normal` or `mr`.
    pub fn suffix(&self) -> &'static str {
        match self {
            MapKind::BaseColor => "color",
            MapKind::Normal => "normal",
            MapKind::MetallicRoughness => "mr",
        }
    }
}

/// The maps of one material, with the averages that let a surface keep its own colour and
/// roughness on average when the maps multiply them.
#[derive(Debug, Clone, PartialEq)]
pub struct Maps {
    /// RGB8 texels of the base-colour map, rows top to bottom.
    pub base_color: Vec<u8>,
    /// RGB8 texels of the normal map.
    pub normal: Vec<u8>,
    /// RGB8 texels of the metallic-roughness map.
    pub metallic_roughness: Vec<u8>,
    /// Mean linear value of the base-colour map per channel.
    pub mean_albedo: [f32; 3],
    /// Mean roughness multiplier of the metallic-roughness map.
    pub mean_roughness: f32,
    png: [OnceLock<Vec<u8>>; 3],
}

impl Maps {
    /// Maps from their texels and averages (their PNG files encoded when first asked for).
    pub(crate) fn from_parts(
        base_color: Vec<u8>,
        normal: Vec<u8>,
        metallic_roughness: Vec<u8>,
        mean_albedo: [f32; 3],
        mean_roughness: f32,
    ) -> Self {
        Maps {
            base_color,
            normal,
            metallic_roughness,
            mean_albedo,
            mean_roughness,
            png: Default::default(),
        }
    }

    /// The texels of one map.
    pub fn texels(&self, kind: MapKind) -> &[u8] {
        match kind {
            MapKind::BaseColor => &self.base_color,
            MapKind::Normal => &self.normal,
            MapKind::MetallicRoughness => &self.metallic_roughness,
        }
    }

    /// One map as a PNG file (encoded on first use, then kept).
    pub fn png(&self, kind: MapKind) -> &[u8] {
        let slot = MapKind::ALL.iter().position(|k| *k == kind).unwrap_or(0);
        self.png[slot].get_or_init(|| encode_png(self.texels(kind)))
    }

    /// The factor that turns a surface's linear colour into the base-colour factor to pair
    /// with this map, so that the textured surface averages that colour (clamped to 1).
    pub fn color_factor(&self, linear: [f32; 4]) -> [f32; 4] {
        let f = |c: f32, mean: f32| (c / mean.max(1e-3)).clamp(0.0, 1.0);
        [
            f(linear[0], self.mean_albedo[0]),
            f(linear[1], self.mean_albedo[1]),
            f(linear[2], self.mean_albedo[2]),
            linear[3].clamp(0.0, 1.0),
        ]
    }

    /// The roughness factor to pair with this map for a surface of `roughness`.
    pub fn roughness_factor(&self, roughness: f32) -> f32 {
        (roughness / self.mean_roughness.max(1e-3)).clamp(0.0, 1.0)
    }
}

/// A stable seed from a material's id (FNV-1a), so that two materials of one pattern differ.
fn seed_of(id: &str) -> u32 {
    id.bytes().fold(0x811C_9DC5u32, |h, b| {
        (h ^ b as u32).wrapping_mul(0x0100_0193)
    })
}

/// The maps of `material`, generated from its pattern.
pub(crate) fn generate(material: &LibraryMaterial) -> Maps {
    let n = TEXTURE_SIZE as usize;
    let seed = seed_of(material.id);
    let texels: Vec<Texel> = (0..n * n)
        .map(|i| {
            let (x, y) = (i % n, i / n);
            let u = (x as f32 + 0.5) / n as f32;
            let v = (y as f32 + 0.5) / n as f32;
            material.pattern.texel(u, v, seed)
        })
        .collect();
    let mut base_color = Vec::with_capacity(n * n * 3);
    let mut sum = [0.0f64; 3];
    let mut roughness_sum = 0.0f64;
    let mut metallic_roughness = Vec::with_capacity(n * n * 3);
    let metal = if material.metallic > 0.0 { 255 } else { 0 };
    for t in &texels {
        for (k, c) in t.albedo.iter().enumerate() {
            let byte = linear_to_srgb_byte(*c);
            base_color.push(byte);
            sum[k] += crate::color::srgb_byte_to_linear(byte) as f64;
        }
        let r = (t.roughness.clamp(0.0, 1.0) * 255.0).round() as u8;
        roughness_sum += r as f64 / 255.0;
        metallic_roughness.extend_from_slice(&[255, r, metal]);
    }
    let count = (n * n) as f64;
    Maps::from_parts(
        base_color,
        normal_map(&texels, n, material.bump),
        metallic_roughness,
        sum.map(|s| (s / count) as f32),
        (roughness_sum / count) as f32,
    )
}

/// The tangent-space normals of the height field (wrapping at the edges, so the map tiles):
/// `(−bump·∂h/∂x, +bump·∂h/∂row, 1)` normalised, rows running down the image.
fn normal_map(texels: &[Texel], n: usize, bump: f32) -> Vec<u8> {
    let h = |x: usize, y: usize| texels[(y % n) * n + (x % n)].height;
    let mut out = Vec::with_capacity(n * n * 3);
    for y in 0..n {
        for x in 0..n {
            let dx = (h(x + 1, y) - h(x + n - 1, y)) * 0.5;
            let dy = (h(x, y + 1) - h(x, y + n - 1)) * 0.5;
            let v = [-bump * dx, bump * dy, 1.0];
            let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
            for c in v {
                out.push(((c / len * 0.5 + 0.5) * 255.0).round().clamp(0.0, 255.0) as u8);
            }
        }
    }
    out
}

fn encode_png(rgb: &[u8]) -> Vec<u8> {
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out)
        .write_image(
            rgb,
            TEXTURE_SIZE,
            TEXTURE_SIZE,
            image::ExtendedColorType::Rgb8,
        )
        .expect("encoding an RGB8 image of the declared size into memory cannot fail");
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::library::by_id;

    #[test]
    fn maps_are_cached_deterministic_tileable_and_well_formed() {
        let oak = by_id("oak").unwrap();
        let first = &generate(oak);
        assert_eq!(first.base_color, generate(oak).base_color, "deterministic");
        let png = first.png(MapKind::BaseColor);
        assert_eq!(&png[1..4], b"PNG");
        let decoded = image::load_from_memory(png).unwrap().to_rgb8();
        assert_eq!(decoded.as_raw(), &first.base_color);
        // Seamless: the jump across the wrap edge is no larger than typical neighbour steps.
        let n = TEXTURE_SIZE as usize;
        let at = |x: usize, y: usize| first.base_color[(y * n + x) * 3] as i32;
        let step = |a: i32, b: i32| (a - b).abs();
        let seam: i32 = (0..n).map(|y| step(at(n - 1, y), at(0, y))).sum();
        let inner: i32 = (0..n).map(|y| step(at(n / 2, y), at(n / 2 + 1, y))).sum();
        assert!(seam <= inner * 2 + n as i32, "seam {seam} vs inner {inner}");
        let seam_v: i32 = (0..n).map(|x| step(at(x, n - 1), at(x, 0))).sum();
        let inner_v: i32 = (0..n).map(|x| step(at(x, n / 2), at(x, n / 2 + 1))).sum();
        assert!(
            seam_v <= inner_v * 2 + n as i32,
            "seam {seam_v} vs inner {inner_v}"
        );
        assert!(first.mean_albedo.iter().all(|m| (0.3..=1.0).contains(m)));
        // glTF layout: metals have B = 255, dielectrics B = 0; roughness in G.
        let steel = &generate(by_id("brushed_steel").unwrap());
        assert!(steel.metallic_roughness.chunks(3).all(|c| c[2] == 255));
        assert!(first
            .metallic_roughness
            .chunks(3)
            .all(|c| c[0] == 255 && c[2] == 0));
        // Normals point out of the surface.
        assert!(first.normal.chunks(3).all(|c| c[2] > 128));
    }
}
