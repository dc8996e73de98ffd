//! `fix store/state`: per-particle snapshots (f_ID, or f_ID[N] with several inputs).

use crate::commands::fix::FixDef;
use crate::commands::specs::{arg, kw, style, Spec, YES_NO};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::ave_atom::AtomInput;
use crate::engine::fixes::FixStyle;
use crate::engine::store_state::{Snapshot, StoreState};
use crate::io::dump::Column;

/// The declared signature.
pub const SPEC: Spec = style(
    "fix",
    "store/state",
    "fix ID GROUP store/state N ATTRIBUTE|c_ID|c_ID[N]|f_ID|f_ID[N]|v_NAME ...",
    &[
        kw(
            "com",
            &[arg("yes|no", YES_NO)],
            "unwrapped positions xu yu zu relative to the group's centre of mass",
        ),
    ],
    "per-particle snapshot when defined (attributes) and at the first run (computes, fixes, variables), then every N steps if N > 0 (f_ID or f_ID[N] in dumps and variables)",
);

const ILLEGAL: &str = "Illegal fix store/state command";

/// Attributes of atom style granular that fix store/state stores.
const ATTRIBUTES: &[&str] = &[
    "id", "type", "mass", "x", "y", "z", "xs", "ys", "zs", "xu", "yu", "zu", "ix", "iy", "iz",
    "vx", "vy", "vz", "fx", "fy", "fz", "radius", "omegax", "omegay", "omegaz", "tqx", "tqy",
    "tqz",
];

/// Attributes LIGGGHTS knows but atom style granular does not allocate.
const NOT_ALLOCATED: &[&str] = &[
    "mol", "q", "mux", "muy", "muz", "angmomx", "angmomy", "angmomz",
];

/// `fix ID GROUP store/state N input ... [com yes|no]`: inputs are atom attributes,
/// c_ID, c_ID[N], f_ID, f_ID[N], v_name; the attributes are stored now.
pub fn build(a: &Args, ctx: &mut Ctx, fix: &FixDef) -> Result<Box<dyn FixStyle>, CommandError> {
    if a.len() < 5 {
        return Err(a.error(2, ILLEGAL));
    }
    let every = a.int(3)?;
    if every < 0 {
        return Err(a.error(3, ILLEGAL));
    }
    let mut inputs = Vec::new();
    let mut i = 4;
    while i < a.len() {
        let w = a.word(i)?;
        if ATTRIBUTES.contains(&w) {
            let col = Column::parse(w).map_err(|_| a.error(i, ILLEGAL))?;
            inputs.push(AtomInput::Atom(col));
        } else if NOT_ALLOCATED.contains(&w) {
            return Err(a.error(i, "Fix store/state for atom property that isn't allocated"));
        } else if let Some(prefix) = ["c_", "f_", "v_"].into_iter().find(|p| w.starts_with(p)) {
            inputs.push(reference(a, ctx, i, prefix, every)?);
        } else {
            break;
        }
        i += 1;
    }
    let mut com = false;
    while i < a.len() {
        if a.word(i)? != "com" || i + 2 > a.len() {
            return Err(a.error(i, ILLEGAL));
        }
        com = match a.word(i + 1)? {
            "no" => false,
            "yes" => true,
            _ => return Err(a.error(i + 1, ILLEGAL)),
        };
        i += 2;
    }
    if inputs.is_empty() {
        return Err(a
            .error(4, ILLEGAL)
            .with_help("name at least one value to store"));
    }
    let state = StoreState {
        every,
        inputs,
        com,
        first: true,
        array: format!("store_state_{}", fix.id),
    };
    // zero, then the attributes as they are now (a dump may read them at once)
    let n = state.inputs.len();
    let k = ctx.sim.particles.extra_index(&state.array, n);
    ctx.sim.particles.extra[k].data.fill(0.0);
    let none = &mut crate::engine::sim::NoVariables;
    ctx.sim
        .store_snapshot(&state, fix.bit, Snapshot::Attributes, none)
        .map_err(|e| a.engine_error(2, e))?;
    Ok(Box::new(state))
}

/// A `c_`, `f_` or `v_` input at word `i`, checked as LIGGGHTS checks it when the fix is
/// defined.
fn reference(
    a: &Args,
    ctx: &Ctx,
    i: usize,
    prefix: &str,
    every: i64,
) -> Result<AtomInput, CommandError> {
    let body = &a.word(i)?[2..];
    let (id, index) =
        crate::util::numbers::split_reference_atoi(body).ok_or_else(|| a.error(i, ILLEGAL))?;
    match prefix {
        "c_" => {
            let c = super::input_compute(a, ctx, i, id, "store/state")?;
            let cols = c.per_atom_columns();
            check_width(a, i, cols, index)?;
            Ok(AtomInput::Compute(id.to_string(), index))
        }
        "f_" => {
            let fix = ctx
                .sim
                .fixes
                .iter()
                .find(|f| f.id == id)
                .ok_or_else(|| a.error(i, "Fix ID for fix store/state does not exist"))?;
            crate::engine::fix_columns::column(ctx.sim, id, index)
                .map_err(|e| a.error(i, format!("Fix store/state: {e}")))?;
            if let Some(ave) = fix.kind.style_as::<crate::engine::ave_atom::AveAtom>() {
                if every % ave.freq != 0 {
                    return Err(
                        a.error(i, "Fix for fix store/state not computed at compatible time")
                    );
                }
            }
            Ok(AtomInput::Fix(id.to_string(), index))
        }
        _ => {
            super::input_atom_variable(a, ctx, i, id, "store/state")?;
            Ok(AtomInput::Variable(id.to_string()))
        }
    }
}

/// LIGGGHTS's checks of a per-atom compute's shape (one column: a per-atom vector) against
/// the index asked for.
fn check_width(a: &Args, i: usize, cols: usize, index: Option<usize>) -> Result<(), CommandError> {
    let problem = match index {
        _ if cols == 0 => "does not calculate per-atom values",
        None if cols > 1 => "does not calculate a per-atom vector",
        Some(_) if cols == 1 => "does not calculate a per-atom array",
        Some(k) if k > cols => "array is accessed out-of-range",
        _ => return Ok(()),
    };
    Err(a.error(i, format!("Fix store/state compute {problem}")))
}
