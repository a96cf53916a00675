//! Stage progress reported to an optional Python callable.

use std::time::Duration;

use pyo3::prelude::*;
use scenethesis_pipeline::{Progress, Stage};

/// Calls `callback(stage, event, round, seconds, note)` as each stage starts (`event`
/// "started", 0 seconds) and finishes ("finished"), re-acquiring the GIL only for the call.
/// The first exception the callback raises is kept, ends the run before its next stage and is
/// raised then; so does an interrupt (Ctrl-C) that Python's signal handlers turn into one.
pub struct PyProgress {
    callback: Option<Py<PyAny>>,
    error: Option<PyErr>,
}

impl PyProgress {
    /// Progress reported to `callback`, or nowhere.
    pub fn new(callback: Option<Py<PyAny>>) -> Self {
        Self {
            callback,
            error: None,
        }
    }

    fn call(&mut self, stage: Stage, event: &str, round: usize, seconds: f64, note: &str) {
        let Some(callback) = &self.callback else {
            return;
        };
        if self.error.is_some() {
            return;
        }
        let result = Python::attach(|py| {
            callback
                .call1(py, (stage.as_str(), event, round, seconds, note))
                .map(drop)
        });
        if let Err(e) = result {
            self.error = Some(e);
        }
    }

    /// Raises the callback's first exception, if it raised one.
    pub fn raise_if_failed(&mut self) -> PyResult<()> {
        match self.error.take() {
            Some(e) => Err(e),
            None => Ok(()),
        }
    }
}

impl Progress for PyProgress {
    fn stage_started(&mut self, stage: Stage, round: usize) {
        self.call(stage, "started", round, 0.0, "");
    }

    fn stage_finished(&mut self, stage: Stage, round: usize, elapsed: Duration, note: &str) {
        self.call(stage, "finished", round, elapsed.as_secs_f64(), note);
    }

    fn stop_requested(&mut self) -> bool {
        if self.error.is_none() {
            // Runs the signal handlers (on the main thread only; elsewhere this is a no-op).
            if let Err(e) = Python::attach(|py| py.check_signals()) {
                self.error = Some(e);
            }
        }
        self.error.is_some()
    }
}
