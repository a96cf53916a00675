//! The correspond stage on a ~30-object scene: every object of the detailed benchmark prompt's
//! scene, started 6–8 cm and 10° off its true pose, aligned to guidance (mask and depth of a
//! 640 × 480 view) with the default shape matcher. Target: ≤ 1 s added per scene.

use std::collections::BTreeMap;

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::{Point3, Vector3};
use scenethesis_correspondence::{correspond, rasterized_guidance, GuidedSettings, ShapeMatcher};
use scenethesis_imagery::{Camera, Guidance, Intrinsics};
use scenethesis_pipeline::{
    resolve_meshes, GenerateOptions, NoProgress, Pipeline, RetrievalSource,
};
use scenethesis_scene_graph::{Mesh, Pose, Scene};

const PROMPT: &str = "a living room with a grey three-seat sofa against the back wall, a low \
     round coffee table in front of it with two mugs and a small vase on top, two armchairs on \
     either side of the table turned toward the sofa, a tall bookshelf in the corner with books \
     and a plant inside its shelves, and a floor lamp beside the sofa";

/// Guidance of `scene` seen from a corner of the room at eye height.
fn guidance(scene: &Scene, meshes: &BTreeMap<String, Mesh>) -> Guidance {
    let floor = &scene.architecture.floor;
    let camera = Camera::look_at(
        Intrinsics::from_vertical_fov(640, 480, 1.0),
        Point3::new(floor.min.x + 0.3, 1.6, floor.max.y - 0.3),
        Point3::new(
            (floor.min.x + floor.max.x) / 2.0,
            0.5,
            (floor.min.y + floor.max.y) / 2.0,
        ),
        Vector3::y(),
    );
    rasterized_guidance(scene, meshes, &camera)
}

fn bench_correspond(c: &mut Criterion) {
    let options = GenerateOptions {
        previews: false,
        ..GenerateOptions::default()
    };
    let generated = Pipeline::offline()
        .generate(PROMPT, 0, &options, &mut NoProgress)
        .expect("offline generation works");
    let truth = generated.scene;
    let meshes = resolve_meshes(&truth, &RetrievalSource::default()).expect("meshes resolve");
    let guidance = guidance(&truth, &meshes);
    let mut start = truth.clone();
    for (k, o) in start.objects.iter_mut().enumerate() {
        let a = k as f64 * 2.399;
        o.pose = Pose::new(
            o.pose.scale,
            o.pose.yaw + 10f64.to_radians(),
            o.pose.translation + Vector3::new(0.06 * a.cos(), 0.0, 0.08 * a.sin()),
        );
    }
    let ranges = BTreeMap::new();
    let mut group = c.benchmark_group("correspond");
    group.sample_size(10);
    group.bench_function(format!("{}_objects", start.objects.len()), |b| {
        b.iter(|| {
            correspond(
                &start,
                &meshes,
                &ranges,
                &guidance,
                1.0,
                &ShapeMatcher::default(),
                &GuidedSettings::default(),
            )
        })
    });
    group.finish();
}

criterion_group!(benches, bench_correspond);
criterion_main!(benches);
