//! The cross-check of the Jacobi importers: the largest difference between two results CSVs.

use anyhow::{bail, Context, Result};
use std::collections::HashMap;
use std::path::Path;

/// The largest absolute difference over the columns both files have, on the rows of the same
/// time (matched to 1 ns), and how many values were compared. Cells that are empty in either
/// file (crane-cosim leaves outputs that are not defined yet empty at t0) are skipped.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Difference {
    /// The largest absolute difference.
    pub max_abs: f64,
    /// How many values were compared.
    pub values: usize,
}

pub fn max_difference(a: &Path, b: &Path) -> Result<Difference> {
    let read = |p: &Path| std::fs::read_to_string(p).with_context(|| format!("reading {}", p.display()));
    difference(&read(a)?, &read(b)?).with_context(|| format!("comparing {} with {}", a.display(), b.display()))
}

/// [`max_difference`] on the texts of two CSVs with a `time` column.
pub fn difference(a: &str, b: &str) -> Result<Difference> {
    let (a, b) = (Table::parse(a)?, Table::parse(b)?);
    let shared: Vec<(usize, usize)> = a
        .columns
        .iter()
        .enumerate()
        .filter(|(_, name)| name.as_str() != "time")
        .filter_map(|(i, name)| b.columns.iter().position(|n| n == name).map(|j| (i, j)))
        .collect();
    let b_rows: HashMap<i64, &Vec<Option<f64>>> = b.rows.iter().map(|row| (nanoseconds(row[b.time]), row)).collect();
    let mut result = Difference { max_abs: 0.0, values: 0 };
    for row in &a.rows {
        let Some(other) = b_rows.get(&nanoseconds(row[a.time])) else { continue };
        for &(i, j) in &shared {
            if let (Some(x), Some(y)) = (row[i], other[j]) {
                // NaN compares as no difference with `max`: count it as infinitely different.
                let d = if x.is_nan() || y.is_nan() { f64::INFINITY } else { (x - y).abs() };
                result.max_abs = result.max_abs.max(d);
                result.values += 1;
            }
        }
    }
    if result.values == 0 {
        bail!("no values in common (columns or times differ)");
    }
    Ok(result)
}

fn nanoseconds(time: Option<f64>) -> i64 {
    time.map_or(i64::MIN, |t| (t * 1e9).round() as i64)
}

struct Table {
    columns: Vec<String>,
    time: usize,
    rows: Vec<Vec<Option<f64>>>,
}

impl Table {
    /// Parses with the csv crate (quoted names, trimmed cells); a row whose length differs
    /// from the header's is an error.
    fn parse(text: &str) -> Result<Table> {
        let mut reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(text.as_bytes());
        let columns: Vec<String> = reader.headers()?.iter().map(str::to_string).collect();
        let Some(time) = columns.iter().position(|c| c == "time") else { bail!("no 'time' column") };
        let rows = reader
            .records()
            .map(|record| {
                record?
                    .iter()
                    .map(|c| match c {
                        "" => Ok(None),
                        c => c.parse().map(Some).with_context(|| format!("'{c}' is not a number")),
                    })
                    .collect()
            })
            .collect::<Result<_>>()?;
        Ok(Table { columns, time, rows })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rows_are_matched_by_time_and_columns_by_name() {
        // b has its columns in another order, no row at t0 and an extra row; the only
        // difference is y at 0.02 (3e-15).
        let a = "time,x,y\n0.0,1,\n0.01,2,5\n0.02,3,0.1\n";
        let b = "time,y,x,z\n0.01,5,2,9\n0.02,0.100000000000003,3,9\n0.03,7,7,9\n";
        let d = difference(a, b).unwrap();
        assert!((d.max_abs - 3e-15).abs() < 1e-17, "{}", d.max_abs);
        assert_eq!(d.values, 4);
    }

    #[test]
    fn nan_is_a_difference_and_nothing_in_common_is_an_error() {
        assert_eq!(difference("time,x\n0.01,NaN\n", "time,x\n0.01,1\n").unwrap().max_abs, f64::INFINITY);
        assert!(difference("time,x\n0.01,1\n", "time,y\n0.01,1\n").is_err());
        assert!(difference("time,x\n0.01,1,2\n", "time,x\n0.01,1\n").is_err(), "a ragged row");
    }
}
