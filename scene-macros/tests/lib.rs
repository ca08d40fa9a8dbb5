//! The integration tests of `mechdiff-scene-macros`, one module per topic, compiled and
//! linked as one test binary.

mod scene_module;
