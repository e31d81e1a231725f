//! The shipped cranes: the files of `cranes/`, compiled in, so an FMU finds them by name in any
//! tool without a path (docs/crane-description.md lists them with their sources).

/// The crane an empty `crane` parameter names: the project's full-scale crane of the third
/// wave, kept bit for bit.
pub const DEFAULT_CRANE: &str = "osp_derived";

/// Each catalogue crane's name and its file's text.
pub const CATALOGUE: &[(&str, &str)] = &[
    ("osp_derived", include_str!("../../../cranes/osp_derived.json")),
    ("osp_test_crane", include_str!("../../../cranes/osp_test_crane.json")),
    ("ahc_10t", include_str!("../../../cranes/ahc_10t.json")),
];

/// The catalogue's names, in order.
pub fn names() -> Vec<&'static str> {
    CATALOGUE.iter().map(|(name, _)| *name).collect()
}

/// The text of the catalogue crane `name`.
pub fn text(name: &str) -> Option<&'static str> {
    CATALOGUE.iter().find(|(n, _)| *n == name).map(|(_, text)| *text)
}

/// Whether `spec` is a catalogue name rather than a path: letters, digits and `_` only.
pub fn is_name(spec: &str) -> bool {
    !spec.is_empty() && spec.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
}
