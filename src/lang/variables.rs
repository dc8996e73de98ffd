//! The `variable` command's store: every style LIGGGHTS 3.8.0 has, `next`, and retrieval of
//! a variable's text for `$` substitution.

use crate::lang::error::{SystemError, VariableCommandError};
use crate::util::random::RanMars;

/// A variable's style, as named in the `variable` command.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Style {
    /// `index v1 v2 ...`: advanced by `next`.
    Index,
    /// `loop N` / `loop N1 N2`, optionally `pad`.
    Loop,
    /// `world v1 ...`: one value per partition.
    World,
    /// `universe v1 ...`: values handed out across partitions.
    Universe,
    /// `uloop N`: like universe with integers.
    Uloop,
    /// `string text`: redefinable text.
    String,
    /// `getenv NAME`: an environment variable's value.
    Getenv,
    /// `file name`: one value per non-blank line of a file.
    File,
    /// `atomfile name`: per-atom values from a file.
    AtomFile,
    /// `equal expr`: evaluated whenever used.
    Equal,
    /// `atom expr`: evaluated per atom.
    Atom,
}

impl Style {
    /// The style's name in the `variable` command.
    pub fn name(self) -> &'static str {
        match self {
            Style::Index => "index",
            Style::Loop => "loop",
            Style::World => "world",
            Style::Universe => "universe",
            Style::Uloop => "uloop",
            Style::String => "string",
            Style::Getenv => "getenv",
            Style::File => "file",
            Style::AtomFile => "atomfile",
            Style::Equal => "equal",
            Style::Atom => "atom",
        }
    }
}

/// Every style name the `variable` command accepts (for messages and suggestions).
pub const STYLE_NAMES: &[&str] = &[
    "delete", "index", "loop", "world", "universe", "uloop", "string", "getenv", "file",
    "atomfile", "equal", "atom",
];

/// The values of a `file`-style variable still to be read (non-blank lines, comments cut).
#[derive(Debug, Clone)]
struct FileValues {
    values: std::collections::VecDeque<String>,
}

impl FileValues {
    fn from_text(text: &str) -> FileValues {
        let blank = |c: char| " \t\n\r\u{0c}".contains(c);
        let values = text
            .lines()
            .filter_map(|line| {
                let line = match line.find('#') {
                    Some(i) => &line[..i],
                    None => line,
                };
                // LIGGGHTS keeps the line up to the end of its first word, leading blanks included
                let start = line.find(|c: char| !blank(c))?;
                let end = line[start..].find(blank).map_or(line.len(), |e| start + e);
                Some(line[..end].to_string())
            })
            .collect();
        FileValues { values }
    }
}

/// One defined variable.
#[derive(Debug, Clone)]
pub struct Variable {
    /// Its name (letters, digits, underscores).
    pub name: String,
    /// Its style.
    pub style: Style,
    values: Vec<String>,
    which: i64,
    count: i64,
    pad: usize,
    file: Option<FileValues>,
}

impl Variable {
    /// A new variable `name` of `style` holding `values`, at its first value.
    fn new(name: &str, style: Style, values: Vec<String>) -> Variable {
        Variable {
            name: name.to_string(),
            style,
            values,
            which: 0,
            count: 0,
            pad: 0,
            file: None,
        }
    }

    /// The formula of an equal- or atom-style variable, or the text of a string variable.
    pub fn formula(&self) -> Option<&str> {
        match self.style {
            Style::Equal | Style::Atom | Style::String | Style::Getenv => {
                self.values.first().map(String::as_str)
            }
            _ => None,
        }
    }
}

/// What a `variable` command needs from the outside world.
pub trait VariableHost {
    /// Read a whole file (relative names resolve as the deck sees them).
    fn read_file(&mut self, name: &str) -> Result<String, SystemError>;
    /// The value of an environment variable.
    fn getenv(&mut self, name: &str) -> Option<String>;
    /// Number of partitions (always 1 in regolith) and this one's index.
    fn partitions(&self) -> (usize, usize) {
        (1, 0)
    }
    /// Read and advance the shared universe counter (the `tmp.lammps.variable` file).
    fn universe_next(&mut self) -> Result<usize, SystemError>;
    /// Create the shared universe counter file holding `worlds`.
    fn universe_init(&mut self, worlds: usize) -> Result<(), SystemError>;
}

/// A variable's value as `$` substitution sees it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Value {
    /// Text to substitute as is.
    Text(String),
    /// An equal-style formula still to be evaluated.
    Formula(String),
}

/// What a `next` command did.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NextOutcome {
    /// A variable ran out of values and was deleted (the following `jump` is skipped).
    pub exhausted: bool,
    /// For universe/uloop variables: the 0-based counter value taken.
    pub universe_index: Option<usize>,
}

/// All defined variables, in definition order.
#[derive(Debug, Default)]
pub struct Variables {
    vars: Vec<Variable>,
    /// Generator behind `random()`/`normal()` in equal-style formulas, made on first use.
    pub random_equal: Option<RanMars>,
    /// Generator behind `random()`/`normal()` in atom-style formulas, made on first use.
    pub random_atom: Option<RanMars>,
}

fn illegal() -> VariableCommandError {
    VariableCommandError::Illegal
}

fn parse_int(word: &str) -> Result<i64, VariableCommandError> {
    // LIGGGHTS's force->inumeric: digits with an optional leading minus sign only
    let digits = word.strip_prefix('-').unwrap_or(word);
    if digits.is_empty() || !digits.bytes().all(|b| b.is_ascii_digit()) {
        return Err(VariableCommandError::ExpectedInteger(word.to_string()));
    }
    word.parse::<i64>()
        .map_err(|_| VariableCommandError::IntegerRange(word.to_string()))
}

fn pad_width(last: i64) -> usize {
    last.to_string().len()
}

impl Variables {
    /// Find a variable by name.
    pub fn get(&self, name: &str) -> Option<&Variable> {
        self.vars.iter().find(|v| v.name == name)
    }

    fn position(&self, name: &str) -> Option<usize> {
        self.vars.iter().position(|v| v.name == name)
    }

    /// Remove a variable if it exists.
    pub fn remove(&mut self, name: &str) {
        if let Some(i) = self.position(name) {
            self.vars.remove(i);
        }
    }

    /// `-var NAME v1 v2 ...` from the command line: an index variable.
    pub fn set_from_command_line(
        &mut self,
        name: &str,
        values: &[String],
        host: &mut dyn VariableHost,
    ) -> Result<(), VariableCommandError> {
        let mut args = vec![name.to_string(), "index".to_string()];
        args.extend(values.iter().cloned());
        self.set(&args, host)
    }

    /// The `variable` command: `args` are its words after the command name.
    pub fn set(
        &mut self,
        args: &[String],
        host: &mut dyn VariableHost,
    ) -> Result<(), VariableCommandError> {
        if args.len() < 2 {
            return Err(illegal());
        }
        let name = args[0].as_str();
        let style_word = args[1].as_str();
        let rest = &args[2..];
        let exists = self.position(name);
        // None: an existing variable of a style LIGGGHTS does not redefine is kept
        let var = match style_word {
            "delete" => {
                if !rest.is_empty() {
                    return Err(illegal());
                }
                self.remove(name);
                return Ok(());
            }
            "index" | "world" | "universe" => {
                if rest.is_empty() {
                    return Err(illegal());
                }
                match exists {
                    Some(_) => None,
                    None => Some(self.value_list(name, style_word, rest, host)?),
                }
            }
            "loop" => match exists {
                Some(_) => None,
                None => Some(loop_variable(name, rest)?),
            },
            "uloop" => self.uloop_variable(name, rest, exists, host)?,
            "string" | "getenv" | "equal" | "atom" => {
                Some(self.formula_variable(name, style_word, rest, exists)?)
            }
            "file" | "atomfile" => {
                if rest.len() != 1 {
                    return Err(illegal());
                }
                match exists {
                    Some(_) => None,
                    None => Some(file_variable(name, style_word, &rest[0], host)?),
                }
            }
            _ => return Err(illegal()),
        };
        let Some(var) = var else {
            return Ok(());
        };
        if !name.bytes().all(|b| b.is_ascii_alphanumeric() || b == b'_') {
            return Err(VariableCommandError::BadName);
        }
        self.vars.push(var);
        Ok(())
    }

    /// `index|world|universe V1 V2 ...`: a new variable stepping through its values (a
    /// `world` variable takes the value of this partition).
    fn value_list(
        &self,
        name: &str,
        style_word: &str,
        values: &[String],
        host: &mut dyn VariableHost,
    ) -> Result<Variable, VariableCommandError> {
        let style = match style_word {
            "index" => Style::Index,
            "world" => Style::World,
            _ => Style::Universe,
        };
        let mut v = Variable::new(name, style, values.to_vec());
        v.count = values.len() as i64;
        let (worlds, me) = host.partitions();
        if style == Style::World {
            if v.count != worlds as i64 {
                return Err(VariableCommandError::WorldCount);
            }
            v.which = me as i64;
        }
        if style == Style::Universe {
            self.universe_checks(&v, host)?;
        }
        Ok(v)
    }

    /// `uloop N [pad]`: a new universe loop over 1..N (None when `name` exists).
    fn uloop_variable(
        &self,
        name: &str,
        rest: &[String],
        exists: Option<usize>,
        host: &mut dyn VariableHost,
    ) -> Result<Option<Variable>, VariableCommandError> {
        let padded = match rest {
            [_] => false,
            [_, p] if p == "pad" => true,
            _ => return Err(illegal()),
        };
        if exists.is_some() {
            return Ok(None);
        }
        let n = parse_int(&rest[0])?;
        let mut v = Variable::new(name, Style::Uloop, Vec::new());
        v.count = n.max(0);
        if padded {
            v.pad = pad_width(n);
        }
        self.universe_checks(&v, host)?;
        Ok(Some(v))
    }

    /// `string|getenv|equal|atom TEXT`: a variable of one value, replacing an existing one of
    /// the same style (`exists`: its index).
    fn formula_variable(
        &mut self,
        name: &str,
        style_word: &str,
        rest: &[String],
        exists: Option<usize>,
    ) -> Result<Variable, VariableCommandError> {
        if rest.len() != 1 {
            return Err(illegal());
        }
        let style = match style_word {
            "string" => Style::String,
            "getenv" => Style::Getenv,
            "equal" => Style::Equal,
            _ => Style::Atom,
        };
        if let Some(i) = exists {
            if self.vars[i].style != style {
                return Err(VariableCommandError::Redefined);
            }
            self.vars.remove(i);
        }
        let mut v = Variable::new(name, style, rest.to_vec());
        v.count = 1;
        Ok(v)
    }

    fn universe_checks(
        &self,
        v: &Variable,
        host: &mut dyn VariableHost,
    ) -> Result<(), VariableCommandError> {
        let (worlds, me) = host.partitions();
        if v.count < worlds as i64 {
            return Err(VariableCommandError::UniverseCount);
        }
        let _ = me;
        host.universe_init(worlds)?;
        for other in &self.vars {
            if matches!(other.style, Style::Universe | Style::Uloop)
                && other.count != 0
                && other.count != v.count
            {
                return Err(VariableCommandError::UniverseMismatch);
            }
        }
        Ok(())
    }

    /// The `next` command. Says whether any variable ran out (it is then deleted) and, for
    /// universe/uloop variables, which counter value this partition took.
    pub fn next(
        &mut self,
        names: &[String],
        host: &mut dyn VariableHost,
    ) -> Result<NextOutcome, VariableCommandError> {
        let Some(first) = names.first() else {
            return Err(VariableCommandError::IllegalNext);
        };
        let mut styles = Vec::with_capacity(names.len());
        for n in names {
            match self.get(n) {
                Some(v) => styles.push(v.style),
                None => return Err(VariableCommandError::NextUnknown),
            }
        }
        let lead = self.get(first).map(|v| v.style).unwrap_or(Style::Index);
        let universe_like = |s: Style| matches!(s, Style::Universe | Style::Uloop);
        for &s in &styles {
            if s != lead && !(universe_like(s) && universe_like(lead)) {
                return Err(VariableCommandError::NextMixed);
            }
        }
        if matches!(
            lead,
            Style::String | Style::Equal | Style::World | Style::Getenv | Style::Atom
        ) {
            return Err(VariableCommandError::NextStyle);
        }
        let mut exhausted = false;
        let universe_index = if universe_like(lead) {
            Some(host.universe_next()?)
        } else {
            None
        };
        for n in names {
            let i = self.position(n).expect("checked above");
            let v = &mut self.vars[i];
            let done = match v.style {
                Style::Index | Style::Loop => {
                    v.which += 1;
                    v.which >= v.count
                }
                Style::File => match v.file.as_mut().and_then(|f| f.values.pop_front()) {
                    Some(value) => {
                        v.values[0] = value;
                        false
                    }
                    None => true,
                },
                Style::Universe | Style::Uloop => {
                    v.which = universe_index.unwrap_or(0) as i64;
                    v.which >= v.count
                }
                _ => false,
            };
            if done {
                exhausted = true;
                self.vars.remove(i);
            }
        }
        Ok(NextOutcome {
            exhausted,
            universe_index,
        })
    }

    /// What `$name` stands for: text, or an equal-style formula the caller evaluates and
    /// prints with `%.15g`. None if there is no such variable, it is exhausted, or per-atom.
    pub fn retrieve(&self, name: &str, host: &mut dyn VariableHost) -> Option<Value> {
        let v = self.get(name)?;
        if v.which >= v.count {
            return None;
        }
        Some(match v.style {
            Style::Index | Style::World | Style::Universe | Style::String | Style::File => {
                Value::Text(v.values[v.which.max(0) as usize].clone())
            }
            Style::Loop | Style::Uloop => {
                let n = v.which + 1;
                Value::Text(format!("{n:0width$}", width = v.pad))
            }
            Style::Equal => Value::Formula(v.values[0].clone()),
            Style::Getenv => Value::Text(host.getenv(&v.values[0]).unwrap_or_default()),
            Style::Atom | Style::AtomFile => return None,
        })
    }

    /// The formula of an atom-style variable.
    pub fn atom_formula(&self, name: &str) -> Option<String> {
        let v = self.get(name)?;
        (v.style == Style::Atom).then(|| v.values[0].clone())
    }

    /// Names of all defined variables (for suggestions).
    pub fn names(&self) -> Vec<&str> {
        self.vars.iter().map(|v| v.name.as_str()).collect()
    }
}

/// `loop N` or `loop N1 N2 [pad]`: a new loop variable over N1..N2 (1..N).
fn loop_variable(name: &str, rest: &[String]) -> Result<Variable, VariableCommandError> {
    let (first, last, padded) = loop_range(rest)?;
    // LIGGGHTS stores which = N1 - 1 and count = N2, so N1 may be negative
    let mut v = Variable::new(name, Style::Loop, Vec::new());
    v.count = last;
    v.which = first - 1;
    if padded {
        v.pad = pad_width(last);
    }
    Ok(v)
}

/// `file F` (`atomfile` is not supported yet): a new variable stepping through the file's
/// values, the first one current.
fn file_variable(
    name: &str,
    style_word: &str,
    file_name: &str,
    host: &mut dyn VariableHost,
) -> Result<Variable, VariableCommandError> {
    let text = host
        .read_file(file_name)
        .map_err(|_| VariableCommandError::CannotOpen(file_name.to_string()))?;
    if style_word == "atomfile" {
        return Err(VariableCommandError::Unsupported(
            "variable atomfile".into(),
        ));
    }
    let mut file = FileValues::from_text(&text);
    let Some(first) = file.values.pop_front() else {
        return Err(VariableCommandError::EmptyFile);
    };
    let mut v = Variable::new(name, Style::File, vec![first]);
    v.count = 1;
    v.file = Some(file);
    Ok(v)
}

/// The words after `variable NAME loop`: `N` or `N1 N2`, then `pad` or not. Gives the first
/// and last values and whether the values are zero-padded.
fn loop_range(rest: &[String]) -> Result<(i64, i64, bool), VariableCommandError> {
    let padded = rest.last().map(String::as_str) == Some("pad");
    let numbers = if padded {
        &rest[..rest.len() - 1]
    } else {
        rest
    };
    let (first, last) = match numbers {
        [n] => {
            let n = parse_int(n)?;
            if n <= 0 {
                return Err(illegal());
            }
            (1, n)
        }
        [a, b] => {
            let (a, b) = (parse_int(a)?, parse_int(b)?);
            if a > b || b < 0 {
                return Err(illegal());
            }
            (a, b)
        }
        _ => return Err(illegal()),
    };
    Ok((first, last, padded))
}

#[cfg(test)]
mod tests {
    use super::*;

    struct Host;
    impl VariableHost for Host {
        fn read_file(&mut self, _: &str) -> Result<String, SystemError> {
            Ok("# header\n\n 1.5 extra\n two\n".into())
        }
        fn getenv(&mut self, name: &str) -> Option<String> {
            (name == "HOME_X").then(|| "here".into())
        }
        fn universe_next(&mut self) -> Result<usize, SystemError> {
            Ok(1)
        }
        fn universe_init(&mut self, _: usize) -> Result<(), SystemError> {
            Ok(())
        }
    }

    fn words(s: &str) -> Vec<String> {
        s.split_whitespace().map(str::to_string).collect()
    }

    fn text(v: &Variables, name: &str) -> Option<String> {
        v.retrieve(name, &mut Host).map(|r| match r {
            Value::Text(t) => t,
            Value::Formula(f) => format!("={f}"),
        })
    }

    #[test]
    fn index_loop_and_next() {
        let mut v = Variables::default();
        v.set(&words("a index x y"), &mut Host).unwrap();
        v.set(&words("a index z"), &mut Host).unwrap(); // ignored: already defined
        assert_eq!(text(&v, "a").as_deref(), Some("x"));
        assert!(!v.next(&words("a"), &mut Host).unwrap().exhausted);
        assert_eq!(text(&v, "a").as_deref(), Some("y"));
        assert!(v.next(&words("a"), &mut Host).unwrap().exhausted);
        assert_eq!(text(&v, "a"), None);

        v.set(&words("i loop 3 12 pad"), &mut Host).unwrap();
        assert_eq!(text(&v, "i").as_deref(), Some("03"));
        v.set(&words("j loop 10 pad"), &mut Host).unwrap();
        assert_eq!(text(&v, "j").as_deref(), Some("01"));
        let e = v.set(&words("k loop 0"), &mut Host).unwrap_err();
        assert!(matches!(e, VariableCommandError::Illegal), "{e:?}");
        assert_eq!(e.to_string(), "Illegal variable command");
    }

    #[test]
    fn string_equal_file_getenv() {
        let mut v = Variables::default();
        v.set(&words("s string abc"), &mut Host).unwrap();
        v.set(&words("s string def"), &mut Host).unwrap();
        assert_eq!(text(&v, "s").as_deref(), Some("def"));
        assert!(matches!(
            v.set(&words("s equal 1"), &mut Host),
            Err(VariableCommandError::Redefined)
        ));
        v.set(&words("e equal 1/4"), &mut Host).unwrap();
        assert_eq!(text(&v, "e").as_deref(), Some("=1/4"));
        v.set(&words("f file data.txt"), &mut Host).unwrap();
        assert_eq!(text(&v, "f").as_deref(), Some(" 1.5"));
        assert!(!v.next(&words("f"), &mut Host).unwrap().exhausted);
        assert_eq!(text(&v, "f").as_deref(), Some(" two"));
        assert!(v.next(&words("f"), &mut Host).unwrap().exhausted);
        v.set(&words("h getenv HOME_X"), &mut Host).unwrap();
        assert_eq!(text(&v, "h").as_deref(), Some("here"));
        assert!(matches!(
            v.set(&words("bad-name index 1"), &mut Host),
            Err(VariableCommandError::BadName)
        ));
        assert!(matches!(
            v.next(&words("s"), &mut Host),
            Err(VariableCommandError::NextStyle)
        ));
        let e = v.set(&words("a atomfile x.txt"), &mut Host).unwrap_err();
        assert!(matches!(&e, VariableCommandError::Unsupported(f) if f == "variable atomfile"));
        assert_eq!(e.to_string(), "variable atomfile: not supported yet");
    }
}
