//! The LIGGGHTS input language: lines, words, `$` substitution, variables, expressions and
//! the control-flow commands (`next`, `jump`, `label`, `if`, `include`, `print`, ...).

pub mod error;
pub mod expr;
pub mod interp;
pub mod line;
pub mod scope;
pub mod system;
pub mod variables;
