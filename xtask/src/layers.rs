//! `cargo xtask layers`: docs/architecture.md is checked against the code, so the map stays true.
//!
//! * The crate table lists every workspace crate, lowest first, with its folder and exactly the
//!   workspace crates it depends on (`cargo metadata`); each crate depends only on crates above
//!   it in the table, and an FMU-side crate only on FMU-side crates (also for tests and examples).
//! * Each crate's module layers list every top-level module once; a module names (`crate::…`)
//!   only modules of lower layers.
//! * The binaries' rows name exactly their subcommands ([`subcommands`]).
//! * The FMU list ([`fmu_list`]): every FMU crate declares itself and the README's table is its
//!   summary.

mod fmu_list;
mod map;
mod modules;
mod subcommands;

use crate::{root, workspace};
use anyhow::{bail, Context, Result};
use map::{CrateRow, Map, ModuleLayers, Side};
use modules::Graph;
use std::collections::BTreeMap;
use std::path::Path;

/// The document the map is in, relative to the workspace root.
const ARCHITECTURE: &str = "docs/architecture.md";

pub fn check() -> Result<()> {
    let path = root().join(ARCHITECTURE);
    let text = std::fs::read_to_string(&path).with_context(|| format!("reading {}", path.display()))?;
    let map = Map::parse(&text).with_context(|| ARCHITECTURE)?;
    let crates = workspace::crates()?;
    let mut problems = crate_problems(&map.crates, &crates);
    let mut module_count = 0;
    for krate in &crates {
        let graph = module_graph(&root().join(&krate.folder))?;
        module_count += graph.len();
        problems.extend(module_problems(&krate.name, map.modules.iter().find(|m| m.krate == krate.name), &graph));
    }
    for unknown in map.modules.iter().filter(|m| crates.iter().all(|c| c.name != m.krate)) {
        problems.push(format!("module layers of `{}`, which is not a workspace crate", unknown.krate));
    }
    problems.extend(subcommands::problems(&map.crates)?);
    problems.extend(fmu_list::problems(&crates)?);
    if !problems.is_empty() {
        bail!("the map ({ARCHITECTURE}, the README's FMU table) and the code disagree:\n  {}", problems.join("\n  "));
    }
    println!(
        "layers: {} crates and {module_count} top-level modules as {ARCHITECTURE} lists them; {} FMU crates, \
         each declared and in the README",
        crates.len(),
        crates.iter().filter(|c| c.fmu.is_some()).count()
    );
    Ok(())
}

/// `cargo xtask layers --print`: the module layers the code has (each module one layer above the
/// highest it uses), in the document's format, for writing or reviewing the map.
pub fn print() -> Result<()> {
    for krate in workspace::crates()? {
        let graph = module_graph(&root().join(&krate.folder))?;
        if graph.is_empty() {
            continue;
        }
        println!("### `{}`\n", krate.name);
        for (i, layer) in derived_layers(&graph).with_context(|| krate.name.clone())?.iter().enumerate() {
            let names: Vec<String> = layer.iter().map(|m| format!("`{m}`")).collect();
            println!("{}. {}", i + 1, names.join(", "));
        }
        println!();
    }
    Ok(())
}

/// The module graph of the crate in `folder` (none without `src/`).
fn module_graph(folder: &Path) -> Result<Graph> {
    let src = folder.join("src");
    if src.is_dir() {
        modules::graph(&src)
    } else {
        Ok(Graph::new())
    }
}

/// The table against the workspace: the same crates, folders and dependencies, in an order
/// where every dependency comes first, with the FMU side closed.
fn crate_problems(rows: &[CrateRow], crates: &[workspace::Crate]) -> Vec<String> {
    let mut problems = Vec::new();
    for krate in crates.iter().filter(|c| rows.iter().all(|r| r.name != c.name)) {
        problems.push(format!("crate `{}` ({}) is missing from the crate table", krate.name, krate.folder.display()));
    }
    for (position, row) in rows.iter().enumerate() {
        let Some(krate) = crates.iter().find(|c| c.name == row.name) else {
            problems.push(format!("the crate table lists `{}`, which is not a workspace crate", row.name));
            continue;
        };
        let name = &row.name;
        if Path::new(&row.folder) != krate.folder {
            problems.push(format!(
                "crate `{name}`: folder {} in the table, {} in fact",
                row.folder,
                krate.folder.display()
            ));
        }
        for (listed, actual, kind) in [
            (&row.dependencies, &krate.dependencies, "depends on"),
            (&row.dev_dependencies, &krate.dev_dependencies, "dev-depends on"),
        ] {
            if listed != actual {
                problems.push(format!("crate `{name}` {kind} {actual:?} (Cargo.toml), the table says {listed:?}"));
            }
        }
        let above = &rows[..position];
        for dependency in row.dependencies.iter().chain(&row.dev_dependencies) {
            match above.iter().find(|r| r.name == *dependency) {
                None => problems.push(format!("crate `{name}` uses `{dependency}`, which is not listed above it")),
                Some(used) if row.side == Side::Fmu && used.side != Side::Fmu => problems
                    .push(format!("the FMU-side crate `{name}` uses `{dependency}`, which is not on the FMU side")),
                Some(_) => {}
            }
        }
        if krate.fmu.is_some() && row.side != Side::Fmu {
            problems.push(format!("the FMU crate `{name}` is not on the FMU side"));
        }
    }
    problems
}

/// One crate's modules against its layers: every module listed once, none listed that does not
/// exist, and every use pointing to a lower layer.
fn module_problems(krate: &str, listed: Option<&ModuleLayers>, graph: &Graph) -> Vec<String> {
    let Some(listed) = listed else {
        return match graph.is_empty() {
            true => Vec::new(),
            false => vec![format!("crate `{krate}` has modules ({}) but no module layers", join(graph.keys()))],
        };
    };
    let mut layer_of: BTreeMap<&str, usize> = BTreeMap::new();
    let mut problems = Vec::new();
    for (layer, module) in listed.layers.iter().enumerate().flat_map(|(i, l)| l.iter().map(move |m| (i + 1, m))) {
        if layer_of.insert(module, layer).is_some() {
            problems.push(format!("crate `{krate}`: module `{module}` is listed twice"));
        }
        if !graph.contains_key(module) {
            problems.push(format!("crate `{krate}`: module `{module}` is listed but does not exist"));
        }
    }
    for (module, uses) in graph {
        let Some(&layer) = layer_of.get(module.as_str()) else {
            problems.push(format!("crate `{krate}`: module `{module}` is missing from its module layers"));
            continue;
        };
        for (used, site) in uses {
            let Some(&used_layer) = layer_of.get(used.as_str()) else { continue };
            if used_layer >= layer {
                problems.push(format!(
                    "crate `{krate}`: module `{module}` (layer {layer}) uses `{used}` (layer {used_layer}), which is \
                     not below it: {}:{}: {}",
                    site.file.strip_prefix(root()).unwrap_or(&site.file).display(),
                    site.line,
                    site.text
                ));
            }
        }
    }
    problems
}

/// Layers from the graph: a module that uses nothing is in layer 1, any other one layer above
/// the highest module it uses; fails on a cycle.
fn derived_layers(graph: &Graph) -> Result<Vec<Vec<String>>> {
    let mut layer: BTreeMap<&str, usize> = BTreeMap::new();
    while layer.len() < graph.len() {
        let ready: Vec<(&str, usize)> = graph
            .iter()
            .filter(|(m, uses)| !layer.contains_key(m.as_str()) && uses.keys().all(|u| layer.contains_key(u.as_str())))
            .map(|(m, uses)| (m.as_str(), 1 + uses.keys().map(|u| layer[u.as_str()]).max().unwrap_or(0)))
            .collect();
        if ready.is_empty() {
            let rest: Vec<&String> = graph.keys().filter(|m| !layer.contains_key(m.as_str())).collect();
            bail!("the modules {} use each other in a circle", join(rest));
        }
        layer.extend(ready);
    }
    let mut layers = vec![Vec::new(); layer.values().copied().max().unwrap_or(0)];
    for (module, l) in layer {
        layers[l - 1].push(module.to_string());
    }
    Ok(layers)
}

fn join<'a>(names: impl IntoIterator<Item = &'a String>) -> String {
    names.into_iter().map(|n| format!("`{n}`")).collect::<Vec<_>>().join(", ")
}

#[cfg(test)]
mod tests {
    use super::*;
    use modules::UseSite;
    use std::collections::BTreeSet;
    use std::path::PathBuf;

    /// `graph(&[("engine", &["time"])])`: modules and what they use, each use at line 1 of
    /// `src/<module>.rs`.
    fn graph(edges: &[(&str, &[&str])]) -> Graph {
        let site = |module: &str, used: &str| UseSite {
            file: PathBuf::from(format!("src/{module}.rs")),
            line: 1,
            text: format!("use crate::{used};"),
        };
        let uses = |module: &str, used: &[&str]| used.iter().map(|u| (u.to_string(), site(module, u))).collect();
        edges.iter().map(|(m, used)| (m.to_string(), uses(m, used))).collect()
    }

    fn layers(krate: &str, layers: &[&[&str]]) -> ModuleLayers {
        let layers = layers.iter().map(|l| l.iter().map(|m| m.to_string()).collect()).collect();
        ModuleLayers { krate: krate.into(), layers }
    }

    #[test]
    fn a_use_of_a_module_not_below_is_found_with_its_line() {
        let listed = layers("demo", &[&["error", "time"], &["engine"]]);
        assert!(module_problems(
            "demo",
            Some(&listed),
            &graph(&[("error", &[]), ("time", &[]), ("engine", &["time"])])
        )
        .is_empty());
        let upward = graph(&[("error", &[]), ("time", &["engine"]), ("engine", &["time"])]);
        assert_eq!(
            module_problems("demo", Some(&listed), &upward),
            ["crate `demo`: module `time` (layer 1) uses `engine` (layer 2), which is not below it: \
              src/time.rs:1: use crate::engine;"]
        );
        let sideways = graph(&[("error", &["time"]), ("time", &[]), ("engine", &[])]);
        assert!(
            module_problems("demo", Some(&listed), &sideways)[0].contains("`error` (layer 1) uses `time` (layer 1)")
        );
    }

    #[test]
    fn a_module_missing_from_the_list_or_listed_but_absent_is_found() {
        let listed = layers("demo", &[&["error", "time"], &["engine"]]);
        let code = graph(&[("error", &[]), ("engine", &[]), ("observer", &[])]);
        assert_eq!(
            module_problems("demo", Some(&listed), &code),
            [
                "crate `demo`: module `time` is listed but does not exist",
                "crate `demo`: module `observer` is missing from its module layers"
            ]
        );
        assert_eq!(
            module_problems("demo", None, &code),
            ["crate `demo` has modules (`engine`, `error`, `observer`) but no module layers"]
        );
        assert!(module_problems("leaf", None, &Graph::new()).is_empty());
    }

    #[test]
    fn the_crate_table_must_match_the_workspace_and_keep_the_fmu_side_closed() {
        let names = |n: &[&str]| n.iter().map(|s| s.to_string()).collect::<BTreeSet<_>>();
        let row = |name: &str, side, deps: &[&str]| CrateRow {
            name: name.into(),
            folder: name.into(),
            side,
            dependencies: names(deps),
            dev_dependencies: BTreeSet::new(),
            holds: Vec::new(),
        };
        let krate = |name: &str, deps: &[&str]| workspace::Crate {
            name: name.into(),
            folder: name.into(),
            fmu: None,
            dependencies: names(deps),
            dev_dependencies: BTreeSet::new(),
        };
        let crates = [krate("sys", &[]), krate("import", &["sys"]), krate("model", &["sys"])];
        let rows =
            [row("sys", Side::Fmu, &[]), row("import", Side::Cosim, &["sys"]), row("model", Side::Fmu, &["sys"])];
        assert!(crate_problems(&rows, &crates).is_empty());
        let upside_down = [row("import", Side::Cosim, &["sys"]), row("sys", Side::Fmu, &[]), rows[2].clone()];
        assert_eq!(crate_problems(&upside_down, &crates), ["crate `import` uses `sys`, which is not listed above it"]);
        let crates = [krate("sys", &[]), krate("import", &["sys"]), krate("model", &["sys", "import"])];
        let problems = crate_problems(&rows, &crates);
        assert!(problems[0].contains("crate `model` depends on {\"import\", \"sys\"}"), "{problems:?}");
        let leaking = [rows[0].clone(), rows[1].clone(), row("model", Side::Fmu, &["sys", "import"])];
        assert_eq!(
            crate_problems(&leaking, &crates),
            ["the FMU-side crate `model` uses `import`, which is not on the FMU side"]
        );
        assert!(crate_problems(&rows[..2], &crates)[0].contains("crate `model` (model) is missing"));
    }

    #[test]
    fn derived_layers_put_each_module_above_what_it_uses() {
        let code = graph(&[("error", &[]), ("time", &[]), ("engine", &["time", "error"]), ("cli", &["engine"])]);
        assert_eq!(derived_layers(&code).unwrap(), [vec!["error", "time"], vec!["engine"], vec!["cli"]]);
        let circle = graph(&[("a", &["b"]), ("b", &["a"]), ("c", &[])]);
        assert!(derived_layers(&circle).unwrap_err().to_string().contains("`a`, `b`"));
    }
}
