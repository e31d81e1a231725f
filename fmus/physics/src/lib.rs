//! Pure-Rust models of the test-scale maritime crane system (no FFI).
//!
//! Frames and units follow the specification: SI units, world frame W North-East-Down
//! (x north, y east, z down, gravity along +z), quaternions scalar-first W←body.
//! Equation numbers refer to the thesis "Motion Compensation and Robotic Control of Maritime
//! Cranes".
//!
//! The top-level modules form layers: a module uses its own children and modules of lower layers,
//! never one that uses it (checked by a test below).
//!
//! 0. [`math`], [`integrate`], [`noise`]: vocabulary and numerics;
//! 1. [`motion`] (the shared motion types and the ship's degree-of-freedom indices), [`imu`],
//!    [`pendulum`];
//! 2. [`crane`], [`platform`];
//! 3. [`ship`] (its sources are scaled to fit the platform), [`estimation`];
//! 4. [`control`].

pub mod control;
pub mod crane;
pub mod estimation;
pub mod imu;
pub mod integrate;
pub mod math;
pub mod motion;
pub mod noise;
pub mod pendulum;
pub mod platform;
pub mod ship;

#[cfg(test)]
mod tests {
    use std::collections::{BTreeMap, BTreeSet};
    use std::path::Path;

    /// Every `.rs` file below `dir`.
    fn sources(dir: &Path, out: &mut Vec<std::path::PathBuf>) {
        for entry in std::fs::read_dir(dir).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                sources(&path, out);
            } else if path.extension().is_some_and(|e| e == "rs") {
                out.push(path);
            }
        }
    }

    /// Edges A → B between top-level modules: a file of A (A.rs or A/…) names `crate::B` outside
    /// a comment.
    fn module_graph() -> BTreeMap<String, BTreeSet<String>> {
        let src = Path::new(env!("CARGO_MANIFEST_DIR")).join("src");
        let mut files = Vec::new();
        sources(&src, &mut files);
        let mut graph: BTreeMap<String, BTreeSet<String>> = BTreeMap::new();
        for file in files {
            let relative = file.strip_prefix(&src).unwrap();
            let first = relative.components().next().unwrap().as_os_str().to_string_lossy().into_owned();
            let module = first.trim_end_matches(".rs").to_string();
            if module == "lib" {
                continue;
            }
            let text = std::fs::read_to_string(&file).unwrap();
            for line in text.lines().filter(|l| !l.trim_start().starts_with("//")) {
                for (at, _) in line.match_indices("crate::") {
                    let rest = &line[at + "crate::".len()..];
                    let name: String = rest.chars().take_while(|c| c.is_ascii_lowercase() || *c == '_').collect();
                    if !name.is_empty() && name != module {
                        graph.entry(module.clone()).or_default().insert(name);
                    }
                }
            }
            graph.entry(module).or_default();
        }
        graph
    }

    #[test]
    fn top_level_modules_do_not_use_each_other_in_a_cycle() {
        let graph = module_graph();
        // Peel off modules whose dependencies are all peeled: what remains holds a cycle.
        let mut remaining = graph.clone();
        let mut layers = Vec::new();
        while !remaining.is_empty() {
            let ready: Vec<String> =
                remaining.iter().filter(|(_, deps)| deps.is_empty()).map(|(m, _)| m.clone()).collect();
            assert!(!ready.is_empty(), "the modules {:?} use each other in a cycle", remaining);
            for m in &ready {
                remaining.remove(m);
            }
            for deps in remaining.values_mut() {
                deps.retain(|d| !ready.contains(d));
            }
            layers.push(ready);
        }
        for (i, layer) in layers.iter().enumerate() {
            println!("layer {i}: {}", layer.join(", "));
        }
        assert!(graph.contains_key("motion") && graph["ship"].contains("platform"));
    }
}
