//! Throughput of exact mesh queries, building the exact field, baked grid lookups, grid baking
//! and scene batches.
//!
//! Single-thread figures run on the calling thread (the bake inside a one-thread rayon pool)
//! and are timed in the thread's own CPU time (Linux `/proc/thread-self/schedstat`, falling back
//! to wall time elsewhere), so other processes sharing the machine do not distort them; the
//! `*_2threads` figures use a two-thread pool and wall time.

use std::hint::black_box;
use std::sync::Arc;

use criterion::measurement::{Measurement, ValueFormatter};
use criterion::{criterion_group, criterion_main, Criterion, Throughput};
use nalgebra::{Point3, Vector3};
use rand::{Rng, SeedableRng};
use rand_chacha::ChaCha8Rng;
use scenethesis_sdf::{shapes, GridSdf, MeshSdf, Pose, SceneSdf, SignedDistance};

const QUERIES: usize = 100_000;

/// The 10 000-triangle closed bumpy sphere and 100k points in a box 20% larger than it.
fn setup() -> (MeshSdf, Vec<Point3<f32>>) {
    let (positions, triangles) = shapes::bumpy_sphere(0.5, 0.15, 100, 51);
    assert_eq!(triangles.len(), 10_000);
    points_around(positions, triangles, 0.6)
}

/// A 10 000-triangle torus and 100k points in its own box (the setting of the parry3d figure
/// in the project's stack notes).
fn setup_torus() -> (MeshSdf, Vec<Point3<f32>>) {
    let (positions, triangles) = shapes::torus(0.35, 0.15, 100, 50);
    assert_eq!(triangles.len(), 10_000);
    points_around(positions, triangles, 0.5)
}

/// The field of a mesh and 100k seeded points in its box scaled by `2 × half_scale`.
fn points_around(
    positions: Vec<[f32; 3]>,
    triangles: Vec<[u32; 3]>,
    half_scale: f32,
) -> (MeshSdf, Vec<Point3<f32>>) {
    let sdf = MeshSdf::new(&positions, &triangles).expect("closed mesh");
    let (lo, hi) = sdf.local_bounds();
    let centre = nalgebra::center(&lo, &hi);
    let half = (hi - lo) * half_scale;
    let mut rng = ChaCha8Rng::seed_from_u64(42);
    let points = (0..QUERIES)
        .map(|_| {
            centre
                + Vector3::new(
                    half.x * (2.0 * rng.random::<f32>() - 1.0),
                    half.y * (2.0 * rng.random::<f32>() - 1.0),
                    half.z * (2.0 * rng.random::<f32>() - 1.0),
                )
        })
        .collect();
    (sdf, points)
}

/// CPU time consumed by the calling thread, in nanoseconds.
struct ThreadCpuTime;

fn thread_cpu_ns() -> u64 {
    std::fs::read_to_string("/proc/thread-self/schedstat")
        .ok()
        .and_then(|s| s.split_whitespace().next()?.parse().ok())
        .unwrap_or_else(|| {
            static START: std::sync::OnceLock<std::time::Instant> = std::sync::OnceLock::new();
            START
                .get_or_init(std::time::Instant::now)
                .elapsed()
                .as_nanos() as u64
        })
}

impl Measurement for ThreadCpuTime {
    type Intermediate = u64;
    type Value = u64;
    fn start(&self) -> u64 {
        thread_cpu_ns()
    }
    fn end(&self, start: u64) -> u64 {
        thread_cpu_ns().saturating_sub(start)
    }
    fn add(&self, a: &u64, b: &u64) -> u64 {
        a + b
    }
    fn zero(&self) -> u64 {
        0
    }
    fn to_f64(&self, v: &u64) -> f64 {
        *v as f64
    }
    fn formatter(&self) -> &dyn ValueFormatter {
        &NanosFormatter
    }
}

/// Formats CPU nanoseconds like criterion's wall-time formatter (always in ns).
struct NanosFormatter;

impl ValueFormatter for NanosFormatter {
    fn scale_values(&self, _typical: f64, _values: &mut [f64]) -> &'static str {
        "ns"
    }
    fn scale_throughputs(&self, _typical: f64, t: &Throughput, values: &mut [f64]) -> &'static str {
        let n = match t {
            Throughput::Elements(n) | Throughput::Bytes(n) | Throughput::BytesDecimal(n) => *n,
            _ => 1,
        } as f64;
        for v in values.iter_mut() {
            *v = n * 1e9 / *v;
        }
        "elem/s"
    }
    fn scale_for_machines(&self, _values: &mut [f64]) -> &'static str {
        "ns"
    }
}

fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("thread pool")
}

fn single_thread(c: &mut Criterion<ThreadCpuTime>) {
    let (sdf, points) = setup();
    let mut group = c.benchmark_group("sdf");
    group.sample_size(10);

    group.throughput(Throughput::Elements(QUERIES as u64));
    group.bench_function("mesh_exact_10k_tris_1thread", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for p in &points {
                acc += sdf.distance(p);
            }
            black_box(acc)
        })
    });
    let (torus, torus_points) = setup_torus();
    group.bench_function("mesh_exact_torus_10k_tris_1thread", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for p in &torus_points {
                acc += torus.distance(p);
            }
            black_box(acc)
        })
    });

    // Building the exact field (welding, components, pseudo-normals, BVH, packets).
    let (positions, triangles) = shapes::bumpy_sphere(0.5, 0.15, 100, 51);
    group.throughput(Throughput::Elements(triangles.len() as u64));
    group.bench_function("mesh_build_10k_tris_1thread", |b| {
        b.iter(|| black_box(MeshSdf::new(&positions, &triangles).expect("closed mesh")))
    });
    group.throughput(Throughput::Elements(QUERIES as u64));

    let one = pool(1);
    let cell = cell_for_64_cubed(&sdf);
    let grid = one.install(|| GridSdf::bake_with_cell(&sdf, cell));
    assert_eq!(grid.dims(), [65, 65, 65]);
    group.bench_function("grid_lookup_1thread", |b| {
        b.iter(|| {
            let mut acc = 0.0f32;
            for p in &points {
                acc += grid.sample(p);
            }
            black_box(acc)
        })
    });

    group.throughput(Throughput::Elements(64 * 64 * 64));
    group.bench_function("grid_bake_64cubed_1thread", |b| {
        // Timed on the pool's only worker, where all of the bake's work runs.
        b.iter_custom(|iters| {
            one.install(|| {
                let start = thread_cpu_ns();
                for _ in 0..iters {
                    black_box(GridSdf::bake_with_cell(&sdf, cell));
                }
                thread_cpu_ns() - start
            })
        })
    });
    group.finish();
}

/// 60 cells over the surface + 2 padding cells per side = a 64³-cell grid.
fn cell_for_64_cubed(sdf: &MeshSdf) -> f32 {
    let (lo, hi) = sdf.local_bounds();
    (hi - lo).amax() / 60.0
}

fn two_threads(c: &mut Criterion) {
    let (sdf, points) = setup();
    let mut group = c.benchmark_group("sdf");
    group.sample_size(10);
    let two = pool(2);
    group.throughput(Throughput::Elements(QUERIES as u64));
    group.bench_function("mesh_exact_10k_tris_2threads", |b| {
        b.iter(|| two.install(|| black_box(sdf.distances(&points))))
    });
    let cell = cell_for_64_cubed(&sdf);
    group.throughput(Throughput::Elements(64 * 64 * 64));
    group.bench_function("grid_bake_64cubed_2threads", |b| {
        b.iter(|| two.install(|| black_box(GridSdf::bake_with_cell(&sdf, cell))))
    });
    let grid = two.install(|| GridSdf::bake_with_cell(&sdf, cell));

    // A scene of 40 baked objects on a 5 × 8 layout, batch over 100k points on 2 threads.
    let grid = Arc::new(grid);
    let mut scene = SceneSdf::new();
    for i in 0..40 {
        let pose = Pose::new(
            0.5 + 0.02 * i as f64,
            0.3 * i as f64,
            nalgebra::Vector3::new((i % 5) as f64 * 1.2, 0.5, (i / 5) as f64 * 1.2),
        );
        scene.insert(format!("object_{i:02}"), grid.clone(), pose);
    }
    let mut rng = ChaCha8Rng::seed_from_u64(7);
    let scene_points: Vec<Point3<f32>> = (0..QUERIES)
        .map(|_| {
            Point3::new(
                rng.random::<f32>() * 6.0 - 0.6,
                rng.random::<f32>() * 1.2,
                rng.random::<f32>() * 9.6 - 0.6,
            )
        })
        .collect();
    group.throughput(Throughput::Elements(QUERIES as u64));
    group.bench_function("scene_40_grids_batch_2threads", |b| {
        b.iter(|| two.install(|| black_box(scene.distances(&scene_points, &["object_03"]))))
    });
    group.finish();
}

criterion_group! {
    name = cpu_time;
    config = Criterion::default().with_measurement(ThreadCpuTime);
    targets = single_thread
}
criterion_group!(wall_time, two_threads);
criterion_main!(cpu_time, wall_time);
