//! `compute pair/gran/local`: one row per touching particle pair with the chosen contact
//! fields, re-evaluated at output in LIGGGHTS 3.8.0's row order
//! (compute_pair_gran_local.cpp).

use crate::commands::compute::ComputeDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle, LocalField, LocalRows};
use crate::engine::error::EngineError;
use crate::engine::neighbor::{BinOrder, Pair};
use crate::engine::particles::Particles;
use crate::engine::sim::Simulation;

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
    let order = RowOrder::of(sim);
    let mut out = Vec::new();
    let mut keyed: Vec<(RowKey, usize)> = Vec::new();
    for (k, fi, ti, fj, tj) in pair.contacts(
        p,
        pairs,
        &sim.history,
        sim.dt,
        (&sim.force_time_state.0, &sim.force_time_state.1),
    ) {
        let pr = &pairs[k];
        let (i, j) = (pr.i as usize, pr.j as usize);
        if p.mask[i] & at.group == 0 || p.mask[j] & at.group == 0 {
            continue;
        }
        let side = order.reporting_side(p, pr, (fi, ti), (fj, tj));
        keyed.push((order.key(p, &side), out.len()));
        let history = &sim.history[k * width..(k + 1) * width];
        let contact = Contact::between(p, &side);
        push_row(&mut out, fields, p, &side, &contact, (history, &flips));
    }
    Ok((ncols, sorted_rows(keyed, &out, ncols)))
}

/// A row's place in LIGGGHTS's order: (reporting atom, partner's bin, partner).
type RowKey = (usize, [i64; 3], usize);

/// LIGGGHTS's row order: by the reporting atom, then its partners in bin order (positions
/// of the last list build, ghosts of periodic partners beyond the box).
struct RowOrder<'a> {
    /// The bins of the last list build.
    bins: BinOrder,
    /// The particle positions at the last list build (length).
    built: &'a [[f64; 3]],
    /// The exact path's place of each particle when the fast path keeps its own order:
    /// pairs are reported and their rows ordered as the exact path (LIGGGHTS) does.
    exact: Option<&'a [f64]>,
}

/// A touching pair as its row reports it: from particle `i` to particle `j`, whose ghost
/// across a periodic face lies `shift` (length) away; force and torque on `i`.
struct Side {
    i: usize,
    j: usize,
    periodic: bool,
    shift: [f64; 3],
    force: [f64; 3],
    torque: [f64; 3],
    /// -1 when the pair is reported from its second particle (signed history flips).
    sign: f64,
}

impl<'a> RowOrder<'a> {
    fn of(sim: &'a Simulation) -> Self {
        RowOrder {
            bins: BinOrder::sized(
                sim.domain.lo,
                sim.domain.hi,
                sim.neighbor.cutneighmax,
                sim.extras.neigh_binsize,
            ),
            built: sim.list.built_positions(),
            exact: sim.exact_rank().filter(|r| r.len() == sim.particles.len()),
        }
    }

    /// Particle `k`'s place in the exact path's order.
    fn place(&self, k: usize) -> usize {
        self.exact.map_or(k, |r| r[k] as usize)
    }

    /// The side pair `pr` is reported from: across a periodic face LIGGGHTS reports the
    /// pair from the atom with the larger ID (its ghost partner carries the shift), other
    /// pairs from the atom first in its order. `on_i` and `on_j` are (force, torque) on
    /// each particle.
    fn reporting_side(
        &self,
        p: &Particles,
        pr: &Pair,
        on_i: ([f64; 3], [f64; 3]),
        on_j: ([f64; 3], [f64; 3]),
    ) -> Side {
        let (i, j) = (pr.i as usize, pr.j as usize);
        let periodic = pr.shift != [0.0; 3];
        let from_j = if periodic {
            p.id[i] < p.id[j]
        } else {
            self.place(i) > self.place(j)
        };
        if from_j {
            Side {
                i: j,
                j: i,
                periodic,
                shift: pr.shift.map(|v| -v),
                force: on_j.0,
                torque: on_j.1,
                sign: -1.0,
            }
        } else {
            Side {
                i,
                j,
                periodic,
                shift: pr.shift,
                force: on_i.0,
                torque: on_i.1,
                sign: 1.0,
            }
        }
    }

    /// The row's sort key.
    fn key(&self, p: &Particles, side: &Side) -> RowKey {
        let xb = self.built.get(side.j).copied().unwrap_or(p.x[side.j]);
        (
            self.place(side.i),
            self.bins.bin([0, 1, 2].map(|d| xb[d] + side.shift[d])),
            self.place(side.j),
        )
    }
}

/// The geometry of a reported contact: the partner's ghost position, the unit vector from
/// `i` to `j` along which forces are split, the radii and the centre distance.
struct Contact {
    xi: [f64; 3],
    xj_ghost: [f64; 3],
    normal: [f64; 3],
    ri: f64,
    rj: f64,
    /// The squared centre distance (length^2).
    rsq: f64,
    /// The centre distance (length).
    r: f64,
}

impl Contact {
    fn between(p: &Particles, side: &Side) -> Contact {
        let (i, j, shift) = (side.i, side.j, side.shift);
        let xi = p.x[i];
        let xj_ghost = [
            p.x[j][0] + shift[0],
            p.x[j][1] + shift[1],
            p.x[j][2] + shift[2],
        ];
        let mut normal = [
            xj_ghost[0] - xi[0],
            xj_ghost[1] - xi[1],
            xj_ghost[2] - xi[2],
        ];
        let len = (normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]).sqrt();
        if len > 0.0 {
            normal = normal.map(|c| c / len);
        }
        let del = [
            xi[0] - xj_ghost[0],
            xi[1] - xj_ghost[1],
            xi[2] - xj_ghost[2],
        ];
        let rsq = del[0] * del[0] + del[1] * del[1] + del[2] * del[2];
        Contact {
            xi,
            xj_ghost,
            normal,
            ri: p.radius[i],
            rj: p.radius[j],
            rsq,
            r: rsq.sqrt(),
        }
    }

    /// LIGGGHTS's contact area of two overlapping spheres (length^2).
    fn area(&self) -> f64 {
        let (r, ri, rj) = (self.r, self.ri, self.rj);
        -std::f64::consts::PI / 4.0
            * ((r - ri - rj) * (r + ri - rj) * (r - ri + rj) * (r + ri + rj))
            / self.rsq
    }
}

/// Append the row of a reported contact: each field's values in `fields` order;
/// `history` is the pair's stored history and which of its values flip sign with the
/// reporting side.
fn push_row(
    out: &mut Vec<f64>,
    fields: &[LocalField],
    p: &Particles,
    side: &Side,
    c: &Contact,
    history: (&[f64], &[bool]),
) {
    let (i, j) = (side.i, side.j);
    for field in fields {
        match field {
            LocalField::Pos => {
                out.extend_from_slice(&c.xi);
                out.extend_from_slice(&p.x[j]);
            }
            LocalField::Vel => {
                out.extend_from_slice(&p.v[i]);
                out.extend_from_slice(&p.v[j]);
            }
            LocalField::Id => {
                out.push(p.id[i] as f64);
                out.push(p.id[j] as f64);
                out.push(if side.periodic { 1.0 } else { 0.0 });
            }
            LocalField::Force
            | LocalField::ForceNormal
            | LocalField::ForceTangential
            | LocalField::Torque
            | LocalField::TorqueNormal
            | LocalField::TorqueTangential => {
                out.extend_from_slice(&force_torque(*field, side.force, side.torque, c.normal))
            }
            LocalField::History => {
                out.extend(
                    history
                        .0
                        .iter()
                        .zip(history.1)
                        .map(|(h, &f)| if f { h * side.sign } else { *h }),
                )
            }
            LocalField::ContactArea => out.push(c.area()),
            LocalField::Delta => out.push(c.ri + c.rj - c.r),
            LocalField::HeatFlux => out.push(0.0),
            LocalField::ContactPoint => {
                for d in 0..3 {
                    out.push((c.xi[d] * c.rj + c.xj_ghost[d] * c.ri) / (c.ri + c.rj));
                }
            }
        }
    }
}

/// The rows of `out` (`ncols` values each, at the indices `keyed` holds) in the order of
/// their keys.
fn sorted_rows(mut keyed: Vec<(RowKey, usize)>, out: &[f64], ncols: usize) -> Vec<f64> {
    keyed.sort_by_key(|(key, _)| *key);
    let mut sorted = Vec::with_capacity(out.len());
    for (_, at) in keyed {
        sorted.extend_from_slice(&out[at..at + ncols]);
    }
    sorted
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
