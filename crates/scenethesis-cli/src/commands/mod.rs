//! One module per subcommand; `main` only parses arguments and dispatches.

pub mod assets;
pub mod eval;
pub mod render;
pub mod validate;
