//! The LIGGGHTS input interpreter: reads a deck line by line (echo, comments, `$`
//! substitution, words), runs the control-flow commands (`next`, `jump`, `label`, `if`,
//! `include`, `print`, ...) and hands every other command to the command layer.

pub mod interp;
