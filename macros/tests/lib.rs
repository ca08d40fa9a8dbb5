//! The integration tests of `mechdiff-macros`, one module per topic, compiled and linked
//! as one test binary.

mod agree_with_dual;
