//! The plots' font: plotters draws text only with a registered TrueType font, which this finds
//! once per process (`CRANE_PLOT_FONT=<file.ttf>`, else the first DejaVu/Liberation sans font or
//! any `.ttf` under /usr/share/fonts).

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::style::FontStyle;

/// Registers a sans-serif font once per process; false if none could be found.
pub fn register_font() -> bool {
    static REGISTERED: OnceLock<bool> = OnceLock::new();
    *REGISTERED.get_or_init(|| {
        let Some(bytes) = font_candidates().iter().find_map(|p| std::fs::read(p).ok()) else {
            return false;
        };
        // plotters keeps fonts for the whole run, hence the leak.
        let bytes: &'static [u8] = Box::leak(bytes.into_boxed_slice());
        plotters::style::register_font("sans-serif", FontStyle::Normal, bytes).is_ok()
    })
}

fn font_candidates() -> Vec<PathBuf> {
    let mut candidates: Vec<PathBuf> = std::env::var_os("CRANE_PLOT_FONT").map(PathBuf::from).into_iter().collect();
    for name in ["dejavu/DejaVuSans.ttf", "liberation/LiberationSans-Regular.ttf", "freefont/FreeSans.ttf"] {
        candidates.push(Path::new("/usr/share/fonts/truetype").join(name));
    }
    candidates.extend(find_ttf(Path::new("/usr/share/fonts"), 4));
    candidates
}

fn find_ttf(dir: &Path, depth: usize) -> Vec<PathBuf> {
    let Ok(entries) = std::fs::read_dir(dir) else { return Vec::new() };
    let mut found = Vec::new();
    for entry in entries.flatten() {
        let path = entry.path();
        if path.is_dir() && depth > 0 {
            found.extend(find_ttf(&path, depth - 1));
        } else if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("ttf")) {
            found.push(path);
        }
    }
    found.sort();
    found
}
