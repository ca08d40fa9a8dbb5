//! The integration tests of `mechdiff` (the facade library and the CLI), one module per
//! topic, compiled and linked as one test binary.

mod common;

mod accuracy_command;
mod accuracy_scenes;
mod accuracy_whitworth;
mod authoring;
mod bad_scenes;
mod balancing_scenes;
mod cam_joint_scene;
mod cam_scenes;
mod cli;
mod cli_formula;
mod codegen_command;
mod codegen_constants;
mod codegen_fuzz;
mod codegen_piecewise;
mod conventions;
mod dynamics_scenes;
mod fuzz_scenes;
mod hard_cases;
mod import;
mod joint_types;
mod linkage_metrics;
mod motion_scenes;
mod parameter_study;
mod pictures;
mod report_in_browser;
mod run_evaluator;
mod scene_codegen;
mod scene_inputs;
mod scene_jerk;
mod scene_tangent;
mod scenes;
mod sensitivity;
mod sensitivity_dynamics;
mod sensitivity_exact;
mod sensitivity_methods;
mod streaming;
mod sweep_limits;
mod synthesis_scenes;
mod synthesize_cli;
mod user_files;
mod whitworth_report;
