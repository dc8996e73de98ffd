//! `compute wall/gran/local`: one row per particle-mesh contact of a mesh wall fix with
//! the chosen contact fields, the wall's contacts re-evaluated at output as LIGGGHTS
//! re-runs the wall's loop (docs/notes/wall_gran_local.md).

use crate::commands::compute::pair_gran_local::force_torque;
use crate::commands::compute::ComputeDef;
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::{ComputeAt, ComputeStyle, LocalField, LocalRows};
use crate::engine::error::EngineError;

/// The declared signature.
pub const SPEC: Spec = style(
    "compute",
    "wall/gran/local",
    "compute ID GROUP wall/gran/local [FIELDS...]",
    &[],
    "per-contact data of particles with a wall",
);

/// `compute wall/gran/local`: one row per particle-mesh contact of the mesh wall fix
/// `wall`, with the selected fields.
#[derive(Debug)]
pub struct WallGranLocal {
    /// The fields, in LIGGGHTS's column order.
    pub fields: Vec<LocalField>,
    /// ID of the mesh wall fix.
    pub wall: String,
}

impl ComputeStyle for WallGranLocal {
    fn name(&self) -> &str {
        "wall/gran/local"
    }

    fn local_rows(&self) -> Option<LocalRows> {
        Some(LocalRows::Array)
    }

    fn local(&self, at: &ComputeAt) -> Result<(usize, Vec<f64>), EngineError> {
        rows(at, &self.fields, &self.wall)
    }

    fn local_fields(&self) -> Option<&[LocalField]> {
        Some(&self.fields)
    }

    fn reads_wall(&self) -> Option<&str> {
        Some(&self.wall)
    }
}

/// The rows now: (columns per row, values row-major).
fn rows(
    at: &ComputeAt,
    fields: &[LocalField],
    wall: &str,
) -> Result<(usize, Vec<f64>), EngineError> {
    let sim = at.sim;
    let k = sim
        .fixes
        .iter()
        .position(|f| f.id == wall)
        .ok_or_else(|| format!("Compute wall/gran/local: wall fix {wall} is gone"))?;
    let width = sim.fixes[k]
        .kind
        .mesh_wall()
        .map_or(0, |w| w.history_width());
    let ncols: usize = fields.iter().map(|f| f.width(width)).sum();
    let p = &sim.particles;
    let mut out = Vec::new();
    // LIGGGHTS's row order: mesh, triangle, then the triangle's neighbour list, which
    // walks bins x-outermost, z-innermost (positions of the last list build) and atoms
    // in index order within a bin
    let mut contacts = crate::engine::fixes::mesh_wall_contacts(&sim.fixes, k, p, sim.dt);
    let order = crate::engine::neighbor::BinOrder::sized(
        sim.domain.lo,
        sim.domain.hi,
        sim.neighbor.cutneighmax,
        sim.extras.neigh_binsize,
    );
    let built = sim.list.built_positions();
    contacts.sort_by_cached_key(|c| {
        let x = built.get(c.particle).copied().unwrap_or(p.x[c.particle]);
        let b = order.bin(x);
        (c.mesh, c.tri, b[2], b[1], b[0], c.particle)
    });
    for c in contacts {
        let i = c.particle;
        if p.mask[i] & at.group == 0 {
            continue;
        }
        let (f, t) = (c.out.f, c.out.t);
        let normal = c.out.en.map(|x| -x);
        let radius = p.radius[i];
        let r = radius - (-c.gap);
        let rsq = r * r;
        for field in fields {
            match field {
                LocalField::Pos => {
                    let dvec = c.to_wall.map(|x| -x);
                    out.extend((0..3).map(|d| p.x[i][d] - dvec[d]));
                    out.extend_from_slice(&p.x[i]);
                }
                LocalField::Vel => {
                    out.extend_from_slice(&c.v_wall);
                    out.extend_from_slice(&p.v[i]);
                }
                LocalField::Id => {
                    out.push(c.mesh as f64);
                    out.push(c.tri as f64);
                    out.push(p.id[i] as f64);
                }
                LocalField::Force
                | LocalField::ForceNormal
                | LocalField::ForceTangential
                | LocalField::Torque
                | LocalField::TorqueNormal
                | LocalField::TorqueTangential => {
                    out.extend_from_slice(&force_torque(*field, f, t, normal))
                }
                LocalField::History => out.extend_from_slice(&c.hist[..width]),
                LocalField::ContactArea => out.push((radius * radius - rsq) * std::f64::consts::PI),
                LocalField::Delta => out.push(radius - rsq.sqrt()),
                // walls fill neither (LIGGGHTS leaves them as allocated: zero)
                LocalField::HeatFlux => out.push(0.0),
                LocalField::ContactPoint => out.extend_from_slice(&[0.0; 3]),
            }
        }
    }
    Ok((ncols, out))
}

/// `compute ID group wall/gran/local [keywords]`, with LIGGGHTS's rules and messages.
pub fn build(
    a: &Args,
    ctx: &mut Ctx,
    def: &ComputeDef,
) -> Result<Box<dyn ComputeStyle>, CommandError> {
    let id = def.id;
    if ctx.sim.step > 0 && !ctx.sim.restart_in_progress {
        return Err(a.error(
            2,
            format!(
                "Compute wall/gran/local (id {id}): Need to define this compute before first run"
            ),
        ));
    }
    let mut fields = Vec::new();
    for i in 3..a.len() {
        match a.word(i)? {
            "verbose" => {}
            "extraSurfDistance" => return Err(a.error(i, "this keyword is deprecated; neighbor->contactDistanceFactor is now used directly")),
            "ms_id" => return Err(a.unsupported(i, "compute wall/gran/local ms_id (multisphere bodies)")),
            w => match LocalField::parse(w) {
                Some(f) => fields.push(f),
                None => {
                    return Err(a
                        .error(
                            i,
                            format!("Compute wall/gran/local (id {id}): illegal/unrecognized keyword"),
                        )
                        .with_help("pos, vel, id, force, force_normal, force_tangential, torque, torque_normal, torque_tangential, history, contactArea, delta, heatFlux, contactPoint"))
                }
            },
        }
    }
    if a.len() == 3 {
        fields = LocalField::defaults();
    }
    if fields.is_empty() {
        // LIGGGHTS 3.8.0 crashes at the first output of a compute without columns
        return Err(a.error(
            3,
            format!("Compute wall/gran/local (id {id}): no output keyword given"),
        ));
    }
    fields.sort();
    fields.dedup();
    // the last mesh wall fix; primitive walls are not reported
    let mut wall = None;
    let mut primitive = false;
    for f in &ctx.sim.fixes {
        if let Some(w) = f.kind.mesh_wall() {
            wall = Some((f.id.clone(), w.history_width()));
        } else if f.kind.wall_selection().is_some() {
            primitive = true;
        }
    }
    if primitive {
        ctx.say("WARNING: Compute wall/gran/local detected primitive wall, output will only happen for mesh wall - particle pairs (./src/compute_pair_gran_local.cpp:263)\n");
    }
    let Some((wall, history)) = wall else {
        return Err(a.error(2, "Compute wall/gran/local requires a fix of type wall/gran using one or more mesh walls. This fix has to come before the compute in the script"));
    };
    if ctx
        .sim
        .computes
        .iter()
        .any(|c| c.style().reads_wall() == Some(wall.as_str()))
    {
        return Err(a.error(
            2,
            format!("Fix wall/gran (id {wall}): Fix wall/gran allows only one compute of type wall/gran/local"),
        ));
    }
    if history == 0 && fields.contains(&LocalField::History) {
        return Err(a.error(2, "Compute pair/gran/local or wall/gran/local can not calculate history values since pair or wall style does not compute them"));
    }
    Ok(Box::new(WallGranLocal { fields, wall }))
}
