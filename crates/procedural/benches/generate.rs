//! Generating every built-in category once per iteration.

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use scenethesis_procedural::catalog;

fn generate_all(c: &mut Criterion) {
    let categories: Vec<_> = catalog::categories().collect();
    let mut group = c.benchmark_group("assets");
    group.throughput(Throughput::Elements(categories.len() as u64));
    group.bench_function("generate_all_categories", |b| {
        let mut seed = 0u64;
        b.iter(|| {
            seed += 1;
            let triangles: usize = categories
                .iter()
                .map(|c| catalog::generate(c, seed).mesh.triangle_count())
                .sum();
            std::hint::black_box(triangles)
        })
    });
    group.finish();
}

criterion_group!(benches, generate_all);
criterion_main!(benches);
