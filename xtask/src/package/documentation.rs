//! `documentation/index.html` of an FMU: one self-contained page (inline CSS, no scripts, no
//! external files) with a header from the model description (model name, FMI version, GUID,
//! generation tool and date, platforms), the model's README rendered from Markdown (equations,
//! conventions, errors) and the table of every variable with its unit from the XML.
//!
//! Links must resolve inside the archive, whose only page this is: a README link to anything but
//! a fragment of this page (a repository file, a web address) is rendered as its plain text, and
//! raw HTML is shown as text.

use anyhow::{ensure, Result};
use fmu_import::fmu::ModelDescription;
use pulldown_cmark::{html, Event, HeadingLevel, Options, Parser, Tag, TagEnd};

/// What the header states besides the model description's own attributes.
pub struct PageFacts<'a> {
    /// FMI platform folders in the archive (`linux64`, `aarch64-linux`, `win64`; FMI 3.0:
    /// `x86_64-linux`, …).
    pub platforms: &'a [&'a str],
    /// When the FMU was generated (ISO 8601, UTC).
    pub generated: &'a str,
}

/// The page for the model described by `model`, with `readme` (Markdown) as its body.
pub fn page(model: &ModelDescription, readme: &str, facts: &PageFacts) -> Result<String> {
    let name = escape(&model.model_name);
    let description = escape(model.description.as_deref().unwrap_or_default());
    let header = header_table(model, facts);
    let body = render_markdown(readme)?;
    let variables = variable_table(model);
    Ok(format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <title>{name} — FMI {fmi} Co-Simulation FMU</title>\n<style>{STYLE}</style>\n</head>\n<body>\n\
         <header>\n<h1>{name}</h1>\n<p class=\"lead\">{description}</p>\n{header}\
         <nav><a href=\"#model\">Model</a> · <a href=\"#variables\">Variables</a></nav>\n</header>\n\
         <main>\n<section id=\"model\">\n{body}</section>\n\
         <section id=\"variables\">\n<h2>Variables</h2>\n{variables}</section>\n</main>\n</body>\n</html>\n",
        fmi = escape(&model.fmi_version),
    ))
}

fn header_table(model: &ModelDescription, facts: &PageFacts) -> String {
    let rows = [
        ("FMI version", format!("{} (Co-Simulation)", escape(&model.fmi_version))),
        (
            if model.fmi_version.starts_with('3') { "Instantiation token" } else { "GUID" },
            format!("<code>{}</code>", escape(&model.guid)),
        ),
        ("Model identifier", format!("<code>{}</code>", escape(&model.co_simulation.model_identifier))),
        ("Generation tool", escape(model.generation_tool.as_deref().unwrap_or("not stated"))),
        ("Generation date", escape(facts.generated)),
        ("Platforms", escape(&facts.platforms.join(", "))),
    ];
    let rows: String = rows.iter().map(|(key, value)| format!("<tr><th>{key}</th><td>{value}</td></tr>\n")).collect();
    format!("<table class=\"facts\">\n{rows}</table>\n")
}

/// The README as HTML with GitHub-style tables. Its headings move down one level, below the
/// page's single `<h1>` (the model name), and links out of the page become their text.
fn render_markdown(readme: &str) -> Result<String> {
    let mut in_dropped_link = Vec::new();
    let events = Parser::new_ext(readme, Options::ENABLE_TABLES).filter_map(|event| match event {
        Event::Start(Tag::Heading { level, id, classes, attrs }) => {
            Some(Event::Start(Tag::Heading { level: demoted(level), id, classes, attrs }))
        }
        Event::End(TagEnd::Heading(level)) => Some(Event::End(TagEnd::Heading(demoted(level)))),
        Event::Start(Tag::Link { ref dest_url, .. }) => {
            let keep = dest_url.starts_with('#');
            in_dropped_link.push(!keep);
            keep.then_some(event)
        }
        Event::End(TagEnd::Link) => (!in_dropped_link.pop().unwrap_or(false)).then_some(event),
        // Raw HTML in a README is shown as written: it could hold a link out of the archive.
        Event::Html(raw) | Event::InlineHtml(raw) => Some(Event::Text(raw)),
        other => Some(other),
    });
    let mut out = String::new();
    html::push_html(&mut out, events);
    ensure!(!out.contains("<img"), "README images are not packaged into the FMU");
    Ok(out)
}

fn demoted(level: HeadingLevel) -> HeadingLevel {
    match level {
        HeadingLevel::H1 => HeadingLevel::H2,
        HeadingLevel::H2 => HeadingLevel::H3,
        HeadingLevel::H3 => HeadingLevel::H4,
        HeadingLevel::H4 => HeadingLevel::H5,
        HeadingLevel::H5 | HeadingLevel::H6 => HeadingLevel::H6,
    }
}

fn variable_table(model: &ModelDescription) -> String {
    let mut rows = String::new();
    for v in &model.variables {
        let start = v.start.as_ref().map_or(String::new(), |s| s.to_string());
        rows.push_str(&format!(
            "<tr><td><code>{}</code></td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td><td>{}</td></tr>\n",
            escape(&v.name),
            v.value_reference,
            v.causality,
            v.variability,
            v.variable_type,
            escape(v.unit.as_deref().unwrap_or_default()),
            escape(&start),
            escape(v.description.as_deref().unwrap_or_default()),
        ));
    }
    format!(
        "<table class=\"variables\">\n<thead><tr><th>name</th><th>value reference</th><th>causality</th>\
         <th>variability</th><th>type</th><th>unit</th><th>start</th><th>description</th></tr></thead>\n\
         <tbody>\n{rows}</tbody>\n</table>\n"
    )
}

/// A packaged model description's text, escaped by the one escaper both sides share.
fn escape(s: &str) -> String {
    common::markup::escape_own(s).into_owned()
}

/// Readable on screen and in print; long formulas wrap or scroll inside their own block only.
const STYLE: &str = "
body { font: 16px/1.5 system-ui, -apple-system, 'Segoe UI', 'DejaVu Sans', sans-serif; color: #1f2328;
  max-width: 60rem; margin: 0 auto; padding: 1.5rem; }
header { border-bottom: 2px solid #d0d7de; margin-bottom: 1.5rem; }
h1 { margin: 0 0 .25rem; font-size: 2rem; }
h2 { border-bottom: 1px solid #d0d7de; padding-bottom: .2rem; margin-top: 2rem; }
.lead { color: #57606a; margin-top: 0; }
nav { margin: .75rem 0 1rem; }
a { color: #0969da; }
table { border-collapse: collapse; margin: 1rem 0; font-size: .9rem; display: block; overflow-x: auto; }
th, td { border: 1px solid #d0d7de; padding: .3rem .6rem; text-align: left; vertical-align: top; }
thead th { background: #f6f8fa; }
table.facts th { background: #f6f8fa; white-space: nowrap; }
code { font-family: ui-monospace, 'DejaVu Sans Mono', monospace; font-size: .9em; background: #f6f8fa;
  padding: .1em .3em; border-radius: 4px; }
pre { background: #f6f8fa; padding: .75rem 1rem; border-radius: 6px; overflow-x: auto; }
pre code { background: none; padding: 0; }
table.variables td:first-child { white-space: nowrap; }
table.variables td:last-child { min-width: 18rem; }
";

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn tables_and_headings_are_rendered_and_demoted() {
        let html = render_markdown("# Title\n\n## Ports\n\n| a | b |\n|---|---|\n| 1 | **2** |\n").unwrap();
        assert!(html.contains("<h2>Title</h2>") && html.contains("<h3>Ports</h3>"), "{html}");
        assert!(html.contains("<table>") && html.contains("<td><strong>2</strong></td>"), "{html}");
    }

    #[test]
    fn links_out_of_the_page_become_text_and_fragments_stay() {
        let html = render_markdown(
            "See [the physics](../physics/README.md), [FMI](https://fmi-standard.org) \
             and [ports](#variables).",
        )
        .unwrap();
        assert!(!html.contains("physics/README") && !html.contains("https:"), "{html}");
        assert!(html.contains("the physics") && html.contains("FMI"), "{html}");
        assert!(html.contains("<a href=\"#variables\">ports</a>"), "{html}");
    }
}
