//! `regolith bench`: time decks as whole processes, regolith's exact and fast paths and
//! (with `--liggghts`) Debian's LIGGGHTS, interleaved run by run, and report medians of the
//! rate in particle-steps per second with the time split and neighbour figures each program
//! prints. Timing is measured here, never asserted by tests.
//!
//! `regolith bench beds` runs the standard beds ([`beds`]); `regolith bench DECK|SCENE`
//! one deck.

pub mod beds;
pub mod measure;

use std::path::{Path, PathBuf};

use crate::tool_error::ToolError;

pub use measure::{parse_output, Measure, Program};

/// Built-in scenes: (name, deck text).
pub const SCENES: &[(&str, &str)] = &[
    (
        "settled_bed",
        include_str!("../../benches/settled_bed/in.bed"),
    ),
    (
        "struck_chain",
        include_str!("../../examples/struck_chain/in.struck_chain"),
    ),
];

/// Which programs to time.
#[derive(Debug, Clone, PartialEq)]
pub struct ProgramChoice {
    /// Debian's `liggghts` (one core).
    pub liggghts: bool,
    /// regolith's exact path on one thread.
    pub exact: bool,
    /// regolith's fast path at these thread counts.
    pub fast_threads: Vec<usize>,
    /// regolith's fast path under `mpirun -np N`, one thread per rank, at these rank counts.
    pub ranks: Vec<usize>,
}

impl ProgramChoice {
    /// The programs, in the order they run in each round.
    pub fn programs(&self) -> Result<Vec<Program>, ToolError> {
        let me = std::env::current_exe().map_err(|e| ToolError::Run(e.to_string()))?;
        let mut v = Vec::new();
        if self.liggghts {
            v.push(Program {
                label: "liggghts".into(),
                exe: PathBuf::from("liggghts"),
                args: Vec::new(),
                env: vec![("OMP_NUM_THREADS".into(), "1".into())],
                threads: 1,
            });
        }
        if self.exact {
            v.push(Program {
                label: "exact".into(),
                exe: me.clone(),
                args: Vec::new(),
                env: vec![("RAYON_NUM_THREADS".into(), "1".into())],
                threads: 1,
            });
        }
        for &t in &self.fast_threads {
            v.push(Program {
                label: format!("fast {t}t"),
                exe: me.clone(),
                args: vec![
                    "-sf".into(),
                    "fast".into(),
                    "-pk".into(),
                    "fast".into(),
                    t.to_string(),
                ],
                env: Vec::new(),
                threads: t,
            });
        }
        for &n in &self.ranks {
            v.push(Program {
                label: format!("fast {n}r"),
                exe: PathBuf::from("mpirun"),
                args: vec![
                    "-np".into(),
                    n.to_string(),
                    me.to_string_lossy().into_owned(),
                    "-sf".into(),
                    "fast".into(),
                    "-pk".into(),
                    "fast".into(),
                    "1".into(),
                ],
                // Open MPI refuses to start as root unless told both
                env: vec![
                    ("OMPI_ALLOW_RUN_AS_ROOT".into(), "1".into()),
                    ("OMPI_ALLOW_RUN_AS_ROOT_CONFIRM".into(), "1".into()),
                ],
                threads: n,
            });
        }
        if v.is_empty() {
            return Err(ToolError::usage(
                "nothing to time: give --exact, --fast, --ranks or --liggghts",
            ));
        }
        Ok(v)
    }
}

/// Options of a one-deck benchmark.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// A built-in scene name or a deck path.
    pub scene: String,
    /// Runs per program.
    pub repeat: usize,
    /// The programs.
    pub choice: ProgramChoice,
    /// `-var NAME VALUE` pairs passed to the deck.
    pub vars: Vec<(String, String)>,
}

/// Time one deck; returns the report text.
pub fn bench(opts: &BenchOptions) -> Result<String, ToolError> {
    let dir = std::env::temp_dir().join(format!("regolith-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(ToolError::file(&dir))?;
    let builtin = SCENES.iter().find(|(n, _)| *n == opts.scene);
    let (workdir, deck) = match builtin {
        Some((name, text)) => {
            let file = dir.join(format!("in.{name}"));
            std::fs::write(&file, text).map_err(ToolError::file(&file))?;
            (dir.clone(), file)
        }
        None => {
            let p = PathBuf::from(&opts.scene);
            if !p.is_file() {
                let names: Vec<&str> = SCENES.iter().map(|(n, _)| *n).collect();
                return Err(ToolError::Usage(format!(
                    "{}: neither a deck file nor a built-in scene ({}, or `beds`)",
                    opts.scene,
                    names.join(", ")
                )));
            }
            let deck = std::fs::canonicalize(&p).map_err(ToolError::file(&p))?;
            // decks with side files run from their own folder
            let folder = deck.parent().map_or_else(|| dir.clone(), Path::to_path_buf);
            (folder, deck)
        }
    };
    let programs = opts.choice.programs()?;
    let deck_arg = deck.to_string_lossy().into_owned();
    let mut runs: Vec<Vec<Measure>> = vec![Vec::new(); programs.len()];
    let mut report = format!(
        "scene {} ({} run(s) each, interleaved)\n{:<10} {:>4} {:>12} {:>10} {:>16}\n",
        opts.scene, opts.repeat, "program", "run", "loop s", "steps", "atom-steps/s"
    );
    for r in 0..opts.repeat.max(1) {
        for (k, p) in programs.iter().enumerate() {
            let m = measure::run_once(p, &workdir, &deck_arg, &opts.vars)?;
            report.push_str(&format!(
                "{:<10} {:>4} {:>12.3} {:>10} {:>16.4e}\n",
                p.label,
                r + 1,
                m.seconds,
                m.steps,
                m.rate()
            ));
            runs[k].push(m);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    let contacts = runs.iter().flatten().find_map(|m| m.contacts);
    let rows: Vec<beds::Row> = programs
        .iter()
        .zip(&runs)
        .map(|(p, r)| {
            let case = (opts.scene.clone(), String::new(), String::new());
            beds::summarise(case, p, r, contacts)
        })
        .collect();
    report.push('\n');
    report.push_str(&details(&rows));
    Ok(report)
}

/// Millions, 3 significant digits.
fn mega(v: f64) -> String {
    if v.is_finite() {
        format!("{:.3}", v / 1e6)
    } else {
        "-".into()
    }
}

/// Per-program medians: rate, ratios, contacts, neighbour builds, time split, memory.
pub fn details(rows: &[beds::Row]) -> String {
    let mut s = String::from(
        "| case | program | M particle-steps/s | vs liggghts | M contacts/s | builds (dangerous) | pair % | neigh % | comm % | output % | other % | bytes/particle |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let base = rows
            .iter()
            .find(|o| o.case == r.case && o.program == "liggghts")
            .map(|o| o.rate);
        let case = [&r.case.0, &r.case.1, &r.case.2]
            .iter()
            .filter(|x| !x.is_empty())
            .map(|x| x.as_str())
            .collect::<Vec<_>>()
            .join(" ");
        s.push_str(&format!(
            "| {case} | {} | {} | {} | {} | {} ({}) | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} | {:.0} |\n",
            r.program,
            mega(r.rate),
            base.map_or("-".into(), |b| format!("{:.2}x", r.rate / b)),
            mega(r.contacts_rate),
            r.builds.0,
            r.builds.1,
            100.0 * r.split[0],
            100.0 * r.split[1],
            100.0 * r.split[2],
            100.0 * r.split[3],
            100.0 * r.split[4],
            r.bytes_per_particle
        ));
    }
    s
}

/// The speed table: one line per case, particle-steps/s of each program and the ratios to
/// LIGGGHTS (and of the largest thread count to one thread on the fast path).
pub fn speed_table(rows: &[beds::Row]) -> String {
    let mut labels: Vec<&str> = Vec::new();
    for r in rows {
        if !labels.contains(&r.program.as_str()) {
            labels.push(&r.program);
        }
    }
    let mut s = String::from("| bed | model | state |");
    for l in &labels {
        s.push_str(&format!(" {l} (M/s) |"));
    }
    let has_liggghts = labels.contains(&"liggghts");
    if has_liggghts {
        for l in labels.iter().filter(|l| **l != "liggghts") {
            s.push_str(&format!(" {l} / liggghts |"));
        }
    }
    s.push('\n');
    s.push_str(&"|---".repeat(3 + labels.len() + if has_liggghts { labels.len() - 1 } else { 0 }));
    s.push_str("|\n");
    let mut cases: Vec<&(String, String, String)> = Vec::new();
    for r in rows {
        if !cases.contains(&&r.case) {
            cases.push(&r.case);
        }
    }
    for case in cases {
        let rate = |l: &str| {
            rows.iter()
                .find(|r| &r.case == case && r.program == l)
                .map_or(f64::NAN, |r| r.rate)
        };
        s.push_str(&format!("| {} | {} | {} |", case.0, case.1, case.2));
        for l in &labels {
            s.push_str(&format!(" {} |", mega(rate(l))));
        }
        if has_liggghts {
            for l in labels.iter().filter(|l| **l != "liggghts") {
                s.push_str(&format!(" {:.2}x |", rate(l) / rate("liggghts")));
            }
        }
        s.push('\n');
    }
    s
}

/// A PNG of particle-steps/s against thread count: the fast path of each case as a line,
/// LIGGGHTS and the exact path (one core each) as markers at one thread.
pub fn plot(rows: &[beds::Row], path: &Path) -> Result<(), ToolError> {
    use crate::analyze::plot::{save, Chart, Curve, Style};
    let mut cases: Vec<&(String, String, String)> = Vec::new();
    for r in rows {
        if !cases.contains(&&r.case) {
            cases.push(&r.case);
        }
    }
    let name = |c: &(String, String, String)| {
        [&c.0, &c.1, &c.2]
            .iter()
            .filter(|x| !x.is_empty())
            .map(|x| x.as_str())
            .collect::<Vec<_>>()
            .join(" ")
    };
    let mut curves = Vec::new();
    for case in &cases {
        let fast: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| &&r.case == case && r.program.starts_with("fast"))
            .map(|r| (r.threads as f64, r.rate / 1e6))
            .collect();
        if !fast.is_empty() {
            curves.push(Curve::new(
                &format!("{} fast", name(case)),
                fast,
                Style::Line,
            ));
        }
    }
    for label in ["exact", "liggghts"] {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.program == label)
            .map(|r| (1.0, r.rate / 1e6))
            .collect();
        if !pts.is_empty() {
            curves.push(Curve::new(
                &format!("{label} (1 core, all cases)"),
                pts,
                Style::Points,
            ));
        }
    }
    let chart = Chart {
        title: "particle-steps per second against threads".into(),
        x_label: "threads".into(),
        y_label: "M particle-steps/s".into(),
        log_x: false,
        log_y: false,
        curves,
    };
    Ok(save(path, &[chart], 900, 560)?)
}

/// The rows as CSV.
pub fn csv(rows: &[beds::Row]) -> String {
    let mut s = String::from(
        "bed,model,state,program,threads,particle_steps_per_s,contacts_per_s,builds,dangerous,pair,neigh,comm,output,other,bytes_per_particle,atoms,runs\n",
    );
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{},{},{:.6e},{:.6e},{},{},{:.4},{:.4},{:.4},{:.4},{:.4},{:.1},{},{}\n",
            r.case.0,
            r.case.1,
            r.case.2,
            r.program,
            r.threads,
            r.rate,
            r.contacts_rate,
            r.builds.0,
            r.builds.1,
            r.split[0],
            r.split[1],
            r.split[2],
            r.split[3],
            r.split[4],
            r.bytes_per_particle,
            r.atoms,
            r.runs
        ));
    }
    s
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rank_counts_run_the_fast_path_under_mpirun_one_thread_per_rank() {
        let choice = ProgramChoice {
            liggghts: false,
            exact: false,
            fast_threads: vec![1],
            ranks: vec![2, 3],
        };
        let p = choice.programs().unwrap();
        let labels: Vec<&str> = p.iter().map(|p| p.label.as_str()).collect();
        assert_eq!(labels, ["fast 1t", "fast 2r", "fast 3r"]);
        assert_eq!(p[2].exe, PathBuf::from("mpirun"));
        assert_eq!(&p[2].args[..2], ["-np", "3"]);
        assert_eq!(&p[2].args[3..], ["-sf", "fast", "-pk", "fast", "1"]);
        assert_eq!(p[2].threads, 3);
    }

    fn row(program: &str, rate: f64) -> beds::Row {
        beds::Row {
            case: ("10k".into(), "hh".into(), "rest".into()),
            program: program.into(),
            threads: 1,
            rate,
            contacts_rate: 2.0 * rate,
            split: [0.8, 0.1, 0.0, 0.0, 0.1],
            builds: (3, 0),
            bytes_per_particle: 500.0,
            atoms: 10_000,
            runs: 3,
        }
    }

    #[test]
    fn tables_show_rates_and_ratios() {
        let rows = vec![row("liggghts", 2e6), row("exact", 3e6), row("fast 2t", 1e7)];
        let t = speed_table(&rows);
        assert!(
            t.contains("| 10k | hh | rest | 2.000 | 3.000 | 10.000 | 1.50x | 5.00x |"),
            "{t}"
        );
        let d = details(&rows);
        assert!(
            d.contains("| 10k hh rest | fast 2t | 10.000 | 5.00x | 20.000 | 3 (0) | 80 |"),
            "{d}"
        );
        assert!(csv(&rows)
            .lines()
            .nth(3)
            .unwrap()
            .starts_with("10k,hh,rest,fast 2t,1,1.000000e7"));
    }
}
