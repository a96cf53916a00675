//! Correspond: when the guide produced guidance and a matcher is configured, every object the
//! guidance shows is matched against its mask and depth and its pose aligned (the stage itself
//! is [`scenethesis_correspondence::correspond`]; this phase hands it the retrieved meshes and
//! scale ranges); the aligned poses replace the guide's and the final matches become the
//! optimizer's pose-alignment term (stage 1 of its two stages).

use std::collections::BTreeMap;

use scenethesis_correspondence::{
    facing_hint, kept_lift, GuidedPose, GuidedSettings, KeptLift, Matcher, PoseAlignment,
};
use scenethesis_imagery::{Guidance, Mask};
use scenethesis_scene_graph::{Scene, SceneObject};

use super::retrieve::{AssetCache, AssetKey, Retrieved};
use crate::{GenerateOptions, PipelineError};

/// What the correspond phase hands on: the correspondences per aligned object (the
/// optimizer's alignment term) and the objects that kept their raw lift, with why.
#[derive(Default)]
pub(crate) struct Aligned {
    pub(crate) alignments: BTreeMap<String, PoseAlignment>,
    pub(crate) kept_lift: Vec<KeptLift>,
}

/// Alignments made in earlier rounds of a run, for the re-plan rounds: an alignment is a
/// function of the guidance picture (camera, image, depth), the object's mask, and its
/// asset, starting pose, scale range and facing hint, so an object whose inputs are all as
/// they were keeps its alignment instead of redoing it (a re-plan that moves or drops two
/// objects leaves the others' starts and masks untouched).
#[derive(Default)]
pub(crate) struct AlignmentMemo {
    /// The guidance the alignments were made against; another picture forgets them.
    guidance: Option<Guidance>,
    /// The alignments that finished in time, by their inputs, with the mask each was made
    /// against.
    done: BTreeMap<AlignmentInputs, (Mask, GuidedPose)>,
}

/// Everything one object's alignment depends on besides the guidance and the settings
/// (which stay the same through a run); poses and ranges bit for bit.
#[derive(PartialEq, Eq, PartialOrd, Ord)]
struct AlignmentInputs {
    id: String,
    asset: AssetKey,
    start: [u64; 5],
    scale_range: [u64; 2],
    hint: Option<u64>,
}

impl AlignmentInputs {
    /// The inputs of `object`'s alignment in `scene` with `asset` and `scale_range`.
    fn of(scene: &Scene, object: &SceneObject, asset: &AssetKey, scale_range: [f64; 2]) -> Self {
        Self {
            id: object.id.clone(),
            asset: asset.clone(),
            start: object.pose.to_bits(),
            scale_range: scale_range.map(f64::to_bits),
            hint: facing_hint(scene, object).map(f64::to_bits),
        }
    }
}

impl AlignmentMemo {
    /// Forgets every alignment unless it was made against the picture of `guidance` (its
    /// masks may differ: each alignment is checked against its own).
    fn against(&mut self, guidance: &Guidance) {
        let same = self.guidance.as_ref().is_some_and(|g| {
            g.camera == guidance.camera && g.image == guidance.image && g.depth == guidance.depth
        });
        if !same {
            self.done.clear();
            self.guidance = Some(guidance.clone());
        }
    }

    /// The alignment made with `inputs` against `mask`, if any.
    fn get(&self, inputs: &AlignmentInputs, mask: Option<&Mask>) -> Option<&GuidedPose> {
        let (seen, done) = self.done.get(inputs)?;
        let mask = mask?;
        let same = seen.width() == mask.width()
            && seen.height() == mask.height()
            && seen.pixels().eq(mask.pixels());
        same.then_some(done)
    }
}

/// Aligns `scene`'s poses to `guidance` in place (its depth taken as metric), reusing the
/// alignments in `memo` whose inputs are unchanged and remembering the new ones.
#[allow(clippy::too_many_arguments)]
pub(crate) fn correspond(
    scene: &mut Scene,
    guidance: &Guidance,
    retrieved: &Retrieved,
    cache: &mut AssetCache,
    memo: &mut AlignmentMemo,
    matcher: &dyn Matcher,
    settings: &GuidedSettings,
    options: &GenerateOptions,
) -> Result<Aligned, PipelineError> {
    memo.against(guidance);
    let mut meshes = BTreeMap::new();
    let mut ranges = BTreeMap::new();
    let mut asked = Vec::new();
    let mut guided = BTreeMap::new();
    for object in &scene.objects {
        let Some(key) = retrieved.chosen.get(&object.id) else {
            continue;
        };
        let range = cache.prepared(key, &options.prepare)?.scale_range();
        let inputs = AlignmentInputs::of(scene, object, key, range);
        if let Some(done) = memo.get(&inputs, guidance.masks.get(&object.id)) {
            guided.insert(object.id.clone(), done.clone());
            continue;
        }
        ranges.insert(object.id.clone(), range);
        meshes.insert(object.id.clone(), cache.asset(key).mesh.clone());
        asked.push(inputs);
    }
    let reused = guided.len();
    let fresh = scenethesis_correspondence::correspond(
        scene, &meshes, &ranges, guidance, 1.0, matcher, settings,
    );
    for inputs in asked {
        let done = fresh.get(&inputs.id).filter(|g| !g.out_of_time);
        if let (Some(g), Some(mask)) = (done, guidance.masks.get(&inputs.id)) {
            memo.done.insert(inputs, (mask.clone(), g.clone()));
        }
    }
    tracing::debug!(reused, aligned = fresh.len(), "alignments");
    guided.extend(fresh);
    let late: Vec<String> = guided
        .iter()
        .filter(|(_, g)| g.out_of_time)
        .map(|(id, _)| scenethesis_scene_graph::printable(id).into_owned())
        .collect();
    if !late.is_empty() {
        tracing::warn!(
            "the alignment time budget ({} s) ran out: {} kept the best pose found in time",
            settings.time_budget,
            late.join(", ")
        );
    }
    for object in &mut scene.objects {
        if let Some(g) = guided.get(&object.id) {
            object.pose = g.pose;
        }
    }
    Ok(Aligned {
        kept_lift: kept_lift(&guided),
        alignments: guided
            .into_iter()
            .map(|(id, g)| (id, g.alignment))
            .collect(),
    })
}
