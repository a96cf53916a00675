//! Readable tables of metrics, with the goals of `metrics.md`.

use std::fmt::Write;

use crate::{MetricsSummary, SceneMetrics};

fn percent(v: f64) -> String {
    format!("{:.1} %", v * 100.0)
}

fn ratio(v: Option<f64>) -> String {
    v.map_or_else(|| "n/a".to_owned(), |v| format!("{v:.3}"))
}

fn row(out: &mut String, metric: &str, value: &str, goal: &str) {
    let _ = writeln!(out, "{metric:<24} {value:>10}   {goal}");
}

fn header(out: &mut String) {
    row(out, "metric", "value", "goal");
    let _ = writeln!(out, "{}", "-".repeat(48));
}

/// The collision, stability, Walk and Reach values one table shows (rates as fractions).
struct PhysicalRows {
    col_o: f64,
    col_s: f64,
    col_arch: f64,
    inst_o: f64,
    inst_s: f64,
    walk: f64,
    reach_floor: Option<f64>,
    reach_all: Option<f64>,
}

/// The rows both tables share, each with its goal.
fn physical_rows(out: &mut String, v: &PhysicalRows) {
    row(out, "Col-O", &percent(v.col_o), "0.0 %");
    row(out, "Col-S", &percent(v.col_s), "0 %");
    row(out, "Col-arch", &percent(v.col_arch), "0 %");
    row(out, "Inst-O", &percent(v.inst_o), "< 0.5 %");
    row(out, "Inst-S", &percent(v.inst_s), "< 5 %");
    row(out, "Walk", &format!("{:.3}", v.walk), ">= 0.99");
    row(
        out,
        "Reach (floor objects)",
        &ratio(v.reach_floor),
        ">= 0.98",
    );
    row(
        out,
        "Reach (all objects)",
        &ratio(v.reach_all),
        "(reported)",
    );
}

/// The rows of the joints: openable objects, joints and the share that opens freely (none
/// when nothing opens).
fn opening_rows(out: &mut String, openable: usize, joints: usize, held: Option<f64>) {
    if joints == 0 {
        return;
    }
    row(out, "openable objects", &openable.to_string(), "(reported)");
    row(out, "joints", &joints.to_string(), "(reported)");
    row(
        out,
        "opening clearance",
        &held.map_or("n/a".into(), percent),
        "100 %",
    );
}

impl SceneMetrics {
    /// A readable table: metric, value and goal, then the details (colliding pairs, unstable
    /// objects, penetrated architecture, unreachable objects).
    pub fn to_table(&self) -> String {
        let mut out = String::new();
        header(&mut out);
        row(&mut out, "objects", &self.objects.to_string(), ">= 20");
        row(
            &mut out,
            "categories",
            &self.categories.to_string(),
            ">= 10",
        );
        row(
            &mut out,
            "relation kinds",
            &self.relation_kinds.to_string(),
            ">= 4",
        );
        physical_rows(
            &mut out,
            &PhysicalRows {
                col_o: self.col_o,
                col_s: self.col_s as u8 as f64,
                col_arch: self.col_arch,
                inst_o: self.inst_o,
                inst_s: self.inst_s as u8 as f64,
                walk: self.walk,
                reach_floor: self.reach_floor,
                reach_all: self.reach_all,
            },
        );
        let openable: std::collections::BTreeSet<&str> =
            self.openings.iter().map(|o| o.object.as_str()).collect();
        let held = self.openings.len() - self.blocked_openings().count();
        opening_rows(
            &mut out,
            openable.len(),
            self.openings.len(),
            Some(held as f64 / self.openings.len().max(1) as f64),
        );
        for p in &self.colliding_pairs {
            let _ = writeln!(
                out,
                "collision: {} / {} by {:.1} mm",
                p.a,
                p.b,
                p.depth * 1e3
            );
        }
        for p in &self.arch_penetrations {
            let _ = writeln!(
                out,
                "architecture: {} sinks into {} by {:.1} mm",
                p.object,
                p.architecture,
                p.depth * 1e3
            );
        }
        for u in &self.unstable {
            if u.non_finite {
                let _ = writeln!(out, "unstable: {} (state became non-finite)", u.id);
            } else {
                let _ = writeln!(
                    out,
                    "unstable: {} moved {:.1} cm, turned {:.3} rad",
                    u.id,
                    u.displacement * 100.0,
                    u.rotation
                );
            }
        }
        if !self.unreachable_floor_objects.is_empty() {
            let _ = writeln!(
                out,
                "unreachable floor objects: {}",
                self.unreachable_floor_objects.join(", ")
            );
        }
        for o in self.blocked_openings() {
            let _ = writeln!(
                out,
                "opening: {} joint {} opens {:.0} % of its range, stopped by {}",
                o.object,
                o.joint,
                o.free_share * 100.0,
                o.blocked_by.as_deref().unwrap_or("?")
            );
        }
        if !self.welded.is_empty() {
            let _ = writeln!(
                out,
                "wall-mounted (not simulated): {}",
                self.welded.join(", ")
            );
        }
        out
    }
}

impl MetricsSummary {
    /// A readable table of the pooled metrics with their goals.
    pub fn to_table(&self) -> String {
        let mut out = String::new();
        header(&mut out);
        row(&mut out, "scenes", &self.scenes.to_string(), "");
        row(
            &mut out,
            "objects / scene",
            &format!("{:.1}", self.mean_objects),
            ">= 20",
        );
        row(
            &mut out,
            "categories / scene",
            &format!("{:.1}", self.mean_categories),
            ">= 10",
        );
        row(
            &mut out,
            "relation kinds / scene",
            &format!("{:.1}", self.mean_relation_kinds),
            ">= 4",
        );
        physical_rows(
            &mut out,
            &PhysicalRows {
                col_o: self.col_o,
                col_s: self.col_s,
                col_arch: self.col_arch,
                inst_o: self.inst_o,
                inst_s: self.inst_s,
                walk: self.walk,
                reach_floor: self.reach_floor,
                reach_all: self.reach_all,
            },
        );
        opening_rows(
            &mut out,
            self.openable_objects,
            self.joints,
            self.opening_clearance,
        );
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn summary_table_lists_every_metric_with_its_goal() {
        let summary = MetricsSummary {
            scenes: 3,
            objects: 60,
            col_o: 0.0126,
            col_s: 1.0 / 3.0,
            col_arch: 0.0,
            inst_o: 0.004,
            inst_s: 0.0,
            walk: 0.99512,
            reach_floor: Some(0.98765),
            reach_all: None,
            mean_objects: 20.0,
            mean_categories: 11.333,
            mean_relation_kinds: 4.5,
            openable_objects: 0,
            joints: 0,
            opening_clearance: None,
        };
        let expected = [
            "metric                        value   goal",
            "------------------------------------------------",
            "scenes                            3   ",
            "objects / scene                20.0   >= 20",
            "categories / scene             11.3   >= 10",
            "relation kinds / scene          4.5   >= 4",
            "Col-O                         1.3 %   0.0 %",
            "Col-S                        33.3 %   0 %",
            "Col-arch                      0.0 %   0 %",
            "Inst-O                        0.4 %   < 0.5 %",
            "Inst-S                        0.0 %   < 5 %",
            "Walk                          0.995   >= 0.99",
            "Reach (floor objects)         0.988   >= 0.98",
            "Reach (all objects)             n/a   (reported)",
        ];
        let table = summary.to_table();
        let lines: Vec<&str> = table.lines().collect();
        assert_eq!(lines, expected);
    }
}
