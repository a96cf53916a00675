//! Scene exporters for the tools that consume scenethesis scenes.
//!
//! An [`ExportScene`] pairs a [`Scene`] with the mesh of every object (in the asset's own frame;
//! the exporters apply the pose). From it this crate writes:
//!
//! - **glTF 2.0 binary** ([`glb::to_glb`]): +Y up, metres, one node per object named by its id,
//!   one mesh per object with one primitive per part, PBR metallic-roughness materials, and the
//!   architecture (`floor`, `wall_0`, …, walls split around their door openings) as box nodes.
//! - **OpenUSD text** ([`usd::to_usda`]): `upAxis = "Y"`, `metersPerUnit = 1`, an `Xform` per
//!   object with translate / rotateY / scale ops, `Mesh` prims per part bound to
//!   `UsdPreviewSurface` materials.
//! - **MuJoCo MJCF** ([`mjcf::to_mjcf`]): Z-up as MuJoCo expects, one body per object with a
//!   free joint (objects mounted on walls are welded to the world: no joint), one convex mesh geom per
//!   part, density 1000 kg/m³, friction 0.5, a floor plane and static wall boxes.
//! - **URDF** ([`urdf::to_urdf`]): Z-up as ROS expects, a `world` root link, a link per object
//!   with visual and collision meshes per part (OBJ files beside the URDF), mass and inertia
//!   from the closed part meshes, floating or fixed joints.
//!
//!
//! An object with joints ([`SceneObject::joints`], its mesh's parts naming them in
//! [`scenethesis_scene_graph::MeshPart::joint`]) is articulated in every format: its fixed body
//! plus one moving link per joint, nested as the joints are (MJCF child bodies with hinge and
//! slide joints, URDF revolute and prismatic joints, UsdPhysics joints under an articulation
//! root, GLB child nodes pivoting at the joint with the joint in `extras`). Objects without
//! joints are written exactly as before.
//!
//! Every writer is deterministic: the same input gives byte-identical output.
//!
//! A one-box scene written as MJCF and GLB:
//!
//! ```
//! use std::collections::BTreeMap;
//! use scenethesis_export::{glb, mjcf, Dynamics, ExportScene};
//! use scenethesis_scene_graph::nalgebra::{Point3, Vector3};
//! use scenethesis_scene_graph::{
//!     Aabb, Architecture, AssetRef, Material, Mesh, MeshPart, ParentRef, Pose, RelationKind,
//!     Scene, SceneObject,
//! };
//!
//! let mut scene = Scene::new(Architecture::rectangular_room(3.0, 3.0, 2.5, 0.9));
//! scene.objects.push(SceneObject {
//!     id: "crate_0".into(),
//!     category: "crate".into(),
//!     asset: AssetRef::Procedural { generator: "crate".into(), seed: 0, look: None },
//!     pose: Pose::new(1.0, 0.3, Vector3::new(0.5, 0.0, 0.0)),
//!     parent: ParentRef::Ground,
//!     support: RelationKind::OnFloor,
//!     relations: Vec::new(),
//!     local_bounds: Aabb::new(Point3::new(-0.2, 0.0, -0.2), Point3::new(0.2, 0.4, 0.2)),
//!     joints: Vec::new(),
//!     parent_link: None,
//!     room: None,
//! });
//! let mesh = Mesh {
//!     parts: vec![MeshPart::cuboid("body", 0, [-0.2, 0.0, -0.2], [0.2, 0.4, 0.2])],
//!     materials: vec![Material::new("wood", [0.6, 0.4, 0.2], 0.8)],
//! };
//! let meshes = BTreeMap::from([("crate_0".to_owned(), mesh)]);
//! let export = ExportScene::new(&scene, &meshes)?;
//! assert_eq!(export.dynamics(&scene.objects[0]), Dynamics::Free);
//!
//! let xml = mjcf::to_mjcf(&export);
//! assert!(xml.contains("crate_0") && xml.contains("freejoint"));
//! let bytes = glb::to_glb(&export);
//! assert_eq!(&bytes[..4], b"glTF");
//! assert_eq!(bytes, glb::to_glb(&export), "deterministic");
//! # Ok::<(), scenethesis_export::ExportError>(())
//! ```

#![warn(missing_docs)]

pub mod architecture;
mod articulation;
mod file;
mod geometry;
pub mod glb;
pub mod mjcf;
mod textures;
pub mod urdf;
pub mod usd;

use std::collections::BTreeMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::str::FromStr;

use scenethesis_scene_graph::{limits, printable, write_file_atomic, Mesh, Scene, SceneObject};

pub use articulation::{JOINT_DAMPING, MIN_JOINT_FRICTION};
pub use file::write_formats;
pub use geometry::MassProperties;
pub use textures::TEXTURE_DIR;

/// Density given to every object in the physics formats, kg/m³ (water; solid wood is 500–900).
pub const DENSITY: f64 = 1000.0;
/// Sliding friction coefficient of every object in the physics formats.
pub const FRICTION: f64 = 0.5;

/// Why a scene could not be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// An object of the scene has no mesh in the mesh map.
    #[error("object `{id}` has no mesh: every object of the scene needs one to be exported")]
    MissingMesh {
        /// The object's id.
        id: String,
    },
    /// An object's mesh cannot be written.
    #[error("mesh of object `{id}` is unusable: {reason}")]
    InvalidMesh {
        /// The object's id.
        id: String,
        /// What is wrong, e.g. an index out of range.
        reason: String,
    },
    /// An object's pose is not finite or its scale is not positive.
    #[error("object `{id}` has an invalid pose (expected finite numbers, a scale in (0, 10] and coordinates within ±1000 m; see docs/limits.md)")]
    InvalidPose {
        /// The object's id.
        id: String,
    },
    /// A floor, wall or door holds a value outside what the formats can hold (non-finite, or
    /// beyond the limits of `docs/limits.md`).
    #[error("{element}: field `{field}` must be finite and within ±1000 m (see docs/limits.md)")]
    InvalidArchitecture {
        /// The floor, wall or door id.
        element: String,
        /// The field.
        field: &'static str,
    },
    /// A file could not be written.
    #[error("cannot write {path}")]
    Write {
        /// The file.
        path: PathBuf,
        /// The OS error.
        #[source]
        source: std::io::Error,
    },
}

/// How an object behaves in the physics formats (MJCF, URDF).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Dynamics {
    /// A free rigid body under gravity (six degrees of freedom).
    Free,
    /// Welded to the world: objects mounted on a wall.
    Fixed,
}

/// A scene ready to export: the scene graph plus the mesh of every object.
#[derive(Debug, Clone)]
pub struct ExportScene<'a> {
    scene: &'a Scene,
    meshes: &'a BTreeMap<String, Mesh>,
}

impl<'a> ExportScene<'a> {
    /// Pairs a scene with its meshes (keyed by object id, in each asset's own frame) and checks
    /// that every object has a usable mesh and a valid pose. Meshes of ids that are not objects
    /// of the scene are ignored.
    pub fn new(scene: &'a Scene, meshes: &'a BTreeMap<String, Mesh>) -> Result<Self, ExportError> {
        for object in &scene.objects {
            let mesh = meshes
                .get(&object.id)
                .ok_or_else(|| ExportError::MissingMesh {
                    id: object.id.clone(),
                })?;
            check_mesh(&object.id, mesh)?;
            let pose = &object.pose;
            let in_range = pose.is_finite()
                && pose.scale > 0.0
                && pose.scale <= limits::MAX_SCALE
                && pose.yaw.abs() <= limits::MAX_YAW
                && pose
                    .translation
                    .iter()
                    .all(|v| v.abs() <= limits::MAX_COORDINATE);
            if !in_range {
                return Err(ExportError::InvalidPose {
                    id: printable(&object.id).into_owned(),
                });
            }
        }
        check_architecture(scene)?;
        Ok(Self { scene, meshes })
    }

    /// The scene being exported.
    pub fn scene(&self) -> &'a Scene {
        self.scene
    }

    /// The mesh of an object (checked to exist by [`ExportScene::new`]).
    pub fn mesh(&self, object: &SceneObject) -> &'a Mesh {
        &self.meshes[&object.id]
    }

    /// Whether an object is a free body or welded to the world: fixed exactly when the scene
    /// says it is fixed to the world ([`SceneObject::fixed_to_world`]: support `mounted`, its
    /// parent a wall). Everything else is free, including an object that floats: the
    /// simulation then shows the defect instead of hiding it.
    pub fn dynamics(&self, object: &SceneObject) -> Dynamics {
        if object.fixed_to_world() {
            Dynamics::Fixed
        } else {
            Dynamics::Free
        }
    }
}

/// Floor, walls and doors: every number finite and within the coordinate limit
/// ([`scenethesis_scene_graph::Architecture::out_of_bounds`]), so that no format (GLB stores
/// `f32`) receives a value it cannot hold.
fn check_architecture(scene: &Scene) -> Result<(), ExportError> {
    match scene.architecture.out_of_bounds() {
        Some(bad) => Err(ExportError::InvalidArchitecture {
            element: printable(bad.id).into_owned(),
            field: bad.fields,
        }),
        None => Ok(()),
    }
}

fn check_mesh(id: &str, mesh: &Mesh) -> Result<(), ExportError> {
    let id = &*printable(id);
    let invalid = |reason: String| ExportError::InvalidMesh {
        id: id.to_owned(),
        reason,
    };
    if mesh.parts.iter().all(|p| p.triangles.is_empty()) {
        return Err(invalid("it has no triangles".into()));
    }
    for part in &mesh.parts {
        if part.material >= mesh.materials.len() {
            return Err(invalid(format!(
                "part `{}` uses material {} but the mesh has {} material(s)",
                printable(&part.name),
                part.material,
                mesh.materials.len()
            )));
        }
        let n = part.positions.len() as u32;
        if let Some(t) = part.triangles.iter().find(|t| t.iter().any(|&i| i >= n)) {
            return Err(invalid(format!(
                "part `{}` has triangle {t:?} indexing past its {n} vertices",
                printable(&part.name)
            )));
        }
        if let Some(uvs) = &part.uvs {
            if uvs.len() != part.positions.len() || uvs.iter().flatten().any(|v| !v.is_finite()) {
                return Err(invalid(format!(
                    "part `{}` has {} texture coordinates for {} vertices, or one that is not finite",
                    printable(&part.name),
                    uvs.len(),
                    part.positions.len()
                )));
            }
        }
        if part.positions.iter().flatten().any(|v| {
            !v.is_finite() || v.abs() as f64 > scenethesis_scene_graph::limits::MAX_OBJECT_SIZE
        }) {
            return Err(invalid(format!(
                "part `{}` has a vertex position that is not finite or beyond ±{} m",
                printable(&part.name),
                scenethesis_scene_graph::limits::MAX_OBJECT_SIZE
            )));
        }
    }
    Ok(())
}

/// An export file format.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Format {
    /// glTF 2.0 binary (`scene.glb`).
    Glb,
    /// OpenUSD text layer (`scene.usda`).
    Usd,
    /// MuJoCo XML (`scene.mjcf.xml`), meshes inline.
    Mjcf,
    /// URDF (`scene.urdf`) with OBJ meshes in `meshes/`.
    Urdf,
}

impl Format {
    /// Every format, in a stable order.
    pub const ALL: [Format; 4] = [Format::Glb, Format::Usd, Format::Mjcf, Format::Urdf];

    /// The name used on the command line: `glb`, `usd`, `mjcf` or `urdf`.
    pub fn as_str(&self) -> &'static str {
        match self {
            Format::Glb => "glb",
            Format::Usd => "usd",
            Format::Mjcf => "mjcf",
            Format::Urdf => "urdf",
        }
    }

    /// The main file this format writes into an output folder.
    pub fn file_name(&self) -> &'static str {
        match self {
            Format::Glb => "scene.glb",
            Format::Usd => "scene.usda",
            Format::Mjcf => "scene.mjcf.xml",
            Format::Urdf => "scene.urdf",
        }
    }
}

impl fmt::Display for Format {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// The error of parsing an unknown format name.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("unknown export format `{0}`: expected one of glb, usd, mjcf, urdf")]
pub struct UnknownFormat(pub String);

impl FromStr for Format {
    type Err = UnknownFormat;

    fn from_str(s: &str) -> Result<Self, Self::Err> {
        match s.to_ascii_lowercase().as_str() {
            "glb" | "gltf" => Ok(Format::Glb),
            "usd" | "usda" => Ok(Format::Usd),
            "mjcf" | "mujoco" => Ok(Format::Mjcf),
            "urdf" => Ok(Format::Urdf),
            _ => Err(UnknownFormat(s.to_owned())),
        }
    }
}

fn write(path: &Path, bytes: &[u8]) -> Result<(), ExportError> {
    write_file_atomic(path, bytes).map_err(|source| ExportError::Write {
        path: path.to_owned(),
        source,
    })
}
