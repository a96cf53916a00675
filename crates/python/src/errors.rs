//! The package's exception classes and how library errors map onto them. Each exception
//! carries the message the CLI prints for the same failure: what was being done, then each
//! cause once.

use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyUserWarning};
use pyo3::prelude::*;
use scenethesis_agents::{PlanError, PlanFileError};
use scenethesis_pipeline::batch::error_chain;
use scenethesis_pipeline::PipelineError;
use scenethesis_setup::SetupError;

create_exception!(
    scenethesis,
    ScenethesisError,
    PyException,
    "Base class of every error scenethesis raises."
);
create_exception!(
    scenethesis,
    InvalidInputError,
    ScenethesisError,
    "A prompt, plan, setting, file or folder scenethesis cannot use; the message names it."
);
create_exception!(
    scenethesis,
    ProviderError,
    ScenethesisError,
    "A model provider (an OpenAI-compatible server or its response cache) failed or answered \
     something unusable; the message names the endpoint and model."
);
create_exception!(
    scenethesis,
    SceneRejectedError,
    ScenethesisError,
    "The judge did not accept the scene and strict=True was asked; `.scene` holds it."
);

/// Which exception class a failure raises.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Bad input: [`InvalidInputError`].
    Input,
    /// A model provider failed: [`ProviderError`].
    Provider,
    /// Anything else (a write failed, an internal error): [`ScenethesisError`].
    Other,
}

/// A failure of a native call, classified, with the message the CLI would print.
#[derive(Debug)]
pub struct Failure {
    kind: Kind,
    message: String,
}

impl Failure {
    fn new(kind: Kind, context: Option<String>, error: &(dyn std::error::Error + 'static)) -> Self {
        let chain = error_chain(error);
        let message = match context {
            Some(context) => format!("{context}: {chain}"),
            None => chain,
        };
        let kind = if from_provider(error) {
            Kind::Provider
        } else {
            kind
        };
        Self {
            kind,
            message: scenethesis_scene_graph::printable(&message).into_owned(),
        }
    }

    /// A pipeline error while `context` was being done.
    pub fn pipeline(error: &PipelineError, context: String) -> Self {
        Self::new(pipeline_kind(error), Some(context), error)
    }

    /// A pipeline that could not be built from its settings.
    pub fn setup(error: SetupError) -> Self {
        let kind = match error {
            SetupError::Client(_) => Kind::Provider,
            SetupError::NoRenderer(_) => Kind::Other,
            SetupError::Pipeline(ref e) => pipeline_kind(e),
            _ => Kind::Input,
        };
        Self::new(kind, None, &error)
    }

    /// A plan given as JSON that cannot be used.
    pub fn plan_file(error: PlanFileError) -> Self {
        Self::new(Kind::Input, Some("reading the plan".into()), &error)
    }

    /// Bad input while `context` was being done.
    pub fn input(error: &(dyn std::error::Error + 'static), context: String) -> Self {
        Self::new(Kind::Input, Some(context), error)
    }

    /// Any other failure while `context` was being done.
    pub fn other(error: &(dyn std::error::Error + 'static), context: String) -> Self {
        Self::new(Kind::Other, Some(context), error)
    }

    /// The Python exception to raise.
    pub fn into_py(self) -> PyErr {
        match self.kind {
            Kind::Input => InvalidInputError::new_err(self.message),
            Kind::Provider => ProviderError::new_err(self.message),
            Kind::Other => ScenethesisError::new_err(self.message),
        }
    }
}

/// Whether a model provider's error is anywhere in the chain.
fn from_provider(error: &(dyn std::error::Error + 'static)) -> bool {
    let mut cause = Some(error);
    while let Some(e) = cause {
        if e.is::<scenethesis_models::ProviderError>() {
            return true;
        }
        cause = e.source();
    }
    false
}

fn pipeline_kind(error: &PipelineError) -> Kind {
    match error {
        PipelineError::Plan(PlanError::Provider { .. } | PlanError::InvalidPlan { .. }) => {
            Kind::Provider
        }
        PipelineError::Plan(_)
        | PipelineError::BadOutput { .. }
        | PipelineError::Read { .. }
        | PipelineError::Batch(_)
        | PipelineError::SceneIo(_)
        | PipelineError::Asset(_) => Kind::Input,
        _ => Kind::Other,
    }
}

/// Issues each of `warnings` as a Python `UserWarning`.
pub fn warn_all(py: Python<'_>, warnings: &[String]) -> PyResult<()> {
    let category = py.get_type::<PyUserWarning>();
    for warning in warnings {
        let text = scenethesis_scene_graph::printable(warning);
        let text = std::ffi::CString::new(text.replace('\0', "\\0")).expect("no NUL left");
        PyErr::warn(py, &category, &text, 2)?;
    }
    Ok(())
}

/// Adds the exception classes to the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("ScenethesisError", py.get_type::<ScenethesisError>())?;
    m.add("InvalidInputError", py.get_type::<InvalidInputError>())?;
    m.add("ProviderError", py.get_type::<ProviderError>())?;
    m.add("SceneRejectedError", py.get_type::<SceneRejectedError>())?;
    Ok(())
}
