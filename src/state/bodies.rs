//! The per-particle body tag of clumped spheres (`fix multisphere`): which particles belong
//! to a rigid body, as the dump's `mol` column shows it.

use crate::state::particles::Particles;

/// Name of the per-particle array holding the body tag (-1: not in a body).
pub const BODY_ARRAY: &str = "multisphere_body";

/// Index of the body-tag array in `p.extra`, if any particle array exists for it.
pub fn body_array(p: &Particles) -> Option<usize> {
    p.extra.iter().position(|e| e.name == BODY_ARRAY)
}

/// The body tags of the particles (None when no clump was ever created).
pub fn body_tags(p: &Particles) -> Option<&[f64]> {
    body_array(p).map(|k| &p.extra[k].data[..])
}

/// True if particle `i` belongs to a body (`tags` from [`body_tags`]).
#[inline]
pub fn is_member(tags: Option<&[f64]>, i: usize) -> bool {
    tags.is_some_and(|t| t[i] >= 0.0)
}
