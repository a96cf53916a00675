//! Evaluating a furnished 30-object room (collision, stability, walk, reach). Target: < 1 s.

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

criterion_group!(benches, evaluate_thirty_objects);
criterion_main!(benches);
