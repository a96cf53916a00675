//! End-to-end seconds per prompt: the whole offline pipeline (plan, retrieve, guide, optimize,
//! judge with every metric, no previews) on benchmark prompts. Target: median < 2 s in release.

use criterion::{criterion_group, criterion_main, Criterion};
use scenethesis_pipeline::batch::slug;
use scenethesis_pipeline::{GenerateOptions, NoProgress, Pipeline};

/// The public benchmark prompts (`../shared/benchmarks/prompts.txt`): the paper's indoor
/// categories, an outdoor scene and a detailed prompt.
const PROMPTS: [&str; 14] = [
    "a cozy living room with reading materials",
    "a children's playroom",
    "a garage",
    "a warehouse",
    "a bookstore",
    "a convenience store",
    "a museum gallery",
    "a piano showroom",
    "a gym room",
    "a billiard club",
    "a hospital ward",
    "a chemistry laboratory",
    "a peaceful beach during sunset",
    "a living room with a grey three-seat sofa against the back wall, a low round coffee table \
     in front of it with two mugs and a small vase on top, two armchairs on either side of the \
     table turned toward the sofa, a tall bookshelf in the corner with books and a plant inside \
     its shelves, and a floor lamp beside the sofa",
];

fn end_to_end(c: &mut Criterion) {
    let options = GenerateOptions {
        previews: false,
        ..GenerateOptions::default()
    };
    let mut group = c.benchmark_group("end_to_end");
    group.sample_size(10);
    group.warm_up_time(std::time::Duration::from_secs(1));
    for prompt in PROMPTS {
        group.bench_function(slug(prompt), |b| {
            // A fresh pipeline each time, as a CLI run has: no cache warmed by earlier runs.
            b.iter(|| {
                Pipeline::offline()
                    .generate(prompt, 0, &options, &mut NoProgress)
                    .expect("offline generation works")
            })
        });
    }
    group.finish();
}

criterion_group!(benches, end_to_end);
criterion_main!(benches);
