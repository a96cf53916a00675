//! End-to-end seconds per prompt: the whole offline pipeline (plan, retrieve, guide, optimize,
//! judge with every metric, no previews) on benchmark prompts. Target: median < 2 s in release.

use criterion::{criterion_group, criterion_main, Criterion};
use scenethesis_pipeline::batch::slug;
use scenethesis_pipeline::{GenerateOptions, NoProgress, Pipeline};

/// Short and detailed prompts, indoor and outdoor (some from the public benchmark list).
const PROMPTS: [&str; 6] = [
    "a cozy living room with reading materials",
    "a garage",
    "a bookstore",
    "a peaceful beach during sunset",
    "a gym room",
    "a small office with a desk, a chair and a bookshelf with books",
];

fn end_to_end(c: &mut Criterion) {
    let pipeline = Pipeline::offline();
    let options = GenerateOptions {
        previews: false,
        ..GenerateOptions::default()
    };
    let mut group = c.benchmark_group("end_to_end");
    group.sample_size(10);
    group.warm_up_time(std::time::Duration::from_secs(1));
    for prompt in PROMPTS {
        group.bench_function(slug(prompt), |b| {
            b.iter(|| {
                pipeline
                    .generate(prompt, 0, &options, &mut NoProgress)
                    .expect("offline generation works")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, end_to_end);
criterion_main!(benches);
