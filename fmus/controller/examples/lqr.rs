//! The LQR design of thesis §6.2: K for Q = 10·I12, R = I6 on the linearised tip–pendulum model
//! at pendulum lengths 0.05–1.0 m, and the sign structure the delta compensation law inherits.
//!
//! ```text
//! cargo run --release -p controller --example lqr                  # the report
//! cargo run --release -p controller --example lqr -- --json        # the sweep as JSON
//! cargo run --release -p controller --example lqr -- --solve FILE  # S, K for {"A","B","Q","R"}
//! ```

use nalgebra::DMatrix;
use physics::control::lqr::{lqr, pendulum_model, INPUTS, STATES};
use physics::math::STANDARD_GRAVITY;
use serde_json::{json, Value};

const LENGTHS: [f64; 8] = [0.05, 0.1, 0.25, 0.4, 0.55, 0.7, 0.85, 1.0];

fn rows(m: &DMatrix<f64>) -> Value {
    json!((0..m.nrows()).map(|i| m.row(i).iter().cloned().collect::<Vec<f64>>()).collect::<Vec<_>>())
}

fn matrix(v: &Value, name: &str) -> Result<DMatrix<f64>, String> {
    let rows: Vec<Vec<f64>> = serde_json::from_value(v[name].clone()).map_err(|e| format!("{name}: {e}"))?;
    let n = rows.len();
    let m = rows.first().map_or(0, Vec::len);
    if rows.iter().any(|r| r.len() != m) {
        return Err(format!("{name}: rows of different lengths"));
    }
    Ok(DMatrix::from_row_iterator(n, m, rows.into_iter().flatten()))
}

fn thesis_weights() -> (DMatrix<f64>, DMatrix<f64>) {
    (DMatrix::identity(12, 12) * 10.0, DMatrix::identity(6, 6))
}

fn sweep_json() -> Result<Value, String> {
    let (q, r) = thesis_weights();
    let cases = LENGTHS
        .iter()
        .map(|&lp| {
            let (a, b) = pendulum_model(lp, STANDARD_GRAVITY);
            let design = lqr(&a, &b, &q, &r)?;
            let poles: Vec<[f64; 2]> = design.poles.iter().map(|p| [p.re, p.im]).collect();
            Ok(json!({
                "lp": lp,
                "A": rows(&a),
                "B": rows(&b),
                "Q": rows(&q),
                "R": rows(&r),
                "S": rows(&design.s),
                "K": rows(&design.k),
                "poles": poles
            }))
        })
        .collect::<Result<Vec<_>, String>>()?;
    Ok(json!({"g": STANDARD_GRAVITY, "cases": cases}))
}

fn solve(path: &str) -> Result<Value, String> {
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let v: Value = serde_json::from_str(&text).map_err(|e| format!("{path}: {e}"))?;
    let design = lqr(&matrix(&v, "A")?, &matrix(&v, "B")?, &matrix(&v, "Q")?, &matrix(&v, "R")?)?;
    Ok(json!({"S": rows(&design.s), "K": rows(&design.k)}))
}

fn report() -> Result<(), String> {
    let (q, r) = thesis_weights();
    println!(
        "LQR of the linearised tip-pendulum model (thesis eqs. 6.12-6.25), Q = 10*I12, R = I6, g = \
        {STANDARD_GRAVITY} m/s^2"
    );
    println!("u = K e, e = x_d - x; rows: inputs (tip accelerations, length acceleration); columns: state errors\n");
    println!(
        "{:>6} | {:>8} {:>8} {:>8} {:>8} | {:>8} {:>8} {:>8} {:>8} | {:>8} {:>8} | {:>8} {:>8} | {:>9}",
        "l_p m",
        "ax:x_t",
        "ax:th_y",
        "ax:vx_t",
        "ax:w_y",
        "ay:y_t",
        "ay:th_x",
        "ay:vy_t",
        "ay:w_x",
        "az:z_t",
        "az:vz_t",
        "al:l_p",
        "al:vl_p",
        "max Re(s)"
    );
    for lp in LENGTHS {
        let (a, b) = pendulum_model(lp, STANDARD_GRAVITY);
        let d = lqr(&a, &b, &q, &r)?;
        let k = &d.k;
        let slowest = d.poles.iter().map(|p| p.re).fold(f64::MIN, f64::max);
        println!(
            "{lp:>6.2} | {:>8.3} {:>8.3} {:>8.3} {:>8.3} | {:>8.3} {:>8.3} {:>8.3} {:>8.3} | {:>8.3} {:>8.3} \
                | {:>8.3} {:>8.3} | {slowest:>9.3}",
            k[(0, 0)],
            k[(0, 4)],
            k[(0, 6)],
            k[(0, 10)],
            k[(1, 1)],
            k[(1, 3)],
            k[(1, 7)],
            k[(1, 9)],
            k[(2, 2)],
            k[(2, 8)],
            k[(5, 5)],
            k[(5, 11)]
        );
    }
    let (a, b) = pendulum_model(0.7, STANDARD_GRAVITY);
    let d = lqr(&a, &b, &q, &r)?;
    println!("\nK at l_p = 0.7 m (rows {INPUTS:?}, columns {STATES:?}):");
    for (input, row) in INPUTS.iter().zip(d.k.row_iter()) {
        let row: Vec<String> = row.iter().map(|v| format!("{:>7.3}", if v.abs() < 5e-13 { 0.0 } else { *v })).collect();
        println!("  {input:>5} [{}]", row.join(" "));
    }
    println!("\nSign structure (e = x_d - x, so e_th = -th at the set-point):");
    println!("  e_theta_x enters y_t'' with {:+.3}: the delta law uses dy_t = e_y + 0.1 e_theta_x", d.k[(1, 3)]);
    println!("  e_theta_y enters x_t'' with {:+.3}: the delta law uses dx_t = e_x - 0.1 e_theta_y", d.k[(0, 4)]);
    println!(
        "  diagonal: positions {:.3} = sqrt(10), coupled tip velocities {:.3}, z_t and l_p velocities \
        {:.3} = sqrt(10 + 2 sqrt(10))",
        d.k[(0, 0)],
        d.k[(0, 6)],
        d.k[(2, 8)]
    );
    println!("  x, y, z and l_p do not couple to each other; the two angle inputs get no gain");
    Ok(())
}

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let result = match args.iter().map(String::as_str).collect::<Vec<_>>().as_slice() {
        [] => report(),
        ["--json"] => sweep_json().map(|v| println!("{v}")),
        ["--solve", path] => solve(path).map(|v| println!("{v}")),
        _ => Err("usage: lqr [--json | --solve FILE]".into()),
    };
    if let Err(e) = result {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}
