//! Any bytes as a system or scenario file: loaded and validated, or refused with an error, never
//! a panic. Relative paths inside point nowhere useful (the file lies alone in a fresh folder), so
//! validation usually fails at the latest when it opens the FMUs.
#![no_main]

use cosim_engine::system::{Overrides, System, SystemFiles};
use libfuzzer_sys::fuzz_target;

fuzz_target!(|bytes: &[u8]| {
    let dir = tempfile::tempdir().expect("temporary folder");
    let file = dir.path().join("system.json");
    std::fs::write(&file, bytes).expect("write the input");
    if let Err(error) = System::load(&file, &Overrides::default(), &SystemFiles::default()) {
        assert!(!fmu_import::error_chain(&error).is_empty());
    }
});
