//! Stage 2 of the method: a [`Plan`] becomes an initial scene graph with poses.

mod assemble;
mod candidates;
mod geometry;
mod grow;
mod lookup;
mod place_floor;
mod procedural;
mod room;
mod runs;
mod shared;
mod surfaces;
mod walkway;

pub use lookup::{CatalogAssets, NominalAssets};
pub use procedural::ProceduralGuide;
pub use room::room_architecture;

use std::collections::BTreeMap;

use scenethesis_scene_graph::AssetInfo;
use scenethesis_scene_graph::Scene;
use serde::{Deserialize, Serialize};

use crate::plan::{Plan, PlannedObject};

/// Where a guide finds each planned object's asset metadata (size, support surfaces, scale
/// range). Retrieval, the built-in catalog or nominal priors can serve it.
pub trait AssetLookup {
    /// The metadata of the asset for `object`, or `None` when nothing fits.
    fn asset_info(&self, object: &PlannedObject) -> Option<AssetInfo>;
}

/// Assets already chosen per object id (e.g. by retrieval).
impl AssetLookup for BTreeMap<String, AssetInfo> {
    fn asset_info(&self, object: &PlannedObject) -> Option<AssetInfo> {
        self.get(&object.id).cloned()
    }
}

/// An object the guide left out, and why.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct DroppedObject {
    /// The planned object's id.
    pub id: String,
    /// Why it was left out.
    pub reason: String,
}

/// A label of a guidance image whose category the asset library cannot map: it guides
/// nothing, and the report offers the nearest category the library has.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub struct UnmappedLabel {
    /// The label's object id.
    pub id: String,
    /// The category the label names.
    pub category: String,
    /// The library's category nearest to it (by the words it shares, else by spelling), if any.
    pub nearest: Option<String>,
}

/// What a guide adopts from its image before assets are retrieved: objects the image shows
/// that the plan lacks (appended to the plan, parents before children, so they are retrieved,
/// laid out, optimized and judged like planned ones), and labels it could not use.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Adoption {
    /// The objects to add to the plan, each with its support relation from the image.
    pub objects: Vec<PlannedObject>,
    /// Labels whose category the library cannot map.
    pub unmapped: Vec<UnmappedLabel>,
    /// The size each object the image shows appears to have there, by object id (planned and
    /// adopted): `[width, height, depth]` in metres of its box, width the longer side of the
    /// footprint. Retrieval may prefer the asset variant that fits it.
    pub sizes: BTreeMap<String, [f64; 3]>,
    /// The room's size `[x, z]` in metres as the image shows it (its walls), when it differs
    /// from the plan's.
    pub room_size: Option<[f64; 2]>,
    /// What the guide wants said in the run's report.
    pub notes: Vec<String>,
}

impl Adoption {
    /// `plan` with the adopted objects appended (parents come first, as a plan orders them)
    /// and the room the image shows.
    pub fn apply(&self, plan: &Plan) -> Plan {
        let mut plan = plan.clone();
        plan.objects.extend(self.objects.iter().cloned());
        if let Some(size) = self.room_size {
            plan.room_size = size;
        }
        plan
    }
}

/// How walkable the guided floor is, by the raster rules of the metrics.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct WalkwayReport {
    /// Largest free component / all free floor, with the robot radius (Walk).
    pub walk_ratio: f64,
    /// Whether the door is reachable through a walkway of the plan's aisle width.
    pub door_reachable: bool,
    /// Floor objects whose access side the aisle-width walkway does not reach.
    pub unreachable: Vec<String>,
}

/// A guided layout: the scene and a report of what happened.
#[derive(Debug, Clone, PartialEq)]
pub struct GuidedLayout {
    /// The scene graph with initial poses; passes [`Scene::validate`].
    pub scene: Scene,
    /// Planned objects that did not fit.
    pub dropped: Vec<DroppedObject>,
    /// Walkway figures of the final floor.
    pub walkway: WalkwayReport,
    /// What the guide saw, for the optimizer to align the assets to (camera, image, optional
    /// depth, per-object masks). Guides that read no image (the [`ProceduralGuide`]) give
    /// `None`, and the pipeline then optimizes without alignment terms.
    pub guidance: Option<scenethesis_imagery::Guidance>,
    /// What the guide wants said in the run's report (e.g. where a model's answer and the
    /// geometry disagreed, and which was kept).
    pub notes: Vec<String>,
}

/// Why a plan could not be laid out.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GuideError {
    /// The plan names an object the asset lookup cannot provide.
    #[error("object `{id}` (category `{category}`): no asset metadata available")]
    MissingAsset {
        /// The object id.
        id: String,
        /// Its category.
        category: String,
    },
    /// The plan is inconsistent (unknown parent, bad room size, …).
    #[error("invalid plan: {0}")]
    InvalidPlan(String),
    /// Nothing could be placed on the floor.
    #[error("no floor object of the plan fits a {width} × {depth} m floor")]
    NothingFits {
        /// Floor width (x).
        width: f64,
        /// Floor depth (z).
        depth: f64,
    },
    /// A provider failed (vision guides: image generation, segmentation, depth).
    #[error("guide provider `{provider}` failed: {message}")]
    Provider {
        /// The provider's name.
        provider: String,
        /// What went wrong.
        message: String,
    },
}

/// Stage 2: lays out a [`Plan`] as a scene graph rooted at the ground, with initial poses that
/// the optimizer then makes exact.
///
/// The offline [`ProceduralGuide`] places objects by rules; a vision guide implements the same
/// trait by generating a guidance image for the plan's description, segmenting it, lifting the
/// masks with depth to 3D boxes and matching them to the planned objects. The same plan,
/// assets and seed must give the identical scene.
///
/// Laying out a small plan with the offline guide and the nominal (category-prior) assets:
///
/// ```
/// use scenethesis_agents::{Guide, KnowledgePlanner, NominalAssets, PlanRequest, Planner};
///
/// let request = PlanRequest::new("a bedroom with a bed", ["bed", "nightstand"], 0);
/// let plan = KnowledgePlanner::new().plan(&request).unwrap();
/// let guide: &dyn Guide = &scenethesis_agents::ProceduralGuide::default();
/// let layout = guide.layout(&plan, &NominalAssets::default(), 0).unwrap();
/// assert!(layout.scene.validate().is_ok());
/// assert!(layout.scene.objects.iter().any(|object| object.category == "bed"));
/// ```
pub trait Guide: Send + Sync {
    /// A short name for reports (`report.json` records it).
    fn name(&self) -> &str;

    /// Lays out `plan` with the assets' metadata, seeded by `seed`.
    fn layout(
        &self,
        plan: &Plan,
        assets: &dyn AssetLookup,
        seed: u64,
    ) -> Result<GuidedLayout, GuideError>;

    /// What the guide's image shows beyond `plan`, to add to it before assets are retrieved.
    /// Guides that read no image adopt nothing (the default).
    fn adopt(&self, plan: &Plan, seed: u64) -> Result<Adoption, GuideError> {
        let _ = (plan, seed);
        Ok(Adoption::default())
    }
}
