//! The interpreter's view of the outside world: files, the working directory, environment
//! variables. In check mode every effect goes to an in-memory overlay, so a dry run of a deck
//! touches nothing on disk yet sees the files the deck itself would have written.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use crate::script::variables::VariableHost;

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
    overlay_binary: HashMap<PathBuf, Vec<u8>>,
    overlay_env: HashMap<String, String>,
}

impl System {
    /// A system rooted at the process's working directory.
    pub fn new(mode: Mode) -> System {
        System {
            mode,
            cwd: std::env::current_dir().unwrap_or_else(|_| PathBuf::from(".")),
            overlay_files: HashMap::new(),
            overlay_binary: HashMap::new(),
            overlay_env: HashMap::new(),
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
    pub fn read(&self, name: &str) -> Result<String, String> {
        let path = self.resolve(name);
        if let Some(entry) = self.overlay_files.get(&path) {
            return entry.clone().ok_or_else(|| format!("{name}: no such file"));
        }
        std::fs::read(&path)
            .map(|b| String::from_utf8_lossy(&b).into_owned())
            .map_err(|e| format!("{name}: {e}"))
    }

    /// Check mode: remember a binary file (a restart) the deck would write.
    pub fn keep_binary(&mut self, path: &Path, bytes: Vec<u8>) {
        self.overlay_binary.insert(path.to_path_buf(), bytes);
    }

    /// Check mode: a binary file the deck wrote earlier, if any.
    pub fn kept_binary(&self, path: &Path) -> Option<&[u8]> {
        self.overlay_binary.get(path).map(Vec::as_slice)
    }

    /// Write (or append to) a text file.
    pub fn write(&mut self, name: &str, text: &str, append: bool) -> Result<(), String> {
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
                    .map_err(|e| format!("{name}: {e}"))?;
                f.write_all(text.as_bytes())
                    .map_err(|e| format!("{name}: {e}"))
            }
            Mode::Check => {
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

    /// `mkdir` with LIGGGHTS's permissions (rwxr-x---); failures are silent.
    pub fn mkdir(&mut self, name: &str) {
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
    pub fn create_parent_dirs(&mut self, name: &str) -> Result<(), String> {
        if self.mode == Mode::Run {
            if let Some(parent) = self.resolve(name).parent() {
                std::fs::create_dir_all(parent)
                    .map_err(|e| format!("{}: {e}", parent.display()))?;
            }
        }
        Ok(())
    }

    /// `rmdir`; failures are silent.
    pub fn rmdir(&mut self, name: &str) {
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

const UNIVERSE_FILE: &str = "tmp.lammps.variable";
const UNIVERSE_LOCK: &str = "tmp.lammps.variable.lock";

impl VariableHost for System {
    fn read_file(&mut self, name: &str) -> Result<String, String> {
        self.read(name)
    }

    fn getenv(&mut self, name: &str) -> Option<String> {
        self.overlay_env
            .get(name)
            .cloned()
            .or_else(|| std::env::var(name).ok())
    }

    fn universe_init(&mut self, worlds: usize) -> Result<(), String> {
        self.write(UNIVERSE_FILE, &format!("{worlds}\n"), false)
    }

    fn universe_next(&mut self) -> Result<usize, String> {
        // the same file protocol LIGGGHTS uses, so partitions of either program could share it
        self.rename(UNIVERSE_FILE, UNIVERSE_LOCK);
        let text = self
            .read(UNIVERSE_LOCK)
            .map_err(|e| format!("universe counter: {e}"))?;
        let next: usize = text
            .trim()
            .parse()
            .map_err(|_| format!("universe counter holds '{}'", text.trim()))?;
        self.write(UNIVERSE_LOCK, &format!("{}\n", next + 1), false)?;
        self.rename(UNIVERSE_LOCK, UNIVERSE_FILE);
        Ok(next)
    }
}
