//! Moving parts of imported assets: the `joints` field of a manifest entry, read strictly (a
//! malformed joint fails the whole import, naming the field), checked with the scene graph's
//! own rules ([`Joint::check`]) and carried into the normalised asset frame with the mesh.

use scenethesis_scene_graph::{is_printable_id, Joint, JointError, JointKind, Mesh, OpensTo};
use serde::Deserialize;
use serde_json::Value;

use crate::limits::{MAX_ASSET_SIZE, MAX_FILE_COORDINATE, MAX_JOINTS};
use crate::printable;

/// One moving part of a manifest entry: the part of the file it moves, and its joint in the
/// file's own frame and units (the manifest's `up_axis`, `front` and `unit_scale` then apply to
/// it as to the vertices). In JSON the joint's fields sit beside `part`:
///
/// ```
/// use scenethesis_import::ManifestJoint;
///
/// let door: ManifestJoint = serde_json::from_str(r#"{
///     "part": "door", "name": "door", "kind": "revolute", "axis": [0, 0, -1],
///     "anchor": [-20, 25, 0], "limits": [0, 1.7], "opens_to": "left" }"#)?;
/// assert_eq!(door.part, "door");
/// assert_eq!(door.joint.limits, [0.0, 1.7]);
/// # Ok::<(), serde_json::Error>(())
/// ```
#[derive(Debug, Clone, PartialEq, Deserialize)]
pub struct ManifestJoint {
    /// The part that moves: the name of a glTF node (every triangle primitive of it; a node
    /// without a name goes by its mesh's name), or, for other formats, a part name exactly as
    /// the loader gives it (an OBJ group: `g door`, or `door_oak` when it uses material `oak`).
    pub part: String,
    /// The joint, in the file's frame and units: `axis` and `anchor` as the file's vertices,
    /// prismatic `limits` in file units (revolute ones in radians).
    #[serde(flatten)]
    pub joint: Joint,
}

/// What is wrong with an entry's `joints`: the field (`joints[1].axis`) and what it is and
/// should be (`is [0, 0, 0]; expected ...`).
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Fault {
    pub(crate) field: String,
    pub(crate) problem: String,
}

impl Fault {
    /// As the error of one mesh file's import.
    pub(crate) fn into_error(self) -> crate::MeshLoadError {
        crate::MeshLoadError::Joint {
            field: self.field,
            problem: self.problem,
        }
    }
}

fn fault(field: impl Into<String>, problem: impl Into<String>) -> Fault {
    Fault {
        field: field.into(),
        problem: problem.into(),
    }
}

/// `[0, 0.5, -1]`: numbers as a message shows them.
fn numbers(values: &[f32]) -> String {
    let shown: Vec<String> = values.iter().map(|v| v.to_string()).collect();
    format!("[{}]", shown.join(", "))
}

/// A JSON value as a message quotes it, cut short.
fn quoted(value: &Value) -> String {
    let text = value.to_string();
    let cut: String = text.chars().take(60).collect();
    let more = if cut.len() < text.len() { "..." } else { "" };
    format!("{}{more}", printable(&cut))
}

/// Reads the `joints` field of a manifest entry strictly: every problem is a [`Fault`]
/// naming the field.
pub(crate) fn parse_joints(value: &Value) -> Result<Vec<ManifestJoint>, Fault> {
    let Value::Array(list) = value else {
        return Err(fault(
            "joints",
            format!("is {}; expected an array of joints", quoted(value)),
        ));
    };
    if list.len() > MAX_JOINTS {
        return Err(fault(
            "joints",
            format!("has {} joints; expected at most {MAX_JOINTS}", list.len()),
        ));
    }
    list.iter()
        .enumerate()
        .map(|(k, v)| parse_joint(k, v))
        .collect()
}

/// The fields of a manifest joint and what each must be.
const FIELDS: [(&str, &str); 8] = [
    ("part", "the name of a part of the file (a glTF node)"),
    ("name", "a name for the joint"),
    ("kind", "\"revolute\" or \"prismatic\""),
    ("axis", "[x, y, z]"),
    ("anchor", "[x, y, z]"),
    ("limits", "[lower, upper]"),
    (
        "opens_to",
        "\"left\", \"right\", \"up\", \"down\" or \"out\"",
    ),
    ("parent", "the name of another joint of the entry, or null"),
];

/// One joint, every field read on its own so that the fault names it.
fn parse_joint(k: usize, value: &Value) -> Result<ManifestJoint, Fault> {
    use serde_json::from_value as de;
    let Value::Object(map) = value else {
        return Err(fault(
            format!("joints[{k}]"),
            format!(
                "is {}; expected an object with part, name, kind, axis, anchor, limits and \
                 opens_to",
                quoted(value)
            ),
        ));
    };
    for (key, v) in map {
        let field = format!("joints[{k}].{}", printable(key));
        let Some((_, expected)) = FIELDS.iter().find(|(f, _)| f == key) else {
            let names: Vec<&str> = FIELDS.iter().map(|(f, _)| *f).collect();
            return Err(fault(
                field,
                format!("is not a joint field; expected {}", names.join(", ")),
            ));
        };
        let ok = match key.as_str() {
            "part" | "name" => de::<String>(v.clone()).is_ok(),
            "kind" => de::<JointKind>(v.clone()).is_ok(),
            "axis" | "anchor" => de::<[f32; 3]>(v.clone()).is_ok(),
            "limits" => de::<[f32; 2]>(v.clone()).is_ok(),
            "opens_to" => de::<OpensTo>(v.clone()).is_ok(),
            _ => de::<Option<String>>(v.clone()).is_ok(),
        };
        if !ok {
            return Err(fault(
                field,
                format!("is {}; expected {expected}", quoted(v)),
            ));
        }
    }
    if let Some((missing, expected)) = FIELDS[..7].iter().find(|(f, _)| !map.contains_key(*f)) {
        return Err(fault(
            format!("joints[{k}].{missing}"),
            format!("is missing; expected {expected}"),
        ));
    }
    de::<ManifestJoint>(value.clone()).map_err(|e| fault(format!("joints[{k}]"), e.to_string()))
}

/// The fault of joint `k` that [`Joint::check`] found, naming the field.
fn check_fault(k: usize, error: &JointError) -> Fault {
    match error {
        JointError::ZeroAxis { axis, .. } => fault(
            format!("joints[{k}].axis"),
            format!(
                "is {}; expected a finite, non-zero direction",
                numbers(axis)
            ),
        ),
        JointError::BadAnchor { anchor, .. } => fault(
            format!("joints[{k}].anchor"),
            format!("is {}; expected a finite point", numbers(anchor)),
        ),
        JointError::BadLimits { limits, .. } => fault(
            format!("joints[{k}].limits"),
            format!(
                "is {}; expected [lower, upper] with lower <= 0 <= upper and lower < upper \
                 (0 is closed)",
                numbers(limits)
            ),
        ),
    }
}

/// Checks what can be checked without the file: each joint by [`Joint::check`], names
/// printable and unique, each parent listed before its child, limits within one turn
/// (revolute) or [`MAX_FILE_COORDINATE`] file units (prismatic).
pub(crate) fn check_joints(joints: &[ManifestJoint]) -> Result<(), Fault> {
    if joints.len() > MAX_JOINTS {
        return Err(fault(
            "joints",
            format!("has {} joints; expected at most {MAX_JOINTS}", joints.len()),
        ));
    }
    for (k, j) in joints.iter().map(|m| &m.joint).enumerate() {
        let before = &joints[..k];
        let field = |name: &str| format!("joints[{k}].{name}");
        if !is_printable_id(&j.name) {
            return Err(fault(
                field("name"),
                format!(
                    "is \"{}\"; expected 1 to {} bytes of printable characters",
                    printable(&j.name),
                    scenethesis_scene_graph::limits::MAX_ID_BYTES
                ),
            ));
        }
        if let Some(i) = before.iter().position(|m| m.joint.name == j.name) {
            return Err(fault(
                field("name"),
                format!(
                    "is \"{}\", as joints[{i}]'s; expected a name unique within the entry",
                    j.name
                ),
            ));
        }
        if let Some(p) = &j.parent {
            if !before.iter().any(|m| &m.joint.name == p) {
                return Err(fault(
                    field("parent"),
                    format!(
                        "is \"{}\"; expected the name of a joint listed before it",
                        printable(p)
                    ),
                ));
            }
        }
        j.check().map_err(|e| check_fault(k, &e))?;
        check_range(k, j, MAX_FILE_COORDINATE as f32, "file units")?;
    }
    Ok(())
}

/// The limits stay within one turn (revolute) or `reach` (prismatic, in `unit`), so that the
/// opening sweep stays short.
fn check_range(k: usize, joint: &Joint, reach: f32, unit: &str) -> Result<(), Fault> {
    let (bound, what) = match joint.kind {
        JointKind::Revolute => (std::f32::consts::TAU, "radians (one turn)".to_owned()),
        JointKind::Prismatic => (reach, unit.to_owned()),
    };
    if joint.limits.iter().all(|l| l.abs() <= bound) {
        return Ok(());
    }
    Err(fault(
        format!("joints[{k}].limits"),
        format!(
            "is {}; expected limits within ±{bound} {what}",
            numbers(&joint.limits)
        ),
    ))
}

/// The indices of the parts of `mesh` that `part` names: those named `part` followed by `_`
/// and a primitive index (a glTF node's primitives), or else the one named `part` exactly.
fn named_parts(mesh: &Mesh, part: &str) -> Vec<usize> {
    let numbered: Vec<usize> = (0..mesh.parts.len())
        .filter(|&i| {
            mesh.parts[i]
                .name
                .strip_prefix(part)
                .and_then(|rest| rest.strip_prefix('_'))
                .is_some_and(|n| !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()))
        })
        .collect();
    if !numbered.is_empty() {
        return numbered;
    }
    (0..mesh.parts.len())
        .filter(|&i| mesh.parts[i].name == part)
        .collect()
}

/// The names a joint's `part` can take in `mesh`, for a message: each part's name without its
/// primitive index, the first few.
fn part_names(mesh: &Mesh) -> String {
    let mut names: Vec<&str> = Vec::new();
    for p in &mesh.parts {
        let name = match p.name.rsplit_once('_') {
            Some((node, n)) if !n.is_empty() && n.bytes().all(|b| b.is_ascii_digit()) => node,
            _ => p.name.as_str(),
        };
        if !names.contains(&name) {
            names.push(name);
        }
    }
    let more = if names.len() > 8 { ", ..." } else { "" };
    let shown: Vec<String> = names
        .iter()
        .take(8)
        .map(|n| format!("\"{}\"", printable(n)))
        .collect();
    format!("{}{more}", shown.join(", "))
}

/// Links the parts each joint moves ([`MeshPart::joint`](scenethesis_scene_graph::MeshPart))
/// and returns the joints in the asset frame, each mapped by `to_asset` (the normalisation the
/// vertices went through). Faults: a part the file does not hold, a part two joints move, and
/// a joint that normalisation takes beyond the asset limits.
pub(crate) fn link_joints(
    mesh: &mut Mesh,
    joints: &[ManifestJoint],
    to_asset: impl Fn(&Joint) -> Joint,
) -> Result<Vec<Joint>, Fault> {
    let mut placed = Vec::with_capacity(joints.len());
    for (k, m) in joints.iter().enumerate() {
        let parts = named_parts(mesh, &m.part);
        if parts.is_empty() {
            return Err(fault(
                format!("joints[{k}].part"),
                format!(
                    "is \"{}\", which the file does not hold; expected one of its parts: {}",
                    printable(&m.part),
                    part_names(mesh)
                ),
            ));
        }
        for &i in &parts {
            if let Some(other) = &mesh.parts[i].joint {
                let j = joints.iter().position(|o| &o.joint.name == other);
                return Err(fault(
                    format!("joints[{k}].part"),
                    format!(
                        "is \"{}\", which joints[{}] already moves; expected each part moved \
                         by one joint at most",
                        printable(&m.part),
                        j.unwrap_or(k)
                    ),
                ));
            }
            mesh.parts[i].joint = Some(m.joint.name.clone());
        }
        let joint = to_asset(&m.joint);
        joint.check().map_err(|e| check_fault(k, &e))?;
        check_range(k, &joint, MAX_ASSET_SIZE as f32, "m")?;
        if joint.anchor.iter().any(|a| a.abs() > MAX_ASSET_SIZE as f32) {
            return Err(fault(
                format!("joints[{k}].anchor"),
                format!(
                    "is {} m from the asset's origin after unit_scale; expected within \
                     ±{MAX_ASSET_SIZE} m",
                    numbers(&joint.anchor)
                ),
            ));
        }
        placed.push(joint);
    }
    Ok(placed)
}
