//! A crate's top-level modules as the code has them, and which of them each one names through
//! `crate::` (test modules left out: a test may use anything).

use anyhow::{Context, Result};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

/// Where a module names another one: the file, the line (from 1) and that line's text.
#[derive(Debug, Clone, PartialEq)]
pub struct UseSite {
    /// The file.
    pub file: PathBuf,
    /// The line, from 1.
    pub line: usize,
    /// That line's text.
    pub text: String,
}

/// Top-level module → the top-level modules it names, each with its first use.
pub type Graph = BTreeMap<String, BTreeMap<String, UseSite>>;

/// The module graph of the crate whose sources are in `src`; a module is `name.rs`, `name/`
/// (with `name.rs` or `name/mod.rs`) or both, never `lib`, `main`, `tests` or `src/bin/`.
pub fn graph(src: &Path) -> Result<Graph> {
    let mut graph = Graph::new();
    for entry in std::fs::read_dir(src).with_context(|| format!("reading {}", src.display()))? {
        let path = entry?.path();
        let Some(module) = module_name(&path) else { continue };
        let uses = graph.entry(module.clone()).or_default();
        for file in rust_files(&path)? {
            let text = std::fs::read_to_string(&file).with_context(|| format!("reading {}", file.display()))?;
            for (used, line, text) in crate_paths(&text) {
                uses.entry(used).or_insert(UseSite { file: file.clone(), line, text });
            }
        }
        uses.remove(&module);
    }
    let known: Vec<String> = graph.keys().cloned().collect();
    for uses in graph.values_mut() {
        uses.retain(|u, _| known.contains(u));
    }
    Ok(graph)
}

/// The module that `path` (an entry of `src/`) is part of, if any.
fn module_name(path: &Path) -> Option<String> {
    let name = if path.is_dir() {
        let name = path.file_name()?.to_str()?;
        let declared = path.with_extension("rs").is_file() || path.join("mod.rs").is_file();
        declared.then_some(name)?
    } else {
        path.extension().filter(|e| *e == "rs")?;
        path.file_stem()?.to_str()?
    };
    (!["lib", "main", "tests"].contains(&name)).then(|| name.to_string())
}

/// `path` itself, or every `.rs` file below it, without test modules (`tests.rs`, `tests/`).
fn rust_files(path: &Path) -> Result<Vec<PathBuf>> {
    if path.is_file() {
        return Ok(vec![path.to_path_buf()]);
    }
    let mut files = Vec::new();
    for entry in std::fs::read_dir(path)? {
        let path = entry?.path();
        if path.file_stem().is_some_and(|s| s == "tests") {
            continue;
        }
        if path.is_dir() || path.extension().is_some_and(|e| e == "rs") {
            files.extend(rust_files(&path)?);
        }
    }
    files.sort();
    Ok(files)
}

/// The first segments after `crate::` in code (comments and everything from `#[cfg(test)]` on
/// skipped), including each item of `crate::{a, b::{c, d}}`, with the line number and text of
/// the line where the path starts.
pub fn crate_paths(text: &str) -> Vec<(String, usize, String)> {
    let lines: Vec<&str> = text.lines().take_while(|l| !l.contains("#[cfg(test)]")).collect();
    let code = lines.iter().map(|l| l.split("//").next().unwrap_or_default()).collect::<Vec<_>>().join("\n");
    let mut found = Vec::new();
    for (position, _) in code.match_indices("crate::") {
        let line = code[..position].matches('\n').count();
        let rest = &code[position + "crate::".len()..];
        let items = match rest.strip_prefix('{') {
            Some(group) => top_level_items(group),
            None => vec![rest],
        };
        for item in items {
            let name: String = item.trim().chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            if !name.is_empty() {
                found.push((name, line + 1, lines[line].trim().to_string()));
            }
        }
    }
    found
}

/// The comma-separated items of a `{…}` group (its text after the `{`), nested groups kept whole.
fn top_level_items(group: &str) -> Vec<&str> {
    let (mut items, mut depth, mut start) = (Vec::new(), 0usize, 0);
    for (i, c) in group.char_indices() {
        match c {
            '{' => depth += 1,
            '}' if depth == 0 => {
                items.push(&group[start..i]);
                return items;
            }
            '}' => depth -= 1,
            ',' if depth == 0 => {
                items.push(&group[start..i]);
                start = i + 1;
            }
            _ => {}
        }
    }
    items
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crate_paths_are_read_from_code_not_comments_with_their_lines() {
        let text = "use crate::{alpha::{X, Y},\n    beta};\n// crate::gamma\nfn f() { crate::delta::g(); }\n\
                    #[cfg(test)]\nuse crate::epsilon;\n";
        let found = crate_paths(text);
        let names: Vec<&str> = found.iter().map(|(n, ..)| n.as_str()).collect();
        assert_eq!(names, ["alpha", "beta", "delta"]);
        assert_eq!(found[2], ("delta".to_string(), 4, "fn f() { crate::delta::g(); }".to_string()));
        assert_eq!(found[1].1, 1, "a group is reported at the line of its `crate::`");
    }
}
