//! The leak test's workload, run under `valgrind --leak-check=full` by `cargo xtask test`: per
//! FMU, 1,000 instance cycles (instantiate, initialize, step, FMU states of which one is left
//! unfreed, free) on one loaded library, then 20 cycles that load and unload the library (100
//! in all; loading is slow under valgrind, and the resident-set test runs 200 per FMU natively).
//! Then, for each ordered pair of FMU libraries, an instance and a state of the first are handed
//! to the functions of the second (`cycles::cross_library_cycle`), which must refuse them without
//! reading through them. Valgrind fails the run if any memory is definitely lost or any access is
//! invalid.

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
    cross_library()
}

/// Every ordered pair of the libraries, all loaded at once.
fn cross_library() -> Result<(), String> {
    let fmus = fmu::models()?.iter().map(|model| Fmu::load(model)).collect::<Result<Vec<_>, _>>()?;
    let (mut pairs, mut refusals) = (0, 0);
    for a in &fmus {
        for b in fmus.iter().filter(|b| b.model != a.model) {
            refusals += cycles::cross_library_cycle(a, b)?;
            pairs += 1;
        }
    }
    println!("cross-library: {pairs} ordered pairs, {refusals} calls with a foreign instance or state, all refused");
    Ok(())
}
