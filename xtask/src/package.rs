//! `cargo xtask package`: FMI 2.0 archives from the release cdylibs.
//!
//! The model description is not kept in the repository: it is read from the built library itself
//! (`fmi2rs_model_description`), so the XML and the binary always come from the same table.

use crate::{reference, root, run_command};
use anyhow::{anyhow, Context, Result};
use fmu_import::fmu::ModelDescription;
use std::ffi::{c_char, CStr};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use zip::write::SimpleFileOptions;

/// FMU crates; each crate's name is its modelIdentifier.
pub const FMUS: &[&str] = &["pendulum", "imu", "crane", "platform", "controller"];

pub fn package_all() -> Result<Vec<PathBuf>> {
    let mut build = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()));
    build.args(["build", "--release"]);
    for name in FMUS {
        build.args(["--package", name]);
    }
    run_command(&mut build)?;
    let out_dir = root().join("target/fmu");
    std::fs::create_dir_all(&out_dir)?;
    let paths = FMUS
        .iter()
        .map(|name| {
            let path = package(name, &out_dir).with_context(|| format!("packaging {name}"))?;
            println!("packaged {}", path.display());
            Ok(path)
        })
        .collect::<Result<Vec<_>>>()?;
    // The reference results come from running the archives just written.
    reference::write_all(FMUS, &out_dir)?;
    Ok(paths)
}

fn package(name: &str, out_dir: &Path) -> Result<PathBuf> {
    let library = root().join(format!("target/release/lib{name}.so"));
    let xml = model_description(&library)?;
    let readme = std::fs::read_to_string(root().join(format!("fmus/{name}/README.md")))
        .with_context(|| format!("fmus/{name}/README.md"))?;
    let path = out_dir.join(format!("{name}.fmu"));
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&path)?);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("modelDescription.xml", options)?;
    zip.write_all(xml.as_bytes())?;
    // The library is stored, not deflated: a master extracts it at every load, and copying is
    // far cheaper than inflating (the archive grows by about 1.5x).
    let stored = options.compression_method(zip::CompressionMethod::Stored).unix_permissions(0o755);
    zip.start_file(format!("binaries/linux64/{name}.so"), stored)?;
    zip.write_all(&std::fs::read(&library)?)?;
    zip.start_file("documentation/index.html", options)?;
    zip.write_all(documentation(name, &xml, &readme)?.as_bytes())?;
    zip.finish()?;
    Ok(path)
}

fn model_description(library: &Path) -> Result<String> {
    // SAFETY: the library is one of ours; loading it runs no initialisers with side effects.
    unsafe {
        let lib = libloading::Library::new(library).with_context(|| format!("loading {}", library.display()))?;
        // The library writes the text into our buffer (it keeps no copy): first the size, then
        // the text.
        let describe: libloading::Symbol<unsafe extern "C" fn(*mut c_char, usize) -> usize> =
            lib.get(b"fmi2rs_model_description")?;
        let mut buffer = vec![0u8; describe(std::ptr::null_mut(), 0)];
        describe(buffer.as_mut_ptr() as *mut c_char, buffer.len());
        let text = CStr::from_bytes_until_nul(&buffer)?.to_str()?.to_owned();
        if text.starts_with("<!-- error") {
            return Err(anyhow!("{text}"));
        }
        Ok(text)
    }
}

/// `documentation/index.html`: the model's readme and a port table rendered from the XML.
fn documentation(name: &str, xml: &str, readme: &str) -> Result<String> {
    let model = ModelDescription::parse(xml)?;
    let mut rows = String::new();
    for v in &model.variables {
        let start = v.start.as_ref().map_or(String::new(), |s| s.to_string());
        rows.push_str(&format!(
            "<tr><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            escape(&v.name),
            v.value_reference,
            v.causality,
            v.variability,
            escape(v.unit.as_deref().unwrap_or_default()),
            escape(&start),
            escape(v.description.as_deref().unwrap_or_default()),
        ));
    }
    Ok(format!(
        "<!DOCTYPE html>\n<html><head><meta charset=\"utf-8\"><title>{name}</title></head><body>\n\
         <pre>{}</pre>\n<h2>Variables</h2>\n<table border=\"1\">\n\
         <tr><th>name</th><th>vr</th><th>causality</th><th>variability</th><th>unit</th><th>start</th><th>description</th></tr>\n\
         {rows}</table>\n</body></html>\n",
        escape(readme)
    ))
}

fn escape(s: &str) -> String {
    s.replace('&', "&amp;").replace('<', "&lt;").replace('>', "&gt;")
}
