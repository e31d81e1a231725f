//! "Did you mean ...?" suggestions and name lists for error messages.

/// Levenshtein distance between two strings, counted in characters (not bytes).
pub fn edit_distance(a: &str, b: &str) -> usize {
    strsim::levenshtein(a, b)
}

/// The candidate most similar to `name`, if one is close enough to be a
/// plausible typo (case is ignored; at most a third of the characters differ,
/// and never more than 3).
pub fn closest<'a, I>(name: &str, candidates: I) -> Option<String>
where
    I: IntoIterator<Item = &'a str>,
{
    let wanted = name.to_lowercase();
    let limit = (wanted.chars().count() / 3).clamp(1, 3);
    candidates
        .into_iter()
        .map(|candidate| (edit_distance(&wanted, &candidate.to_lowercase()), candidate))
        .filter(|(distance, _)| *distance <= limit)
        .min_by_key(|(distance, _)| *distance)
        .map(|(_, candidate)| candidate.to_string())
}

/// `"a", "b", "c"` — or `(none)` for an empty list.
pub fn quoted_list<'a, I>(names: I) -> String
where
    I: IntoIterator<Item = &'a str>,
{
    let list: Vec<String> = names.into_iter().map(|n| format!("{n:?}")).collect();
    if list.is_empty() {
        "(none)".to_string()
    } else {
        list.join(", ")
    }
}

/// ` (did you mean "x"?)` or nothing.
pub fn did_you_mean(suggestion: &Option<String>) -> String {
    match suggestion {
        Some(s) => format!(" (did you mean {s:?}?)"),
        None => String::new(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances() {
        assert_eq!(edit_distance("kitten", "sitting"), 3);
        assert_eq!(edit_distance("", "abc"), 3);
        assert_eq!(edit_distance("theta_x9", "theta_x0"), 1);
        // Characters, not bytes: one umlaut is one substitution.
        assert_eq!(edit_distance("lüft", "luft"), 1);
    }

    #[test]
    fn suggestions() {
        let names = ["theta_x0", "theta_y0", "lp", "load.x"];
        assert_eq!(closest("theta_x9", names).as_deref(), Some("theta_x0"));
        assert_eq!(closest("LOAD.X", names).as_deref(), Some("load.x"));
        assert_eq!(closest("velocity", names), None);
        assert_eq!(closest("lq", names).as_deref(), Some("lp"));
        assert_eq!(quoted_list(["a", "b"]), "\"a\", \"b\"");
        assert_eq!(quoted_list([]), "(none)");
    }
}
