//! CSV tables: a header row naming each column with its unit, then numbers.

use std::path::Path;

use super::AnalyzeError;

/// A table to be written as CSV.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Table {
    header: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Table {
    /// A table with these column names (units in the names, e.g. `t_s`).
    pub fn new(header: &[&str]) -> Table {
        Table {
            header: header.iter().map(|h| h.to_string()).collect(),
            rows: Vec::new(),
        }
    }

    /// Append a row of numbers.
    pub fn push(&mut self, row: &[f64]) {
        self.rows.push(row.iter().map(|v| format!("{v}")).collect());
    }

    /// Append a row of words (labels, numbers already formatted).
    pub fn push_words(&mut self, row: Vec<String>) {
        self.rows.push(row);
    }

    /// The CSV text.
    pub fn to_csv(&self) -> String {
        let mut s = self.header.join(",");
        s.push('\n');
        for r in &self.rows {
            s.push_str(&r.join(","));
            s.push('\n');
        }
        s
    }

    /// Write the CSV file.
    pub fn write(&self, path: &Path) -> Result<(), AnalyzeError> {
        crate::io::write_atomically(&path.to_string_lossy(), self.to_csv().as_bytes()).map_err(
            |e| AnalyzeError::Write {
                path: path.display().to_string(),
                message: e.to_string(),
            },
        )
    }
}

/// Create the output folder.
pub fn ensure_dir(dir: &Path) -> Result<(), AnalyzeError> {
    std::fs::create_dir_all(dir).map_err(|e| AnalyzeError::Write {
        path: dir.display().to_string(),
        message: e.to_string(),
    })
}

#[cfg(test)]
mod tests {
    #[test]
    fn csv_text() {
        let mut t = super::Table::new(&["t_s", "y_m"]);
        t.push(&[0.5, 1e-3]);
        t.push_words(vec!["a".into(), "b".into()]);
        assert_eq!(t.to_csv(), "t_s,y_m\n0.5,0.001\na,b\n");
    }
}
