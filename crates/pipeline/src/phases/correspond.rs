//! Correspond: when the guide produced guidance and a matcher is configured, every object the
//! guidance shows is matched against its mask and depth and its pose aligned (the stage itself
//! is [`scenethesis_correspondence::correspond`]; this phase hands it the retrieved meshes and
//! scale ranges); the aligned poses replace the guide's and the final matches become the
//! optimizer's pose-alignment term (stage 1 of its two stages).

use std::collections::BTreeMap;

use scenethesis_correspondence::{kept_lift, GuidedSettings, KeptLift, Matcher, PoseAlignment};
use scenethesis_imagery::Guidance;
use scenethesis_scene_graph::Scene;

use super::retrieve::{AssetCache, Retrieved};
use crate::{GenerateOptions, PipelineError};

/// What the correspond phase hands on: the correspondences per aligned object (the
/// optimizer's alignment term) and the objects that kept their raw lift, with why.
#[derive(Default)]
pub(crate) struct Aligned {
    pub(crate) alignments: BTreeMap<String, PoseAlignment>,
    pub(crate) kept_lift: Vec<KeptLift>,
}

/// Aligns `scene`'s poses to `guidance` in place (its depth taken as metric).
pub(crate) fn correspond(
    scene: &mut Scene,
    guidance: &Guidance,
    retrieved: &Retrieved,
    cache: &mut AssetCache,
    matcher: &dyn Matcher,
    settings: &GuidedSettings,
    options: &GenerateOptions,
) -> Result<Aligned, PipelineError> {
    let mut meshes = BTreeMap::new();
    let mut ranges = BTreeMap::new();
    for object in &scene.objects {
        let Some(key) = retrieved.chosen.get(&object.id) else {
            continue;
        };
        ranges.insert(
            object.id.clone(),
            cache.prepared(key, &options.prepare)?.scale_range(),
        );
        meshes.insert(object.id.clone(), cache.asset(key).mesh.clone());
    }
    let guided = scenethesis_correspondence::correspond(
        scene, &meshes, &ranges, guidance, 1.0, matcher, settings,
    );
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
