//! Expanding a study into numbered, deterministic cases.
//!
//! Unit samples u ∈ (0, 1) are drawn with ChaCha8 seeded by the study seed (one stream for
//! the whole plan, so a plan is the same on every machine) and mapped through the inverse
//! CDF of each parameter's distribution; a case's own seed is the SplitMix64 output for
//! (study seed, index): `mix(seed + (index + 1)·0x9E3779B97F4A7C15)`, i.e. the (index+1)-th
//! value of the SplitMix64 stream started at the study seed.

use rand_chacha::rand_core::{RngCore, SeedableRng};
use rand_chacha::ChaCha8Rng;
use serde::Serialize;

use super::normal::inverse_normal_cdf;
use super::study::{Sampling, Study, Values};
use crate::StudyError;

/// One case of a study.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Case {
    /// 0-based position in the plan.
    pub index: usize,
    /// The zero-padded index, e.g. `0007`: names the case's files.
    pub id: String,
    /// The case's seed (see the module documentation).
    pub seed: u64,
    /// `("instance.variable", value)` in the study's parameter order.
    pub values: Vec<(String, f64)>,
}

/// The most cases a study may plan unless the caller raises the limit: a million cases already
/// take hundreds of megabytes of plan and manifest, and a plan far larger exhausts memory.
pub const MAX_CASES: usize = 1_000_000;

/// How many cases `study` plans, without drawing them; `None` when the count does not fit in a
/// `usize` (a grid whose product overflows).
pub fn case_count(study: &Study) -> Option<usize> {
    match study.sampling {
        Sampling::Grid => study.parameters.iter().try_fold(1usize, |count, parameter| match &parameter.values {
            Values::Grid(values) => count.checked_mul(values.len()),
            _ => Some(count),
        }),
        Sampling::Random | Sampling::LatinHypercube | Sampling::Sobol => Some(study.cases.unwrap_or(0)),
    }
}

/// Refuses a study (read from `file`) planning more than `max` cases, before any is drawn.
pub fn check_case_count(study: &Study, file: &std::path::Path, max: usize) -> Result<(), StudyError> {
    match case_count(study) {
        Some(cases) if cases <= max => Ok(()),
        cases => Err(StudyError::TooManyCases {
            file: file.to_path_buf(),
            cases: cases.map_or_else(|| "more than 2^64".to_string(), |n| n.to_string()),
            max,
        }),
    }
}

/// The cases of `study`, numbered from 0; a sample that is infinite (a distribution too wide
/// for an f64) is refused with the parameter's name.
pub fn plan(study: &Study) -> Result<Vec<Case>, StudyError> {
    let count = case_count(study).unwrap_or(usize::MAX);
    let points: Vec<Vec<f64>> = match study.sampling {
        Sampling::LatinHypercube => latin_hypercube_points(study),
        Sampling::Grid | Sampling::Random | Sampling::Sobol => (0..count).map(|index| point(study, index)).collect(),
    };
    points.into_iter().enumerate().map(|(index, point)| new_case(study, index, count, point)).collect()
}

/// Case `index` of `study`'s plan, equal to `plan(study)?[index]` but computed alone where the
/// sampling allows, so that running one case of a large study neither draws nor stores the
/// others (see `point`).
pub fn case(study: &Study, index: usize) -> Result<Case, StudyError> {
    let count = case_count(study).unwrap_or(usize::MAX);
    if index >= count {
        return Err(StudyError::NoSuchCase { index, cases: count });
    }
    new_case(study, index, count, point(study, index))
}

/// The parameter values of case `index`: grid, its mixed-radix digits; random, the ChaCha8
/// stream from the case's first word; sobol, its own points. A latin hypercube pairs its strata
/// across all cases: it is drawn whole.
fn point(study: &Study, index: usize) -> Vec<f64> {
    match study.sampling {
        Sampling::Grid => grid_point(study, index),
        Sampling::Random => random_point(study, index),
        Sampling::Sobol => sobol_point(study, index),
        Sampling::LatinHypercube => latin_hypercube_points(study).swap_remove(index),
    }
}

/// Case `index` of a plan of `count` cases at `point`, refused if a sample is not finite.
fn new_case(study: &Study, index: usize, count: usize, point: Vec<f64>) -> Result<Case, StudyError> {
    check_finite_point(study, index, &point)?;
    Ok(Case {
        index,
        id: case_id(index, count),
        seed: case_seed(study.seed, index),
        values: study.parameters.iter().map(|p| p.name.clone()).zip(point).collect(),
    })
}

/// The id of case `index` of a plan of `count` cases: the index zero-padded to the width of
/// the last index, at least 4 digits.
pub fn case_id(index: usize, count: usize) -> String {
    let width = count.saturating_sub(1).to_string().len().max(4);
    format!("{index:0width$}")
}

/// The grid point of case `index`: its digits in the grids' lengths, the first parameter
/// slowest.
fn grid_point(study: &Study, index: usize) -> Vec<f64> {
    let grids: Vec<&[f64]> = study
        .parameters
        .iter()
        .filter_map(|p| match &p.values {
            Values::Grid(values) => Some(values.as_slice()),
            _ => None,
        })
        .collect();
    let mut rest = index;
    let mut point: Vec<f64> = grids
        .iter()
        .rev()
        .map(|grid| {
            let value = grid[rest % grid.len()];
            rest /= grid.len();
            value
        })
        .collect();
    point.reverse();
    point
}

/// Case `index` of random sampling: the plan's one stream read from the case's first unit
/// (two 32-bit ChaCha words per unit, one unit per parameter and case).
fn random_point(study: &Study, index: usize) -> Vec<f64> {
    let mut rng = ChaCha8Rng::seed_from_u64(study.seed);
    let dimensions = study.parameters.len() as u128;
    rng.set_word_pos(index as u128 * dimensions * 2);
    study.parameters.iter().map(|p| quantile(&p.values, unit(&mut rng))).collect()
}

/// Case `index` of the Owen-scrambled Sobol sequence of sobol_burley, scrambled by the study
/// seed folded to 32 bits. Its values are multiples of 2⁻²⁴ in [0, 1); half a step is added so
/// that none is 0 (where a normal's inverse CDF is infinite). The study checks the generator's
/// limits (2¹⁶ cases, 256 dimensions).
fn sobol_point(study: &Study, index: usize) -> Vec<f64> {
    let seed = (study.seed ^ (study.seed >> 32)) as u32;
    let half_step = 0.5 / (1u32 << 24) as f64;
    let index = index as u32;
    study
        .parameters
        .iter()
        .zip(0u32..)
        .map(|(p, d)| quantile(&p.values, f64::from(sobol_burley::sample(index, d, seed)) + half_step))
        .collect()
}

/// A sample of `point` (case `sample`) that is ±∞ (or NaN), as an error naming its parameter.
fn check_finite_point(study: &Study, sample: usize, point: &[f64]) -> Result<(), StudyError> {
    for (parameter, &value) in study.parameters.iter().zip(point) {
        if !value.is_finite() {
            return Err(StudyError::InfiniteSample {
                parameter: parameter.name.clone(),
                sample,
                value,
                distribution: parameter.values.describe(),
            });
        }
    }
    Ok(())
}

/// The seed of case `index` of a study seeded with `study_seed` (SplitMix64).
pub fn case_seed(study_seed: u64, index: usize) -> u64 {
    splitmix64(study_seed.wrapping_add((index as u64 + 1).wrapping_mul(GOLDEN_GAMMA)))
}

/// The integer start value of the `k`-th of a study's `seed_variables` for a case: 31 bits
/// (an FMI Integer is an i32) of SplitMix64 of the case seed + k, so that two instances of one
/// case never share a noise seed.
pub fn variable_seed(case_seed: u64, k: usize) -> i32 {
    (splitmix64(case_seed.wrapping_add(k as u64)) >> 33) as i32
}

const GOLDEN_GAMMA: u64 = 0x9E37_79B9_7F4A_7C15;

/// SplitMix64's output function (Steele, Lea, Flood 2014).
fn splitmix64(state: u64) -> u64 {
    let mut z = state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    z ^ (z >> 31)
}

/// The latin hypercube's points of `study` (all of its cases).
fn latin_hypercube_points(study: &Study) -> Vec<Vec<f64>> {
    let mut rng = ChaCha8Rng::seed_from_u64(study.seed);
    let units = latin_hypercube(&mut rng, study.cases.unwrap_or(0), study.parameters.len());
    units.iter().map(|u| study.parameters.iter().zip(u).map(|(p, &u)| quantile(&p.values, u)).collect()).collect()
}

/// `cases` points in the unit hypercube with exactly one in each stratum [k/n, (k+1)/n) of
/// every dimension: per dimension a random permutation of the strata, jittered within each.
fn latin_hypercube(rng: &mut ChaCha8Rng, cases: usize, dimensions: usize) -> Vec<Vec<f64>> {
    let mut points = vec![vec![0.0; dimensions]; cases];
    for d in 0..dimensions {
        let mut strata: Vec<usize> = (0..cases).collect();
        // Fisher–Yates.
        for i in (1..cases).rev() {
            strata.swap(i, below(rng, i + 1));
        }
        for (point, stratum) in points.iter_mut().zip(strata) {
            point[d] = (stratum as f64 + unit(rng)) / cases as f64;
        }
    }
    points
}

/// Uniform on (0, 1) with 53 random bits ([`common::unit::open`]): never 0, where a normal's
/// inverse CDF is infinite (and 1 for only one word in 2⁵³).
fn unit(rng: &mut ChaCha8Rng) -> f64 {
    common::unit::open(rng.next_u64())
}

/// Uniform integer in 0..n (Lemire's multiply-shift; the bias, below n/2⁶⁴, is immaterial).
fn below(rng: &mut ChaCha8Rng, n: usize) -> usize {
    ((rng.next_u64() as u128 * n as u128) >> 64) as usize
}

/// The value of a distribution at cumulative probability `u`.
fn quantile(values: &Values, u: f64) -> f64 {
    match *values {
        Values::Uniform([a, b]) => a + (b - a) * u,
        Values::Normal([mu, sigma]) => mu + sigma * inverse_normal_cdf(u),
        Values::Lognormal([mu, sigma]) => (mu + sigma * inverse_normal_cdf(u)).exp(),
        Values::Grid(ref grid) => grid[((u * grid.len() as f64) as usize).min(grid.len() - 1)],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn study(json: &str) -> Study {
        crate::sweep::study::load_json(json).unwrap()
    }

    const METRICS: &str = r#""metrics": [{"variable": "pendulum.theta_x", "stat": "rms"}]"#;

    #[test]
    fn a_grid_plan_is_the_cartesian_product_with_the_first_parameter_slowest() {
        let s = study(&format!(
            r#"{{"scenario": "s.json", "sampling": "grid", "seed": 7, {METRICS},
                "parameters": [{{"name": "a.x", "grid": [1, 2]}}, {{"name": "b.y", "grid": [10, 20, 30]}}]}}"#
        ));
        let cases = plan(&s).unwrap();
        let values: Vec<[f64; 2]> = cases.iter().map(|c| [c.values[0].1, c.values[1].1]).collect();
        assert_eq!(values, [[1., 10.], [1., 20.], [1., 30.], [2., 10.], [2., 20.], [2., 30.]]);
        assert_eq!((cases[4].id.as_str(), cases[4].index), ("0004", 4));
        assert_eq!(cases[0].values[1].0, "b.y");
    }

    #[test]
    fn case_seeds_are_splitmix64_of_the_study_seed_and_index() {
        // SplitMix64 seeded with 0: first outputs 0xE220A8397B1DCDAF, 0x6E789E6AA1B965F4
        // (the reference sequence of Vigna's splitmix64.c).
        assert_eq!(case_seed(0, 0), 0xE220_A839_7B1D_CDAF);
        assert_eq!(case_seed(0, 1), 0x6E78_9E6A_A1B9_65F4);
        assert_ne!(case_seed(1, 0), case_seed(0, 0));
        assert!(variable_seed(case_seed(0, 0), 0) >= 0 && variable_seed(case_seed(0, 0), 1) >= 0);
        assert_ne!(variable_seed(12, 0), variable_seed(12, 1));
    }

    #[test]
    fn a_latin_hypercube_has_one_case_in_every_stratum_of_every_parameter() {
        let s = study(&format!(
            r#"{{"scenario": "s.json", "sampling": "latin-hypercube", "cases": 50, "seed": 3, {METRICS},
                "parameters": [{{"name": "a.x", "uniform": [2, 4]}}, {{"name": "b.y", "uniform": [-1, 0]}}]}}"#
        ));
        let cases = plan(&s).unwrap();
        assert_eq!(cases.len(), 50);
        for (k, [low, high]) in [[2.0, 4.0], [-1.0, 0.0]].into_iter().enumerate() {
            let mut strata: Vec<usize> =
                cases.iter().map(|c| ((c.values[k].1 - low) / (high - low) * 50.0) as usize).collect();
            strata.sort_unstable();
            assert_eq!(strata, (0..50).collect::<Vec<_>>(), "parameter {k}");
        }
        assert_eq!(plan(&s).unwrap(), cases, "the same study gives the same plan");
    }

    #[test]
    fn sobol_points_fill_every_dyadic_box_of_a_power_of_two_plan() {
        // The first two Sobol dimensions form a (0, 2)-sequence, which Owen scrambling keeps:
        // 64 points put 8 in each eighth of either range and one in each of the 8 × 8 boxes.
        let s = study(&format!(
            r#"{{"scenario": "s.json", "sampling": "sobol", "cases": 64, "seed": 5, {METRICS},
                "parameters": [{{"name": "a.x", "uniform": [0, 8]}}, {{"name": "b.y", "uniform": [0, 8]}}]}}"#
        ));
        let cases = plan(&s).unwrap();
        for k in 0..2 {
            let mut counts = [0; 8];
            for case in &cases {
                counts[case.values[k].1 as usize] += 1;
            }
            assert_eq!(counts, [8; 8], "parameter {k}");
        }
        let mut boxes = [[0; 8]; 8];
        for case in &cases {
            boxes[case.values[0].1 as usize][case.values[1].1 as usize] += 1;
        }
        assert!(boxes.iter().flatten().all(|&n| n == 1), "one point per box of the first two dimensions: {boxes:?}");
    }

    #[test]
    fn random_plans_follow_the_seed_and_the_distributions() {
        let json = |seed: u64| {
            format!(
                r#"{{"scenario": "s.json", "sampling": "random", "cases": 4000, "seed": {seed}, {METRICS},
                    "parameters": [{{"name": "a.x", "normal": [1.5, 0.2]}}, {{"name": "b.y", "lognormal": [0, 0.5]}}]}}"#
            )
        };
        let cases = plan(&study(&json(11))).unwrap();
        assert_eq!(plan(&study(&json(11))).unwrap(), cases);
        assert_ne!(plan(&study(&json(12))).unwrap()[0].values, cases[0].values);
        let column = |k: usize| cases.iter().map(|c| c.values[k].1).collect::<Vec<_>>();
        let mean = |v: &[f64]| v.iter().sum::<f64>() / v.len() as f64;
        let (x, y) = (column(0), column(1));
        let sd = (x.iter().map(|v| (v - 1.5).powi(2)).sum::<f64>() / x.len() as f64).sqrt();
        assert!((mean(&x) - 1.5).abs() < 0.01 && (sd - 0.2).abs() < 0.01, "{} {sd}", mean(&x));
        // Log-normal: positive, median e^0 = 1.
        let mut sorted = y.clone();
        sorted.sort_by(f64::total_cmp);
        assert!(sorted[0] > 0.0 && (sorted[2000] - 1.0).abs() < 0.05, "{}", sorted[2000]);
    }
    /// FNV-1a (64 bits) of a plan's ids, seeds, parameter names and value bits.
    fn digest(cases: &[Case]) -> u64 {
        let mut hash = 0xCBF2_9CE4_8422_2325_u64;
        let mut add = |bytes: &[u8]| {
            for &byte in bytes {
                hash = (hash ^ u64::from(byte)).wrapping_mul(0x0100_0000_01B3);
            }
        };
        for case in cases {
            add(case.id.as_bytes());
            add(&case.seed.to_le_bytes());
            for (name, value) in &case.values {
                add(name.as_bytes());
                add(&value.to_bits().to_le_bytes());
            }
        }
        hash
    }

    /// The example study of docs/sweeps.md as it was before linked parameters, with the sampling
    /// `sampling`.
    fn example(sampling: &str) -> String {
        let cases = if sampling == "grid" { "" } else { r#""cases": 64,"# };
        let values = |kind: &str, grid: &str| if sampling == "grid" { grid.to_string() } else { kind.to_string() };
        format!(
            r#"{{"scenario": "s.json", "sampling": "{sampling}", {cases} "seed": 2024, {METRICS},
                "seed_variables": ["imu1.seed", "imu2.seed"],
                "parameters": [{{"name": "crane.lp0", {}}}, {{"name": "pendulum.theta_x0", {}}}]}}"#,
            values(r#""uniform": [0.4, 1.0]"#, r#""grid": [0.4, 0.7, 1.0]"#),
            values(r#""normal": [-0.3, 0.05]"#, r#""grid": [-0.3, -0.2]"#),
        )
    }

    #[test]
    fn plans_of_studies_without_set_or_scale_are_unchanged() {
        // Digests of the plans made before linked and scaled parameters existed: adding them
        // must not move a sample or a seed of an existing study.
        let samplings = ["grid", "random", "latin-hypercube", "sobol"];
        let digests = samplings.map(|sampling| format!("{:#018X}", digest(&plan(&study(&example(sampling))).unwrap())));
        assert_eq!(
            digests,
            ["0x1457D0ADBC0D6571", "0xE835970F92282A74", "0x124296BA24AA333B", "0xB216F42B62F8CA70"],
            "{samplings:?}"
        );
    }

    #[test]
    fn a_case_computed_alone_is_the_planned_case() {
        for sampling in ["grid", "random", "latin-hypercube", "sobol"] {
            let s = study(&example(sampling));
            let cases = plan(&s).unwrap();
            for (index, planned) in cases.iter().enumerate() {
                assert_eq!(&case(&s, index).unwrap(), planned, "{sampling} case {index}");
            }
            assert_eq!(
                case(&s, cases.len()).unwrap_err().to_string(),
                format!("case index {} is not in the plan (cases 0 to {})", cases.len(), cases.len() - 1)
            );
        }
        let grid = example("grid").replace(r#"[-0.3, -0.2]"#, r#"[-0.3, -0.2, 0.1, 0.4]"#);
        let s = study(&grid);
        let cases = plan(&s).unwrap();
        assert!(cases.iter().all(|c| case(&s, c.index).unwrap() == *c));
    }

    #[test]
    fn a_linked_or_scaled_parameter_draws_what_a_single_one_would() {
        let single = plan(&study(&example("latin-hypercube"))).unwrap();
        let linked = example("latin-hypercube")
            .replace(r#""name": "crane.lp0","#, r#""name": "length", "set": ["crane.lp0", "controller.sp.lp"],"#)
            .replace(r#""name": "pendulum.theta_x0","#, r#""name": "angle", "scale": ["pendulum.theta_x0"],"#);
        let linked = plan(&study(&linked)).unwrap();
        for (a, b) in single.iter().zip(&linked) {
            assert_eq!((a.seed, a.values[0].1, a.values[1].1), (b.seed, b.values[0].1, b.values[1].1));
            assert_eq!((b.values[0].0.as_str(), b.values[1].0.as_str()), ("length", "angle"));
        }
        assert_eq!(linked.len(), 64);
    }
}
