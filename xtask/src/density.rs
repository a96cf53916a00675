//! Density and physics of the benchmark scenes (`density/…` figures): how full the rooms are
//! — objects per scene and the small objects resting on, inside or under another object — and
//! whether they stay physically clean (Col-O, Col-arch and Inst-O 0, Walk and Reach 1) and
//! accepted by the judge.

use std::collections::BTreeMap;
use std::path::Path;

use anyhow::{Context, Result};
use serde_json::{json, Value};

use crate::{benchmark_prompts, fresh_scratch, generate, median, prompt_lines, release_cli};

/// Seeds over which the benchmark scenes' density is measured (`density/…`).
const DENSITY_SEEDS: u64 = 3;

/// Issue #33's target for the median objects per benchmark scene.
const TARGET_MEDIAN_OBJECTS: f64 = 45.0;

/// The density of the benchmark scenes (`fixtures/prompts/benchmark.txt`), each prompt
/// generated with the release binary (no previews) at seeds 0–2. Adds one `density/pNN`
/// figure per prompt — per seed: accepted, attempts, objects, small objects (support `on`,
/// `inside` or `under` another object), Col-O, Col-arch, Inst-O, Walk, Reach and seconds; and
/// the prompt's median objects and small objects — then `density/all`: the median objects and
/// small objects over every scene, the accepted and physically clean scenes, the worst
/// Col-O / Col-arch / Inst-O and the lowest Walk / Reach, and the median seconds per scene.
pub fn add_density(
    root: &Path,
    target: &Path,
    json_out: bool,
    figures: &mut BTreeMap<String, Value>,
) -> Result<()> {
    let exe = release_cli(root, target, json_out)?;
    let prompts_text = benchmark_prompts(root)?;
    let scratch = fresh_scratch(target, "xtask-density")?;
    let mut all = Vec::new();
    for (k, prompt) in prompt_lines(&prompts_text).into_iter().enumerate() {
        let mut rows = Vec::new();
        for seed in 0..DENSITY_SEEDS {
            let dir = scratch.join(format!("p{k:02}-s{seed}"));
            generate(&exe, prompt, seed, &dir)?;
            rows.push(SceneRow::read(&dir)?);
        }
        figures.insert(format!("density/p{k:02}"), prompt_figure(prompt, &rows));
        all.extend(rows);
    }
    figures.insert("density/all".to_owned(), all_figure(&all));
    Ok(())
}

/// The physics metrics of a scene's verdict (`report.json`'s `verdict.metrics`).
#[derive(Debug, Clone, PartialEq)]
pub struct Physics {
    /// Colliding objects / objects.
    pub col_o: f64,
    /// Objects penetrating the floor or a wall / objects.
    pub col_arch: f64,
    /// Unstable objects / simulated objects.
    pub inst_o: f64,
    /// Largest walkable component / walkable area.
    pub walk: f64,
    /// Reach over floor-standing objects (`None` without any).
    pub reach_floor: Option<f64>,
}

impl Physics {
    /// Reads the metrics of a report; a missing metric reads as the worst value.
    pub fn from_report(report: &Value) -> Self {
        let m = &report["verdict"]["metrics"];
        let rate = |name: &str| m[name].as_f64().unwrap_or(1.0);
        Self {
            col_o: rate("col_o"),
            col_arch: rate("col_arch"),
            inst_o: rate("inst_o"),
            walk: m["walk"].as_f64().unwrap_or(0.0),
            reach_floor: m["reach_floor"].as_f64(),
        }
    }

    /// Col-O, Col-arch and Inst-O 0, Walk and Reach (when there is any) 1.
    pub fn clean(&self) -> bool {
        self.col_o == 0.0
            && self.col_arch == 0.0
            && self.inst_o == 0.0
            && self.walk >= 1.0
            && self.reach_floor.is_none_or(|r| r >= 1.0)
    }

    /// Adds the metrics to a JSON object as fields `col_o`, `col_arch`, `inst_o`, `walk` and
    /// `reach_floor` (a value that is no object is left as it is).
    pub fn add_to(&self, row: &mut Value) {
        if let Some(row) = row.as_object_mut() {
            row.insert("col_o".to_owned(), json!(self.col_o));
            row.insert("col_arch".to_owned(), json!(self.col_arch));
            row.insert("inst_o".to_owned(), json!(self.inst_o));
            row.insert("walk".to_owned(), json!(self.walk));
            row.insert("reach_floor".to_owned(), json!(self.reach_floor));
        }
    }
}

/// One generated scene's row: its report's verdict and counts, and the small objects of its
/// `scene.json`.
#[derive(Debug, Clone, PartialEq)]
struct SceneRow {
    seed: u64,
    accepted: bool,
    attempts: u64,
    objects: u64,
    small: u64,
    physics: Physics,
    seconds: f64,
}

impl SceneRow {
    /// Reads `report.json` and `scene.json` of a generated scene's folder.
    fn read(dir: &Path) -> Result<Self> {
        let read = |name: &str| -> Result<Value> {
            let path = dir.join(name);
            let text = std::fs::read_to_string(&path)
                .with_context(|| format!("cannot read {}", path.display()))?;
            serde_json::from_str(&text).with_context(|| format!("cannot parse {}", path.display()))
        };
        Ok(Self::from_json(&read("report.json")?, &read("scene.json")?))
    }

    /// The row of a report and its scene.
    fn from_json(report: &Value, scene: &Value) -> Self {
        let count = |name: &str| report[name].as_u64().unwrap_or(0);
        Self {
            seed: count("seed"),
            accepted: report["accepted"].as_bool().unwrap_or(false),
            attempts: count("attempts"),
            objects: count("objects"),
            small: small_objects(scene),
            physics: Physics::from_report(report),
            seconds: report["total_seconds"].as_f64().unwrap_or(f64::NAN),
        }
    }

    fn to_json(&self) -> Value {
        let mut row = json!({
            "seed": self.seed,
            "accepted": self.accepted,
            "attempts": self.attempts,
            "objects": self.objects,
            "small_objects": self.small,
            "physics_clean": self.physics.clean(),
            "seconds": self.seconds,
        });
        self.physics.add_to(&mut row);
        row
    }
}

/// Objects of a `scene.json` resting on, inside or under another object (not on the floor,
/// against a wall or mounted on one).
fn small_objects(scene: &Value) -> u64 {
    scene["objects"].as_object().map_or(0, |objects| {
        objects
            .values()
            .filter(|o| matches!(o["support"].as_str(), Some("on" | "inside" | "under")))
            .count() as u64
    })
}

/// The median of a field over rows.
fn median_of(rows: &[SceneRow], field: impl Fn(&SceneRow) -> f64) -> f64 {
    median(rows.iter().map(field).collect())
}

/// One prompt's figure: its seeds' rows and medians.
fn prompt_figure(prompt: &str, rows: &[SceneRow]) -> Value {
    json!({
        "prompt": prompt,
        "seeds": rows.len(),
        "objects_median": median_of(rows, |r| r.objects as f64),
        "small_objects_median": median_of(rows, |r| r.small as f64),
        "accepted": rows.iter().filter(|r| r.accepted).count(),
        "physics_clean": rows.iter().filter(|r| r.physics.clean()).count(),
        "per_seed": rows.iter().map(SceneRow::to_json).collect::<Vec<_>>(),
    })
}

/// `density/all`: every scene of every prompt.
fn all_figure(rows: &[SceneRow]) -> Value {
    let worst = |f: fn(&Physics) -> f64| rows.iter().map(|r| f(&r.physics)).fold(0.0, f64::max);
    let lowest = |f: fn(&Physics) -> f64| rows.iter().map(|r| f(&r.physics)).fold(1.0, f64::min);
    let objects_median = median_of(rows, |r| r.objects as f64);
    json!({
        "scenes": rows.len(),
        "objects_median": objects_median,
        "objects_min": rows.iter().map(|r| r.objects).min(),
        "objects_max": rows.iter().map(|r| r.objects).max(),
        "small_objects_median": median_of(rows, |r| r.small as f64),
        "target_objects_median": TARGET_MEDIAN_OBJECTS,
        "meets_target": objects_median >= TARGET_MEDIAN_OBJECTS,
        "accepted": rows.iter().filter(|r| r.accepted).count(),
        "physics_clean": rows.iter().filter(|r| r.physics.clean()).count(),
        "attempts": rows.iter().map(|r| r.attempts).sum::<u64>(),
        "col_o_max": worst(|p| p.col_o),
        "col_arch_max": worst(|p| p.col_arch),
        "inst_o_max": worst(|p| p.inst_o),
        "walk_min": lowest(|p| p.walk),
        "reach_floor_min": lowest(|p| p.reach_floor.unwrap_or(1.0)),
        "seconds_median": median_of(rows, |r| r.seconds),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A generated scene's `report.json` and `scene.json`, cut down to the fields read.
    fn fixture(name: &str) -> Value {
        let path = Path::new(env!("CARGO_MANIFEST_DIR"))
            .join("fixtures/density")
            .join(name);
        serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
    }

    #[test]
    fn a_scene_row_counts_small_objects_and_reads_the_physics() {
        let row = SceneRow::from_json(&fixture("report.json"), &fixture("scene.json"));
        assert_eq!(row.seed, 1);
        assert!(row.accepted);
        assert_eq!(row.attempts, 2);
        assert_eq!(row.objects, 6);
        // A book inside the shelf, a mug on the table and a basket under it; the table on the
        // floor, the shelf against a wall and the painting mounted are not small objects.
        assert_eq!(row.small, 3);
        assert_eq!(row.physics.reach_floor, Some(1.0));
        assert!(row.physics.clean());
        assert!((row.seconds - 2.5).abs() < 1e-9);
    }

    #[test]
    fn missing_or_bad_metrics_are_not_clean() {
        let mut report = fixture("report.json");
        report["verdict"]["metrics"]["col_arch"] = json!(0.02);
        assert!(!Physics::from_report(&report).clean());
        let empty = Physics::from_report(&json!({}));
        assert!(!empty.clean());
        assert_eq!(SceneRow::from_json(&json!({}), &json!({})).small, 0);
    }

    #[test]
    fn the_summary_takes_medians_and_extremes_over_scenes() {
        let report = fixture("report.json");
        let scene = fixture("scene.json");
        let mut rows = vec![SceneRow::from_json(&report, &scene); 3];
        rows[1].objects = 50;
        rows[2].objects = 60;
        rows[2].physics.walk = 0.9;
        let all = all_figure(&rows);
        assert_eq!(all["scenes"], 3);
        assert_eq!(all["objects_median"], 50.0);
        assert_eq!(all["meets_target"], true);
        assert_eq!(all["objects_min"], 6);
        assert_eq!(all["physics_clean"], 2);
        assert_eq!(all["walk_min"], 0.9);
        let prompt = prompt_figure("a room", &rows);
        assert_eq!(prompt["small_objects_median"], 3.0);
        assert_eq!(prompt["per_seed"][2]["physics_clean"], false);
        assert_eq!(prompt["per_seed"][0]["col_arch"], 0.0);
    }
}
