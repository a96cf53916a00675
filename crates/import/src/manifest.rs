//! The `assets.json` manifest: its entries, read leniently (one bad entry is a warning naming
//! the field, not the end of the import) and checked against the limits.

use std::path::{Path, PathBuf};

use scenethesis_scene_graph::{Placement, SupportSurface};
use serde::Deserialize;

use crate::joints::{check_joints, parse_joints, ManifestJoint};
use crate::limits::{
    MAX_ASSET_SCALE, MAX_ASSET_SIZE, MAX_MANIFEST_BYTES, MAX_MANIFEST_ENTRIES, MAX_SYNONYMS,
};
use crate::{printable, ImportError};

/// The manifest file name looked up in an asset directory.
pub const MANIFEST_FILE: &str = "assets.json";

/// The axis that points up in a source file.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum UpAxis {
    /// +Y up (glTF convention).
    #[default]
    #[serde(rename = "y", alias = "Y", alias = "+y")]
    Y,
    /// +Z up (Blender, many CAD tools).
    #[serde(rename = "z", alias = "Z", alias = "+z")]
    Z,
}

/// The direction an asset's front faces in its source file (after the up axis is turned to +Y).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Deserialize)]
pub enum Front {
    /// Already +Z.
    #[default]
    #[serde(rename = "+z", alias = "z")]
    PosZ,
    /// Faces −Z.
    #[serde(rename = "-z")]
    NegZ,
    /// Faces +X.
    #[serde(rename = "+x", alias = "x")]
    PosX,
    /// Faces −X.
    #[serde(rename = "-x")]
    NegX,
}

/// One manifest entry.
#[derive(Debug, Clone, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ManifestEntry {
    /// Mesh file, relative to the asset directory.
    pub file: PathBuf,
    /// Asset id; defaults to the file stem.
    #[serde(default)]
    pub id: Option<String>,
    /// Category name, e.g. `armchair`.
    pub category: String,
    /// Other names for retrieval.
    #[serde(default)]
    pub synonyms: Vec<String>,
    /// Up axis of the file.
    #[serde(default)]
    pub up_axis: UpAxis,
    /// Metres per file unit.
    #[serde(default = "one")]
    pub unit_scale: f32,
    /// Front direction in the file (after turning the up axis to +Y).
    #[serde(default)]
    pub front: Front,
    /// Placement kind; defaults to the built-in category's placement, else floor.
    #[serde(default)]
    pub placement: Option<Placement>,
    /// Support surfaces in the normalised frame; found automatically when absent.
    #[serde(default)]
    pub support_surfaces: Option<Vec<SupportSurface>>,
    /// Allowed uniform scale range.
    #[serde(default)]
    pub scale_range: Option<[f32; 2]>,
    /// The moving parts, in the file's frame and units (empty for a rigid asset).
    #[serde(default)]
    pub joints: Vec<ManifestJoint>,
}

fn one() -> f32 {
    1.0
}

/// Reads `assets.json` into one (label, entry or error naming the field) per entry. A
/// malformed `joints` field is an [`ImportError::Joint`], not an unusable entry.
#[allow(clippy::type_complexity)]
pub(crate) fn read_manifest(
    path: &Path,
) -> Result<Vec<(String, Result<ManifestEntry, String>)>, ImportError> {
    let bytes =
        scenethesis_scene_graph::read_bounded(path, MAX_MANIFEST_BYTES).map_err(|source| {
            ImportError::ManifestIo {
                path: path.to_owned(),
                source,
            }
        })?;
    let value: serde_json::Value =
        serde_json::from_slice(&bytes).map_err(|source| ImportError::ManifestJson {
            path: path.to_owned(),
            source,
        })?;
    let shape = |reason: &str| ImportError::ManifestShape {
        path: path.to_owned(),
        reason: reason.to_owned(),
    };
    let list = match value {
        serde_json::Value::Array(list) => list,
        serde_json::Value::Object(mut map) => match map.remove("assets") {
            Some(serde_json::Value::Array(list)) => list,
            Some(_) => return Err(shape("field `assets` must be an array of entries")),
            None => {
                return Err(shape(
                    "expected an array of {\"file\", \"category\", ...} entries or an object with an `assets` array",
                ))
            }
        },
        _ => {
            return Err(shape(
                "expected an array of {\"file\", \"category\", ...} entries or an object with an `assets` array",
            ))
        }
    };
    if list.len() > MAX_MANIFEST_ENTRIES {
        return Err(shape(&format!(
            "{} entries, more than the limit of {MAX_MANIFEST_ENTRIES}",
            list.len()
        )));
    }
    list.into_iter()
        .enumerate()
        .map(|(k, value)| {
            let file = value
                .get("file")
                .and_then(|f| f.as_str())
                .map(|f| format!(" (file `{}`)", printable(f)))
                .unwrap_or_default();
            let label = format!("entry #{k}{file}");
            if let Some(joints) = value.get("joints") {
                let checked = parse_joints(joints).and_then(|j| check_joints(&j));
                if let Err(fault) = checked {
                    return Err(ImportError::joint(path, label, fault));
                }
            }
            Ok((label, parse_entry(value)))
        })
        .collect()
}

/// One manifest entry, or why it is unusable, naming the field.
fn parse_entry(value: serde_json::Value) -> Result<ManifestEntry, String> {
    use serde_json::from_value as de;
    let serde_json::Value::Object(map) = &value else {
        return Err("expected an object with `file` and `category`".into());
    };
    for (key, v) in map {
        let v = v.clone();
        let result = match key.as_str() {
            "file" => de::<PathBuf>(v).map(drop),
            "id" => de::<Option<String>>(v).map(drop),
            "category" => de::<String>(v).map(drop),
            "synonyms" => de::<Vec<String>>(v).map(drop),
            "up_axis" => de::<UpAxis>(v).map(drop),
            "unit_scale" => de::<f32>(v).map(drop),
            "front" => de::<Front>(v).map(drop),
            "placement" => de::<Option<Placement>>(v).map(drop),
            "support_surfaces" => de::<Option<Vec<SupportSurface>>>(v).map(drop),
            "scale_range" => de::<Option<[f32; 2]>>(v).map(drop),
            "joints" => de::<Vec<ManifestJoint>>(v).map(drop),
            other => {
                return Err(format!(
                    "unknown field `{}` (expected file, id, category, synonyms, up_axis, unit_scale, front, placement, support_surfaces, scale_range or joints)",
                    printable(other)
                ))
            }
        };
        if let Err(e) = result {
            return Err(format!("field `{key}`: {e}"));
        }
    }
    for required in ["file", "category"] {
        if !map.contains_key(required) {
            return Err(format!("missing field `{required}`"));
        }
    }
    de::<ManifestEntry>(value).map_err(|e| e.to_string())
}

/// Checks the values of a parsed entry, naming the field at fault.
pub(crate) fn check_entry(entry: &ManifestEntry) -> Result<(), String> {
    let names = [
        ("category", Some(&entry.category)),
        ("id", entry.id.as_ref()),
    ];
    for (field, value) in names {
        if let Some(v) = value {
            if !scenethesis_scene_graph::is_printable_id(v) {
                return Err(format!(
                    "field `{field}` is `{}`, expected 1 to {} bytes of printable characters",
                    printable(v),
                    scenethesis_scene_graph::limits::MAX_ID_BYTES
                ));
            }
        }
    }
    if entry.synonyms.len() > MAX_SYNONYMS {
        return Err(format!(
            "field `synonyms` has {} names, more than the limit of {MAX_SYNONYMS}",
            entry.synonyms.len()
        ));
    }
    if let Some(s) = entry
        .synonyms
        .iter()
        .find(|s| !scenethesis_scene_graph::is_printable_id(s))
    {
        return Err(format!(
            "field `synonyms` holds `{}`, expected printable names",
            printable(s)
        ));
    }
    if !(entry.unit_scale.is_finite() && entry.unit_scale > 0.0 && entry.unit_scale <= 1000.0) {
        return Err(format!(
            "field `unit_scale` is {}, expected a positive number of metres per file unit (at most 1000)",
            entry.unit_scale
        ));
    }
    if let Some([lo, hi]) = entry.scale_range {
        if !(lo.is_finite() && hi.is_finite() && lo > 0.0 && lo <= hi && hi <= MAX_ASSET_SCALE) {
            return Err(format!(
                "field `scale_range` is [{lo}, {hi}], expected [min, max] with 0 < min <= max <= {MAX_ASSET_SCALE}"
            ));
        }
    }
    if let Some(surfaces) = &entry.support_surfaces {
        if let Some(k) = surfaces.iter().position(|s| !surface_ok(s)) {
            return Err(format!(
                "field `support_surfaces[{k}]` has a non-finite number or a coordinate beyond ±{MAX_ASSET_SIZE} m"
            ));
        }
    }
    Ok(())
}

fn surface_ok(surface: &SupportSurface) -> bool {
    serde_json::to_value(surface)
        .ok()
        .map(|v| numbers_ok(&v))
        .unwrap_or(false)
}

/// Every number in `v` is finite and within ±[`MAX_ASSET_SIZE`].
fn numbers_ok(v: &serde_json::Value) -> bool {
    match v {
        serde_json::Value::Number(n) => n
            .as_f64()
            .is_some_and(|x| x.is_finite() && x.abs() <= MAX_ASSET_SIZE),
        serde_json::Value::Array(a) => a.iter().all(numbers_ok),
        serde_json::Value::Object(o) => o.values().all(numbers_ok),
        _ => true,
    }
}
