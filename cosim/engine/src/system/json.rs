//! Reading the JSON of system, scenario and study files.
//!
//! The text is checked for JSON syntax before it is read as a kind of file: read straight into a
//! [`SystemSpec`](super::SystemSpec), a scenario with a trailing comma fails first on its
//! `system` key, and the user is sent looking for a wrong field instead of the comma.

use serde::de::{DeserializeOwned, Deserializer as _, IgnoredAny, MapAccess, Visitor};

/// What a file was read as, for messages.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FileKind {
    System,
    Scenario,
    Study,
    /// A tuning study (`crane-cosim tune`).
    Tuning,
    /// The `SystemStructure.ssd` of an SSP archive.
    Ssp,
    /// An `OspSystemStructure.xml` (libcosim's format).
    Osp,
}

impl FileKind {
    /// The kind with its article, e.g. "a scenario file".
    pub fn with_article(self) -> &'static str {
        match self {
            FileKind::System => "a system file",
            FileKind::Scenario => "a scenario file",
            FileKind::Study => "a study file",
            FileKind::Tuning => "a tuning file",
            FileKind::Ssp => "an SSP archive",
            FileKind::Osp => "an OSP system structure",
        }
    }

    /// The kind without article, e.g. "scenario file".
    pub fn noun(self) -> &'static str {
        self.with_article().split_once(' ').map_or("file", |(_, noun)| noun)
    }
}

/// A file that is not valid JSON (or XML), or whose content is not what its kind allows.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "{}",
    match syntax {
        Some(format) => format!(
            "{format} syntax error at line {line} column {column} (read as {}): {message}",
            kind.with_article()
        ),
        None => format!("invalid {}: {message}", kind.noun()),
    }
)]
pub struct ParseError {
    /// What the file was read as.
    pub kind: FileKind,
    /// `Some("JSON")` for text that is not JSON at all; `None` for valid JSON with a wrong field.
    pub syntax: Option<&'static str>,
    /// Line of the error, from 1.
    pub line: usize,
    /// Column of the error, from 1.
    pub column: usize,
    /// What is wrong there.
    pub message: String,
}

impl ParseError {
    /// The error of reading the text of a `kind` file, located at serde_json's line and column.
    pub fn from_json(error: &serde_json::Error, kind: FileKind) -> Self {
        let mut message = error.to_string();
        // serde_json appends " at line L column C"; the position is reported separately.
        if let Some(position) = message.rfind(" at line ") {
            message.truncate(position);
        }
        let syntax = (error.is_syntax() || error.is_eof()).then_some("JSON");
        Self { kind, syntax, line: error.line(), column: error.column(), message }
    }
}

/// Reads JSON text as a `kind` file; a syntax error anywhere is reported before a wrong field.
pub fn parse<T: DeserializeOwned>(text: &str, kind: FileKind) -> Result<T, ParseError> {
    top_level_keys(text).map_err(|(_, error)| ParseError::from_json(&error, kind))?;
    serde_json::from_str(text).map_err(|error| ParseError::from_json(&error, kind))
}

/// Whether JSON text is a scenario file (it names a `system`) or a system file; a syntax error
/// says which of the two the keys before it made the text.
pub fn system_or_scenario(text: &str) -> Result<FileKind, ParseError> {
    let kind = |keys: &[String]| {
        if keys.iter().any(|key| key == "system") {
            FileKind::Scenario
        } else {
            FileKind::System
        }
    };
    match top_level_keys(text) {
        Ok(keys) => Ok(kind(&keys)),
        Err((keys, error)) => Err(ParseError::from_json(&error, kind(&keys))),
    }
}

/// The keys of the top-level object of JSON text (none if it is no object); on a syntax error,
/// the keys before it and the error.
fn top_level_keys(text: &str) -> Result<Vec<String>, (Vec<String>, serde_json::Error)> {
    let mut keys = Vec::new();
    let mut deserializer = serde_json::Deserializer::from_str(text);
    let read = deserializer.deserialize_any(KeyCollector(&mut keys)).and_then(|()| deserializer.end());
    match read {
        Err(error) if error.is_syntax() || error.is_eof() => Err((keys, error)),
        // Valid JSON that is no object: reading it as a file reports that.
        _ => Ok(keys),
    }
}

/// Collects the keys of an object, skipping (but checking the syntax of) their values.
struct KeyCollector<'a>(&'a mut Vec<String>);

impl<'de> Visitor<'de> for KeyCollector<'_> {
    type Value = ();

    fn expecting(&self, formatter: &mut std::fmt::Formatter) -> std::fmt::Result {
        formatter.write_str("a JSON object")
    }

    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<(), A::Error> {
        while let Some(key) = map.next_key::<String>()? {
            self.0.push(key);
            map.next_value::<IgnoredAny>()?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_trailing_comma_is_a_syntax_error_of_the_kind_its_keys_tell() {
        let error = system_or_scenario("{\n  \"system\": \"a.json\",\n  \"stop_time\": 1,\n}").unwrap_err();
        assert_eq!((error.syntax, error.kind, error.line), (Some("JSON"), FileKind::Scenario, 4));
        assert_eq!(error.to_string(), "JSON syntax error at line 4 column 1 (read as a scenario file): trailing comma");
        let error = system_or_scenario("{ \"fmus\": {}, ").unwrap_err();
        assert_eq!((error.kind, error.line), (FileKind::System, 1));
        assert_eq!(system_or_scenario("[1, 2]"), Ok(FileKind::System));
        assert_eq!(system_or_scenario("{\"system\": 1} x").unwrap_err().message, "trailing characters");
    }

    #[test]
    fn syntax_errors_come_before_wrong_fields() {
        #[derive(Debug, serde::Deserialize)]
        #[serde(deny_unknown_fields)]
        struct Only {
            #[allow(dead_code)]
            a: f64,
        }
        let error = parse::<Only>("{\"b\": 1,\n \"a\": 2,}", FileKind::Study).unwrap_err();
        assert_eq!((error.syntax, error.line), (Some("JSON"), 2), "{error}");
        let error = parse::<Only>("{\"b\": 1}", FileKind::Study).unwrap_err();
        assert_eq!(error.to_string(), "invalid study file: unknown field `b`, expected `a`");
    }
}
