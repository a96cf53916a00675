//! Functional arrangement over the benchmark prompts (`fixtures/prompts/benchmark.txt`) and the
//! kitchen prompts of issue #16, seeds 0–1: the share of arrangement rules
//! (`crates/agents/knowledge/arrangement.toml`: seating faces what it serves, a bed's head
//! against a wall, kitchen counters in continuous runs, …) holding in the final scenes, as the
//! geometric judge reports it in `verdict.arrangement` (target ≥ 95 %); every kitchen accepted
//! with the physics and walkway goals met, its layout (one-wall, L, U, galley) reported.

use scenethesis_agents::{check_arrangement, run_layout};
use scenethesis_pipeline::{GenerateOptions, NoProgress, Pipeline};

/// The prompts of a prompts file: non-empty lines that are not `#` comments.
fn lines(text: &'static str) -> Vec<&'static str> {
    text.lines()
        .map(str::trim)
        .filter(|l| !l.is_empty() && !l.starts_with('#'))
        .collect()
}

/// The kitchen prompts of issue #16 (`fixtures/prompts/kitchens.txt`).
fn kitchens() -> Vec<&'static str> {
    lines(include_str!("../../../fixtures/prompts/kitchens.txt"))
}

/// Seeds 0–1 here, one thread each; `cargo xtask bench --json rooms` measures the same prompts
/// over seeds 0–3 and the README reports its figures.
const SEEDS: u64 = 2;

fn prompts() -> Vec<&'static str> {
    let mut prompts = lines(include_str!("../../../fixtures/prompts/benchmark.txt"));
    prompts.extend(kitchens());
    prompts
}

/// What one run gave: rules held / checked, broken rules, and for kitchens a line of figures
/// plus any goal it misses.
struct Outcome {
    held: u32,
    checked: u32,
    broken: Vec<String>,
    line: String,
    problems: Vec<String>,
    /// Kitchens the judge did not accept, with its reasons.
    rejected: Vec<String>,
}

fn run(pipeline: &Pipeline, prompt: &str, seed: u64) -> Outcome {
    let options = GenerateOptions {
        previews: false,
        ..GenerateOptions::default()
    };
    let g = pipeline
        .generate(prompt, seed, &options, &mut NoProgress)
        .unwrap_or_else(|e| panic!("{prompt} #{seed}: {e}"));
    let check = g
        .report
        .verdict
        .arrangement
        .clone()
        .expect("the geometric judge checks the arrangement");
    // The verdict's check is the one `check_arrangement` gives on the final scene.
    assert_eq!(check, check_arrangement(&g.scene), "{prompt} #{seed}");
    let m = &g.report.verdict.metrics;
    let mut problems = Vec::new();
    let mut rejected = Vec::new();
    let layout = run_layout(&g.scene).unwrap_or_else(|| "-".into());
    if kitchens().contains(&prompt) {
        let reach = m.reach_floor.unwrap_or(0.0);
        if !g.report.accepted {
            rejected.push(format!("{prompt} #{seed}: {}", g.report.verdict.reasons()));
        }
        if m.col_o > 0.0 || m.inst_o >= 0.005 || m.walk < 0.99 || reach < 0.98 {
            problems.push(format!(
                "{prompt} #{seed}: accepted {} Col-O {} Inst-O {} Walk {:.3} Reach {reach:.3}: {}",
                g.report.accepted,
                m.col_o,
                m.inst_o,
                m.walk,
                g.report.verdict.reasons()
            ));
        }
        for c in ["kitchen_counter", "sink", "stove", "refrigerator"] {
            if !g.scene.objects.iter().any(|o| o.category == c) {
                problems.push(format!("{prompt} #{seed}: no {c}"));
            }
        }
    }
    Outcome {
        held: check.held,
        checked: check.checked,
        broken: check
            .broken
            .iter()
            .map(|b| {
                format!(
                    "{prompt} #{seed}: `{}` {} ({})",
                    b.subject, b.reason, b.rule
                )
            })
            .collect(),
        line: format!(
            "#{seed} {}/{} rules, {} objects, layout {layout}, accepted {}, attempts {}: {prompt}",
            check.held,
            check.checked,
            g.scene.objects.len(),
            g.report.accepted,
            g.report.attempts
        ),
        problems,
        rejected,
    }
}

#[test]
fn arrangement_rules_hold_in_the_benchmark_and_kitchen_scenes() {
    let pipeline = Pipeline::offline();
    let prompts = prompts();
    // One thread per seed.
    let outcomes: Vec<Outcome> = std::thread::scope(|scope| {
        let handles: Vec<_> = (0..SEEDS)
            .map(|seed| {
                let (pipeline, prompts) = (&pipeline, &prompts);
                scope.spawn(move || {
                    prompts
                        .iter()
                        .map(|p| run(pipeline, p, seed))
                        .collect::<Vec<_>>()
                })
            })
            .collect();
        handles
            .into_iter()
            .flat_map(|h| h.join().expect("seed thread"))
            .collect()
    });
    let held: u32 = outcomes.iter().map(|o| o.held).sum();
    let checked: u32 = outcomes.iter().map(|o| o.checked).sum();
    let share = f64::from(held) / f64::from(checked.max(1));
    let broken: Vec<&String> = outcomes.iter().flat_map(|o| &o.broken).collect();
    let problems: Vec<&String> = outcomes.iter().flat_map(|o| &o.problems).collect();
    let rejected: Vec<&String> = outcomes.iter().flat_map(|o| &o.rejected).collect();
    eprintln!(
        "arrangement rules per prompt and seed:\n{}\noverall {:.1} % ({held}/{checked}) over {} prompts × {SEEDS} seeds\nbroken:\n{}",
        outcomes.iter().map(|o| o.line.as_str()).collect::<Vec<_>>().join("\n"),
        100.0 * share,
        prompts.len(),
        broken.iter().map(|s| s.as_str()).collect::<Vec<_>>().join("\n")
    );
    assert!(
        checked >= 14 * SEEDS as u32,
        "only {checked} rule instances applied"
    );
    assert!(
        share >= 0.95,
        "{held}/{checked} arrangement rules hold:\n{}",
        broken
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
    // The judge re-plans a kitchen whose doors cannot open or whose chairs lost their table,
    // up to its attempt limit; one kitchen in eight may still end unaccepted (its physics
    // holds: that is a problem above).
    assert!(
        rejected.len() <= 1,
        "kitchens the judge did not accept:\n{}",
        rejected
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
    assert!(
        problems.is_empty(),
        "{}",
        problems
            .iter()
            .map(|s| s.as_str())
            .collect::<Vec<_>>()
            .join("\n")
    );
}
