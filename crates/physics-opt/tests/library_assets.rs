//! Real procedural library assets: a bookshelf filled with books, a dining table with mugs and
//! books, chairs around it — every object starts a little sunk or floating.

mod support;

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use scenethesis_physics_opt::{
    optimize_scene, OptimizeSettings, Optimizer, PrepareSettings, PreparedAsset,
    ProjectedGaussNewton, Sgd,
};
use scenethesis_procedural::catalog;
use scenethesis_scene_graph::{Asset, SurfaceKind};
use scenethesis_scene_graph::{Pose, RelationKind, Scene, SceneObject};
use support::{object, problem};

/// An object that uses a library asset (so the metrics can regenerate its mesh).
fn library_object(
    id: &str,
    parent: Option<&str>,
    support: RelationKind,
    asset: &(Asset, Arc<PreparedAsset>),
    pose: Pose,
) -> SceneObject {
    let mut o = object(id, parent, support, &asset.1, pose);
    o.asset = asset.0.info.source.clone();
    o.category = asset.0.info.category.clone();
    o
}

fn asset(name: &str, seed: u64) -> (Asset, Arc<PreparedAsset>) {
    let category = catalog::category(name).unwrap_or_else(|| panic!("no category {name}"));
    let asset = catalog::generate(category, seed);
    let prepared = PreparedAsset::from_asset(&asset, &PrepareSettings::default()).unwrap();
    (asset, Arc::new(prepared))
}

#[test]
fn library_bookshelf_and_dining_table_are_settled() {
    let shelf_full = asset("bookshelf", 1);
    let table_full = asset("dining_table", 2);
    let book_full = asset("book", 3);
    let mug_full = asset("mug", 4);
    let (shelf_asset, shelf) = (&shelf_full.0, shelf_full.1.clone());
    let (table_asset, table) = (&table_full.0, table_full.1.clone());
    let book = book_full.1.clone();
    let mug = mug_full.1.clone();
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
            library_object(
                "bookshelf",
                None,
                RelationKind::AgainstWall,
                &shelf_full,
                shelf_pose,
            ),
            shelf.clone(),
        ),
        (
            library_object(
                "table",
                None,
                RelationKind::OnFloor,
                &table_full,
                table_pose,
            ),
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
            library_object(
                &id,
                Some("bookshelf"),
                RelationKind::Inside,
                &book_full,
                pose,
            ),
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
            library_object(
                &format!("mug_{i}"),
                Some("table"),
                RelationKind::On,
                &mug_full,
                pose,
            ),
            mug.clone(),
        ));
    }
    let book_pose = Pose::new(1.0, 0.4, Vector3::new(0.8, top_y - 0.01, 0.45));
    objects.push((
        library_object(
            "table_book",
            Some("table"),
            RelationKind::On,
            &book_full,
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
        // The project's own metrics (real meshes regenerated from the library, rigid-body
        // simulation) agree: no collision, nothing in the walls or floor, nothing moves.
        let mut scene: Scene = problem.scene.clone();
        placement.apply_to(&mut scene);
        let metrics = scenethesis_eval::evaluate(
            &scenethesis_eval::EvalScene::from_scene_procedural(&scene).unwrap(),
        );
        let name = &placement.optimizer;
        assert_eq!(metrics.col_o, 0.0, "[{name}] {:?}", metrics.colliding_pairs);
        assert_eq!(
            metrics.col_arch, 0.0,
            "[{name}] {:?}",
            metrics.arch_penetrations
        );
        assert_eq!(metrics.inst_o, 0.0, "[{name}] {:?}", metrics.unstable);
    }
    // The starting layout (books sunk 5 mm into the boards) does collide by the same metric.
    let before = scenethesis_eval::evaluate(
        &scenethesis_eval::EvalScene::from_scene_procedural(&problem.scene).unwrap(),
    );
    assert!(before.col_o > 0.0, "{:?}", before.colliding_pairs);
}
