//! The leak test's workload, run under `valgrind --leak-check=full` by `cargo xtask test`: per
//! FMU, 1,000 instance cycles (instantiate, initialize, step, FMU states of which one is left
//! unfreed, free) on one loaded library, then 20 cycles that load and unload the library (100
//! in all; loading is slow under valgrind, and the resident-set test runs 200 per FMU natively).
//! Valgrind fails the run if any memory is definitely lost.

use fmu_fuzz::{cycles, fmu, fmu::Fmu};

/// Cycles per FMU unless the arguments say otherwise (`fmu-leak [instance cycles] [load cycles]`).
const INSTANCE_CYCLES: usize = 1000;
const LOAD_CYCLES: usize = 20;

fn main() -> Result<(), String> {
    let mut args = std::env::args().skip(1).map(|a| a.parse::<usize>().map_err(|e| format!("{a}: {e}")));
    let instance_cycles = args.next().transpose()?.unwrap_or(INSTANCE_CYCLES);
    let load_cycles = args.next().transpose()?.unwrap_or(LOAD_CYCLES);
    for model in fmu::models()? {
        let fmu = Fmu::load(&model)?;
        for _ in 0..instance_cycles {
            cycles::instance_cycle(&fmu)?;
        }
        drop(fmu);
        for _ in 0..load_cycles {
            cycles::load_cycle(&model)?;
        }
        println!("{model}: {instance_cycles} instance cycles, {load_cycles} load/unload cycles");
    }
    Ok(())
}
