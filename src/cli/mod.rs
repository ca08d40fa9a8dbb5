//! The `run` and `check` subcommands of the `mechdiff` tool (scene files).

pub mod accuracy;
pub mod cam;
pub mod check;
pub mod run;
