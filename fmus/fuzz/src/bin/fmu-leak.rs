//! The leak test's workload, run under `valgrind --leak-check=full` by `cargo xtask test`: per
//! FMU, 1,000 instance cycles (instantiate, initialize, step, FMU states of which one is left
//! unfreed, free) on one loaded library, then 100 cycles that load and unload the library.
//! Valgrind fails the run if any memory is definitely lost.

use fmu_fuzz::{cycles, fmu::Fmu, MODELS};

const INSTANCE_CYCLES: usize = 1000;
const LOAD_CYCLES: usize = 100;

fn main() -> Result<(), String> {
    for model in MODELS {
        let fmu = Fmu::load(model)?;
        for _ in 0..INSTANCE_CYCLES {
            cycles::instance_cycle(&fmu)?;
        }
        drop(fmu);
        for _ in 0..LOAD_CYCLES {
            cycles::load_cycle(model)?;
        }
        println!("{model}: {INSTANCE_CYCLES} instance cycles, {LOAD_CYCLES} load/unload cycles");
    }
    Ok(())
}
