//! Evaluating a furnished 30-object room (collision, stability, walk, reach). Target: < 1 s.
//! And the stability simulation of a shop shelf stocked with cans (the catalog's 24-sided
//! round items on shelf boards), which must settle and end well before the 2 s it may run.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};

#[path = "../tests/support/mod.rs"]
mod support;

fn evaluate_thirty_objects(c: &mut Criterion) {
    let scene = support::thirty_objects();
    let mut group = c.benchmark_group("eval");
    group.sample_size(10);
    group.throughput(Throughput::Elements(scene.objects.len() as u64));
    group.bench_function("evaluate_30_objects", |b| {
        b.iter(|| scenethesis_eval::evaluate(std::hint::black_box(&scene)))
    });
    group.bench_function("collisions_30_objects", |b| {
        b.iter(|| scenethesis_eval::collision::collisions(std::hint::black_box(&scene)))
    });
    let cache = scenethesis_eval::DecompositionCache::new();
    group.bench_function("stability_30_objects", |b| {
        b.iter(|| scenethesis_eval::stability::simulate(std::hint::black_box(&scene), &cache))
    });
    group.bench_function("walk_reach_30_objects", |b| {
        b.iter(|| scenethesis_eval::raster::walk_and_reach(std::hint::black_box(&scene)))
    });
    group.finish();
}

/// A catalog store shelf on the floor with a catalog can every 9 cm along each shelf board.
fn stocked_shelf() -> scenethesis_eval::EvalScene {
    use scenethesis_procedural::catalog;
    use scenethesis_scene_graph::{Architecture, RelationKind, SurfaceKind};
    let generate = |name: &str, seed| {
        let category = catalog::categories()
            .find(|c| c.name == name)
            .unwrap_or_else(|| panic!("the catalog has `{name}`"));
        catalog::generate(category, seed)
    };
    let shelf = generate("store_shelf", 0);
    let can = generate("can", 0);
    let drop = 0.00125;
    let mut objects = vec![support::place(
        "store_shelf",
        "store_shelf",
        &shelf.mesh,
        support::at(0.0, drop, 0.0, 0.0),
        None,
        RelationKind::OnFloor,
    )];
    for surface in shelf
        .info
        .support_surfaces
        .iter()
        .filter(|s| matches!(s.kind, SurfaceKind::Shelf | SurfaceKind::Top))
    {
        let xs = surface.polygon.iter().map(|p| p[0]);
        let (x0, x1) = xs.fold((f32::MAX, f32::MIN), |(a, b), x| (a.min(x), b.max(x)));
        let z = surface.center()[1];
        let mut x = x0 + 0.05;
        while x < x1 - 0.05 {
            let id = format!("can_{}", objects.len());
            objects.push(support::place(
                &id,
                "can",
                &can.mesh,
                support::at(x as f64, surface.height as f64 + 2.0 * drop, z as f64, 0.0),
                Some("store_shelf"),
                RelationKind::Inside,
            ));
            x += 0.09;
        }
    }
    scenethesis_eval::EvalScene {
        objects,
        architecture: Architecture::open_ground(6.0, 6.0),
    }
}

fn stability_stocked_shelf(c: &mut Criterion) {
    let scene = stocked_shelf();
    let cache = scenethesis_eval::DecompositionCache::new();
    let report = scenethesis_eval::stability::simulate(&scene, &cache);
    eprintln!(
        "stocked shelf: {} objects, settled after {:.3} s, {} unstable",
        scene.objects.len(),
        report.simulated_seconds,
        report.unstable.len()
    );
    let mut group = c.benchmark_group("eval");
    group.sample_size(10);
    group.throughput(Throughput::Elements(scene.objects.len() as u64));
    group.bench_function("stability_stocked_shelf", |b| {
        b.iter(|| scenethesis_eval::stability::simulate(std::hint::black_box(&scene), &cache))
    });
    group.finish();
}

criterion_group!(benches, evaluate_thirty_objects, stability_stocked_shelf);
criterion_main!(benches);
