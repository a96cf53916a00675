//! One module per subcommand; `main` only parses arguments and dispatches.

pub mod assets;
pub mod batch;
pub mod eval;
pub mod export;
pub mod generate;
pub mod guide;
pub mod plan;
pub mod providers;
pub mod render;
pub mod roundtrip;
pub mod validate;
