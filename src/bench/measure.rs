//! One timed run of a deck as a separate process (regolith or Debian's `liggghts`), and the
//! figures read back from its screen output: LIGGGHTS's end-of-run statistics (loop time,
//! time split, neighbour-list builds), which both programs print, and the peak memory the
//! operating system measured.

use std::io::Read;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};

use crate::tool_error::ToolError;

/// A program to time: an executable with its fixed arguments and environment.
#[derive(Debug, Clone, PartialEq)]
pub struct Program {
    /// Label in reports (e.g. `liggghts`, `exact`, `fast 2t`).
    pub label: String,
    /// The executable.
    pub exe: PathBuf,
    /// Arguments before `-in` (e.g. `-sf fast -pk fast 2`).
    pub args: Vec<String>,
    /// Environment variables set for the run.
    pub env: Vec<(String, String)>,
    /// Threads it runs on (for reports).
    pub threads: usize,
}

/// The figures of one run (summed over the deck's runs).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Measure {
    /// Loop time (s).
    pub seconds: f64,
    /// Steps.
    pub steps: u64,
    /// Atom-steps (atoms at the end of each run times its steps).
    pub atom_steps: f64,
    /// Atoms at the end of the last run.
    pub atoms: u64,
    /// Time in pair forces, neighbour lists, communication, output (s).
    pub split: [f64; 4],
    /// Neighbour-list builds.
    pub builds: u64,
    /// Dangerous builds.
    pub dangerous: u64,
    /// Pairs in contact at the last step (regolith only).
    pub contacts: Option<u64>,
    /// Peak resident memory of the process (bytes), where measured.
    pub peak_bytes: Option<u64>,
}

impl Measure {
    /// Particle-steps per second.
    pub fn rate(&self) -> f64 {
        self.atom_steps / self.seconds.max(1e-12)
    }
}

fn number_after<'a>(line: &'a str, prefix: &str) -> Option<&'a str> {
    line.strip_prefix(prefix)?.split_whitespace().next()
}

/// Read the end-of-run statistics of every run in a screen output; None without a
/// `Loop time` line.
pub fn parse_output(text: &str) -> Option<Measure> {
    let mut m = Measure::default();
    let mut found = false;
    for line in text.lines() {
        if line.starts_with("Loop time of ") {
            // Loop time of T on P procs for N steps with M atoms
            let w: Vec<&str> = line.split_whitespace().collect();
            let seconds: f64 = w.get(3)?.parse().ok()?;
            let steps: u64 = w.get(8)?.parse().ok()?;
            let atoms: u64 = w.get(11)?.trim_end_matches(',').parse().ok()?;
            m.seconds += seconds;
            m.steps += steps;
            m.atom_steps += atoms as f64 * steps as f64;
            m.atoms = atoms;
            found = true;
            continue;
        }
        for (k, name) in ["Pair  time", "Neigh time", "Comm  time", "Outpt time"]
            .iter()
            .enumerate()
        {
            if let Some(v) = number_after(line, &format!("{name} (%) = ")) {
                m.split[k] += v.parse::<f64>().unwrap_or(0.0);
            }
        }
        if let Some(v) = number_after(line, "Neighbor list builds = ") {
            m.builds += v.parse::<u64>().unwrap_or(0);
        }
        if let Some(v) = number_after(line, "Dangerous builds = ") {
            m.dangerous += v.parse::<u64>().unwrap_or(0);
        }
        if let Some(v) = number_after(line, "Contacts (touching pairs at the last step) = ") {
            m.contacts = v.parse().ok();
        }
    }
    found.then_some(m)
}

/// Run `program -in deck -log none [-var ...]` in `dir` and read its figures.
pub fn run_once(
    program: &Program,
    dir: &Path,
    deck: &str,
    vars: &[(String, String)],
) -> Result<Measure, ToolError> {
    let mut cmd = Command::new(&program.exe);
    cmd.args(&program.args)
        .args(["-in", deck, "-log", "none"])
        .current_dir(dir)
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::null());
    for (k, v) in vars {
        cmd.args(["-var", k, v]);
    }
    for (k, v) in &program.env {
        cmd.env(k, v);
    }
    let mut child = cmd
        .spawn()
        .map_err(|e| ToolError::Run(format!("cannot start {}: {e}", program.exe.display())))?;
    let mut text = String::new();
    if let Some(mut out) = child.stdout.take() {
        let mut bytes = Vec::new();
        out.read_to_end(&mut bytes)
            .map_err(|e| ToolError::Run(e.to_string()))?;
        text = String::from_utf8_lossy(&bytes).into_owned();
    }
    let (ok, peak) = wait_with_peak(child)?;
    if !ok {
        let tail: Vec<&str> = text.lines().rev().take(5).collect();
        return Err(ToolError::Run(format!(
            "{} ({}) failed: {}",
            program.label,
            program.exe.display(),
            tail.into_iter().rev().collect::<Vec<_>>().join("\n")
        )));
    }
    let mut m = parse_output(&text).ok_or_else(|| {
        ToolError::Content(format!(
            "{}: no 'Loop time' line in its output",
            program.exe.display()
        ))
    })?;
    m.peak_bytes = peak;
    Ok(m)
}

/// Wait for the process; (exited successfully, peak resident bytes).
#[cfg(target_os = "linux")]
fn wait_with_peak(child: std::process::Child) -> Result<(bool, Option<u64>), ToolError> {
    let pid = child.id() as libc::pid_t;
    let mut status = 0;
    // SAFETY: rusage is plain data; wait4 reaps our own child, which `Child` never waits
    // for afterwards (it is dropped without waiting).
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let r = unsafe { libc::wait4(pid, &mut status, 0, &mut usage) };
    drop(child);
    if r < 0 {
        return Err(ToolError::Run(format!("waiting for process {pid} failed")));
    }
    let ok = libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0;
    Ok((ok, Some(usage.ru_maxrss as u64 * 1024)))
}

#[cfg(not(target_os = "linux"))]
fn wait_with_peak(mut child: std::process::Child) -> Result<(bool, Option<u64>), ToolError> {
    let s = child.wait().map_err(|e| ToolError::Run(e.to_string()))?;
    Ok((s.success(), None))
}

/// The median of `v` (NaN for none).
pub fn median(v: &[f64]) -> f64 {
    if v.is_empty() {
        return f64::NAN;
    }
    let mut s = v.to_vec();
    s.sort_by(f64::total_cmp);
    let n = s.len();
    if n % 2 == 1 {
        s[n / 2]
    } else {
        0.5 * (s[n / 2 - 1] + s[n / 2])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn statistics_of_both_programs_are_read() {
        let text = "x\nLoop time of 2.5 on 1 procs for 100 steps with 10 atoms\n\n\
            Pair  time (%) = 2 (80)\nNeigh time (%) = 0.25 (10)\nComm  time (%) = 0 (0)\n\
            Outpt time (%) = 0.05 (2)\nOther time (%) = 0.2 (8)\n\
            Neighbor list builds = 7\nDangerous builds = 1\n\
            Contacts (touching pairs at the last step) = 12\n\
            Loop time of 0.5 on 1 procs for 50 steps with 20 atoms, finish time Sun Nov 22\n\
            Neighbor list builds = 3\n";
        let m = parse_output(text).unwrap();
        assert_eq!(m.steps, 150);
        assert!((m.seconds - 3.0).abs() < 1e-12);
        assert!((m.atom_steps - 2000.0).abs() < 1e-9);
        assert_eq!(m.atoms, 20);
        assert_eq!(m.split, [2.0, 0.25, 0.0, 0.05]);
        assert_eq!((m.builds, m.dangerous, m.contacts), (10, 1, Some(12)));
        assert!((m.rate() - 2000.0 / 3.0).abs() < 1e-9);
        assert!(parse_output("no runs").is_none());
        assert_eq!(median(&[3.0, 1.0, 2.0]), 2.0);
        assert_eq!(median(&[4.0, 1.0, 2.0, 3.0]), 2.5);
    }
}
