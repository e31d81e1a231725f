//! The recorder's numbers read back bit-exactly, written as Rust's `{:?}` writes them; the table
//! recorder holds what the CSV reads back as.

use fmu_import::fmu::Causality;
use fmu_import::value::Value;

use super::inputs::real_input;
use super::mock::{Journal, Law, Mock};
use crate::algorithm::{algorithm, AlgorithmKind, Wiring};
use crate::execution::Execution;
use crate::observer::{CsvRecorder, TableRecorder};
use crate::table::SignalTable;
use crate::time::TimeGrid;
use crate::variable::VariableRef;

/// Values whose text is easy to get wrong: non-finite, signed zero, subnormals, the notation
/// boundaries (1e-5, 1e-4, 1e16), and integers beyond what an f32 or a 53-bit mantissa shows.
const VALUES: [f64; 18] = [
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    -0.0,
    5e-324,
    -2.225073858507201e-308,
    1e-7,
    1.5e-5,
    -9.999999999999999e-5,
    1e-4,
    0.1,
    0.30000000000000004,
    1e16,
    9007199254740992.0,
    9007199254740994.0,
    123456789012.0,
    -1.7976931348623157e308,
    2.5,
];

/// Outputs `m.v<i>` of instance 0 with value reference `i`.
fn outputs(count: usize) -> Vec<VariableRef> {
    (0..count)
        .map(|i| VariableRef {
            instance: 0,
            qualified_name: format!("m.v{i}"),
            variable: fmu_import::fmu::ScalarVariable {
                causality: Causality::Output,
                ..real_input(&format!("v{i}"), i as u32)
            },
        })
        .collect()
}

/// A Gauss–Seidel run from 0 to `stop` in steps of `step` of one mock `m` whose outputs `v<i>`
/// start at [`VALUES`], the ones in `ramps` then ramping (`Law::Ramps`).
fn values_run(stop: f64, step: f64, ramps: &'static [u32], journal: &Journal) -> Execution {
    let start = VALUES.iter().enumerate().map(|(i, &v)| (i as u32, Value::Real(v))).collect();
    let grid = TimeGrid::new(0.0, stop, step).expect("grid");
    let mut execution = Execution::new(grid, stop, algorithm(AlgorithmKind::GaussSeidel, Wiring::new(1)));
    execution.add_simulator(Box::new(Mock::new("m", Law::Ramps(ramps), journal)), start);
    execution
}

#[test]
fn recorded_numbers_read_back_bit_exactly() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("values.csv");
    let variables = outputs(VALUES.len());
    let journal = Journal::default();
    let mut execution = values_run(1e-5, 1e-5, &[], &journal);
    execution.add_observer(Box::new(CsvRecorder::create(&file, &variables, 1).expect("recorder")));
    execution.run().expect("run");
    execution.finish_observers().expect("flush");

    let text = std::fs::read_to_string(&file).expect("csv");
    let lines: Vec<&str> = text.lines().collect();
    assert_eq!(lines.len(), 3, "header and the rows of t = 0 and t = 1e-5");
    let expected: Vec<String> = VALUES.iter().map(|v| format!("{v:?}")).collect();
    assert_eq!(lines[2], format!("1e-5,{}", expected.join(",")));

    let table = SignalTable::read(&file).expect("the results read back");
    assert_eq!(table.times, [0.0, 1e-5]);
    for (column, value) in table.columns.iter().zip(VALUES) {
        for read in column {
            assert!(read.to_bits() == value.to_bits() || (read.is_nan() && value.is_nan()), "{read:?} != {value:?}");
        }
    }
}

/// Bits of every value of a table (NaN != NaN would hide equal tables from `==`).
fn bits(table: &SignalTable) -> (Vec<String>, Vec<u64>, Vec<Vec<u64>>) {
    let column_bits = |c: &Vec<f64>| c.iter().map(|v| v.to_bits()).collect();
    (
        table.names.clone(),
        table.times.iter().map(|t| t.to_bits()).collect(),
        table.columns.iter().map(column_bits).collect(),
    )
}

#[test]
fn the_table_recorder_holds_what_the_csv_recorder_reads_back_as() {
    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("values.csv");
    // Ramps v_i = i·t after the start values: rows of different values, every second row kept.
    let variables = outputs(VALUES.len());
    let journal = Journal::default();
    let mut execution = values_run(0.5, 0.1, &[1, 2, 10, 17], &journal);
    let table = std::rc::Rc::new(std::cell::RefCell::new(TableRecorder::new(&file, &variables, 2).expect("reals")));
    execution.add_observer(Box::new(std::rc::Rc::clone(&table)));
    execution.add_observer(Box::new(CsvRecorder::create(&file, &variables, 2).expect("recorder")));
    execution.run().expect("run");
    execution.finish_observers().expect("flush");
    drop(execution);

    let recorded = std::rc::Rc::into_inner(table).expect("sole owner").into_inner().into_table();
    let read = SignalTable::read(&file).expect("the results read back");
    assert_eq!(recorded.times, [0.0, 0.2, 0.4], "rows at k = 0, 2, 4");
    assert_eq!(recorded.columns[17][2], 17.0 * 0.4, "a ramp's value at t = 0.4");
    assert_eq!(bits(&recorded), bits(&read));
    assert_eq!(recorded.file, read.file);
}

/// The partial file a recorder in `dir` is writing (renamed into place when it finishes).
fn partial_file(dir: &std::path::Path) -> std::path::PathBuf {
    let mut entries = std::fs::read_dir(dir).expect("dir").map(|entry| entry.expect("entry").path());
    entries.find(|path| path.to_string_lossy().ends_with(".partial")).expect("a partial file")
}

/// Lines of `file` and whether it ends on a complete row.
fn complete_lines(file: &std::path::Path) -> usize {
    let text = std::fs::read_to_string(file).expect("csv");
    assert!(text.ends_with('\n'), "the file must end on a complete row: {text:?}");
    text.lines().count()
}

#[test]
fn rows_reach_the_file_in_whole_rows_as_the_flush_policy_says() {
    use crate::observer::{FlushPolicy, Observer};
    use crate::simulator::Simulator;
    use std::time::Duration;

    let dir = tempfile::tempdir().expect("tempdir");
    let file = dir.path().join("rows.csv");
    let journal = Journal::default();
    let slaves: Vec<Box<dyn Simulator>> = vec![Box::new(Mock::new("m", Law::Ramps(&[]), &journal))];
    let every_three = FlushPolicy { rows: 3, interval: Duration::from_secs(3600) };
    let mut recorder = CsvRecorder::create(&file, &outputs(2), 1).expect("recorder").with_flush(every_three);
    let mut lines_after_each_row = Vec::new();
    let partial = partial_file(dir.path());
    for k in 0..7 {
        recorder.observe(k, k as f64, &slaves).expect("row");
        lines_after_each_row.push(complete_lines(&partial));
    }
    // The header at once, then three rows at a time: a process killed outright loses at most
    // two rows.
    assert_eq!(lines_after_each_row, [1, 1, 4, 4, 4, 7, 7]);
    assert!(!file.exists(), "the target appears only when the run ends");
    recorder.finish().expect("finish");
    assert_eq!(complete_lines(&file), 8);
    assert!(!partial.exists(), "renamed into place");
    drop(recorder);

    let at_once = FlushPolicy { rows: u64::MAX, interval: Duration::ZERO };
    let mut recorder = CsvRecorder::create(&file, &outputs(2), 1).expect("recorder").with_flush(at_once);
    recorder.observe(0, 0.0, &slaves).expect("row");
    assert_eq!(complete_lines(&partial_file(dir.path())), 2, "an elapsed interval writes the row at once");
}
