//! The integration tests of `mechdiff-mechanisms`, one module per topic, compiled and
//! linked as one test binary.

mod common;

mod whitworth_errors;
mod whitworth_methods;
mod whitworth_symbolic;
mod whitworth_table;
