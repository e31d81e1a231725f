//! What a path given to run names: one FMU to run alone, or a system (system or scenario file,
//! SSP archive, OSP system structure). Decided here only, for every use case and front end.

use std::path::{Path, PathBuf};

use cosim_engine::system::single::instance_name;

/// A path to run, by what it holds.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Source {
    /// A `.fmu` run alone: its instance is named after the file (`pendulum.fmu` → `pendulum`).
    Fmu(PathBuf),
    /// Anything else: a system or scenario file, an SSP archive or an OSP system structure.
    System(PathBuf),
}

impl Source {
    /// The source `path` names: an FMU by its extension (any case), else a system.
    pub fn of(path: &Path) -> Source {
        if path.extension().is_some_and(|e| e.eq_ignore_ascii_case("fmu")) {
            Source::Fmu(path.to_path_buf())
        } else {
            Source::System(path.to_path_buf())
        }
    }

    /// The path as given.
    pub fn path(&self) -> &Path {
        match self {
            Source::Fmu(path) | Source::System(path) => path,
        }
    }

    /// The instance prefix a lone FMU's names may leave out (`"pendulum."`); empty for a system,
    /// whose names always carry their instance.
    pub fn prefix(&self) -> String {
        match self {
            Source::Fmu(path) => format!("{}.", instance_name(path)),
            Source::System(_) => String::new(),
        }
    }

    /// `name` with the instance prefix a lone FMU's names may leave out (a name that already
    /// carries it is kept): `theta_x0` and `pendulum.theta_x0` both name `pendulum.theta_x0`.
    pub fn qualified(&self, name: &str) -> String {
        let prefix = self.prefix();
        if prefix.is_empty() || name.starts_with(&prefix) {
            name.to_string()
        } else {
            format!("{prefix}{name}")
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_fmu_is_told_by_its_extension_in_any_case() {
        assert!(matches!(Source::of(Path::new("a/pendulum.FMU")), Source::Fmu(_)));
        assert!(matches!(Source::of(Path::new("a/fmu.json")), Source::System(_)));
        assert!(matches!(Source::of(Path::new("out/osp")), Source::System(_)));
    }

    #[test]
    fn a_lone_fmus_names_may_leave_out_its_instance() {
        let fmu = Source::of(Path::new("target/fmu/pendulum.fmu"));
        assert_eq!(fmu.qualified("theta_x0"), "pendulum.theta_x0");
        assert_eq!(fmu.qualified("pendulum.theta_x0"), "pendulum.theta_x0");
        let system = Source::of(Path::new("systems/closed_loop.json"));
        assert_eq!(system.qualified("pendulum.theta_x0"), "pendulum.theta_x0");
        assert_eq!(system.prefix(), "");
    }
}
