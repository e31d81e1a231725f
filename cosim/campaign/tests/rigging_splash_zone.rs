//! The splash-zone stress case of docs/rigging.md at full scale (scenarios/splash_zone_off.json
//! and splash_zone_ahc.json): 1 t and a 300 kg hook on 100 m of soft rope whose bounce frequency
//! sits on the wave peak of ship motion profile 2, the crane's joints held, 300 s.
//!
//! - Without heave compensation the rope goes slack and snaps taut again; the run still ends
//!   normally, with the slack phases and the peak snap load as outputs (a rope that ended the run
//!   on slack, or a snap record that missed the catch, fails here).
//! - With the winch compensating the heave the rope stays taut and the load heaves less.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use cosim_engine::run::{run_system_file, RunOptions};

/// The static load of hook and load, (300 + 1000) kg · g (N).
const STATIC_TENSION: f64 = 1300.0 * 9.80665;

struct Rope {
    slack_samples: usize,
    min_tension: f64,
    max_tension: f64,
    peak_snap: f64,
    heave_rms: f64,
}

fn run(scenario: &str) -> Rope {
    let dir = tempfile::tempdir().expect("tempdir");
    let output = dir.path().join("run.csv");
    let options = RunOptions { output: output.clone(), ..RunOptions::default() };
    let file = common::workspace_root().join("scenarios").join(scenario);
    run_system_file(&file, &options).unwrap_or_else(|e| panic!("{scenario}: {e}"));
    let (header, rows) = common::read_results(&output);
    let column = |name: &str| header.iter().position(|h| h == name).unwrap_or_else(|| panic!("no column {name}"));
    let values = |name: &str| rows.iter().map(|r| r[column(name)]).collect::<Vec<f64>>();
    let (tension, heave) = (values("pendulum.tension"), values("pendulum.load.z"));
    let mean = heave.iter().sum::<f64>() / heave.len() as f64;
    let last = rows.last().expect("rows");
    assert!((last[0] - 300.0).abs() < 1e-9, "{scenario} ends at {} s", last[0]);
    Rope {
        slack_samples: values("pendulum.slack").iter().filter(|&&s| s > 0.5).count(),
        min_tension: tension.iter().copied().fold(f64::INFINITY, f64::min),
        max_tension: tension.iter().copied().fold(0.0, f64::max),
        peak_snap: last[column("pendulum.hoist.peak_snap")],
        heave_rms: (heave.iter().map(|z| (z - mean).powi(2)).sum::<f64>() / heave.len() as f64).sqrt(),
    }
}

#[test]
fn a_soft_rope_on_the_wave_peak_goes_slack_and_snaps_without_compensation_and_stays_taut_with_it() {
    let off = run("splash_zone_off.json");
    let ahc = run("splash_zone_ahc.json");
    println!(
        "splash zone, no compensation: slack {:.2} s, tension {:.2}..{:.2} kN, peak snap {:.2} kN ({:.2} x static), \
         load heave {:.2} m RMS",
        off.slack_samples as f64 * 0.01,
        off.min_tension * 1e-3,
        off.max_tension * 1e-3,
        off.peak_snap * 1e-3,
        off.peak_snap / STATIC_TENSION,
        off.heave_rms
    );
    println!(
        "splash zone, winch AHC: slack {:.2} s, tension {:.2}..{:.2} kN, load heave {:.2} m RMS",
        ahc.slack_samples as f64 * 0.01,
        ahc.min_tension * 1e-3,
        ahc.max_tension * 1e-3,
        ahc.heave_rms
    );
    assert!(off.slack_samples >= 100 && off.min_tension == 0.0, "the rope goes slack for a second or more");
    // The snap after the slack: well above the static load, and the substep record at least the
    // largest tension sampled every 10 ms.
    assert!(off.peak_snap > 1.8 * STATIC_TENSION, "{}", off.peak_snap);
    assert!(off.peak_snap >= off.max_tension - 1e-9 && off.peak_snap < 1.05 * off.max_tension);
    assert_eq!(ahc.slack_samples, 0);
    assert!(ahc.min_tension > 0.0 && ahc.peak_snap == 0.0);
    assert!(ahc.heave_rms < 0.7 * off.heave_rms, "{} vs {}", ahc.heave_rms, off.heave_rms);
}
