//! Escaping text for XML and HTML (attribute values and element content alike).
//!
//! XML 1.0 (§2.2, production `Char`) admits of the C0 control characters only tab, line feed
//! and carriage return; no escape can carry the others (`&#1;` is not well-formed either). Text a
//! user supplied (names, descriptions, start values) is therefore refused with
//! [`ForbiddenCharacter`] by [`escape`]; text the program wrote itself goes through
//! [`escape_own`], whose tests keep it free of them.

use std::borrow::Cow;
use std::fmt;

/// A character that XML 1.0 cannot hold, found in text to be escaped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ForbiddenCharacter {
    /// The character (a C0 control other than tab, line feed and carriage return).
    pub character: char,
    /// Its position in the text, in characters from 0.
    pub position: usize,
}

impl fmt::Display for ForbiddenCharacter {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "the control character U+{:04X} at position {} cannot be written to XML",
            u32::from(self.character),
            self.position
        )
    }
}

impl std::error::Error for ForbiddenCharacter {}

/// True for the characters XML 1.0 forbids that a `&str` can hold: C0 controls other than tab,
/// line feed and carriage return (U+FFFE, U+FFFF and surrogates never reach UTF-8 text here).
fn forbidden(c: char) -> bool {
    c < ' ' && !matches!(c, '\t' | '\n' | '\r')
}

/// `text` with `&`, `<`, `>` and `"` escaped, safe in XML or HTML element content and in
/// double-quoted attribute values; a forbidden control character is refused.
pub fn escape(text: &str) -> Result<Cow<'_, str>, ForbiddenCharacter> {
    if let Some((position, character)) = text.chars().enumerate().find(|&(_, c)| forbidden(c)) {
        return Err(ForbiddenCharacter { character, position });
    }
    Ok(escape_markup(text))
}

/// [`escape`] for the program's own text (variable tables, page titles it builds): a forbidden
/// control character, which its tests rule out, becomes U+FFFD instead of an error.
pub fn escape_own(text: &str) -> Cow<'_, str> {
    if text.chars().any(forbidden) {
        let cleaned: String = text.chars().map(|c| if forbidden(c) { '\u{FFFD}' } else { c }).collect();
        return Cow::Owned(escape_markup(&cleaned).into_owned());
    }
    escape_markup(text)
}

/// The markup characters replaced by their entities; borrowed when there are none.
fn escape_markup(text: &str) -> Cow<'_, str> {
    if !text.contains(['&', '<', '>', '"']) {
        return Cow::Borrowed(text);
    }
    let mut escaped = String::with_capacity(text.len() + 16);
    for c in text.chars() {
        match c {
            '&' => escaped.push_str("&amp;"),
            '<' => escaped.push_str("&lt;"),
            '>' => escaped.push_str("&gt;"),
            '"' => escaped.push_str("&quot;"),
            c => escaped.push(c),
        }
    }
    Cow::Owned(escaped)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn markup_characters_become_entities() {
        assert_eq!(escape("a < b && c > \"d\"").unwrap(), "a &lt; b &amp;&amp; c &gt; &quot;d&quot;");
        assert_eq!(escape("tab\tline\ncr\r 'ü'").unwrap(), "tab\tline\ncr\r 'ü'");
        assert!(matches!(escape("plain").unwrap(), Cow::Borrowed("plain")));
    }

    #[test]
    fn control_characters_are_refused() {
        let refused = escape("ab\u{1}c").unwrap_err();
        assert_eq!(refused, ForbiddenCharacter { character: '\u{1}', position: 2 });
        assert_eq!(refused.to_string(), "the control character U+0001 at position 2 cannot be written to XML");
        assert!(escape("\u{0}").is_err() && escape("\u{1b}[0m").is_err() && escape("\u{1f}").is_err());
        assert_eq!(escape_own("a\u{7}<"), "a\u{FFFD}&lt;");
    }
}
