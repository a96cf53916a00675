//! The material maps on the GPU: three texture arrays (base colour, normal,
//! metallic-roughness) with one layer per library material, each layer uploaded with its mip
//! chain the first time a prepared scene wears that material and kept for the renderer's
//! life, so that every part, scene and view of a material shares one copy. Imported images
//! (a material's own [`TextureImage`]) get layers after the library's, one per distinct image
//! (by digest), resampled to the layers' size with a flat normal and full roughness and
//! metalness maps (their material's factors apply unchanged); the arrays grow, their layers
//! copied on the device, when a scene brings more images than they hold.

use std::collections::BTreeMap;
use std::sync::Mutex;

use scenethesis_materials::color::{linear_to_srgb_byte, srgb_byte_to_linear};
use scenethesis_materials::{library, maps, MapKind, TEXTURE_SIZE};
use scenethesis_scene_graph::TextureImage;

/// Mip levels of a [`TEXTURE_SIZE`]² map, down to 1 × 1.
const MIP_LEVELS: u32 = TEXTURE_SIZE.ilog2() + 1;

/// Layers added at a time when imported images outgrow the arrays.
const GROWTH: u32 = 8;

/// The texture arrays of a renderer and which layers hold their material's maps.
pub(super) struct MaterialTextures {
    layout: wgpu::BindGroupLayout,
    sampler: wgpu::Sampler,
    state: Mutex<State>,
}

/// The arrays, their bind group and what their layers hold.
struct State {
    arrays: [wgpu::Texture; 3],
    /// Group 2 of the scene pass: the three arrays and their sampler.
    group: wgpu::BindGroup,
    /// Layers of each array.
    layers: u32,
    /// Per library material, whether its layer holds its maps.
    uploaded: Vec<bool>,
    /// The layer of each imported image uploaded, by digest.
    images: BTreeMap<u64, u32>,
}

impl MaterialTextures {
    /// Empty arrays (one layer per library material) bound with `sampler` after `layout`.
    pub(super) fn new(
        device: &wgpu::Device,
        layout: &wgpu::BindGroupLayout,
        sampler: &wgpu::Sampler,
    ) -> Self {
        let layers = library().len() as u32;
        let (arrays, group) = arrays(device, layout, sampler, layers);
        Self {
            layout: layout.clone(),
            sampler: sampler.clone(),
            state: Mutex::new(State {
                arrays,
                group,
                layers,
                uploaded: vec![false; layers as usize],
                images: BTreeMap::new(),
            }),
        }
    }

    fn state(&self) -> std::sync::MutexGuard<'_, State> {
        self.state
            .lock()
            .unwrap_or_else(std::sync::PoisonError::into_inner)
    }

    /// Group 2 of the scene pass, as the arrays are now.
    pub(super) fn group(&self) -> wgpu::BindGroup {
        self.state().group.clone()
    }

    /// Uploads the maps of the library materials at `indices` that no earlier scene used.
    pub(super) fn ensure(&self, queue: &wgpu::Queue, indices: impl IntoIterator<Item = usize>) {
        let mut state = self.state();
        for index in indices {
            if state.uploaded.get(index).copied().unwrap_or(true) {
                continue;
            }
            let material_maps = maps(&library()[index]);
            for (array, kind) in state.arrays.iter().zip(MapKind::ALL) {
                for (level, (size, texels)) in mip_chain(material_maps.texels(kind), kind)
                    .iter()
                    .enumerate()
                {
                    write_layer(queue, array, index as u32, level as u32, *size, texels);
                }
            }
            state.uploaded[index] = true;
        }
    }

    /// Uploads the imported `images` that no earlier scene showed, each into a layer of its
    /// own (growing the arrays when they are full), and returns the layer of every image of
    /// `images` by digest. An image whose PNG cannot be decoded gets no layer (its parts are
    /// drawn in their flat colour).
    pub(super) fn ensure_images(
        &self,
        device: &wgpu::Device,
        queue: &wgpu::Queue,
        images: &[&TextureImage],
    ) -> BTreeMap<u64, u32> {
        let mut state = self.state();
        let mut decoded = Vec::new();
        for image in images {
            if state.images.contains_key(&image.digest())
                || decoded.iter().any(|(d, _)| *d == image.digest())
            {
                continue;
            }
            match layer_texels(image) {
                Ok(texels) => decoded.push((image.digest(), texels)),
                Err(e) => tracing::warn!(
                    "image {}: cannot be decoded for the preview ({e}); drawn in its flat colour",
                    image.digest_hex()
                ),
            }
        }
        let needed = library().len() as u32 + (state.images.len() + decoded.len()) as u32;
        if needed > state.layers {
            let layers = needed.max(state.layers + GROWTH);
            self.grow(device, queue, &mut state, layers);
        }
        let flat = [
            mip_chain(&flat_map([128, 128, 255]), MapKind::Normal),
            mip_chain(&flat_map([0, 255, 255]), MapKind::MetallicRoughness),
        ];
        for (digest, texels) in decoded {
            let layer = library().len() as u32 + state.images.len() as u32;
            let color = mip_chain(&texels, MapKind::BaseColor);
            for (array, chain) in state.arrays.iter().zip([&color, &flat[0], &flat[1]]) {
                for (level, (size, texels)) in chain.iter().enumerate() {
                    write_layer(queue, array, layer, level as u32, *size, texels);
                }
            }
            state.images.insert(digest, layer);
        }
        images
            .iter()
            .filter_map(|i| Some((i.digest(), *state.images.get(&i.digest())?)))
            .collect()
    }

    /// Replaces the arrays by ones of `layers` layers holding the same maps (copied on the
    /// device) and rebinds them.
    fn grow(&self, device: &wgpu::Device, queue: &wgpu::Queue, state: &mut State, layers: u32) {
        let (arrays, group) = arrays(device, &self.layout, &self.sampler, layers);
        let mut encoder = device.create_command_encoder(&Default::default());
        for (old, new) in state.arrays.iter().zip(&arrays) {
            for level in 0..MIP_LEVELS {
                let side = TEXTURE_SIZE >> level;
                let at = |texture| wgpu::TexelCopyTextureInfo {
                    texture,
                    mip_level: level,
                    origin: wgpu::Origin3d::ZERO,
                    aspect: wgpu::TextureAspect::All,
                };
                encoder.copy_texture_to_texture(
                    at(old),
                    at(new),
                    wgpu::Extent3d {
                        width: side,
                        height: side,
                        depth_or_array_layers: state.layers,
                    },
                );
            }
        }
        queue.submit([encoder.finish()]);
        state.arrays = arrays;
        state.group = group;
        state.layers = layers;
    }
}

/// Three empty arrays of `layers` layers and their bind group.
fn arrays(
    device: &wgpu::Device,
    layout: &wgpu::BindGroupLayout,
    sampler: &wgpu::Sampler,
    layers: u32,
) -> ([wgpu::Texture; 3], wgpu::BindGroup) {
    let arrays = MapKind::ALL.map(|kind| {
        device.create_texture(&wgpu::TextureDescriptor {
            label: Some(kind.suffix()),
            size: wgpu::Extent3d {
                width: TEXTURE_SIZE,
                height: TEXTURE_SIZE,
                depth_or_array_layers: layers,
            },
            mip_level_count: MIP_LEVELS,
            sample_count: 1,
            dimension: wgpu::TextureDimension::D2,
            format: format(kind),
            usage: wgpu::TextureUsages::TEXTURE_BINDING
                | wgpu::TextureUsages::COPY_DST
                | wgpu::TextureUsages::COPY_SRC,
            view_formats: &[],
        })
    });
    let views = arrays.each_ref().map(|t| {
        t.create_view(&wgpu::TextureViewDescriptor {
            dimension: Some(wgpu::TextureViewDimension::D2Array),
            ..Default::default()
        })
    });
    let group = device.create_bind_group(&wgpu::BindGroupDescriptor {
        label: Some("material textures"),
        layout,
        entries: &[
            wgpu::BindGroupEntry {
                binding: 0,
                resource: wgpu::BindingResource::TextureView(&views[0]),
            },
            wgpu::BindGroupEntry {
                binding: 1,
                resource: wgpu::BindingResource::TextureView(&views[1]),
            },
            wgpu::BindGroupEntry {
                binding: 2,
                resource: wgpu::BindingResource::TextureView(&views[2]),
            },
            wgpu::BindGroupEntry {
                binding: 3,
                resource: wgpu::BindingResource::Sampler(sampler),
            },
        ],
    });
    (arrays, group)
}

/// A [`TEXTURE_SIZE`]² RGB8 map of one texel value.
fn flat_map(texel: [u8; 3]) -> Vec<u8> {
    texel.repeat((TEXTURE_SIZE * TEXTURE_SIZE) as usize)
}

/// An imported image as a [`TEXTURE_SIZE`]² RGB8 map: enlarged by repeating pixels (a small
/// image keeps its sharp texels), reduced by a triangle filter.
fn layer_texels(image: &TextureImage) -> Result<Vec<u8>, image::ImageError> {
    let rgb = image::load_from_memory_with_format(image.png(), image::ImageFormat::Png)?.to_rgb8();
    let filter = if rgb.width() < TEXTURE_SIZE || rgb.height() < TEXTURE_SIZE {
        image::imageops::FilterType::Nearest
    } else {
        image::imageops::FilterType::Triangle
    };
    Ok(image::imageops::resize(&rgb, TEXTURE_SIZE, TEXTURE_SIZE, filter).into_raw())
}

/// The texel format of a map: sRGB for colour, linear for the data maps.
fn format(kind: MapKind) -> wgpu::TextureFormat {
    match kind {
        MapKind::BaseColor => wgpu::TextureFormat::Rgba8UnormSrgb,
        MapKind::Normal | MapKind::MetallicRoughness => wgpu::TextureFormat::Rgba8Unorm,
    }
}

/// Writes one mip `level` of one array `layer`: `size`² RGBA8 texels.
fn write_layer(
    queue: &wgpu::Queue,
    array: &wgpu::Texture,
    layer: u32,
    level: u32,
    size: u32,
    texels: &[u8],
) {
    queue.write_texture(
        wgpu::TexelCopyTextureInfo {
            texture: array,
            mip_level: level,
            origin: wgpu::Origin3d {
                x: 0,
                y: 0,
                z: layer,
            },
            aspect: wgpu::TextureAspect::All,
        },
        texels,
        wgpu::TexelCopyBufferLayout {
            offset: 0,
            bytes_per_row: Some(size * 4),
            rows_per_image: Some(size),
        },
        wgpu::Extent3d {
            width: size,
            height: size,
            depth_or_array_layers: 1,
        },
    );
}

/// The mip chain of a square RGB8 map as RGBA8 levels (side, texels), from full size to
/// 1 × 1, each level the 2 × 2 average of the one above: in linear light for colour, as
/// renormalised vectors for normals, plainly for metallic-roughness.
fn mip_chain(rgb: &[u8], kind: MapKind) -> Vec<(u32, Vec<u8>)> {
    let decode = |b: u8| match kind {
        MapKind::BaseColor => srgb_byte_to_linear(b),
        MapKind::Normal => b as f32 / 255.0 * 2.0 - 1.0,
        MapKind::MetallicRoughness => b as f32 / 255.0,
    };
    let encode = |v: f32| match kind {
        MapKind::BaseColor => linear_to_srgb_byte(v),
        MapKind::Normal => ((v * 0.5 + 0.5) * 255.0).round().clamp(0.0, 255.0) as u8,
        MapKind::MetallicRoughness => (v * 255.0).round().clamp(0.0, 255.0) as u8,
    };
    let mut level: Vec<[f32; 3]> = rgb
        .chunks_exact(3)
        .map(|c| [decode(c[0]), decode(c[1]), decode(c[2])])
        .collect();
    let mut size = TEXTURE_SIZE as usize;
    let mut out = Vec::with_capacity(MIP_LEVELS as usize);
    loop {
        let texels = level
            .iter()
            .flat_map(|t| [encode(t[0]), encode(t[1]), encode(t[2]), 255])
            .collect();
        out.push((size as u32, texels));
        if size == 1 {
            return out;
        }
        let half = size / 2;
        level = (0..half * half)
            .map(|i| {
                let (x, y) = (2 * (i % half), 2 * (i / half));
                let mut sum = [0.0f32; 3];
                for (dx, dy) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
                    let t = level[(y + dy) * size + x + dx];
                    sum = [sum[0] + t[0], sum[1] + t[1], sum[2] + t[2]];
                }
                let mean = sum.map(|s| s / 4.0);
                if kind == MapKind::Normal {
                    normalized(mean)
                } else {
                    mean
                }
            })
            .collect();
        size = half;
    }
}

/// `v` scaled to unit length (straight up when it vanishes).
fn normalized(v: [f32; 3]) -> [f32; 3] {
    let len = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
    if len > 1e-6 {
        v.map(|c| c / len)
    } else {
        [0.0, 0.0, 1.0]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn mip_chains_average_down_to_one_texel() {
        let oak = scenethesis_materials::by_id("oak").unwrap();
        let chain = mip_chain(maps(oak).texels(MapKind::BaseColor), MapKind::BaseColor);
        assert_eq!(chain.len(), MIP_LEVELS as usize);
        assert_eq!(chain[0].1.len(), (TEXTURE_SIZE * TEXTURE_SIZE * 4) as usize);
        let (side, last) = chain.last().unwrap();
        assert_eq!(*side, 1);
        // The 1 × 1 level is the map's mean colour (in linear light).
        let mean = maps(oak).mean_albedo;
        for c in 0..3 {
            let got = srgb_byte_to_linear(last[c]);
            assert!((got - mean[c]).abs() < 0.02, "{got} vs {}", mean[c]);
        }
        let normals = mip_chain(maps(oak).texels(MapKind::Normal), MapKind::Normal);
        let top = &normals.last().unwrap().1;
        assert!(top[2] > 240, "averaged normals still point out: {top:?}");
    }
}
