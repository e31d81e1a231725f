//! The command line's words for the settings the libraries' messages name: each setting is the
//! option that sets it (`Setting::Start("x")` → `--start x`).

use crane_app::{Setting, Wording};

/// The command line's wording of settings.
pub struct Flags;

impl Wording for Flags {
    fn word(&self, setting: &Setting) -> String {
        match setting {
            Setting::Start(name) => format!("--start {name}"),
            Setting::Record(pattern) => format!("--record {pattern}"),
            Setting::Input(file) => format!("--input {file}"),
            Setting::Tests(selection) => format!("--tests {selection}"),
            Setting::StopTime => "--stop-time".into(),
            Setting::StepSize => "--step-size".into(),
            Setting::RecordInterval => "--record-interval".into(),
            Setting::Force => "--force".into(),
            Setting::MaxUnpackedBytes => "--max-unpacked-size".into(),
            Setting::MaxEntries => "--max-archive-entries".into(),
            Setting::MaxRatio => "--max-compression-ratio".into(),
            Setting::MaxCases => "--max-cases".into(),
            Setting::CampaignSystem => "--system FILE".into(),
            Setting::StartFile => "--start-file".into(),
            Setting::Check => "--check".into(),
            Setting::Crane => "--crane".into(),
            Setting::FullScale => "--scale full".into(),
        }
    }
}

/// `message` with every setting it names replaced by the option that sets it, e.g.
/// `Overrides::start["lod.x"]: unknown instance` → `--start lod.x: unknown instance`.
pub fn name_flags(message: &str) -> String {
    crane_app::reword(message, &Flags)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn archive_limits_name_their_options() {
        let message =
            "a.fmu: refusing to extract: 3 entries, more than the limit of 2 (raise ExtractLimits::max_entries)";
        assert_eq!(
            name_flags(message),
            "a.fmu: refusing to extract: 3 entries, more than the limit of 2 (raise it with --max-archive-entries)"
        );
        assert!(name_flags("(raise ExtractLimits::max_unpacked_bytes)").ends_with("--max-unpacked-size)"));
        assert!(name_flags("(raise ExtractLimits::max_ratio)").ends_with("--max-compression-ratio)"));
    }

    #[test]
    fn keyed_settings_become_option_and_value() {
        let message = "Overrides::start[\"lod.x\"]: unknown instance\n  Overrides::record[\"thet_*\"]: matches no \
                       variable; give Overrides::stop_time";
        assert_eq!(
            name_flags(message),
            "--start lod.x: unknown instance\n  --record thet_*: matches no variable; give --stop-time"
        );
    }
}
