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
    scenethesis_eval::EvalScene {
        objects: support::stocked_shelf(0.0, 0.0),
        architecture: scenethesis_scene_graph::Architecture::open_ground(6.0, 6.0),
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
