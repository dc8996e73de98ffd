//! The time-step margin a deck runs at (issue 16): the time step as a percentage of the
//! Rayleigh time of each material pair and of its Hertz contact time at the fastest speed the
//! deck can be expected to reach. `regolith check` prints it; a run prints it on standard
//! error (the screen and log keep LIGGGHTS's lines). LIGGGHTS says nothing of this unless the
//! deck asks (`fix check/timestep/gran`).

use crate::engine::fixes::{FixKind, Motion, Move};
use crate::engine::insert::Velocity;
use crate::engine::sim::Simulation;
use std::f64::consts::PI;

/// Fraction of the Rayleigh time above which the margin warns (a single Hertz collision
/// at 90 % of it loses 45 % of its energy to the integrator; EDEM's guidance is 20 % for
/// four or more contacts per particle, 40 % below).
pub const RAYLEIGH_WARN: f64 = 0.4;

/// The trade study's errors along its time-step axis: `scene,observable,path,frac,error,
/// absolute,spread`, one row per run (`frac` is dt as a fraction of the Rayleigh time; `error`
/// is relative to the exact path at the scene's reference step, or absolute where `absolute`
/// is 1; `spread` is the observable's relative run-to-run spread, 0 for a deterministic one,
/// and may be missing). Written by
/// `examples/trade/study.sh` (its `docs/trade_margin.csv`) and compiled in, so `check` and the
/// run header can say what a deck's margin costs in accuracy (docs/trade.md has the whole
/// study).
const TRADE_STUDY: &str = include_str!("../../docs/trade_margin.csv");

/// The error the trade's recommendation stays within.
pub const TRADE_TOLERANCE: f64 = 0.01;

/// A statistical observable's error counts as a draw (not a time-step error) up to this many
/// times its relative run-to-run spread.
pub const SPREAD_SIGMAS: f64 = 3.0;

/// One row of [`TRADE_STUDY`].
#[derive(Debug, Clone, PartialEq)]
pub struct TradeRow {
    /// The scene (collision, elastic, slide, chain_weak, chain_strong).
    pub scene: &'static str,
    /// The observable's name in the study.
    pub observable: &'static str,
    /// The fast path (`-sf fast`) rather than the exact one.
    pub fast: bool,
    /// dt as a fraction of the Rayleigh time.
    pub frac: f64,
    /// The error (relative, or absolute when `absolute`).
    pub error: f64,
    /// The error is absolute (the observable's exact value is 0).
    pub absolute: bool,
    /// The observable's relative run-to-run spread (0: deterministic): a statistical
    /// observable's errors within it are draws, not time-step errors.
    pub spread: f64,
}

/// One observable of the study at a deck's margin ([`trade_at`]).
#[derive(Debug, Clone, PartialEq)]
pub struct TradeAt {
    /// What it is, in words.
    pub label: String,
    /// The error measured at the margin (relative, or absolute when `absolute`).
    pub error: f64,
    /// The error is absolute.
    pub absolute: bool,
    /// The largest dt / Rayleigh time up to which every error stays within the tolerance (or
    /// within [`SPREAD_SIGMAS`] run-to-run spreads where that is larger); None: not even the
    /// smallest step.
    pub within: Option<f64>,
    /// The relative run-to-run spread (0: deterministic).
    pub spread: f64,
}

/// The rows of the compiled-in trade study (rows that do not parse are left out).
pub fn trade_study() -> Vec<TradeRow> {
    TRADE_STUDY
        .lines()
        .skip(1)
        .filter_map(|l| {
            let w: Vec<&'static str> = l.split(',').map(str::trim).collect();
            if w.len() < 6 {
                return None;
            }
            Some(TradeRow {
                scene: w[0],
                observable: w[1],
                fast: w[2] == "fast",
                frac: w[3].parse().ok()?,
                error: w[4].parse().ok()?,
                absolute: w[5] == "1",
                spread: w.get(6).and_then(|x| x.parse().ok()).unwrap_or(0.0),
            })
        })
        .collect()
}

/// What an observable of the study is, in words.
fn trade_label(scene: &str, observable: &str) -> String {
    match (scene, observable) {
        ("collision", "e") => "restitution".into(),
        ("collision", "tc") => "contact time".into(),
        ("elastic", "drift") => "energy drift at e = 1".into(),
        ("slide", "v_roll") => "rolling speed".into(),
        ("slide", "t_roll") => "sliding time".into(),
        ("chain_weak", "c_w") => "wave speed (weak impact)".into(),
        ("chain_strong", "c_w") => "wave speed (strong impact)".into(),
        ("bed", "phi") => "bed packing fraction".into(),
        ("bed", "H") => "bed height".into(),
        ("channel", "c_w") => "channel front speed".into(),
        ("channel", "rise") => "channel surface rise".into(),
        _ => format!("{scene} {observable}"),
    }
}

/// Per observable of the study (in the study's order): its label, the error measured at
/// `frac` (the study's nearest time step at or above it, or its largest), whether that error
/// is absolute, and the largest time step (fraction of the Rayleigh time) up to which every
/// error of the observable stays within `tolerance` (or within [`SPREAD_SIGMAS`] times its
/// run-to-run spread, where that is larger), on the given path (None: not even at the study's
/// smallest step).
pub fn trade_at(rows: &[TradeRow], frac: f64, fast: bool, tolerance: f64) -> Vec<TradeAt> {
    let mut keys: Vec<(&str, &str)> = Vec::new();
    for r in rows {
        if !keys.contains(&(r.scene, r.observable)) {
            keys.push((r.scene, r.observable));
        }
    }
    let mut out = Vec::new();
    for (scene, observable) in keys {
        let mut pts: Vec<&TradeRow> = rows
            .iter()
            .filter(|r| r.scene == scene && r.observable == observable && r.fast == fast)
            .collect();
        pts.sort_by(|a, b| a.frac.total_cmp(&b.frac));
        let Some(last) = pts.last() else { continue };
        // the reference run (error 0 by definition) is no measurement of the error
        let measured: Vec<&&TradeRow> = pts
            .iter()
            .filter(|r| r.error != 0.0 || r.absolute)
            .collect();
        let at = measured
            .iter()
            .find(|r| r.frac >= frac * (1.0 - 1e-9))
            .or(measured.last())
            .map_or(0.0, |r| r.error);
        let spread = pts.iter().map(|r| r.spread).fold(0.0, f64::max);
        let bound = tolerance.max(SPREAD_SIGMAS * spread);
        let mut within = None;
        for r in &pts {
            if r.error.abs() <= bound {
                within = Some(r.frac);
            } else {
                break;
            }
        }
        out.push(TradeAt {
            label: trade_label(scene, observable),
            error: at,
            absolute: last.absolute,
            within,
            spread,
        });
    }
    out
}

/// The lines `check` and the run header add after the margin: the study's errors at the
/// deck's largest dt / Rayleigh time (`frac`) and the largest time step that keeps every
/// observable within 1 %.
pub fn trade_lines(frac: f64) -> String {
    let rows = trade_study();
    // a NaN fraction has no row either
    #[allow(clippy::neg_cmp_op_on_partial_ord)]
    if rows.is_empty() || !(frac > 0.0) {
        return String::new();
    }
    let largest = rows.iter().map(|r| r.frac).fold(0.0, f64::max);
    let exact = trade_at(&rows, frac, false, TRADE_TOLERANCE);
    let fast = trade_at(&rows, frac, true, TRADE_TOLERANCE);
    // the study's column the errors are read from: its next measured step up
    let column = rows
        .iter()
        .filter(|r| r.frac >= frac * (1.0 - 1e-9) && r.error != 0.0)
        .map(|r| r.frac)
        .fold(f64::INFINITY, f64::min);
    let mut s = String::from("  trade study (docs/trade.md): ");
    if column.is_finite() {
        s.push_str(&format!(
            "measured errors at {} of the Rayleigh time (the study's {} column, exact path):\n",
            pct(100.0 * frac),
            pct(100.0 * column)
        ));
    } else {
        s.push_str(&format!(
            "{} of the Rayleigh time is beyond the study's largest step; errors at {} (exact path):\n",
            pct(100.0 * frac),
            pct(100.0 * largest)
        ));
    }
    s.push_str(&observable_lines(&exact));
    // statistical observables do not resolve a time-step error below their spread: they are
    // quoted, but do not set the fastest setting
    let smallest = |set: &[TradeAt]| {
        set.iter()
            .filter(|x| x.spread == 0.0)
            .map(|x| x.within.unwrap_or(0.0))
            .fold(f64::INFINITY, f64::min)
    };
    let (best_exact, best_fast) = (smallest(&exact), smallest(&fast));
    if best_exact > 0.0 && best_exact.is_finite() {
        s.push_str(&fastest_line(&rows, &exact, frac, best_exact, best_fast));
    }
    s
}

/// The study's errors per observable at the deck's step, and the largest step within the
/// tolerance per observable.
fn observable_lines(exact: &[TradeAt]) -> String {
    let words: Vec<String> = exact
        .iter()
        .map(|t| {
            if t.absolute {
                format!("{} {:.1e}", t.label, t.error)
            } else if t.spread > 0.0 {
                format!(
                    "{} {} (run-to-run spread {})",
                    t.label,
                    pct_err(100.0 * t.error),
                    pct_err(100.0 * t.spread)
                )
            } else {
                format!("{} {}", t.label, pct_err(100.0 * t.error))
            }
        })
        .collect();
    let mut s = format!("    {}\n", words.join(", "));
    let each: Vec<String> = exact
        .iter()
        .map(|t| {
            let within = match t.within {
                Some(f) => pct(100.0 * f),
                None => "none".into(),
            };
            if t.spread > 0.0 {
                format!("{} {within} (statistical)", t.label)
            } else {
                format!("{} {within}", t.label)
            }
        })
        .collect();
    s.push_str(&format!(
        "  within {}, dt up to (of the Rayleigh time): {}\n",
        pct(100.0 * TRADE_TOLERANCE),
        each.join(", ")
    ));
    s
}

/// The fastest setting (time step, engine path) that keeps every deterministic observable
/// within the tolerance: `best_exact` and `best_fast` are each path's largest fraction of
/// the Rayleigh time.
fn fastest_line(
    rows: &[TradeRow],
    exact: &[TradeAt],
    frac: f64,
    best_exact: f64,
    best_fast: f64,
) -> String {
    // the fast path's errors in the study, against the exact path's at the same step
    let same = rows.iter().filter(|r| r.fast && r.spread == 0.0).all(|r| {
        rows.iter().any(|x| {
            !x.fast
                && (x.scene, x.observable, x.frac) == (r.scene, r.observable, r.frac)
                && x.error == r.error
        })
    });
    let (best, path) = if best_fast >= best_exact && same {
        (
            best_fast,
            ", -sf fast (the study's fast-path errors are the exact path's)",
        )
    } else if best_fast >= best_exact {
        (best_fast, ", -sf fast")
    } else {
        (best_exact, " on the exact path")
    };
    let gain = if best > frac * (1.0 + 1e-9) {
        format!(" ({} this deck's)", times(best / frac))
    } else {
        String::new()
    };
    let aside = if exact.iter().any(|t| t.spread > 0.0) {
        " (the statistical ones aside)"
    } else {
        ""
    };
    format!(
        "  fastest setting within {} for all of them{aside}: dt = {} of the Rayleigh time{gain}{path}\n",
        pct(100.0 * TRADE_TOLERANCE),
        pct(100.0 * best),
    )
}

fn times(x: f64) -> String {
    if x >= 10.0 {
        format!("{x:.0}x")
    } else {
        format!("{x:.1}x")
    }
}

/// An error in percent, two significant digits.
fn pct_err(p: f64) -> String {
    if p == 0.0 {
        "0 %".into()
    } else if p < 0.001 {
        "< 0.001 %".into()
    } else if p >= 10.0 {
        format!("{p:.0} %")
    } else {
        let digits = (1 - p.log10().floor() as i32).clamp(0, 12) as usize;
        format!("{p:.digits$} %")
    }
}

/// The Rayleigh time of a sphere of radius `r` and density `rho` of a material with Young's
/// modulus `e` and Poisson ratio `nu`: pi r sqrt(rho / G) / (0.1631 nu + 0.8766), with the
/// shear modulus G = E / (2 (1 + nu)).
pub fn rayleigh_time(r: f64, rho: f64, e: f64, nu: f64) -> f64 {
    let g = e / (2.0 * (1.0 + nu));
    PI * r * (rho / g).sqrt() / (0.1631 * nu + 0.8766)
}

/// The contact time of an undamped Hertz collision of two spheres (radii `r1`, `r2`,
/// densities `rho1`, `rho2`, effective Young's modulus `yeff`) at impact speed `v`:
/// 2.87 (m*^2 / (R* Y*^2 v))^(1/5), m* and R* the reduced mass and radius.
pub fn hertz_time(r1: f64, rho1: f64, r2: f64, rho2: f64, yeff: f64, v: f64) -> f64 {
    let m = |r: f64, rho: f64| 4.0 / 3.0 * PI * r * r * r * rho;
    let (m1, m2) = (m(r1, rho1), m(r2, rho2));
    let meff = m1 * m2 / (m1 + m2);
    let reff = r1 * r2 / (r1 + r2);
    2.87 * (meff * meff / (reff * yeff * yeff * v)).powf(0.2)
}

/// The fastest speed a deck can be expected to reach, and where it comes from.
#[derive(Debug, Clone, PartialEq)]
pub struct ExpectedSpeed {
    /// Speed (length/time).
    pub value: f64,
    /// What gives it ("free fall over the box height (0.5 m)", "fix push (move linear)", ...).
    pub source: String,
}

/// One atom type's smallest particle: (radius, density).
type Size = (f64, f64);

fn g(x: f64) -> String {
    crate::util::format::g(x)
}

fn pct(x: f64) -> String {
    if x >= 10.0 {
        format!("{x:.1} %")
    } else if x >= 0.1 {
        format!("{x:.2} %")
    } else {
        format!("{} %", g(x))
    }
}

impl Simulation {
    /// Per atom type (index type - 1): the particle (present or from a particle template)
    /// with the shortest Rayleigh time, as (radius, density); None for a type without any.
    fn type_sizes(&self) -> Vec<Option<Size>> {
        let n = self.ntypes as usize;
        let mut sizes: Vec<Option<Size>> = vec![None; n];
        let mut offer = |t: usize, r: f64, rho: f64| {
            if t == 0 || t > n || !(r > 0.0 && rho > 0.0) {
                return;
            }
            // the Rayleigh time grows as r sqrt(rho)
            let key = |s: Size| s.0 * s.1.sqrt();
            if sizes[t - 1].is_none_or(|s| key((r, rho)) < key(s)) {
                sizes[t - 1] = Some((r, rho));
            }
        };
        let p = &self.particles;
        for i in 0..p.len() {
            offer(p.kind[i] as usize, p.radius[i], p.density[i]);
        }
        for f in &self.fixes {
            if let Some(t) = f.kind.template() {
                offer(t.atom_type as usize, t.radius, t.density);
            }
        }
        sizes
    }

    /// The fastest speed the deck can be expected to reach: the fastest particle now, the
    /// insertion velocities, prescribed motion (`fix move linear`), a sheared wall, and free
    /// fall over the box height under `fix gravity`.
    pub fn expected_speed(&self) -> ExpectedSpeed {
        let mut best = ExpectedSpeed {
            value: 0.0,
            source: "no particle moves and nothing drives them".into(),
        };
        let mut offer = |v: f64, source: String| {
            if v.is_finite() && v > best.value {
                best = ExpectedSpeed { value: v, source };
            }
        };
        let norm = |v: [f64; 3]| (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
        let p = &self.particles;
        if let Some(i) = (0..p.len()).max_by(|&a, &b| norm(p.v[a]).total_cmp(&norm(p.v[b]))) {
            offer(
                norm(p.v[i]),
                format!("the fastest particle now (atom {})", p.id[i]),
            );
        }
        let insertion = |v: &Velocity| match v {
            Velocity::Constant(v) => norm(*v),
            Velocity::Uniform(v, d) | Velocity::Gaussian(v, d) => norm(*v) + norm(*d),
        };
        for f in &self.fixes {
            if let Some(m) = f.kind.style_as::<Move>() {
                if let Motion::Linear(v) = &m.motion {
                    offer(
                        norm(v.map(|c| c.unwrap_or(0.0))),
                        format!("fix {} (move linear)", f.id),
                    );
                }
                continue;
            }
            if let Some(ins) = f.kind.insert_pack() {
                offer(
                    insertion(&ins.velocity),
                    format!("fix {} (insertion velocity)", f.id),
                );
                continue;
            }
            if let Some(s) = f.kind.stream() {
                offer(
                    insertion(&s.velocity),
                    format!("fix {} (insertion velocity)", f.id),
                );
                continue;
            }
            if let Some((_, v)) = f.kind.primitive_wall().and_then(|w| w.shear) {
                offer(v.abs(), format!("fix {} (wall shear)", f.id));
                continue;
            }
            // free fall under `fix gravity`
            let FixKind::Style(s) = &f.kind else {
                continue;
            };
            let Some(acc) = s.acceleration() else {
                continue;
            };
            let a = norm(acc);
            if a > 0.0 {
                let h: f64 = (0..3)
                    .map(|d| acc[d].abs() / a * self.domain.length(d))
                    .sum();
                offer(
                    (2.0 * a * h).sqrt(),
                    format!("free fall over the box height ({} at {})", g(h), g(a)),
                );
            }
        }
        best
    }

    /// The time-step margin, as lines of text (each ending in a newline); empty when the deck
    /// has no granular pair style, no Young's modulus and Poisson ratio per type, or no
    /// particle sizes yet.
    pub fn timestep_margin(&self) -> String {
        let Some(sel) = &self.pair_selection else {
            return String::new();
        };
        let table = |name: &str| self.property(name).map(|(_, _, v)| v);
        let (Some(e), Some(nu)) = (table("youngsModulus"), table("poissonsRatio")) else {
            return String::new();
        };
        let sizes = self.type_sizes();
        let n = sizes.len().min(e.len()).min(nu.len());
        let dt = self.dt.abs();
        // a NaN time step has no margin either
        #[allow(clippy::neg_cmp_op_on_partial_ord)]
        if n == 0 || !(dt > 0.0) || sizes.iter().all(Option::is_none) {
            return String::new();
        }
        let speed = self.expected_speed();
        // two particles meeting head-on, each at the fastest expected speed
        let impact = 2.0 * speed.value;
        let hertz = sel.normal == "hertz" || sel.normal == "hertz/stiffness";
        let mut s = format!("Time-step margin (regolith; dt = {} s):\n", g(self.dt));
        // the largest dt / Rayleigh time over the type pairs
        let mut worst_frac: f64 = 0.0;
        for (t, size) in sizes.iter().enumerate().take(n) {
            if let Some((r, rho)) = size {
                s.push_str(&format!(
                    "  type {}: radius {}, density {}, E {}, nu {}: Rayleigh time {} s\n",
                    t + 1,
                    g(*r),
                    g(*rho),
                    g(e[t]),
                    g(nu[t]),
                    g(rayleigh_time(*r, *rho, e[t], nu[t]))
                ));
            }
        }
        for i in 0..n {
            for j in i..n {
                let (Some((ri, rhoi)), Some((rj, rhoj))) = (sizes[i], sizes[j]) else {
                    continue;
                };
                // the pair's Rayleigh time: the shorter of its two types'
                let tr =
                    rayleigh_time(ri, rhoi, e[i], nu[i]).min(rayleigh_time(rj, rhoj, e[j], nu[j]));
                worst_frac = worst_frac.max(dt / tr);
                s.push_str(&format!(
                    "  types {}-{}: dt is {} of the Rayleigh time",
                    i + 1,
                    j + 1,
                    pct(100.0 * dt / tr),
                ));
                if hertz && impact > 0.0 {
                    let yeff = crate::engine::contact::material::mix_yeff(e[i], e[j], nu[i], nu[j]);
                    let th = hertz_time(ri, rhoi, rj, rhoj, yeff, impact);
                    s.push_str(&format!(
                        " and {} of the Hertz contact time {} s at impact speed {}",
                        pct(100.0 * dt / th),
                        g(th),
                        g(impact)
                    ));
                }
                s.push('\n');
                if dt > RAYLEIGH_WARN * tr {
                    s.push_str(&format!(
                        "  WARNING: types {}-{}: dt is above {} of the Rayleigh time: contacts \
                         lose energy they should keep and the run may blow up (a dense packing \
                         wants at most 20 %)\n",
                        i + 1,
                        j + 1,
                        pct(100.0 * RAYLEIGH_WARN)
                    ));
                }
            }
        }
        if hertz {
            if impact > 0.0 {
                s.push_str(&format!(
                    "  impact speed: twice the fastest expected speed {} (two particles head-on), from {}\n",
                    g(speed.value),
                    speed.source
                ));
            } else {
                s.push_str(&format!("  no Hertz contact time: {}\n", speed.source));
            }
        }
        if hertz && worst_frac.is_finite() {
            s.push_str(&trade_lines(worst_frac));
        }
        s
    }
}

/// A contact model's sub-models, as LIGGGHTS's keywords name them.
fn composed(sel: &crate::engine::granular::Selection) -> String {
    let mut s = format!("normal {}, tangential {}", sel.normal, sel.tangential);
    if sel.cohesion != "off" {
        s.push_str(&format!(", cohesion {}", sel.cohesion));
    }
    if sel.rolling != "off" {
        s.push_str(&format!(", rolling {}", sel.rolling));
    }
    if sel.surface != "default" {
        s.push_str(&format!(", surface {}", sel.surface));
    }
    s
}

fn doubles(w: usize) -> String {
    let unit = if w == 1 { "double" } else { "doubles" };
    format!("{w} {unit} ({} bytes)", 8 * w)
}

impl Simulation {
    /// The composed contact models of the pair style and of each granular wall, with their
    /// contact-history widths and the history's bytes per particle (the pair's from the
    /// listed pairs at this moment); empty without contact models. Models are built at a
    /// run's setup, so a run (not a dry run) reports widths.
    pub fn contact_models(&self) -> String {
        let mut lines = Vec::new();
        let n = self.particles.len();
        if let Some(sel) = &self.pair_selection {
            let mut line = format!("  pair_style gran: {}", composed(sel));
            if let Some(pair) = &self.pair {
                let w = pair.history_width();
                line.push_str(&format!("; history {} per neighbour pair", doubles(w)));
                if w > 0 && n > 0 {
                    let pairs = self.list.pairs.len();
                    line.push_str(&format!(
                        ", {} pairs listed now: {} bytes per particle",
                        pairs,
                        g((8 * w * pairs) as f64 / n as f64)
                    ));
                }
            }
            lines.push(line);
        }
        for f in &self.fixes {
            if let Some(w) = f.kind.primitive_wall() {
                let mut line = format!(
                    "  fix {} (wall/gran primitive): {}",
                    f.id,
                    composed(&w.selection)
                );
                if let Some(m) = &w.model {
                    line.push_str(&format!(
                        "; history {} per particle",
                        doubles(m.history_width())
                    ));
                }
                lines.push(line);
                continue;
            }
            if let Some(w) = f.kind.mesh_wall() {
                let mut line = format!(
                    "  fix {} (wall/gran mesh {}): {}",
                    f.id,
                    w.meshes.join(" "),
                    composed(&w.selection)
                );
                if w.model.is_some() {
                    line.push_str(&format!(
                        "; history {} per contact with a triangle",
                        doubles(w.history_width())
                    ));
                }
                lines.push(line);
            }
        }
        if lines.is_empty() {
            return String::new();
        }
        format!("Contact models (regolith):\n{}\n", lines.join("\n"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn contact_times_by_hand() {
        // lunar material, R = 1.25 mm: G = 5e6 / 2.4 = 2.08333e6 Pa, sqrt(2500 / G) = 0.0346410,
        // pi R 0.0346410 / (0.1631 * 0.2 + 0.8766) = 1.360350e-4 / 0.90922 = 1.496172e-4 s
        let t = rayleigh_time(0.00125, 2500.0, 5e6, 0.2);
        assert!((t / 1.496172e-4 - 1.0).abs() < 1e-6, "{t}");
        // two such spheres meeting at 2 m/s: m = 2.045308e-5 kg, m* = m / 2, R* = 6.25e-4 m,
        // Y* = 5e6 / (2 (1 - 0.04)) = 2.604167e6 Pa:
        // 2.87 (m*^2 / (R* Y*^2 v))^(1/5) = 2.87 (1.045822e-10 / 8.477105e9)^(1/5) = 2.993118e-4 s
        let y = 5e6 / (2.0 * (1.0 - 0.04));
        let th = hertz_time(0.00125, 2500.0, 0.00125, 2500.0, y, 2.0);
        assert!((th / 2.993118e-4 - 1.0).abs() < 1e-6, "{th}");
    }

    fn row(observable: &'static str, fast: bool, frac: f64, error: f64) -> TradeRow {
        TradeRow {
            scene: "collision",
            observable,
            fast,
            frac,
            error,
            absolute: false,
            spread: 0.0,
        }
    }

    #[test]
    fn trade_errors_at_a_margin_and_the_largest_step_within_tolerance() {
        let rows = vec![
            row("e", false, 0.001, 0.0),
            row("e", false, 0.01, 0.002),
            row("e", false, 0.1, 0.005),
            row("e", false, 0.2, 0.02),
            row("e", false, 0.4, 0.005),
            row("tc", false, 0.001, 0.0),
            row("tc", false, 0.01, 0.001),
            row("tc", false, 0.1, 0.03),
            row("e", true, 0.01, 0.002),
        ];
        let exact = trade_at(&rows, 0.0067, false, 0.01);
        // measured at the study's next step up (1 %); within 1 % up to the first step past it
        // (not again at 40 %, where the error happens to be small)
        let t = |x: &TradeAt| (x.label.clone(), x.error, x.absolute, x.within);
        assert_eq!(
            t(&exact[0]),
            ("restitution".to_string(), 0.002, false, Some(0.1))
        );
        assert_eq!(
            t(&exact[1]),
            ("contact time".to_string(), 0.001, false, Some(0.01))
        );
        // beyond the study: its largest step's error
        assert_eq!(trade_at(&rows, 0.5, false, 0.01)[0].error, 0.005);
        // below the study's smallest measured step: that step's error (not the reference's 0)
        assert_eq!(trade_at(&rows, 0.0005, false, 0.01)[0].error, 0.002);
        assert_eq!(trade_at(&rows, 0.01, true, 0.01)[0].within, Some(0.01));
        // a statistical observable: errors within three run-to-run spreads (3 x 1 %) are draws
        let noisy: Vec<TradeRow> = rows
            .iter()
            .map(|r| TradeRow {
                spread: 0.01,
                ..r.clone()
            })
            .collect();
        let at = trade_at(&noisy, 0.0067, false, 0.01);
        assert_eq!((at[0].within, at[0].spread), (Some(0.4), 0.01));
        assert_eq!(at[1].within, Some(0.1));
    }

    #[test]
    fn the_compiled_in_study_is_read_and_quoted() {
        let rows = trade_study();
        assert!(rows.len() > 50, "{}", rows.len());
        assert!(rows.iter().any(|r| r.fast) && rows.iter().any(|r| r.absolute));
        let text = trade_lines(0.0067);
        assert!(
            text.starts_with(
                "  trade study (docs/trade.md): measured errors at 0.67 % of the Rayleigh time \
                 (the study's 1.00 % column, exact path):\n    restitution "
            ),
            "{text}"
        );
        assert!(
            text.contains("fastest setting within 1.00 % for all of them"),
            "{text}"
        );
        assert!(trade_lines(0.5).contains("beyond the study's largest step; errors at 40.0 %"));
    }
}
