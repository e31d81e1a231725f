//! The FMI call-sequence fuzzer over every built FMU (`target/release/lib<model>.so`, built by
//! `cargo xtask package`).
//!
//! The fuzzer runs in a child process so that its stderr can be inspected: an FMU library has its
//! own panic hook, which must report to the FMI logger and never print, and nothing else in an
//! FMU writes to stderr.

use fmu_fuzz::{fmu, fmu::Fmu, fuzz};
use std::process::Command;
use std::sync::atomic::{AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Duration;

/// Random call sequences per FMU.
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

/// The child: every FMU, seeded (reruns are identical), under a watchdog.
#[test]
#[ignore = "run by fmi_call_sequences_neither_crash_panic_hang_nor_print, in a child process"]
fn fuzz_every_fmu() {
    let progress = Arc::new(AtomicU64::new(0));
    watchdog(progress.clone());
    for (i, model) in fmu::models().unwrap().into_iter().enumerate() {
        let fmu = Fmu::load(&model).unwrap();
        let started = std::time::Instant::now();
        let figures = fuzz::run(&fmu, SEQUENCES, 1_000_000 * i as u64, &progress).unwrap_or_else(|e| panic!("{e}"));
        println!(
            "{model}: {} sequences, {} calls ({} steps taken, {} refused, {} bad by construction, all refused); \
             0 crashes, 0 panics, 0 hangs; slowest call {:?}: {}; {:.1} s",
            figures.sequences,
            figures.calls,
            figures.steps,
            figures.refused,
            figures.bad_calls,
            figures.slowest_call,
            figures.slowest,
            started.elapsed().as_secs_f64()
        );
        assert_eq!(
            figures.unserializable, 0,
            "{model}: saved states the FMU could not serialize, first: {}",
            figures.unserializable_example
        );
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
