//! Tuning the controller's parameters over the campaign (`crane-cosim tune`, docs/tuning.md):
//! CMA-ES over the parameters a tuning file names, each candidate scored by its compensated
//! campaign runs against their references (Tables 7.1–7.3's ratios), on a training selection of
//! tests and seeds, then judged on a held-out one.
//!
//! Modules, bottom up: [`study`] (the tuning file), [`space`] (the optimiser's unit box),
//! [`objective`] (runs, pairs and the score), [`search`] (CMA-ES as ask-and-tell by replay),
//! [`folder`] (the output folder), [`report`] (log, convergence plot, best start values, report).
//!
//! The campaign it scores by (test matrix, runs, metrics, Tables 7.1–7.3's groups) is
//! `crane-campaign`'s; what it shares with every study (the error of files, parses and worker
//! threads, atomic writes, seeds of random variables) is `cosim-studies`'; [`TuneError`] adds
//! only the tuning's own failures to [`StudyError`].

pub mod folder;
pub mod objective;
pub mod report;
pub mod search;
pub mod space;
pub mod study;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use rayon::prelude::*;
use serde_json::Value;

use cosim_engine::interrupt::{signal_name, Interrupt};
use cosim_engine::system::{System, SystemFiles};
use cosim_studies::StudyError;
use fmu_import::error_chain;
use fmu_import::fmu::ExtractLimits;

use folder::{candidate_id, parse_candidate_id, point_key, Candidate, Folder, References};
use objective::{pairs, score, Outcome, Pair, Runner, Score};
use search::{Ask, Search};
use space::Space;
use study::Tuning;

/// Why a tuning cannot start or go on (a failing run only makes its candidate score badly).
#[derive(Debug, thiserror::Error)]
pub enum TuneError {
    /// What any study's files, parse and threads can fail with, in the studies' words.
    #[error(transparent)]
    Study(#[from] StudyError),
    #[error("{0}")]
    Run(String),
    #[error("interrupted by {0}: the candidates evaluated so far are kept; run the same command again to resume")]
    Interrupted(String),
}

/// How to run a tuning.
#[derive(Debug, Clone)]
pub struct TuneOptions {
    /// The tuning file.
    pub tuning_file: PathBuf,
    /// The system file when the tuning file names none.
    pub default_system: PathBuf,
    /// The output folder.
    pub out: PathBuf,
    /// Worker threads (0: one per core).
    pub jobs: usize,
    /// Show a progress bar (on a terminal).
    pub progress: bool,
    /// Stops the runs between steps when requested (signals).
    pub interrupt: Option<Interrupt>,
    /// What each FMU archive may unpack to.
    pub limits: ExtractLimits,
}

/// What to do.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Step {
    /// Run the search to its end here, then write the results.
    All,
    /// Compute the references if missing and say which candidates the next generation needs
    /// (for an external scheduler: each is then evaluated with [`Step::Candidate`]).
    Ask,
    /// Evaluate one candidate of the current generation (`g003-k05`).
    Candidate(String),
}

/// What [`tune`] did.
#[derive(Debug, Clone, PartialEq)]
pub enum StepResult {
    /// The next generation and the ids of its candidates not evaluated yet.
    Asked { generation: usize, candidates: Vec<String> },
    /// The search had ended (`Ask` after the last generation).
    Finished,
    /// One candidate evaluated.
    Evaluated(Box<Candidate>),
    /// The whole tuning: its report.
    Done(Box<report::Summary>),
}

/// A tuning's fixed parts: the file, the runs, the search.
pub struct Tuner {
    /// The tuning file as read.
    pub tuning: Tuning,
    /// The output folder: candidates, references and the report.
    pub folder: Folder,
    /// Runs and evaluates the tuning's runs.
    pub runner: Runner,
    /// The tuned parameters' ranges.
    pub space: Space,
    /// The optimiser's settings, its initial mean at `start`.
    pub search: Search,
    /// The pairs the optimiser sees.
    pub training: Vec<Pair>,
    /// The pairs the result is judged on and the optimiser never sees.
    pub held_out: Vec<Pair>,
    /// The start values of the search's initial mean (the system's own, unless the tuning file
    /// gives a start), by parameter.
    pub start: Vec<f64>,
    pool: rayon::ThreadPool,
    options: TuneOptions,
}

/// Runs `step` of the tuning `options.tuning_file`.
pub fn tune(options: &TuneOptions, step: &Step) -> Result<StepResult, TuneError> {
    let tuner = Tuner::new(options)?;
    match step {
        Step::Ask => tuner.ask_step(),
        Step::Candidate(id) => tuner.candidate_step(id),
        Step::All => tuner.run_all(),
    }
}

impl Tuner {
    pub fn new(options: &TuneOptions) -> Result<Tuner, TuneError> {
        let file = &options.tuning_file;
        let tuning = Tuning::load(file)?;
        let system = tuning.system_path(file).unwrap_or_else(|| options.default_system.clone());
        let system = objective::absolute(&system).map_err(TuneError::Run)?;
        let files = SystemFiles::new(options.limits);
        let loaded = System::load(&system, &Default::default(), &files)
            .map_err(|e| StudyError::Invalid { file: file.clone(), message: error_chain(&e) })?;
        check_names(&tuning, &system_names(&loaded), &system)
            .map_err(|message| StudyError::Invalid { file: file.clone(), message })?;
        let start =
            start_values(&tuning, &loaded).map_err(|message| StudyError::Invalid { file: file.clone(), message })?;
        // Opened only once the tuning is known to name the system's variables: a refused tuning
        // leaves no folder behind.
        let folder = Folder::open(&options.out, &tuning)?;
        let invalid = |message: String| StudyError::Invalid { file: file.clone(), message };
        let training = pairs(&tuning.training, tuning.variant()).map_err(|e| invalid(format!("training: {e}")))?;
        let held_out = pairs(&tuning.held_out, tuning.variant()).map_err(|e| invalid(format!("held_out: {e}")))?;
        let space = Space { parameters: tuning.parameters.clone() };
        let search = Search {
            mean: space.point(&start),
            sigma: tuning.optimizer.sigma,
            population: tuning.population(),
            generations: tuning.optimizer.generations,
            seed: tuning.optimizer.seed,
        };
        let runner = Runner {
            system,
            tuning_file: file.clone(),
            files,
            seed_variables: tuning.seed_variables.clone(),
            saturation: tuning.objective.saturation.clone(),
            interrupt: options.interrupt.clone(),
        };
        let pool = rayon::ThreadPoolBuilder::new().num_threads(options.jobs).build().map_err(StudyError::Threads)?;
        Ok(Tuner { tuning, folder, runner, space, search, training, held_out, start, pool, options: options.clone() })
    }

    fn ask_step(&self) -> Result<StepResult, TuneError> {
        self.references()?;
        let known = self.folder.candidates()?;
        match self.ask(&known)? {
            Ask::Finished { .. } => Ok(StepResult::Finished),
            Ask::Generation { number, points } => Ok(StepResult::Asked {
                generation: number,
                candidates: points
                    .iter()
                    .enumerate()
                    .filter(|(_, p)| !known.contains_key(&point_key(p)))
                    .map(|(k, _)| candidate_id(number, k))
                    .collect(),
            }),
        }
    }

    fn candidate_step(&self, id: &str) -> Result<StepResult, TuneError> {
        let invalid =
            |message: String| TuneError::from(StudyError::Invalid { file: self.options.tuning_file.clone(), message });
        let (generation, index) =
            parse_candidate_id(id).ok_or_else(|| invalid(format!("{id}: expected a candidate id such as g003-k05")))?;
        let references = self
            .folder
            .references()?
            .ok_or_else(|| invalid("the references have not run: run `crane-cosim tune … --ask` first".into()))?;
        let known = self.folder.candidates()?;
        let Ask::Generation { number, points } = self.ask(&known)? else {
            return Err(invalid(format!("{id}: the search has ended")));
        };
        let point = points.get(index).filter(|_| number == generation).ok_or_else(|| {
            invalid(format!(
                "{id} is not a candidate of the current generation ({number}, {} candidates)",
                points.len()
            ))
        })?;
        let candidate = self.evaluate(&[(generation, index, point.clone())], &references)?.remove(0);
        self.folder.write_candidate(&candidate)?;
        Ok(StepResult::Evaluated(Box::new(candidate)))
    }

    fn run_all(&self) -> Result<StepResult, TuneError> {
        let references = self.references()?;
        let mut known = self.folder.candidates()?;
        let progress = report::Progress::new(self.tuning.optimizer.generations as u64, self.options.progress);
        let clock = Instant::now();
        let finished = loop {
            let ask = self.ask(&known)?;
            let Ask::Generation { number, points } = ask else { break ask };
            progress.at(number as u64, best(&known));
            let missing: Vec<(usize, usize, Vec<f64>)> = points
                .into_iter()
                .enumerate()
                .filter(|(_, p)| !known.contains_key(&point_key(p)))
                .map(|(k, p)| (number, k, p))
                .collect();
            for candidate in self.evaluate(&missing, &references)? {
                self.folder.write_candidate(&candidate)?;
                folder::remember(&mut known, candidate);
            }
        };
        progress.finish();
        let summary = report::finish(self, &known, &finished, clock.elapsed().as_secs_f64())?;
        Ok(StepResult::Done(Box::new(summary)))
    }

    fn ask(&self, known: &std::collections::HashMap<Vec<u64>, Candidate>) -> Result<Ask, TuneError> {
        self.search.ask(&|point| known.get(&point_key(point)).map(|c| c.objective)).map_err(TuneError::Run)
    }

    /// The references of the training and held-out pairs: from the folder, else run (in
    /// parallel) and written there.
    pub fn references(&self) -> Result<References, TuneError> {
        let mut references = self.folder.references()?.unwrap_or_default();
        let mut missing: Vec<objective::TuningRun> = self
            .training
            .iter()
            .chain(&self.held_out)
            .map(|p| p.reference)
            .filter(|r| !references.contains_key(&r.id()))
            .collect();
        missing.dedup_by_key(|r| r.id());
        if missing.is_empty() {
            return Ok(references);
        }
        let none = BTreeMap::new();
        let outcomes: Vec<Result<Outcome, String>> =
            self.pool.install(|| missing.par_iter().map(|run| self.runner.run(run, &none)).collect());
        self.check_interrupt()?;
        references.extend(missing.iter().map(|r| r.id()).zip(outcomes));
        self.folder.write_references(&references)?;
        Ok(references)
    }

    /// Evaluates the candidates `(generation, index, point)` on the training pairs, all their
    /// runs on the pool at once.
    pub fn evaluate(
        &self,
        candidates: &[(usize, usize, Vec<f64>)],
        references: &References,
    ) -> Result<Vec<Candidate>, TuneError> {
        let clock = Instant::now();
        let valued: Vec<(Vec<f64>, f64)> = candidates.iter().map(|(_, _, p)| self.space.values(p)).collect();
        let scores =
            self.score_values(&valued.iter().map(|(v, _)| v.clone()).collect::<Vec<_>>(), &self.training, references)?;
        let wall_time = clock.elapsed().as_secs_f64() / candidates.len().max(1) as f64;
        Ok(candidates
            .iter()
            .zip(valued)
            .zip(scores)
            .map(|(((generation, index, point), (values, bound_penalty)), score)| Candidate {
                id: candidate_id(*generation, *index),
                generation: *generation,
                index: *index,
                point: point.clone(),
                values: self.tuning.parameters.iter().map(|p| p.name.clone()).zip(values).collect(),
                objective: score.objective + bound_penalty,
                score,
                bound_penalty,
                wall_time,
            })
            .collect())
    }

    /// The scores of several value sets on `pairs`: every (values, pair) run on the pool.
    pub fn score_values(
        &self,
        sets: &[Vec<f64>],
        pairs: &[Pair],
        references: &References,
    ) -> Result<Vec<Score>, TuneError> {
        let starts: Vec<BTreeMap<String, Value>> = sets.iter().map(|values| self.start_map(values)).collect();
        let jobs: Vec<(usize, &Pair)> = (0..sets.len()).flat_map(|s| pairs.iter().map(move |p| (s, p))).collect();
        let outcomes: Vec<Result<Outcome, String>> = self
            .pool
            .install(|| jobs.par_iter().map(|(s, pair)| self.runner.run(&pair.compensated, &starts[*s])).collect());
        self.check_interrupt()?;
        let refs: Vec<Result<Outcome, String>> = pairs
            .iter()
            .map(|p| {
                references
                    .get(&p.reference.id())
                    .cloned()
                    .unwrap_or_else(|| Err(format!("no reference run {}", p.reference.id())))
            })
            .collect();
        Ok(outcomes.chunks(pairs.len().max(1)).map(|chunk| score(&self.tuning, pairs, &refs, chunk)).collect())
    }

    /// The start values `values` (one per tuned parameter) give.
    pub fn start_map(&self, values: &[f64]) -> BTreeMap<String, Value> {
        self.tuning
            .parameters
            .iter()
            .zip(values)
            .flat_map(|(p, &v)| p.targets().into_iter().map(move |t| (t, Value::from(v))))
            .collect()
    }

    fn check_interrupt(&self) -> Result<(), TuneError> {
        match self.options.interrupt.as_ref().and_then(Interrupt::requested) {
            Some(signal) => Err(TuneError::Interrupted(signal_name(signal))),
            None => Ok(()),
        }
    }
}

/// The best (lowest objective, then earliest) candidate known.
pub fn best(known: &std::collections::HashMap<Vec<u64>, Candidate>) -> Option<&Candidate> {
    known
        .values()
        .min_by(|a, b| a.objective.total_cmp(&b.objective).then((a.generation, a.index).cmp(&(b.generation, b.index))))
}

/// Every `"instance.variable"` of `system`'s instances.
fn system_names(system: &System) -> Vec<String> {
    let qualified = |instance: &cosim_engine::system::Instance| {
        let variables = &instance.fmu.model_description().variables;
        variables.iter().map(|v| format!("{}.{}", instance.name, v.name)).collect::<Vec<_>>()
    };
    system.instances.iter().flat_map(qualified).collect()
}

/// Checks that every variable the tuning names is one of `names` (the system's), before any run:
/// an unknown saturation command or tuned start value would otherwise fail every run, and the
/// search would go on scoring failures. The error names the element, the variable and the
/// closest existing name.
fn check_names(tuning: &Tuning, names: &[String], system: &Path) -> Result<(), String> {
    let known: std::collections::HashSet<&str> = names.iter().map(String::as_str).collect();
    let mut used: Vec<(String, &str)> = Vec::new();
    for (k, parameter) in tuning.parameters.iter().enumerate() {
        let targets = if parameter.set.is_empty() { std::slice::from_ref(&parameter.name) } else { &parameter.set[..] };
        used.extend(targets.iter().map(|t| (format!("parameters[{k}] ({})", parameter.name), t.as_str())));
    }
    let commands = tuning.objective.saturation.iter().flat_map(|s| s.commands.iter());
    used.extend(
        commands
            .enumerate()
            .map(|(k, c)| (format!("objective.saturation.commands[{k}].variable"), c.variable.as_str())),
    );
    // The seed variables are only set when a selection lists seeds.
    if !(tuning.training.seeds.is_empty() && tuning.held_out.seeds.is_empty()) {
        used.extend(
            tuning.seed_variables.iter().enumerate().map(|(k, s)| (format!("seed_variables[{k}]"), s.as_str())),
        );
    }
    match used.into_iter().find(|(_, name)| !known.contains(name)) {
        Some((element, name)) => Err(format!(
            "{element}: {name:?} is not a variable of {}{}",
            system.display(),
            fmu_import::names::did_you_mean(&fmu_import::names::closest(name, known.iter().copied()))
        )),
        None => Ok(()),
    }
}

/// Each parameter's start: the tuning file's, else its first target's start value in the system
/// (or its FMU's default); it must be a number inside the bounds.
fn start_values(tuning: &Tuning, loaded: &System) -> Result<Vec<f64>, String> {
    tuning
        .parameters
        .iter()
        .map(|parameter| {
            if let Some(start) = parameter.start {
                return Ok(start);
            }
            let target = &parameter.targets()[0];
            let value = cosim_studies::sweep::execute::base_value(loaded, target)?
                .and_then(|v| match v {
                    fmu_import::value::Value::Real(x) => Some(x),
                    fmu_import::value::Value::Integer(i) => Some(f64::from(i)),
                    _ => None,
                })
                .ok_or(format!("parameter {}: {target} has no numeric start value: give \"start\"", parameter.name))?;
            let [lower, upper] = parameter.bounds;
            if !(value >= lower && value <= upper) {
                return Err(format!(
                    "parameter {}: the start value {value} of {target} is outside the bounds [{lower}, {upper}]",
                    parameter.name
                ));
            }
            Ok(value)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_saturation_command_or_tuned_value_the_system_lacks_is_refused_with_the_closest_name() {
        let text = r#"{ "variant": 1, "parameters": [{ "name": "controller.k.angle", "bounds": [0.1, 2] }],
            "objective": { "terms": [{ "group": "energy-dissipation", "metric": "tau_theta_x" }],
                           "saturation": { "weight": 1, "commands": [{ "variable": "controller.u.slew", "range": [-1, 1] }] } },
            "training": { "tests": "41" }, "held_out": { "tests": "42" } }"#;
        let tuning: Tuning = serde_json::from_str(text).unwrap();
        let system = Path::new("closed_loop.json");
        let names = |list: &[&str]| list.iter().map(|n| n.to_string()).collect::<Vec<_>>();
        check_names(&tuning, &names(&["controller.k.angle", "controller.u.slew"]), system).expect("all known");
        let error = check_names(&tuning, &names(&["controller.k.angle", "controller.u.slow"]), system).unwrap_err();
        assert_eq!(
            error,
            "objective.saturation.commands[0].variable: \"controller.u.slew\" is not a variable of closed_loop.json \
             (did you mean \"controller.u.slow\"?)"
        );
        let error = check_names(&tuning, &names(&["controller.k.angel", "controller.u.slew"]), system).unwrap_err();
        assert!(error.starts_with("parameters[0] (controller.k.angle): \"controller.k.angle\" is not"), "{error}");
    }
}
