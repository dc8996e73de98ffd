//! `compute pair/gran/local`: one row per touching particle pair with the chosen contact
//! fields, re-evaluated at output in LIGGGHTS 3.8.0's row order
//! (compute_pair_gran_local.cpp).

use crate::commands::compute::ComputeDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle, LocalField, LocalRows};
use crate::engine::error::EngineError;

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "pair/gran/local",
    "compute ID GROUP pair/gran/local [FIELDS...]",
    &[],
    "per-contact positions, forces, overlaps of particle pairs",
);

/// `compute pair/gran/local`: one row per touching pair with the selected fields.
#[derive(Debug)]
pub struct PairGranLocal {
    /// The fields, in LIGGGHTS's column order.
    pub fields: Vec<LocalField>,
}

/// The three values of one of a local compute's force or torque fields: the force (or
/// torque) on the particle, or its part along the unit `normal`, or the rest.
pub(super) fn force_torque(
    field: LocalField,
    f: [f64; 3],
    t: [f64; 3],
    normal: [f64; 3],
) -> [f64; 3] {
    use crate::engine::contact::split;
    match field {
        LocalField::Force => f,
        LocalField::ForceNormal => split(f, normal).0,
        LocalField::ForceTangential => split(f, normal).1,
        LocalField::Torque => t,
        LocalField::TorqueNormal => split(t, normal).0,
        LocalField::TorqueTangential => split(t, normal).1,
        other => unreachable!("{other:?} is not a force or torque field"),
    }
}

impl ComputeStyle for PairGranLocal {
    fn name(&self) -> &str {
        "pair/gran/local"
    }

    fn local_rows(&self) -> Option<LocalRows> {
        Some(LocalRows::VectorOrArray)
    }

    fn local(&self, at: &ComputeAt) -> Result<(usize, Vec<f64>), EngineError> {
        rows(at, &self.fields)
    }

    fn local_fields(&self) -> Option<&[LocalField]> {
        Some(&self.fields)
    }

    fn reads_pair_contacts(&self) -> bool {
        true
    }
}

/// The rows now: (columns per row, values row-major).
fn rows(at: &ComputeAt, fields: &[LocalField]) -> Result<(usize, Vec<f64>), EngineError> {
    let sim = at.sim;
    let Some(pair) = sim.pair.as_ref() else {
        return Err("compute pair/gran/local needs a granular pair style".into());
    };
    let width = pair.history_width();
    let flips = pair.history_flips();
    let ncols: usize = fields.iter().map(|f| f.width(width)).sum();
    let p = &sim.particles;
    let pairs = &sim.list.pairs;
    let mut out = Vec::new();
    // rows in LIGGGHTS's order: by the reporting atom, then its partners in bin order
    // (positions of the last list build, ghosts of periodic partners beyond the box)
    let order = crate::engine::neighbor::BinOrder::sized(
        sim.domain.lo,
        sim.domain.hi,
        sim.neighbor.cutneighmax,
        sim.extras.neigh_binsize,
    );
    let built = sim.list.built_positions();
    // the fast path keeps its own order and records the exact path's: pairs are reported
    // and their rows ordered as the exact path (LIGGGHTS) does, by that order
    let exact = sim.exact_rank().filter(|r| r.len() == p.len());
    let place = |k: usize| exact.map_or(k, |r| r[k] as usize);
    // (reporting atom, partner's bin, partner) and the row's index in `out`
    type RowKey = (usize, [i64; 3], usize);
    let mut keyed: Vec<(RowKey, usize)> = Vec::new();
    for (k, fi, ti, fj, tj) in pair.contacts(
        p,
        pairs,
        &sim.history,
        sim.dt,
        (&sim.force_time_state.0, &sim.force_time_state.1),
    ) {
        let pr = &pairs[k];
        let (mut i, mut j) = (pr.i as usize, pr.j as usize);
        if p.mask[i] & at.group == 0 || p.mask[j] & at.group == 0 {
            continue;
        }
        let periodic = pr.shift != [0.0; 3];
        // across a periodic face LIGGGHTS reports the pair from the atom with the
        // larger ID (its ghost partner carries the shift); other pairs from the atom
        // first in its order
        let mut shift = pr.shift;
        let (mut f, mut t, mut sign) = (fi, ti, 1.0);
        let from_j = if periodic {
            p.id[i] < p.id[j]
        } else {
            place(i) > place(j)
        };
        if from_j {
            std::mem::swap(&mut i, &mut j);
            shift = shift.map(|v| -v);
            f = fj;
            t = tj;
            sign = -1.0;
        }
        let xb = built.get(j).copied().unwrap_or(p.x[j]);
        keyed.push((
            (
                place(i),
                order.bin([0, 1, 2].map(|d| xb[d] + shift[d])),
                place(j),
            ),
            out.len(),
        ));
        let xi = p.x[i];
        let xj_ghost = [
            p.x[j][0] + shift[0],
            p.x[j][1] + shift[1],
            p.x[j][2] + shift[2],
        ];
        // the unit vector from i to j, along which force and torque are split
        let mut normal = [
            xj_ghost[0] - xi[0],
            xj_ghost[1] - xi[1],
            xj_ghost[2] - xi[2],
        ];
        let len = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
        if len > 0.0 {
            normal = normal.map(|c| c / len);
        }
        let (ri, rj) = (p.radius[i], p.radius[j]);
        let del = [
            xi[0] - xj_ghost[0],
            xi[1] - xj_ghost[1],
            xi[2] - xj_ghost[2],
        ];
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        let r = rsq.sqrt();
        for field in fields {
            match field {
                LocalField::Pos => {
                    out.extend_from_slice(&xi);
                    out.extend_from_slice(&p.x[j]);
                }
                LocalField::Vel => {
                    out.extend_from_slice(&p.v[i]);
                    out.extend_from_slice(&p.v[j]);
                }
                LocalField::Id => {
                    out.push(p.id[i] as f64);
                    out.push(p.id[j] as f64);
                    out.push(if periodic { 1.0 } else { 0.0 });
                }
                LocalField::Force
                | LocalField::ForceNormal
                | LocalField::ForceTangential
                | LocalField::Torque
                | LocalField::TorqueNormal
                | LocalField::TorqueTangential => {
                    out.extend_from_slice(&force_torque(*field, f, t, normal))
                }
                LocalField::History => out.extend(
                    sim.history[k * width..(k + 1) * width]
                        .iter()
                        .zip(&flips)
                        .map(|(h, &f)| if f { h * sign } else { *h }),
                ),
                LocalField::ContactArea => out.push(
                    -std::f64::consts::PI / 4.0
                        * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj))
                        / rsq,
                ),
                LocalField::Delta => out.push(ri + rj - r),
                LocalField::HeatFlux => out.push(0.0),
                LocalField::ContactPoint => {
                    for d in 0..3 {
                        out.push((xi[d] * rj + xj_ghost[d] * ri) / (ri + rj));
                    }
                }
            }
        }
    }
    keyed.sort_by_key(|(key, _)| *key);
    let mut sorted = Vec::with_capacity(out.len());
    for (_, at) in keyed {
        sorted.extend_from_slice(&out[at..at + ncols]);
    }
    Ok((ncols, sorted))
}

/// `compute ID GROUP pair/gran/local [FIELD ...]`: one row per touching pair with the
/// fields (LIGGGHTS's defaults without any), defined before the first run.
pub fn build(
    a: &Args,
    ctx: &mut Ctx,
    _def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    if ctx.sim.step > 0 && !ctx.sim.restart_in_progress {
        return Err(a.error(
            2,
            "Compute pair/gran/local: Need to define this compute before first run",
        ));
    }
    let mut fields = Vec::new();
    for i in 3..a.len() {
        let w = a.word(i)?;
        match LocalField::parse(w) {
            Some(LocalField::HeatFlux) => {
                return Err(a.unsupported(i, "compute pair/gran/local heatFlux"))
            }
            Some(f) => fields.push(f),
            None if w == "verbose" => {}
            None if matches!(w, "heatFlux" | "ms_id") => {
                return Err(a.unsupported(i, &format!("compute pair/gran/local {w}")))
            }
            None => return Err(a.error(i, "Compute pair/gran/local: illegal/unrecognized keyword")),
        }
    }
    if a.len() == 3 {
        fields = LocalField::defaults();
    }
    // LIGGGHTS registers the compute with the pair style when it is created
    let Some(sel) = &ctx.sim.pair_selection else {
        return Err(a.error(2, "No pair style is defined for compute pair/gran/local"));
    };
    if ctx
        .sim
        .computes
        .iter()
        .any(|c| c.style().reads_pair_contacts())
    {
        return Err(a.error(2, "Pair gran allows only one compute of type pair/local"));
    }
    if fields.contains(&LocalField::History) && pair_history_width(sel) == 0 {
        return Err(a.error(2, "Compute pair/gran/local or wall/gran/local can not calculate history values since pair or wall style does not compute them"));
    }
    fields.sort();
    fields.dedup();
    Ok(Box::new(PairGranLocal { fields }))
}

/// Doubles of history per neighbour pair the pair style `sel` keeps: the wet bridge and
/// multicontact loops keep their own besides the dry model's.
pub fn pair_history_width(sel: &crate::engine::granular::Selection) -> usize {
    let own = usize::from(sel.cohesion == crate::engine::wet::EASO)
        + if sel.surface == "multicontact" {
            crate::engine::contact::multicontact::PAIR_HISTORY
        } else {
            0
        };
    own + crate::engine::contact::AnyContactModel::new(&crate::engine::wet::dry(sel))
        .map_or(0, |m| m.history_len())
}
