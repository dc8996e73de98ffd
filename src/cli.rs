//! The command line: LIGGGHTS's single-dash flags (`-in`, `-var`, `-log`, ...) exactly as
//! `liggghts` reads them, plus regolith's own subcommands (`run`, `check`, ...).

use crate::commands::suggest::did_you_mean;

/// Settings from LIGGGHTS-style flags.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct DeckOptions {
    /// `-in FILE`: the script; standard input when absent.
    pub input: Option<String>,
    /// `-var NAME V1 V2 ...`, in order.
    pub vars: Vec<(String, Vec<String>)>,
    /// `-log FILE|none`; `log.liggghts` when absent.
    pub log: Option<String>,
    /// `-screen FILE|none`; standard output when absent.
    pub screen: Option<String>,
    /// `-echo none|screen|log|both`.
    pub echo: Option<String>,
    /// `-nocite`: accepted; regolith writes no citation file anyway.
    pub nocite: bool,
    /// `-seedtolerant`: accept random seeds that are not large primes.
    pub seed_tolerant: bool,
    /// regolith extension `-zero_restitution`: allow coefficients of restitution down to 0.
    pub zero_restitution: bool,
    /// `-restart RESTART DATAFILE`: convert a restart file to a data file and exit.
    pub restart_to_data: Option<(String, String)>,
    /// `-suffix fast` / `-sf fast`: the fast engine path (LAMMPS's accelerator switch).
    pub fast: bool,
    /// `-package fast N` / `-pk fast N`: threads of the engine (LAMMPS's package switch).
    pub threads: Option<usize>,
    /// `-help`.
    pub help: bool,
    /// The MPI ranks this process is one of (set at start, not a flag).
    pub ranks: crate::util::comm::Ranks,
}

/// A command-line problem (exit status 2).
#[derive(Debug, Clone, PartialEq)]
pub struct UsageError {
    /// What is wrong, in LIGGGHTS's words where it has them.
    pub message: String,
    /// Nearest valid flag or what was expected.
    pub help: Option<String>,
}

/// The flags `liggghts` 3.8.0 accepts (long and short forms).
pub const FLAGS: &[&str] = &[
    "-echo",
    "-e",
    "-in",
    "-i",
    "-help",
    "-h",
    "-log",
    "-l",
    "-nocite",
    "-nc",
    "-partition",
    "-p",
    "-plog",
    "-pl",
    "-pscreen",
    "-ps",
    "-reorder",
    "-ro",
    "-restart",
    "-r",
    "-restart_offset",
    "-roff",
    "-screen",
    "-sc",
    "-var",
    "-v",
    "-suffix",
    "-sf",
    "-package",
    "-pk",
    "-seedtolerant",
    "-st",
    "-cuda",
    "-c",
    "-domain",
    "-uid",
    "-thermo",
    "-wb",
    "-zero_restitution",
];

fn usage(message: impl Into<String>, help: Option<String>) -> UsageError {
    UsageError {
        message: message.into(),
        help,
    }
}

/// Parse LIGGGHTS-style flags (everything after the program name or subcommand).
pub fn parse_deck_flags(args: &[String]) -> Result<DeckOptions, UsageError> {
    let mut o = DeckOptions::default();
    let mut i = 0;
    while i < args.len() {
        i = deck_flag(args, i, &mut o)?;
    }
    Ok(o)
}

/// The error for `flag` given without `what` it takes.
fn missing(flag: &str, what: &str) -> UsageError {
    usage(
        "Invalid command-line argument",
        Some(format!("{flag} needs {what}")),
    )
}

/// Read the flag `args[i]` and its values into `o`: the index of the next flag.
fn deck_flag(args: &[String], i: usize, o: &mut DeckOptions) -> Result<usize, UsageError> {
    let flag = args[i].as_str();
    let value = |n: usize| args.get(i + n).cloned();
    // the words the flag takes, itself included
    let words = match flag {
        "-in" | "-i" => {
            o.input = Some(value(1).ok_or_else(|| missing(flag, "a file name"))?);
            2
        }
        "-log" | "-l" => {
            o.log = Some(value(1).ok_or_else(|| missing(flag, "a file name or none"))?);
            2
        }
        "-screen" | "-sc" => {
            o.screen = Some(value(1).ok_or_else(|| missing(flag, "a file name or none"))?);
            2
        }
        "-echo" | "-e" => {
            o.echo = Some(echo_style(flag, value(1))?);
            2
        }
        "-var" | "-v" => return command_line_variable(args, i, o),
        "-nocite" | "-nc" => {
            o.nocite = true;
            1
        }
        "-seedtolerant" | "-st" => {
            o.seed_tolerant = true;
            1
        }
        "-zero_restitution" => {
            o.zero_restitution = true;
            1
        }
        "-help" | "-h" => {
            o.help = true;
            1
        }
        "-suffix" | "-sf" => {
            let v = value(1).ok_or_else(|| missing(flag, "an accelerator style (fast)"))?;
            o.fast =
                parse_suffix(&v).map_err(|m| usage(m.to_string(), Some(SUFFIX_HELP.into())))?;
            2
        }
        "-package" | "-pk" => {
            let style = value(1).ok_or_else(|| missing(flag, "fast and a thread count"))?;
            let n = value(2).ok_or_else(|| missing(flag, "fast and a thread count"))?;
            o.threads = Some(
                parse_package(&style, &n)
                    .map_err(|m| usage(m.to_string(), Some(PACKAGE_HELP.into())))?,
            );
            3
        }
        "-restart" | "-r" => {
            let (Some(r), Some(d)) = (value(1), value(2)) else {
                return Err(missing(flag, "a restart file and a data file"));
            };
            o.restart_to_data = Some((r, d));
            3
        }
        "-partition" | "-p" => return one_partition(args, i),
        _ => return Err(unknown_flag(flag)),
    };
    Ok(i + words)
}

/// The value of `-echo none|screen|log|both`.
fn echo_style(flag: &str, value: Option<String>) -> Result<String, UsageError> {
    let v = value.ok_or_else(|| missing(flag, "none, screen, log or both"))?;
    if !["none", "screen", "log", "both"].contains(&v.as_str()) {
        return Err(usage(
            "Illegal echo command",
            Some(format!("-echo takes none, screen, log or both, not '{v}'")),
        ));
    }
    Ok(v)
}

/// `-var NAME VALUE ...` at `args[i]` into `o`: the index of the next flag. As liggghts: the
/// name and first value are taken whatever they look like, further values run until the
/// next word starting with '-'.
fn command_line_variable(
    args: &[String],
    i: usize,
    o: &mut DeckOptions,
) -> Result<usize, UsageError> {
    let (Some(name), Some(first)) = (args.get(i + 1).cloned(), args.get(i + 2).cloned()) else {
        return Err(missing(&args[i], "a name and at least one value"));
    };
    let mut values = vec![first];
    let mut j = i + 3;
    while j < args.len() && !args[j].starts_with('-') {
        values.push(args[j].clone());
        j += 1;
    }
    o.vars.push((name, values));
    Ok(j)
}

/// `-partition 1` at `args[i]` (the only partitioning regolith runs): the index of the next
/// flag.
fn one_partition(args: &[String], i: usize) -> Result<usize, UsageError> {
    let flag = args[i].as_str();
    let mut j = i + 1;
    let mut worlds = Vec::new();
    while j < args.len() && !args[j].starts_with('-') {
        worlds.push(args[j].clone());
        j += 1;
    }
    if worlds.is_empty() {
        return Err(missing(flag, "partition sizes"));
    }
    if worlds != ["1"] {
        return Err(usage(
            format!("{flag} {}: not supported yet", worlds.join(" ")),
            Some("regolith runs one partition; parallelism comes from threads".into()),
        ));
    }
    Ok(j)
}

/// The error for `flag`: a LIGGGHTS flag regolith does not take yet, or no flag at all (the
/// nearest flags, or how to run a deck named so).
fn unknown_flag(flag: &str) -> UsageError {
    if FLAGS.contains(&flag) {
        return usage(
            format!("{flag}: not supported yet"),
            Some("supported: -in -var -log -screen -echo -nocite -seedtolerant -partition 1 -help -restart -suffix fast -package fast N".into()),
        );
    }
    let help = did_you_mean(flag, FLAGS).or_else(|| {
        (!flag.starts_with('-')).then(|| format!("to run a deck, write: regolith -in {flag}"))
    });
    usage(format!("Invalid command-line argument: {flag}"), help)
}

pub use crate::engine::accel::{parse_package, parse_suffix, PACKAGE_HELP, SUFFIX_HELP};

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(s: &str) -> Result<DeckOptions, UsageError> {
        let v: Vec<String> = s.split_whitespace().map(str::to_string).collect();
        parse_deck_flags(&v)
    }

    #[test]
    fn liggghts_flags() {
        let o = parse("-in in.deck -var v 10 -v list a b c -log log.txt -e screen -nc").unwrap();
        assert_eq!(o.input.as_deref(), Some("in.deck"));
        assert_eq!(
            o.vars,
            vec![
                ("v".to_string(), vec!["10".to_string()]),
                ("list".to_string(), vec!["a".into(), "b".into(), "c".into()])
            ]
        );
        assert_eq!(o.log.as_deref(), Some("log.txt"));
        assert_eq!(o.echo.as_deref(), Some("screen"));
        assert!(o.nocite);
    }

    #[test]
    fn negative_first_value_is_kept() {
        let o = parse("-var x -5 -in a").unwrap();
        assert_eq!(o.vars[0].1, vec!["-5".to_string()]);
        assert_eq!(o.input.as_deref(), Some("a"));
    }

    #[test]
    fn bad_flags_explain_themselves() {
        let e = parse("-inn deck").unwrap_err();
        assert!(e.message.contains("-inn"));
        assert!(e.help.unwrap().contains("-in"));
        assert!(parse("-var x").is_err());
        assert!(parse("-in").is_err());
        assert!(parse("-echo loud").is_err());
        assert!(parse("-p 2 2")
            .unwrap_err()
            .message
            .contains("not supported yet"));
        assert!(parse("-p 1").is_ok());
    }

    #[test]
    fn accelerator_switches() {
        let o = parse("-sf fast -pk fast 3 -in a").unwrap();
        assert!(o.fast);
        assert_eq!(o.threads, Some(3));
        assert!(parse("-suffix off").is_ok_and(|o| !o.fast));
        assert!(parse("-sf omp")
            .unwrap_err()
            .message
            .contains("not supported"));
        assert!(parse("-pk fast 0").is_err());
        assert!(parse("-pk omp 2").is_err());
    }
}
