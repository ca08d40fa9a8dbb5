//! The `run` and `check` subcommands of the `mechdiff` tool (scene files).

pub mod check;
pub mod run;
