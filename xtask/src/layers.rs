//! Layering checks: the crates form a DAG with the FMU side independent of the co-simulation
//! side, and inside every crate the top-level modules form a DAG (a module uses its own
//! children and modules below it, never one that uses it).

use crate::root;
use anyhow::{bail, Context, Result};
use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;
use std::process::Command;

/// Crates that load, run or evaluate FMUs; no FMU crate may depend on them.
const COSIM_SIDE: [&str; 5] = ["fmu-import", "cosim-engine", "crane-campaign", "crane-viewer", "crane-cosim"];
/// The crates that end up inside an `.fmu`, and the crates they are built from.
const FMU_SIDE: [&str; 9] =
    ["common", "fmi2-sys", "fmi2", "physics", "pendulum", "crane", "platform", "imu", "controller"];

/// Source folders of the crates whose modules are checked.
const CRATES: [&str; 14] = [
    "fmus/common/src",
    "fmus/fmi2-sys/src",
    "fmus/fmi2/src",
    "fmus/physics/src",
    "fmus/pendulum/src",
    "fmus/crane/src",
    "fmus/platform/src",
    "fmus/imu/src",
    "fmus/controller/src",
    "cosim/import/src",
    "cosim/engine/src",
    "cosim/campaign/src",
    "cosim/viewer/src",
    "cosim/cli/src",
];

pub fn check() -> Result<()> {
    check_crates()?;
    for dir in CRATES {
        let graph = module_graph(&root().join(dir))?;
        if let Some(cycle) = find_cycle(&graph) {
            bail!("{dir}: top-level modules import each other in a circle: {}", cycle.join(" → "));
        }
    }
    println!("layers: {} crates, no module cycle; FMU crates independent of {}", CRATES.len(), COSIM_SIDE.join(", "));
    Ok(())
}

/// No FMU crate reaches the co-simulation side, also not through dev-dependencies.
fn check_crates() -> Result<()> {
    for package in FMU_SIDE {
        let output = Command::new(std::env::var("CARGO").unwrap_or_else(|_| "cargo".into()))
            .args(["tree", "--offline", "-q", "-e", "normal,dev,build", "--prefix", "none", "-p", package])
            .current_dir(root())
            .output()
            .context("cannot run cargo tree")?;
        if !output.status.success() {
            bail!("cargo tree -p {package} failed: {}", String::from_utf8_lossy(&output.stderr));
        }
        let tree = String::from_utf8_lossy(&output.stdout);
        let names: BTreeSet<&str> = tree.lines().filter_map(|l| l.split_whitespace().next()).collect();
        if let Some(bad) = COSIM_SIDE.iter().find(|c| names.contains(*c)) {
            bail!("the FMU crate {package} depends on {bad}");
        }
    }
    Ok(())
}

/// Top-level module → the top-level modules it names through `crate::`.
fn module_graph(src: &Path) -> Result<BTreeMap<String, BTreeSet<String>>> {
    let mut graph = BTreeMap::new();
    for entry in std::fs::read_dir(src).with_context(|| format!("reading {}", src.display()))? {
        let path = entry?.path();
        let module = match (path.is_dir(), path.extension().and_then(|e| e.to_str())) {
            (true, _) => path.file_name(),
            (false, Some("rs")) => path.file_stem(),
            _ => None,
        };
        let Some(module) = module.map(|m| m.to_string_lossy().into_owned()) else { continue };
        if ["lib", "main", "tests"].contains(&module.as_str()) {
            continue;
        }
        // `name.rs` and `name/` are one module.
        let uses: &mut BTreeSet<String> = graph.entry(module.clone()).or_default();
        for file in rust_files(&path)? {
            uses.extend(crate_paths(&std::fs::read_to_string(&file)?));
        }
        uses.remove(&module);
    }
    let known: BTreeSet<String> = graph.keys().cloned().collect();
    for uses in graph.values_mut() {
        uses.retain(|u| known.contains(u));
    }
    Ok(graph)
}

/// `path` itself, or every `.rs` file below it, without test modules (`tests.rs`, `tests/`):
/// a test may use anything.
fn rust_files(path: &Path) -> Result<Vec<std::path::PathBuf>> {
    if path.is_file() {
        return Ok(vec![path.to_path_buf()]);
    }
    let mut files = Vec::new();
    for entry in std::fs::read_dir(path)? {
        let path = entry?.path();
        if path.file_stem().is_some_and(|s| s == "tests") {
            continue;
        }
        files.extend(rust_files(&path)?);
    }
    Ok(files)
}

/// The first segments after `crate::` in code (comments skipped), including `crate::{a, b}`.
fn crate_paths(text: &str) -> BTreeSet<String> {
    let mut names = BTreeSet::new();
    let code = text.lines().map(|l| l.split("//").next().unwrap_or_default()).collect::<Vec<_>>().join("\n");
    let code = code.split("#[cfg(test)]").next().unwrap_or_default();
    for (position, _) in code.match_indices("crate::") {
        let rest = &code[position + "crate::".len()..];
        let group = rest.strip_prefix('{').map(|inner| inner.split('}').next().unwrap_or_default());
        for item in group.map_or_else(|| vec![rest], |g| g.split(',').collect()) {
            let name: String = item.trim().chars().take_while(|c| c.is_alphanumeric() || *c == '_').collect();
            if !name.is_empty() {
                names.insert(name);
            }
        }
    }
    names
}

/// A cycle of the graph, if there is one (depth-first search).
fn find_cycle(graph: &BTreeMap<String, BTreeSet<String>>) -> Option<Vec<String>> {
    fn visit<'a>(
        node: &'a str,
        graph: &'a BTreeMap<String, BTreeSet<String>>,
        path: &mut Vec<&'a str>,
        done: &mut BTreeSet<&'a str>,
    ) -> Option<Vec<String>> {
        if let Some(start) = path.iter().position(|n| *n == node) {
            let mut cycle: Vec<String> = path[start..].iter().map(|s| s.to_string()).collect();
            cycle.push(node.to_string());
            return Some(cycle);
        }
        if !done.insert(node) {
            return None;
        }
        path.push(node);
        for next in &graph[node] {
            if let Some(cycle) = visit(next, graph, path, done) {
                return Some(cycle);
            }
        }
        path.pop();
        None
    }
    let mut done = BTreeSet::new();
    graph.keys().find_map(|node| visit(node, graph, &mut Vec::new(), &mut done))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn graph(edges: &[(&str, &[&str])]) -> BTreeMap<String, BTreeSet<String>> {
        edges.iter().map(|(n, uses)| (n.to_string(), uses.iter().map(|u| u.to_string()).collect())).collect()
    }

    #[test]
    fn a_circle_is_found_and_a_layering_is_not() {
        let circle = graph(&[("a", &["b"]), ("b", &["c"]), ("c", &["a"])]);
        assert_eq!(find_cycle(&circle).expect("cycle"), ["a", "b", "c", "a"]);
        let layers = graph(&[("a", &["b", "c"]), ("b", &["c"]), ("c", &[])]);
        assert_eq!(find_cycle(&layers), None);
    }

    #[test]
    fn crate_paths_are_read_from_code_not_comments() {
        let text = "use crate::{alpha::X, beta};\n// crate::gamma\nfn f() { crate::delta::g(); }\n";
        let found: Vec<String> = crate_paths(text).into_iter().collect();
        assert_eq!(found, ["alpha", "beta", "delta"]);
    }
}
