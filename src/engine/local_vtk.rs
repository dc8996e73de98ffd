//! One snapshot of `dump local/gran/vtk`: the rows of its local compute, evaluated now,
//! written as a VTK contact network.

use crate::engine::error::EngineError;
use crate::engine::sim::Simulation;
use crate::io::local_vtk::{write_contacts, ContactLayout};
use crate::io::local_vtk_xml::{write_contacts_xml, XmlKind};

/// The VTK text of compute `cid`'s contacts at the current step, `evaluated` (its columns
/// and rows: on several ranks every rank's rows gathered), in the layout the dump's `file`
/// name asks for (legacy `.vtk`, XML `.vtp` or `.vtu`).
pub fn snapshot(
    sim: &Simulation,
    cid: &str,
    file: &str,
    evaluated: &(usize, Vec<f64>),
) -> Result<Vec<u8>, EngineError> {
    let c = sim
        .computes
        .iter()
        .find(|c| c.id == cid)
        .ok_or_else(|| format!("Could not find dump local/gran/vtk compute ID {cid}"))?;
    let fields = c
        .style()
        .local_fields()
        .ok_or_else(|| format!("compute {cid} is not a compute pair/gran/local"))?;
    let (ncols, rows) = (evaluated.0, &evaluated.1);
    // the history columns are what the other fields leave of a row
    let fixed: usize = fields.iter().map(|f| f.width(0)).sum();
    let layout = ContactLayout::new(fields, ncols.saturating_sub(fixed))
        .ok_or_else(|| format!("compute {cid} does not write the positions"))?;
    let mut text = Vec::new();
    match XmlKind::of_file(file) {
        Some(kind) => write_contacts_xml(&mut text, kind, &layout, ncols, rows),
        None => write_contacts(&mut text, &layout, ncols, rows),
    }
    .map_err(|e| e.to_string())?;
    Ok(text)
}
