//! `--shard auto`: a shard's index and count read from the job scheduler's environment.
//!
//! The array and indexed jobs of common schedulers tell each task its index, and most of them
//! the number of tasks, through environment variables:
//!
//! | scheduler | index | count |
//! |---|---|---|
//! | SLURM job arrays | `(SLURM_ARRAY_TASK_ID − SLURM_ARRAY_TASK_MIN) / SLURM_ARRAY_TASK_STEP` | `SLURM_ARRAY_TASK_COUNT` |
//! | Kubernetes Indexed Jobs | `JOB_COMPLETION_INDEX` | none: the user gives it (`auto/N`) |
//! | AWS Batch array jobs | `AWS_BATCH_JOB_ARRAY_INDEX` | `AWS_BATCH_JOB_ARRAY_SIZE` |
//! | Google Cloud Batch | `BATCH_TASK_INDEX` | `BATCH_TASK_COUNT` |
//!
//! SLURM's minimum defaults to 0 and its step to 1 (so `--array=1-8` and `--array=0-14:2` both
//! give shards `0..8`); without `SLURM_ARRAY_TASK_COUNT` (old versions) the count is
//! `(SLURM_ARRAY_TASK_MAX − MIN) / STEP + 1`. A variable set to the empty string counts as not
//! set. [`Shard::from_scheduler`] reads the variables through a lookup function, so it is tested
//! without touching the process environment; [`process_env`] is the real one.

use std::fmt;
use std::str::FromStr;

use super::Shard;
use crate::PipelineError;

/// A job scheduler whose array or indexed jobs `--shard auto` understands.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Scheduler {
    /// SLURM job arrays (`sbatch --array`).
    Slurm,
    /// Kubernetes Indexed Jobs (`completionMode: Indexed`).
    Kubernetes,
    /// AWS Batch array jobs (`--array-properties size=N`).
    AwsBatch,
    /// Google Cloud Batch task groups (`taskCount`).
    GoogleBatch,
}

impl Scheduler {
    /// Every scheduler, in the order they are looked for.
    pub const ALL: [Scheduler; 4] = [
        Scheduler::Slurm,
        Scheduler::Kubernetes,
        Scheduler::AwsBatch,
        Scheduler::GoogleBatch,
    ];

    /// The variable holding the task's index; its presence means "running under this scheduler".
    pub fn index_variable(self) -> &'static str {
        match self {
            Scheduler::Slurm => "SLURM_ARRAY_TASK_ID",
            Scheduler::Kubernetes => "JOB_COMPLETION_INDEX",
            Scheduler::AwsBatch => "AWS_BATCH_JOB_ARRAY_INDEX",
            Scheduler::GoogleBatch => "BATCH_TASK_INDEX",
        }
    }

    /// The variable holding the number of tasks, if the scheduler sets one.
    pub fn count_variable(self) -> Option<&'static str> {
        match self {
            Scheduler::Slurm => Some("SLURM_ARRAY_TASK_COUNT"),
            Scheduler::Kubernetes => None,
            Scheduler::AwsBatch => Some("AWS_BATCH_JOB_ARRAY_SIZE"),
            Scheduler::GoogleBatch => Some("BATCH_TASK_COUNT"),
        }
    }

    /// The scheduler's name for messages, e.g. `AWS Batch`.
    pub fn name(self) -> &'static str {
        match self {
            Scheduler::Slurm => "SLURM",
            Scheduler::Kubernetes => "Kubernetes",
            Scheduler::AwsBatch => "AWS Batch",
            Scheduler::GoogleBatch => "Google Cloud Batch",
        }
    }
}

impl fmt::Display for Scheduler {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// What `--shard` asks for: a fixed shard `I/N`, or `auto` / `auto/N` (from the scheduler).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum ShardSpec {
    /// `I/N`: this shard.
    Fixed(Shard),
    /// `auto` or `auto/N`: read the shard from the scheduler's environment; `count` is `N`,
    /// required under Kubernetes and checked against the scheduler's own count elsewhere.
    Auto {
        /// The shard count the user gave, if any.
        count: Option<usize>,
    },
}

impl Default for ShardSpec {
    fn default() -> Self {
        ShardSpec::Fixed(Shard::ALL)
    }
}

impl FromStr for ShardSpec {
    type Err = PipelineError;

    /// Parses `I/N`, `auto` or `auto/N` (`N ≥ 1`).
    fn from_str(s: &str) -> Result<Self, Self::Err> {
        let Some(rest) = s.trim().strip_prefix("auto") else {
            return s.parse().map(ShardSpec::Fixed);
        };
        if rest.is_empty() {
            return Ok(ShardSpec::Auto { count: None });
        }
        match rest.strip_prefix('/').map(|n| n.trim().parse::<usize>()) {
            Some(Ok(n)) if n > 0 => Ok(ShardSpec::Auto { count: Some(n) }),
            _ => Err(PipelineError::Batch(format!(
                "shard `{s}`: auto/N needs a shard count N >= 1, e.g. auto/8"
            ))),
        }
    }
}

impl fmt::Display for ShardSpec {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            ShardSpec::Fixed(shard) => write!(f, "{shard}"),
            ShardSpec::Auto { count: None } => f.write_str("auto"),
            ShardSpec::Auto { count: Some(n) } => write!(f, "auto/{n}"),
        }
    }
}

impl ShardSpec {
    /// The shard to run: a fixed one as given (no scheduler), or the scheduler's through
    /// [`Shard::from_scheduler`] with the lookup `env`.
    pub fn resolve(
        self,
        env: impl Fn(&str) -> Option<String>,
    ) -> Result<(Shard, Option<Scheduler>), PipelineError> {
        match self {
            ShardSpec::Fixed(shard) => Ok((shard, None)),
            ShardSpec::Auto { count } => {
                Shard::from_scheduler(env, count).map(|(shard, s)| (shard, Some(s)))
            }
        }
    }
}

/// The process environment as a lookup for [`Shard::from_scheduler`] (a value that is not
/// UTF-8 is passed on lossily, so that its error names it).
pub fn process_env(name: &str) -> Option<String> {
    std::env::var_os(name).map(|v| v.to_string_lossy().into_owned())
}

/// One scheduler's answer: its shard and the variables it came from, `NAME=value, …`.
struct Reading {
    scheduler: Scheduler,
    shard: Shard,
    from: String,
}

fn auto_error(message: impl fmt::Display) -> PipelineError {
    PipelineError::Batch(format!("--shard auto: {message}"))
}

/// Reads environment variables as whole numbers, remembering the ones it saw for messages.
struct Vars<'a, F> {
    env: &'a F,
    seen: Vec<String>,
}

impl<F: Fn(&str) -> Option<String>> Vars<'_, F> {
    /// `name`'s value as a whole number; `None` when unset or empty.
    fn number(&mut self, name: &str) -> Result<Option<usize>, PipelineError> {
        let Some(raw) = (self.env)(name).filter(|v| !v.trim().is_empty()) else {
            return Ok(None);
        };
        let value = raw.trim().parse::<usize>().map_err(|_| {
            auto_error(format!(
                "{name} is {raw:?}, not a whole number >= 0; \
                 check the job's environment or pass --shard I/N"
            ))
        })?;
        self.seen.push(format!("{name}={value}"));
        Ok(Some(value))
    }
}

impl Shard {
    /// The shard of this task of a scheduler's array or indexed job (see
    /// [`crate::batch::scheduler`] for the variables), looked up through `env` (e.g.
    /// [`process_env`]); `count` is the `N` of `--shard auto/N`, required under Kubernetes and
    /// otherwise checked against the scheduler's count. Errors say what was looked for when
    /// no scheduler's variables are set, name a variable that is not a number, refuse an index
    /// not below the count, and name both schedulers when two disagree.
    pub fn from_scheduler(
        env: impl Fn(&str) -> Option<String>,
        count: Option<usize>,
    ) -> Result<(Shard, Scheduler), PipelineError> {
        let mut readings = Vec::new();
        for scheduler in Scheduler::ALL {
            if let Some(reading) = read(scheduler, &env, count)? {
                readings.push(reading);
            }
        }
        let Some(first) = readings.first() else {
            return Err(none_set());
        };
        if let Some(other) = readings.iter().find(|r| r.shard != first.shard) {
            return Err(auto_error(format!(
                "the variables of two schedulers are set and disagree: {} says shard {} ({}) \
                 but {} says shard {} ({}); unset one of them or pass --shard I/N",
                first.scheduler, first.shard, first.from, other.scheduler, other.shard, other.from
            )));
        }
        Ok((first.shard, first.scheduler))
    }
}

fn none_set() -> PipelineError {
    let looked: Vec<String> = Scheduler::ALL
        .iter()
        .map(|s| format!("{} ({s})", s.index_variable()))
        .collect();
    auto_error(format!(
        "no scheduler's array index is set (looked for {}); outside an array or indexed job \
         pass --shard I/N",
        looked.join(", ")
    ))
}

/// `scheduler`'s shard, or `None` when its index variable is not set.
fn read<F: Fn(&str) -> Option<String>>(
    scheduler: Scheduler,
    env: &F,
    given: Option<usize>,
) -> Result<Option<Reading>, PipelineError> {
    let mut vars = Vars {
        env,
        seen: Vec::new(),
    };
    let Some(raw) = vars.number(scheduler.index_variable())? else {
        return Ok(None);
    };
    let (index, own) = match scheduler {
        Scheduler::Slurm => slurm(&mut vars, raw)?,
        _ => {
            let count = match scheduler.count_variable() {
                Some(name) => vars.number(name)?,
                None => None,
            };
            (raw, count)
        }
    };
    let from = vars.seen.join(", ");
    let count = agree(scheduler, own, given, &from)?;
    if index >= count {
        return Err(auto_error(format!(
            "{scheduler} gives shard index {index} ({from}), not below the shard count {count}; \
             check the array's range or pass --shard I/N"
        )));
    }
    Ok(Some(Reading {
        scheduler,
        shard: Shard { index, count },
        from,
    }))
}

/// SLURM's 0-based shard index `(ID − MIN) / STEP` and its count, if it says one.
fn slurm<F: Fn(&str) -> Option<String>>(
    vars: &mut Vars<'_, F>,
    id: usize,
) -> Result<(usize, Option<usize>), PipelineError> {
    let min = vars.number("SLURM_ARRAY_TASK_MIN")?.unwrap_or(0);
    let step = vars.number("SLURM_ARRAY_TASK_STEP")?.unwrap_or(1);
    if step == 0 {
        return Err(auto_error("SLURM_ARRAY_TASK_STEP is 0"));
    }
    let offset = id.checked_sub(min).filter(|o| o % step == 0);
    let Some(offset) = offset else {
        return Err(auto_error(format!(
            "SLURM_ARRAY_TASK_ID={id} is not SLURM_ARRAY_TASK_MIN={min} plus a multiple of \
             SLURM_ARRAY_TASK_STEP={step}; use a regular --array=A-B[:S] or pass --shard I/N"
        )));
    };
    let count = match vars.number("SLURM_ARRAY_TASK_COUNT")? {
        Some(count) => Some(count),
        None => vars
            .number("SLURM_ARRAY_TASK_MAX")?
            .and_then(|max| max.checked_sub(min))
            .map(|span| span / step + 1),
    };
    Ok((offset / step, count))
}

/// The shard count: the scheduler's and the user's must agree; one of them must be given.
fn agree(
    scheduler: Scheduler,
    own: Option<usize>,
    given: Option<usize>,
    from: &str,
) -> Result<usize, PipelineError> {
    match (own, given) {
        (Some(own), Some(given)) if own != given => Err(auto_error(format!(
            "the shard count {given} given (auto/{given}) disagrees with {scheduler}'s {own} \
             ({from}); pass --shard auto, or auto/{own}"
        ))),
        (Some(0), _) => Err(auto_error(format!(
            "{scheduler} says there are 0 tasks ({from})"
        ))),
        (Some(count), _) | (None, Some(count)) => Ok(count),
        (None, None) => Err(auto_error(match scheduler.count_variable() {
            None => format!(
                "{scheduler} gives the index ({from}) but not the shard count; pass \
                 --shard auto/N with N the Job's completions"
            ),
            Some(name) => format!(
                "{scheduler} gives the index ({from}) but not {name}; pass --shard auto/N \
                 with N the number of tasks"
            ),
        })),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A lookup over `pairs`.
    fn env<'a>(pairs: &'a [(&'a str, &'a str)]) -> impl Fn(&str) -> Option<String> + 'a {
        move |name| {
            pairs
                .iter()
                .find(|(k, _)| *k == name)
                .map(|(_, v)| (*v).to_owned())
        }
    }

    fn shard(pairs: &[(&str, &str)], count: Option<usize>) -> Result<(Shard, Scheduler), String> {
        Shard::from_scheduler(env(pairs), count).map_err(|e| e.to_string())
    }

    fn ok(index: usize, count: usize, scheduler: Scheduler) -> Result<(Shard, Scheduler), String> {
        Ok((Shard { index, count }, scheduler))
    }

    fn err(pairs: &[(&str, &str)], count: Option<usize>) -> String {
        shard(pairs, count).expect_err("an error")
    }

    #[test]
    fn slurm_arrays_from_zero_from_one_and_with_a_step() {
        let plain = [
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ];
        assert_eq!(shard(&plain, None), ok(3, 8, Scheduler::Slurm));
        assert_eq!(shard(&plain, Some(8)), ok(3, 8, Scheduler::Slurm));
        // --array=1-8
        let from_one = [
            ("SLURM_ARRAY_TASK_ID", "1"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_MAX", "8"),
            ("SLURM_ARRAY_TASK_STEP", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ];
        assert_eq!(shard(&from_one, None), ok(0, 8, Scheduler::Slurm));
        // --array=10-24:2 → 10, 12, …, 24: eight tasks.
        let stepped = [
            ("SLURM_ARRAY_TASK_ID", "24"),
            ("SLURM_ARRAY_TASK_MIN", "10"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ];
        assert_eq!(shard(&stepped, None), ok(7, 8, Scheduler::Slurm));
        // No COUNT (old SLURM): from MAX.
        let no_count = [
            ("SLURM_ARRAY_TASK_ID", "12"),
            ("SLURM_ARRAY_TASK_MIN", "10"),
            ("SLURM_ARRAY_TASK_MAX", "24"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
        ];
        assert_eq!(shard(&no_count, None), ok(1, 8, Scheduler::Slurm));
    }

    #[test]
    fn slurm_ids_off_the_array_are_refused() {
        let off_step = [
            ("SLURM_ARRAY_TASK_ID", "13"),
            ("SLURM_ARRAY_TASK_MIN", "10"),
            ("SLURM_ARRAY_TASK_STEP", "2"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ];
        let e = err(&off_step, None);
        assert!(e.contains("SLURM_ARRAY_TASK_ID=13"), "{e}");
        assert!(e.contains("SLURM_ARRAY_TASK_STEP=2"), "{e}");
        let below_min = [("SLURM_ARRAY_TASK_ID", "0"), ("SLURM_ARRAY_TASK_MIN", "1")];
        assert!(err(&below_min, Some(4)).contains("SLURM_ARRAY_TASK_MIN=1"));
        let zero_step = [("SLURM_ARRAY_TASK_ID", "0"), ("SLURM_ARRAY_TASK_STEP", "0")];
        assert!(err(&zero_step, Some(4)).contains("SLURM_ARRAY_TASK_STEP is 0"));
        // --array=1,3,7: not one regular range; index 6 of 3 tasks.
        let list = [
            ("SLURM_ARRAY_TASK_ID", "7"),
            ("SLURM_ARRAY_TASK_MIN", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "3"),
        ];
        let e = err(&list, None);
        assert!(e.contains("index 6") && e.contains("shard count 3"), "{e}");
    }

    #[test]
    fn kubernetes_needs_the_count_from_the_user() {
        let k8s = [("JOB_COMPLETION_INDEX", "5")];
        assert_eq!(shard(&k8s, Some(6)), ok(5, 6, Scheduler::Kubernetes));
        let e = err(&k8s, None);
        assert!(
            e.contains("Kubernetes") && e.contains("--shard auto/N"),
            "{e}"
        );
        assert!(e.contains("JOB_COMPLETION_INDEX=5"), "{e}");
        let e = err(&k8s, Some(5));
        assert!(e.contains("index 5") && e.contains("shard count 5"), "{e}");
    }

    #[test]
    fn aws_and_google_batch() {
        let aws = [
            ("AWS_BATCH_JOB_ARRAY_INDEX", "0"),
            ("AWS_BATCH_JOB_ARRAY_SIZE", "4"),
        ];
        assert_eq!(shard(&aws, None), ok(0, 4, Scheduler::AwsBatch));
        let gcp = [("BATCH_TASK_INDEX", "9"), ("BATCH_TASK_COUNT", "10")];
        assert_eq!(shard(&gcp, None), ok(9, 10, Scheduler::GoogleBatch));
        // A missing count can come from the user.
        let aws_no_size = [("AWS_BATCH_JOB_ARRAY_INDEX", "2")];
        assert!(err(&aws_no_size, None).contains("AWS_BATCH_JOB_ARRAY_SIZE"));
        assert_eq!(shard(&aws_no_size, Some(3)), ok(2, 3, Scheduler::AwsBatch));
    }

    #[test]
    fn nothing_set_lists_what_was_looked_for() {
        let e = err(&[("HOME", "/root"), ("SLURM_ARRAY_TASK_ID", "")], None);
        for name in [
            "SLURM_ARRAY_TASK_ID",
            "JOB_COMPLETION_INDEX",
            "AWS_BATCH_JOB_ARRAY_INDEX",
            "BATCH_TASK_INDEX",
            "--shard I/N",
        ] {
            assert!(e.contains(name), "{name} in {e}");
        }
    }

    #[test]
    fn a_variable_that_is_not_a_number_is_named_with_its_value() {
        let e = err(&[("SLURM_ARRAY_TASK_ID", "3a")], Some(8));
        assert!(
            e.contains("SLURM_ARRAY_TASK_ID") && e.contains("\"3a\""),
            "{e}"
        );
        let e = err(
            &[("BATCH_TASK_INDEX", "1"), ("BATCH_TASK_COUNT", "-4")],
            None,
        );
        assert!(
            e.contains("BATCH_TASK_COUNT") && e.contains("\"-4\""),
            "{e}"
        );
        let e = err(&[("JOB_COMPLETION_INDEX", "1.5")], Some(2));
        assert!(
            e.contains("JOB_COMPLETION_INDEX") && e.contains("\"1.5\""),
            "{e}"
        );
    }

    #[test]
    fn index_not_below_count_and_zero_counts_are_refused() {
        let e = err(
            &[("BATCH_TASK_INDEX", "4"), ("BATCH_TASK_COUNT", "4")],
            None,
        );
        assert!(e.contains("index 4") && e.contains("shard count 4"), "{e}");
        let e = err(
            &[
                ("AWS_BATCH_JOB_ARRAY_INDEX", "0"),
                ("AWS_BATCH_JOB_ARRAY_SIZE", "0"),
            ],
            None,
        );
        assert!(e.contains("0 tasks"), "{e}");
    }

    #[test]
    fn the_users_count_must_agree_with_the_schedulers() {
        let slurm = [
            ("SLURM_ARRAY_TASK_ID", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
        ];
        let e = err(&slurm, Some(4));
        assert!(e.contains("auto/4") && e.contains("8"), "{e}");
        assert!(e.contains("SLURM_ARRAY_TASK_COUNT=8"), "{e}");
    }

    #[test]
    fn two_schedulers_must_agree() {
        let both = [
            ("SLURM_ARRAY_TASK_ID", "3"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
            ("JOB_COMPLETION_INDEX", "1"),
        ];
        let e = err(&both, Some(8));
        assert!(e.contains("SLURM") && e.contains("Kubernetes"), "{e}");
        assert!(e.contains("3/8") && e.contains("1/8"), "{e}");
        assert!(
            e.contains("SLURM_ARRAY_TASK_ID=3") && e.contains("JOB_COMPLETION_INDEX=1"),
            "{e}"
        );
        // The same answer from both is fine (the first is named).
        let agreeing = [
            ("SLURM_ARRAY_TASK_ID", "1"),
            ("SLURM_ARRAY_TASK_COUNT", "8"),
            ("JOB_COMPLETION_INDEX", "1"),
        ];
        assert_eq!(shard(&agreeing, Some(8)), ok(1, 8, Scheduler::Slurm));
    }

    #[test]
    fn shard_specs_parse_and_resolve() {
        let parse = |s: &str| s.parse::<ShardSpec>().map_err(|e| e.to_string());
        assert_eq!(parse("auto"), Ok(ShardSpec::Auto { count: None }));
        assert_eq!(parse("auto/8"), Ok(ShardSpec::Auto { count: Some(8) }));
        assert_eq!(
            parse("2/5"),
            Ok(ShardSpec::Fixed(Shard { index: 2, count: 5 }))
        );
        for bad in ["auto/0", "auto/", "auto/x", "autox", "5/5", "auto8"] {
            assert!(parse(bad).is_err(), "{bad}");
        }
        for s in ["auto", "auto/8", "2/5"] {
            assert_eq!(parse(s).unwrap().to_string(), s);
        }
        let fixed = ShardSpec::Fixed(Shard { index: 1, count: 2 });
        let slurm = [
            ("SLURM_ARRAY_TASK_ID", "0"),
            ("SLURM_ARRAY_TASK_COUNT", "2"),
        ];
        assert_eq!(
            fixed.resolve(env(&slurm)).unwrap(),
            (Shard { index: 1, count: 2 }, None),
            "a fixed shard ignores the environment"
        );
        assert_eq!(
            ShardSpec::Auto { count: None }
                .resolve(env(&slurm))
                .unwrap(),
            (Shard { index: 0, count: 2 }, Some(Scheduler::Slurm))
        );
    }
}
