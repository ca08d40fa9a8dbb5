//! The `run` and `check` subcommands of the `mechdiff` tool (scene files).

pub mod cam;
pub mod accuracy;
pub mod check;
pub mod run;
