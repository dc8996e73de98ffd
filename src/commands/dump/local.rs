//! `dump local`: the rows of local computes (pair and wall contacts), one column per
//! `c_ID` / `c_ID[N]`.

use crate::commands::dump::{style_words, Built, DumpDef};
use crate::commands::specs::{style, Spec};
use crate::commands::{Args, CommandError, Ctx};
use crate::engine::computes::LocalRows;
use crate::engine::dump_style::{DumpAt, DumpStyle};
use crate::engine::error::EngineError;
use crate::engine::sim::VariableSource;
use crate::io::dump::Layout;

/// The declared signature of `local`.
pub const SPEC: Spec = style(
    "dump",
    "local",
    "dump ID GROUP local N FILE c_ID[N] ...",
    &[],
    "per-contact columns of local computes",
);

/// `dump local`: (compute ID, 0-based column) per column.
#[derive(Debug)]
pub struct Local {
    /// The columns, in order.
    cols: Vec<(String, usize)>,
}

impl DumpStyle for Local {
    fn name(&self) -> &str {
        "local"
    }

    fn snapshot(
        &self,
        at: &mut DumpAt,
        _vars: &mut dyn VariableSource,
    ) -> Result<Vec<u8>, EngineError> {
        let mut data = Vec::new();
        for (cid, col) in &self.cols {
            let evaluated = at.local_rows(cid)?;
            let ncols = evaluated.0;
            if *col >= ncols.max(1) {
                return Err(format!(
                    "Dump local compute vector is accessed out-of-range: c_{cid}[{}] of a compute with {ncols} column(s)",
                    col + 1
                ).into());
            }
            data.push((evaluated, *col));
        }
        let nrows = data.first().map_or(0, |d| d.0 .1.len() / d.0 .0.max(1));
        let (sim, layout) = (at.sim, &at.dump.layout);
        let mut text = Vec::new();
        crate::io::dump::write_local(
            &mut text,
            sim.step,
            &sim.domain,
            &layout.names,
            layout.format.as_deref(),
            nrows,
            |r, c| data[c].0 .1[r * data[c].0 .0 + data[c].1],
        )
        .map_err(|e| e.to_string())?;
        Ok(text)
    }

    fn takes_binary(&self) -> Option<bool> {
        Some(false)
    }

    fn local_computes(&self) -> Vec<String> {
        let mut ids: Vec<String> = Vec::new();
        for (cid, _) in &self.cols {
            if !ids.contains(cid) {
                ids.push(cid.clone());
            }
        }
        ids
    }
}

/// `dump ID GROUP local N FILE c_ID[N] ...`.
pub fn build(a: &Args, ctx: &mut Ctx, _def: &DumpDef) -> Result<Built, CommandError> {
    let names = style_words(a)?;
    if names.is_empty() {
        return Err(a.error(4, "Illegal dump local command"));
    }
    let cols = local_columns(a, ctx, &names)?;
    let mut layout = Layout::new(&[]).expect("no columns");
    layout.names = names.iter().map(|s| s.to_string()).collect();
    Ok((layout, Box::new(Local { cols })))
}

/// The columns of `dump local`: each a local vector or array column of a compute, as
/// (compute ID, 0-based column).
fn local_columns(
    a: &Args,
    ctx: &Ctx,
    names: &[&str],
) -> Result<Vec<(String, usize)>, CommandError> {
    let mut cols = Vec::new();
    for (k, n) in names.iter().enumerate() {
        let body = n
            .strip_prefix("c_")
            .ok_or_else(|| a.unsupported(5 + k, &format!("dump local column {n}")))?;
        let (cid, index) = crate::util::numbers::split_reference(body)
            .ok_or_else(|| a.error(5 + k, "Invalid attribute in dump local command"))?;
        let c = ctx
            .sim
            .computes
            .iter()
            .find(|c| c.id == cid)
            .ok_or_else(|| a.error(5 + k, "Could not find dump local compute ID"))?;
        match c.style().local_rows() {
            Some(LocalRows::VectorOrArray) => {}
            Some(LocalRows::Array) => {
                if index.is_none() {
                    return Err(
                        a.error(5 + k, "Dump local compute does not calculate local vector")
                    );
                }
            }
            None => return Err(a.error(5 + k, "Dump local compute does not compute local info")),
        }
        cols.push((cid.to_string(), index.unwrap_or(1).max(1) - 1));
    }
    Ok(cols)
}
