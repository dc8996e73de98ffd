//! Plain simulation state shared by the engine and the file readers and writers: the box,
//! the particle arrays, the body tags of clumped spheres, the per-contact fields of local
//! computes, and the limits checked where values are set. Nothing here runs a step.

pub mod bodies;
pub mod domain;
pub mod limits;
pub mod local_field;
pub mod particles;
