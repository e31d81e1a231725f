//! Line plots, PNG or SVG (plotters): figures of stacked panels sharing an x axis, each with its
//! legend beside or under the plot, axes with round ticks, the curves' colours and dashes, and the
//! font lookup. PNGs are supersampled and averaged down, so the same figure gives the same bytes.
//!
//! Text needs a TrueType font: `CRANE_PLOT_FONT=<file.ttf>`, else the first DejaVu/Liberation
//! sans font (or any `.ttf`) under /usr/share/fonts. Without one, plots are drawn without text.
//!
//! Nothing here knows a crane, a metric or a study: the campaign's figures, the studies' plots,
//! the tuning's convergence plot and `crane-cosim plot` draw their own content with these parts.
//!
//! Modules, bottom up: [`axis`], [`font`], [`png`], [`style`]; [`figure`] on all of them.

pub mod axis;
pub mod figure;
pub mod font;
pub mod png;
pub mod style;

pub use axis::{chart_builder, style_mesh, tick_label, ticks, y_range, Ticked};
pub use figure::{draw, Figure, Layout, LegendPlacement, Panel, Series};
pub use font::register_font;
pub use png::{write_png, DrawResult, SUPERSAMPLE};
pub use style::{series_color, series_dash};
