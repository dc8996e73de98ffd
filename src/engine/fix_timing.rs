//! `modify_timing on|verbose`: the time each fix takes during a run, and LIGGGHTS's report of
//! it after the run (`Modfy time (%) = ...` and one `Fix ID style time (%) = ...` line per fix).
//!
//! LIGGGHTS lists every fix of its fix list, in that list's order, and the list holds fixes
//! LIGGGHTS creates itself beside those of the deck: a primitive wall's `history_ID`, a mesh
//! wall's `wall_neighlist_MESH`/`n_neighs_mesh_MESH`/`tracker_MESH` per mesh, an insertion
//! stream's `release_fix_insert_stream`, the heat fixes' per-atom arrays, a compute msd's
//! `ID_COMPUTE_STORE`, and the pair style's `contacthistory` created at the first run's
//! init. [`ModifyList`] keeps that order as fixes, computes and runs come; regolith does the
//! work of a created fix inside its owner, so such a fix shows (close to) no time.

use std::time::Instant;

/// A fix's clock: on only while a run has `modify_timing` on.
#[derive(Debug, Clone, Copy, Default)]
pub struct FixClock {
    /// Whether the fix's hooks are timed in this run.
    pub on: bool,
    /// Time spent in the fix's hooks since the run started (s).
    pub seconds: f64,
}

impl FixClock {
    /// The start of a timed hook (None while timing is off).
    #[inline]
    pub fn start(&self) -> Option<Instant> {
        self.on.then(Instant::now)
    }

    /// The end of a hook started at `started` (its time added, when it was timed).
    #[inline]
    pub fn stop(&mut self, started: Option<Instant>) {
        if let Some(t) = started {
            self.seconds += t.elapsed().as_secs_f64();
        }
    }
}

/// One fix of LIGGGHTS's fix list.
#[derive(Debug, Clone, PartialEq)]
pub struct ModifyEntry {
    /// The fix ID.
    pub id: String,
    /// Its style name.
    pub style: String,
    /// The fix or compute that created it (None: a fix of the deck, or one the run created).
    pub owner: Option<String>,
}

/// LIGGGHTS's fix list, in its order.
#[derive(Debug, Clone, Default)]
pub struct ModifyList {
    /// The fixes, first created first.
    pub entries: Vec<ModifyEntry>,
}

impl ModifyList {
    /// The deck's fix `id` of `style` (kept in place when it replaces a fix of that ID),
    /// then the fixes LIGGGHTS creates with it.
    pub fn define(&mut self, id: &str, style: &str, created: &[(String, String)]) {
        self.ensure(id, style, None);
        for (cid, cstyle) in created {
            self.ensure(cid, cstyle, Some(id));
        }
    }

    /// Fix `id` of `style` appended unless the list holds it.
    pub fn ensure(&mut self, id: &str, style: &str, owner: Option<&str>) {
        if !self.entries.iter().any(|e| e.id == id) {
            self.entries.push(ModifyEntry {
                id: id.to_string(),
                style: style.to_string(),
                owner: owner.map(str::to_string),
            });
        }
    }

    /// Fix (or compute) `id` gone, with the fixes it created.
    pub fn remove(&mut self, id: &str) {
        self.entries
            .retain(|e| e.id != id && e.owner.as_deref() != Some(id));
    }

    /// The report LIGGGHTS prints after a run of `loop_time` (s): the total of the fixes'
    /// times (s) and one line per fix, `times` giving a fix's time by its ID (s);
    /// `verbose` adds the per-process lines of `modify_timing verbose`.
    pub fn report(&self, times: &dyn Fn(&str) -> f64, loop_time: f64, verbose: bool) -> String {
        use crate::util::format::g;
        let mut s = String::new();
        for e in &self.entries {
            let t = times(&e.id);
            s.push_str(&format!(
                "Fix {} {} time (%) = {} ({})\n",
                e.id,
                e.style,
                g(t),
                g(percent(t, loop_time))
            ));
            if verbose {
                s.push_str(&format!("  [0] Fix {} {} time {}\n", e.id, e.style, g(t)));
            }
        }
        s
    }

    /// The sum of the fixes' times (s), `times` giving a fix's time by its ID (s).
    pub fn total(&self, times: &dyn Fn(&str) -> f64) -> f64 {
        self.entries.iter().map(|e| times(&e.id)).sum()
    }
}

/// `x` as a percentage of `whole` (0 for an empty whole).
pub fn percent(x: f64, whole: f64) -> f64 {
    if whole > 0.0 {
        100.0 * x / whole
    } else {
        0.0
    }
}

/// The fixes LIGGGHTS creates with fix `fix` (IDs and styles, in its order), given the fixes
/// defined before it.
pub fn created_with(
    fix: &crate::engine::fixes::Fix,
    before: &[crate::engine::fixes::Fix],
) -> Vec<(String, String)> {
    use crate::engine::fixes::FixKind;
    let pa = |id: &str| (id.to_string(), "property/atom".to_string());
    let mut out = Vec::new();
    let kind = &fix.kind;
    if let Some(w) = kind.primitive_wall() {
        if crate::engine::fixes::dry_history_width(&w.selection) > 0 {
            out.push(pa(&format!("history_{}", fix.id)));
        }
        return out;
    }
    if let Some(w) = kind.mesh_wall() {
        for m in &w.meshes {
            out.push((format!("wall_neighlist_{m}"), "neighlist/mesh".into()));
            out.push(pa(&format!("n_neighs_mesh_{m}")));
            out.push((format!("tracker_{m}"), "contacthistory/mesh".into()));
        }
        return out;
    }
    if kind.style_as::<crate::engine::clumps::Clumps>().is_some() {
        for name in ["cornerghost", "delflag", "existflag", "volumeweight_ms"] {
            out.push(pa(name));
        }
        return out;
    }
    if let FixKind::Style(_) = &fix.kind {
        if fix.kind.stream().is_some() {
            out.push(pa(crate::engine::insert::RELEASE_NAME));
        } else if let Some(h) = fix.kind.style_as::<crate::engine::heat::HeatGran>() {
            let [temp, flux, source, directional] = &h.arrays;
            out.push(pa(directional));
            out.push(("ste_heattransfer".into(), "transportequation/scalar".into()));
            out.extend([pa(temp), pa(flux), pa(source)]);
            if let Some(data) = &h.contact_data {
                out.extend(data.iter().map(|d| pa(d)));
            }
        } else if let Some(m) = fix.kind.style_as::<crate::engine::massflow::Massflow>() {
            let (id, mesh) = (&fix.id, &m.mesh);
            out.push(pa(&format!("massflow_{id}")));
            out.push((format!("neighlist_{id}_{mesh}"), "neighlist/mesh".into()));
            out.push(pa(&format!(
                "n_neighs_mesh_{mesh}_fix_neighlist_{id}_{mesh}"
            )));
        } else if fix.style == "adapt" {
            out.push(pa(&format!("adaptProp_{}", fix.id)));
        } else if fix.style == "multicontact/halfspace" {
            // one contact store per wall (per mesh of a mesh wall) with the model
            for f in before {
                let wall = "contactproperty/atom/wall".to_string();
                if let Some(w) = f.kind.primitive_wall() {
                    if w.selection.surface == "multicontact" {
                        out.push((format!("multicontactData_{}", f.id), wall));
                    }
                } else if let Some(w) = f.kind.mesh_wall() {
                    if w.selection.surface == "multicontact" {
                        for m in &w.meshes {
                            out.push((format!("multicontactData_{m}"), wall.clone()));
                        }
                    }
                }
            }
        }
    }
    out
}

/// The fix LIGGGHTS creates with compute `id` of `style` (its ID and style), if any.
pub fn created_with_compute(id: &str, style: &str) -> Option<(String, String)> {
    matches!(style, "msd" | "displace/atom")
        .then(|| (format!("{id}_COMPUTE_STORE"), "STORE".to_string()))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ids(l: &ModifyList) -> Vec<&str> {
        l.entries.iter().map(|e| e.id.as_str()).collect()
    }

    #[test]
    fn created_fixes_follow_their_owner_and_go_with_it() {
        let mut l = ModifyList::default();
        l.define("m1", "property/global", &[]);
        let h = [("history_w".to_string(), "property/atom".to_string())];
        l.define("w", "wall/gran", &h);
        l.define("integr", "nve/sphere", &[]);
        l.ensure("contacthistory", "contacthistory", None);
        l.define("late", "gravity", &[]);
        // replacing a fix keeps its place
        l.define("w", "wall/gran", &h);
        assert_eq!(
            ids(&l),
            ["m1", "w", "history_w", "integr", "contacthistory", "late"]
        );
        l.remove("w");
        assert_eq!(ids(&l), ["m1", "integr", "contacthistory", "late"]);
    }

    #[test]
    fn report_lines_and_percentages() {
        let mut l = ModifyList::default();
        l.define("a", "gravity", &[]);
        l.define("b", "nve/sphere", &[]);
        let t = |id: &str| if id == "a" { 0.25 } else { 0.5 };
        assert_eq!(l.total(&t), 0.75);
        assert_eq!(
            l.report(&t, 2.0, false),
            "Fix a gravity time (%) = 0.25 (12.5)\nFix b nve/sphere time (%) = 0.5 (25)\n"
        );
        assert_eq!(
            l.report(&t, 0.0, true),
            "Fix a gravity time (%) = 0.25 (0)\n  [0] Fix a gravity time 0.25\n\
             Fix b nve/sphere time (%) = 0.5 (0)\n  [0] Fix b nve/sphere time 0.5\n"
        );
    }
}
