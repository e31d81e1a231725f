//! The settings that the libraries' messages name, typed, and how each front end words them.
//!
//! fmu-import, cosim-engine and crane-campaign know no front end: a message about a setting
//! names the field that holds it (`Overrides::start["pendulum.x"]`, `ExtractLimits::max_ratio`).
//! [`reword`] finds each such field in a message, makes it a [`Setting`] and puts the front
//! end's own words for it in its place, so that the command line says `--start pendulum.x` and
//! Python says `start={"pendulum.x": …}` about the same mistake.

/// A setting a user gives, as the libraries' messages name it.
#[derive(Debug, Clone, PartialEq, Eq)]
pub enum Setting {
    /// A start value of the variable named (`instance.variable`).
    Start(String),
    /// A variable or pattern to record.
    Record(String),
    /// An inputs file.
    Input(String),
    /// The stop time replacing the file's.
    StopTime,
    /// The communication step size replacing the file's.
    StepSize,
    /// The recording interval replacing the file's.
    RecordInterval,
    /// Running although the workload is over its limits.
    Force,
    /// The archive limits: total unpacked size, entries, compression ratio.
    MaxUnpackedBytes,
    MaxEntries,
    MaxRatio,
    /// The most cases a sweep study may plan.
    MaxCases,
    /// A campaign's closed-loop system file, its start-values file, its test selection, and
    /// its judgement against docs/acceptance.md.
    CampaignSystem,
    StartFile,
    Tests(String),
    Check,
    /// A campaign's crane description, and its choice of the full-scale crane.
    Crane,
    FullScale,
}

impl Setting {
    /// Whether the libraries phrase it as a limit to raise ("raise …").
    pub fn is_limit(&self) -> bool {
        matches!(self, Setting::MaxUnpackedBytes | Setting::MaxEntries | Setting::MaxRatio | Setting::MaxCases)
    }
}

/// How a front end names settings to its user.
pub trait Wording {
    /// The words for `setting`: `--start x`, `start={"x": …}`, `--max-cases`.
    fn word(&self, setting: &Setting) -> String;
}

/// The libraries' phrase of each setting without a key. A limit is phrased as the advice to
/// raise it, which becomes "raise it with <words>".
const FIXED: [(&str, Setting); 13] = [
    ("raise ExtractLimits::max_unpacked_bytes", Setting::MaxUnpackedBytes),
    ("raise ExtractLimits::max_entries", Setting::MaxEntries),
    ("raise ExtractLimits::max_ratio", Setting::MaxRatio),
    ("raise the case limit max_cases", Setting::MaxCases),
    ("Overrides::stop_time", Setting::StopTime),
    ("Overrides::step_size", Setting::StepSize),
    ("Overrides::record_interval", Setting::RecordInterval),
    ("RunOptions::force", Setting::Force),
    ("CampaignRequest::system", Setting::CampaignSystem),
    ("CampaignRequest::start_file", Setting::StartFile),
    ("CampaignRequest::check", Setting::Check),
    ("CampaignRequest::crane", Setting::Crane),
    ("CampaignRequest::scale = full", Setting::FullScale),
];

/// A setting given per name, made of its name.
type Keyed = fn(String) -> Setting;

/// The libraries' field of each setting given per name, written `Field["name"]`.
const KEYED: [(&str, Keyed); 4] = [
    ("Overrides::start", Setting::Start),
    ("Overrides::record", Setting::Record),
    ("Overrides::inputs", Setting::Input),
    ("CampaignRequest::tests", Setting::Tests),
];

/// `message` with every setting it names in `wording`'s words, e.g. with the command line's
/// `Overrides::start["lod.x"]: unknown instance` → `--start lod.x: unknown instance`.
pub fn reword(message: &str, wording: &impl Wording) -> String {
    let mut text = FIXED.iter().fold(message.to_string(), |text, (phrase, setting)| {
        let words = wording.word(setting);
        let words = if setting.is_limit() { format!("raise it with {words}") } else { words };
        text.replace(phrase, &words)
    });
    for (field, setting) in KEYED {
        text = replace_keyed(&text, field, |key| wording.word(&setting(key.to_string())));
    }
    text
}

/// Replaces each `field["key"]` in `text` with `words(key)`; an unterminated key is left as it is.
fn replace_keyed(text: &str, field: &str, words: impl Fn(&str) -> String) -> String {
    let opening = format!("{field}[\"");
    let mut out = String::with_capacity(text.len());
    let mut rest = text;
    while let Some(at) = rest.find(&opening) {
        let after = &rest[at + opening.len()..];
        let Some(end) = after.find("\"]") else { break };
        out.push_str(&rest[..at]);
        out.push_str(&words(&after[..end]));
        rest = &after[end + 2..];
    }
    out.push_str(rest);
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A wording that shows which setting was recognised.
    struct Debug;

    impl Wording for Debug {
        fn word(&self, setting: &Setting) -> String {
            format!("<{setting:?}>")
        }
    }

    #[test]
    fn limits_become_advice_to_raise_the_front_ends_setting() {
        let message = "a.fmu: 3 entries, more than the limit of 2 (raise ExtractLimits::max_entries)";
        assert_eq!(reword(message, &Debug), "a.fmu: 3 entries, more than the limit of 2 (raise it with <MaxEntries>)");
        assert_eq!(reword("(raise the case limit max_cases)", &Debug), "(raise it with <MaxCases>)");
    }

    #[test]
    fn keyed_settings_carry_their_key() {
        let message = "Overrides::start[\"lod.x\"]: unknown instance\n  Overrides::record[\"thet_*\"]: matches no \
                       variable; give Overrides::stop_time";
        assert_eq!(
            reword(message, &Debug),
            "<Start(\"lod.x\")>: unknown instance\n  <Record(\"thet_*\")>: matches no variable; give <StopTime>"
        );
        assert_eq!(reword("Overrides::start[\"x", &Debug), "Overrides::start[\"x");
    }
}
