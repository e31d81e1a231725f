//! Any bytes as an `.fmu` archive: extracted within small limits into a fresh folder, or
//! refused; never a panic, a write outside the folder, or more bytes than the limit.
#![no_main]

use fmu_import::fmu::{extract_within, ExtractLimits};
use libfuzzer_sys::fuzz_target;

/// Small enough that a bomb costs milliseconds, large enough for real entries of the inputs.
const LIMITS: ExtractLimits = ExtractLimits { max_unpacked_bytes: 4 << 20, max_entries: 256, max_ratio: 200 };

fuzz_target!(|bytes: &[u8]| {
    let dir = tempfile::tempdir().expect("temporary folder");
    let archive = dir.path().join("model.fmu");
    std::fs::write(&archive, bytes).expect("write the input");
    let out = dir.path().join("out");
    std::fs::create_dir(&out).expect("output folder");
    let _ = extract_within(&archive, &out, &LIMITS);
    let mut written = 0;
    for entry in walk(dir.path()) {
        assert!(entry == archive || entry.starts_with(&out), "written outside the folder: {}", entry.display());
        if entry.starts_with(&out) {
            written += std::fs::symlink_metadata(&entry).map_or(0, |m| if m.is_file() { m.len() } else { 0 });
        }
    }
    assert!(written <= LIMITS.max_unpacked_bytes, "{written} bytes written");
});

/// Every path under `dir`, without following links.
fn walk(dir: &std::path::Path) -> Vec<std::path::PathBuf> {
    let mut paths = Vec::new();
    for entry in std::fs::read_dir(dir).into_iter().flatten().flatten() {
        let path = entry.path();
        if entry.file_type().is_ok_and(|t| t.is_dir()) {
            paths.extend(walk(&path));
        }
        paths.push(path);
    }
    paths
}
