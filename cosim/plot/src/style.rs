//! The curves' colours and dashes, the same for the same curve index in every figure.

use plotters::prelude::*;

/// The Okabe–Ito colours (Okabe and Ito, "Color Universal Design", 2008), distinct for the
/// colour-blind, without their yellow, which is unreadable on white.
const PALETTE: [RGBColor; 7] = [
    RGBColor(0x00, 0x72, 0xB2), // blue
    RGBColor(0xD5, 0x5E, 0x00), // vermillion
    RGBColor(0x00, 0x9E, 0x73), // bluish green
    RGBColor(0xCC, 0x79, 0xA7), // reddish purple
    RGBColor(0xE6, 0x9F, 0x00), // orange
    RGBColor(0x56, 0xB4, 0xE9), // sky blue
    RGBColor(0x00, 0x00, 0x00), // black
];

/// The colour of a panel's `index`-th curve: the same in every panel, so that stacked panels of
/// the same files match. After the palette's seven colours they repeat, dashed, dotted, then
/// long-dashed.
pub fn series_color(index: usize) -> RGBColor {
    PALETTE[index % PALETTE.len()]
}

/// The dash and gap lengths (pixels) of the `index`-th curve; `None` for a solid line.
pub fn series_dash(index: usize) -> Option<(u32, u32)> {
    match (index / PALETTE.len()) % 4 {
        0 => None,
        1 => Some((10, 6)),
        2 => Some((2, 4)),
        _ => Some((20, 5)),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// WCAG's contrast ratio of a colour against white.
    fn contrast_on_white(color: RGBColor) -> f64 {
        let linear = |c: u8| {
            let c = f64::from(c) / 255.0;
            if c <= 0.03928 {
                c / 12.92
            } else {
                ((c + 0.055) / 1.055).powf(2.4)
            }
        };
        let luminance = 0.2126 * linear(color.0) + 0.7152 * linear(color.1) + 0.0722 * linear(color.2);
        1.05 / (luminance + 0.05)
    }

    #[test]
    fn every_curve_colour_reads_on_white_and_repeats_only_with_another_dash() {
        for i in 0..PALETTE.len() {
            assert!(contrast_on_white(series_color(i)) >= 2.0, "colour {i}: {:?}", series_color(i));
        }
        let styles: Vec<(RGBColor, Option<(u32, u32)>)> = (0..28).map(|i| (series_color(i), series_dash(i))).collect();
        for (i, a) in styles.iter().enumerate() {
            assert!(styles[..i].iter().all(|b| b != a), "curve {i} looks like an earlier one");
        }
    }
}
