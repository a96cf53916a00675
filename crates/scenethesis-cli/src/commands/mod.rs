//! One module per subcommand; `main` only parses arguments and dispatches.

pub mod eval;
pub mod validate;
