//! Real procedural library assets: a bookshelf filled with books, a dining table with mugs and
//! books, chairs around it — every object starts a little sunk or floating.

mod support;

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use scenethesis_assets::{catalog, Asset, SurfaceKind};
use scenethesis_physics_opt::{
    optimize_scene, OptimizeSettings, Optimizer, PrepareSettings, PreparedAsset,
    ProjectedGaussNewton, Sgd,
};
use scenethesis_scene_graph::{Pose, RelationKind};
use support::{object, problem};

fn asset(name: &str, seed: u64) -> (Asset, Arc<PreparedAsset>) {
    let category = catalog::category(name).unwrap_or_else(|| panic!("no category {name}"));
    let asset = catalog::generate(category, seed);
    let prepared = PreparedAsset::from_asset(&asset, &PrepareSettings::default()).unwrap();
    (asset, Arc::new(prepared))
}

#[test]
fn library_bookshelf_and_dining_table_are_settled() {
    let (shelf_asset, shelf) = asset("bookshelf", 1);
    let (table_asset, table) = asset("dining_table", 2);
    let (_, book) = asset("book", 3);
    let (_, mug) = asset("mug", 4);
    // The 6 × 4 m room's back wall is at z = −2.
    let shelf_depth = shelf_asset.info.size[2] as f64;
    let shelf_pose = Pose::new(
        1.0,
        0.0,
        Vector3::new(-1.5, 0.0, -2.0 + shelf_depth / 2.0 + 0.01),
    );
    let table_pose = Pose::new(1.0, 0.0, Vector3::new(0.8, 0.0, 0.3));
    let mut objects = vec![
        (
            object(
                "bookshelf",
                None,
                RelationKind::AgainstWall,
                &shelf,
                shelf_pose,
            ),
            shelf.clone(),
        ),
        (
            object("table", None, RelationKind::OnFloor, &table, table_pose),
            table.clone(),
        ),
    ];
    let mut expected_surface = Vec::new();
    for (i, s) in shelf_asset
        .info
        .support_surfaces
        .iter()
        .filter(|s| s.kind == SurfaceKind::Shelf)
        .enumerate()
    {
        let c = s.center();
        let at =
            shelf_pose.transform_point(&Point3::new(c[0] as f64, s.height as f64, c[1] as f64));
        // Sunk 5 mm into the board.
        let pose = Pose::new(1.0, 0.0, at.coords - Vector3::new(0.0, 0.005, 0.0));
        let id = format!("book_{i}");
        objects.push((
            object(&id, Some("bookshelf"), RelationKind::Inside, &book, pose),
            book.clone(),
        ));
        expected_surface.push((id, s.name.clone()));
    }
    assert!(
        !expected_surface.is_empty(),
        "the bookshelf has no shelf surfaces"
    );
    let top = table_asset
        .info
        .support_surfaces
        .iter()
        .find(|s| s.kind == SurfaceKind::Top)
        .expect("a table top");
    let top_y = top.height as f64;
    for (i, dx) in [-0.25, 0.25].into_iter().enumerate() {
        let pose = Pose::new(1.0, 0.0, Vector3::new(0.8 + dx, top_y + 0.01, 0.3));
        objects.push((
            object(
                &format!("mug_{i}"),
                Some("table"),
                RelationKind::On,
                &mug,
                pose,
            ),
            mug.clone(),
        ));
    }
    let book_pose = Pose::new(1.0, 0.4, Vector3::new(0.8, top_y - 0.01, 0.45));
    objects.push((
        object(
            "table_book",
            Some("table"),
            RelationKind::On,
            &book,
            book_pose,
        ),
        book.clone(),
    ));
    let problem = problem("bookshelf", objects);
    let optimizers: Vec<Box<dyn Optimizer>> = vec![
        Box::new(ProjectedGaussNewton::default()),
        Box::new(Sgd::default()),
    ];
    for opt in optimizers {
        let placement =
            optimize_scene(&problem, opt.as_ref(), &OptimizeSettings::default()).unwrap();
        let failures: Vec<String> = placement.failures().map(|o| o.to_string()).collect();
        assert!(
            failures.is_empty(),
            "[{}] {failures:#?}",
            placement.optimizer
        );
        for (id, surface) in &expected_surface {
            let report = placement.object(id).unwrap();
            assert_eq!(&report.support.plane().unwrap().surface, surface, "{id}");
            let gap = report.support_gap.unwrap();
            assert!(
                (0.0..=0.002).contains(&gap),
                "[{}] {id} gap {gap}",
                placement.optimizer
            );
        }
    }
}
