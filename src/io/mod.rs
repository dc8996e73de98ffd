//! Files regolith writes and reads: dumps (and, later, logs, restarts and data files).

pub mod convert;
pub mod data;
pub mod diff;
pub mod dump;
pub mod dump_compare;
pub mod mesh_vtk;
pub mod restart;
pub mod stl;
pub mod vtk;

/// Write `bytes` to `path` through a temporary file in the same folder and a rename, so a
/// reader (or a crash) never sees a half-written file.
pub fn write_atomically(path: &str, bytes: &[u8]) -> std::io::Result<()> {
    let tmp = format!("{path}.tmp{}", std::process::id());
    std::fs::write(&tmp, bytes)?;
    std::fs::rename(&tmp, path).inspect_err(|_| {
        let _ = std::fs::remove_file(&tmp);
    })
}
