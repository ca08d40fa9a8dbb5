//! The integration tests of `mechdiff-core`, one module per topic, compiled and linked as
//! one test binary.

mod common;

mod balancing_linkage;
mod balancing_rotor;
mod cams_geometry;
mod cams_joint;
mod cams_laws;
mod cams_program;
mod cams_reference_002;
mod dynamics_errors;
mod dynamics_four_bar;
mod dynamics_joints;
mod dynamics_plan;
mod dynamics_properties;
mod dynamics_rack_slotted_link;
mod dynamics_tangent;
mod dynamics_whitworth;
mod geometry_closed_form;
mod geometry_errors;
mod geometry_joints;
mod geometry_parametric;
mod geometry_rack_slotted_link;
mod geometry_sweep_properties;
mod geometry_sweeps;
mod geometry_trace;
mod geometry_whitworth;
mod linkage_metrics;
mod machine_motion;
mod symbolic_evaluator_edges;
mod symbolic_hard_points;
mod symbolic_limits;
mod symbolic_random_expressions;
mod symbolic_reference_precision;
mod symbolic_removable;
mod symbolic_rules;
mod symbolic_signs;
mod synthesis_bad_input;
mod synthesis_known_answers;
mod synthesis_literature;
