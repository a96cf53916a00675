//! What the CLI's integration tests share: running the built binary with a clean provider
//! environment, and its output as one string.

#![allow(dead_code)] // each test binary uses its own subset

use std::process::{Command, Output};

/// The environment variables that choose providers; removed so a developer's shell cannot
/// change what a test runs.
const PROVIDER_VARS: [&str; 6] = [
    "OPENAI_BASE_URL",
    "OPENAI_API_KEY",
    "SCENETHESIS_LLM_MODEL",
    "SCENETHESIS_VLM_MODEL",
    "SCENETHESIS_IMAGE_MODEL",
    "RUST_LOG",
];

/// Runs `scenethesis ARGS` with no provider configured from the environment and, when `key` is
/// given, `OPENAI_API_KEY` set to it (tests then check that it is never printed).
pub fn scenethesis_with_key(key: Option<&str>, args: &[&str]) -> Output {
    let mut cmd = Command::new(env!("CARGO_BIN_EXE_scenethesis"));
    for var in PROVIDER_VARS {
        cmd.env_remove(var);
    }
    if let Some(key) = key {
        cmd.env("OPENAI_API_KEY", key);
    }
    cmd.args(args).output().expect("run scenethesis")
}

/// Standard output followed by standard error, for assertion messages and searches.
pub fn text(out: &Output) -> String {
    format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    )
}
