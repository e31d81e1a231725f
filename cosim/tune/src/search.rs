//! CMA-ES (the `cmaes` crate) driven as ask-and-tell by deterministic replay.
//!
//! The crate's optimiser calls an objective function for each of a generation's λ points and
//! then updates its distribution; its random numbers come from a ChaCha generator seeded with the
//! tuning's seed. Given the seed and the objective values of all earlier points, the points of
//! the next generation are therefore fixed. [`Search::ask`] replays the optimiser from the start
//! with the values already known (one lookup per point, microseconds per generation) until it
//! reaches a generation with a point not evaluated yet, and returns that generation's points.
//! The values known are the candidate files of the output folder, so an interrupted tuning
//! resumes where it stopped and gives the same result as an uninterrupted one, and a
//! generation's candidates can be evaluated anywhere (threads here, or tasks on a Ray cluster)
//! before the next is asked for.

use std::cell::RefCell;

use cmaes::{CMAESOptions, DVector};

/// The optimiser's settings.
#[derive(Debug, Clone)]
pub struct Search {
    /// The initial mean (unit-box coordinates).
    pub mean: Vec<f64>,
    /// The initial step size (unit-box coordinates).
    pub sigma: f64,
    /// λ.
    pub population: usize,
    /// The most generations to run (the search may end earlier).
    pub generations: usize,
    /// Seed of the random draws.
    pub seed: u64,
}

/// What to evaluate next.
#[derive(Debug, Clone, PartialEq)]
pub enum Ask {
    /// Generation `number` (from 0): its λ points, some of which may already be known.
    Generation { number: usize, points: Vec<Vec<f64>> },
    /// The search has ended: after its last generation, or by a stopping criterion of CMA-ES
    /// (e.g. `TolFun`: the values stopped changing), named.
    Finished { generations: usize, reasons: Vec<String> },
}

impl Search {
    /// The next generation to evaluate, given `known`: the objective of a point evaluated before.
    pub fn ask(&self, known: &dyn Fn(&[f64]) -> Option<f64>) -> Result<Ask, String> {
        let seen: RefCell<Vec<(Vec<f64>, bool)>> = RefCell::new(Vec::new());
        let objective = |x: &DVector<f64>| {
            let point: Vec<f64> = x.iter().copied().collect();
            let value = known(&point);
            seen.borrow_mut().push((point, value.is_some()));
            // An unknown point's value is never used: the replay stops after its generation.
            value.unwrap_or(0.0)
        };
        let mut cmaes = CMAESOptions::new(self.mean.clone(), self.sigma)
            .population_size(self.population)
            .seed(self.seed)
            .build(objective)
            .map_err(|e| format!("CMA-ES: invalid options: {e:?}"))?;
        for number in 0..self.generations {
            let first = seen.borrow().len();
            let stopped = cmaes.next();
            let generation: Vec<(Vec<f64>, bool)> = seen.borrow()[first..].to_vec();
            if generation.iter().any(|(_, known)| !known) {
                return Ok(Ask::Generation { number, points: generation.into_iter().map(|(p, _)| p).collect() });
            }
            if let Some(data) = stopped {
                let reasons = data.reasons.iter().map(|r| format!("{r:?}")).collect();
                return Ok(Ask::Finished { generations: number + 1, reasons });
            }
        }
        Ok(Ask::Finished { generations: self.generations, reasons: vec!["the last generation".into()] })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn key(point: &[f64]) -> Vec<u64> {
        point.iter().map(|v| v.to_bits()).collect()
    }

    /// Runs the search to its end on `f`, one generation per ask.
    fn minimise(search: &Search, f: impl Fn(&[f64]) -> f64) -> (HashMap<Vec<u64>, f64>, usize) {
        let mut values = HashMap::new();
        loop {
            let ask = search.ask(&|p| values.get(&key(p)).copied()).unwrap();
            match ask {
                Ask::Generation { points, .. } => {
                    for p in points {
                        values.insert(key(&p), f(&p));
                    }
                }
                Ask::Finished { generations, .. } => return (values, generations),
            }
        }
    }

    #[test]
    fn the_replay_finds_the_minimum_of_a_shifted_sphere() {
        let search = Search { mean: vec![0.5; 3], sigma: 0.2, population: 8, generations: 80, seed: 1 };
        let target = [0.2, 0.7, 0.4];
        let f = |p: &[f64]| p.iter().zip(target).map(|(x, t)| (x - t) * (x - t)).sum::<f64>();
        let (values, _) = minimise(&search, f);
        let best = values.values().copied().fold(f64::INFINITY, f64::min);
        assert!(best < 1e-8, "best {best}");
    }

    #[test]
    fn a_generation_is_the_same_whatever_was_asked_before() {
        let search = Search { mean: vec![0.5; 2], sigma: 0.3, population: 6, generations: 5, seed: 9 };
        let f = |p: &[f64]| (p[0] - 0.1).powi(2) + 10.0 * (p[1] - 0.8).powi(2);
        let (values, generations) = minimise(&search, f);
        assert_eq!(generations, 5);
        assert_eq!(values.len(), 30, "five generations of six new points");
        // Asking again with everything known finishes at once; with another seed the points differ.
        let again = search.ask(&|p| values.get(&key(p)).copied()).unwrap();
        assert!(matches!(again, Ask::Finished { generations: 5, .. }));
        let other = Search { seed: 10, ..search.clone() }.ask(&|p| values.get(&key(p)).copied()).unwrap();
        assert!(matches!(other, Ask::Generation { number: 0, .. }));
    }
}
