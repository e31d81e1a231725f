//! What a use case has to tell the user besides its results.

use std::fmt;
use std::path::{Path, PathBuf};

use cosim_engine::system::SystemFiles;
use fmu_import::fmu::ExtractLimits;

/// A note or warning a use case returns instead of printing it; its `Display` is the line a
/// front end shows (`note: …`, `warning: …`, or the text of an announcement as it is).
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Notice {
    /// Something the user may want to know that changes nothing (a default taken, a file read).
    Note(String),
    /// Something that is likely not what the user meant (an input never fed, data that ends).
    Warning(String),
    /// What is about to run (the system file and its FMUs), shown before the work starts.
    Announcement(String),
}

impl fmt::Display for Notice {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Notice::Note(text) => write!(f, "note: {text}"),
            Notice::Warning(text) => write!(f, "warning: {text}"),
            Notice::Announcement(text) => f.write_str(text),
        }
    }
}

/// What a campaign or sweep is about to run: the system file and the FMU archives it names, as
/// absolute paths. A scenario can point into another checkout, and then it runs that checkout's
/// FMUs, which the user should see before the runs start. `None` for a file that cannot be read:
/// the run reports it in its own words.
pub fn announce_system(system: &Path, limits: ExtractLimits) -> Option<Notice> {
    let spec = SystemFiles::new(limits).spec(system).ok()?;
    let folder = system.parent().unwrap_or_else(|| Path::new(""));
    let mut text = format!("system: {}", absolute(system).display());
    for (alias, archive) in &spec.fmus {
        text.push_str(&format!("\n  FMU {alias}: {}", absolute(&folder.join(archive)).display()));
    }
    Some(Notice::Announcement(text))
}

/// `path` without `.` and `..`, from the root (as given when it cannot be resolved).
fn absolute(path: &Path) -> PathBuf {
    std::fs::canonicalize(path).or_else(|_| std::path::absolute(path)).unwrap_or_else(|_| path.to_path_buf())
}
