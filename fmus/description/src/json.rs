//! The description file's JSON: finding it, `extends`, and every field present and known.
//!
//! A description may start with `"extends": "<name or path>"` and give only what differs: its
//! objects are merged into the other description's field by field (arrays and numbers replace
//! whole), and a relative path in `extends` is taken from the extending file's folder.
//!
//! After merging, the description must hold every field of the format and no other: a missing
//! field would otherwise take a value nobody chose, and a misspelt one would be ignored. Both
//! errors name the field's path (`boom.cylinder.bore`), an unknown one with the nearest known
//! path.

use crate::catalogue;
use crate::CraneDescription;
use serde_json::Value;
use std::collections::BTreeSet;
use std::path::{Path, PathBuf};

/// How many descriptions an `extends` chain may pass through (a loop is refused well before).
const MAX_EXTENDS: usize = 8;

/// The merged JSON of the description `spec` names (see [`crate::load`]), with a name for
/// messages: the catalogue entry or the file's path.
pub fn resolve(spec: &str, resource_dir: Option<&Path>) -> Result<(String, Value), String> {
    resolve_chain(spec, resource_dir, None, 0)
}

fn resolve_chain(
    spec: &str,
    resource_dir: Option<&Path>,
    from: Option<&Path>,
    depth: usize,
) -> Result<(String, Value), String> {
    if depth > MAX_EXTENDS {
        return Err(format!("`extends` passes through more than {MAX_EXTENDS} descriptions (a loop?) at '{spec}'"));
    }
    let (origin, folder, text) = read(spec, resource_dir, from)?;
    let value: Value =
        serde_json::from_str(&text).map_err(|e| format!("crane description {origin}: {}", syntax(&e)))?;
    let Value::Object(mut object) = value else {
        return Err(format!("crane description {origin}: the file must hold one JSON object"));
    };
    match object.remove("extends") {
        None => Ok((origin, Value::Object(object))),
        Some(Value::String(parent)) => {
            let (_, mut base) = resolve_chain(&parent, resource_dir, folder.as_deref(), depth + 1)
                .map_err(|e| format!("{e}\n  (extended by {origin})"))?;
            merge(&mut base, Value::Object(object));
            Ok((origin, base))
        }
        Some(other) => Err(format!("crane description {origin}: `extends` must name a crane, got {other}")),
    }
}

/// The text of the description `spec` names, its origin for messages, and its folder (for a
/// relative `extends` in it).
fn read(
    spec: &str,
    resource_dir: Option<&Path>,
    from: Option<&Path>,
) -> Result<(String, Option<PathBuf>, String), String> {
    let spec = if spec.is_empty() { catalogue::DEFAULT_CRANE } else { spec };
    if catalogue::is_name(spec) {
        let text = catalogue::text(spec).ok_or_else(|| {
            format!(
                "no crane named '{spec}' in the catalogue ({}); a file is named by its path",
                catalogue::names().join(", ")
            )
        })?;
        return Ok((format!("'{spec}' (catalogue)"), None, text.to_string()));
    }
    let candidates = candidates(Path::new(spec), resource_dir, from);
    let found = candidates.iter().find(|p| p.is_file()).ok_or_else(|| {
        let tried: Vec<String> = candidates.iter().map(|p| p.display().to_string()).collect();
        format!("crane description '{spec}' not found (looked at {})", tried.join(", "))
    })?;
    let text = std::fs::read_to_string(found).map_err(|e| format!("crane description {}: {e}", found.display()))?;
    Ok((found.display().to_string(), found.parent().map(Path::to_path_buf), text))
}

/// Where a file path may point: as given when absolute; else from the extending file's folder
/// (inside a chain), or from the working directory and then the FMU's resources.
fn candidates(path: &Path, resource_dir: Option<&Path>, from: Option<&Path>) -> Vec<PathBuf> {
    if path.is_absolute() {
        return vec![path.to_path_buf()];
    }
    match from {
        Some(folder) => vec![folder.join(path)],
        None => std::iter::once(path.to_path_buf()).chain(resource_dir.map(|r| r.join(path))).collect(),
    }
}

/// JSON's syntax error with the hint for the two things people write that JSON does not allow.
fn syntax(e: &serde_json::Error) -> String {
    let hint = if e.is_syntax() { " (JSON allows no comments and no comma after the last item)" } else { "" };
    format!("{e}{hint}")
}

/// Merges `changes` into `base`: objects field by field, anything else replaced whole.
pub fn merge(base: &mut Value, changes: Value) {
    match (base, changes) {
        (Value::Object(base), Value::Object(changes)) => {
            for (key, value) in changes {
                match base.get_mut(&key) {
                    Some(existing) => merge(existing, value),
                    None => {
                        base.insert(key, value);
                    }
                }
            }
        }
        (base, changes) => *base = changes,
    }
}

/// The description in `value`, every field present and known (module documentation).
pub fn typed(value: &Value) -> Result<CraneDescription, String> {
    let mut value = value.clone();
    if let Some(arm) = value.get("arm").and_then(Value::as_object) {
        if arm.contains_key("base") {
            return Err(
                "arm.base is not part of a crane description: the FMUs' base.* parameters place the crane".into()
            );
        }
    }
    if let Some(Value::Object(arm)) = value.get_mut("arm") {
        arm.insert("base".into(), Value::from(vec![0.0, 0.0, 0.0]));
    }
    let description: CraneDescription =
        serde_path_to_error::deserialize(&value).map_err(|e| format!("{}: {}", e.path(), e.inner()))?;
    let written = serde_json::to_value(&description).map_err(|e| e.to_string())?;
    let (given, known) = (leaves(&value), leaves(&written));
    // Sets for the membership tests: an FMU reads its description at instantiation, so this is
    // start-up work of every run. Ordered sets: a hashed one would seed itself from the OS's
    // random source, which ties the FMU's Windows DLL to an import older Windows and Wine lack.
    let (given_set, known_set): (BTreeSet<&str>, BTreeSet<&str>) =
        (given.iter().map(String::as_str).collect(), known.iter().map(String::as_str).collect());
    if let Some(unknown) = given.iter().find(|p| !known_set.contains(p.as_str()) && !p.starts_with("sources.")) {
        return Err(format!("unknown field {unknown}{}", nearest(unknown, &known)));
    }
    if let Some(missing) = known.iter().find(|p| !given_set.contains(p.as_str()) && !p.starts_with("sources.")) {
        return Err(format!("missing field {missing}"));
    }
    let sections = sections(&known);
    if let Some(key) = description.sources.keys().find(|k| sections.binary_search(k).is_err()) {
        return Err(format!("sources.{key} names no field of the description{}", nearest(key, &sections)));
    }
    Ok(description)
}

/// Every leaf's path in `value`: `a.b`, arrays as `a[0]`.
pub fn leaves(value: &Value) -> Vec<String> {
    let mut out = Vec::new();
    collect(value, String::new(), &mut out);
    out
}

fn collect(value: &Value, path: String, out: &mut Vec<String>) {
    match value {
        Value::Object(map) if !map.is_empty() => {
            for (key, v) in map {
                let next = if path.is_empty() { key.clone() } else { format!("{path}.{key}") };
                collect(v, next, out);
            }
        }
        Value::Array(items) if !items.is_empty() => {
            for (i, v) in items.iter().enumerate() {
                collect(v, format!("{path}[{i}]"), out);
            }
        }
        _ => out.push(path),
    }
}

/// Every leaf path and every path of a section above one (`a.b.c` gives `a`, `a.b`, `a.b.c`).
fn sections(leaves: &[String]) -> Vec<String> {
    let mut out: Vec<String> = leaves
        .iter()
        .flat_map(|leaf| {
            leaf.char_indices().filter(|(_, c)| *c == '.' || *c == '[').map(|(i, _)| leaf[..i].to_string())
        })
        .chain(leaves.iter().cloned())
        .collect();
    out.sort();
    out.dedup();
    out
}

/// ", did you mean `x`?" for the known path nearest `path` in edits, if it is near.
fn nearest(path: &str, known: &[String]) -> String {
    known
        .iter()
        .map(|k| (edits(path, k), k))
        .min()
        .filter(|(d, _)| *d <= 3.max(path.len() / 4))
        .map(|(_, k)| format!(" (did you mean {k}?)"))
        .unwrap_or_default()
}

/// Levenshtein distance of two strings, by characters.
fn edits(a: &str, b: &str) -> usize {
    let b: Vec<char> = b.chars().collect();
    let mut row: Vec<usize> = (0..=b.len()).collect();
    for (i, ca) in a.chars().enumerate() {
        let mut diagonal = row[0];
        row[0] = i + 1;
        for (j, cb) in b.iter().enumerate() {
            let next = (row[j + 1] + 1).min(row[j] + 1).min(diagonal + usize::from(ca != *cb));
            diagonal = row[j + 1];
            row[j + 1] = next;
        }
    }
    row[b.len()]
}
