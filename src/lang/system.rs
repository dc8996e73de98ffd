//! The interpreter's view of the outside world: files, the working directory, environment
//! variables. In check mode every effect goes to an in-memory overlay, so a dry run of a deck
//! touches nothing on disk yet sees the files the deck itself would have written.

use std::collections::{HashMap, HashSet};
use std::path::{Path, PathBuf};
use std::rc::Rc;

use crate::lang::error::SystemError;
use crate::lang::variables::VariableHost;

/// Whether commands really act or are only checked.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Mode {
    /// Execute the deck.
    Run,
    /// Validate the deck without side effects.
    Check,
}

/// Files, directory and environment as the deck sees them.
#[derive(Debug)]
pub struct System {
    /// Run or check.
    pub mode: Mode,
    /// Working directory for relative names (changed by `shell cd`).
    pub cwd: PathBuf,
    overlay_files: HashMap<PathBuf, Option<String>>,
    overlay_binary: HashMap<PathBuf, (u64, KeptFile)>,
    series: Vec<(u64, KeptSeries)>,
    kept_count: u64,
    overlay_env: HashMap<String, String>,
    overlay_dirs: HashSet<PathBuf>,
}

/// Check mode: a binary file (a restart) the deck would have written, and the step it would
/// hold when that differs from the one in the bytes.
#[derive(Debug, Clone)]
pub struct KeptFile {
    /// The file's contents.
    pub bytes: Rc<Vec<u8>>,
    /// The step the real file would hold (periodic output of a run the dry run did not step).
    pub step: Option<i64>,
}

/// Check mode: the files of periodic output during a run: `template` with `*` replaced by
/// each multiple of `every` after step `after` up to step `upto`.
#[derive(Debug, Clone)]
pub struct KeptSeries {
    /// Absolute name with a `*` for the step.
    pub template: String,
    /// Interval.
    pub every: i64,
    /// The run's first step (not written).
    pub after: i64,
    /// The run's last step.
    pub upto: i64,
    /// Contents of every file (the state the dry run has).
    pub bytes: Rc<Vec<u8>>,
}

impl KeptSeries {
    /// The step of `path` if it is one of the series' files.
    fn step_of(&self, path: &str) -> Option<i64> {
        let (prefix, suffix) = self.template.split_once('*')?;
        let mid = path.strip_prefix(prefix)?.strip_suffix(suffix)?;
        if mid.is_empty() || !mid.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        let step: i64 = mid.parse().ok()?;
        (step > self.after && step <= self.upto && step % self.every == 0).then_some(step)
    }

    /// The series' last file: (step, name), if the run writes any.
    fn last(&self) -> Option<(i64, String)> {
        let step = self.upto - self.upto.rem_euclid(self.every);
        (step > self.after).then(|| (step, self.template.replacen('*', &step.to_string(), 1)))
    }
}

impl System {
    /// A system rooted at the process's working directory.
    pub fn new(mode: Mode) -> System {
        System {
            mode,
            cwd: std::env::current_dir().unwrap_or_else(|_| PathBuf::from(".")),
            overlay_files: HashMap::new(),
            overlay_binary: HashMap::new(),
            series: Vec::new(),
            kept_count: 0,
            overlay_env: HashMap::new(),
            overlay_dirs: HashSet::new(),
        }
    }

    /// Absolute path for a name as the deck wrote it.
    pub fn resolve(&self, name: &str) -> PathBuf {
        let p = Path::new(name);
        if p.is_absolute() {
            p.to_path_buf()
        } else {
            self.cwd.join(p)
        }
    }

    /// Read a file as text (check mode sees files the deck wrote earlier).
    pub fn read(&self, name: &str) -> Result<String, SystemError> {
        let path = self.resolve(name);
        if let Some(entry) = self.overlay_files.get(&path) {
            return entry
                .clone()
                .ok_or_else(|| SystemError::NoSuchFile(name.to_string()));
        }
        std::fs::read(&path)
            .map(|b| String::from_utf8_lossy(&b).into_owned())
            .map_err(|e| file_error(name, e))
    }

    /// Check mode: remember a binary file (a restart) the deck would write.
    pub fn keep_binary(&mut self, path: &Path, bytes: Vec<u8>) {
        let file = KeptFile {
            bytes: Rc::new(bytes),
            step: None,
        };
        self.keep_file(path, file);
    }

    /// Check mode: remember a binary file that holds a given step.
    pub fn keep_file(&mut self, path: &Path, file: KeptFile) {
        self.kept_count += 1;
        self.overlay_binary
            .insert(path.to_path_buf(), (self.kept_count, file));
    }

    /// Check mode: remember the files of periodic output during a run.
    pub fn keep_series(&mut self, series: KeptSeries) {
        self.kept_count += 1;
        self.series.push((self.kept_count, series));
    }

    /// Check mode: a binary file the deck wrote earlier, if any (the latest write wins).
    pub fn kept_binary(&self, path: &Path) -> Option<KeptFile> {
        let name = path.to_string_lossy();
        let single = self.overlay_binary.get(path).cloned();
        let periodic = self.series.iter().rev().find_map(|(n, s)| {
            s.step_of(&name).map(|step| {
                let file = KeptFile {
                    bytes: s.bytes.clone(),
                    step: Some(step),
                };
                (*n, file)
            })
        });
        match (single, periodic) {
            (Some(a), Some(b)) => Some(if a.0 > b.0 { a.1 } else { b.1 }),
            (a, b) => a.or(b).map(|(_, f)| f),
        }
    }

    /// Check mode: the kept files matching `pattern` (one `*` standing for a step), as
    /// (step, name), for `read_restart NAME.*`.
    pub fn kept_matching(&self, pattern: &str) -> Vec<(i64, String)> {
        let Some((prefix, suffix)) = pattern.split_once('*') else {
            return Vec::new();
        };
        let mut found: Vec<(i64, String)> = self
            .overlay_binary
            .keys()
            .filter_map(|p| {
                let name = p.to_string_lossy().into_owned();
                let mid = name.strip_prefix(prefix)?.strip_suffix(suffix)?;
                let step = mid.parse::<i64>().ok()?;
                Some((step, name))
            })
            .collect();
        for (_, s) in &self.series {
            if let Some((step, name)) = s.last() {
                if name.starts_with(prefix) && name.ends_with(suffix) {
                    found.push((step, name));
                }
            }
        }
        found.sort();
        found
    }

    /// Write (or append to) a text file.
    pub fn write(&mut self, name: &str, text: &str, append: bool) -> Result<(), SystemError> {
        let path = self.resolve(name);
        match self.mode {
            Mode::Run => {
                use std::io::Write;
                let mut f = std::fs::OpenOptions::new()
                    .create(true)
                    .write(true)
                    .append(append)
                    .truncate(!append)
                    .open(&path)
                    .map_err(|e| file_error(name, e))?;
                f.write_all(text.as_bytes())
                    .map_err(|e| file_error(name, e))
            }
            Mode::Check => {
                if !self.overlay_files.contains_key(&path) {
                    self.check_creatable(name)
                        .map_err(|e| file_error(name, e))?;
                }
                let mut content = if append {
                    self.read(name).unwrap_or_default()
                } else {
                    String::new()
                };
                content.push_str(text);
                self.overlay_files.insert(path, Some(content));
                Ok(())
            }
        }
    }

    /// Delete a file; failures are silent, as with LIGGGHTS's `shell rm`.
    pub fn remove_file(&mut self, name: &str) {
        let path = self.resolve(name);
        match self.mode {
            Mode::Run => {
                let _ = std::fs::remove_file(path);
            }
            Mode::Check => {
                self.overlay_files.insert(path, None);
            }
        }
    }

    /// Rename a file; failures are silent.
    pub fn rename(&mut self, from: &str, to: &str) {
        match self.mode {
            Mode::Run => {
                let _ = std::fs::rename(self.resolve(from), self.resolve(to));
            }
            Mode::Check => {
                if let Ok(text) = self.read(from) {
                    self.overlay_files.insert(self.resolve(from), None);
                    self.overlay_files.insert(self.resolve(to), Some(text));
                }
            }
        }
    }

    /// Check mode: whether a file named `name` could be created, i.e. its folder exists on
    /// disk or the deck made it earlier (`shell mkdir`); a missing folder gives the error
    /// opening the file would give (no such file or directory). Run mode: always Ok, the
    /// opening itself reports.
    pub fn check_creatable(&self, name: &str) -> Result<(), std::io::Error> {
        if self.mode == Mode::Run {
            return Ok(());
        }
        let path = self.resolve(name);
        match path.parent() {
            Some(dir) if !self.dir_exists(dir) => Err(missing_entry()),
            _ => Ok(()),
        }
    }

    /// Whether a directory exists on disk or in the check-mode overlay.
    fn dir_exists(&self, dir: &Path) -> bool {
        dir.as_os_str().is_empty() || self.overlay_dirs.contains(dir) || dir.is_dir()
    }

    /// `mkdir` with LIGGGHTS's permissions (rwxr-x---); failures are silent.
    pub fn mkdir(&mut self, name: &str) {
        if self.mode == Mode::Check {
            let path = self.resolve(name);
            if path.parent().is_none_or(|p| self.dir_exists(p)) {
                self.overlay_dirs.insert(path);
            }
            return;
        }
        if self.mode == Mode::Run {
            let mut builder = std::fs::DirBuilder::new();
            #[cfg(unix)]
            {
                use std::os::unix::fs::DirBuilderExt;
                builder.mode(0o750);
            }
            let _ = builder.create(self.resolve(name));
        }
    }

    /// Create a directory and its parents (for output files); errors are reported.
    pub fn create_parent_dirs(&mut self, name: &str) -> Result<(), SystemError> {
        if self.mode == Mode::Check {
            let path = self.resolve(name);
            self.overlay_dirs
                .extend(path.ancestors().skip(1).map(Path::to_path_buf));
        }
        if self.mode == Mode::Run {
            if let Some(parent) = self.resolve(name).parent() {
                std::fs::create_dir_all(parent)
                    .map_err(|e| file_error(&parent.display().to_string(), e))?;
            }
        }
        Ok(())
    }

    /// `rmdir`; failures are silent.
    pub fn rmdir(&mut self, name: &str) {
        if self.mode == Mode::Check {
            self.overlay_dirs.remove(&self.resolve(name));
        }
        if self.mode == Mode::Run {
            let _ = std::fs::remove_dir(self.resolve(name));
        }
    }

    /// `shell cd`: change the directory relative names resolve from; failures are silent.
    pub fn chdir(&mut self, name: &str) {
        let target = self.resolve(name);
        if self.mode == Mode::Run {
            if std::env::set_current_dir(&target).is_ok() {
                self.cwd = std::env::current_dir().unwrap_or(target);
            }
        } else if target.is_dir() {
            self.cwd = target;
        }
    }

    /// `shell putenv NAME=value`.
    pub fn putenv(&mut self, assignment: &str) {
        let (k, v) = assignment.split_once('=').unwrap_or((assignment, ""));
        match self.mode {
            Mode::Run => std::env::set_var(k, v),
            Mode::Check => {
                self.overlay_env.insert(k.to_string(), v.to_string());
            }
        }
    }

    /// Run a command line through `sh -c` (run mode only); returns its exit status.
    pub fn system(&mut self, command: &str) -> Option<i32> {
        if self.mode != Mode::Run {
            return None;
        }
        std::process::Command::new("sh")
            .arg("-c")
            .arg(command)
            .current_dir(&self.cwd)
            .status()
            .ok()
            .and_then(|s| s.code())
    }
}

/// The error opening a file in a folder that does not exist gives (ENOENT).
fn missing_entry() -> std::io::Error {
    std::io::Error::from_raw_os_error(2)
}

fn file_error(name: &str, source: std::io::Error) -> SystemError {
    SystemError::File {
        name: name.to_string(),
        source,
    }
}

const UNIVERSE_FILE: &str = "tmp.lammps.variable";
const UNIVERSE_LOCK: &str = "tmp.lammps.variable.lock";

impl VariableHost for System {
    fn read_file(&mut self, name: &str) -> Result<String, SystemError> {
        self.read(name)
    }

    fn getenv(&mut self, name: &str) -> Option<String> {
        self.overlay_env
            .get(name)
            .cloned()
            .or_else(|| std::env::var(name).ok())
    }

    fn universe_init(&mut self, worlds: usize) -> Result<(), SystemError> {
        self.write(UNIVERSE_FILE, &format!("{worlds}\n"), false)
    }

    fn universe_next(&mut self) -> Result<usize, SystemError> {
        // the same file protocol LIGGGHTS uses, so partitions of either program could share it
        self.rename(UNIVERSE_FILE, UNIVERSE_LOCK);
        let text = self
            .read(UNIVERSE_LOCK)
            .map_err(|e| SystemError::CounterUnreadable(Box::new(e)))?;
        let next: usize = text
            .trim()
            .parse()
            .map_err(|_| SystemError::CounterText(text.trim().to_string()))?;
        self.write(UNIVERSE_LOCK, &format!("{}\n", next + 1), false)?;
        self.rename(UNIVERSE_LOCK, UNIVERSE_FILE);
        Ok(next)
    }
}
