//! PNG output: drawn at a multiple of the size and averaged down, so that lines are antialiased
//! and the bytes are the same on every run.

use std::path::Path;

use plotters::prelude::*;

/// PNGs are drawn at this multiple of their size and averaged down, which antialiases the lines
/// (plotters' bitmap backend draws them aliased).
pub const SUPERSAMPLE: u32 = 2;

pub type DrawResult = Result<(), Box<dyn std::error::Error>>;

/// Writes a PNG of `size` that `paint` draws at [`SUPERSAMPLE`] times the size (it gets the
/// factor to scale its pixel sizes by), each pixel the mean of its block: antialiased, and the
/// same bytes for the same drawing.
pub fn write_png(
    out: &Path,
    size: (u32, u32),
    paint: impl FnOnce(DrawingArea<BitMapBackend<'_>, plotters::coord::Shift>, u32) -> DrawResult,
) -> DrawResult {
    let scale = SUPERSAMPLE;
    let (width, height) = (size.0 * scale, size.1 * scale);
    let mut large = vec![0u8; width as usize * height as usize * 3];
    paint(BitMapBackend::with_buffer(&mut large, (width, height)).into_drawing_area(), scale)?;
    let small = downsample(&large, (width, height), scale);
    let mut png = BitMapBackend::new(out, size);
    png.blit_bitmap((0, 0), size, &small).map_err(|e| e.to_string())?;
    png.present().map_err(|e| e.to_string())?;
    Ok(())
}

/// An RGB image of `size` reduced by `factor` in each direction, each pixel the rounded mean of
/// its `factor` × `factor` block.
fn downsample(rgb: &[u8], (width, height): (u32, u32), factor: u32) -> Vec<u8> {
    let (w, f) = (width as usize, factor as usize);
    let (small_w, small_h) = (w / f, height as usize / f);
    let mut small = vec![0u8; small_w * small_h * 3];
    let n = (f * f) as u32;
    for y in 0..small_h {
        for x in 0..small_w {
            for c in 0..3 {
                let mut sum = 0u32;
                for dy in 0..f {
                    let row = (y * f + dy) * w;
                    for dx in 0..f {
                        sum += u32::from(rgb[(row + x * f + dx) * 3 + c]);
                    }
                }
                small[(y * small_w + x) * 3 + c] = ((sum + n / 2) / n) as u8;
            }
        }
    }
    small
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_block_averages_to_its_mean() {
        // A 2 × 2 block of one black and three white pixels averages to a grey.
        let block = [0, 0, 0, 255, 255, 255, 255, 255, 255, 255, 255, 255];
        assert_eq!(downsample(&block, (2, 2), 2), [191, 191, 191]);
    }
}
