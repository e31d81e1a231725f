//! Ship motion profiles 1–3 at full and test scale: CSV files and plots in the style of the
//! thesis' Fig. 3.8 (full scale on the left axis, test scale on the right).
//!
//! ```text
//! cargo run --release -p platform --example profiles -- <out_dir>
//! ```
//!
//! Writes, per profile n, `profile<n>_full.csv` and `profile<n>_test.csv` (time, surge, sway,
//! heave, roll, pitch, yaw in SI units: the motion-file format of profile 5), `profile<n>_la.csv`
//! (time, LA1–LA5 set-points in m, crane at the port side) and `profile<n>.png`. The plots need a
//! TrueType font, found as the cosim-plot plots find it (`CRANE_PLOT_FONT=<file.ttf>`, else a
//! DejaVu/Liberation sans font or any `.ttf` under /usr/share/fonts).

use physics::motion::{DOF_NAMES, ROLL};
use physics::platform::kinematics::{exact_inverse, PlatformGeometry};
use physics::ship::motion::HarmonicMotion;
use physics::ship::profiles::{test_scale, Profile, PROFILES, WINDOW};
use physics::ship::rao::Hull;
use plotters::prelude::*;
use std::error::Error;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

/// Sampling step of the files and plots (s).
const STEP: f64 = 0.05;

fn main() {
    let Some(out) = std::env::args_os().nth(1).map(PathBuf::from) else {
        eprintln!("usage: cargo run --release -p platform --example profiles -- <out_dir>");
        std::process::exit(2);
    };
    if let Err(e) = run(&out) {
        eprintln!("error: {e}");
        std::process::exit(1);
    }
}

fn run(out: &Path) -> Result<(), Box<dyn Error>> {
    std::fs::create_dir_all(out)?;
    if !cosim_plot::register_font() {
        return Err("no TrueType font found: set CRANE_PLOT_FONT to a .ttf file".into());
    }
    let (hull, geom) = (Hull::default(), PlatformGeometry::default());
    for p in &PROFILES {
        let full = p.full_scale(&hull, p.seed);
        let scaled = test_scale(&full, &geom)?;
        let times: Vec<f64> = (0..=(WINDOW / STEP).round() as usize).map(|k| k as f64 * STEP).collect();
        let full_rows: Vec<[f64; 6]> = times.iter().map(|&t| full.sample(t).pose()).collect();
        let test_rows: Vec<[f64; 6]> = times.iter().map(|&t| scaled.motion.sample(t).pose()).collect();
        write_motion(&out.join(format!("profile{}_full.csv", p.number)), &times, &full_rows)?;
        write_motion(&out.join(format!("profile{}_test.csv", p.number)), &times, &test_rows)?;
        let mut la = String::from("time,la1,la2,la3,la4,la5\n");
        for (t, r) in times.iter().zip(&test_rows) {
            let s = exact_inverse(&geom, &[r[0], r[1], r[2], r[3], r[4]])?;
            let _ = writeln!(la, "{t},{}", s.la.map(|x| x.to_string()).join(","));
        }
        std::fs::write(out.join(format!("profile{}_la.csv", p.number)), la)?;
        let png = out.join(format!("profile{}.png", p.number));
        plot(&png, p, &full, scaled.scale, &times, &full_rows, &test_rows)?;
        println!("profile {}: test scale 1:{:.1} -> {}", p.number, 1.0 / scaled.scale, png.display());
    }
    Ok(())
}

fn write_motion(path: &Path, times: &[f64], rows: &[[f64; 6]]) -> std::io::Result<()> {
    let mut text = String::from("time,surge,sway,heave,roll,pitch,yaw\n");
    for (t, r) in times.iter().zip(rows) {
        let _ = writeln!(text, "{t},{}", r.map(|x| x.to_string()).join(","));
    }
    std::fs::write(path, text)
}

/// Six panels, one per degree of freedom: full scale (m, deg) on the left axis, test scale (mm,
/// deg) on the right, the right axis mapped so both curves lie on top of each other.
#[allow(clippy::too_many_arguments)]
fn plot(
    path: &Path,
    p: &Profile,
    full: &HarmonicMotion,
    scale: f64,
    times: &[f64],
    full_rows: &[[f64; 6]],
    test_rows: &[[f64; 6]],
) -> Result<(), Box<dyn Error>> {
    let root = BitMapBackend::new(path, (1000, 1500)).into_drawing_area();
    root.fill(&WHITE)?;
    let title = format!("Ship motion profile {}: {} (test scale 1:{:.1})", p.number, p.description, 1.0 / scale);
    let root = root.titled(&title, ("sans-serif", 16))?;
    let mean = full.window_mean(0.0, WINDOW);
    for (j, area) in root.split_evenly((6, 1)).iter().enumerate() {
        let angle = j >= ROLL;
        let (unit, factor) = if angle { ("deg", 180.0 / std::f64::consts::PI) } else { ("m", 1.0) };
        let (test_unit, test_factor) = if angle { ("deg", factor) } else { ("mm", 1000.0 * scale) };
        let column = |rows: &[[f64; 6]], f: f64| rows.iter().map(|r| r[j] * f).collect::<Vec<_>>();
        let (f_values, t_values) = (column(full_rows, factor), column(test_rows, if angle { factor } else { 1000.0 }));
        let lo = f_values.iter().copied().fold(f64::INFINITY, f64::min);
        let hi = f_values.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        let pad = ((hi - lo) * 0.08).max(1e-3);
        let (lo, hi) = (lo - pad, hi + pad);
        let offset = mean[j] * factor;
        let (test_lo, test_hi) = if j == 5 {
            (-1.0, 1.0)
        } else {
            ((lo - offset) * test_factor / factor, (hi - offset) * test_factor / factor)
        };
        let mut chart = ChartBuilder::on(area)
            .caption(DOF_NAMES[j], ("sans-serif", 16))
            .margin(6)
            .x_label_area_size(28)
            .y_label_area_size(64)
            .right_y_label_area_size(64)
            .build_cartesian_2d(0.0..WINDOW, lo..hi)?
            .set_secondary_coord(0.0..WINDOW, test_lo..test_hi);
        chart
            .configure_mesh()
            .y_desc(format!("full scale ({unit})"))
            .x_desc(if j == 5 { "time (s)" } else { "" })
            .label_style(("sans-serif", 12))
            .draw()?;
        chart
            .configure_secondary_axes()
            .y_desc(format!("test scale ({test_unit})"))
            .label_style(("sans-serif", 12))
            .draw()?;
        chart
            .draw_series(LineSeries::new(times.iter().copied().zip(f_values), BLUE.stroke_width(2)))?
            .label("full scale")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], BLUE.stroke_width(2)));
        chart
            .draw_secondary_series(LineSeries::new(times.iter().copied().zip(t_values), RED.stroke_width(1)))?
            .label("test scale")
            .legend(|(x, y)| PathElement::new([(x, y), (x + 18, y)], RED));
        chart
            .configure_series_labels()
            .position(SeriesLabelPosition::UpperRight)
            .background_style(WHITE.mix(0.8))
            .border_style(BLACK)
            .label_font(("sans-serif", 11))
            .draw()?;
    }
    root.present()?;
    Ok(())
}
