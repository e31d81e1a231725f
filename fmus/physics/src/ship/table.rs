//! Ship motion read from a CSV file (profile 5 of the platform, SPEC §4.1).
//!
//! Format: one sample per line, seven comma-separated numbers: time (s), surge, sway, heave (m;
//! W, heave positive down), roll, pitch, yaw (rad; Z–Y–X). Blank lines and lines starting with
//! `#` are skipped; the first remaining line may be a header (any field that is not a number
//! makes it one). Times must increase strictly; at least two samples. Each degree of freedom is
//! interpolated by a natural cubic spline, so velocity and acceleration exist (continuous); before
//! the first and after the last sample the end values are held.

use super::spline::CubicSpline;
use crate::motion::DeckMotion;
use serde::{Deserialize, Serialize};
use std::path::{Path, PathBuf};

/// Column names of the file, in order.
pub const COLUMNS: [&str; 7] = ["time", "surge", "sway", "heave", "roll", "pitch", "yaw"];

/// Deck motion interpolated from samples.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct MotionTable {
    splines: Vec<CubicSpline>,
}

impl MotionTable {
    /// Parses the CSV text (see the module documentation). Errors name the line.
    pub fn parse(text: &str) -> Result<MotionTable, String> {
        let mut columns: [Vec<f64>; 7] = Default::default();
        let mut first = true;
        for (index, raw) in text.lines().enumerate() {
            let line = raw.trim();
            let number = index + 1;
            if line.is_empty() || line.starts_with('#') {
                continue;
            }
            let fields: Vec<&str> = line.split(',').map(str::trim).collect();
            let values: Vec<Option<f64>> = fields.iter().map(|f| f.parse::<f64>().ok()).collect();
            if std::mem::take(&mut first) && values.iter().any(Option::is_none) {
                continue; // header
            }
            if fields.len() != COLUMNS.len() {
                return Err(format!(
                    "line {number}: expected {} comma-separated columns ({}), found {}",
                    COLUMNS.len(),
                    COLUMNS.join(", "),
                    fields.len()
                ));
            }
            for ((column, value), (field, name)) in columns.iter_mut().zip(&values).zip(fields.iter().zip(COLUMNS)) {
                match value {
                    Some(v) if v.is_finite() => column.push(*v),
                    _ => return Err(format!("line {number}: {name} = {field:?} is not a finite number")),
                }
            }
            let t = &columns[0];
            if t.len() >= 2 && !(t[t.len() - 1] > t[t.len() - 2]) {
                return Err(format!(
                    "line {number}: time {} does not increase (previous {})",
                    t[t.len() - 1],
                    t[t.len() - 2]
                ));
            }
        }
        let [time, dofs @ ..] = columns;
        if time.len() < 2 {
            return Err(format!("at least 2 samples are needed, found {}", time.len()));
        }
        let splines = dofs.into_iter().map(|y| CubicSpline::natural(time.clone(), y)).collect::<Result<Vec<_>, _>>()?;
        Ok(MotionTable { splines })
    }

    /// Reads and parses the file at `path`; errors name the file.
    pub fn load(path: &Path) -> Result<MotionTable, String> {
        let text =
            std::fs::read_to_string(path).map_err(|e| format!("cannot read motion file {}: {e}", path.display()))?;
        MotionTable::parse(&text).map_err(|e| format!("motion file {}: {e}", path.display()))
    }

    /// The time span covered by the samples (s).
    pub fn span(&self) -> (f64, f64) {
        self.splines[0].span()
    }

    /// The interpolated deck motion at time `t` (s).
    pub fn sample(&self, t: f64) -> DeckMotion {
        let mut m = DeckMotion::default();
        for (axis, spline) in m.dof.iter_mut().zip(&self.splines) {
            *axis = spline.eval(t);
        }
        m
    }
}

/// `file` as given if absolute, else relative to `resource_dir` (the FMU's resources folder) when
/// there is one.
pub fn resolve_path(file: &str, resource_dir: Option<&Path>) -> PathBuf {
    let path = Path::new(file);
    match resource_dir {
        Some(dir) if path.is_relative() => dir.join(path),
        _ => path.to_path_buf(),
    }
}

/// A short recorded deck motion in this format, with a comment and a blank line (for tests).
#[cfg(test)]
pub(super) const RECORDED_DECK: &str = "# recorded deck motion\n\
time,surge,sway,heave,roll,pitch,yaw\n\
0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0\n\
\n\
0.5, 0.01, -0.02, 0.005, 0.01, -0.01, 0.001\n\
1.0, 0.02, -0.01, 0.0, 0.02, 0.0, 0.002\n\
1.5, 0.01, 0.0, -0.005, 0.01, 0.01, 0.001\n";

#[cfg(test)]
mod tests;
