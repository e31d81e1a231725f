//! The cost of one re-design of the anti-sway gain (docs/tuning.md, "Gain scheduling over the
//! cable length"): the test scale's K_θ(l) (a 4-state CARE, [`angle_coupling`]), the full
//! scale's K(l) (a 3-state CARE, [`AntiSway::design`]) and, for comparison, the 12-state design
//! of §6.2 it stands for.
//!
//! ```text
//! cargo run --release -p physics --example gain_schedule_cost -- 2000
//! valgrind --tool=callgrind target/release/examples/gain_schedule_cost 100 test
//! ```
//!
//! A second argument, `test`, `full` or `12`, runs that design alone (for an instruction count:
//! the difference between two counts over the difference of their design counts).
//!
//! Each design runs at a length that moves every call (0.4–1.0 m, 5–30 m), as a winch paying out
//! would give. Prints the wall time per design and a checksum of the gains.

use nalgebra::DMatrix;
use physics::control::lqr::{angle_coupling, lqr, pendulum_model};
use physics::math::STANDARD_GRAVITY;
use physics::offshore_control::antisway::{AntiSway, AntiSwayWeights};
use std::hint::black_box;
use std::time::Instant;

fn time<F: FnMut(f64) -> Result<f64, String>>(
    name: &str,
    n: usize,
    (from, to): (f64, f64),
    mut f: F,
) -> Result<(), String> {
    let start = Instant::now();
    let mut checksum = 0.0;
    for i in 0..n {
        let lp = from + (to - from) * i as f64 / n as f64;
        checksum += f(black_box(lp))?;
    }
    let ns = start.elapsed().as_nanos() as f64 / n as f64;
    println!("{name}: {n} designs, {:.1} us per design; checksum {checksum:.12e}", ns / 1000.0);
    Ok(())
}

/// The largest |d ln k / d ln l| of each gain component over `from`–`to` (central differences on
/// 1 % steps of l): how far a gain designed at l lags its fresh design 1 % away.
fn sensitivity<const N: usize>(
    name: &str,
    (from, to): (f64, f64),
    design: impl Fn(f64) -> Result<[f64; N], String>,
) -> Result<(), String> {
    let mut worst = [0.0f64; N];
    let mut lp = from;
    while lp <= to {
        let (low, high) = (design(lp / 1.01)?, design(lp * 1.01)?);
        for i in 0..N {
            let slope = (high[i].abs().ln() - low[i].abs().ln()) / (2.0 * 1.01f64.ln());
            worst[i] = worst[i].max(slope.abs());
        }
        lp *= 1.01;
    }
    println!("{name}: largest |d ln k / d ln l| over {from}-{to} m: {worst:.3?}");
    Ok(())
}

fn main() -> Result<(), String> {
    let n: usize = match std::env::args().nth(1) {
        Some(arg) => arg.parse().map_err(|e| format!("design count {arg:?}: {e}"))?,
        None => 2000,
    };
    let only = std::env::args().nth(2);
    let run = |name: &str| only.as_deref().is_none_or(|o| o == name);
    let g = STANDARD_GRAVITY;
    if only.is_none() {
        sensitivity("test scale K_theta", (0.05, 1.3), |lp| Ok([angle_coupling(lp, g)?]))?;
        sensitivity("full scale (k_e, k_d, k_w)", (5.0, 30.0), |lp| {
            Ok(AntiSway::design(lp, g, &AntiSwayWeights::DEFAULT)?.0.gain)
        })?;
    }
    if run("test") {
        time("test scale K_theta(l), 4 states", n, (0.4, 1.0), |lp| angle_coupling(lp, g))?;
    }
    if run("full") {
        time("full scale K(l), 3 states", n, (5.0, 30.0), |lp| {
            Ok(AntiSway::design(lp, g, &AntiSwayWeights::DEFAULT)?.0.gain.iter().sum())
        })?;
    }
    if !run("12") {
        return Ok(());
    }
    let (q, r) = (DMatrix::identity(12, 12) * 10.0, DMatrix::identity(6, 6));
    time("12-state design of section 6.2", (n / 20).max(1), (0.4, 1.0), |lp| {
        let (a, b) = pendulum_model(lp, g);
        Ok(lqr(&a, &b, &q, &r)?.k[(1, 3)])
    })?;
    Ok(())
}
