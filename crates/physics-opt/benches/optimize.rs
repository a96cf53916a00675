//! Whole-scene optimization of a 30-object room with each optimizer (target: under 0.5 s on one
//! core). Throughput is objects per second.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use scenethesis_physics_opt::{
    optimize_scene, OptimizeSettings, Optimizer, ProjectedGaussNewton, Sgd,
};

#[path = "../tests/support/mod.rs"]
mod support;

fn thirty_objects(c: &mut Criterion) {
    let problem = support::thirty_object_room(3);
    let settings = OptimizeSettings::default();
    let optimizers: Vec<Box<dyn Optimizer>> = vec![
        Box::new(Sgd::default()),
        Box::new(ProjectedGaussNewton::default()),
    ];
    let mut group = c.benchmark_group("optimize_30_objects");
    group.sample_size(10);
    group.throughput(Throughput::Elements(problem.scene.objects.len() as u64));
    for optimizer in &optimizers {
        let placement = optimize_scene(&problem, optimizer.as_ref(), &settings).unwrap();
        let failures: Vec<String> = placement.failures().map(|o| o.to_string()).collect();
        eprintln!(
            "{}: {} objects, {} failing {:?}",
            optimizer.name(),
            placement.objects.len(),
            failures.len(),
            failures
        );
        group.bench_function(optimizer.name(), |b| {
            b.iter(|| optimize_scene(&problem, optimizer.as_ref(), &settings).unwrap())
        });
    }
    group.finish();
}

criterion_group!(benches, thirty_objects);
criterion_main!(benches);
