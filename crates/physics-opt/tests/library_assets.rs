//! Real procedural library assets: a bookshelf filled with books, a dining table with mugs and
//! books, chairs around it — every object starts a little sunk or floating.

mod support;

use std::sync::Arc;

use nalgebra::{Point3, Vector3};
use scenethesis_physics_opt::{
    optimize_scene, OptimizeSettings, Optimizer, Placement, PrepareSettings, PreparedAsset,
    ProjectedGaussNewton, SceneProblem, Sgd,
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

/// The four library assets of the room.
struct Library {
    shelf: (Asset, Arc<PreparedAsset>),
    table: (Asset, Arc<PreparedAsset>),
    book: (Asset, Arc<PreparedAsset>),
    mug: (Asset, Arc<PreparedAsset>),
}

#[test]
fn library_bookshelf_and_dining_table_are_settled() {
    let library = Library {
        shelf: asset("bookshelf", 1),
        table: asset("dining_table", 2),
        book: asset("book", 3),
        mug: asset("mug", 4),
    };
    let (problem, expected_surface) = furnished_room(&library);
    let optimizers: Vec<Box<dyn Optimizer>> = vec![
        Box::new(ProjectedGaussNewton::default()),
        Box::new(Sgd::default()),
    ];
    for opt in optimizers {
        let placement =
            optimize_scene(&problem, opt.as_ref(), &OptimizeSettings::default()).unwrap();
        check_settled(&problem, &placement, &expected_surface);
    }
    // The starting layout (books sunk 5 mm into the boards) does collide by the same metric.
    let before = scenethesis_eval::evaluate(
        &scenethesis_eval::EvalScene::from_scene_procedural(&problem.scene).unwrap(),
    );
    assert!(before.col_o > 0.0, "{:?}", before.colliding_pairs);
}

/// A 6 × 4 m room (back wall at z = −2): the bookshelf against the back wall with a book sunk
/// 5 mm into each shelf board, the dining table with two mugs floating 1 cm above its top and
/// a turned book sunk 1 cm into it. Returns the problem and each shelf book's expected surface.
fn furnished_room(library: &Library) -> (SceneProblem, Vec<(String, String)>) {
    let shelf_depth = library.shelf.0.info.size[2] as f64;
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
                &library.shelf,
                shelf_pose,
            ),
            library.shelf.1.clone(),
        ),
        (
            library_object(
                "table",
                None,
                RelationKind::OnFloor,
                &library.table,
                table_pose,
            ),
            library.table.1.clone(),
        ),
    ];
    let expected_surface = shelf_books(library, &shelf_pose, &mut objects);
    table_items(library, &mut objects);
    (problem("bookshelf", objects), expected_surface)
}

/// A book sunk 5 mm into each shelf board of the bookshelf at `shelf_pose`; returns each
/// book's id and the surface it should rest on.
fn shelf_books(
    library: &Library,
    shelf_pose: &Pose,
    objects: &mut Vec<(SceneObject, Arc<PreparedAsset>)>,
) -> Vec<(String, String)> {
    let mut expected_surface = Vec::new();
    for (i, s) in library
        .shelf
        .0
        .info
        .support_surfaces
        .iter()
        .filter(|s| s.kind == SurfaceKind::Shelf)
        .enumerate()
    {
        let c = s.center();
        let at =
            shelf_pose.transform_point(&Point3::new(c[0] as f64, s.height as f64, c[1] as f64));
        let pose = Pose::new(1.0, 0.0, at.coords - Vector3::new(0.0, 0.005, 0.0));
        let id = format!("book_{i}");
        objects.push((
            library_object(
                &id,
                Some("bookshelf"),
                RelationKind::Inside,
                &library.book,
                pose,
            ),
            library.book.1.clone(),
        ));
        expected_surface.push((id, s.name.clone()));
    }
    assert!(
        !expected_surface.is_empty(),
        "the bookshelf has no shelf surfaces"
    );
    expected_surface
}

/// Two mugs 1 cm above the table top and a turned book 1 cm into it.
fn table_items(library: &Library, objects: &mut Vec<(SceneObject, Arc<PreparedAsset>)>) {
    let top = library
        .table
        .0
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
                &library.mug,
                pose,
            ),
            library.mug.1.clone(),
        ));
    }
    let book_pose = Pose::new(1.0, 0.4, Vector3::new(0.8, top_y - 0.01, 0.45));
    objects.push((
        library_object(
            "table_book",
            Some("table"),
            RelationKind::On,
            &library.book,
            book_pose,
        ),
        library.book.1.clone(),
    ));
}

/// Every post-condition holds, each shelf book rests on its shelf within 2 mm, and the
/// project's own metrics (real meshes regenerated from the library, rigid-body simulation)
/// agree: no collision, nothing in the walls or floor, nothing moves.
fn check_settled(
    problem: &SceneProblem,
    placement: &Placement,
    expected_surface: &[(String, String)],
) {
    let failures: Vec<String> = placement.failures().map(|o| o.to_string()).collect();
    assert!(
        failures.is_empty(),
        "[{}] {failures:#?}",
        placement.optimizer
    );
    for (id, surface) in expected_surface {
        let report = placement.object(id).unwrap();
        assert_eq!(&report.support.plane().unwrap().surface, surface, "{id}");
        let gap = report.support_gap.unwrap();
        assert!(
            (0.0..=0.002).contains(&gap),
            "[{}] {id} gap {gap}",
            placement.optimizer
        );
    }
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
