//! The instruction budgets of the closed loop (issue 13), in one place, and their check.
//!
//! Instructions, not seconds: callgrind counts hardly depend on the machine or its load, so the
//! check can fail a build without flaking (they vary by about 0.5 % between runs).

use super::report::Instructions;

/// Instructions per 10 ms macro step in still water, compensated (demo_still_compensated).
pub const STILL_WATER_PER_STEP: u64 = 25_000;
/// Instructions per macro step under ship profile 1, compensated with sensor noise
/// (demo_profile1_compensated).
pub const PROFILE_1_PER_STEP: u64 = 40_000;
/// Instructions of the start-up (load, instantiate, initialize, first step) with a ship profile.
pub const START_UP_WITH_PROFILE: u64 = 30_000_000;

/// The bench's cases (see `super::CASES`) and what they may cost.
pub const BUDGETS: [Budget; 4] = [
    Budget { case: "demo_still_compensated", measure: Measure::PerStep, limit: STILL_WATER_PER_STEP },
    Budget { case: "demo_profile1_compensated", measure: Measure::PerStep, limit: PROFILE_1_PER_STEP },
    Budget { case: "demo_profile1_compensated", measure: Measure::StartUp, limit: START_UP_WITH_PROFILE },
    Budget { case: super::HEAVIEST, measure: Measure::StartUp, limit: START_UP_WITH_PROFILE },
];

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "kebab-case")]
pub enum Measure {
    PerStep,
    StartUp,
}

impl Measure {
    pub fn label(self) -> &'static str {
        match self {
            Measure::PerStep => "instructions per macro step",
            Measure::StartUp => "start-up instructions",
        }
    }
}

#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
pub struct Budget {
    pub case: &'static str,
    pub measure: Measure,
    pub limit: u64,
}

/// A budget against what was measured.
#[derive(Debug, Clone, PartialEq, Eq, serde::Serialize)]
pub struct Verdict {
    #[serde(flatten)]
    pub budget: Budget,
    pub measured: u64,
    pub within: bool,
}

/// Every budget whose case was measured, with its verdict.
pub fn verdicts(measured: &[Instructions]) -> Vec<Verdict> {
    BUDGETS
        .iter()
        .filter_map(|budget| {
            let case = measured.iter().find(|m| m.case == budget.case)?;
            let value = match budget.measure {
                Measure::PerStep => case.per_step,
                Measure::StartUp => case.start_up,
            };
            Some(Verdict { budget: *budget, measured: value, within: value <= budget.limit })
        })
        .collect()
}

/// One line per exceeded budget, e.g. "demo_still_compensated: 286,000 instructions per macro
/// step > budget 25,000".
pub fn failures(verdicts: &[Verdict]) -> Vec<String> {
    verdicts
        .iter()
        .filter(|v| !v.within)
        .map(|v| {
            format!(
                "{}: {} {} > budget {}",
                v.budget.case,
                super::report::thousands(v.measured),
                v.budget.measure.label(),
                super::report::thousands(v.budget.limit)
            )
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn measured(case: &str, per_step: u64, start_up: u64) -> Instructions {
        Instructions {
            case: case.into(),
            scenario: format!("scenarios/{case}.json"),
            window_s: [11.0, 12.0],
            per_step,
            start_up,
            libraries: Vec::new(),
        }
    }

    #[test]
    fn each_budget_is_checked_against_its_own_case_and_measure() {
        let all = [
            measured("demo_still_compensated", 25_000, 40_000_000),
            measured("demo_profile1_compensated", 40_001, 30_000_000),
        ];
        let verdicts = verdicts(&all);
        // Still water: per step exactly at the budget passes, its start-up has no budget; profile
        // 1: one instruction over per step fails, the start-up at the budget passes; the heaviest
        // run was not measured, so it has no verdict.
        assert_eq!(verdicts.len(), 3);
        assert_eq!(verdicts.iter().map(|v| v.within).collect::<Vec<_>>(), [true, false, true]);
        assert_eq!(
            failures(&verdicts),
            ["demo_profile1_compensated: 40,001 instructions per macro step > budget 40,000"]
        );
    }
}
