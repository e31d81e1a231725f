//! The viewer page: one self-contained HTML file, its data embedded as JSON and the JavaScript
//! bundle (three.js and the viewer, built from the repository's `viewer/` folder by
//! `cargo xtask viewer`) inlined, so it opens without a network.

use serde::Serialize;

use crate::replay::FrameColumns;

/// The bundled viewer (minified IIFE with three.js's licence notice).
pub const BUNDLE: &str = include_str!("../assets/viewer.js");

/// What the page shows: a finished run, or a live session it connects to.
#[derive(Debug, Serialize)]
#[serde(tag = "mode", rename_all = "lowercase")]
pub enum PageData<'a> {
    /// Every frame of a recorded run.
    Replay { title: &'a str, frames: &'a FrameColumns },
    /// Frames arrive over the WebSocket at `socket` (a path on the page's own host); `scale` is
    /// the crane's ([`crate::scene::Crane::scale`]).
    Live { title: &'a str, scale: &'a str, socket: &'a str },
}

/// The HTML page showing `data`.
pub fn html(data: &PageData) -> Result<String, serde_json::Error> {
    let title = match data {
        PageData::Replay { title, .. } | PageData::Live { title, .. } => *title,
    };
    // `</` inside a script element would end it early; `<\/` is the same JSON string.
    let json = serde_json::to_string(data)?.replace("</", "<\\/");
    Ok(format!(
        "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
         <meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n\
         <link rel=\"icon\" href=\"data:,\">\n\
         <title>{} — crane viewer</title>\n</head>\n<body>\n\
         <script id=\"crane-data\" type=\"application/json\">{json}</script>\n\
         <script>{BUNDLE}</script>\n</body>\n</html>\n",
        escape_html(title)
    ))
}

/// `text` safe inside HTML element content (a control character becomes U+FFFD).
fn escape_html(text: &str) -> std::borrow::Cow<'_, str> {
    common::markup::escape_own(text)
}

#[cfg(test)]
mod tests;
