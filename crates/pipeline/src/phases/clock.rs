//! Stage timing and progress: every phase runs inside [`StageClock::run`], which announces it,
//! times it and adds the time to the run's per-stage totals.

use std::collections::BTreeMap;
use std::time::{Duration, Instant};

use crate::report::{PartTiming, StageTiming};
use crate::stage::{Progress, Stage};
use crate::PipelineError;

/// Announces stages to a [`Progress`] and sums their wall-clock time.
pub(crate) struct StageClock<'p> {
    progress: &'p mut dyn Progress,
    totals: BTreeMap<Stage, f64>,
    /// Per stage, its parts' seconds in the order first reported.
    parts: BTreeMap<Stage, Vec<(&'static str, f64)>>,
    started: Instant,
    limit: Option<Duration>,
}

impl<'p> StageClock<'p> {
    /// A clock started now, for a run of at most `limit`.
    pub(crate) fn new(progress: &'p mut dyn Progress, limit: Option<Duration>) -> Self {
        Self {
            progress,
            totals: BTreeMap::new(),
            parts: BTreeMap::new(),
            started: Instant::now(),
            limit,
        }
    }

    /// `Ok` while the run's time limit is not spent and the progress has not asked to stop;
    /// checked before `stage` of `round` starts.
    pub(crate) fn check(&mut self, stage: Stage, round: usize) -> Result<(), PipelineError> {
        if self.progress.stop_requested() {
            return Err(PipelineError::Stopped { stage, round });
        }
        match self.limit {
            Some(limit) if self.started.elapsed() >= limit => Err(PipelineError::OutOfTime {
                stage,
                round,
                limit_seconds: limit.as_secs_f64(),
            }),
            _ => Ok(()),
        }
    }

    /// When the run's time limit runs out (`None`: no limit, or one past what the clock can
    /// represent).
    pub(crate) fn deadline(&self) -> Option<Instant> {
        self.limit.and_then(|limit| self.started.checked_add(limit))
    }

    /// Runs `work` as `stage` of `round`; on success the progress hears `note` of its result.
    pub(crate) fn run<T, E>(
        &mut self,
        stage: Stage,
        round: usize,
        work: impl FnOnce() -> Result<T, E>,
        note: impl FnOnce(&T) -> String,
    ) -> Result<T, E> {
        self.progress.stage_started(stage, round);
        let listener = self.progress.answer_listener(stage, round);
        let started = Instant::now();
        let result = scenethesis_models::with_answer_listener(listener, work);
        *self.totals.entry(stage).or_default() += started.elapsed().as_secs_f64();
        let value = result?;
        self.progress
            .stage_finished(stage, round, started.elapsed(), &note(&value));
        Ok(value)
    }

    /// Runs `work` as part of `stage`, adding its time to the stage's total without
    /// announcing it.
    pub(crate) fn run_quietly<T, E>(
        &mut self,
        stage: Stage,
        work: impl FnOnce() -> Result<T, E>,
    ) -> Result<T, E> {
        let started = Instant::now();
        let result = work();
        *self.totals.entry(stage).or_default() += started.elapsed().as_secs_f64();
        result
    }

    /// Runs `work`, which cannot fail, as `stage` of `round`.
    pub(crate) fn run_infallible<T>(
        &mut self,
        stage: Stage,
        round: usize,
        work: impl FnOnce() -> T,
        note: impl FnOnce(&T) -> String,
    ) -> T {
        match self.run(
            stage,
            round,
            || Ok::<T, std::convert::Infallible>(work()),
            note,
        ) {
            Ok(value) => value,
            Err(never) => match never {},
        }
    }

    /// Announces `stage` of `round` as run elsewhere (on a thread of its own, beside other
    /// stages) and adds the `elapsed` time it took there to the stage's total.
    pub(crate) fn record(&mut self, stage: Stage, round: usize, elapsed: Duration, note: &str) {
        self.progress.stage_started(stage, round);
        *self.totals.entry(stage).or_default() += elapsed.as_secs_f64();
        self.progress.stage_finished(stage, round, elapsed, note);
    }

    /// Adds the seconds of `stage`'s parts, as the stage measured them, to their totals.
    pub(crate) fn add_parts(&mut self, stage: Stage, parts: &[(&'static str, f64)]) {
        let totals = self.parts.entry(stage).or_default();
        for &(name, seconds) in parts {
            match totals.iter_mut().find(|(n, _)| *n == name) {
                Some(total) => total.1 += seconds,
                None => totals.push((name, seconds)),
            }
        }
    }

    /// The per-stage totals with their parts, in stage order.
    pub(crate) fn timings(&self) -> Vec<StageTiming> {
        Stage::ALL
            .iter()
            .filter_map(|s| {
                let parts = self.parts.get(s).map_or(&[][..], Vec::as_slice);
                self.totals.get(s).map(|&seconds| StageTiming {
                    stage: *s,
                    seconds,
                    parts: parts
                        .iter()
                        .map(|&(part, seconds)| PartTiming {
                            part: part.to_owned(),
                            seconds,
                        })
                        .collect(),
                })
            })
            .collect()
    }
}
