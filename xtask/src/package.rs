//! `cargo xtask package`: FMI 2.0 and FMI 3.0 archives from the release cdylibs.
//!
//! One library per FMU and platform exports both APIs (`fmi2*` and `fmi3*`), so the same binary
//! goes into `target/fmu/<model>.fmu` (FMI 2.0) and `target/fmu/fmi3/<model>.fmu` (FMI 3.0).
//! The model descriptions are not kept in the repository: they are read from the built library
//! itself (`fmi2rs_model_description`, `fmi3rs_model_description`), so the XML and the binary
//! always come from the same table. Each archive holds the x86_64 Linux library, the aarch64
//! Linux library and the Windows DLL when their cross toolchains are installed ([`aarch64`],
//! [`windows`]), in the version's platform folders ([`Version::platform_folder`]), and
//! `documentation/index.html` ([`documentation`]). The FMUs are the workspace crates with
//! `[package.metadata.fmu]` ([`crate::workspace`]); `target/fmu/index.json` lists what was
//! packaged ([`index`]).

pub mod aarch64;
mod cross;
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

/// Builds the libraries (aarch64 Linux and win64 too when their cross toolchains are installed),
/// writes the archives, their reference files and the index of both.
pub fn package_all() -> Result<Vec<PathBuf>> {
    let fmus = workspace::fmus()?;
    let names: Vec<&str> = fmus.iter().map(|f| f.name.as_str()).collect();
    let mut build = cargo();
    build.args(["build", "--release"]);
    for name in &names {
        build.args(["--package", name]);
    }
    run_command(&mut build)?;
    let mut platforms = vec![Platform::X86_64Linux];
    if aarch64::available() {
        aarch64::CROSS.build(&names)?;
        platforms.push(Platform::Aarch64Linux);
    } else {
        println!(
            "packaging no aarch64-linux binaries: the Rust target {} or {} is missing \
             (`cargo xtask test` installs both)",
            aarch64::TARGET,
            aarch64::LINKER
        );
    }
    if windows::available() {
        windows::CROSS.build(&names)?;
        platforms.push(Platform::X86_64Windows);
    } else {
        println!(
            "packaging no win64 binaries: the Rust target {} or {} (MinGW-w64) is missing \
             (`cargo xtask test` installs both)",
            windows::TARGET,
            windows::LINKER
        );
    }
    let generated = generation_date()?;
    let out_dir = root().join("target/fmu");
    std::fs::create_dir_all(out_dir.join(Version::Fmi3.folder()))?;
    let mut paths = Vec::new();
    for name in &names {
        for version in [Version::Fmi2, Version::Fmi3] {
            let path = package(name, version, &out_dir, &platforms, &generated)
                .with_context(|| format!("packaging {name} ({})", version.name()))?;
            println!("packaged {}", path.display());
            paths.push(path);
        }
    }
    // The reference results come from running the archives just written.
    let references = reference::write_all(&names, &out_dir)?;
    copy_references_for_fmi3(&out_dir, &references)?;
    index::write(&out_dir, &fmus, &platforms, &references)?;
    Ok(paths)
}

/// The cross-check files of the FMI 3.0 archives, next to them: the FMI 2.0 ones, since an FMI 3.0
/// archive runs the same binary to the same bits (tests/test_fmi3.py holds FMPy to it).
fn copy_references_for_fmi3(out_dir: &Path, references: &[reference::ReferenceFiles]) -> Result<()> {
    let fmi3 = out_dir.join(Version::Fmi3.folder());
    for files in references {
        for file in [Some(&files.options), files.inputs.as_ref(), Some(&files.results)].into_iter().flatten() {
            std::fs::copy(out_dir.join(file), fmi3.join(file))
                .with_context(|| format!("copying {file} for FMI 3.0"))?;
        }
    }
    Ok(())
}

/// The FMI version of an archive.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Version {
    Fmi2,
    Fmi3,
}

/// The platforms the archives carry binaries for.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Platform {
    X86_64Linux,
    Aarch64Linux,
    X86_64Windows,
}

impl Platform {
    /// The library of `name` for this platform: its file name in the archive and where the build
    /// left it.
    fn library(self, name: &str) -> (String, PathBuf) {
        match self {
            Platform::X86_64Linux => (format!("{name}.so"), root().join(format!("target/release/lib{name}.so"))),
            Platform::Aarch64Linux => (format!("{name}.so"), aarch64::library(name)),
            Platform::X86_64Windows => (format!("{name}.dll"), windows::dll(name)),
        }
    }
}

impl Version {
    pub fn name(self) -> &'static str {
        match self {
            Version::Fmi2 => "FMI 2.0",
            Version::Fmi3 => "FMI 3.0",
        }
    }

    /// The folder of `target/fmu` the archives of this version go to.
    pub fn folder(self) -> &'static str {
        match self {
            Version::Fmi2 => "",
            Version::Fmi3 => "fmi3",
        }
    }

    /// The symbol that writes this version's model description.
    fn describe_symbol(self) -> &'static [u8] {
        match self {
            Version::Fmi2 => b"fmi2rs_model_description",
            Version::Fmi3 => b"fmi3rs_model_description",
        }
    }

    /// The `binaries/` folder of `platform`: FMI 2.0's names (`linux64`, `win64`) or FMI 3.0's
    /// platform tuples (`x86_64-linux`, `aarch64-linux`, `x86_64-windows`).
    ///
    /// FMI 2.0 standardises only `win32`, `win64`, `linux32`, `linux64`, `darwin32` and
    /// `darwin64` and lets vendors introduce further names (FMI 2.0, section 2.3). It has none
    /// for aarch64 Linux, and the importers that run FMI 2.0 FMUs there have none either: FMPy
    /// (0.3.32, `fmpy/__init__.py`) sets `platform = 'linux64'` on an aarch64 machine (the bit
    /// width only; `platform_tuple = 'aarch64-linux'` serves FMI 3.0), and so does the Reference
    /// FMUs' importer fmusim (`include/FMI.h`: `FMI_PLATFORM` is system and bit width,
    /// `FMI_PLATFORM_TUPLE` architecture and system), whose releases carry aarch64-linux binaries
    /// in the FMI 3.0 archives only (`build/merge_binaries.py`). `linux64` holds the x86_64
    /// library here, so the FMI 2.0 archive uses the FMI 3.0 tuple `aarch64-linux` as its vendor
    /// name: importers that know the tuple find the library there, FMPy and fmusim on aarch64
    /// take the FMI 3.0 archive.
    pub fn platform_folder(self, platform: Platform) -> &'static str {
        match (self, platform) {
            (Version::Fmi2, Platform::X86_64Linux) => "linux64",
            (Version::Fmi2, Platform::Aarch64Linux) => "aarch64-linux",
            (Version::Fmi2, Platform::X86_64Windows) => "win64",
            (Version::Fmi3, Platform::X86_64Linux) => "x86_64-linux",
            (Version::Fmi3, Platform::Aarch64Linux) => "aarch64-linux",
            (Version::Fmi3, Platform::X86_64Windows) => "x86_64-windows",
        }
    }
}

/// Writes the `version` archive of `name` with its libraries for `platforms`; the model
/// description comes from the native (x86_64 Linux) library.
fn package(name: &str, version: Version, out_dir: &Path, platforms: &[Platform], generated: &str) -> Result<PathBuf> {
    let (_, library) = Platform::X86_64Linux.library(name);
    let xml = model_description(&library, version)?;
    let readme = std::fs::read_to_string(root().join(format!("fmus/{name}/README.md")))
        .with_context(|| format!("fmus/{name}/README.md"))?;
    let binaries: Vec<(&str, String, PathBuf)> = platforms
        .iter()
        .map(|&platform| {
            let (file, built) = platform.library(name);
            (version.platform_folder(platform), file, built)
        })
        .collect();
    let platforms: Vec<&str> = binaries.iter().map(|(platform, ..)| *platform).collect();
    let described = documented_model(&library, version, &xml)?;
    let page = documentation::page(&described, &readme, &PageFacts { platforms: &platforms, generated })?;
    let path = out_dir.join(version.folder()).join(format!("{name}.fmu"));
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

/// The model as its documentation page shows it. The page is built from the FMI 2.0 reading of
/// the variables (the same table in both versions: names, value references, units, causality);
/// for FMI 3.0 it states the version and the instantiation token of the FMI 3.0 description.
fn documented_model(library: &Path, version: Version, xml: &str) -> Result<ModelDescription> {
    let mut model = ModelDescription::parse(&model_description(library, Version::Fmi2)?)?;
    if version == Version::Fmi3 {
        model.fmi_version = "3.0".to_owned();
        model.guid = attribute(xml, "instantiationToken").context("the FMI 3.0 description has no token")?;
    }
    Ok(model)
}

/// The value of the first `name="…"` attribute in `xml`.
fn attribute(xml: &str, name: &str) -> Option<String> {
    let start = xml.find(&format!("{name}=\""))? + name.len() + 2;
    Some(xml[start..start + xml[start..].find('"')?].to_owned())
}

fn model_description(library: &Path, version: Version) -> Result<String> {
    // SAFETY: the library is one of ours; loading it runs no initialisers with side effects.
    unsafe {
        let lib = libloading::Library::new(library).with_context(|| format!("loading {}", library.display()))?;
        // The library writes the text into our buffer (it keeps no copy): first the size, then
        // the text.
        let describe: libloading::Symbol<unsafe extern "C" fn(*mut c_char, usize) -> usize> =
            lib.get(version.describe_symbol())?;
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
