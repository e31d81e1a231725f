//! `cargo xtask package`: FMI 2.0 archives from the release cdylibs.
//!
//! The model description is not kept in the repository: it is read from the built library itself
//! (`fmi2rs_model_description`), so the XML and the binary always come from the same table.
//! Each archive holds `binaries/linux64/<model>.so`, `binaries/win64/<model>.dll` when the
//! Windows cross toolchain is installed ([`windows`]) and `documentation/index.html`
//! ([`documentation`]). The FMUs are the workspace crates with `[package.metadata.fmu]`
//! ([`crate::workspace`]); `target/fmu/index.json` lists what was packaged ([`index`]).

mod documentation;
mod index;
pub mod windows;

use crate::{cargo, reference, root, run_command, workspace};
use anyhow::{anyhow, Context, Result};
use documentation::PageFacts;
use fmu_import::fmu::ModelDescription;
use std::ffi::{c_char, CStr};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use zip::write::SimpleFileOptions;

/// Builds the libraries (win64 too when the cross toolchain is installed), writes the archives,
/// their reference files and the index of both.
pub fn package_all() -> Result<Vec<PathBuf>> {
    let fmus = workspace::fmus()?;
    let names: Vec<&str> = fmus.iter().map(|f| f.name.as_str()).collect();
    let mut build = cargo();
    build.args(["build", "--release"]);
    for name in &names {
        build.args(["--package", name]);
    }
    run_command(&mut build)?;
    let with_windows = windows::available();
    if with_windows {
        windows::build(&names)?;
    } else {
        println!(
            "packaging linux64 binaries only: the Rust target {} or {} (MinGW-w64) is missing \
             (`cargo xtask test` installs both)",
            windows::TARGET,
            windows::LINKER
        );
    }
    let generated = generation_date()?;
    let out_dir = root().join("target/fmu");
    std::fs::create_dir_all(&out_dir)?;
    let paths = names
        .iter()
        .map(|name| {
            let path =
                package(name, &out_dir, with_windows, &generated).with_context(|| format!("packaging {name}"))?;
            println!("packaged {}", path.display());
            Ok(path)
        })
        .collect::<Result<Vec<_>>>()?;
    // The reference results come from running the archives just written.
    let references = reference::write_all(&names, &out_dir)?;
    let platforms = if with_windows { &["linux64", "win64"][..] } else { &["linux64"] };
    index::write(&out_dir, &fmus, platforms, &references)?;
    Ok(paths)
}

fn package(name: &str, out_dir: &Path, with_windows: bool, generated: &str) -> Result<PathBuf> {
    let library = root().join(format!("target/release/lib{name}.so"));
    let xml = model_description(&library)?;
    let readme = std::fs::read_to_string(root().join(format!("fmus/{name}/README.md")))
        .with_context(|| format!("fmus/{name}/README.md"))?;
    let mut binaries = vec![("linux64", format!("{name}.so"), library)];
    if with_windows {
        binaries.push(("win64", format!("{name}.dll"), windows::dll(name)));
    }
    let platforms: Vec<&str> = binaries.iter().map(|(platform, ..)| *platform).collect();
    let page =
        documentation::page(&ModelDescription::parse(&xml)?, &readme, &PageFacts { platforms: &platforms, generated })?;
    let path = out_dir.join(format!("{name}.fmu"));
    let mut zip = zip::ZipWriter::new(std::fs::File::create(&path)?);
    let options = SimpleFileOptions::default().compression_method(zip::CompressionMethod::Deflated);
    zip.start_file("modelDescription.xml", options)?;
    zip.write_all(xml.as_bytes())?;
    // The libraries are stored, not deflated: an importer extracts one at every load, and copying is
    // far cheaper than inflating (the archive grows by about 1.5x).
    let stored = options.compression_method(zip::CompressionMethod::Stored).unix_permissions(0o755);
    for (platform, file, built) in &binaries {
        zip.start_file(format!("binaries/{platform}/{file}"), stored)?;
        zip.write_all(&std::fs::read(built).with_context(|| format!("reading {}", built.display()))?)?;
    }
    zip.start_file("documentation/index.html", options)?;
    zip.write_all(page.as_bytes())?;
    zip.finish()?;
    Ok(path)
}

/// The generation date of the FMUs, reproducible as reproducible builds define it:
/// `SOURCE_DATE_EPOCH` when set, else the time of the last commit, as ISO 8601 UTC.
fn generation_date() -> Result<String> {
    let epoch = match std::env::var("SOURCE_DATE_EPOCH") {
        Ok(value) => value,
        Err(_) => {
            let out = Command::new("git").args(["log", "-1", "--format=%ct"]).current_dir(root()).output()?;
            anyhow::ensure!(out.status.success(), "no SOURCE_DATE_EPOCH and no git history to date the FMUs");
            String::from_utf8(out.stdout)?
        }
    };
    let seconds: i64 = epoch.trim().parse().with_context(|| format!("SOURCE_DATE_EPOCH {epoch:?}"))?;
    Ok(iso8601_utc(seconds))
}

/// Seconds since 1970-01-01T00:00:00Z as `YYYY-MM-DDThh:mm:ssZ` (the proleptic Gregorian
/// calendar, by Howard Hinnant's days-to-civil algorithm).
fn iso8601_utc(seconds: i64) -> String {
    let (days, second_of_day) = (seconds.div_euclid(86_400), seconds.rem_euclid(86_400));
    let shifted = days + 719_468; // days since 0000-03-01
    let era = shifted.div_euclid(146_097);
    let day_of_era = shifted.rem_euclid(146_097);
    let year_of_era = (day_of_era - day_of_era / 1460 + day_of_era / 36_524 - day_of_era / 146_096) / 365;
    let day_of_year = day_of_era - (365 * year_of_era + year_of_era / 4 - year_of_era / 100);
    let month_index = (5 * day_of_year + 2) / 153; // 0 = March
    let day = day_of_year - (153 * month_index + 2) / 5 + 1;
    let month = if month_index < 10 { month_index + 3 } else { month_index - 9 };
    let year = year_of_era + era * 400 + i64::from(month <= 2);
    let (hour, minute, second) = (second_of_day / 3600, second_of_day / 60 % 60, second_of_day % 60);
    format!("{year:04}-{month:02}-{day:02}T{hour:02}:{minute:02}:{second:02}Z")
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

#[cfg(test)]
mod tests {
    use super::iso8601_utc;

    #[test]
    fn dates_are_iso8601_utc() {
        assert_eq!(iso8601_utc(0), "1970-01-01T00:00:00Z");
        // A leap day and the last second of a day, checked against `date -u -d @…`.
        assert_eq!(iso8601_utc(951_868_799), "2000-02-29T23:59:59Z");
        assert_eq!(iso8601_utc(1_798_761_600), "2027-01-01T00:00:00Z");
        assert_eq!(iso8601_utc(-1), "1969-12-31T23:59:59Z");
    }
}
