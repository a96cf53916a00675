//! The paper's ablation of the physics-aware optimization, measured against ground truth
//! instead of judged by a language model: a saved scene's guidance is rendered and perturbed
//! as in the round trip ([`crate::roundtrip`]), lifted to boxes, and the recovered objects are
//! posed four ways —
//!
//! 1. `raw`: each true asset placed in its lifted box (yaw from the box, scale from the
//!    median ratio of box to asset extents, centre on the box's);
//! 2. `alignment`: after the correspond stage ([`scenethesis_correspondence::correspond`]: yaw
//!    hypotheses, shape matching against mask and depth, matches refreshed while the pose
//!    moves; an object whose raw lift agrees with the image better than its fitted pose keeps
//!    the lift, listed in [`AblationReport::kept_lift`]);
//! 3. `collision`: after the optimizer's alignment stage and a physics stage that only resolves
//!    collisions ([`ProjectedGaussNewton::stability`] off);
//! 4. `stability`: after the full optimizer (collision and stability).
//!
//! Each row reports the medians over recovered objects of the translation error (box centre),
//! the yaw error (modulo the asset's footprint symmetry), the relative scale error and the 3D
//! IoU with the true box, and the scene's Col-O and Inst-O (`scenethesis-eval`) over the
//! recovered objects. The scene graph (who supports whom) is the scene's own, as a plan would
//! give it; objects whose parent was not recovered rest on the floor.

use std::collections::{BTreeMap, BTreeSet};
use std::sync::Arc;

use scenethesis_correspondence::{correspond, kept_lift, GuidedSettings, KeptLift, ShapeMatcher};
use scenethesis_eval::{evaluate_with_cache, DecompositionCache, EvalObject, EvalScene};
use scenethesis_imagery::Guidance;
use scenethesis_import::AssetResolver;
use scenethesis_physics_opt::{
    optimize_scene, OptimizeSettings, PrepareSettings, PreparedAsset, ProjectedGaussNewton,
    SceneProblem,
};
use scenethesis_render::Renderer;
use scenethesis_scene_graph::{Mesh, ParentRef, Pose, Scene};
use scenethesis_vision::boxes::DepthSource;
use scenethesis_vision::{lift_scene, LiftOptions, LiftedBox};
use serde::{Deserialize, Serialize};

use crate::roundtrip::{
    median, perturbed_guidance, true_boxes, yaw_error, yaw_symmetry, RoundtripError,
    RoundtripOptions,
};

/// The four rows of the ablation.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum AblationStage {
    /// The raw lift.
    Raw,
    /// + pose alignment (the correspond stage).
    Alignment,
    /// + the collision loss.
    Collision,
    /// + the stability loss (the full optimizer).
    Stability,
}

/// One row of the ablation.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AblationRow {
    /// Which poses.
    pub stage: AblationStage,
    /// Median distance between the posed and true box centres, metres.
    pub translation_median_m: f64,
    /// Median yaw error, degrees, modulo the asset's footprint symmetry.
    pub yaw_median_deg: f64,
    /// Median relative scale error `|s / s_true − 1|`.
    pub scale_error_median: f64,
    /// Median 3D IoU of the posed and true boxes.
    pub iou_median: f64,
    /// Colliding objects / objects.
    pub col_o: f64,
    /// Unstable objects / objects simulated.
    pub inst_o: f64,
}

/// One recovered object's distance from its true box centre after each stage.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectErrors {
    /// The object.
    pub id: String,
    /// Metres, per stage: raw, alignment, collision, stability.
    pub translation_m: [f64; 4],
}

/// The ablation of one scene: `{"rows": [...], "objects": [...], "kept_lift": [...]}`.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AblationReport {
    /// Raw, alignment, collision and stability, in that order.
    pub rows: Vec<AblationRow>,
    /// Every recovered object's translation error per stage, by id.
    #[serde(default)]
    pub objects: Vec<ObjectErrors>,
    /// The objects whose raw lift the alignment kept, with why.
    #[serde(default)]
    pub kept_lift: Vec<KeptLift>,
}

/// Why an ablation failed.
#[derive(Debug, thiserror::Error)]
pub enum AblationError {
    /// Rendering or lifting the guidance failed.
    #[error(transparent)]
    Roundtrip(#[from] RoundtripError),
    /// An object's asset could not be resolved.
    #[error("object `{id}`: cannot resolve its asset: {reason}")]
    Asset {
        /// The object.
        id: String,
        /// Why.
        reason: String,
    },
    /// The optimizer refused the scene.
    #[error("cannot optimize the recovered scene")]
    Optimize(#[source] scenethesis_physics_opt::PhysicsOptError),
}

/// Renders, perturbs and lifts `scene`'s guidance, then measures the four stages.
pub fn ablation(
    renderer: &Renderer,
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    options: &RoundtripOptions,
) -> Result<AblationReport, AblationError> {
    let guidance = perturbed_guidance(renderer, scene, meshes, options)?;
    ablate(scene, meshes, &guidance)
}

/// The pose that puts an asset with asset-frame bounds `aabb` into lifted box `b`.
fn pose_in_box(b: &LiftedBox, aabb: &scenethesis_scene_graph::Aabb) -> Pose {
    let size = aabb.size();
    let ratio = |m: f64, t: f64| if t > 1e-3 { Some(m / t) } else { None };
    let full = b.size();
    let mut r: Vec<f64> = [
        ratio(full.x, size.x),
        ratio(full.y, size.y),
        ratio(full.z, size.z),
    ]
    .into_iter()
    .flatten()
    .collect();
    let scale = if r.is_empty() {
        1.0
    } else {
        median(std::mem::take(&mut r))
    };
    let pose = Pose::new(scale, b.yaw, nalgebra::Vector3::zeros());
    let offset = pose.transform_point(&aabb.center()).coords;
    Pose::new(scale, b.yaw, b.center.coords - offset)
}

/// The ablation of `scene` from (perturbed) `guidance`, with the scene's own meshes as the
/// retrieved assets.
pub fn ablate(
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    guidance: &Guidance,
) -> Result<AblationReport, AblationError> {
    let truth = true_boxes(scene, meshes);
    let lift_options = LiftOptions {
        priors: truth.iter().map(|(id, b)| (id.clone(), b.size())).collect(),
        ..LiftOptions::default()
    };
    let lifted = lift_scene(guidance, &lift_options).map_err(RoundtripError::Lift)?;
    // Raw poses of the recovered objects.
    let mut raw: BTreeMap<String, Pose> = BTreeMap::new();
    for b in &lifted.boxes {
        if let Some(aabb) = meshes.get(&b.id).and_then(|m| m.bounds()) {
            if scene.object(&b.id).is_some() {
                raw.insert(b.id.clone(), pose_in_box(b, &aabb));
            }
        }
    }
    let recovered = recovered_scene(scene, &raw);
    // Assets (for scale ranges, support surfaces and placement).
    let mut resolver = AssetResolver::new();
    let mut prepared: BTreeMap<String, Arc<PreparedAsset>> = BTreeMap::new();
    let mut by_object: BTreeMap<String, Arc<PreparedAsset>> = BTreeMap::new();
    for o in &recovered.objects {
        let key = o.asset.to_string();
        let prep = match prepared.get(&key) {
            Some(p) => p.clone(),
            None => {
                let asset = resolver.asset(&o.asset).map_err(|e| AblationError::Asset {
                    id: o.id.clone(),
                    reason: e.to_string(),
                })?;
                let p = Arc::new(
                    PreparedAsset::from_asset(&asset, &PrepareSettings::default())
                        .map_err(AblationError::Optimize)?,
                );
                prepared.insert(key, p.clone());
                p
            }
        };
        by_object.insert(o.id.clone(), prep);
    }
    let ranges: BTreeMap<String, [f64; 2]> = by_object
        .iter()
        .map(|(id, p)| (id.clone(), p.scale_range()))
        .collect();
    let guided = correspond(
        &recovered,
        meshes,
        &ranges,
        guidance,
        lifted.depth_scale,
        &ShapeMatcher::default(),
        &GuidedSettings::default(),
    );
    let mut aligned = raw.clone();
    for (id, g) in &guided {
        aligned.insert(id.clone(), g.pose);
    }
    let aligned_scene = with_poses(&recovered, &aligned);
    let optimize = |stability: bool| -> Result<BTreeMap<String, Pose>, AblationError> {
        let mut problem = SceneProblem::new(aligned_scene.clone());
        for (id, p) in &by_object {
            problem.set_asset(id, p.clone());
        }
        for (id, g) in &guided {
            problem.set_alignment(id, g.alignment.clone());
        }
        let optimizer = ProjectedGaussNewton {
            stability,
            ..ProjectedGaussNewton::default()
        };
        let placement = optimize_scene(&problem, &optimizer, &OptimizeSettings::default())
            .map_err(AblationError::Optimize)?;
        Ok(placement
            .objects
            .iter()
            .map(|r| (r.id.clone(), r.pose))
            .collect())
    };
    let collision = optimize(false)?;
    let stability = optimize(true)?;
    let cache = DecompositionCache::new();
    let stages = [
        (AblationStage::Raw, &raw),
        (AblationStage::Alignment, &aligned),
        (AblationStage::Collision, &collision),
        (AblationStage::Stability, &stability),
    ];
    let mut objects: BTreeMap<String, [f64; 4]> = BTreeMap::new();
    let mut rows = Vec::new();
    for (k, (stage, poses)) in stages.into_iter().enumerate() {
        let poses: BTreeMap<String, Pose> = poses
            .iter()
            .filter(|(id, _)| recovered.object(id).is_some())
            .map(|(id, p)| (id.clone(), *p))
            .collect();
        let errors = pose_errors(scene, meshes, &poses);
        for (id, e) in &errors {
            objects.entry(id.clone()).or_insert([f64::NAN; 4])[k] = e.translation;
        }
        rows.push(row(stage, &errors, &recovered, meshes, &poses, &cache));
    }
    Ok(AblationReport {
        rows,
        objects: objects
            .into_iter()
            .map(|(id, translation_m)| ObjectErrors { id, translation_m })
            .collect(),
        kept_lift: kept_lift(&guided),
    })
}

/// The scene restricted to the objects in `poses` whose whole support chain is among them,
/// posed by them; relations to dropped objects are removed. (An object whose supporting parent
/// was not recovered has nothing to rest on, so its collision and stability rows would measure
/// the missing parent, not the optimizer.)
fn recovered_scene(scene: &Scene, poses: &BTreeMap<String, Pose>) -> Scene {
    let mut kept: BTreeSet<String> = poses.keys().cloned().collect();
    loop {
        let before = kept.len();
        for o in &scene.objects {
            if let ParentRef::Object(p) = &o.parent {
                if !kept.contains(p) {
                    kept.remove(&o.id);
                }
            }
        }
        if kept.len() == before {
            break;
        }
    }
    let mut out = scene.clone();
    out.objects.retain(|o| kept.contains(&o.id));
    for o in &mut out.objects {
        o.relations
            .retain(|r| kept.contains(&r.target) || scene.object(&r.target).is_none());
    }
    if out.anchor.as_ref().is_some_and(|a| !kept.contains(a)) {
        out.anchor = None;
    }
    with_poses(&out, poses)
}

fn with_poses(scene: &Scene, poses: &BTreeMap<String, Pose>) -> Scene {
    let mut out = scene.clone();
    for o in &mut out.objects {
        if let Some(p) = poses.get(&o.id) {
            o.pose = *p;
        }
    }
    out
}

/// One object's pose errors against the truth.
struct PoseError {
    translation: f64,
    yaw_deg: f64,
    scale: f64,
    iou: f64,
}

/// The pose errors against `truth` of every object in `poses` that the truth has.
fn pose_errors(
    truth: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    poses: &BTreeMap<String, Pose>,
) -> BTreeMap<String, PoseError> {
    let boxes = true_boxes(truth, meshes);
    let mut out = BTreeMap::new();
    for (id, pose) in poses {
        let (Some(object), Some(mesh), Some(tb)) =
            (truth.object(id), meshes.get(id), boxes.get(id))
        else {
            continue;
        };
        let Some(aabb) = mesh.bounds() else { continue };
        let center = pose.transform_point(&aabb.center());
        let period = yaw_symmetry(mesh);
        let posed = LiftedBox {
            id: id.clone(),
            center,
            half_extents: aabb.size() * pose.scale / 2.0,
            yaw: pose.yaw,
            points: 0,
            depth_source: DepthSource::Measured,
            completed: false,
            seen_height: aabb.size().y * pose.scale,
        };
        let error = PoseError {
            translation: (center - tb.center).norm(),
            yaw_deg: if period > 0.0 {
                yaw_error(pose.yaw, object.pose.yaw, period)
            } else {
                0.0
            },
            scale: (pose.scale / object.pose.scale - 1.0).abs(),
            iou: posed.iou(tb),
        };
        out.insert(id.clone(), error);
    }
    out
}

/// One row: the medians of `errors` and Col-O / Inst-O of `recovered` posed by `poses`.
fn row(
    stage: AblationStage,
    errors: &BTreeMap<String, PoseError>,
    recovered: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    poses: &BTreeMap<String, Pose>,
    cache: &DecompositionCache,
) -> AblationRow {
    let of = |f: fn(&PoseError) -> f64| median(errors.values().map(f).collect());
    let scene = with_poses(recovered, poses);
    let eval = EvalScene {
        objects: scene
            .objects
            .iter()
            .filter_map(|o| Some(EvalObject::from_scene_object(o, meshes.get(&o.id)?)))
            .collect(),
        architecture: scene.architecture.clone(),
    };
    let metrics = evaluate_with_cache(&eval, cache);
    AblationRow {
        stage,
        translation_median_m: of(|e| e.translation),
        yaw_median_deg: of(|e| e.yaw_deg),
        scale_error_median: of(|e| e.scale),
        iou_median: of(|e| e.iou),
        col_o: metrics.col_o,
        inst_o: metrics.inst_o,
    }
}
