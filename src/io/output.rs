//! The screen and the log a run writes to (LIGGGHTS's `screen` and `logfile`), each
//! optional; a failed write is reported once and the run goes on.

use std::io::Write;

/// Where screen and log text go, and which of them echo input lines.
pub struct Output {
    /// The screen (standard output, a file, or nothing for `-screen none`).
    pub screen: Option<Box<dyn Write>>,
    /// The log file (nothing for `-log none`).
    pub log: Option<Box<dyn Write>>,
    /// Echo input lines to the screen.
    pub echo_screen: bool,
    /// Echo input lines to the log.
    pub echo_log: bool,
    /// The first failed write to the screen and to the log (a full disk, a closed pipe):
    /// reported once on standard error when it happens, and again at the end.
    pub write_errors: [Option<String>; 2],
    /// Text LIGGGHTS prints with `printf` goes to standard output itself, not through the
    /// screen (set when the screen is a file or `none`).
    pub stdout_apart: bool,
}

impl Output {
    /// Output that goes nowhere (used by check mode).
    pub fn silent() -> Output {
        Output {
            screen: None,
            log: None,
            echo_screen: false,
            echo_log: false,
            write_errors: [None, None],
            stdout_apart: false,
        }
    }

    /// Remember (and report once) a failed write to stream `k` (0 screen, 1 log).
    pub fn failed(&mut self, k: usize, e: std::io::Error) {
        if self.write_errors[k].is_none() {
            let what = ["the screen output", "the log file"][k];
            let _ = writeln!(
                std::io::stderr(),
                "WARNING: writing {what} failed: {e}; it is incomplete from here on"
            );
            self.write_errors[k] = Some(format!("writing {what} failed: {e}"));
        }
    }

    /// Write `text` to the screen.
    pub fn screen(&mut self, text: &str) {
        if let Some(s) = self.screen.as_mut() {
            if let Err(e) = s.write_all(text.as_bytes()) {
                self.failed(0, e);
            }
        }
    }

    /// Write `text` to the log.
    pub fn log(&mut self, text: &str) {
        if let Some(l) = self.log.as_mut() {
            if let Err(e) = l.write_all(text.as_bytes()) {
                self.failed(1, e);
            }
        }
    }

    /// Write `text` to standard output, as LIGGGHTS's `printf` does: through the screen
    /// when the screen is standard output, else directly (neither to a screen file nor to
    /// the log).
    pub fn stdout(&mut self, text: &str) {
        if self.stdout_apart {
            let _ = std::io::stdout().write_all(text.as_bytes());
        } else {
            self.screen(text);
        }
    }

    /// Write `text` to both screen and log.
    pub fn both(&mut self, text: &str) {
        self.screen(text);
        self.log(text);
    }

    /// Write the engine's text of a run's setup and steps: most lines to both streams, but
    /// those LIGGGHTS prints on the screen only (an insertion's progress, a region's
    /// random generator reset) to the screen, the insertion-rate line to the log with
    /// the comma LIGGGHTS's log version of it has, and `modify_timing verbose`'s per-process
    /// fix lines to the log with one leading space where the screen's have two.
    pub fn engine_text(&mut self, text: &str) {
        for line in text.split_inclusive('\n') {
            if line.starts_with("  [0] Fix ") {
                self.screen(line);
                self.log(&line[1..]);
            } else if line.starts_with("insertion: proc ")
                || line.starts_with("INFO: Resetting random generator for region ")
            {
                self.screen(line);
            } else if line.starts_with("INFO: Particle insertion ")
                && line.contains(" - particle rate ")
            {
                self.screen(line);
                self.log(&line.replacen("  (mass rate ", ", (mass rate ", 1));
            } else {
                self.both(line);
            }
        }
    }

    /// Echo an input line where `echo` says.
    pub fn echo(&mut self, text: &str) {
        if self.echo_screen {
            self.screen(&format!("{text}\n"));
        }
        if self.echo_log {
            self.log(&format!("{text}\n"));
        }
    }

    /// Flush both streams.
    pub fn flush(&mut self) {
        if let Some(Err(e)) = self.screen.as_mut().map(|s| s.flush()) {
            self.failed(0, e);
        }
        if let Some(Err(e)) = self.log.as_mut().map(|l| l.flush()) {
            self.failed(1, e);
        }
    }
}
