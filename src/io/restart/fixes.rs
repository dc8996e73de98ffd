//! Section 5, the fixes: the global state of each fix that keeps one (its bytes are the
//! fix's own) and the list of fixes that add a block to every atom record.

use super::read::Reader;
use super::write::{put_int, put_string};
use super::{Restart, RestartError};

/// A fix's global restart state.
#[derive(Debug, Clone, PartialEq)]
pub struct GlobalFix {
    /// Fix ID.
    pub id: String,
    /// Fix style.
    pub style: String,
    /// The fix's bytes.
    pub state: Vec<u8>,
}

/// A fix that stores values with every atom.
#[derive(Debug, Clone, PartialEq)]
pub struct PeratomFix {
    /// Fix ID.
    pub id: String,
    /// Fix style.
    pub style: String,
    /// Largest per-atom block (doubles, length included).
    pub maxsize: i32,
}

impl Restart {
    /// Section 5, the fixes' global states and the list of per-atom states; gives the
    /// per-atom count.
    pub(super) fn read_fixes(&mut self, r: &mut Reader) -> Result<usize, RestartError> {
        let nglobal = r.count("count of fixes with global state", 4096)?;
        for _ in 0..nglobal {
            let id = r.string()?;
            let style = r.string()?;
            let n = r.count("fix state size", 1 << 30)?;
            let state = r.take(n, "fix state")?.to_vec();
            self.global_fixes.push(GlobalFix { id, style, state });
        }
        let nperatom = r.count("count of fixes with per-atom state", 4096)?;
        for _ in 0..nperatom {
            let id = r.string()?;
            let style = r.string()?;
            let maxsize = r.i32()?;
            self.peratom_fixes.push(PeratomFix { id, style, maxsize });
        }
        Ok(nperatom)
    }

    /// Section 5 as [`Restart::read_fixes`] reads it.
    pub(super) fn write_fixes(&self, b: &mut Vec<u8>) {
        put_int(b, self.global_fixes.len() as i32);
        for f in &self.global_fixes {
            put_string(b, &f.id);
            put_string(b, &f.style);
            put_int(b, f.state.len() as i32);
            b.extend_from_slice(&f.state);
        }
        put_int(b, self.peratom_fixes.len() as i32);
        for f in &self.peratom_fixes {
            put_string(b, &f.id);
            put_string(b, &f.style);
            put_int(b, f.maxsize);
        }
    }
}
