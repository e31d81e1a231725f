//! The leak test's workload, run under `valgrind --leak-check=full` by `cargo xtask test`: per
//! FMU and per API (FMI 2.0, then FMI 3.0), 500 instance cycles (instantiate, initialize, step,
//! FMU states of which one is left unfreed, free) on one loaded library, then 10 cycles that
//! load and unload the library (1,000 and 20 per FMU in all; loading is slow under valgrind,
//! and the resident-set test runs 200 per FMU natively). Then, for each ordered pair of FMU
//! libraries, an instance and a state of the first are handed to the functions of the second,
//! through FMI 2.0 (`cycles::cross_library_cycle`) and through FMI 3.0, whose instance also
//! goes to the second's FMI 2.0 functions (`cycles::cross_library_cycle3`): they must refuse
//! them without reading through them. Valgrind fails the run if any memory is definitely lost
//! or any access is invalid.

use fmu_fuzz::fmu::{Api, Fmu};
use fmu_fuzz::{cycles, fmu};

/// Cycles per FMU and API unless the arguments say otherwise (`fmu-leak [instance cycles]
/// [load cycles]`).
const INSTANCE_CYCLES: usize = 500;
const LOAD_CYCLES: usize = 10;

fn main() -> Result<(), String> {
    let mut args = std::env::args().skip(1).map(|a| a.parse::<usize>().map_err(|e| format!("{a}: {e}")));
    let instance_cycles = args.next().transpose()?.unwrap_or(INSTANCE_CYCLES);
    let load_cycles = args.next().transpose()?.unwrap_or(LOAD_CYCLES);
    for model in fmu::models()? {
        let fmu = Fmu::load(&model)?;
        for api in Api::BOTH {
            for _ in 0..instance_cycles {
                cycles::instance_cycle(&fmu, api)?;
            }
        }
        drop(fmu);
        for api in Api::BOTH {
            for _ in 0..load_cycles {
                cycles::load_cycle(&model, api)?;
            }
        }
        println!(
            "{model}: {instance_cycles} instance cycles and {load_cycles} load/unload cycles through each of \
             FMI 2.0 and FMI 3.0"
        );
    }
    cross_library()
}

/// Every ordered pair of the libraries, all loaded at once, through both APIs.
fn cross_library() -> Result<(), String> {
    let fmus = fmu::models()?.iter().map(|model| Fmu::load(model)).collect::<Result<Vec<_>, _>>()?;
    let (mut pairs, mut refusals, mut refusals3) = (0, 0, 0);
    for a in &fmus {
        for b in fmus.iter().filter(|b| b.model != a.model) {
            refusals += cycles::cross_library_cycle(a, b)?;
            refusals3 += cycles::cross_library_cycle3(a, b)?;
            pairs += 1;
        }
    }
    println!(
        "cross-library: {pairs} ordered pairs, {refusals} FMI 2.0 and {refusals3} FMI 3.0 calls with a foreign \
         instance or state, all refused"
    );
    Ok(())
}
