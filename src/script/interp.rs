//! The script interpreter: reads logical lines from a stack of input files, echoes them,
//! substitutes variables, splits words and executes the script-level commands itself
//! (`variable`, `next`, `jump`, `label`, `if`, `include`, `print`, `log`, `echo`, `shell`,
//! `quit`, `clear`, `partition`); everything else goes to the command registry.

use std::collections::HashSet;
use std::io::Write;
use std::rc::Rc;

use crate::commands::{CommandLine, Engine};
use crate::error::{Diagnostic, Location, Severity};
use crate::lang::expr;
use crate::lang::line::{self, LexError, VarRef, Word};
use crate::lang::scope::Scope;
use crate::lang::system::{Mode, System};
use crate::lang::variables::{Value, Variables};
use crate::util::format;

pub use crate::io::output::Output;
pub use crate::lang::{SCRIPT_COMMANDS, UNKNOWN_VALUE};

/// How deeply `include` may nest input files.
pub const MAX_INCLUDE_DEPTH: usize = 64;

/// Lines a dry run executes while following loops as a real run would; past this, each jump
/// is followed once (every line still gets checked, every loop ends).
pub const CHECK_LINE_BUDGET: u64 = 20_000;

/// A script's text split into physical lines.
#[derive(Debug)]
pub struct Source {
    /// The name shown in diagnostics (as given by the user; `-` for standard input).
    pub name: String,
    /// Physical lines without their line terminators.
    pub lines: Vec<String>,
    /// True when the script came from standard input (`jump SELF` is then refused).
    pub from_stdin: bool,
}

impl Source {
    /// Split `text` into lines (a final line without newline counts).
    pub fn from_text(name: &str, text: &str, from_stdin: bool) -> Source {
        let lines = text.lines().map(str::to_string).collect();
        Source {
            name: name.to_string(),
            lines,
            from_stdin,
        }
    }
}

struct Frame {
    source: Rc<Source>,
    pos: usize,
}

/// Runs (or checks) a deck.
pub struct Interpreter {
    /// Files, directory and environment as the deck sees them.
    pub sys: System,
    /// The deck's variables.
    pub vars: Variables,
    /// Screen and log.
    pub out: Output,
    /// Everything below the script language.
    pub engine: Engine,
    /// Problems found in check mode (run mode stops at the first one instead).
    pub diagnostics: Vec<Diagnostic>,
    frames: Vec<Frame>,
    label: Option<String>,
    jump_skip: bool,
    if_depth: usize,
    quit: bool,
    uncertain: bool,
    fired_jumps: HashSet<(String, usize)>,
    checked_lines: u64,
    location: Location,
    text: String,
}

fn lex_error(e: LexError, text: &str) -> Diagnostic {
    Diagnostic::error(e.message).with_source(text, Some(e.span))
}

impl Interpreter {
    /// A fresh interpreter.
    pub fn new(mode: Mode, out: Output) -> Interpreter {
        Interpreter {
            sys: System::new(mode),
            vars: Variables::default(),
            out,
            engine: Engine::new(),
            diagnostics: Vec::new(),
            frames: Vec::new(),
            label: None,
            jump_skip: false,
            if_depth: 0,
            quit: false,
            uncertain: false,
            fired_jumps: HashSet::new(),
            checked_lines: 0,
            location: Location {
                file: String::new(),
                line: 0,
            },
            text: String::new(),
        }
    }

    /// True once a `quit` command ended the script.
    pub fn quit_requested(&self) -> bool {
        self.quit
    }

    /// Run or check mode.
    pub fn mode(&self) -> Mode {
        self.sys.mode
    }

    /// `-var NAME values...` from the command line.
    pub fn set_command_line_variable(
        &mut self,
        name: &str,
        values: &[String],
    ) -> Result<(), Diagnostic> {
        self.vars
            .set_from_command_line(name, values, &mut self.sys)
            .map_err(|e| Diagnostic::error(e.to_string()).with_help(format!("in -var {name}")))
    }

    /// Execute a whole script (and whatever it includes or jumps to).
    ///
    /// In run mode the first error is returned. In check mode problems are collected in
    /// [`Interpreter::diagnostics`] and checking goes on with the next line.
    pub fn run_source(&mut self, source: Source) -> Result<(), Diagnostic> {
        self.frames.push(Frame {
            source: Rc::new(source),
            pos: 0,
        });
        while !self.quit {
            let Some(frame) = self.frames.last_mut() else {
                break;
            };
            let Some((text, first)) = line::next_logical_line(&frame.source.lines, &mut frame.pos)
            else {
                let done = self.frames.pop().expect("frame exists");
                if let Some(label) = self.label.take() {
                    let d =
                        Diagnostic::error("Label wasn't found in input script").with_help(format!(
                            "no 'label {label}' found after the jump in {}",
                            done.source.name
                        ));
                    self.fail(d.at(&self.location.clone()))?;
                }
                continue;
            };
            self.location = Location {
                file: frame.source.name.clone(),
                line: first + 1,
            };
            if self.sys.mode == Mode::Check {
                // every line read counts, those skipped while looking for a label too
                self.checked_lines += 1;
            }
            let result = self.execute_line(&text, true);
            if let Err(d) = result {
                let d = d.at(&self.location.clone());
                self.fail(d)?;
            }
        }
        self.out.flush();
        Ok(())
    }

    /// In run mode return the error; in check mode record it (unless the dry run is no longer
    /// certain what a real run would do, and it is not about an unsupported feature).
    fn fail(&mut self, d: Diagnostic) -> Result<(), Diagnostic> {
        match self.sys.mode {
            Mode::Run => Err(d),
            Mode::Check => {
                let seen = self
                    .diagnostics
                    .iter()
                    .any(|e| e.location == d.location && e.message == d.message);
                if !seen && (d.severity == Severity::Unsupported || !self.uncertain) {
                    self.diagnostics.push(d);
                } else if !seen && d.severity == Severity::Error {
                    // past a command whose effects the dry run cannot follow (a shell
                    // command, values it cannot know): what a run may well stop at, said
                    // without counting it
                    let mut w = Diagnostic::warning(format!(
                        "a run may stop here (check cannot be sure after a command whose effects it cannot follow): {}",
                        d.message
                    ));
                    if let Some(loc) = &d.location {
                        w = w.at(loc);
                    }
                    self.diagnostics.push(w);
                }
                Ok(())
            }
        }
    }

    /// Echo, substitute, split and execute one logical line (the core of LIGGGHTS's `one()`).
    fn execute_line(&mut self, raw: &str, from_file: bool) -> Result<(), Diagnostic> {
        let _ = from_file;
        if self.label.is_none() {
            self.out.echo(raw);
        }
        let stripped = line::strip_comment(raw);
        let text = if self.label.is_none() {
            self.substitute(stripped, true)?
        } else {
            stripped.to_string()
        };
        let words = line::split_words(&text).map_err(|e| lex_error(e, &text))?;
        let Some(first) = words.first() else {
            return Ok(());
        };
        if let Some(label) = &self.label {
            if first.text != "label" {
                return Ok(());
            }
            if words.len() == 2 && &words[1].text == label {
                self.label = None;
            }
            return Ok(());
        }
        self.text = text.clone();
        let cmd = CommandLine {
            words,
            text,
            location: self.location.clone(),
        };
        if self.sys.mode == Mode::Check && self.uncertain && self.name_error(&cmd) {
            return Ok(());
        }
        self.execute(&cmd).map_err(|d| {
            let span = d.span.or(Some((cmd.words[0].start, cmd.words[0].end)));
            d.with_source(&cmd.text, span)
        })
    }

    /// Replace `$` references in `text`; echo progress when `echo` (as LIGGGHTS does).
    pub fn substitute(&mut self, text: &str, echo: bool) -> Result<String, Diagnostic> {
        let check = self.sys.mode == Mode::Check;
        let uncertain = self.uncertain;
        let mut became_uncertain = false;
        let vars = &mut self.vars;
        let sys = &mut self.sys;
        let engine = &self.engine;
        let out = &mut self.out;
        let result = line::substitute(
            text,
            |r| {
                let value = match r {
                    VarRef::Named(name) => match vars.retrieve(name, sys) {
                        None => Err(None),
                        Some(Value::Text(t)) => Ok(t),
                        Some(Value::Formula(f)) => {
                            let mut scope = Scope::new(vars, sys, &engine.sim);
                            expr::evaluate(&f, &mut scope)
                                .map(|x| format::g_precision(x, 15))
                                .map_err(Some)
                        }
                    },
                    VarRef::Immediate(e) => {
                        let mut scope = Scope::new(vars, sys, &engine.sim);
                        expr::evaluate(e, &mut scope)
                            .map(|x| format::g_precision(x, 20))
                            .map_err(Some)
                    }
                };
                // a formula whose value only a run knows may still be wrong in its syntax
                let value = match (value, r) {
                    (Err(e), VarRef::Immediate(text)) if check => {
                        expr::Expr::parse(text).map_err(Some).and(Err(e))
                    }
                    (value, _) => value,
                };
                match value {
                    Err(e)
                        if check
                            && (uncertain || e.as_ref().is_some_and(|e| e.is_known_when_run())) =>
                    {
                        became_uncertain = true;
                        Ok(UNKNOWN_VALUE.to_string())
                    }
                    Ok(text) => Ok(text),
                    Err(None) => Err(line::SubstitutionError::Undefined),
                    Err(Some(e)) => Err(line::SubstitutionError::Formula(e)),
                }
            },
            |progress| {
                if echo {
                    out.echo(progress);
                }
            },
        );
        if became_uncertain {
            self.uncertain = true;
        }
        result.map_err(|e| lex_error(e, text))
    }
}

/// Words of a command after its name, as strings.
fn arg_texts(cmd: &CommandLine) -> Vec<String> {
    cmd.words[1..].iter().map(|w| w.text.clone()).collect()
}

/// An error pointing at argument `i` (0-based, after the command name).
fn at_arg(d: Diagnostic, cmd: &CommandLine, i: usize) -> Diagnostic {
    let w: Option<&Word> = cmd.words.get(i + 1).or(cmd.words.last());
    let span = w.map(|w| (w.start, w.end));
    d.with_source(&cmd.text, span)
}

fn illegal(cmd: &str, expected: &str) -> Diagnostic {
    Diagnostic::error(format!("Illegal {cmd} command")).with_help(format!("expected: {expected}"))
}

impl Interpreter {
    /// Execute one parsed command.
    pub fn execute(&mut self, cmd: &CommandLine) -> Result<(), Diagnostic> {
        let args = arg_texts(cmd);
        if self.engine.sim.procs.nprocs > 1 {
            if let Some(what) = crate::commands::ranks::refusal(cmd, &self.engine.sim) {
                if self.sys.mode == Mode::Check {
                    self.engine.diverged = true;
                }
                let mut d = Diagnostic::unsupported(crate::commands::ranks::message(&what));
                let procs = &self.engine.sim.procs;
                if let Some((lines, _)) = procs.reported.first() {
                    let said: Vec<&str> = lines.lines().map(str::trim).collect();
                    d = d.with_help(format!(
                        "the box is split over the {} ranks as a {}; {}",
                        procs.nprocs,
                        said.join(", "),
                        crate::commands::ranks::WHAT_RUNS
                    ));
                } else {
                    d = d.with_help(crate::commands::ranks::WHAT_RUNS);
                }
                return Err(d.at(&cmd.location));
            }
        }
        match cmd.name() {
            "clear" => {
                if !args.is_empty() {
                    return Err(illegal("clear", "no arguments"));
                }
                self.engine.clear();
                Ok(())
            }
            "echo" => self.echo_command(&args),
            "if" => self.if_command(cmd, &args),
            "include" => self.include(&args),
            "jump" => self.jump(&args),
            "label" => {
                if args.len() != 1 {
                    return Err(illegal("label", "label ID"));
                }
                Ok(())
            }
            "log" => self.log_command(&args),
            "next" => {
                let outcome = self
                    .vars
                    .next(&args, &mut self.sys)
                    .map_err(|e| Diagnostic::error(e.to_string()))?;
                if let Some(i) = outcome.universe_index {
                    self.out.both(&format!(
                        "Increment via next: value {} on partition 0\n",
                        i + 1
                    ));
                }
                if outcome.exhausted {
                    self.jump_skip = true;
                }
                Ok(())
            }
            "partition" => self.partition(cmd, &args),
            "print" => self.print(&args),
            "run" if args.iter().any(|w| w == "every") => self.run_every(&args),
            "quit" => {
                if !args.is_empty() {
                    return Err(illegal("quit", "no arguments"));
                }
                self.quit = true;
                Ok(())
            }
            "shell" => self.shell(&args),
            "variable" => self.variable(cmd, &args),
            _ => self
                .engine
                .execute(cmd, &mut self.sys, &mut self.vars, &mut self.out),
        }
    }

    /// `run N [keywords] every M c1 c2 ...`: runs of M steps (the last one shorter), each
    /// followed by the commands (`NULL`: none), as LIGGGHTS's run command does.
    fn run_every(&mut self, args: &[String]) -> Result<(), Diagnostic> {
        let bad = || {
            illegal(
                "run",
                "run N [upto] [start N] [stop N] [pre yes|no] [post yes|no] every M c1 c2 ...",
            )
        };
        let n: i64 = args[0].parse().map_err(|_| bad())?;
        let mut keep = Vec::new();
        let (mut upto, mut pre) = (false, true);
        let mut i = 1;
        while args[i] != "every" {
            match args[i].as_str() {
                "upto" => {
                    upto = true;
                    i += 1;
                }
                "start" | "stop" | "post" | "pre" if i + 1 < args.len() => {
                    if args[i] == "pre" {
                        pre = args[i + 1] == "yes";
                    } else {
                        keep.push(format!("{} {}", args[i], args[i + 1]));
                    }
                    i += 2;
                }
                _ => return Err(bad()),
            }
        }
        let every: i64 = match args.get(i + 1).map(|w| w.parse()) {
            Some(Ok(m)) if m > 0 => m,
            _ => return Err(bad()),
        };
        let mut commands: Vec<String> = args[i + 2..].to_vec();
        if commands.len() == 1 && commands[0] == "NULL" {
            commands.clear();
        }
        let step = self.engine.sim.step;
        let nsteps = if upto {
            n.checked_sub(step).ok_or_else(bad)?
        } else {
            n
        };
        if nsteps < 0 {
            let what = if upto { "upto value" } else { "N value" };
            return Err(Diagnostic::error(format!("Invalid run command {what}")));
        }
        let mut left = nsteps;
        let mut first = true;
        while left > 0 || first {
            // a dry run checks the commands once, after one chunk as long as the whole run
            // (so that its step count and periodic restart files are the run's)
            let chunk = if self.sys.mode == Mode::Check {
                left
            } else {
                left.min(every)
            };
            let pre_word = if pre || first { "yes" } else { "no" };
            let text = format!("run {chunk} pre {pre_word} {}", keep.join(" "));
            let words = line::split_words(&text).map_err(|e| lex_error(e, &text))?;
            let cmd = CommandLine {
                words,
                text: text.clone(),
                location: self.location.clone(),
            };
            self.engine
                .execute(&cmd, &mut self.sys, &mut self.vars, &mut self.out)?;
            for c in &commands {
                if self.sys.mode == Mode::Check {
                    self.check_only(c);
                } else {
                    self.execute_line(c, false)?;
                }
                if self.quit {
                    return Ok(());
                }
            }
            left -= chunk;
            first = false;
            if self.sys.mode == Mode::Check {
                break; // one chunk checks every command
            }
        }
        Ok(())
    }

    fn variable(&mut self, cmd: &CommandLine, args: &[String]) -> Result<(), Diagnostic> {
        if args.len() >= 2 && !crate::lang::variables::STYLE_NAMES.contains(&args[1].as_str()) {
            let help = crate::commands::suggest::did_you_mean(
                &args[1],
                crate::lang::variables::STYLE_NAMES,
            )
            .unwrap_or_else(|| {
                format!(
                    "a variable style: {}",
                    crate::lang::variables::STYLE_NAMES.join(", ")
                )
            });
            return Err(
                at_arg(Diagnostic::error("Illegal variable command"), cmd, 1).with_help(help),
            );
        }
        self.vars.set(args, &mut self.sys).map_err(|e| {
            let d = Diagnostic::error(e.to_string());
            if args.len() < 2 {
                d.with_help("variable NAME STYLE ARGS ...")
            } else {
                d
            }
        })
    }

    fn echo_command(&mut self, args: &[String]) -> Result<(), Diagnostic> {
        let (screen, log) = match args {
            [a] if a == "none" => (false, false),
            [a] if a == "screen" => (true, false),
            [a] if a == "log" => (false, true),
            [a] if a == "both" => (true, true),
            _ => return Err(illegal("echo", "none, screen, log or both")),
        };
        if self.sys.mode == Mode::Run {
            self.out.echo_screen = screen;
            self.out.echo_log = log;
        }
        Ok(())
    }

    fn log_command(&mut self, args: &[String]) -> Result<(), Diagnostic> {
        let append = match args {
            [_] => false,
            [_, a] if a == "append" => true,
            _ => return Err(illegal("log", "log FILE [append], or log none")),
        };
        if self.sys.mode == Mode::Check {
            if args[0] != "none" {
                self.sys.check_creatable(&args[0]).map_err(|e| {
                    Diagnostic::error(format!("Cannot open logfile {}", args[0]))
                        .with_help(e.to_string())
                })?;
            }
            return Ok(());
        }
        if let Some(mut old) = self.out.log.take() {
            if let Err(e) = old.flush() {
                self.out.failed(1, e);
            }
        }
        if args[0] != "none" {
            let path = self.sys.resolve(&args[0]);
            let file = std::fs::OpenOptions::new()
                .create(true)
                .write(true)
                .append(append)
                .truncate(!append)
                .open(&path)
                .map_err(|e| {
                    Diagnostic::error(format!("Cannot open logfile {}", args[0]))
                        .with_help(e.to_string())
                })?;
            self.out.log = Some(Box::new(std::io::BufWriter::new(file)));
        }
        Ok(())
    }

    fn include(&mut self, args: &[String]) -> Result<(), Diagnostic> {
        if args.len() != 1 {
            return Err(illegal("include", "include FILE"));
        }
        if self.if_depth > 0 {
            return Err(Diagnostic::error(
                "Cannot use include command within an if command",
            ));
        }
        if self.frames.len() >= MAX_INCLUDE_DEPTH {
            return Err(Diagnostic::error(format!(
                "Cannot include {}: input files nested {MAX_INCLUDE_DEPTH} deep",
                args[0]
            ))
            .with_help("does the deck include itself?"));
        }
        let source = self.open_script(&args[0])?;
        self.frames.push(Frame {
            source: Rc::new(source),
            pos: 0,
        });
        Ok(())
    }

    fn open_script(&mut self, name: &str) -> Result<Source, Diagnostic> {
        let text = self.sys.read(name).map_err(|e| {
            Diagnostic::error(format!("Cannot open input script {name}")).with_help(e.to_string())
        })?;
        Ok(Source::from_text(name, &text, false))
    }

    fn jump(&mut self, args: &[String]) -> Result<(), Diagnostic> {
        if args.is_empty() || args.len() > 2 {
            return Err(illegal("jump", "jump FILE|SELF [label]"));
        }
        if self.jump_skip {
            self.jump_skip = false;
            return Ok(());
        }
        if self.sys.mode == Mode::Check {
            // a dry run follows loops as a real run does while it knows every value (a loop
            // over `next` then ends where the real one ends, and the lines after it are
            // checked with the variables' real values); once uncertain, or past the budget,
            // it follows each jump once: every line gets checked, every loop ends
            let site = (self.location.file.clone(), self.location.line);
            let first_time = self.fired_jumps.insert(site);
            let faithful = !self.uncertain && self.checked_lines < CHECK_LINE_BUDGET;
            if !first_time && !faithful {
                self.uncertain = true;
                return Ok(());
            }
        }
        let top = self.frames.last_mut().expect("a jump runs inside a script");
        if args[0] == "SELF" {
            if top.source.from_stdin {
                return Err(Diagnostic::error(
                    "jump SELF is not allowed when using stdin, use -in instead",
                ));
            }
            top.pos = 0;
        } else {
            let source = self.open_script(&args[0])?;
            let top = self.frames.last_mut().expect("a jump runs inside a script");
            *top = Frame {
                source: Rc::new(source),
                pos: 0,
            };
        }
        if let Some(label) = args.get(1) {
            self.label = Some(label.clone());
        }
        Ok(())
    }

    fn if_command(&mut self, cmd: &CommandLine, args: &[String]) -> Result<(), Diagnostic> {
        if args.len() < 3 {
            return Err(illegal("if", "if \"condition\" then \"command\" ... [elif \"condition\" \"command\" ...] [else \"command\" ...]"));
        }
        if args[1] != "then" {
            return Err(at_arg(illegal("if", "'then' after the condition"), cmd, 1));
        }
        // LIGGGHTS reads the branches lazily: a true branch runs without the rest being
        // looked at, and only reaching the end after a false `elif` is an error
        let scan = |from: usize| {
            let mut k = from;
            while k < args.len() && args[k] != "elif" && args[k] != "else" {
                k += 1;
            }
            k
        };
        let mut condition = Some(args[0].clone());
        let mut first = 2;
        let mut end = scan(first);
        loop {
            let truth = match &condition {
                None => Some(true),
                Some(c) => self.condition(c)?,
            };
            let commands = &args[first..end];
            match truth {
                Some(true) => {
                    if commands.is_empty() || commands.iter().any(String::is_empty) {
                        return Err(illegal("if", "a non-empty command for each branch"));
                    }
                    return self.run_branch(commands);
                }
                Some(false) => {}
                None => {
                    // check mode, condition unknown: check this branch's commands without
                    // acting on them and keep looking at the others
                    self.uncertain = true;
                    for c in commands {
                        self.check_only(c);
                    }
                }
            }
            if condition.is_some() && first == 2 && end == args.len() {
                return Ok(()); // no elif or else
            }
            let i = end;
            if i + 2 > args.len() {
                return Err(at_arg(
                    illegal(
                        "if",
                        "a condition and command after elif, a command after else",
                    ),
                    cmd,
                    i.min(args.len().saturating_sub(1)),
                ));
            }
            if args[i] == "elif" {
                condition = Some(args[i + 1].clone());
                first = i + 2;
            } else {
                condition = None;
                first = i + 1;
            }
            end = scan(first);
        }
    }

    /// Evaluate an `if`/`elif` condition; None when check mode cannot know it.
    fn condition(&mut self, text: &str) -> Result<Option<bool>, Diagnostic> {
        let text = self.substitute(text, false)?;
        if text.contains(UNKNOWN_VALUE) {
            return Ok(None);
        }
        if let Some(name) = text.strip_prefix("property_") {
            if text.len() < 11 {
                return Err(Diagnostic::error(
                    "Illegal if command, length of argument too short",
                ));
            }
            return Ok(Some(self.engine.has_property_global(name)));
        }
        match expr::evaluate_boolean(&text) {
            Ok(v) => Ok(Some(v != 0.0)),
            Err(e) if self.sys.mode == Mode::Check && e.is_known_when_run() => Ok(None),
            Err(e) => {
                Err(Diagnostic::error(e.to_string())
                    .with_help(format!("in the condition \"{text}\"")))
            }
        }
    }

    fn run_branch(&mut self, commands: &[String]) -> Result<(), Diagnostic> {
        self.if_depth += 1;
        let mut result = Ok(());
        for c in commands {
            result = self.execute_line(c, false);
            if result.is_err() || self.quit {
                break;
            }
        }
        self.if_depth -= 1;
        result
    }

    /// Check mode, once values are uncertain: errors that depend on values are no longer
    /// reported, but a misspelt command or style name is one whatever the values. Records
    /// such an error and returns true (the command is then not executed).
    fn name_error(&mut self, cmd: &CommandLine) -> bool {
        let name = cmd.name();
        if SCRIPT_COMMANDS.contains(&name) || cmd.text.contains(UNKNOWN_VALUE) {
            return false;
        }
        match self.engine.validate_names(cmd) {
            Err(d) if d.severity == Severity::Error => {
                let span = d.span.or(Some((cmd.words[0].start, cmd.words[0].end)));
                let d = d.with_source(&cmd.text, span).at(&self.location.clone());
                let seen = self
                    .diagnostics
                    .iter()
                    .any(|e| e.location == d.location && e.message == d.message);
                if !seen {
                    self.diagnostics.push(d);
                }
                true
            }
            _ => false,
        }
    }

    /// In check mode, look at a command whose execution is uncertain: report unknown or
    /// unsupported names, change nothing.
    fn check_only(&mut self, text: &str) {
        let stripped = line::strip_comment(text).to_string();
        let Ok(words) = line::split_words(&stripped) else {
            return;
        };
        if words.is_empty() {
            return;
        }
        // the formulas of `$(...)` read when the command runs: their syntax is known now
        // (a print substitutes its own quoted text, other commands their line)
        let mut pieces = vec![stripped.clone()];
        if words[0].text == "print" {
            pieces.extend(words.get(1).map(|w| w.text.clone()));
        }
        for piece in &pieces {
            let mut bad = None;
            let _ = line::substitute(
                piece,
                |r| {
                    if let VarRef::Immediate(e) = r {
                        if let Err(err) = expr::Expr::parse(e) {
                            bad.get_or_insert(err);
                        }
                    }
                    Ok(String::new())
                },
                |_| {},
            );
            if let Some(err) = bad {
                let d = Diagnostic::error(err.to_string()).at(&self.location.clone());
                let seen = (self.diagnostics.iter())
                    .any(|e| e.location == d.location && e.message == d.message);
                if !seen {
                    self.diagnostics.push(d);
                }
                return;
            }
        }
        if SCRIPT_COMMANDS.contains(&words[0].text.as_str()) {
            return; // the interpreter's own commands: nothing for the engine to check
        }
        let cmd = CommandLine {
            words,
            text: stripped,
            location: self.location.clone(),
        };
        if let Err(d) = self.engine.validate_names(&cmd) {
            self.diagnostics.push(d.at(&self.location.clone()));
        }
    }

    fn print(&mut self, args: &[String]) -> Result<(), Diagnostic> {
        let Some(message) = args.first() else {
            return Err(illegal(
                "print",
                "print \"text\" [file F] [append F] [screen yes|no] [newline yes|no]",
            ));
        };
        let text = self.substitute(message, false)?;
        let mut files: Vec<(String, bool)> = Vec::new();
        let mut screen = true;
        let mut newline = true;
        let mut i = 1;
        let yes_no = |w: Option<&String>| match w.map(String::as_str) {
            Some("yes") => Ok(true),
            Some("no") => Ok(false),
            _ => Err(illegal("print", "yes or no")),
        };
        while i < args.len() {
            match args[i].as_str() {
                "file" | "append" => {
                    let Some(name) = args.get(i + 1) else {
                        return Err(illegal("print", "a file name after file/append"));
                    };
                    files.push((name.clone(), args[i] == "append"));
                }
                "screen" => screen = yes_no(args.get(i + 1))?,
                "newline" => newline = yes_no(args.get(i + 1))?,
                // regolith extension: with one partition the universe screen is the screen
                "universe" => screen = yes_no(args.get(i + 1))? || screen,
                other => {
                    let keys = ["file", "append", "screen", "newline", "universe"];
                    let help = crate::commands::suggest::did_you_mean(other, &keys)
                        .unwrap_or_else(|| "keywords file, append, screen, newline".into());
                    return Err(Diagnostic::error("Illegal print command").with_help(help));
                }
            }
            i += 2;
        }
        let line = if newline { format!("{text}\n") } else { text };
        // as LIGGGHTS: each file/append keyword opens its file (file truncates), but only the
        // last one opened receives the text
        for (k, (name, append)) in files.iter().enumerate() {
            let content = if k + 1 == files.len() {
                line.as_str()
            } else {
                ""
            };
            self.sys.write(name, content, *append).map_err(|e| {
                Diagnostic::error(format!("Cannot open print file {name}")).with_help(e.to_string())
            })?;
        }
        if screen {
            self.out.both(&line);
        }
        Ok(())
    }

    fn shell(&mut self, args: &[String]) -> Result<(), Diagnostic> {
        let Some(what) = args.first() else {
            return Err(illegal(
                "shell",
                "shell cd|mkdir|mv|rm|rmdir|putenv ARGS, or a shell command",
            ));
        };
        let rest = &args[1..];
        // on several MPI ranks, as LIGGGHTS: files and commands by rank 0 alone; cd and
        // putenv on every rank
        let root = self.sys.mode == Mode::Check
            || self.engine.sim.comm.as_ref().is_none_or(|c| c.rank() == 0);
        let need = |ok: bool, usage: &str| {
            if ok {
                Ok(())
            } else {
                Err(Diagnostic::error(format!("Illegal shell {what} command"))
                    .with_help(usage.to_string()))
            }
        };
        match what.as_str() {
            "cd" => {
                need(rest.len() == 1, "shell cd DIR")?;
                self.sys.chdir(&rest[0]);
            }
            "mkdir" => {
                need(!rest.is_empty(), "shell mkdir DIR ...")?;
                if root {
                    rest.iter().for_each(|d| self.sys.mkdir(d));
                }
            }
            "mv" => {
                need(rest.len() == 2, "shell mv OLD NEW")?;
                if root {
                    self.sys.rename(&rest[0], &rest[1]);
                }
            }
            "rm" => {
                need(!rest.is_empty(), "shell rm FILE ...")?;
                if root {
                    rest.iter().for_each(|f| self.sys.remove_file(f));
                }
            }
            "rmdir" => {
                need(!rest.is_empty(), "shell rmdir DIR ...")?;
                if root {
                    rest.iter().for_each(|d| self.sys.rmdir(d));
                }
            }
            "putenv" => {
                need(!rest.is_empty(), "shell putenv NAME=VALUE ...")?;
                rest.iter().for_each(|a| self.sys.putenv(a));
            }
            _ if !root => {}
            _ => {
                self.out.flush();
                if self.sys.system(&args.join(" ")).is_none() && self.sys.mode == Mode::Check {
                    // an arbitrary shell command may change anything the deck reads later
                    self.uncertain = true;
                }
            }
        }
        Ok(())
    }

    fn partition(&mut self, cmd: &CommandLine, args: &[String]) -> Result<(), Diagnostic> {
        if args.len() < 3 {
            return Err(illegal("partition", "partition yes|no I1:I2 command ..."));
        }
        let yes = match args[0].as_str() {
            "yes" => true,
            "no" => false,
            _ => return Err(at_arg(illegal("partition", "yes or no"), cmd, 0)),
        };
        let (lo, hi) = crate::util::numbers::bounds(&args[1], 1)
            .map_err(|m| at_arg(Diagnostic::error(m.to_string()), cmd, 1))?;
        let inside = lo <= 1 && 1 <= hi;
        if inside == yes {
            let rest = &cmd.text[cmd.words[3].start..];
            return self.execute_line(rest, false);
        }
        Ok(())
    }
}
