//! The FMI call-sequence fuzzer over every built FMU (`target/release/lib<model>.so`, built by
//! `cargo xtask package`), through its FMI 2.0 and its FMI 3.0 entry points.
//!
//! The fuzzer runs in a child process so that its stderr can be inspected: an FMU library has its
//! own panic hook, which must report to the FMI logger and never print, and nothing else in an
//! FMU writes to stderr.

use fmu_fuzz::fmu::{Api, Fmu};
use fmu_fuzz::{fmu, fuzz};
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// Random call sequences per FMU, half through each API.
const SEQUENCES: u64 = 10_000;
/// A call sequence that makes no call for this long hangs.
const HANG: Duration = Duration::from_secs(20);

#[test]
fn fmi_call_sequences_neither_crash_panic_hang_nor_print() {
    let exe = std::env::current_exe().unwrap();
    let output = Command::new(exe)
        .args(["--ignored", "--exact", "fuzz_every_fmu", "--nocapture", "--test-threads=1"])
        .output()
        .expect("the test binary runs");
    let (stdout, stderr) = (String::from_utf8_lossy(&output.stdout), String::from_utf8_lossy(&output.stderr));
    println!("{stdout}");
    assert!(output.status.success(), "the fuzzer failed ({}):\n{stderr}", output.status);
    assert!(!stderr.contains("panicked"), "a panic message reached stderr:\n{stderr}");
    assert!(stdout.contains("test result: ok. 1 passed"), "the fuzzer did not run:\n{stdout}");
}

/// The child: every FMU through both APIs, seeded (reruns are identical), under a watchdog.
#[test]
#[ignore = "run by fmi_call_sequences_neither_crash_panic_hang_nor_print, in a child process"]
fn fuzz_every_fmu() {
    let progress = Arc::new(AtomicU64::new(0));
    watchdog(progress.clone());
    for (i, model) in fmu::models().unwrap().into_iter().enumerate() {
        let fmu = Fmu::load(&model).unwrap();
        for (k, api) in Api::BOTH.into_iter().enumerate() {
            let started = std::time::Instant::now();
            let seed = 1_000_000 * i as u64 + 500_000 * k as u64;
            let figures = fuzz::run(&fmu, api, SEQUENCES / 2, seed, &progress).unwrap_or_else(|e| panic!("{e}"));
            let seconds = started.elapsed().as_secs_f64();
            let table = match api {
                Api::Fmi2 => String::new(),
                Api::Fmi3 => format!(
                    "{} forbidden by the FMI 3.0 state table, all refused; {} accepted after an fmi3Error \
                     (strictly Terminated); ",
                    figures.forbidden, figures.lenient
                ),
            };
            println!(
                "{model} {}: {} sequences, {} calls ({:.0}/s; {} steps taken, {} refused, {} bad by construction, \
                 all refused; {} through the other API, all refused); {table}0 crashes, 0 panics, 0 hangs; \
                 slowest call {:?}: {}; {seconds:.1} s",
                api.name(),
                figures.sequences,
                figures.calls,
                figures.calls as f64 / seconds,
                figures.steps,
                figures.refused,
                figures.bad_calls,
                figures.cross_version,
                figures.slowest_call,
                figures.slowest,
            );
            assert!(figures.steps > 0, "{model} ({}): no step was accepted", api.name());
            assert_eq!(
                figures.unserializable,
                0,
                "{model} ({}): saved states the FMU could not serialize, first: {}",
                api.name(),
                figures.unserializable_example
            );
        }
    }
}

/// Aborts the process (failing the parent test) if no FMI call completes for [`HANG`].
fn watchdog(progress: Arc<AtomicU64>) {
    std::thread::spawn(move || {
        let mut last = progress.load(Ordering::Relaxed);
        loop {
            std::thread::sleep(HANG);
            let now = progress.load(Ordering::Relaxed);
            if now == last {
                eprintln!("hang: no FMI call returned for {HANG:?} (after call {now})");
                std::process::abort();
            }
            last = now;
        }
    });
}
