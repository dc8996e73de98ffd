//! Files regolith writes and reads: dumps (and, later, logs, restarts and data files).

pub mod convert;
pub mod data;
pub mod diff;
pub mod dump;
pub mod dump_compare;
pub mod error;
pub mod local_vtk;
pub mod local_vtk_xml;
pub mod mesh_vtk;
pub mod output;
pub mod restart;
pub mod restart_error;
pub mod restart_values;
pub mod stl;
pub mod vtk;

/// Write `bytes` to `path` so that a reader (or a crash, or a kill) never sees a half-written
/// file under that name: a regular file (or a new one) is written as a temporary file beside
/// it and renamed over it. The temporary file is named `.NAME.regolith-tmp.PID`; it is removed
/// when the write fails (a full disk), and one left behind by a killed run (its process gone)
/// is removed by the next write of the same name.
///
/// Anything else is written in place, never replaced: a device (`/dev/null`), a named pipe, a
/// socket. A symbolic link stays a link: its target is written (renamed over if it is a
/// regular file, created if the link dangles), so the link sees the new contents.
pub fn write_atomically(path: &str, bytes: &[u8]) -> std::io::Result<()> {
    let target = resolve_links(std::path::Path::new(path))?;
    if let Ok(meta) = std::fs::metadata(&target) {
        if !meta.is_file() {
            if meta.is_dir() {
                return Err(std::io::Error::other("is a directory"));
            }
            return write_in_place(&target, bytes);
        }
    }
    remove_stale_temps(&target);
    let tmp = temp_name(&target, std::process::id());
    let result = std::fs::write(&tmp, bytes).and_then(|()| std::fs::rename(&tmp, &target));
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result
}

/// The temporary file a write of `target` by process `pid` goes through.
pub fn temp_name(target: &std::path::Path, pid: u32) -> std::path::PathBuf {
    let name = target
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    target.with_file_name(format!(".{name}{TEMP_MARK}{pid}"))
}

/// What marks regolith's temporary files (between the name and the process ID).
pub const TEMP_MARK: &str = ".regolith-tmp.";

/// Follow symbolic links from `path` to the file they finally name (which may not exist yet);
/// a relative link target is taken from the link's folder.
fn resolve_links(path: &std::path::Path) -> std::io::Result<std::path::PathBuf> {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => {
                let link = std::fs::read_link(&p)?;
                p = match p.parent() {
                    Some(dir) if link.is_relative() => dir.join(link),
                    _ => link,
                };
            }
            _ => return Ok(p),
        }
    }
    Err(std::io::Error::other("too many levels of symbolic links"))
}

/// Write into an existing file that is not a regular one (a device, a pipe), without
/// replacing it.
fn write_in_place(path: &std::path::Path, bytes: &[u8]) -> std::io::Result<()> {
    use std::io::Write;
    let mut f = std::fs::OpenOptions::new().write(true).open(path)?;
    f.write_all(bytes)?;
    f.flush()
}

/// Remove temporary files of `target` left by processes that no longer run (a killed run).
fn remove_stale_temps(target: &std::path::Path) {
    let Some(name) = target.file_name().map(|n| n.to_string_lossy().into_owned()) else {
        return;
    };
    let dir = match target.parent() {
        Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
        _ => std::path::PathBuf::from("."),
    };
    let prefix = format!(".{name}{TEMP_MARK}");
    let Ok(entries) = std::fs::read_dir(&dir) else {
        return;
    };
    for e in entries.flatten() {
        let file = e.file_name();
        let Some(pid) = file
            .to_str()
            .and_then(|f| f.strip_prefix(&prefix))
            .and_then(|p| p.parse::<u32>().ok())
        else {
            continue;
        };
        if pid == std::process::id() || !process_alive(pid) {
            let _ = std::fs::remove_file(e.path());
        }
    }
}

/// Whether a process with this ID runs (or exists at all, as a zombie or another user's).
fn process_alive(pid: u32) -> bool {
    let Ok(pid) = libc::pid_t::try_from(pid) else {
        return false;
    };
    if pid <= 0 {
        return false;
    }
    // SAFETY: signal 0 only asks whether the process exists
    let r = unsafe { libc::kill(pid, 0) };
    r == 0 || std::io::Error::last_os_error().raw_os_error() == Some(libc::EPERM)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A folder for one test, removed when the test ends.
    struct Scratch(std::path::PathBuf);

    impl std::ops::Deref for Scratch {
        type Target = std::path::Path;
        fn deref(&self) -> &std::path::Path {
            &self.0
        }
    }

    impl AsRef<std::path::Path> for Scratch {
        fn as_ref(&self) -> &std::path::Path {
            &self.0
        }
    }

    impl Drop for Scratch {
        fn drop(&mut self) {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }

    fn scratch(name: &str) -> Scratch {
        let d = std::env::temp_dir().join(format!("regolith-io-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        Scratch(d)
    }

    #[test]
    fn regular_files_are_replaced_and_temps_named_and_cleaned() {
        let d = scratch("regular");
        let f = d.join("out.data");
        std::fs::write(&f, "old").unwrap();
        // a temp of a dead process (pid 2^22 + 1 is beyond Linux's pid_max default)
        let stale = temp_name(&f, 4_194_305);
        std::fs::write(&stale, "half").unwrap();
        write_atomically(f.to_str().unwrap(), b"new").unwrap();
        assert_eq!(std::fs::read(&f).unwrap(), b"new");
        assert!(!stale.exists(), "stale temp left");
        let left: Vec<_> = std::fs::read_dir(&d).unwrap().flatten().collect();
        assert_eq!(left.len(), 1, "{left:?}");
        assert_eq!(
            temp_name(&f, 42).file_name().unwrap(),
            ".out.data.regolith-tmp.42"
        );
    }

    #[test]
    fn a_failed_write_leaves_no_temp() {
        let d = scratch("failed");
        // the target's folder does not exist: the temp cannot be made, nothing is left
        let f = d.join("missing").join("x.data");
        assert!(write_atomically(f.to_str().unwrap(), b"x").is_err());
        // a directory is not replaced
        std::fs::create_dir(d.join("adir")).unwrap();
        assert!(write_atomically(d.join("adir").to_str().unwrap(), b"x").is_err());
        let left: Vec<_> = std::fs::read_dir(&d)
            .unwrap()
            .flatten()
            .map(|e| e.file_name())
            .collect();
        assert_eq!(left.len(), 1, "{left:?}");
    }

    /// A character device like /dev/null in `dir` (None without the right to make one): the
    /// tests write to it rather than to the real /dev/null, which a regression would replace.
    fn null_device(dir: &std::path::Path) -> Option<std::path::PathBuf> {
        let path = dir.join("null");
        let c = std::ffi::CString::new(path.to_str()?).ok()?;
        // SAFETY: mknod reads the NUL-terminated name only
        let made = unsafe { libc::mknod(c.as_ptr(), libc::S_IFCHR | 0o666, libc::makedev(1, 3)) };
        (made == 0).then_some(path)
    }

    #[test]
    fn special_files_are_written_in_place() {
        let d = scratch("links");
        if let Some(dev) = null_device(&d) {
            write_atomically(dev.to_str().unwrap(), b"nothing").unwrap();
            assert!(std::fs::metadata(&dev)
                .unwrap()
                .file_type()
                .is_char_device());
        }
        let target = d.join("real.data");
        std::fs::write(&target, "old").unwrap();
        let link = d.join("link.data");
        std::os::unix::fs::symlink("real.data", &link).unwrap();
        write_atomically(link.to_str().unwrap(), b"new").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read(&target).unwrap(), b"new");
        // a dangling link: its target is created
        let dangling = d.join("dangling.data");
        std::os::unix::fs::symlink("made.data", &dangling).unwrap();
        write_atomically(dangling.to_str().unwrap(), b"made").unwrap();
        assert_eq!(std::fs::read(d.join("made.data")).unwrap(), b"made");
        assert!(std::fs::symlink_metadata(&dangling)
            .unwrap()
            .file_type()
            .is_symlink());
    }

    #[test]
    fn a_named_pipe_is_written_not_replaced() {
        let d = scratch("fifo");
        let fifo = d.join("pipe");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: mkfifo reads the NUL-terminated name only
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || std::fs::read(fifo).unwrap())
        };
        write_atomically(fifo.to_str().unwrap(), b"through the pipe").unwrap();
        assert_eq!(reader.join().unwrap(), b"through the pipe");
        assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
    }

    use std::os::unix::fs::FileTypeExt;
}
