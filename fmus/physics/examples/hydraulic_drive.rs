//! The hydraulic test rig (physics::hydraulics::rig): one vertical valve–cylinder–mass drive under
//! a spool program, integrated with RK4 at fixed substeps, printed as JSON for the SciPy
//! comparison (tests/test_hydraulic_drive.py).
//!
//! ```text
//! cargo run --release -p physics --example hydraulic_drive -- '{"duration": 20, "program": [[0, 0], [2, 0.6]]}'
//! echo '{…}' | cargo run --release -p physics --example hydraulic_drive
//! ```
//!
//! Input (every key optional): `rig` (fields of `Rig`, nested fields of the drive; `"holding":
//! null` removes the counterbalance valve), `program` ([t, u] breakpoints, linear between them),
//! `duration` (s), `record_every` (substeps between samples), and the start: `initial` (a
//! `DriveState`) or `stroke` (m: at rest, p_B at the centred valve's neutral pressure, p_A
//! holding the load). Output: the resolved rig and start, and per sample t, pos, vel, p_a, p_b, pilot,
//! spool, p_line_a, cbv_opening, relief_flow, makeup_flow, q_supply; the final energies.

use physics::hydraulics::rig::{Rig, Sample, SpoolProgram};
use physics::hydraulics::DriveState;
use serde::Deserialize;
use serde_json::{json, Map, Value};
use std::io::Read;

#[derive(Deserialize)]
#[serde(default)]
struct Input {
    rig: Rig,
    program: Vec<[f64; 2]>,
    duration: f64,
    record_every: usize,
    initial: Option<DriveState>,
    stroke: f64,
}

impl Default for Input {
    fn default() -> Self {
        Input {
            rig: Rig::DEFAULT,
            program: vec![[0.0, 0.0]],
            duration: 1.0,
            record_every: 1,
            initial: None,
            stroke: 0.8,
        }
    }
}

fn input_text() -> Result<String, String> {
    match std::env::args().nth(1) {
        Some(text) => Ok(text),
        None => {
            let mut text = String::new();
            std::io::stdin().read_to_string(&mut text).map_err(|e| format!("stdin: {e}"))?;
            Ok(text)
        }
    }
}

fn simulate(input: &Input) -> Result<Value, String> {
    let rig = &input.rig;
    rig.validate()?;
    let program = SpoolProgram::new(&input.program)?;
    let neutral = rig.drive.valve.neutral_pressure(rig.supply.pressure, rig.supply.tank);
    let initial = input.initial.unwrap_or_else(|| rig.holding_state(input.stroke, neutral));
    let samples = rig.simulate(&program, initial, input.duration, input.record_every)?;
    let column = |f: fn(&Sample) -> f64| samples.iter().map(f).collect::<Vec<f64>>();
    let mut out = Map::new();
    out.insert("rig".into(), json!(rig));
    out.insert("initial".into(), json!(initial));
    // One column per named field of `$s.$part`, under the field's name.
    macro_rules! columns {
        (|$s:ident| $part:expr; $($field:ident),+) => {
            $(out.insert(stringify!($field).into(), json!(column(|$s| $part.$field)));)+
        };
    }
    columns!(|s| s; t, spool);
    columns!(|s| s.state; pos, vel, p_a, p_b, pilot);
    columns!(|s| s.rates; p_line_a, cbv_opening, relief_flow, makeup_flow, q_supply);
    out.insert("energy".into(), json!(samples.last().map(|s| s.energy)));
    Ok(Value::Object(out))
}

fn main() {
    let result = input_text()
        .and_then(|text| serde_json::from_str::<Input>(&text).map_err(|e| format!("input: {e}")))
        .and_then(|input| simulate(&input));
    match result {
        Ok(value) => println!("{value}"),
        Err(e) => {
            eprintln!("hydraulic_drive: {e}");
            std::process::exit(2);
        }
    }
}
