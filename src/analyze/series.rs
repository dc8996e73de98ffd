//! Dump snapshots as the analyses see them: a time series of frames, read one file at a time
//! so that long `*` series of large dumps never sit in memory together.

use super::AnalyzeError;
use crate::io::diff::{expand, read_text};
use crate::io::dump_compare::{parse, Snapshot};

/// One snapshot: rows of per-atom values in ID order.
#[derive(Debug, Clone, PartialEq)]
pub struct Frame {
    /// The timestep.
    pub step: i64,
    /// Simulated time, step x dt (s).
    pub time: f64,
    /// Box bounds, lo/hi per direction (m).
    pub bounds: [[f64; 2]; 3],
    /// Column names.
    pub columns: Vec<String>,
    /// One row per atom, in ID order.
    pub rows: Vec<Vec<f64>>,
}

impl Frame {
    fn from_snapshot(s: Snapshot, dt: f64) -> Frame {
        Frame {
            step: s.step,
            time: s.step as f64 * dt,
            bounds: s.bounds,
            columns: s.columns,
            rows: s.rows.into_values().collect(),
        }
    }

    /// The index of the first of `names` that is a column.
    pub fn opt_col(&self, names: &[&str]) -> Option<usize> {
        names
            .iter()
            .find_map(|n| self.columns.iter().position(|c| c == n))
    }

    /// The index of the first of `names` that is a column; Err naming them all.
    pub fn col(&self, names: &[&str]) -> Result<usize, AnalyzeError> {
        self.opt_col(names)
            .ok_or_else(|| AnalyzeError::MissingColumn {
                step: self.step,
                wanted: names.join(" or "),
                have: self.columns.join(" "),
            })
    }

    /// The indices of x, y, z.
    pub fn xyz(&self) -> Result<[usize; 3], AnalyzeError> {
        Ok([self.col(&["x"])?, self.col(&["y"])?, self.col(&["z"])?])
    }

    /// The indices of fx, fy, fz.
    pub fn force(&self) -> Result<[usize; 3], AnalyzeError> {
        Ok([self.col(&["fx"])?, self.col(&["fy"])?, self.col(&["fz"])?])
    }

    /// The dump as LIGGGHTS writes it (`dump custom`), for tests and tools.
    pub fn to_text(&self) -> String {
        let mut s = format!(
            "ITEM: TIMESTEP\n{}\nITEM: NUMBER OF ATOMS\n{}\nITEM: BOX BOUNDS ff ff ff\n",
            self.step,
            self.rows.len()
        );
        for b in &self.bounds {
            s.push_str(&format!("{} {}\n", b[0], b[1]));
        }
        s.push_str(&format!("ITEM: ATOMS {}\n", self.columns.join(" ")));
        for r in &self.rows {
            let words: Vec<String> = r.iter().map(|v| format!("{v}")).collect();
            s.push_str(&words.join(" "));
            s.push('\n');
        }
        s
    }
}

/// The magnitude of a 3-vector stored in columns `c` of `row`.
pub fn norm(row: &[f64], c: [usize; 3]) -> f64 {
    (row[c[0]].powi(2) + row[c[1]].powi(2) + row[c[2]].powi(2)).sqrt()
}

/// A dump file or `*` series, with the time step that turns steps into seconds.
pub struct Series {
    files: Vec<String>,
    /// A single file is parsed once, up front.
    loaded: Option<Vec<Snapshot>>,
    dt: f64,
}

impl Series {
    /// Open a dump (text or gzip) or a `*` series; `dt` in seconds.
    pub fn open(pattern: &str, dt: f64) -> Result<Series, AnalyzeError> {
        let files = expand(pattern).map_err(|e| AnalyzeError::Read(e.to_string()))?;
        let loaded = if files.len() == 1 {
            Some(read_snapshots(&files[0])?)
        } else {
            None
        };
        Ok(Series { files, loaded, dt })
    }

    /// The steps of the frames, in order (a series: the number in each file name).
    pub fn steps(&self) -> Vec<i64> {
        match &self.loaded {
            Some(snaps) => snaps.iter().map(|s| s.step).collect(),
            None => self.files.iter().map(|f| step_of_name(f)).collect(),
        }
    }

    /// The time step (s).
    pub fn dt(&self) -> f64 {
        self.dt
    }

    /// Call `f` on every frame in order.
    pub fn for_each(
        &self,
        mut f: impl FnMut(Frame) -> Result<(), AnalyzeError>,
    ) -> Result<(), AnalyzeError> {
        if let Some(snaps) = &self.loaded {
            for s in snaps {
                f(Frame::from_snapshot(s.clone(), self.dt))?;
            }
            return Ok(());
        }
        for file in &self.files {
            for s in read_snapshots(file)? {
                f(Frame::from_snapshot(s, self.dt))?;
            }
        }
        Ok(())
    }

    /// Call `f` on the frames at `steps` only (a series reads only those files).
    pub fn for_steps(
        &self,
        steps: &[i64],
        mut f: impl FnMut(Frame) -> Result<(), AnalyzeError>,
    ) -> Result<(), AnalyzeError> {
        if let Some(snaps) = &self.loaded {
            for s in snaps.iter().filter(|s| steps.contains(&s.step)) {
                f(Frame::from_snapshot(s.clone(), self.dt))?;
            }
            return Ok(());
        }
        for file in self
            .files
            .iter()
            .filter(|n| steps.contains(&step_of_name(n)))
        {
            for s in read_snapshots(file)? {
                f(Frame::from_snapshot(s, self.dt))?;
            }
        }
        Ok(())
    }

    /// Every frame, in memory at once (for small dumps).
    pub fn frames(&self) -> Result<Vec<Frame>, AnalyzeError> {
        let mut out = Vec::new();
        self.for_each(|fr| {
            out.push(fr);
            Ok(())
        })?;
        Ok(out)
    }
}

fn read_snapshots(file: &str) -> Result<Vec<Snapshot>, AnalyzeError> {
    let text = read_text(file).map_err(|e| AnalyzeError::Read(e.to_string()))?;
    let snaps = parse(&text).map_err(|m| AnalyzeError::Read(format!("{file}: {m}")))?;
    if snaps.iter().any(|s| s.local) {
        return Err(AnalyzeError::Read(format!(
            "{file}: a dump local file; the analyses read per-atom dumps (dump custom)"
        )));
    }
    Ok(snaps)
}

/// The last run of digits in a file name (0 if none).
fn step_of_name(path: &str) -> i64 {
    let name = path.rsplit('/').next().unwrap_or(path);
    let end = name
        .rfind(|c: char| c.is_ascii_digit())
        .map_or(0, |k| k + 1);
    let start = name[..end]
        .rfind(|c: char| !c.is_ascii_digit())
        .map_or(0, |k| k + 1);
    name[start..end].parse().unwrap_or(0)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn frames_round_trip_and_series_steps() {
        let dir = std::env::temp_dir().join(format!("regolith_series_{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        for step in [0, 50, 100] {
            let fr = Frame {
                step,
                time: 0.0,
                bounds: [[0.0, 1.0]; 3],
                columns: vec!["id".into(), "x".into()],
                rows: vec![vec![1.0, step as f64], vec![2.0, 0.5]],
            };
            std::fs::write(dir.join(format!("d_{step}.dump")), fr.to_text()).unwrap();
        }
        let s = Series::open(&format!("{}/d_*.dump", dir.display()), 1e-3).unwrap();
        assert_eq!(s.steps(), vec![0, 50, 100]);
        let frames = s.frames().unwrap();
        assert_eq!(frames[2].rows[0], vec![1.0, 100.0]);
        assert!((frames[1].time - 0.05).abs() < 1e-15);
        assert!(frames[0].col(&["fx"]).is_err());
        assert_eq!(step_of_name("post/chain_12000.dump.gz"), 12000);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
