//! PNG line plots of results CSVs (plotters, bitmap backend).
//!
//! Text needs a TrueType font: `CRANE_PLOT_FONT=<file.ttf>`, else the first DejaVu/Liberation
//! sans font (or any `.ttf`) under /usr/share/fonts. Without one, plots are drawn without text.

use std::path::{Path, PathBuf};
use std::sync::OnceLock;

use plotters::prelude::*;
use plotters::style::FontStyle;

/// One curve: a label and (t, value) samples.
pub struct Series {
    pub label: String,
    pub points: Vec<(f64, f64)>,
}

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

/// Draws `series` against time into a 1000×500 PNG at `out`.
pub fn line_plot(out: &Path, title: &str, y_label: &str, series: &[Series]) -> Result<(), String> {
    let text = register_font();
    let all = series.iter().flat_map(|s| s.points.iter());
    let (mut t0, mut t1, mut y0, mut y1) = (f64::INFINITY, f64::NEG_INFINITY, f64::INFINITY, f64::NEG_INFINITY);
    for &(t, y) in all {
        (t0, t1, y0, y1) = (t0.min(t), t1.max(t), y0.min(y), y1.max(y));
    }
    if !(t1 > t0) {
        return Err(format!("{}: nothing to plot", out.display()));
    }
    let pad = ((y1 - y0) * 0.05).max(1e-9);
    let draw = || -> Result<(), Box<dyn std::error::Error>> {
        let root = BitMapBackend::new(out, (1000, 500)).into_drawing_area();
        root.fill(&WHITE)?;
        let mut builder = ChartBuilder::on(&root);
        builder.margin(15).x_label_area_size(if text { 40 } else { 5 }).y_label_area_size(if text { 70 } else { 5 });
        if text {
            builder.caption(title, ("sans-serif", 20));
        }
        let mut chart = builder.build_cartesian_2d(t0..t1, (y0 - pad)..(y1 + pad))?;
        let mut mesh = chart.configure_mesh();
        if text {
            mesh.x_desc("time (s)").y_desc(y_label);
        } else {
            mesh.disable_x_axis().disable_y_axis();
        }
        mesh.draw()?;
        for (i, s) in series.iter().enumerate() {
            let color = Palette99::pick(i).to_rgba();
            let drawn = chart.draw_series(LineSeries::new(s.points.iter().copied(), color.stroke_width(2)))?;
            if text {
                drawn.label(s.label.clone()).legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 20, y)], color));
            }
        }
        if text {
            chart.configure_series_labels().background_style(WHITE.mix(0.8)).border_style(BLACK).draw()?;
        }
        root.present()?;
        Ok(())
    };
    draw().map_err(|e| format!("{}: {e}", out.display()))
}
