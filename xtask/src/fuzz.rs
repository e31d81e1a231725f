//! `cargo xtask fuzz`: the cargo-fuzz targets of fuzz/ (modelDescription.xml, system and scenario
//! files, .fmu archives), each run for a while from a seed corpus built from the repository's
//! own files. Needs a nightly toolchain and cargo-fuzz; both are installed on first use.

use crate::{root, run_command, setup};
use anyhow::{Context, Result};
use std::path::{Path, PathBuf};
use std::process::Command;

/// The fuzz targets (`fuzz/fuzz_targets/<name>.rs`).
const TARGETS: [&str; 3] = ["model_description", "system_file", "archive"];

/// Runs every target for `seconds` seconds (libFuzzer's `-max_total_time`); a crash, a panic,
/// a timeout of one input (10 s) or a leak fails the task and leaves the input in
/// `fuzz/artifacts/<target>/`.
pub fn fuzz(seconds: u64) -> Result<()> {
    setup::cargo_fuzz()?;
    for target in TARGETS {
        let corpus = seed_corpus(target)?;
        run_command(
            Command::new("cargo").args(["+nightly", "fuzz", "run", "--fuzz-dir", "fuzz", target]).arg(&corpus).args([
                "--",
                &format!("-max_total_time={seconds}"),
                "-timeout=10",
                "-rss_limit_mb=2048",
            ]),
        )
        .with_context(|| format!("fuzz target {target}"))?;
    }
    Ok(())
}

/// `target/fuzz-corpus/<target>/`, seeded with the repository's own files of that kind.
fn seed_corpus(target: &str) -> Result<PathBuf> {
    let corpus = root().join("target/fuzz-corpus").join(target);
    std::fs::create_dir_all(&corpus)?;
    match target {
        "model_description" => seed_model_descriptions(&corpus)?,
        "system_file" => {
            copy_matching(&root().join("systems"), "json", &corpus)?;
            copy_matching(&root().join("scenarios"), "json", &corpus)?;
        }
        _ => seed_archives(&corpus)?,
    }
    Ok(corpus)
}

/// Copies the files of `dir` ending in `.extension` into `corpus`.
fn copy_matching(dir: &Path, extension: &str, corpus: &Path) -> Result<()> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Ok(()) };
    for entry in entries {
        let path = entry?.path();
        if path.extension().is_some_and(|e| e == extension) {
            let name = path.file_name().context("file name")?;
            std::fs::copy(&path, corpus.join(name))?;
        }
    }
    Ok(())
}

/// The model descriptions inside the packaged FMUs (target/fmu/*.fmu), when they exist.
fn seed_model_descriptions(corpus: &Path) -> Result<()> {
    for (name, archive) in packaged_fmus()? {
        let mut zip = zip::ZipArchive::new(std::fs::File::open(&archive)?)?;
        let mut xml = String::new();
        std::io::Read::read_to_string(&mut zip.by_name("modelDescription.xml")?, &mut xml)?;
        std::fs::write(corpus.join(format!("{name}.xml")), xml)?;
    }
    Ok(())
}

/// Small archives shaped like FMUs (a model description and a resource, stored and deflated):
/// the packaged FMUs themselves are megabytes, beyond libFuzzer's input sizes.
fn seed_archives(corpus: &Path) -> Result<()> {
    use std::io::Write;
    for (name, method) in
        [("stored.fmu", zip::CompressionMethod::Stored), ("deflated.fmu", zip::CompressionMethod::Deflated)]
    {
        let mut writer = zip::ZipWriter::new(std::fs::File::create(corpus.join(name))?);
        let options = zip::write::SimpleFileOptions::default().compression_method(method);
        writer.start_file("modelDescription.xml", options)?;
        writer.write_all(br#"<fmiModelDescription fmiVersion="2.0" modelName="m" guid="g"/>"#)?;
        writer.add_directory("resources/", options)?;
        writer.start_file("resources/table.csv", options)?;
        writer.write_all(b"time,x\n0,0\n1,1\n")?;
        writer.finish()?;
    }
    Ok(())
}

/// (model name, path) of each target/fmu/*.fmu.
fn packaged_fmus() -> Result<Vec<(String, PathBuf)>> {
    let Ok(entries) = std::fs::read_dir(root().join("target/fmu")) else { return Ok(Vec::new()) };
    let mut fmus = Vec::new();
    for entry in entries {
        let path = entry?.path();
        if path.extension().is_some_and(|e| e == "fmu") {
            let stem = path.file_stem().context("file stem")?.to_string_lossy().into_owned();
            fmus.push((stem, path));
        }
    }
    Ok(fmus)
}
