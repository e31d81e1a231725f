//! The command-line options behind the settings that the libraries' messages name.
//!
//! fmu-import and cosim-engine know nothing of this command line: a message about a setting names
//! its field (`ExtractLimits::max_ratio`, `Overrides::start["pendulum.x"]`). Before a message is
//! shown, [`name_flags`] puts the option that sets the field in its place.

/// A setting's phrase in the libraries' messages and what the user reads instead.
const PHRASES: [(&str, &str); 8] = [
    ("raise ExtractLimits::max_unpacked_bytes", "raise it with --max-unpacked-size"),
    ("raise ExtractLimits::max_entries", "raise it with --max-archive-entries"),
    ("raise ExtractLimits::max_ratio", "raise it with --max-compression-ratio"),
    ("Overrides::stop_time", "--stop-time"),
    ("Overrides::step_size", "--step-size"),
    ("Overrides::record_interval", "--record-interval"),
    ("RunOptions::force", "--force"),
    ("raise the case limit max_cases", "raise it with --max-cases"),
];

/// Settings given per name, written `Field["name"]`, and the option that takes `name`.
const KEYED: [(&str, &str); 3] =
    [("Overrides::start", "--start"), ("Overrides::record", "--record"), ("Overrides::inputs", "--input")];

/// `message` with every setting it names replaced by the option that sets it, e.g.
/// `Overrides::start["lod.x"]: unknown instance` → `--start lod.x: unknown instance`.
pub fn name_flags(message: &str) -> String {
    let mut text = PHRASES.iter().fold(message.to_string(), |text, (setting, flag)| text.replace(setting, flag));
    for (setting, flag) in KEYED {
        text = replace_keyed(&text, setting, flag);
    }
    text
}

/// Replaces each `setting["key"]` in `text` with `flag key`.
fn replace_keyed(text: &str, setting: &str, flag: &str) -> String {
    let opening = format!("{setting}[\"");
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(&opening) {
        let after = &rest[at + opening.len()..];
        let Some(end) = after.find("\"]") else { break };
        out.push_str(&rest[..at]);
        out.push_str(&format!("{flag} {}", &after[..end]));
        rest = &after[end + 2..];
    }
    out.push_str(rest);
    out
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
        // An unterminated key is left as it is.
        assert_eq!(name_flags("Overrides::start[\"x"), "Overrides::start[\"x");
    }
}
