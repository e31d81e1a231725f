//! A minimal indented XML writer for the export formats (two-space indentation, attributes in
//! the order given, values escaped), and number formats that read back exactly.

use common::markup::{escape, ForbiddenCharacter};
use fmu_import::value::Value;

/// XML text under construction. Text that XML cannot hold (a control character in a name, a
/// description or a start value the user gave) is written empty and refused by [`Xml::finish`].
pub struct Xml {
    text: String,
    depth: usize,
    refused: Option<(String, ForbiddenCharacter)>,
}

impl Xml {
    /// A document with the XML declaration.
    pub fn new() -> Self {
        Self { text: "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n".into(), depth: 0, refused: None }
    }

    fn start_tag(&mut self, name: &str, attributes: &[(&str, &str)]) {
        self.text.push('<');
        self.text.push_str(name);
        for (key, value) in attributes {
            let value = self.escaped(value);
            self.text.push_str(&format!(" {key}=\"{value}\""));
        }
    }

    fn tag(&mut self, name: &str, attributes: &[(&str, &str)], end: &str) {
        self.text.push_str(&"  ".repeat(self.depth));
        self.start_tag(name, attributes);
        self.text.push_str(end);
        self.text.push('\n');
    }

    /// `<name a="…">`; children follow until [`Xml::close`].
    pub fn open(&mut self, name: &str, attributes: &[(&str, &str)]) {
        self.tag(name, attributes, ">");
        self.depth += 1;
    }

    /// `<name a="…"/>`.
    pub fn empty(&mut self, name: &str, attributes: &[(&str, &str)]) {
        self.tag(name, attributes, "/>");
    }

    /// `<name a="…"><child b="…"/></name>` on one line.
    pub fn wrapped(&mut self, name: &str, attributes: &[(&str, &str)], child: &str, child_attributes: &[(&str, &str)]) {
        self.text.push_str(&"  ".repeat(self.depth));
        self.start_tag(name, attributes);
        self.text.push('>');
        self.start_tag(child, child_attributes);
        self.text.push_str(&format!("/></{name}>\n"));
    }

    /// `<name>text</name>` on one line.
    pub fn text_element(&mut self, name: &str, text: &str) {
        let text = self.escaped(text);
        self.text.push_str(&format!("{}<{name}>{text}</{name}>\n", "  ".repeat(self.depth)));
    }

    /// `</name>`.
    pub fn close(&mut self, name: &str) {
        self.depth -= 1;
        self.text.push_str(&format!("{}</{name}>\n", "  ".repeat(self.depth)));
    }

    /// `text` escaped; empty, with the first refusal kept, when XML cannot hold it.
    fn escaped(&mut self, text: &str) -> String {
        match escape(text) {
            Ok(escaped) => escaped.into_owned(),
            Err(forbidden) => {
                self.refused.get_or_insert((text.to_string(), forbidden));
                String::new()
            }
        }
    }

    /// The document, or the first text that XML cannot hold and why.
    pub fn finish(self) -> Result<String, (String, ForbiddenCharacter)> {
        match self.refused {
            None => Ok(self.text),
            Some(refused) => Err(refused),
        }
    }
}

/// An `xs:double`: the shortest text that reads back as the same double (`{:?}`), with the
/// infinities and NaN spelt as XML Schema spells them.
pub fn double(value: f64) -> String {
    match value {
        f64::INFINITY => "INF".into(),
        f64::NEG_INFINITY => "-INF".into(),
        v if v.is_nan() => "NaN".into(),
        v => format!("{v:?}"),
    }
}

/// The element name (`Real`, `Integer`, `Boolean`, `String`) and value text of a start value;
/// enumerations are integers on the FMI ABI and are written as such.
pub fn typed_value(value: &Value) -> (&'static str, String) {
    match value {
        Value::Real(v) => ("Real", double(*v)),
        Value::Integer(v) => ("Integer", v.to_string()),
        Value::Boolean(v) => ("Boolean", v.to_string()),
        Value::String(v) => ("String", v.clone()),
    }
}
