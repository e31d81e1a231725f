//! The README's quick start as written: every `crane-cosim` line of its first code block runs
//! (from the repository, its `out/` files in a temporary folder), and each later line reads only
//! what an earlier one wrote; and the minimal system file that docs/running.md shows is the one
//! in `systems/`, which runs with its tip motion table.
//!
//! Needs every FMU in `target/fmu` (`cargo xtask package`).

#[path = "../../test_support.rs"]
mod common;

use std::path::Path;

/// The lines of the first ```sh block after `heading` in `text`.
fn code_block<'a>(text: &'a str, heading: &str) -> Vec<&'a str> {
    let after = &text[text.find(heading).unwrap_or_else(|| panic!("no {heading:?}"))..];
    let start = after.find("```sh\n").expect("a sh block") + "```sh\n".len();
    let block = &after[start..];
    block[..block.find("```").expect("the block's end")].lines().collect()
}

/// A command line without its trailing comment, split at spaces (the quick start quotes nothing).
fn words(line: &str) -> Vec<&str> {
    line.split(" #").next().unwrap_or_default().split_whitespace().collect()
}

#[test]
fn the_quick_start_runs_as_written() {
    let root = common::workspace_root();
    let readme = std::fs::read_to_string(root.join("README.md")).unwrap();
    let lines = code_block(&readme, "## Quick start");
    assert_eq!(lines.len(), 5, "a five-line quick start: {lines:?}");
    assert_eq!(words(lines[0]), ["cargo", "xtask", "demo"], "it starts with the demo");
    let out = tempfile::tempdir().unwrap();
    let mut stdout = String::new();
    for line in &lines[1..] {
        let words = words(line);
        assert_eq!(words[0], "target/release/crane-cosim", "{line}");
        // Files under out/ go to the temporary folder; the rest are the repository's.
        let args: Vec<String> = words[1..]
            .iter()
            .map(|w| match w.strip_prefix("out/") {
                Some(file) => out.path().join(file).display().to_string(),
                None => w.to_string(),
            })
            .collect();
        for input in args.iter().filter(|a| a.ends_with(".csv") && !line.contains(" -o ")) {
            assert!(Path::new(input).is_file(), "{line}: {input} was not written by an earlier line");
        }
        let output = common::crane_cosim_command().current_dir(&root).args(&args).output().expect("runs");
        assert!(output.status.success(), "{line}: {}", String::from_utf8_lossy(&output.stderr));
        stdout += &String::from_utf8_lossy(&output.stdout);
    }
    // The comparison it prints: the crane off never settles, compensated it does.
    let row =
        |name: &str| stdout.lines().find(|l| l.starts_with(name)).unwrap_or_else(|| panic!("{stdout}")).to_string();
    assert!(row("off ").contains("never"), "{stdout}");
    assert!(!row("compensated ").contains("never"), "{stdout}");
    assert!(out.path().join("compensated.html").is_file());
}

#[test]
fn the_minimal_system_file_of_the_documentation_is_in_the_repository_and_runs() {
    let root = common::workspace_root();
    let running = std::fs::read_to_string(root.join("docs/running.md")).unwrap();
    let after = &running[running.find("A minimal system file").expect("the minimal system file")..];
    let start = after.find("```json\n").unwrap() + "```json\n".len();
    let shown: serde_json::Value =
        serde_json::from_str(&after[start..start + after[start..].find("```").unwrap()]).unwrap();
    let file = root.join("systems/minimal_pendulum.json");
    let mut shipped: serde_json::Value = serde_json::from_str(&std::fs::read_to_string(&file).unwrap()).unwrap();
    shipped.as_object_mut().unwrap().remove("description");
    assert_eq!(shown, shipped, "docs/running.md shows systems/minimal_pendulum.json");
    let out = tempfile::tempdir().unwrap();
    let csv = out.path().join("min.csv");
    let output = common::crane_cosim_command()
        .args(["run", file.to_str().unwrap(), "-o", csv.to_str().unwrap()])
        .output()
        .expect("runs");
    assert!(output.status.success(), "{}", String::from_utf8_lossy(&output.stderr));
    // No warning: the tip motion table covers the whole run.
    assert!(!String::from_utf8_lossy(&output.stderr).contains("warning"), "{output:?}");
    assert_eq!(std::fs::read_to_string(&csv).unwrap().lines().count(), 6002, "header and 6001 rows");
}
