//! Proc-macros of mechdiff (see the symbolic-engine issue).
