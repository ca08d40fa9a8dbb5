//! The `run`, `check` and `import` subcommands of the `mechdiff` tool (scene files).

pub mod check;
pub mod import;
pub mod run;
