//! Percentage changes of compensated runs against their uncompensated references (eq. 7.1) and
//! the group means the thesis summarises in Tables 7.1–7.3, beside its simulation columns.

use serde::Serialize;

use crate::matrix::{reference_of, Family, Motion, Variant};
use crate::results::RunResult;
use crate::scale::Scale;
use crane_metrics::{percent_change, MetricId};

/// The groups the thesis averages over.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, serde::Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Group {
    /// Table 7.1: tests 041–080 against 001–040.
    EnergyDissipation,
    /// Table 7.2, upper half: 089–091 against 081–083 (ship motion profiles 1–3).
    ShipMotion,
    /// Table 7.2, lower half: 092–096 against 084–088 (sine at the natural frequency).
    NaturalFrequency,
    /// Table 7.3: 102–104 against 098–100 (pick-and-place under profiles 1–3; the thesis'
    /// means leave out the no-motion pair 101/097).
    VariableSetpoint,
}

impl Group {
    pub fn title(self) -> &'static str {
        match self {
            Group::EnergyDissipation => "Table 7.1 — energy dissipation (041–080 vs 001–040)",
            Group::ShipMotion => "Table 7.2 — fixed set-point, ship motion (089–091 vs 081–083)",
            Group::NaturalFrequency => "Table 7.2 — fixed set-point, natural-frequency excitation (092–096 vs 084–088)",
            Group::VariableSetpoint => "Table 7.3 — variable set-point, profiles 1–3 (102–104 vs 098–100)",
        }
    }

    pub fn of(family: Family, motion: Motion) -> Option<Group> {
        match (family, motion) {
            (Family::EnergyDissipation, _) => Some(Group::EnergyDissipation),
            (Family::FixedSetpoint, Motion::NaturalFrequency(_)) => Some(Group::NaturalFrequency),
            (Family::FixedSetpoint, _) => Some(Group::ShipMotion),
            (Family::VariableSetpoint, Motion::Profile(_)) => Some(Group::VariableSetpoint),
            (Family::VariableSetpoint, _) => None,
        }
    }
}

/// What a mean reduction (%) must reach (docs/acceptance.md).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Acceptance {
    AtLeast(f64),
    Within { centre: f64, points: f64 },
}

impl Acceptance {
    pub fn holds(self, reduction: f64) -> bool {
        match self {
            Acceptance::AtLeast(limit) => reduction >= limit,
            Acceptance::Within { centre, points } => (reduction - centre).abs() <= points,
        }
    }

    pub fn describe(self) -> String {
        match self {
            Acceptance::AtLeast(limit) => format!("≥ {limit:.0} %"),
            Acceptance::Within { centre, points } => format!("{centre:.1} ± {points:.0} %"),
        }
    }
}

/// A row of Tables 7.1–7.3: the thesis' mean reductions (%; None where it gives none).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ThesisRow {
    /// The group of test pairs.
    pub group: Group,
    /// The metric reduced.
    pub metric: MetricId,
    /// The thesis' experimental mean reduction (%).
    pub experimental: Option<f64>,
    /// The thesis' simulated mean reduction (%) in variants 1 and 2.
    pub simulation: [Option<f64>; 2],
    /// The acceptance band of docs/acceptance.md in variants 1 and 2, where there is one.
    pub acceptance: [Option<Acceptance>; 2],
}

const fn row(
    group: Group,
    metric: MetricId,
    experimental: Option<f64>,
    simulation: [Option<f64>; 2],
    acceptance: [Option<Acceptance>; 2],
) -> ThesisRow {
    ThesisRow { group, metric, experimental, simulation, acceptance }
}

const AT_85: Option<Acceptance> = Some(Acceptance::AtLeast(85.0));
const NONE: [Option<Acceptance>; 2] = [None, None];

/// Tables 7.1–7.3 (the experimental ellipsoid change of Table 7.2 is an increase of 74.7 %),
/// with the acceptance figures of docs/acceptance.md.
pub const THESIS: [ThesisRow; 14] = [
    row(Group::EnergyDissipation, MetricId::TauThetaX, Some(88.7), [Some(89.7), Some(95.0)], [AT_85, AT_85]),
    row(Group::EnergyDissipation, MetricId::TauThetaY, Some(90.9), [Some(89.5), Some(94.7)], [AT_85, AT_85]),
    row(Group::EnergyDissipation, MetricId::TauHeight, Some(88.2), [Some(93.5), Some(97.2)], [AT_85, AT_85]),
    row(Group::EnergyDissipation, MetricId::Distance, Some(77.8), [Some(92.7), Some(95.2)], [AT_85, AT_85]),
    row(
        Group::EnergyDissipation,
        MetricId::Rmse,
        Some(54.8),
        [Some(72.2), Some(75.7)],
        [
            Some(Acceptance::Within { centre: 72.2, points: 15.0 }),
            Some(Acceptance::Within { centre: 75.7, points: 15.0 }),
        ],
    ),
    row(Group::ShipMotion, MetricId::EllipsoidVolume, Some(-74.7), [Some(66.8), Some(49.9)], NONE),
    row(Group::ShipMotion, MetricId::Distance, None, [None, None], NONE),
    row(Group::ShipMotion, MetricId::Rmse, Some(8.6), [Some(7.1), Some(25.5)], NONE),
    row(Group::NaturalFrequency, MetricId::EllipsoidVolume, Some(99.4), [Some(100.0), Some(100.0)], NONE),
    row(Group::NaturalFrequency, MetricId::Distance, Some(85.4), [Some(93.5), Some(89.6)], NONE),
    row(
        Group::NaturalFrequency,
        MetricId::Rmse,
        Some(80.1),
        [Some(89.6), Some(87.6)],
        [Some(Acceptance::AtLeast(80.0)), Some(Acceptance::AtLeast(80.0))],
    ),
    row(Group::VariableSetpoint, MetricId::EllipsoidVolume, Some(34.5), [Some(77.0), Some(52.9)], NONE),
    row(Group::VariableSetpoint, MetricId::Distance, Some(78.8), [None, None], NONE),
    row(Group::VariableSetpoint, MetricId::Rmse, Some(36.4), [Some(7.8), Some(29.9)], NONE),
];

const AT_80: Option<Acceptance> = Some(Acceptance::AtLeast(80.0));
const BOTH_80: [Option<Acceptance>; 2] = [AT_80, AT_80];

/// The full-scale campaign's bands (docs/full-scale.md, the goal of the full-scale crane): the
/// world-frame compensation reduces the swing's decay time constants and the set-point RMSE by
/// ≥ 80 % against the crane-off or joints-held twin, on the fixed set-point and on the
/// pick-and-place profile (Table 7.3's metrics, as at test scale); the thesis has no full-scale
/// figures.
pub const FULL_SCALE: [ThesisRow; 8] = [
    row(Group::EnergyDissipation, MetricId::TauThetaX, None, [None, None], BOTH_80),
    row(Group::EnergyDissipation, MetricId::TauThetaY, None, [None, None], BOTH_80),
    row(Group::EnergyDissipation, MetricId::Rmse, None, [None, None], NONE),
    row(Group::ShipMotion, MetricId::Rmse, None, [None, None], BOTH_80),
    row(Group::NaturalFrequency, MetricId::Rmse, None, [None, None], BOTH_80),
    row(Group::VariableSetpoint, MetricId::EllipsoidVolume, None, [None, None], NONE),
    row(Group::VariableSetpoint, MetricId::Distance, None, [None, None], NONE),
    row(Group::VariableSetpoint, MetricId::Rmse, None, [None, None], BOTH_80),
];

/// The rows and bands a campaign at `scale` is judged by.
pub fn bands(scale: Scale) -> &'static [ThesisRow] {
    match scale {
        Scale::Test => &THESIS,
        Scale::Full => &FULL_SCALE,
    }
}

/// The eq. 7.1 change (%) of one compensated run against its reference.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Change {
    /// The compensated run's id.
    pub id: String,
    /// Its reference run's id.
    pub reference: String,
    /// The group of test pairs it counts in.
    pub group: Group,
    /// The feedback variant of both runs.
    pub variant: Variant,
    /// (metric, change %) where both runs have the metric and the reference is non-zero.
    pub changes: Vec<(MetricId, f64)>,
}

/// Eq. 7.1 for every compensated run whose reference also ran.
pub fn changes(results: &[RunResult]) -> Vec<Change> {
    let find = |number: u16, variant: Variant| {
        results
            .iter()
            .find(|r| r.run.test.number == number && r.run.variant == variant)
            .and_then(|r| r.metrics.map(|m| (r, m)))
    };
    let mut out = Vec::new();
    for r in results {
        let (Some(metrics), Some(reference)) = (r.metrics, reference_of(&r.run.test)) else { continue };
        let (Some(group), Some((base, base_metrics))) =
            (Group::of(r.run.test.family, r.run.test.motion), find(reference, r.run.variant))
        else {
            continue;
        };
        let changes = MetricId::compared()
            .filter(|m| applies(*m, &r.run.test.theta0_deg))
            .filter_map(|m| match (metrics.get(m), base_metrics.get(m)) {
                (Some(v), Some(b)) if b != 0.0 => Some((m, percent_change(v, b))),
                _ => None,
            })
            .collect();
        out.push(Change { id: r.id.clone(), reference: base.id.clone(), group, variant: r.run.variant, changes });
    }
    out
}

/// The angle time constants are compared on the axis the load was released along (§7.2: the
/// off-axis response is a different phenomenon, reported per test but not averaged).
pub fn applies(metric: MetricId, theta0_deg: &[f64; 2]) -> bool {
    match metric {
        MetricId::TauThetaX => theta0_deg[0] != 0.0,
        MetricId::TauThetaY => theta0_deg[1] != 0.0,
        _ => true,
    }
}

/// Mean reduction (%, i.e. −mean change) of `metric` over `group` in `variant`, and how many
/// pairs it averages.
pub fn mean_reduction(changes: &[Change], group: Group, variant: Variant, metric: MetricId) -> Option<(f64, usize)> {
    let values: Vec<f64> = changes
        .iter()
        .filter(|c| c.group == group && c.variant == variant)
        .filter_map(|c| c.changes.iter().find(|(m, _)| *m == metric).map(|(_, v)| -v))
        .collect();
    (!values.is_empty()).then(|| (values.iter().sum::<f64>() / values.len() as f64, values.len()))
}

/// A band of docs/acceptance.md judged on a campaign: the row and variant it is for, and the
/// mean reduction (%) with its number of pairs, `None` when the selection has no pair for it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Verdict {
    /// The thesis' row judged.
    pub row: ThesisRow,
    /// The feedback variant judged.
    pub variant: Variant,
    /// The band the reduction must meet.
    pub acceptance: Acceptance,
    /// The mean reduction (%) and the pairs it averages; `None` without a pair.
    pub reduction: Option<(f64, usize)>,
}

impl Verdict {
    /// Met, or not; `None` without data.
    pub fn met(&self) -> Option<bool> {
        self.reduction.map(|(r, _)| self.acceptance.holds(r))
    }
}

/// Every band of [`bands`]`(scale)` (in table order, truth before sensor feedback) judged on
/// `changes`.
pub fn verdicts(changes: &[Change], scale: Scale) -> Vec<Verdict> {
    bands(scale)
        .iter()
        .flat_map(|row| {
            Variant::BOTH.into_iter().zip(row.acceptance).filter_map(move |(variant, acceptance)| {
                let reduction = mean_reduction(changes, row.group, variant, row.metric);
                acceptance.map(|acceptance| Verdict { row: *row, variant, acceptance, reduction })
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::matrix::{tests, RunSpec};
    use crane_metrics::run::Metrics;

    fn result(number: u16, variant: Variant, metrics: Metrics) -> RunResult {
        let run = RunSpec::new(tests()[number as usize - 1], variant);
        RunResult { id: run.id(), run, metrics: Some(metrics), error: None, simulated_time: 130.0, wall_time: 1.0 }
    }

    #[test]
    fn changes_pair_each_compensated_run_with_its_reference_by_eq_7_1() {
        let off = Metrics {
            tau_theta_x: Some(70.0),
            tau_theta_y: Some(100.0),
            tau_height: Some(35.0),
            distance: 20.0,
            rmse: 0.1,
            ..Metrics::default()
        };
        let on = Metrics {
            tau_theta_x: Some(7.0),
            tau_theta_y: Some(150.0),
            tau_height: Some(3.5),
            distance: 2.0,
            rmse: 0.03,
            ..Metrics::default()
        };
        // 060 (θx0 = −23°) against 020, and 092 (ωn 0.70 m) against 084.
        let results =
            vec![result(20, Variant::Truth, off), result(60, Variant::Truth, on), result(60, Variant::Sensors, on)];
        let changes = changes(&results);
        assert_eq!(changes.len(), 1, "060-2 has no reference run");
        let c = &changes[0];
        assert_eq!((c.id.as_str(), c.reference.as_str(), c.group), ("060-1", "020-1", Group::EnergyDissipation));
        let get = |m: MetricId| c.changes.iter().find(|(k, _)| *k == m).map(|(_, v)| *v);
        assert!((get(MetricId::TauThetaX).unwrap() + 90.0).abs() < 1e-12);
        assert_eq!(get(MetricId::TauThetaY), None, "off-axis time constants are not compared");
        assert!((get(MetricId::Rmse).unwrap() + 70.0).abs() < 1e-12);
        let (mean, n) = mean_reduction(&changes, Group::EnergyDissipation, Variant::Truth, MetricId::Distance).unwrap();
        assert!((mean - 90.0).abs() < 1e-12 && n == 1);
        assert_eq!(mean_reduction(&changes, Group::EnergyDissipation, Variant::Sensors, MetricId::Distance), None);
    }

    #[test]
    fn the_thesis_tables_compare_only_metrics_the_changes_carry() {
        let compared: Vec<MetricId> = MetricId::compared().collect();
        for row in THESIS.iter().chain(&FULL_SCALE) {
            assert!(compared.contains(&row.metric), "{} is in {:?} but not compared", row.metric, row.group);
        }
    }

    #[test]
    fn acceptance_limits() {
        assert!(Acceptance::AtLeast(85.0).holds(85.0) && !Acceptance::AtLeast(85.0).holds(84.9));
        let within = Acceptance::Within { centre: 72.2, points: 15.0 };
        assert!(within.holds(58.0) && within.holds(87.2) && !within.holds(57.1));
    }
}
