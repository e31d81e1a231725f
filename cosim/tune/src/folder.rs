//! The tuning's output folder:
//!
//! * `tuning.json`: the tuning file as read; a folder holding another tuning (anything but the
//!   number of generations differing) is refused;
//! * `references.json`: the reference runs' outcomes (start values of the system file);
//! * `candidates/g<generation>-k<index>.json`: each evaluated candidate (point, values, score),
//!   written whole through a rename, so that separate processes can fill the folder;
//! * after the search: `start.json` (the start values' training score), `held_out-<best>.json`
//!   (the start's and the best's held-out scores), `log.csv`, `convergence.png`, `best.json` (a
//!   scenario file with the best start values), `summary.json` and `report.md`.

use std::collections::HashMap;
use std::path::{Path, PathBuf};

use serde::{Deserialize, Serialize};

use crate::objective::{Outcome, Score};
use crate::study::{OptimizerSettings, Tuning};
use crate::TuneError;
use cosim_studies::StudyError;
use fmu_import::file::{read_regular_text, MAX_TEXT_FILE_BYTES};

/// One evaluated candidate.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Candidate {
    /// `g<generation>-k<index>`, e.g. `g003-k07`.
    pub id: String,
    /// The generation it belongs to, from 0.
    pub generation: usize,
    /// Its index in the generation, from 0.
    pub index: usize,
    /// The optimiser's point (unit-box coordinates, possibly outside the box).
    pub point: Vec<f64>,
    /// The tuned parameters' values (the point repaired into the box), by parameter name.
    pub values: Vec<(String, f64)>,
    /// Its score on the training runs.
    pub score: Score,
    /// The penalty of a point outside the box.
    pub bound_penalty: f64,
    /// What the optimiser was told: the score's objective plus the bound penalty.
    pub objective: f64,
    /// Wall time of its runs (s).
    pub wall_time: f64,
}

/// The id of candidate `index` of generation `generation`: `g003-k05`.
pub fn candidate_id(generation: usize, index: usize) -> String {
    format!("g{generation:03}-k{index:02}")
}

/// (generation, index) of a candidate id.
pub fn parse_candidate_id(id: &str) -> Option<(usize, usize)> {
    let (g, k) = id.strip_prefix('g')?.split_once("-k")?;
    Some((g.parse().ok()?, k.parse().ok()?))
}

/// The reference runs' outcomes, by tuning-run id.
pub type References = HashMap<String, Result<Outcome, String>>;

/// The output folder of one tuning.
pub struct Folder {
    /// The folder's path.
    pub root: PathBuf,
}

impl Folder {
    /// Opens `root` for `tuning`: creates it (and `candidates/`), or checks that it holds this
    /// tuning. A folder with other files and no `tuning.json` is refused, so that nothing the
    /// tuning did not write is overwritten.
    pub fn open(root: &Path, tuning: &Tuning) -> Result<Folder, TuneError> {
        let folder = Folder { root: root.to_path_buf() };
        let marker = root.join("tuning.json");
        let text = serde_json::to_string_pretty(tuning).map_err(|e| folder.invalid(&marker, &e.to_string()))? + "\n";
        if marker.exists() {
            let held = folder.read(&marker)?;
            let held: Tuning = serde_json::from_str(&held).map_err(|e| folder.invalid(&marker, &e.to_string()))?;
            // The number of generations only ends the replay: a search may be extended or cut
            // short in the same folder, its earlier candidates stay valid.
            let same_search =
                |t: &Tuning| Tuning { optimizer: OptimizerSettings { generations: 0, ..t.optimizer }, ..t.clone() };
            if same_search(&held) != same_search(tuning) {
                return Err(folder.invalid(
                    &marker,
                    "holds another tuning (other parameters, objective, runs or optimiser): choose a new output folder",
                ));
            }
        } else if std::fs::read_dir(root).is_ok_and(|mut entries| entries.next().is_some()) {
            return Err(folder.invalid(root, "is not empty and holds no tuning.json: choose a new or empty folder"));
        }
        std::fs::create_dir_all(root.join("candidates"))
            .map_err(|source| StudyError::Write { file: root.into(), source })?;
        folder.write(&marker, &text)?;
        Ok(folder)
    }

    /// Every candidate file that parses, keyed by its point's bits.
    pub fn candidates(&self) -> Result<HashMap<Vec<u64>, Candidate>, TuneError> {
        let dir = self.root.join("candidates");
        let entries = std::fs::read_dir(&dir).map_err(|source| StudyError::Read { file: dir.clone(), source })?;
        let mut found = HashMap::new();
        for entry in entries.flatten() {
            let path = entry.path();
            if path.extension().is_none_or(|e| e != "json") {
                continue;
            }
            // A file cut short (a killed writer never renames, but a copied folder may hold one)
            // is a candidate to evaluate again.
            let Ok(candidate) = serde_json::from_str::<Candidate>(&self.read(&path)?) else { continue };
            found.insert(point_key(&candidate.point), candidate);
        }
        Ok(found)
    }

    pub fn write_candidate(&self, candidate: &Candidate) -> Result<(), TuneError> {
        let file = self.root.join("candidates").join(format!("{}.json", candidate.id));
        self.write_json(&file, candidate)
    }

    /// The references written by an earlier run, if any.
    pub fn references(&self) -> Result<Option<References>, TuneError> {
        let file = self.root.join("references.json");
        if !file.exists() {
            return Ok(None);
        }
        let text = self.read(&file)?;
        serde_json::from_str(&text).map(Some).map_err(|e| self.invalid(&file, &e.to_string()))
    }

    pub fn write_references(&self, references: &References) -> Result<(), TuneError> {
        self.write_json(&self.root.join("references.json"), references)
    }

    /// Writes `value` as pretty JSON to `file`, whole (a temporary file renamed).
    pub fn write_json<T: Serialize>(&self, file: &Path, value: &T) -> Result<(), TuneError> {
        let text = serde_json::to_string_pretty(value).map_err(|e| self.invalid(file, &e.to_string()))? + "\n";
        self.write(file, &text)
    }

    /// Writes `text` to `file` through a temporary file in the same folder and a rename, as the
    /// sweeps' case files are written.
    pub fn write(&self, file: &Path, text: &str) -> Result<(), TuneError> {
        cosim_studies::files::persist_atomically(file, text.as_bytes())
            .map_err(|source| StudyError::Write { file: file.into(), source }.into())
    }

    fn read(&self, file: &Path) -> Result<String, TuneError> {
        read_regular_text(file, MAX_TEXT_FILE_BYTES)
            .map_err(|source| StudyError::Read { file: file.into(), source }.into())
    }

    fn invalid(&self, file: &Path, message: &str) -> TuneError {
        StudyError::Invalid { file: file.into(), message: message.into() }.into()
    }
}

/// The exact bits of a point: the key under which its value is known.
pub fn point_key(point: &[f64]) -> Vec<u64> {
    point.iter().map(|v| v.to_bits()).collect()
}

/// Adds a freshly evaluated `candidate` to `known`, dropping any other entry of its id: its file
/// was just written over. (A candidate file edited so that its point is no longer the one the
/// search asks for is evaluated again under its id; kept both, `log.csv` and the summary would
/// count that evaluation twice.)
pub fn remember(known: &mut HashMap<Vec<u64>, Candidate>, candidate: Candidate) {
    known.retain(|_, held| held.id != candidate.id);
    known.insert(point_key(&candidate.point), candidate);
}

#[cfg(test)]
mod tests {
    use super::*;

    fn candidate(point: f64) -> Candidate {
        let score = Score { objective: point, terms: Vec::new(), saturation: 0.0, errors: Vec::new() };
        let id = candidate_id(0, 3);
        let (generation, index, values) = (0, 3, vec![("k".to_string(), point)]);
        Candidate {
            id,
            generation,
            index,
            point: vec![point],
            values,
            score,
            bound_penalty: 0.0,
            objective: point,
            wall_time: 0.0,
        }
    }

    #[test]
    fn a_candidate_evaluated_again_under_its_id_replaces_the_edited_one() {
        // As read from the folder: g000-k03.json edited to hold the point 0.9.
        let mut known = HashMap::from([(point_key(&[0.9]), candidate(0.9))]);
        // The search asks for 0.5 again, and its evaluation is written over g000-k03.json.
        remember(&mut known, candidate(0.5));
        let ids: Vec<_> = known.values().map(|c| (c.id.as_str(), c.point[0])).collect();
        assert_eq!(ids, [("g000-k03", 0.5)]);
    }
}
