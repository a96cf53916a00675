//! Query latency of the asset index over every built-in category plus a few hundred imported
//! assets.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use scenethesis_retrieval::AssetIndex;
use scenethesis_scene_graph::AssetRef;
use scenethesis_scene_graph::{AssetInfo, Placement};

const QUERIES: &[&str] = &[
    "sofa",
    "couch",
    "bookcase",
    "TV",
    "fridge",
    "coffee tables",
    "red wooden chair",
    "a small potted plant",
    "bookshelv",
    "beach umbrella",
    "laptop computer",
    "mug",
    "stack of books",
    "office desk",
    "garbage can",
    "surf board",
];

fn index_with_imports(imported: usize) -> AssetIndex {
    let mut index = AssetIndex::builtin();
    let categories: Vec<&str> = scenethesis_procedural::catalog::categories()
        .map(|c| c.name)
        .collect();
    for k in 0..imported {
        let category = categories[k % categories.len().max(1)];
        index.add_imported(&AssetInfo {
            source: AssetRef::Imported {
                id: format!("user_{k}"),
                path: format!("user/{category}_{k}.glb"),
            },
            category: category.to_owned(),
            synonyms: vec![format!("custom {category}")],
            size: [1.0, 1.0, 1.0],
            placement: Placement::Floor,
            front: [0.0, 0.0, 1.0],
            support_surfaces: Vec::new(),
            scale_range: [0.9, 1.1],
            joints: Vec::new(),
            opening_bounds: None,
        });
    }
    index
}

fn search(c: &mut Criterion) {
    let mut group = c.benchmark_group("retrieval_search");
    for imported in [0usize, 500] {
        let index = index_with_imports(imported);
        group.throughput(Throughput::Elements(QUERIES.len() as u64));
        group.bench_with_input(
            BenchmarkId::new(
                "queries",
                format!("{}_categories_{imported}_imported", index.len()),
            ),
            &index,
            |b, index| {
                b.iter(|| {
                    for (k, q) in QUERIES.iter().enumerate() {
                        std::hint::black_box(index.search(q, 5, k as u64));
                    }
                })
            },
        );
    }
    group.finish();
}

criterion_group!(benches, search);
criterion_main!(benches);
