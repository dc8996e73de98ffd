//! Thermo output (`thermo`, `thermo_style`, `thermo_modify`): column headers right-aligned,
//! integers as `%8d`, reals as `%14.8g`, each followed by a blank, as LIGGGHTS prints them.

use crate::engine::error::EngineError;
use crate::engine::sim::{Simulation, Sink, VariableSource};
use crate::util::format;

/// Keywords a formula may use for thermo values (LIGGGHTS 3.8.0's `Thermo::evaluate_keyword`).
pub const THERMO_KEYWORDS: &[&str] = &[
    "atoms",
    "cella",
    "cellalpha",
    "cellb",
    "cellbeta",
    "cellc",
    "cellgamma",
    "cpu",
    "cpuremain",
    "cu",
    "density",
    "dt",
    "elaplong",
    "elapsed",
    "erotate",
    "fmax",
    "fnorm",
    "ke",
    "lx",
    "ly",
    "lz",
    "part",
    "spcpu",
    "step",
    "time",
    "tpcpu",
    "vol",
    "xhi",
    "xlat",
    "xlo",
    "xy",
    "xz",
    "yhi",
    "ylat",
    "ylo",
    "yz",
    "zhi",
    "zlat",
    "zlo",
];

/// Whether a column holds an integer or a real number.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Printed with `%8d`.
    Int,
    /// Printed with `%14.8g`.
    Real,
}

/// One thermo column.
#[derive(Debug, Clone, PartialEq)]
pub struct Field {
    /// The keyword as written (`step`, `ke`, ...).
    pub keyword: String,
    /// The header label LIGGGHTS prints (`Step`, `KinEng`, ...).
    pub label: String,
    /// Integer or real.
    pub kind: Kind,
}

/// Keywords regolith evaluates, with LIGGGHTS's header labels.
const KEYWORDS: &[(&str, &str, Kind)] = &[
    ("step", "Step", Kind::Int),
    ("elapsed", "Elapsed", Kind::Int),
    ("atoms", "Atoms", Kind::Int),
    ("dt", "Dt", Kind::Real),
    ("time", "Time", Kind::Real),
    ("cpu", "CPU", Kind::Real),
    ("ke", "KinEng", Kind::Real),
    ("vol", "Volume", Kind::Real),
    ("lx", "Lx", Kind::Real),
    ("ly", "Ly", Kind::Real),
    ("lz", "Lz", Kind::Real),
    ("xlo", "Xlo", Kind::Real),
    ("xhi", "Xhi", Kind::Real),
    ("ylo", "Ylo", Kind::Real),
    ("yhi", "Yhi", Kind::Real),
    ("zlo", "Zlo", Kind::Real),
    ("zhi", "Zhi", Kind::Real),
    ("elaplong", "Elaplong", Kind::Int),
    ("tpcpu", "T/CPU", Kind::Real),
    ("spcpu", "S/CPU", Kind::Real),
    ("cpuremain", "CPULeft", Kind::Real),
    ("part", "Part", Kind::Int),
    ("cu", "Cu", Kind::Real),
    ("erotate", "RotEng", Kind::Real),
    ("density", "Density", Kind::Real),
    ("xy", "Xy", Kind::Real),
    ("xz", "Xz", Kind::Real),
    ("yz", "Yz", Kind::Real),
    ("xlat", "Xlat", Kind::Real),
    ("ylat", "Ylat", Kind::Real),
    ("zlat", "Zlat", Kind::Real),
    ("fmax", "Fmax", Kind::Real),
    ("fnorm", "Fnorm", Kind::Real),
    ("cella", "Cella", Kind::Real),
    ("cellb", "Cellb", Kind::Real),
    ("cellc", "Cellc", Kind::Real),
    ("cellalpha", "CellAlpha", Kind::Real),
    ("cellbeta", "CellBeta", Kind::Real),
    ("cellgamma", "CellGamma", Kind::Real),
];

/// Thermo settings and state.
#[derive(Debug, Clone)]
pub struct Thermo {
    /// Print every this many steps (0: only at the start and end of runs).
    pub every: i64,
    /// The columns.
    pub fields: Vec<Field>,
    /// Divide extensive values by the atom count (`thermo_modify norm`).
    pub norm: bool,
    /// Step at which the current run started (for `elapsed`).
    pub run_start: i64,
    /// `thermo_style multi` (or `thermo_modify line multi`): labelled values, three per line.
    pub multi: bool,
    /// `thermo_modify format int` (a C format).
    pub int_format: Option<String>,
    /// `thermo_modify format float`.
    pub float_format: Option<String>,
    /// `thermo_modify format N` per column (index N-1).
    pub column_formats: Vec<Option<String>>,
    /// A `thermo_modify` changed these settings since the last `thermo_style` (LIGGGHTS
    /// warns that a new `thermo_style` drops them).
    pub modified: bool,
    /// Style `custom` (styles `one` and `multi` gain a Volume column when the box changes).
    pub custom: bool,
    /// The last column is the Volume column added at run start.
    pub auto_volume: bool,
    /// Last step of the current run (for `cpuremain`).
    pub run_last: i64,
    /// Simulated time and loop time (s) at the last `tpcpu` value.
    pub tpcpu_mark: std::cell::Cell<(f64, f64)>,
    /// Step and loop time (s) at the last `spcpu` or `cu` value.
    pub spcpu_mark: std::cell::Cell<(i64, f64)>,
}

impl Default for Thermo {
    fn default() -> Self {
        let mut t = Thermo {
            every: 0,
            fields: Vec::new(),
            norm: false,
            run_start: 0,
            multi: false,
            int_format: None,
            float_format: None,
            modified: false,
            column_formats: Vec::new(),
            custom: false,
            auto_volume: false,
            run_last: 0,
            tpcpu_mark: Default::default(),
            spcpu_mark: Default::default(),
        };
        t.set_style(&["step", "atoms", "ke", "cpu"])
            .expect("default style is valid");
        t
    }
}

impl Thermo {
    /// `thermo_style custom ...` (or the default columns of style `one`).
    pub fn set_style(&mut self, keywords: &[&str]) -> Result<(), EngineError> {
        let mut fields = Vec::new();
        for k in keywords {
            if let Some(rest) = k
                .strip_prefix("c_")
                .or_else(|| k.strip_prefix("f_"))
                .or_else(|| k.strip_prefix("v_"))
            {
                // LIGGGHTS labels a compute column by its reference without the c_ prefix,
                // cut to its first 8 characters (`c_thermo_temp` is `thermo_t`)
                fields.push(Field {
                    keyword: k.to_string(),
                    label: rest.chars().take(8).collect(),
                    kind: Kind::Real,
                });
                continue;
            }
            let Some(&(_, label, kind)) = KEYWORDS.iter().find(|e| e.0 == *k) else {
                let known = crate::engine::thermo::THERMO_KEYWORDS.contains(k);
                return Err(if known {
                    EngineError::Unsupported(format!("thermo keyword {k}"))
                } else {
                    EngineError::Invalid(format!(
                        "Invalid keyword in thermo_style custom command: {k}"
                    ))
                });
            };
            fields.push(Field {
                keyword: k.to_string(),
                label: label.to_string(),
                kind,
            });
        }
        self.fields = fields;
        self.auto_volume = false;
        Ok(())
    }

    /// At run start, as LIGGGHTS: styles other than `custom` get a Volume column when the
    /// box can change (a shrink-wrapped face).
    pub fn prepare_run(&mut self, box_changes: bool) {
        if self.auto_volume {
            self.fields.pop();
            self.auto_volume = false;
        }
        if box_changes && !self.custom {
            self.fields.push(Field {
                keyword: "vol".into(),
                label: "Volume".into(),
                kind: Kind::Real,
            });
            self.auto_volume = true;
        }
    }

    /// Is a thermo line due at `step` of a run ending at `last`?
    pub fn due(&self, step: i64, last: i64) -> bool {
        step == last || (self.every > 0 && step % self.every == 0)
    }

    /// Print the header line (none in multi-line style).
    pub fn header(&self, out: Sink<'_>) {
        if self.multi {
            return;
        }
        let mut line = String::new();
        for f in &self.fields {
            match f.kind {
                Kind::Real => line.push_str(&format!("{:>14} ", f.label)),
                Kind::Int => line.push_str(&format!("{:>8} ", f.label)),
            }
        }
        line.push('\n');
        out(&line);
    }

    /// The current values of every column.
    pub fn values(
        &self,
        sim: &Simulation,
        vars: &mut dyn VariableSource,
    ) -> Result<Vec<f64>, EngineError> {
        self.fields
            .iter()
            .map(|f| match f.keyword.strip_prefix("v_") {
                Some(name) => vars.equal(sim, name),
                None => keyword_value(&f.keyword, sim, self, vars).ok_or_else(|| {
                    if let Some(e) = fix_array_error(&f.keyword, sim) {
                        return e;
                    }
                    // a fix's own reason (LIGGGHTS's message) where it has one
                    f.keyword
                        .strip_prefix("f_")
                        .and_then(crate::util::numbers::split_reference)
                        .and_then(|(id, index)| sim.fix_value(id, index).err())
                        .or_else(|| {
                            let body = f.keyword.strip_prefix("c_")?;
                            let (id, index) = crate::util::numbers::split_reference(body)?;
                            sim.compute_value(id, index, vars).err()
                        })
                        .map(|e| EngineError::Invalid(e.to_string()))
                        .unwrap_or_else(|| {
                            EngineError::Invalid(format!("Thermo keyword {}: no value", f.keyword))
                        })
                }),
            })
            .collect()
    }

    /// The C format of column `k`, as LIGGGHTS picks it: per column, else per type, else
    /// the default of the line style.
    fn column_format(&self, k: usize) -> &str {
        if let Some(Some(f)) = self.column_formats.get(k) {
            return f;
        }
        match (self.fields[k].kind, self.multi) {
            (Kind::Real, _) if self.float_format.is_some() => self.float_format.as_deref().unwrap(),
            (Kind::Int, _) if self.int_format.is_some() => self.int_format.as_deref().unwrap(),
            (Kind::Real, false) => "%14.8g",
            (Kind::Real, true) => "%14.4f",
            (Kind::Int, false) => "%8d",
            (Kind::Int, true) => "%14d",
        }
    }

    /// Print one line of values (`cpu` is the loop time so far, for the multi-line banner).
    pub fn line(&self, values: &[f64], step: i64, cpu: f64, out: Sink<'_>) {
        let mut line = String::new();
        if self.multi {
            line.push_str(&format!(
                "---------------- Step {step:>8} ----- CPU = {} (sec) ----------------",
                format::with_spec("%11.4f", cpu).unwrap_or_default()
            ));
        }
        for (k, (f, v)) in self.fields.iter().zip(values).enumerate() {
            if self.multi {
                if k % 3 == 0 {
                    line.push('\n');
                }
                line.push_str(&format!("{:<8} = ", f.label));
            }
            let spec = self.column_format(k);
            let text = match f.kind {
                Kind::Real => format::with_spec(spec, *v),
                Kind::Int => format::with_spec(spec, (*v as i64) as f64),
            };
            line.push_str(&text.unwrap_or_default());
            line.push(' ');
        }
        line.push('\n');
        out(&line);
    }
}

/// The value of a thermo keyword, or None if regolith does not evaluate it.
pub fn keyword_value(
    keyword: &str,
    sim: &Simulation,
    thermo: &Thermo,
    vars: &mut dyn VariableSource,
) -> Option<f64> {
    let d = &sim.domain;
    let n = sim.particles.len() as f64;
    let norm = |v: f64| if thermo.norm && n > 0.0 { v / n } else { v };
    Some(match keyword {
        "step" => sim.step as f64,
        "elapsed" => (sim.step - thermo.run_start) as f64,
        "atoms" => n,
        "dt" => sim.dt,
        "time" => sim.time(),
        "cpu" => sim.loop_clock.map_or(0.0, |t| t.elapsed().as_secs_f64()),
        "ke" => norm(
            crate::engine::computes::kinetic_energy(&sim.particles, 1)
                + sim.clumps().map_or(0.0, |c| c.kinetic_energy()),
        ),
        "vol" if sim.dimension == 2 => d.length(0) * d.length(1),
        "vol" => d.length(0) * d.length(1) * d.length(2),
        "lx" => d.length(0),
        "ly" => d.length(1),
        "lz" => d.length(2),
        "xlo" => d.lo[0],
        "xhi" => d.hi[0],
        "ylo" => d.lo[1],
        "yhi" => d.hi[1],
        "zlo" => d.lo[2],
        "zhi" => d.hi[2],
        k if k.starts_with("c_") || k.starts_with("f_") => {
            let body = &k[2..];
            let (id, index) = match body.split_once('[') {
                Some((id, rest)) => (id, rest.trim_end_matches(']').parse::<usize>().ok()),
                None => (body, None),
            };
            return if k.starts_with('c') {
                // LIGGGHTS's norm divides extensive compute values by the atom count
                let value = sim.compute_value(id, index, vars).ok()?;
                let c = sim.computes.iter().find(|c| c.id == id)?;
                let extensive = match index {
                    None => c.style().extensive_scalar(),
                    Some(_) => c.style().extensive(sim, None) == Some(1),
                };
                Some(if extensive { norm(value) } else { value })
            } else {
                // and extensive fix values likewise
                let value = sim.fix_value(id, index).ok()?;
                let extensive = crate::engine::global_values::fix_extensive(sim, id, index);
                Some(if extensive { norm(value) } else { value })
            };
        }
        other => return more_keywords(other, sim, thermo, vars),
    })
}

/// The reason a `f_ID[i][j]` thermo keyword has no value (the fix's own, such as
/// `fix ave/euler`'s during a run), None for other keywords.
fn fix_array_error(keyword: &str, sim: &Simulation) -> Option<EngineError> {
    let body = keyword.strip_prefix("f_")?;
    let (id, rest) = body.split_once('[')?;
    let (i, j) = rest.strip_suffix(']')?.split_once("][")?;
    let (i, j) = (i.parse().ok()?, j.parse().ok()?);
    sim.fix_array_value(id, i, j).err()
}

/// The lattice spacings in x, y, z (length; LIGGGHTS's default lattice has 1).
pub fn lattice_spacings(sim: &Simulation) -> [f64; 3] {
    match (&sim.lattice_cell, &sim.lattice) {
        (Some(cell), _) => cell.spacing,
        (None, Some((scale, _))) => [*scale; 3],
        (None, None) => [1.0; 3],
    }
}

/// The keywords of LIGGGHTS's thermo that need more than a field of the box or the run.
fn more_keywords(
    keyword: &str,
    sim: &Simulation,
    thermo: &Thermo,
    vars: &mut dyn VariableSource,
) -> Option<f64> {
    let d = &sim.domain;
    let p = &sim.particles;
    let n = p.len() as f64;
    // the loop time, None at a run's setup (LIGGGHTS's firststep == 0)
    let clock = sim.loop_clock.map(|t| t.elapsed().as_secs_f64());
    let lattice = lattice_spacings(sim);
    Some(match keyword {
        "elaplong" => (sim.step - sim.run_bounds.map_or(thermo.run_start, |b| b.0)) as f64,
        "part" => 0.0,
        "tpcpu" => {
            let now = sim.step as f64 * sim.dt;
            let (t0, c0) = thermo.tpcpu_mark.get();
            let cpu = clock.unwrap_or(0.0);
            thermo.tpcpu_mark.set((now, cpu));
            match clock {
                Some(c) if now - t0 > 0.0 && c - c0 > 0.0 => (now - t0) / (c - c0),
                _ => 0.0,
            }
        }
        "spcpu" | "cu" => {
            let (s0, c0) = thermo.spcpu_mark.get();
            let cpu = clock.unwrap_or(0.0);
            thermo.spcpu_mark.set((sim.step, cpu));
            let per_step = match clock {
                Some(c) if c - c0 > 0.0 => (sim.step - s0) as f64 / (c - c0),
                _ => 0.0,
            };
            if keyword == "cu" {
                per_step * n
            } else {
                per_step
            }
        }
        "cpuremain" => clock.map_or(0.0, |c| {
            c * (thermo.run_last - sim.step) as f64 / (sim.step - thermo.run_start) as f64
        }),
        "erotate" => {
            let e = crate::engine::computes::rotational_energy(p, 1);
            if thermo.norm && n > 0.0 {
                e / n
            } else {
                e
            }
        }
        "density" => {
            let vol = keyword_value("vol", sim, thermo, vars)?;
            p.mass.iter().sum::<f64>() / vol
        }
        "xy" | "xz" | "yz" => 0.0,
        "xlat" => lattice[0],
        "ylat" => lattice[1],
        "zlat" => lattice[2],
        "fmax" => {
            p.f.iter()
                .flat_map(|f| f.iter())
                .fold(0.0, |m: f64, c| m.max(c.abs()))
        }
        "fnorm" => {
            p.f.iter()
                .map(|f| f[0] * f[0] + f[1] * f[1] + f[2] * f[2])
                .sum::<f64>()
                .sqrt()
        }
        "cella" => d.length(0),
        "cellb" => d.length(1),
        "cellc" => d.length(2),
        "cellalpha" | "cellbeta" | "cellgamma" => 90.0,
        _ => return None,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn layout_matches_liggghts() {
        let mut t = Thermo::default();
        t.set_style(&["step", "atoms", "ke"]).unwrap();
        let mut text = String::new();
        t.header(&mut |s| text.push_str(s));
        t.line(&[0.0, 2.0, 9.0320789e-05], 0, 0.0, &mut |s| {
            text.push_str(s)
        });
        assert_eq!(
            text,
            "    Step    Atoms         KinEng \n       0        2  9.0320789e-05 \n"
        );
        assert!(t
            .set_style(&["step", "bogus"])
            .unwrap_err()
            .to_string()
            .starts_with("Invalid keyword"));
        t.set_style(&["fmax", "fnorm", "elaplong", "cellalpha"])
            .unwrap();
        assert_eq!(t.fields[2].kind, Kind::Int);
        assert_eq!(t.fields[3].label, "CellAlpha");
        t.set_style(&["v_x"]).unwrap();
        assert_eq!(t.fields[0].label, "x");
        // thermo_style multi, then user formats (layouts printed by Debian's LIGGGHTS)
        t.set_style(&["step", "atoms", "ke", "cpu"]).unwrap();
        t.multi = true;
        let mut text = String::new();
        t.header(&mut |s| text.push_str(s));
        t.line(&[2.0, 1.0, 0.0052359878, 0.0], 2, 0.0, &mut |s| {
            text.push_str(s)
        });
        assert_eq!(
            text,
            "---------------- Step        2 ----- CPU =      0.0000 (sec) ----------------\n\
             Step     =              2 Atoms    =              1 KinEng   =         0.0052 \n\
             CPU      =         0.0000 \n"
        );
        t.set_style(&["step", "atoms", "ke", "vol"]).unwrap();
        t.int_format = Some("%5d".into());
        t.column_formats = vec![None, None, Some("%12.5e".into()), None];
        let mut text = String::new();
        t.line(&[4.0, 1.0, 0.0052359878, 8.0], 4, 0.0, &mut |s| {
            text.push_str(s)
        });
        assert!(text.ends_with(
            "Step     =     4 Atoms    =     1 KinEng   =  5.23599e-03 \nVolume   =         8.0000 \n"
        ));
        t.multi = false;
        t.float_format = Some("%.10g".into());
        let mut text = String::new();
        t.line(&[4.0, 1.0, 0.0052359878, 8.0], 4, 0.0, &mut |s| {
            text.push_str(s)
        });
        assert_eq!(text, "    4     1  5.23599e-03 8 \n");
        t.set_style(&["step", "c_rke"]).unwrap();
        assert_eq!(t.fields[1].label, "rke");
        assert!(t.due(100, 1000) == (t.every > 0) && t.due(1000, 1000));
    }
}
