//! `plan.json`: a plan saved for editing and building later (`scenethesis plan`, then
//! `scenethesis generate --plan`). The format is the serde form of
//! [`scenethesis_agents::Plan`], documented in `docs/plan.md`; reading and checking it is
//! [`scenethesis_agents::FixedPlanner::from_file`].

use std::io::Write;
use std::path::Path;

use scenethesis_agents::Plan;

use crate::error::PipelineError;

/// The conventional file name of a saved plan.
pub const PLAN_JSON: &str = "plan.json";

/// The text of a plan file: pretty-printed JSON and a final newline.
pub fn plan_json(plan: &Plan) -> String {
    let mut text = serde_json::to_string_pretty(plan).expect("a plan serializes to JSON");
    text.push('\n');
    text
}

/// Writes `plan` to `path` atomically: the text goes to a temporary file beside `path`, which
/// is then renamed over it, so a reader never sees half a plan. An existing file is replaced
/// only when `replace` is set; a directory never is.
pub fn write_plan(path: &Path, plan: &Plan, replace: bool) -> Result<(), PipelineError> {
    if path.is_dir() {
        return Err(PipelineError::BadOutput {
            path: path.to_owned(),
            reason: "is a directory; expected the path of a plan file (e.g. plan.json)".into(),
        });
    }
    if !replace && path.exists() {
        return Err(PipelineError::BadOutput {
            path: path.to_owned(),
            reason: "already exists; pass --force to replace it".into(),
        });
    }
    let write_error = |source: std::io::Error| PipelineError::Write {
        path: path.to_owned(),
        source,
    };
    let dir = match path.parent() {
        Some(d) if !d.as_os_str().is_empty() => d,
        _ => Path::new("."),
    };
    let mut tmp = tempfile::Builder::new()
        .prefix(".plan.")
        .suffix(".tmp")
        .tempfile_in(dir)
        .map_err(write_error)?;
    tmp.write_all(plan_json(plan).as_bytes())
        .and_then(|()| tmp.as_file().sync_all())
        .map_err(write_error)?;
    if replace {
        tmp.persist(path).map_err(|e| write_error(e.error))?;
    } else {
        tmp.persist_noclobber(path)
            .map_err(|e| write_error(e.error))?;
    }
    Ok(())
}
