//! The command line behaves like `liggghts`: flags, exit statuses, where output goes, and
//! errors that name file, line and word.

use std::path::PathBuf;
use std::process::{Command, Output};

fn scratch(name: &str) -> PathBuf {
    let dir = std::path::Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join(format!("regolith-cli-{}-{name}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn regolith(dir: &PathBuf, args: &[&str], stdin: Option<&str>) -> Output {
    use std::io::Write;
    let mut child = Command::new(env!("CARGO_BIN_EXE_regolith"))
        .args(args)
        .current_dir(dir)
        .stdin(std::process::Stdio::piped())
        .stdout(std::process::Stdio::piped())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .expect("regolith starts");
    if let Some(text) = stdin {
        child
            .stdin
            .take()
            .unwrap()
            .write_all(text.as_bytes())
            .unwrap();
    } else {
        drop(child.stdin.take());
    }
    child.wait_with_output().unwrap()
}

fn text(b: &[u8]) -> String {
    String::from_utf8_lossy(b).into_owned()
}

#[test]
fn runs_deck_with_var_and_writes_default_log() {
    let dir = scratch("var");
    std::fs::write(
        dir.join("in.t"),
        "variable v index 1\nprint \"v=${v} half=$(v_v/2)\"\n",
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-var", "v", "10"], None);
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    assert!(stdout.starts_with("regolith "), "{stdout}");
    assert_eq!(stdout.lines().nth(1), Some("v=10 half=5"));
    // the log echoes input lines and the substituted line, as LIGGGHTS's log does
    let log = std::fs::read_to_string(dir.join("log.liggghts")).unwrap();
    let lines: Vec<&str> = log.lines().collect();
    assert_eq!(lines[1], "variable v index 1");
    assert_eq!(lines[2], "print \"v=${v} half=$(v_v/2)\"");
    assert_eq!(lines[3], "v=10 half=5");
}

#[test]
fn reads_standard_input_and_honours_log_none_and_echo_screen() {
    let dir = scratch("stdin");
    let out = regolith(
        &dir,
        &["-log", "none", "-echo", "screen"],
        Some("print hello\n"),
    );
    assert!(out.status.success());
    let stdout = text(&out.stdout);
    assert_eq!(
        stdout.lines().skip(1).collect::<Vec<_>>(),
        ["print hello", "hello"]
    );
    assert!(!dir.join("log.liggghts").exists());
}

#[test]
fn unknown_command_fails_before_anything_runs() {
    let dir = scratch("unknown");
    std::fs::write(
        dir.join("in.t"),
        "print first\n\nfix 1 all insert/strem foo\n",
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"], None);
    assert_eq!(out.status.code(), Some(1));
    let stdout = text(&out.stdout);
    assert!(!stdout.contains("first"), "nothing may run: {stdout}");
    let err = text(&out.stderr);
    assert!(err.contains("ERROR: Invalid fix style"), "{err}");
    assert!(err.contains("--> in.t:3"), "{err}");
    assert!(err.contains("insert/stream"), "suggestion missing: {err}");
    assert!(err.contains("^^^^^^^^^^^^"), "caret missing: {err}");
}

#[test]
fn unsupported_feature_exits_3_and_check_lists_every_item() {
    let dir = scratch("unsupported");
    std::fs::write(
        dir.join("in.t"),
        "atom_style granular\n# comment\nregion b block 0 1 0 1 0 1\ncreate_box 1 b\nfix ins all multisphere/break\npair_style gran model hertz tangential history cohesion washino/capillary/viscous\ncompute s all centro/atom 12\n",
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"], None);
    assert_eq!(out.status.code(), Some(3));
    let out = regolith(&dir, &["check", "in.t"], None);
    assert_eq!(out.status.code(), Some(3));
    assert_eq!(
        text(&out.stdout),
        "in.t:5: fix multisphere/break: not supported yet\n\
         in.t:6: pair_style gran cohesion washino/capillary/viscous: not supported yet\n\
         in.t:7: compute centro/atom: not supported yet\n"
    );
}

#[test]
fn usage_errors_exit_2_with_suggestion() {
    let dir = scratch("usage");
    let out = regolith(&dir, &["-inn", "x"], None);
    assert_eq!(out.status.code(), Some(2));
    assert!(
        text(&out.stderr).contains("did you mean '-in'"),
        "{}",
        text(&out.stderr)
    );
    let out = regolith(&dir, &["-in", "missing.deck", "-log", "none"], None);
    assert_eq!(out.status.code(), Some(1));
    assert!(text(&out.stderr).contains("Cannot open input script missing.deck"));
}

#[test]
fn check_follows_loops_once_and_includes() {
    let dir = scratch("loops");
    std::fs::write(dir.join("in.inc"), "compute s all centro/atom 12\n").unwrap();
    std::fs::write(
        dir.join("in.t"),
        "region b block 0 1 0 1 0 1\ncreate_box 1 b\nvariable a loop 1000\nlabel top\ninclude in.inc\nnext a\njump SELF top\nprint done\n",
    )
    .unwrap();
    let out = regolith(&dir, &["check", "in.t"], None);
    assert_eq!(
        text(&out.stdout),
        "in.inc:1: compute centro/atom: not supported yet
"
    );
    assert_eq!(out.status.code(), Some(3));
}

#[test]
fn check_does_not_blame_follow_on_effects_of_unsupported_commands() {
    // the insertion fix is skipped in a dry run, so there are no atoms and no fix to remove:
    // only the unsupported command itself is reported, yet later misspellings still are
    let dir = scratch("diverged");
    std::fs::write(
        dir.join("in.t"),
        "region b block 0 1 0 1 0 1\ncreate_box 1 b\nfix ins all multisphere/break\nunfix ins\n\
         velocity all set 0 0 0\nfix g all gravty 9.81 vector 0 0 -1\n",
    )
    .unwrap();
    let out = regolith(&dir, &["check", "in.t"], None);
    let stdout = text(&out.stdout);
    assert_eq!(stdout.lines().count(), 2, "{stdout}");
    assert!(
        stdout.starts_with("in.t:3: fix multisphere/break: not supported yet\n"),
        "{stdout}"
    );
    assert!(
        stdout.contains("in.t:6: Invalid fix style: \"gravty\" (did you mean 'gravity'?)"),
        "{stdout}"
    );
    assert_eq!(out.status.code(), Some(1));
}

#[test]
fn blow_up_guard_stops_with_step_atoms_and_cause() {
    // stiff spheres driven together with a time step far beyond the Hertz time
    let dir = scratch("blowup");
    std::fs::write(
        dir.join("in.t"),
        "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n\
         communicate single vel yes\nunits si\nregion b block -1 1 -1 1 -1 1 units box\n\
         create_box 1 b\nneighbor 0.01 bin\nneigh_modify delay 0\nhard_particles yes\n\
         fix m1 all property/global youngsModulus peratomtype 1e11\n\
         fix m2 all property/global poissonsRatio peratomtype 0.3\n\
         fix m3 all property/global coefficientRestitution peratomtypepair 1 0.9\n\
         fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
         pair_style gran model hertz tangential history\npair_coeff * *\n\
         create_atoms 1 single -0.04 0 0 units box\ncreate_atoms 1 single 0.04 0 0 units box\n\
         set group all diameter 0.05 density 7800\nset atom 1 vx 5\nset atom 2 vx -5\n\
         fix i all nve/sphere\ntimestep 1e-3\nrun 50\n",
    )
    .unwrap();
    let out = regolith(&dir, &["-in", "in.t", "-log", "none"], None);
    assert_eq!(out.status.code(), Some(1));
    let err = text(&out.stderr);
    assert!(err.contains("blow-up at step"), "{err}");
    assert!(
        err.contains("atoms 1 and 2") || err.contains("atom 1") || err.contains("atom 2"),
        "{err}"
    );
    assert!(err.contains("time step"), "{err}");
}

#[test]
fn zero_restitution_needs_the_extension_flag_and_then_kills_the_rebound() {
    let dir = scratch("zero_e");
    std::fs::write(
        dir.join("in.t"),
        "atom_style granular\natom_modify map array\nboundary f f f\nnewton off\n\
         communicate single vel yes\nunits si\nregion b block -1 1 -1 1 -1 1 units box\n\
         create_box 1 b\nneighbor 0.001 bin\nneigh_modify delay 0\n\
         fix m1 all property/global youngsModulus peratomtype 5e6\n\
         fix m2 all property/global poissonsRatio peratomtype 0.2\n\
         fix m3 all property/global coefficientRestitution peratomtypepair 1 0.0\n\
         fix m4 all property/global coefficientFriction peratomtypepair 1 0.5\n\
         pair_style gran model hertz tangential history\npair_coeff * *\n\
         create_atoms 1 single -0.0101 0 0 units box\ncreate_atoms 1 single 0.0101 0 0 units box\n\
         set group all diameter 0.02 density 2500\nset atom 1 vx 0.5\nset atom 2 vx -0.5\n\
         fix i all nve/sphere\ntimestep 1e-6\nrun 20000\n\
         print \"rebound $(vx[2]-vx[1])\"\n",
    )
    .unwrap();
    let refused = regolith(&dir, &["-in", "in.t", "-log", "none"], None);
    assert_eq!(refused.status.code(), Some(1));
    assert!(
        text(&refused.stderr).contains("-zero_restitution"),
        "{}",
        text(&refused.stderr)
    );
    let out = regolith(
        &dir,
        &["-in", "in.t", "-log", "none", "-zero_restitution"],
        None,
    );
    assert!(out.status.success(), "{}", text(&out.stderr));
    let stdout = text(&out.stdout);
    let line = stdout
        .lines()
        .find(|l| l.starts_with("rebound "))
        .expect("rebound printed");
    let rebound: f64 = line[8..].trim().parse().unwrap();
    // approach speed 1 m/s; critically damped contact: separation speed nearly zero
    assert!((0.0..0.05).contains(&rebound), "{line}");
}

#[test]
fn check_handles_lattice_regions_and_script_commands_in_unknown_branches() {
    let dir = scratch("lattice_if");
    std::fs::write(
        dir.join("in.t"),
        "atom_style granular\nlattice sc 0.002\nregion b block 0 10 0 10 0 10 units lattice\n\
         create_box 1 b\nvariable s equal step\nlabel again\n\
         if \"${s} > 5\" then \"variable s delete\" \"jump SELF done\"\nlabel done\n\
         compute r all centro/atom 12\n",
    )
    .unwrap();
    let out = regolith(&dir, &["check", "in.t"], None);
    // only the genuinely unsupported compute: the lattice region is fine, and the script
    // commands inside the branch a dry run cannot decide are the interpreter's own
    assert_eq!(
        text(&out.stdout),
        "in.t:9: compute centro/atom: not supported yet\n"
    );
    assert_eq!(out.status.code(), Some(3));
}

/// Issue 16: `check` and the run header state the time-step margin. The trade study's
/// collision (R 1.25 mm, density 2500, E 5e6, nu 0.2, both spheres at 1 m/s) by hand:
/// G = E / 2.4 = 2.08333e6 Pa, Rayleigh time pi R sqrt(rho / G) / (0.1631 nu + 0.8766)
/// = 1.360350e-4 / 0.90922 = 1.49617e-4 s; dt = 0.0067 of it (0.67 %). Hertz contact time at
/// the impact speed 2 m/s: m* = 1.022654e-5 kg, R* = 6.25e-4 m, Y* = 2.604167e6 Pa,
/// 2.87 (m*^2 / (R* Y*^2 v))^(1/5) = 2.99312e-4 s; dt is 0.335 % of it. With E / 10 both
/// times grow: the Rayleigh time by sqrt(10) (4.73131e-4 s), the Hertz time by 10^(2/5)
/// (7.51837e-4 s).
#[test]
fn check_and_run_state_the_time_step_margin() {
    let dir = scratch("margin");
    let deck = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/trade/in.collision");
    let out = regolith(&dir, &["check", deck], None);
    assert_eq!(out.status.code(), Some(0));
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains(
            "type 1: radius 0.00125, density 2500, E 5e+06, nu 0.2: Rayleigh time 0.000149617 s\n"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains("types 1-1: dt is 0.67 % of the Rayleigh time and 0.33 % of the Hertz contact time 0.000299312 s at impact speed 2\n"),
        "{stdout}"
    );
    assert!(
        stdout.contains("impact speed: twice the fastest expected speed 1 (two particles head-on), from the fastest particle now"),
        "{stdout}"
    );
    let out = regolith(
        &dir,
        &["check", deck, "-var", "frac", "0.2", "-var", "soften", "10"],
        None,
    );
    let stdout = text(&out.stdout);
    assert!(stdout.contains("Rayleigh time 0.000473131 s\n"), "{stdout}");
    assert!(
        stdout.contains("types 1-1: dt is 20.0 % of the Rayleigh time and 12.6 % of the Hertz contact time 0.000751837 s"),
        "{stdout}"
    );
    assert!(!stdout.contains("WARNING: types"), "{stdout}");
    // past 40 % of the Rayleigh time the margin warns
    let out = regolith(&dir, &["check", deck, "-var", "frac", "0.5"], None);
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains("types 1-1: dt is 50.0 % of the Rayleigh time"),
        "{stdout}"
    );
    assert!(
        stdout.contains("WARNING: types 1-1: dt is above 40.0 % of the Rayleigh time"),
        "{stdout}"
    );
    // a run says it on standard error: the screen and log keep LIGGGHTS's lines
    let out = regolith(&dir, &["-in", deck, "-log", "none"], None);
    assert_eq!(out.status.code(), Some(0));
    let stderr = text(&out.stderr);
    assert!(
        stderr.starts_with("Time-step margin (regolith; dt = 1.00244e-06 s):\n"),
        "{stderr}"
    );
    assert!(
        stderr.contains("0.33 % of the Hertz contact time"),
        "{stderr}"
    );
    assert!(!text(&out.stdout).contains("margin"));
    let _ = std::fs::remove_dir_all(&dir);
}

/// Issue 16: next to the margin, `check` and the run header quote the trade study
/// (docs/trade_margin.csv, written by examples/trade/study.sh and compiled in): the errors it
/// measured at the deck's dt / Rayleigh time (at the study's next step up: 1 % for the
/// collision's 0.67 %), the largest step that keeps each observable within 1 %, and the
/// fastest setting that keeps all of them within 1 % (the collision's contact time limits it
/// to 5 %: 7.5x the deck's step). The bed and the channel are statistical (their run-to-run
/// spread is in the table): quoted with it, within when within three spreads, and left out
/// of the fastest setting.
#[test]
fn check_and_run_quote_the_trade_study_at_the_decks_margin() {
    let dir = scratch("trade_margin");
    let deck = concat!(env!("CARGO_MANIFEST_DIR"), "/examples/trade/in.collision");
    let out = regolith(&dir, &["check", deck], None);
    assert_eq!(out.status.code(), Some(0));
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains(
            "  trade study (docs/trade.md): measured errors at 0.67 % of the Rayleigh time \
             (the study's 1.00 % column, exact path):\n    restitution 0.17 %, contact time 0.11 %, \
             energy drift at e = 1 2.7e-6, sliding time < 0.001 %, rolling speed < 0.001 %, \
             wave speed (weak impact) "
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains(
            "bed height 1.1 % (run-to-run spread 0.86 %), bed packing fraction 1.3 % (run-to-run \
             spread 1.9 %), channel front speed 1.2 % (run-to-run spread 2.1 %), channel surface \
             rise 0.22 % (run-to-run spread 0.43 %)\n"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains(
            "  within 1.00 %, dt up to (of the Rayleigh time): restitution 10.0 %, contact time \
             5.00 %, energy drift at e = 1 20.0 %, sliding time 40.0 %, rolling speed 40.0 %, \
             wave speed (weak impact) 40.0 %, wave speed (strong impact) 40.0 %, bed height \
             1.00 % (statistical), bed packing fraction 1.00 % (statistical), channel front \
             speed 20.0 % (statistical), channel surface rise 1.00 % (statistical)\n"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains(
            "  fastest setting within 1.00 % for all of them (the statistical ones aside): dt = \
             5.00 % of the Rayleigh time (7.5x this deck's), -sf fast (the study's fast-path \
             errors are the exact path's)\n"
        ),
        "{stdout}"
    );
    // at 20 % the study's own column; past 40 % beyond it
    let out = regolith(&dir, &["check", deck, "-var", "frac", "0.2"], None);
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains(
            "(the study's 20.0 % column, exact path):\n    restitution 1.4 %, contact time 3.7 %,"
        ),
        "{stdout}"
    );
    assert!(
        stdout.contains("dt = 5.00 % of the Rayleigh time, -sf fast"),
        "{stdout}"
    );
    let out = regolith(&dir, &["check", deck, "-var", "frac", "0.5"], None);
    let stdout = text(&out.stdout);
    assert!(
        stdout.contains("50.0 % of the Rayleigh time is beyond the study's largest step; errors at 40.0 % (exact path):\n    restitution 14 %, contact time 9.9 %,"),
        "{stdout}"
    );
    // the run header says the same on standard error
    let out = regolith(&dir, &["-in", deck, "-log", "none"], None);
    assert_eq!(out.status.code(), Some(0));
    assert!(
        text(&out.stderr).contains(
            "fastest setting within 1.00 % for all of them (the statistical ones aside): dt = 5.00 %"
        ),
        "{}",
        text(&out.stderr)
    );
    assert!(!text(&out.stdout).contains("trade study"));
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn check_without_a_deck_is_a_usage_error_and_check_reads_minus_in() {
    let dir = scratch("check_flags_first");
    std::fs::write(
        dir.join("in.t"),
        "atom_style granular\nregion b block 0 1 0 1 0 1\ncreate_box 1 b\ncompute s all centro/atom 12\n",
    )
    .unwrap();
    // flags before the deck swallow it as -var values: nothing would be checked
    let out = regolith(&dir, &["check", "-var", "frac", "0.2", "in.t"], None);
    assert_eq!(out.status.code(), Some(2));
    assert!(text(&out.stderr).contains("no deck file given"));
    // -in names the deck, as for a run
    let out = regolith(&dir, &["check", "-var", "frac", "0.2", "-in", "in.t"], None);
    assert_eq!(out.status.code(), Some(3));
    assert_eq!(
        text(&out.stdout),
        "in.t:4: compute centro/atom: not supported yet\n"
    );
}
