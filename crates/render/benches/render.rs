//! Render time of a 512×512 colour + depth + instance frame of a furnished 30-object room.

use std::sync::Arc;

use criterion::{criterion_group, criterion_main, Criterion};
use nalgebra::Vector3;
use scenethesis_primitives::{cuboid, cylinder, sphere};
use scenethesis_render::{views, Instance, RenderScene, Renderer, RendererOptions};
use scenethesis_scene_graph::{Architecture, Material, Mesh, Pose};

/// Thirty objects on a 6 × 5 m floor: tables, stools and lamps (≈ 40k triangles).
fn scene() -> RenderScene {
    let wood = Material::new("wood", [0.45, 0.28, 0.14], 0.7);
    let brass = Material::new("brass", [0.8, 0.6, 0.25], 0.3);
    let table = Arc::new(Mesh {
        parts: vec![
            cuboid("top", 0, [-0.5, 0.7, -0.3], [0.5, 0.75, 0.3]),
            cylinder("leg_0", 0, [-0.42, -0.22], 0.03, 0.0, 0.7, 24),
            cylinder("leg_1", 0, [0.42, -0.22], 0.03, 0.0, 0.7, 24),
            cylinder("leg_2", 0, [-0.42, 0.22], 0.03, 0.0, 0.7, 24),
            cylinder("leg_3", 0, [0.42, 0.22], 0.03, 0.0, 0.7, 24),
        ],
        materials: vec![wood.clone()],
    });
    let stool = Arc::new(Mesh {
        parts: vec![
            cylinder("seat", 0, [0.0, 0.0], 0.2, 0.42, 0.46, 48),
            cylinder("post", 0, [0.0, 0.0], 0.04, 0.0, 0.42, 24),
        ],
        materials: vec![wood],
    });
    let lamp = Arc::new(Mesh {
        parts: vec![
            cylinder("base", 0, [0.0, 0.0], 0.12, 0.0, 0.03, 48),
            cylinder("stem", 0, [0.0, 0.0], 0.015, 0.03, 1.3, 16),
            sphere("shade", 0, [0.0, 1.4, 0.0], 0.15, 24, 48),
        ],
        materials: vec![brass],
    });
    let mut instances = Vec::new();
    for i in 0..30 {
        let (row, col) = (i / 6, i % 6);
        let mesh = [&table, &stool, &lamp][i % 3].clone();
        let pose = Pose::new(
            1.0,
            0.3 * i as f64,
            Vector3::new(-2.5 + col as f64, 0.0, -2.0 + row as f64),
        );
        instances.push(Instance::new(format!("object_{i}"), mesh, pose));
    }
    RenderScene::with_architecture(
        instances,
        Architecture::rectangular_room(6.0, 5.0, 2.7, 0.9),
    )
}

fn bench(c: &mut Criterion) {
    let renderer = Renderer::new(RendererOptions::from_env().expect("WGPU_BACKEND"))
        .expect("a graphics adapter");
    let scene = scene();
    let triangles: usize = scene
        .instances
        .iter()
        .map(|i| i.mesh.triangle_count())
        .sum();
    eprintln!(
        "rendering {triangles} object triangles on {}",
        renderer.adapter_description()
    );
    let camera = views::photo_view(&scene, 512, 512);
    let prepared = renderer.prepare(&scene).unwrap();
    let mut group = c.benchmark_group("render");
    group.sample_size(30);
    group.bench_function("frame_512x512_30_objects", |b| {
        b.iter(|| renderer.render_prepared(&prepared, &camera).unwrap())
    });
    group.bench_function("upload_and_frame_512x512_30_objects", |b| {
        b.iter(|| renderer.render(&scene, &camera).unwrap())
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
