//! One rule for an object's generator seed: the asset the guide lays a plan out with
//! (`CatalogAssets`, at the scene seed) is the asset retrieval delivers for the same object in
//! round 0 of a run with that seed (variant = the seed), whichever built-in source delivers it.

use scenethesis_agents::{AssetLookup, CatalogAssets, KnowledgePlanner, PlanRequest, Planner};
use scenethesis_procedural::catalog;
use scenethesis_retrieval::{AssetQuery, AssetSource, CatalogSource, RetrievalSource};
use scenethesis_scene_graph::AssetRef;

const PROMPTS: [&str; 3] = [
    "a cozy living room with reading materials",
    "a chemistry laboratory",
    "a living room with a grey three-seat sofa against the back wall, a low round coffee table \
     in front of it with two mugs and a small vase on top, a tall bookshelf in the corner with \
     books and a plant inside its shelves",
];

#[test]
fn the_guide_plans_with_the_asset_retrieval_generates() {
    let categories: Vec<&str> = catalog::categories().map(|c| c.name).collect();
    let retrieval = RetrievalSource::default();
    let mut checked = std::collections::BTreeSet::new();
    for prompt in PROMPTS {
        for seed in [0, 3, 41] {
            let plan = KnowledgePlanner::new()
                .plan(&PlanRequest::new(prompt, categories.iter().copied(), seed))
                .unwrap();
            let guide = CatalogAssets::new(seed);
            for object in &plan.objects {
                let who = format!("{prompt:?} seed {seed}: {}", object.id);
                let planned = guide.asset_info(object).expect("a built-in category");
                let query = AssetQuery::new(&object.id, &object.category);
                let retrieved = retrieval.retrieve(&query, seed).unwrap();
                let generated = CatalogSource.retrieve(&query, seed).unwrap();
                assert_eq!(planned.source, retrieved.info.source, "{who}");
                assert_eq!(planned.source, generated.info.source, "{who}");
                assert!(matches!(
                    &planned.source,
                    AssetRef::Procedural { seed: s, .. }
                        if *s == catalog::object_seed(&object.id, seed)
                ));
                // The box the guide plans with is the box of the mesh the scene will hold.
                let bounds = retrieved.mesh.bounds().expect("a mesh").size();
                for k in 0..3 {
                    assert!(
                        (bounds[k] as f32 - planned.size[k]).abs() < 1e-4,
                        "{who}: size[{k}] planned {} but the mesh spans {}",
                        planned.size[k],
                        bounds[k]
                    );
                }
                assert_eq!(
                    planned.support_surfaces, retrieved.info.support_surfaces,
                    "{who}"
                );
                checked.insert(object.category.clone());
            }
        }
    }
    assert!(checked.len() >= 20, "categories checked: {checked:?}");
}
