//! The per-contact fields a `compute pair/gran/local` or `wall/gran/local` selects, shared
//! by the engine that fills them and the writers that name their columns.

/// The per-contact fields of `compute pair/gran/local`, in LIGGGHTS's column order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum LocalField {
    /// `pos`: x_i, x_j (6 columns, length).
    Pos,
    /// `vel`: v_i, v_j (6 columns, velocity).
    Vel,
    /// `id`: ID of i, ID of j, 1 if the contact crosses a periodic face (3 columns).
    Id,
    /// `force`: force on i (3 columns, force).
    Force,
    /// `force_normal`: its component along x_j - x_i (3 columns).
    ForceNormal,
    /// `force_tangential`: the rest (3 columns).
    ForceTangential,
    /// `torque`: torque on i (3 columns, force length).
    Torque,
    /// `torque_normal` (3 columns).
    TorqueNormal,
    /// `torque_tangential` (3 columns).
    TorqueTangential,
    /// `history`: the contact history values.
    History,
    /// `contactArea`: the circular lens area (area).
    ContactArea,
    /// `delta`: overlap (length).
    Delta,
    /// `heatFlux`: conductive heat flux (power); 0 without heat transfer.
    HeatFlux,
    /// `contactPoint`: (x_i r_j + x_j r_i)/(r_i + r_j) (3 columns, length).
    ContactPoint,
}

impl LocalField {
    /// Parse a keyword of `compute pair/gran/local`.
    pub fn parse(word: &str) -> Option<LocalField> {
        Some(match word {
            "pos" => LocalField::Pos,
            "vel" => LocalField::Vel,
            "id" => LocalField::Id,
            "force" => LocalField::Force,
            "force_normal" => LocalField::ForceNormal,
            "force_tangential" => LocalField::ForceTangential,
            "torque" => LocalField::Torque,
            "torque_normal" => LocalField::TorqueNormal,
            "torque_tangential" => LocalField::TorqueTangential,
            "history" => LocalField::History,
            "contactArea" => LocalField::ContactArea,
            "delta" => LocalField::Delta,
            "heatFlux" => LocalField::HeatFlux,
            "contactPoint" => LocalField::ContactPoint,
            _ => return None,
        })
    }

    /// LIGGGHTS's selection without keywords: pos vel id force torque history contactArea.
    pub fn defaults() -> Vec<LocalField> {
        use LocalField::*;
        vec![Pos, Vel, Id, Force, Torque, History, ContactArea]
    }

    /// Columns this field adds (`history` adds the model's history length).
    pub fn width(self, history: usize) -> usize {
        match self {
            LocalField::Pos | LocalField::Vel => 6,
            LocalField::History => history,
            LocalField::ContactArea | LocalField::Delta | LocalField::HeatFlux => 1,
            _ => 3,
        }
    }
}
