//! `regolith bench`: time a scene in regolith (and, with `--liggghts`, in Debian's
//! LIGGGHTS, interleaved run by run) and report each run's loop time and the rate in
//! particle-steps per second. Timing is measured here, never asserted by tests.

use std::path::{Path, PathBuf};
use std::process::Command;

/// Built-in scenes: (name, deck text).
pub const SCENES: &[(&str, &str)] = &[
    ("settled_bed", include_str!("../benches/settled_bed/in.bed")),
    (
        "struck_chain",
        include_str!("../examples/struck_chain/in.struck_chain"),
    ),
];

/// One run's figures from its `Loop time of T on P procs for N steps with M atoms` lines.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Timing {
    /// Loop seconds summed over the deck's runs.
    pub seconds: f64,
    /// Steps summed over the runs.
    pub steps: u64,
    /// Atom-steps summed over the runs (atoms at the end of each run times its steps).
    pub atom_steps: f64,
}

/// Sum the `Loop time` lines of a run's screen output.
pub fn parse_loop_times(text: &str) -> Option<Timing> {
    let mut t = Timing {
        seconds: 0.0,
        steps: 0,
        atom_steps: 0.0,
    };
    let mut found = false;
    for line in text.lines().filter(|l| l.starts_with("Loop time of ")) {
        let w: Vec<&str> = line.split_whitespace().collect();
        // Loop time of T on P procs for N steps with M atoms
        let seconds: f64 = w.get(3)?.parse().ok()?;
        let steps: u64 = w.get(8)?.parse().ok()?;
        let atoms: f64 = w.get(11)?.trim_end_matches(',').parse().ok()?;
        t.seconds += seconds;
        t.steps += steps;
        t.atom_steps += atoms * steps as f64;
        found = true;
    }
    found.then_some(t)
}

/// Options of a benchmark.
#[derive(Debug, Clone)]
pub struct BenchOptions {
    /// A built-in scene name or a deck path.
    pub scene: String,
    /// Runs per program.
    pub repeat: usize,
    /// Also time Debian's `liggghts` on the same deck.
    pub liggghts: bool,
    /// `-var NAME VALUE` pairs passed to the deck.
    pub vars: Vec<(String, String)>,
}

fn run_once(
    program: &Path,
    dir: &Path,
    deck: &str,
    vars: &[(String, String)],
) -> Result<Timing, String> {
    let mut cmd = Command::new(program);
    cmd.args(["-in", deck, "-log", "none"]).current_dir(dir);
    for (k, v) in vars {
        cmd.args(["-var", k, v]);
    }
    let out = cmd
        .output()
        .map_err(|e| format!("cannot start {}: {e}", program.display()))?;
    let text = String::from_utf8_lossy(&out.stdout);
    if !out.status.success() {
        return Err(format!(
            "{} failed ({}): {}",
            program.display(),
            out.status,
            String::from_utf8_lossy(&out.stderr)
                .lines()
                .take(5)
                .collect::<Vec<_>>()
                .join("\n")
        ));
    }
    parse_loop_times(&text)
        .ok_or_else(|| format!("{}: no 'Loop time' line in its output", program.display()))
}

/// Run the benchmark; returns the report text.
pub fn bench(opts: &BenchOptions) -> Result<String, String> {
    let dir = std::env::temp_dir().join(format!("regolith-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let deck = match SCENES.iter().find(|(n, _)| *n == opts.scene) {
        Some((name, text)) => {
            let file = dir.join(format!("in.{name}"));
            std::fs::write(&file, text).map_err(|e| e.to_string())?;
            file
        }
        None => {
            let p = PathBuf::from(&opts.scene);
            if !p.is_file() {
                let names: Vec<&str> = SCENES.iter().map(|(n, _)| *n).collect();
                return Err(format!(
                    "{}: neither a deck file nor a built-in scene ({})",
                    opts.scene,
                    names.join(", ")
                ));
            }
            std::fs::canonicalize(&p).map_err(|e| e.to_string())?
        }
    };
    // decks with side files run from their own folder
    let workdir = if SCENES.iter().any(|(n, _)| *n == opts.scene) {
        dir.clone()
    } else {
        deck.parent()
            .map(Path::to_path_buf)
            .unwrap_or_else(|| dir.clone())
    };
    let deck_arg = deck.to_string_lossy().into_owned();
    let me = std::env::current_exe().map_err(|e| e.to_string())?;
    let mut programs = vec![("regolith", me)];
    if opts.liggghts {
        programs.push(("liggghts", PathBuf::from("liggghts")));
    }
    let mut report = format!(
        "scene {} ({} run(s) each{})\n{:<10} {:>4} {:>12} {:>10} {:>16}\n",
        opts.scene,
        opts.repeat,
        if opts.liggghts { ", interleaved" } else { "" },
        "program",
        "run",
        "loop s",
        "steps",
        "atom-steps/s"
    );
    let mut best: Vec<f64> = vec![f64::INFINITY; programs.len()];
    for r in 0..opts.repeat {
        for (k, (name, program)) in programs.iter().enumerate() {
            let t = run_once(program, &workdir, &deck_arg, &opts.vars)?;
            best[k] = best[k].min(t.seconds);
            report.push_str(&format!(
                "{:<10} {:>4} {:>12.3} {:>10} {:>16.4e}\n",
                name,
                r + 1,
                t.seconds,
                t.steps,
                t.atom_steps / t.seconds.max(1e-12)
            ));
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    if opts.liggghts {
        report.push_str(&format!(
            "fastest loop time: regolith {:.3} s, liggghts {:.3} s, ratio liggghts/regolith {:.2}\n",
            best[0],
            best[1],
            best[1] / best[0]
        ));
    } else {
        report.push_str(&format!("fastest loop time: regolith {:.3} s\n", best[0]));
    }
    Ok(report)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn loop_time_lines_add_up() {
        let text = "x\nLoop time of 2.5 on 1 procs for 100 steps with 10 atoms\n\nLoop time of 0.5 on 1 procs for 50 steps with 20 atoms, finish time Sun Nov 22\n";
        let t = parse_loop_times(text).unwrap();
        assert_eq!(t.steps, 150);
        assert!((t.seconds - 3.0).abs() < 1e-12);
        assert!((t.atom_steps - 2000.0).abs() < 1e-9);
        assert!(parse_loop_times("no runs").is_none());
    }
}
