//! Looks: the colours and materials a scene's objects and room surfaces were asked to wear, and
//! what they wear. An [`AssetLook`] travels inside a procedural [`AssetRef`](crate::AssetRef)
//! (so a saved scene regenerates the same materials); a [`SceneLook`] records the room's style,
//! its surfaces' materials and every object's worn materials in `scene.json`.

use std::collections::BTreeMap;
use std::fmt;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

use crate::{fnv1a64, Material, Mesh};

/// A colour as sRGB bytes, written `"#rrggbb"` in JSON.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Srgb(pub [u8; 3]);

impl Srgb {
    /// The colour of a linear RGB triple (channels clamped to [0, 1]).
    pub fn from_linear(rgb: [f32; 3]) -> Self {
        Srgb(rgb.map(|c| {
            let c = c.clamp(0.0, 1.0);
            let s = if c <= 0.003_130_8 {
                12.92 * c
            } else {
                1.055 * c.powf(1.0 / 2.4) - 0.055
            };
            (s * 255.0).round() as u8
        }))
    }

    /// The linear RGB triple of the colour.
    pub fn to_linear(self) -> [f32; 3] {
        self.0.map(|v| {
            let c = v as f32 / 255.0;
            if c <= 0.04045 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        })
    }

    /// Parses `#rrggbb` (the `#` optional).
    pub fn parse(text: &str) -> Option<Self> {
        let hex = text.strip_prefix('#').unwrap_or(text);
        if hex.len() != 6 || !hex.is_ascii() {
            return None;
        }
        let byte = |i: usize| u8::from_str_radix(&hex[i..i + 2], 16).ok();
        Some(Srgb([byte(0)?, byte(2)?, byte(4)?]))
    }

    /// The largest per-channel difference to `other`, in sRGB steps (0–255).
    pub fn distance(self, other: Srgb) -> u8 {
        (0..3)
            .map(|k| self.0[k].abs_diff(other.0[k]))
            .max()
            .unwrap_or(0)
    }
}

impl fmt::Display for Srgb {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let [r, g, b] = self.0;
        write!(f, "#{r:02x}{g:02x}{b:02x}")
    }
}

impl Serialize for Srgb {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        s.serialize_str(&self.to_string())
    }
}

impl<'de> Deserialize<'de> for Srgb {
    fn deserialize<D: Deserializer<'de>>(d: D) -> Result<Self, D::Error> {
        let text = String::deserialize(d)?;
        Srgb::parse(&text).ok_or_else(|| {
            serde::de::Error::custom(format!("colour `{text}`: expected \"#rrggbb\""))
        })
    }
}

/// Which parts of an asset a requested attribute qualifies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum LookScope {
    /// The cover: fabric and leather parts (a sofa's cushions, a bed's mattress); the main
    /// body when the asset has none.
    Upholstery,
    /// The main body: every material of the asset covering a twentieth of its surface or more,
    /// upholstery aside (a table's top and legs, a shelf's boards).
    Body,
    /// The largest material only (a table's top, a counter's worktop).
    Top,
    /// What the object is mostly seen as: its upholstery if it has any, else its largest
    /// material and every other of the same family.
    Main,
}

/// One requested colour or material, resolved to what it does to a procedural asset.
#[derive(Debug, Clone, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
pub struct LookAttribute {
    /// Which parts it qualifies.
    pub scope: LookScope,
    /// The material the parts become: a named material of the palettes (`oak`,
    /// `white_marble`, `brown_leather`) or a family token (`velvet`, `linen`) that keeps the
    /// parts' colour; `None` to keep their material.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub material: Option<String>,
    /// The colour the parts take; `None` to keep it.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color: Option<Srgb>,
    /// The colour's name for material names (`red`, `dark_grey`), with the colour.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub color_name: Option<String>,
}

/// The look a procedural asset is generated with, on top of its seed: the room style's
/// choice per material family, then the object's own requested attributes in order.
#[derive(Debug, Clone, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
pub struct AssetLook {
    /// Per palette family (`wood`, `fabric`, `painted_wood`, …), the named material every
    /// material of that family becomes (`ash`, `cream_fabric`): the room's coherent style.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub families: BTreeMap<String, String>,
    /// The object's requested attributes, applied after the families.
    #[serde(default, skip_serializing_if = "Vec::is_empty")]
    pub attributes: Vec<LookAttribute>,
}

impl AssetLook {
    /// Whether the look changes nothing.
    pub fn is_plain(&self) -> bool {
        self.families.is_empty() && self.attributes.is_empty()
    }

    /// A short stable digest of the look (16 hex digits), for cache keys and names.
    pub fn digest(&self) -> String {
        let text = serde_json::to_string(self).unwrap_or_default();
        format!("{:016x}", fnv1a64(text.as_bytes()))
    }
}

/// A material an object wears, as recorded in `scene.json`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WornMaterial {
    /// The material's name (`red_leather`, `oak`).
    pub name: String,
    /// Its base colour in sRGB.
    pub color: Srgb,
    /// Perceptual roughness.
    pub roughness: f32,
    /// Metalness.
    pub metallic: f32,
    /// Opacity (1 opaque; glass less).
    #[serde(default = "opaque")]
    pub alpha: f32,
    /// The mesh parts wearing it.
    pub parts: Vec<String>,
}

fn opaque() -> f32 {
    1.0
}

impl WornMaterial {
    /// The materials of `mesh` that some part wears, in material order, with their parts.
    pub fn of_mesh(mesh: &Mesh) -> Vec<WornMaterial> {
        mesh.materials
            .iter()
            .enumerate()
            .filter_map(|(i, m)| {
                let parts: Vec<String> = mesh
                    .parts
                    .iter()
                    .filter(|p| p.material == i)
                    .map(|p| p.name.clone())
                    .collect();
                (!parts.is_empty()).then(|| WornMaterial::new(m, parts))
            })
            .collect()
    }

    /// The record of `material` worn by `parts`.
    pub fn new(material: &Material, parts: Vec<String>) -> Self {
        let [r, g, b, a] = material.flat_color();
        WornMaterial {
            name: material.name.clone(),
            color: Srgb::from_linear([r, g, b]),
            roughness: material.roughness,
            metallic: material.metallic,
            alpha: a,
            parts,
        }
    }
}

/// The room's look in `scene.json`: its style, its surfaces' materials and what every object
/// wears. Absent (empty) for scenes made without looks.
#[derive(Debug, Clone, PartialEq, Default, Serialize, Deserialize)]
pub struct SceneLook {
    /// The room's style (`scandinavian`, `industrial`, …).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub style: Option<String>,
    /// The materials of the room's surfaces by name (`floor`, `walls`, `ceiling`).
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub surfaces: BTreeMap<String, Material>,
    /// Every object's worn materials by object id.
    #[serde(default, skip_serializing_if = "BTreeMap::is_empty")]
    pub objects: BTreeMap<String, Vec<WornMaterial>>,
}

impl SceneLook {
    /// Whether nothing is recorded.
    pub fn is_empty(&self) -> bool {
        self.style.is_none() && self.surfaces.is_empty() && self.objects.is_empty()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn srgb_round_trips_through_hex_and_linear() {
        let red = Srgb([0xb2, 0x22, 0x22]);
        assert_eq!(red.to_string(), "#b22222");
        assert_eq!(Srgb::parse("#b22222"), Some(red));
        assert_eq!(Srgb::parse("b22222"), Some(red));
        assert_eq!(Srgb::parse("#b2222"), None);
        assert_eq!(Srgb::from_linear(red.to_linear()), red);
        assert_eq!(red.distance(Srgb([0xb0, 0x22, 0x30])), 14);
    }

    #[test]
    fn a_plain_look_is_plain_and_digests_differ() {
        let plain = AssetLook::default();
        assert!(plain.is_plain());
        let mut look = AssetLook::default();
        look.families.insert("wood".into(), "ash".into());
        assert!(!look.is_plain());
        assert_ne!(look.digest(), plain.digest());
        let json = serde_json::to_string(&look).unwrap();
        assert_eq!(json, r#"{"families":{"wood":"ash"}}"#);
    }
}
