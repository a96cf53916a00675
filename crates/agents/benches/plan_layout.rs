//! Planning and guiding throughput: prompts planned per second and plans laid out per second
//! (benchmark prompts, built-in catalog assets).

use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use scenethesis_agents::{
    CatalogAssets, Guide, KnowledgePlanner, Plan, PlanRequest, Planner, ProceduralGuide,
};

const PROMPTS: &[&str] = &[
    "a cozy living room with reading materials",
    "a gym room",
    "a chemistry laboratory",
    "a peaceful beach during sunset",
    "a living room with a grey three-seat sofa against the back wall, a low round coffee table in front of it with two mugs and a small vase on top, two armchairs on either side of the table turned toward the sofa, a tall bookshelf in the corner with books and a plant inside its shelves, and a floor lamp beside the sofa",
];

fn bench(c: &mut Criterion) {
    let planner = KnowledgePlanner::new();
    let available: Vec<String> = scenethesis_procedural::catalog::categories()
        .map(|c| c.name.to_owned())
        .collect();
    let requests: Vec<PlanRequest> = PROMPTS
        .iter()
        .map(|p| PlanRequest::new(*p, available.clone(), 7))
        .collect();

    let mut group = c.benchmark_group("agents");
    group.throughput(Throughput::Elements(requests.len() as u64));
    group.bench_function("plan_prompts", |b| {
        b.iter(|| {
            requests
                .iter()
                .map(|r| planner.plan(r).expect("plan").objects.len())
                .sum::<usize>()
        })
    });

    let plans: Vec<Plan> = requests
        .iter()
        .map(|r| planner.plan(r).expect("plan"))
        .collect();
    let guide = ProceduralGuide::default();
    let assets = CatalogAssets::new(7);
    group.sample_size(10);
    group.bench_function("layout_plans", |b| {
        b.iter(|| {
            plans
                .iter()
                .map(|p| {
                    guide
                        .layout(p, &assets, 7)
                        .expect("layout")
                        .scene
                        .objects
                        .len()
                })
                .sum::<usize>()
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
