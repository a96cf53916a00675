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
        row(&mut out, "Col-O", &percent(self.col_o), "0.0 %");
        row(&mut out, "Col-S", &percent(self.col_s as u8 as f64), "0 %");
        row(&mut out, "Col-arch", &percent(self.col_arch), "0 %");
        row(&mut out, "Inst-O", &percent(self.inst_o), "< 0.5 %");
        row(
            &mut out,
            "Inst-S",
            &percent(self.inst_s as u8 as f64),
            "< 5 %",
        );
        row(&mut out, "Walk", &format!("{:.3}", self.walk), ">= 0.99");
        row(
            &mut out,
            "Reach (floor objects)",
            &ratio(self.reach_floor),
            ">= 0.98",
        );
        row(
            &mut out,
            "Reach (all objects)",
            &ratio(self.reach_all),
            "(reported)",
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
        row(&mut out, "Col-O", &percent(self.col_o), "0.0 %");
        row(&mut out, "Col-S", &percent(self.col_s), "0 %");
        row(&mut out, "Col-arch", &percent(self.col_arch), "0 %");
        row(&mut out, "Inst-O", &percent(self.inst_o), "< 0.5 %");
        row(&mut out, "Inst-S", &percent(self.inst_s), "< 5 %");
        row(&mut out, "Walk", &format!("{:.3}", self.walk), ">= 0.99");
        row(
            &mut out,
            "Reach (floor objects)",
            &ratio(self.reach_floor),
            ">= 0.98",
        );
        row(
            &mut out,
            "Reach (all objects)",
            &ratio(self.reach_all),
            "(reported)",
        );
        out
    }
}
