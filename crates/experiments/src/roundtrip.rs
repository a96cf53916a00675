//! The vision guide's round trip, measured against ground truth.
//!
//! A saved scene is rendered from the photo view into guidance (colour, metric depth, one mask
//! per object, the camera) exactly as `render DIR --guidance` writes it; the guidance is
//! optionally perturbed the way real models err; the vision lifting recovers a gravity-aligned
//! box and a support parent per object; and every recovered object is compared with the scene's
//! own: translation, yaw (modulo the footprint's symmetry), size, 3D IoU and support parent.
//! Objects whose masks are missing or too small are reported as missing, never invented.

use std::collections::BTreeMap;

use scenethesis_imagery::{DepthMap, Guidance, Mask};
use scenethesis_render::{RenderError, Renderer};
use scenethesis_scene_graph::{fnv1a64, mix64, Mesh, ParentRef, Scene};
use scenethesis_vision::{lift_scene, LiftError, LiftOptions, LiftedBox, SupportKind};
use serde::{Deserialize, Serialize};

/// How the rendered guidance is degraded before lifting.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Perturbation {
    /// The render as is (occlusion as rendered).
    #[default]
    None,
    /// What a monocular depth model and a segmenter typically get wrong: Gaussian depth noise of
    /// 2 % of the depth, a global depth scale error of ±7 %, every mask eroded or dilated by
    /// 2 px, and 10 % of the masks dropped.
    Default,
}

/// Why a round trip failed.
#[derive(Debug, thiserror::Error)]
pub enum RoundtripError {
    /// Rendering the guidance failed.
    #[error("cannot render the guidance")]
    Render(#[source] RenderError),
    /// The lift refused the guidance.
    #[error("cannot lift the guidance")]
    Lift(#[source] LiftError),
}

/// The comparison of one recovered object with the truth.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ObjectResult {
    /// Object id.
    pub id: String,
    /// Its category.
    pub category: String,
    /// Distance between the recovered and the true box centres, metres.
    pub translation_m: f64,
    /// Yaw error in degrees modulo the footprint's symmetry (180°, or 90° for a square one).
    pub yaw_deg: f64,
    /// Mean relative error of the three box extents.
    pub size_error: f64,
    /// Intersection over union of the recovered and true boxes.
    pub iou: f64,
    /// The true support parent (`ground`, an object id, or `mounted` for an object hanging on
    /// a wall or standing more than 10 cm off the floor on nothing).
    pub true_parent: String,
    /// The recovered support parent, in the same terms.
    pub recovered_parent: String,
}

/// Medians over a set of objects.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Objects compared.
    pub objects: usize,
    /// Median translation error, metres.
    pub translation_median_m: f64,
    /// Median yaw error, degrees.
    pub yaw_median_deg: f64,
    /// Median relative size error.
    pub size_error_median: f64,
    /// Median 3D IoU.
    pub iou_median: f64,
    /// Fraction of objects whose support parent was recovered.
    pub parent_accuracy: f64,
}

/// The round trip of one scene.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RoundtripReport {
    /// The perturbation applied.
    pub perturb: Perturbation,
    /// Objects in the scene.
    pub scene_objects: usize,
    /// Objects recovered and compared.
    pub objects: usize,
    /// Ids not recovered (hidden, masks dropped, too few pixels).
    pub missing: Vec<String>,
    /// Median translation error, metres.
    pub translation_median_m: f64,
    /// Median yaw error, degrees.
    pub yaw_median_deg: f64,
    /// Median relative size error.
    pub size_error_median: f64,
    /// Median 3D IoU.
    pub iou_median: f64,
    /// Fraction of recovered objects whose support parent is right.
    pub parent_accuracy: f64,
    /// The depth scale the floor calibration applied.
    pub depth_scale: f64,
    /// The same figures per category.
    pub per_category: BTreeMap<String, Summary>,
    /// Every recovered object.
    pub per_object: Vec<ObjectResult>,
}

/// Round-trip options.
#[derive(Debug, Clone, PartialEq)]
pub struct RoundtripOptions {
    /// Guidance image size in pixels.
    pub size: [u32; 2],
    /// The degradation applied.
    pub perturb: Perturbation,
    /// Seed of the perturbation.
    pub seed: u64,
}

impl Default for RoundtripOptions {
    fn default() -> Self {
        Self {
            size: [640, 480],
            perturb: Perturbation::None,
            seed: 0,
        }
    }
}

/// A deterministic uniform value in [0, 1) from a key. The FNV hash is passed through
/// [`mix64`]: FNV-1a's high bits barely move when only the last bytes of a key change, so
/// without it the "per-pixel" noise of keys `u,v` was one value down long runs of a column.
fn unit(key: &str, seed: u64) -> f64 {
    (mix64(fnv1a64(format!("{seed}/{key}").as_bytes())) >> 11) as f64 / (1u64 << 53) as f64
}

/// Applies `perturb` to `guidance` (deterministic for a seed).
pub fn perturb(guidance: &Guidance, perturb: Perturbation, seed: u64) -> Guidance {
    if perturb == Perturbation::None {
        return guidance.clone();
    }
    let mut out = guidance.clone();
    let (w, h) = (
        guidance.camera.intrinsics.width,
        guidance.camera.intrinsics.height,
    );
    if let Some(depth) = &guidance.depth {
        let scale = if seed % 2 == 0 { 1.07 } else { 0.93 };
        out.depth = Some(DepthMap::from_fn(w, h, |u, v| {
            let z = depth.get(u, v).unwrap_or(0.0) as f64;
            // Box–Muller from two per-pixel uniforms.
            let key = format!("{u},{v}");
            let (a, b) = (unit(&key, seed).max(1e-12), unit(&key, seed ^ 0x5bd1_e995));
            let gauss = (-2.0 * a.ln()).sqrt() * (std::f64::consts::TAU * b).cos();
            (z * scale * (1.0 + 0.02 * gauss)).max(0.0) as f32
        }));
    }
    // Drop 10 % of the masks: those with the smallest hash.
    let mut ids: Vec<&String> = guidance.masks.keys().collect();
    ids.sort_by(|a, b| unit(a, seed).total_cmp(&unit(b, seed)).then(a.cmp(b)));
    let drop = (ids.len() as f64 * 0.1).round() as usize;
    for id in ids.iter().take(drop) {
        out.masks.remove(*id);
    }
    for (id, mask) in out.masks.iter_mut() {
        let dilate = unit(&format!("{id}/morph"), seed) < 0.5;
        *mask = morph(mask, 2, dilate);
    }
    out
}

/// Dilates (or erodes) a mask with a square of radius `r` pixels.
fn morph(mask: &Mask, r: i64, dilate: bool) -> Mask {
    let (w, h) = (mask.width() as i64, mask.height() as i64);
    let mut out = Mask::new(mask.width(), mask.height());
    for y in 0..h {
        for x in 0..w {
            let mut any = false;
            let mut all = true;
            for dy in -r..=r {
                for dx in -r..=r {
                    let (nx, ny) = (x + dx, y + dy);
                    let v = nx >= 0
                        && ny >= 0
                        && nx < w
                        && ny < h
                        && mask.contains(nx as u32, ny as u32);
                    any |= v;
                    all &= v;
                }
            }
            if (dilate && any) || (!dilate && all) {
                out.set(x as u32, y as u32, true);
            }
        }
    }
    out
}

/// The true box of every object: its asset-frame bounds under its pose.
pub(crate) fn true_boxes(
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
) -> BTreeMap<String, LiftedBox> {
    let mut out = BTreeMap::new();
    for o in &scene.objects {
        let Some(aabb) = meshes.get(&o.id).and_then(|m| m.bounds()) else {
            continue;
        };
        let size = aabb.size() * o.pose.scale;
        let center = o.pose.transform_point(&aabb.center());
        out.insert(
            o.id.clone(),
            LiftedBox {
                id: o.id.clone(),
                center,
                half_extents: size / 2.0,
                yaw: o.pose.yaw,
                points: 0,
                depth_source: scenethesis_vision::boxes::DepthSource::Measured,
                completed: false,
                seen_height: size.y,
            },
        );
    }
    out
}

/// The yaw period under which an asset's footprint looks the same: `π` for an oblong footprint,
/// `π/2` for one within 10 % of square, and `0` (any yaw) for a round one — near-square with a
/// convex hull filling less than 85 % of its bounding rectangle (a disc fills 79 %).
pub fn yaw_symmetry(mesh: &Mesh) -> f64 {
    let points: Vec<nalgebra::Point2<f64>> = mesh
        .parts
        .iter()
        .flat_map(|part| part.positions.iter())
        .map(|p| nalgebra::Point2::new(p[0] as f64, p[2] as f64))
        .collect();
    let hull = scenethesis_scene_graph::convex_hull(&points);
    let Some(rect) = scenethesis_vision::min_area_rectangle(&hull, 0.0) else {
        return std::f64::consts::PI;
    };
    let (hx, hz) = (rect.half_extents.x, rect.half_extents.y);
    if (hx - hz).abs() > 0.1 * hx.max(hz) {
        return std::f64::consts::PI;
    }
    let hull_area = (0..hull.len())
        .map(|i| hull[i].coords.perp(&hull[(i + 1) % hull.len()].coords))
        .sum::<f64>()
        .abs()
        / 2.0;
    if hull_area < 0.85 * rect.area() {
        0.0
    } else {
        std::f64::consts::FRAC_PI_2
    }
}

/// The yaw of every wall of `architecture`: the yaw that lays a box's own x axis along it.
pub fn wall_yaws(architecture: &scenethesis_scene_graph::Architecture) -> Vec<f64> {
    architecture
        .walls
        .iter()
        .map(|w| {
            let d = w.end - w.start;
            (-d.y).atan2(d.x)
        })
        .collect()
}

/// Yaw error in degrees modulo `period` radians.
pub(crate) fn yaw_error(a: f64, b: f64, period: f64) -> f64 {
    scenethesis_scene_graph::yaw_distance_modulo(a, b, period).to_degrees()
}

pub(crate) fn median(mut v: Vec<f64>) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    v.sort_by(|a, b| a.total_cmp(b));
    let n = v.len();
    if n % 2 == 1 {
        v[n / 2]
    } else {
        (v[n / 2 - 1] + v[n / 2]) / 2.0
    }
}

fn summarize(results: &[&ObjectResult]) -> Summary {
    Summary {
        objects: results.len(),
        translation_median_m: median(results.iter().map(|r| r.translation_m).collect()),
        yaw_median_deg: median(results.iter().map(|r| r.yaw_deg).collect()),
        size_error_median: median(results.iter().map(|r| r.size_error).collect()),
        iou_median: median(results.iter().map(|r| r.iou).collect()),
        parent_accuracy: if results.is_empty() {
            f64::NAN
        } else {
            results
                .iter()
                .filter(|r| r.true_parent == r.recovered_parent)
                .count() as f64
                / results.len() as f64
        },
    }
}

/// Lifts `guidance` with size priors from the true assets and compares the result with `scene`.
pub fn compare(
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    guidance: &Guidance,
    perturb: Perturbation,
) -> Result<RoundtripReport, RoundtripError> {
    let truth = true_boxes(scene, meshes);
    // What the guide knows besides the image: the planned objects' asset sizes and the room.
    let options = LiftOptions {
        priors: truth.iter().map(|(id, b)| (id.clone(), b.size())).collect(),
        wall_yaws: wall_yaws(&scene.architecture),
        walls: scene.architecture.walls.clone(),
        ..LiftOptions::default()
    };
    let lifted = lift_scene(guidance, &options).map_err(RoundtripError::Lift)?;
    let recovered_parent: BTreeMap<&str, String> = lifted
        .supports
        .iter()
        .map(|s| {
            let p = match (s.kind, &s.parent) {
                (SupportKind::Ground, _) => "ground".to_string(),
                (SupportKind::Unsupported | SupportKind::Mounted, _) => "mounted".to_string(),
                (_, Some(p)) => p.clone(),
                (_, None) => "ground".to_string(),
            };
            (s.id.as_str(), p)
        })
        .collect();
    let mut per_object = Vec::new();
    for b in &lifted.boxes {
        let (Some(t), Some(object)) = (truth.get(&b.id), scene.object(&b.id)) else {
            continue;
        };
        let period = meshes.get(&b.id).map_or(std::f64::consts::PI, yaw_symmetry);
        let yaw_deg = if period > 0.0 {
            yaw_error(b.yaw, t.yaw, period)
        } else {
            0.0
        };
        let (tx, tz) = (t.half_extents.x, t.half_extents.z);
        // Compare extents along matching axes: a quarter turn swaps x and z.
        let quarter = yaw_error(b.yaw, t.yaw, std::f64::consts::PI) > 45.0;
        let (bx, bz) = if quarter {
            (b.half_extents.z, b.half_extents.x)
        } else {
            (b.half_extents.x, b.half_extents.z)
        };
        let rel = |m: f64, t: f64| (m - t).abs() / t.max(1e-6);
        let size_error =
            (rel(bx, tx) + rel(b.half_extents.y, t.half_extents.y) + rel(bz, tz)) / 3.0;
        let true_parent = match &object.parent {
            ParentRef::Object(id) => id.clone(),
            ParentRef::Wall(_) => "mounted".to_string(),
            ParentRef::Ground if t.bottom() > 0.1 => "mounted".to_string(),
            ParentRef::Ground => "ground".to_string(),
        };
        per_object.push(ObjectResult {
            id: b.id.clone(),
            category: object.category.clone(),
            translation_m: (b.center - t.center).norm(),
            yaw_deg,
            size_error,
            iou: b.iou(t),
            true_parent,
            recovered_parent: recovered_parent
                .get(b.id.as_str())
                .cloned()
                .unwrap_or_default(),
        });
    }
    let mut missing: Vec<String> = scene
        .objects
        .iter()
        .filter(|o| !per_object.iter().any(|r| r.id == o.id))
        .map(|o| o.id.clone())
        .collect();
    missing.sort();
    let all: Vec<&ObjectResult> = per_object.iter().collect();
    let overall = summarize(&all);
    let mut by_cat: BTreeMap<String, Vec<&ObjectResult>> = BTreeMap::new();
    for r in &per_object {
        by_cat.entry(r.category.clone()).or_default().push(r);
    }
    Ok(RoundtripReport {
        perturb,
        scene_objects: scene.objects.len(),
        objects: per_object.len(),
        missing,
        translation_median_m: overall.translation_median_m,
        yaw_median_deg: overall.yaw_median_deg,
        size_error_median: overall.size_error_median,
        iou_median: overall.iou_median,
        parent_accuracy: overall.parent_accuracy,
        depth_scale: lifted.depth_scale,
        per_category: by_cat
            .iter()
            .map(|(k, v)| (k.clone(), summarize(v)))
            .collect(),
        per_object,
    })
}

/// Renders, perturbs, lifts and compares one scene.
pub fn roundtrip(
    renderer: &Renderer,
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    options: &RoundtripOptions,
) -> Result<RoundtripReport, RoundtripError> {
    let guidance = perturbed_guidance(renderer, scene, meshes, options)?;
    compare(scene, meshes, &guidance, options.perturb)
}

/// The photo view's guidance of `scene` rendered at `options.size` and perturbed as
/// `options` say (the input of both the round trip and the ablation).
pub fn perturbed_guidance(
    renderer: &Renderer,
    scene: &Scene,
    meshes: &BTreeMap<String, Mesh>,
    options: &RoundtripOptions,
) -> Result<Guidance, RoundtripError> {
    let guidance = renderer
        .render_guidance(scene, meshes, options.size)
        .map_err(RoundtripError::Render)?;
    Ok(perturb(&guidance, options.perturb, options.seed))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn morphology_grows_and_shrinks() {
        let mut m = Mask::new(20, 20);
        for y in 5..15 {
            for x in 5..15 {
                m.set(x, y, true);
            }
        }
        assert_eq!(morph(&m, 2, true).area(), 14 * 14);
        assert_eq!(morph(&m, 2, false).area(), 6 * 6);
    }

    #[test]
    fn depth_noise_is_independent_per_pixel_with_two_percent_spread() {
        use scenethesis_imagery::{Camera, Intrinsics, RgbImage};
        let (w, h) = (64u32, 48u32);
        let k = Intrinsics::from_vertical_fov(w, h, 1.0);
        let camera = Camera::look_at(
            k,
            nalgebra::Point3::new(0.0, 1.6, 0.0),
            nalgebra::Point3::new(0.0, 0.0, -3.0),
            nalgebra::Vector3::y(),
        );
        let image = RgbImage::new(w, h, vec![0; (w * h * 3) as usize]).unwrap();
        let depth = DepthMap::from_fn(w, h, |_, _| 4.0);
        let clean = Guidance::new(camera, image, Some(depth), BTreeMap::new()).unwrap();
        let noisy = perturb(&clean, Perturbation::Default, 0);
        let d = noisy.depth.unwrap();
        // Relative error after removing the 7 % scale: mean 0, spread 2 %.
        let e = |u, v| d.get(u, v).unwrap() as f64 / (4.0 * 1.07) - 1.0;
        let n = (w * h) as f64;
        let mean = (0..h)
            .flat_map(|v| (0..w).map(move |u| (u, v)))
            .map(|(u, v)| e(u, v))
            .sum::<f64>()
            / n;
        let var = (0..h)
            .flat_map(|v| (0..w).map(move |u| (u, v)))
            .map(|(u, v)| (e(u, v) - mean).powi(2))
            .sum::<f64>()
            / n;
        assert!(mean.abs() < 0.002, "mean {mean}");
        assert!((var.sqrt() - 0.02).abs() < 0.002, "spread {}", var.sqrt());
        // Neighbours down a column and along a row are uncorrelated.
        for (du, dv) in [(0, 1), (1, 0)] {
            let mut c = 0.0;
            let mut m = 0.0;
            for v in 0..h - dv {
                for u in 0..w - du {
                    c += (e(u, v) - mean) * (e(u + du, v + dv) - mean);
                    m += 1.0;
                }
            }
            let corr = c / m / var;
            assert!(corr.abs() < 0.1, "correlation {corr} at ({du}, {dv})");
        }
    }

    #[test]
    fn yaw_error_respects_the_period() {
        assert!(yaw_error(0.0, std::f64::consts::PI, std::f64::consts::PI) < 1e-9);
        assert!((yaw_error(0.1, -0.1, std::f64::consts::PI) - 0.2f64.to_degrees()).abs() < 1e-9);
    }
}
