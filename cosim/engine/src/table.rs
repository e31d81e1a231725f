//! Tables of sampled signals by name: input CSVs, results CSVs and in-memory recordings.

use std::path::{Path, PathBuf};

/// A problem with a CSV table (an input or a results file). Each variant names the file.
#[derive(Debug, thiserror::Error)]
pub enum TableError {
    #[error("{}: cannot read", file.display())]
    Read {
        file: PathBuf,
        #[source]
        source: csv::Error,
    },
    #[error("{}: {message}", file.display())]
    Header { file: PathBuf, message: String },
    #[error("{}: line {line}: {message}", file.display())]
    Row { file: PathBuf, line: u64, message: String },
}

/// A table of sampled signals: `times[i]` and `columns[j][i]`.
///
/// File format (FMPy / FMI cross-check compatible): a header
/// `time,<name>,<name>,...` (names may be quoted), then one row per sample,
/// times in seconds and non-decreasing; a repeated time marks a
/// discontinuity. Values are decimal numbers; `nan` and `inf` are accepted
/// (the FMU decides whether it can take them).
#[derive(Debug, Clone, PartialEq)]
pub struct SignalTable {
    pub file: PathBuf,
    /// Column names without `time`.
    pub names: Vec<String>,
    pub times: Vec<f64>,
    /// One vector per name, same length as `times`.
    pub columns: Vec<Vec<f64>>,
}

impl SignalTable {
    /// Reads and checks a CSV file (a regular file of at most
    /// [`MAX_TABLE_FILE_BYTES`](fmu_import::file::MAX_TABLE_FILE_BYTES)).
    pub fn read(file: &Path) -> Result<Self, TableError> {
        let bytes = fmu_import::file::read_regular(file, fmu_import::file::MAX_TABLE_FILE_BYTES)
            .map_err(|source| TableError::Read { file: file.to_path_buf(), source: source.into() })?;
        let reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(bytes.as_slice());
        Self::from_reader(reader, file)
    }

    /// Parses CSV text (`file` is only used in messages).
    pub fn parse(text: &str, file: &Path) -> Result<Self, TableError> {
        let reader = csv::ReaderBuilder::new().trim(csv::Trim::All).from_reader(text.as_bytes());
        Self::from_reader(reader, file)
    }

    fn from_reader<R: std::io::Read>(mut reader: csv::Reader<R>, file: &Path) -> Result<Self, TableError> {
        let read_error = |source| TableError::Read { file: file.to_path_buf(), source };
        let header_error = |message: String| TableError::Header { file: file.to_path_buf(), message };
        let header = reader.headers().map_err(read_error)?.clone();
        let mut fields = header.iter();
        match fields.next() {
            Some("time") => {}
            Some(first) => return Err(header_error(format!("the first column must be \"time\", not {first:?}"))),
            None => return Err(header_error("the file is empty; expected a header time,<variable>,...".into())),
        }
        let names: Vec<String> = fields.map(String::from).collect();
        for (index, name) in names.iter().enumerate() {
            if name.is_empty() {
                return Err(header_error(format!("column {} has an empty name", index + 2)));
            }
            if name == "time" || names[..index].contains(name) {
                return Err(header_error(format!("column {name:?} appears twice")));
            }
        }

        let mut times = Vec::new();
        let mut columns = vec![Vec::new(); names.len()];
        for record in reader.records() {
            let record = record.map_err(read_error)?;
            let line = record.position().map_or(0, |p| p.line());
            let row_error = |message: String| TableError::Row { file: file.to_path_buf(), line, message };
            let mut values = record.iter().enumerate().map(|(index, text)| {
                let column = if index == 0 { "time" } else { names.get(index - 1).map_or("?", String::as_str) };
                text.parse::<f64>().map_err(|_| row_error(format!("{column}: {text:?} is not a number")))
            });
            let time = match values.next() {
                Some(time) => time?,
                None => return Err(row_error("empty row".into())),
            };
            if !time.is_finite() {
                return Err(row_error(format!("time {time:?} is not finite")));
            }
            if let Some(&previous) = times.last() {
                if time < previous {
                    return Err(row_error(format!(
                        "time {time:?} is before the previous row's {previous:?}; rows must be sorted by time"
                    )));
                }
            }
            times.push(time);
            for (column, value) in columns.iter_mut().zip(values) {
                column.push(value?);
            }
        }
        if times.is_empty() {
            return Err(header_error("no data rows".into()));
        }
        Ok(Self { file: file.to_path_buf(), names, times, columns })
    }

    /// Index of the column `name`.
    pub fn column(&self, name: &str) -> Option<usize> {
        self.names.iter().position(|n| n == name)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(text: &str) -> Result<SignalTable, TableError> {
        SignalTable::parse(text, Path::new("in.csv"))
    }

    #[test]
    fn reads_fmpy_style_files() {
        let table = parse("\"time\",\"tip.x\",lp\n0,0.5,0.7\n1, 1.5 ,nan\n1,2,inf\n").expect("valid");
        assert_eq!(table.names, ["tip.x", "lp"]);
        assert_eq!(table.times, [0.0, 1.0, 1.0]);
        assert_eq!(table.columns[0], [0.5, 1.5, 2.0]);
        assert!(table.columns[1][1].is_nan() && table.columns[1][2].is_infinite());
        assert_eq!(table.column("lp"), Some(1));
    }

    #[test]
    fn refuses_bad_files_with_position() {
        let cases = [
            ("t,x\n0,1\n", "first column must be \"time\""),
            ("", "empty"),
            ("time,x,x\n0,1,2\n", "\"x\" appears twice"),
            ("time,x\n", "no data rows"),
            ("time,x\n0,1\n1,abc\n", "line 3: x: \"abc\" is not a number"),
            ("time,x\n1,1\n0,2\n", "line 3: time 0.0 is before"),
            ("time,x\n0,1\n1\n", "in.csv"),
            ("time,x\nnan,1\n", "not finite"),
        ];
        for (text, expected) in cases {
            let message = parse(text).expect_err(text).to_string();
            assert!(message.contains(expected) && message.contains("in.csv"), "{text:?}: {message}");
        }
    }
}
