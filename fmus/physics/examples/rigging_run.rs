//! The hook-and-load rigging (physics::rigging) under a moving tip and a changing hoist length,
//! printed as JSON for the independent SciPy model (tests/test_rigging.py).
//!
//! ```text
//! echo '{"params": {…}, "duration": 60}' | cargo run --release -p physics --example rigging_run
//! ```
//!
//! Input (every key optional): `params` (a `RiggingParams`), `hoist_angles` and `sling_angles`
//! (the start at rest, rad), the tip's motion `tip_amplitude` (m, per W axis) and `tip_omega`
//! (rad/s, per axis): p(t) = A·sin(ω t); the hoist length `lp0` + `lp_amplitude`·sin(`lp_omega` t)
//! (m, rad/s); `duration` and `step` (s). Over each step every input is ramped linearly from its
//! value at the step's start to its value at the step's end (the velocities and accelerations are
//! the analytic derivatives, sampled, not the ramps' slopes). Output: the resolved input, and per
//! step end t, hook, load (positions, m), hoist_tension, sling_tension (N).

use physics::math::Vec3;
use physics::pendulum::TipMotion;
use physics::rigging::{advance, rigging_motion, RiggingParams, RiggingState};
use serde::{Deserialize, Serialize};
use serde_json::json;
use std::io::Read;

#[derive(Deserialize, Serialize)]
#[serde(default)]
struct Input {
    params: RiggingParams,
    hoist_angles: (f64, f64),
    sling_angles: (f64, f64),
    tip_amplitude: [f64; 3],
    tip_omega: [f64; 3],
    lp0: f64,
    lp_amplitude: f64,
    lp_omega: f64,
    duration: f64,
    step: f64,
}

impl Default for Input {
    fn default() -> Self {
        Input {
            params: RiggingParams::DEFAULT,
            hoist_angles: (0.0, 0.0),
            sling_angles: (0.0, 0.0),
            tip_amplitude: [0.0; 3],
            tip_omega: [0.0; 3],
            lp0: 0.7,
            lp_amplitude: 0.0,
            lp_omega: 0.0,
            duration: 1.0,
            step: 0.01,
        }
    }
}

impl Input {
    /// The inputs at time t: A sin(ωt) and its derivatives per axis, l_p and its derivatives.
    fn tip(&self, t: f64) -> TipMotion {
        let axis = |i: usize| {
            let (a, w) = (self.tip_amplitude[i], self.tip_omega[i]);
            let (s, c) = (w * t).sin_cos();
            (a * s, a * w * c, -a * w * w * s)
        };
        let [x, y, z] = [axis(0), axis(1), axis(2)];
        let (a, w) = (self.lp_amplitude, self.lp_omega);
        let (s, c) = (w * t).sin_cos();
        TipMotion {
            pos: Vec3::new(x.0, y.0, z.0),
            vel: Vec3::new(x.1, y.1, z.1),
            acc: Vec3::new(x.2, y.2, z.2),
            lp: self.lp0 + a * s,
            lp_dot: a * w * c,
            lp_ddot: -a * w * w * s,
        }
    }
}

fn simulate(input: &Input) -> Result<serde_json::Value, String> {
    input.params.validate()?;
    if !(input.step > 0.0 && input.duration >= 0.0) {
        return Err(format!("step {} s and duration {} s must be > 0 and ≥ 0", input.step, input.duration));
    }
    let h = input.step;
    let steps = (input.duration / h).round() as usize;
    let mut state = RiggingState::at_angles(&input.params, &input.tip(0.0), input.hoist_angles, input.sling_angles);
    let start = rigging_motion(&input.params, &state, &input.tip(0.0))?;
    let (mut t, mut hook, mut load, mut hoist_tension, mut sling_tension) = (vec![], vec![], vec![], vec![], vec![]);
    for k in 0..steps {
        let (u0, u1) = (input.tip(k as f64 * h), input.tip((k + 1) as f64 * h));
        state = advance(&input.params, &state, &u0, &u0.secant(&u1, h), h)?;
        let m = rigging_motion(&input.params, &state, &u1)?;
        t.push((k + 1) as f64 * h);
        hook.push([m.hook.pos.x, m.hook.pos.y, m.hook.pos.z]);
        load.push([m.load.pos.x, m.load.pos.y, m.load.pos.z]);
        hoist_tension.push(m.hoist_tension);
        sling_tension.push(m.sling_tension);
    }
    Ok(json!({
        "input": input,
        "start": { "hook": start.hook, "load": start.load },
        "t": t, "hook": hook, "load": load, "hoist_tension": hoist_tension, "sling_tension": sling_tension,
    }))
}

fn main() -> Result<(), String> {
    let mut text = String::new();
    std::io::stdin().read_to_string(&mut text).map_err(|e| format!("stdin: {e}"))?;
    let input: Input = serde_json::from_str(&text).map_err(|e| format!("input: {e}"))?;
    println!("{}", simulate(&input)?);
    Ok(())
}
