//! Debug: basket vs side table sizes for the ids of the detailed prompt.
use scenethesis_agents::{AssetLookup, CatalogAssets, KnowledgePlanner, PlanRequest, Planner};
fn main() {
    let planner = KnowledgePlanner::new();
    let available: Vec<String> = scenethesis_assets::catalog::categories().map(|c| c.name.to_owned()).collect();
    let plan = planner.plan(&PlanRequest::new("a cozy living room", available, 3)).unwrap();
    let assets = CatalogAssets::new(3);
    for id in ["basket_0", "side_table_0"] {
        let o = plan.object(id).unwrap();
        let info = assets.asset_info(o).unwrap();
        println!("{id} {:?} {:?}", info.size, info.support_surfaces.iter().map(|s| (&s.name, &s.polygon)).collect::<Vec<_>>());
    }
}
