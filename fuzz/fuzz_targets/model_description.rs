//! Any text as `modelDescription.xml`: parsed to a model description or refused with an error,
//! never a panic, a hang or unbounded memory.
#![no_main]

use libfuzzer_sys::fuzz_target;

fuzz_target!(|text: &str| {
    if let Ok(description) = fmu_import::fmu::ModelDescription::parse(text) {
        // What the importer does next with a parsed description: look variables up by name.
        for variable in &description.variables {
            assert!(description.variable(&variable.name).is_some());
        }
    }
});
