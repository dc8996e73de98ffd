//! The simulation engine: particles, box, regions, neighbours, contact models, fixes,
//! computes and the integrator. Commands in [`crate::commands`] configure it.

pub mod accel;
pub mod buoyancy;
pub mod cells;
pub mod checks;
pub mod clumps;
pub mod computes;
pub mod contact;
pub mod error;
pub mod extras;
pub mod fix_columns;
pub mod fixes;
pub mod granular;
pub mod heat;
pub mod insert;
pub mod integrate;
pub mod lattice;
pub mod local_vtk;
pub mod margin;
pub mod massflow;
pub mod mesh;
pub mod mesh_motion;
pub mod mesh_servo;
pub mod mesh_stress;
pub mod mesh_wall;
pub mod mirror_history;
pub mod momentum;
pub mod multisphere;
pub mod neighbor;
pub mod nve_noforce;
pub mod planar;
pub mod procmap;
pub mod region;
pub mod region_motion;
pub mod restart_fixes;
pub mod restart_state;
pub mod rigid_body;
pub mod sim;
pub mod temperature;
pub mod tet_mesh;
pub mod thermo;
pub mod tracer;
pub mod wet;

pub use crate::state::{domain, particles};
