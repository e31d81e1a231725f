//! The catalogue of the thesis' §7.2.2 performance metrics: each metric's name, unit, titles,
//! display scale and what it measures, defined here once. The campaign's summary, its report
//! and figures, and the sweep studies take their names and labels from [`MetricId::info`]; the
//! values come from [`crate::run::Metrics::get`].

use std::fmt;

use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A §7.2.2 metric of one run, in catalogue order (the column order of `metrics.csv`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum MetricId {
    /// Time constant τ of the exponential decay A·e^(−t/τ) fitted by least squares to the θx
    /// peaks on the side opposite to the release (§7.2, eqs. 7.3–7.6, Figs. 7.2/7.3; see
    /// [`super::decay`]); none without three significant decaying peaks.
    TauThetaX,
    /// As [`MetricId::TauThetaX`] for θy.
    TauThetaY,
    /// Time constant of the decay of the height peaks above the set-point (§7.2); the height
    /// peaks twice per swing period.
    TauHeight,
    /// Sum of the load's frame-to-frame moves over the 3 mm threshold at the 30 Hz capture rate
    /// (§7.2.2).
    Distance,
    /// Volume 4/3·π·s₁s₂s₃ of the ellipsoid holding 95 % of the load positions relative to the
    /// set-point (§7.2.2, Figs. 7.4/7.5; see [`mod@super::ellipsoid`]).
    EllipsoidVolume,
    /// √(mean |p − p_sp|²) of the load position p against the set-point p_sp at 30 Hz (§7.2.2).
    Rmse,
    /// Largest height of the load above the set-point (§7.2).
    PeakHeight,
    /// Largest |θx| of the cable, from the crane tip to the load (§7.2).
    PeakThetaX,
    /// Largest |θy| of the cable (§7.2).
    PeakThetaY,
}

/// An SI unit of a metric's value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Unit {
    Second,
    Metre,
    CubicMetre,
    Radian,
}

impl Unit {
    /// The symbol in text ("m³").
    pub const fn symbol(self) -> &'static str {
        match self {
            Unit::Second => "s",
            Unit::Metre => "m",
            Unit::CubicMetre => "m³",
            Unit::Radian => "rad",
        }
    }

    /// The symbol in ASCII column names ("m3", as in `ellipsoid_volume_m3`).
    pub const fn ascii(self) -> &'static str {
        match self {
            Unit::CubicMetre => "m3",
            other => other.symbol(),
        }
    }
}

/// How a metric is shown in tables and charts: in `unit`, i.e. the SI value × `scale`, with
/// `digits` decimals.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Display {
    /// The unit shown, e.g. `"mm"`.
    pub unit: &'static str,
    /// Shown value per SI value.
    pub scale: f64,
    /// Decimals shown.
    pub digits: usize,
}

impl Display {
    /// The SI value `value` in the displayed unit.
    pub fn scaled(self, value: f64) -> f64 {
        value * self.scale
    }

    /// The SI value `value` in the displayed unit, with [`Display::digits`] decimals.
    pub fn format(self, value: f64) -> String {
        format!("{:.*}", self.digits, self.scaled(value))
    }
}

/// Where a metric comes from, i.e. what a sweep must record and evaluate for it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Source {
    /// The load (`pendulum.load.*`) against its set-point (`controller.sp.load.*`).
    LoadAgainstSetpoint,
    /// The swing evaluation: load, set-point and crane tip (`crane.tip.*`), the window's start
    /// taken as the release.
    Swing,
}

/// Everything the campaign and the sweeps say about one metric.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MetricInfo {
    /// The metric.
    pub id: MetricId,
    /// The identifier in study files, in sweep results and (with the unit) in `metrics.csv`.
    pub name: &'static str,
    /// The SI unit of its value.
    pub unit: Unit,
    /// What it measures, in a sentence.
    pub measures: &'static str,
    /// The row title of the report's tables ("Set-point tracking RMSE").
    pub title: &'static str,
    /// The name inside a chart title ("RMSE from the set-point").
    pub chart_title: &'static str,
    /// The chart axis' name, before the displayed unit ("RMSE").
    pub axis: &'static str,
    /// The per-run table's column name, before the displayed unit ("RMSE").
    pub column: &'static str,
    /// How it is shown in tables and charts.
    pub display: Display,
    /// Values that span orders of magnitude between runs: a logarithmic chart axis.
    pub log_axis: bool,
    /// What a sweep must record and evaluate for it.
    pub source: Source,
    /// Compared between runs by eq. 7.1 in the thesis' Tables 7.1–7.3, and a column of the
    /// report's per-run table (the peaks are neither).
    pub compared: bool,
}

const SECONDS: Display = Display { unit: "s", scale: 1.0, digits: 1 };
const MILLIMETRES: Display = Display { unit: "mm", scale: 1e3, digits: 1 };
const DEGREES: Display = Display { unit: "deg", scale: 180.0 / std::f64::consts::PI, digits: 2 };

/// The catalogue, indexed by `MetricId as usize`.
pub const CATALOGUE: [MetricInfo; 9] = [
    MetricInfo {
        id: MetricId::TauThetaX,
        name: "tau_theta_x",
        unit: Unit::Second,
        measures: "how fast the θx swing decays",
        title: "θx time constant",
        chart_title: "time constant of θx",
        axis: "τθx",
        column: "τθx",
        display: SECONDS,
        log_axis: false,
        source: Source::Swing,
        compared: true,
    },
    MetricInfo {
        id: MetricId::TauThetaY,
        name: "tau_theta_y",
        unit: Unit::Second,
        measures: "how fast the θy swing decays",
        title: "θy time constant",
        chart_title: "time constant of θy",
        axis: "τθy",
        column: "τθy",
        display: SECONDS,
        log_axis: false,
        source: Source::Swing,
        compared: true,
    },
    MetricInfo {
        id: MetricId::TauHeight,
        name: "tau_height",
        unit: Unit::Second,
        measures: "how fast the load's vertical bounce above the set-point decays",
        title: "Height time constant",
        chart_title: "time constant of the height",
        axis: "τ height",
        column: "τh",
        display: SECONDS,
        log_axis: false,
        source: Source::Swing,
        compared: true,
    },
    MetricInfo {
        id: MetricId::Distance,
        name: "distance",
        unit: Unit::Metre,
        measures: "how far the load moves, measurement noise left out",
        title: "Distance travelled",
        chart_title: "distance travelled",
        axis: "distance travelled",
        column: "Distance",
        display: Display { unit: "m", scale: 1.0, digits: 3 },
        log_axis: false,
        source: Source::LoadAgainstSetpoint,
        compared: true,
    },
    MetricInfo {
        id: MetricId::EllipsoidVolume,
        name: "ellipsoid_volume",
        unit: Unit::CubicMetre,
        measures: "how widely the load scatters around its set-point",
        title: "Ellipsoid volume",
        chart_title: "95 % ellipsoid volume",
        axis: "ellipsoid volume",
        column: "Ellipsoid",
        display: Display { unit: "cm³", scale: 1e6, digits: 3 },
        // Compensated and uncompensated volumes differ by orders of magnitude.
        log_axis: true,
        source: Source::LoadAgainstSetpoint,
        compared: true,
    },
    MetricInfo {
        id: MetricId::Rmse,
        name: "rmse",
        unit: Unit::Metre,
        measures: "how closely the load tracks its set-point",
        title: "Set-point tracking RMSE",
        chart_title: "RMSE from the set-point",
        axis: "RMSE",
        column: "RMSE",
        display: MILLIMETRES,
        log_axis: false,
        source: Source::LoadAgainstSetpoint,
        compared: true,
    },
    MetricInfo {
        id: MetricId::PeakHeight,
        name: "peak_height",
        unit: Unit::Metre,
        measures: "how high the load bounces above its set-point",
        title: "Peak height",
        chart_title: "peak height above the set-point",
        axis: "peak height",
        column: "Peak h",
        display: MILLIMETRES,
        log_axis: false,
        source: Source::Swing,
        compared: false,
    },
    MetricInfo {
        id: MetricId::PeakThetaX,
        name: "peak_theta_x",
        unit: Unit::Radian,
        measures: "how far the cable swings in θx",
        title: "Peak θx",
        chart_title: "peak |θx|",
        axis: "peak θx",
        column: "Peak θx",
        display: DEGREES,
        log_axis: false,
        source: Source::Swing,
        compared: false,
    },
    MetricInfo {
        id: MetricId::PeakThetaY,
        name: "peak_theta_y",
        unit: Unit::Radian,
        measures: "how far the cable swings in θy",
        title: "Peak θy",
        chart_title: "peak |θy|",
        axis: "peak θy",
        column: "Peak θy",
        display: DEGREES,
        log_axis: false,
        source: Source::Swing,
        compared: false,
    },
];

/// Every metric's [`MetricInfo::name`], in catalogue order.
pub const NAMES: [&str; CATALOGUE.len()] = {
    let mut names = [""; CATALOGUE.len()];
    let mut i = 0;
    while i < names.len() {
        names[i] = CATALOGUE[i].name;
        i += 1;
    }
    names
};

impl MetricId {
    /// Every metric, in catalogue order.
    pub const ALL: [MetricId; CATALOGUE.len()] = {
        let mut ids = [MetricId::TauThetaX; CATALOGUE.len()];
        let mut i = 0;
        while i < ids.len() {
            ids[i] = CATALOGUE[i].id;
            i += 1;
        }
        ids
    };

    /// This metric's catalogue entry.
    pub const fn info(self) -> &'static MetricInfo {
        &CATALOGUE[self as usize]
    }

    pub const fn name(self) -> &'static str {
        self.info().name
    }

    /// The metric named `name` in study files, if any.
    pub fn from_name(name: &str) -> Option<MetricId> {
        CATALOGUE.iter().find(|info| info.name == name).map(|info| info.id)
    }

    /// The metrics eq. 7.1 compares ([`MetricInfo::compared`]), in catalogue order.
    pub fn compared() -> impl Iterator<Item = MetricId> {
        MetricId::ALL.into_iter().filter(|id| id.info().compared)
    }

    /// A decay time constant (only a free swing decays; see the report).
    pub fn is_time_constant(self) -> bool {
        matches!(self, MetricId::TauThetaX | MetricId::TauThetaY | MetricId::TauHeight)
    }

    /// "ellipsoid volume (cm³)": the chart axis' label, in the displayed unit.
    pub fn axis_label(self) -> String {
        format!("{} ({})", self.info().axis, self.info().display.unit)
    }

    /// "Ellipsoid (cm³)": the per-run table's column header, in the displayed unit.
    pub fn column_label(self) -> String {
        format!("{} ({})", self.info().column, self.info().display.unit)
    }

    /// "ellipsoid_volume_m3": the column of `metrics.csv`, SI unit in ASCII.
    pub fn csv_column(self) -> String {
        format!("{}_{}", self.name(), self.info().unit.ascii())
    }
}

impl fmt::Display for MetricId {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Written in kebab case ("tau-theta-x"), the spelling `changes.json` has always had.
impl Serialize for MetricId {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(&self.name().replace('_', "-"))
    }
}

/// Read by [`MetricInfo::name`], as in study files; an unknown name lists the catalogue's.
impl<'de> Deserialize<'de> for MetricId {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        MetricId::from_name(&name).ok_or_else(|| serde::de::Error::unknown_variant(&name, &NAMES))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_catalogue_is_indexed_by_id_and_names_each_metric_once() {
        for (index, info) in CATALOGUE.iter().enumerate() {
            assert_eq!(info.id as usize, index, "{} is out of place", info.name);
            assert_eq!(MetricId::from_name(info.name), Some(info.id));
        }
        let mut names = NAMES.to_vec();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), CATALOGUE.len(), "a name is given twice");
    }

    #[test]
    fn names_are_written_in_kebab_case_and_read_in_snake_case() {
        let json = serde_json::to_string(&MetricId::EllipsoidVolume).unwrap();
        assert_eq!(json, "\"ellipsoid-volume\"");
        let read: MetricId = serde_json::from_str("\"ellipsoid_volume\"").unwrap();
        assert_eq!(read, MetricId::EllipsoidVolume);
        let error = serde_json::from_str::<MetricId>("\"tau_theta\"").unwrap_err().to_string();
        assert!(error.starts_with("unknown variant `tau_theta`, expected one of `tau_theta_x`, "), "{error}");
    }

    #[test]
    fn labels_carry_the_displayed_unit() {
        assert_eq!(MetricId::EllipsoidVolume.axis_label(), "ellipsoid volume (cm³)");
        assert_eq!(MetricId::TauHeight.column_label(), "τh (s)");
        assert_eq!(MetricId::EllipsoidVolume.csv_column(), "ellipsoid_volume_m3");
        assert_eq!(MetricId::Rmse.info().display.format(0.01234), "12.3");
    }
}
