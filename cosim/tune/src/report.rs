//! What a finished tuning writes: the convergence log and plot, the start and best candidates
//! judged on the training and held-out runs, the best start values as a scenario file, and a
//! Markdown report.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::folder::Candidate;
use crate::objective::Score;
use crate::search::Ask;
use crate::{best, TuneError, Tuner};
use cosim_plot::{self as plot, Figure, Panel, Series};

/// The tuning's result in figures.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Summary {
    /// Generations evaluated.
    pub generations: usize,
    /// Candidates evaluated.
    pub evaluations: usize,
    /// Why the search ended.
    pub reasons: Vec<String>,
    /// The best candidate's id, or `"start"` when none beat the start values on the training runs.
    pub best: String,
    /// The tuned parameters: (name, start value, best value).
    pub parameters: Vec<(String, f64, f64)>,
    /// Scores on the training runs: the start values', then the best's.
    pub training: [Score; 2],
    /// Scores on the held-out runs: the start values', then the best's.
    pub held_out: [Score; 2],
    /// (1 − best/start) × 100 of the objective on the training and held-out runs (%).
    pub improvement: [f64; 2],
    /// Wall time of this invocation (s).
    pub wall_time: f64,
}

/// Writes the results of the ended search `finished` over the candidates `known`.
pub fn finish(
    tuner: &Tuner,
    known: &HashMap<Vec<u64>, Candidate>,
    finished: &Ask,
    wall_time: f64,
) -> Result<Summary, TuneError> {
    let candidate = best(known).ok_or_else(|| TuneError::Run("the search evaluated no candidate".into()))?;
    let reasons = match finished {
        Ask::Finished { reasons, .. } => reasons.clone(),
        Ask::Generation { .. } => Vec::new(),
    };
    let start_training = cached(tuner, "start.json", || {
        let references = tuner.references()?;
        Ok(one(tuner.score_values(std::slice::from_ref(&tuner.start), &tuner.training, &references)?))
    })?;
    // The start values stay the result when no candidate beat them on the training runs.
    let (best_id, best_values, best_training) = if candidate.objective < start_training[0].objective {
        (candidate.id.clone(), candidate.values.iter().map(|(_, v)| *v).collect(), candidate.score.clone())
    } else {
        ("start".to_string(), tuner.start.clone(), start_training[0].clone())
    };
    let held_out = cached(tuner, &format!("held_out-{best_id}.json"), || {
        let references = tuner.references()?;
        Ok(two(tuner.score_values(&[tuner.start.clone(), best_values.clone()], &tuner.held_out, &references)?))
    })?;
    let judged = Judged { training: [start_training[0].clone(), best_training], held_out };
    let parameters = tuner
        .tuning
        .parameters
        .iter()
        .zip(&tuner.start)
        .zip(&best_values)
        .map(|((p, &start), &value)| (p.name.clone(), start, value))
        .collect();
    let improvement = |[start, best]: &[Score; 2]| (1.0 - best.objective / start.objective) * 100.0;
    let mut candidates: Vec<&Candidate> = known.values().collect();
    candidates.sort_by_key(|c| (c.generation, c.index));
    let summary = Summary {
        generations: candidates.last().map_or(0, |c| c.generation + 1),
        evaluations: candidates.len(),
        reasons,
        best: best_id,
        parameters,
        improvement: [improvement(&judged.training), improvement(&judged.held_out)],
        training: judged.training,
        held_out: judged.held_out,
        wall_time,
    };
    let root = &tuner.folder.root;
    tuner.folder.write(&root.join("log.csv"), &log_csv(tuner, &candidates))?;
    // A missing font or an unwritable image does not lose the tuning's results.
    if let Err(message) = plot::draw(&root.join("convergence.png"), &convergence(&candidates, &summary)) {
        eprintln!("warning: {message}");
    }
    tuner.folder.write_json(&root.join("best.json"), &best_scenario(tuner, &best_values, &summary)?)?;
    tuner.folder.write_json(&root.join("summary.json"), &summary)?;
    tuner.folder.write(&root.join("report.md"), &markdown(tuner, &summary))?;
    Ok(summary)
}

/// The start and best parameters' scores on the training and held-out runs.
struct Judged {
    training: [Score; 2],
    held_out: [Score; 2],
}

/// The scores `compute` gives, kept in the output folder's `file` for a later invocation (the
/// same tuning, so the same scores).
fn cached<const N: usize>(
    tuner: &Tuner,
    file: &str,
    compute: impl FnOnce() -> Result<[Score; N], TuneError>,
) -> Result<[Score; N], TuneError> {
    let path = tuner.folder.root.join(file);
    if let Some(scores) = std::fs::read_to_string(&path).ok().and_then(|t| serde_json::from_str::<Vec<Score>>(&t).ok())
    {
        if let Ok(scores) = <[Score; N]>::try_from(scores) {
            return Ok(scores);
        }
    }
    let scores = compute()?;
    tuner.folder.write_json(&path, &scores.to_vec())?;
    Ok(scores)
}

fn one(mut scores: Vec<Score>) -> [Score; 1] {
    [scores.remove(0)]
}

fn two(mut scores: Vec<Score>) -> [Score; 2] {
    let second = scores.remove(1);
    [scores.remove(0), second]
}

/// `log.csv`: one row per candidate in search order, with the best objective so far.
fn log_csv(tuner: &Tuner, candidates: &[&Candidate]) -> String {
    let mut text = String::from("generation,candidate,objective,best_so_far,saturation");
    for p in &tuner.tuning.parameters {
        let _ = write!(text, ",{}", p.name);
    }
    for t in &tuner.tuning.objective.terms {
        let _ = write!(
            text,
            ",{}:{}",
            serde_json::to_value(t.group).ok().and_then(|v| v.as_str().map(String::from)).unwrap_or_default(),
            t.metric.info().name
        );
    }
    text.push('\n');
    let mut best = f64::INFINITY;
    for c in candidates {
        best = best.min(c.objective);
        let _ = write!(text, "{},{},{},{},{}", c.generation, c.id, c.objective, best, c.score.saturation);
        for (_, v) in &c.values {
            let _ = write!(text, ",{v}");
        }
        for t in &c.score.terms {
            let _ = write!(text, ",{}", t.ratio.map_or(String::new(), |r| r.to_string()));
        }
        text.push('\n');
    }
    text
}

/// The convergence plot: each generation's best objective, the best so far, and the start's.
fn convergence(candidates: &[&Candidate], summary: &Summary) -> Figure {
    let generations = summary.generations;
    let mut generation_best = vec![f64::INFINITY; generations];
    for c in candidates {
        generation_best[c.generation] = generation_best[c.generation].min(c.objective);
    }
    let mut so_far = f64::INFINITY;
    let best_so_far: Vec<(f64, f64)> = generation_best
        .iter()
        .enumerate()
        .map(|(g, &v)| {
            so_far = so_far.min(v);
            (g as f64, so_far)
        })
        .collect();
    let start = summary.training[0].objective;
    Figure {
        title: format!("Tuning: objective on the training runs ({} candidates)", summary.evaluations),
        x_label: "generation".into(),
        panels: vec![Panel {
            y_label: "objective (1)".into(),
            series: vec![
                Series {
                    label: "generation's best".into(),
                    points: generation_best.iter().enumerate().map(|(g, &v)| (g as f64, v)).collect(),
                },
                Series { label: "best so far".into(), points: best_so_far },
                Series {
                    label: "start values".into(),
                    points: vec![(0.0, start), (generations.saturating_sub(1).max(1) as f64, start)],
                },
            ],
        }],
    }
}

/// `best.json`: a scenario over the tuned system with the best start values, which
/// `crane-cosim run` and `campaign --start-file` take.
fn best_scenario(tuner: &Tuner, values: &[f64], summary: &Summary) -> Result<serde_json::Value, TuneError> {
    let root = objective_path(&tuner.folder.root)?;
    let system = crane_campaign::runner::relative_path(&tuner.runner.system, &root);
    Ok(serde_json::json!({
        "description": format!(
            "Tuned by crane-cosim tune: candidate {} of {} (objective {:.4} against {:.4} with the start values on the held-out runs)",
            summary.best, summary.evaluations, summary.held_out[1].objective, summary.held_out[0].objective
        ),
        "system": system,
        "start": tuner.start_map(values),
    }))
}

fn objective_path(path: &Path) -> Result<PathBuf, TuneError> {
    crate::objective::absolute(path).map_err(TuneError::Run)
}

/// `report.md`.
fn markdown(tuner: &Tuner, summary: &Summary) -> String {
    let mut md = String::new();
    let t = &tuner.tuning;
    let _ = writeln!(md, "# Tuning: {}\n", if t.description.is_empty() { "(no description)" } else { &t.description });
    let _ = writeln!(
        md,
        "CMA-ES, λ = {}, σ₀ = {}, seed {}: {} candidates in {} generations ({}); best {}.\n",
        tuner.search.population,
        t.optimizer.sigma,
        t.optimizer.seed,
        summary.evaluations,
        summary.generations,
        if summary.reasons.is_empty() { "stopped".into() } else { summary.reasons.join(", ") },
        summary.best
    );
    let _ = writeln!(
        md,
        "Training: tests {} ({} pairs); held out: tests {} ({} pairs); variant {}.\n",
        t.training.tests,
        tuner.training.len(),
        t.held_out.tests,
        tuner.held_out.len(),
        t.variant
    );
    let _ = writeln!(md, "## Parameters\n\n| parameter | bounds | scale | start | best |\n|---|---|---|---|---|");
    for ((name, start, best), p) in summary.parameters.iter().zip(&t.parameters) {
        let _ = writeln!(md, "| {name} | [{}, {}] | {:?} | {start} | {best:.6} |", p.bounds[0], p.bounds[1], p.scale);
    }
    let _ = writeln!(md, "\n## Objective (lower is better) and its terms as reductions (%)\n");
    let _ = writeln!(
        md,
        "| | training, start | training, best | held out, start | held out, best |\n|---|---|---|---|---|"
    );
    let scores = [&summary.training[0], &summary.training[1], &summary.held_out[0], &summary.held_out[1]];
    let row = |label: &str, cell: &dyn Fn(&Score) -> String| {
        format!("| {label} | {} |\n", scores.iter().map(|s| cell(s)).collect::<Vec<_>>().join(" | "))
    };
    md += &row("objective", &|s| format!("{:.4}", s.objective));
    for (i, term) in t.objective.terms.iter().enumerate() {
        let label = format!("{} — {} (weight {})", term.group.title(), term.metric.info().title, term.weight);
        md += &row(&label, &|s| match s.terms.get(i).and_then(|v| v.ratio.map(|r| (r, v.pairs))) {
            Some((r, n)) => format!("{:.1} % (n {n})", (1.0 - r) * 100.0),
            None => "—".into(),
        });
    }
    md += &row("time at an actuator limit", &|s| format!("{:.2} %", s.saturation * 100.0));
    let _ = writeln!(
        md,
        "\nImprovement of the objective: {:.1} % on the training runs, {:.1} % on the held-out runs.",
        summary.improvement[0], summary.improvement[1]
    );
    md
}

/// A progress bar over the generations with the best objective so far.
pub struct Progress(indicatif::ProgressBar);

impl Progress {
    pub fn new(generations: u64, show: bool) -> Self {
        if !show {
            return Progress(indicatif::ProgressBar::hidden());
        }
        let bar = indicatif::ProgressBar::new(generations);
        if let Ok(style) = indicatif::ProgressStyle::with_template(
            "{bar:40} generation {pos}/{len}, {elapsed} elapsed, ~{eta} left  {msg}",
        ) {
            bar.set_style(style);
        }
        Progress(bar)
    }

    /// Generation `generation` starts; `best` is the best candidate so far.
    pub fn at(&self, generation: u64, best: Option<&Candidate>) {
        self.0.set_position(generation);
        if let Some(best) = best {
            self.0.set_message(format!("best objective {:.4} ({})", best.objective, best.id));
        }
    }

    pub fn finish(&self) {
        self.0.finish_and_clear();
    }
}
