//! What to render: posed meshes, the room or ground around them, and the backdrop.

use std::collections::BTreeMap;
use std::sync::Arc;

use nalgebra::Point3;
use scenethesis_scene_graph::{Aabb, Architecture, Environment, Material, Mesh, Pose, Scene};

/// One posed mesh with the id its pixels carry in the instance image.
#[derive(Debug, Clone)]
pub struct Instance {
    /// Stable object id (the scene's object id).
    pub id: String,
    /// The asset's mesh in its own frame; shared so that many views of a scene, or many
    /// instances of one asset, do not copy it.
    pub mesh: Arc<Mesh>,
    /// Where the mesh stands in the world.
    pub pose: Pose,
}

impl Instance {
    /// An instance from its parts.
    pub fn new(id: impl Into<String>, mesh: Arc<Mesh>, pose: Pose) -> Self {
        Self {
            id: id.into(),
            mesh,
            pose,
        }
    }

    /// The world-space box of the posed mesh, or `None` for an empty mesh.
    pub fn world_bounds(&self) -> Option<Aabb> {
        self.mesh.bounds().map(|b| b.transformed(&self.pose))
    }
}

/// What surrounds the scene's own geometry.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Backdrop {
    /// A light grey studio: a soft grey gradient behind a neutral floor plane at y = 0 that
    /// reaches well beyond the objects (contact sheets, objects without a room).
    #[default]
    Studio,
    /// An interior: the room's own floor and walls over a dim neutral gradient; no extra
    /// floor plane.
    Interior,
    /// Outdoors: a sky gradient over a ground plane reaching to the horizon.
    Sky,
}

/// A scene prepared for rendering: posed meshes plus optional architecture.
#[derive(Debug, Clone, Default)]
pub struct RenderScene {
    /// The movable objects; ids must be unique.
    pub instances: Vec<Instance>,
    /// Floor, walls (with their door openings) of a room, or the extent of open ground.
    pub architecture: Option<Architecture>,
    /// What surrounds the scene.
    pub backdrop: Backdrop,
    /// Hide every wall whose outer side faces the camera, so that a camera outside the room
    /// sees into it like an interior photograph (default `true`).
    pub cut_away_walls: bool,
    /// The materials of the room's surfaces by name (`floor`, `walls`), from the scene's look
    /// ([`SceneLook::surfaces`](scenethesis_scene_graph::SceneLook)), laid as the exporters
    /// lay them ([`scenethesis_materials::surface_or`]); a surface not named here wears the
    /// library's default (oak floorboards, wall paint).
    pub surfaces: BTreeMap<String, Material>,
}

impl RenderScene {
    /// A scene of objects only, on a studio floor.
    pub fn studio(instances: Vec<Instance>) -> Self {
        Self {
            instances,
            architecture: None,
            backdrop: Backdrop::Studio,
            cut_away_walls: true,
            surfaces: BTreeMap::new(),
        }
    }

    /// A scene of objects inside `architecture`; the backdrop follows its environment
    /// (a room gets [`Backdrop::Interior`], open ground [`Backdrop::Sky`]).
    pub fn with_architecture(instances: Vec<Instance>, architecture: Architecture) -> Self {
        let backdrop = match architecture.environment {
            Environment::Indoor => Backdrop::Interior,
            Environment::Outdoor => Backdrop::Sky,
        };
        Self {
            instances,
            architecture: Some(architecture),
            backdrop,
            cut_away_walls: true,
            surfaces: BTreeMap::new(),
        }
    }

    /// The render scene of a scene graph: every object whose id `meshes` holds, with that
    /// asset-frame mesh at the object's pose and its moving parts at their joints' states
    /// ([`Mesh::with_joint_states`]), in the scene's architecture (in scene order;
    /// objects without a mesh are left out). The one conversion from a [`Scene`]: meshes held
    /// by value are shared into the scene, meshes already shared (`Arc<Mesh>`) are not copied.
    ///
    /// ```
    /// use std::collections::BTreeMap;
    /// use scenethesis_render::RenderScene;
    /// use scenethesis_scene_graph::{Architecture, Mesh, Scene};
    ///
    /// let scene = Scene::new(Architecture::rectangular_room(4.0, 3.0, 2.5, 0.9));
    /// let empty = RenderScene::from_scene(&scene, &BTreeMap::<String, Mesh>::new());
    /// assert!(empty.instances.is_empty() && empty.architecture.is_some());
    /// ```
    pub fn from_scene<M>(scene: &Scene, meshes: &BTreeMap<String, M>) -> Self
    where
        M: Clone + Into<Arc<Mesh>>,
    {
        let instances = scene
            .objects
            .iter()
            .filter_map(|o| {
                let mut mesh: Arc<Mesh> = meshes.get(&o.id)?.clone().into();
                if o.joints.iter().any(|j| j.state != 0.0) {
                    mesh = Arc::new(mesh.with_joint_states(&o.joints));
                }
                Some(Instance::new(o.id.clone(), mesh, o.pose))
            })
            .collect();
        let mut render = Self::with_architecture(instances, scene.architecture.clone());
        render.surfaces = scene.look.surfaces.clone();
        render
    }

    /// The box around every object, or `None` when no object has geometry.
    pub fn objects_bounds(&self) -> Option<Aabb> {
        self.instances
            .iter()
            .filter_map(Instance::world_bounds)
            .reduce(|a, b| a.union(&b))
    }

    /// The box around the objects, the floor and the walls: what views frame and shadows
    /// cover. A scene with nothing gives a 1 m box at the origin.
    pub fn bounds(&self) -> Aabb {
        let mut bounds = self.objects_bounds();
        if let Some(arch) = &self.architecture {
            let floor = Aabb::new(
                Point3::new(arch.floor.min.x, 0.0, arch.floor.min.y),
                Point3::new(arch.floor.max.x, 0.0, arch.floor.max.y),
            );
            let mut all = bounds.map_or(floor, |b| b.union(&floor));
            for wall in &arch.walls {
                all = all.union(&wall.aabb());
            }
            bounds = Some(all);
        }
        bounds
            .unwrap_or_else(|| Aabb::new(Point3::new(-0.5, 0.0, -0.5), Point3::new(0.5, 1.0, 0.5)))
    }
}
