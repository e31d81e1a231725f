//! Peak detection for the decay fits of thesis §7.2 (the "peak detection" half of the "peak
//! detection and least-squares exponential fitting procedure").
//!
//! Works on plain samples (no units, no time axis); to find minima, negate the signal.

/// Indices of the local maxima of `values` that are significant and separated.
///
/// * A local maximum is a sample higher than both neighbours; a flat top (a run of equal samples
///   with lower samples on both sides) counts once, at its middle sample (the left one of the two
///   middles for an even run), as scipy.signal.find_peaks does. The first and last samples are
///   never peaks: their other side is unknown.
/// * Only peaks whose topographic [`prominence`] is ≥ `min_prominence` are kept: this drops the
///   small wiggles that noise adds to a slope or a broad top.
/// * Then, among kept peaks closer than `min_distance` samples (index difference < min_distance),
///   the higher one wins (the earlier one on a tie). The prominence filter comes first, unlike
///   scipy's order, so that a tall but insignificant wiggle cannot suppress a real peak nearby.
///
/// Returned in increasing index order.
pub fn find_peaks(values: &[f64], min_distance: usize, min_prominence: f64) -> Vec<usize> {
    let prominent: Vec<usize> =
        local_maxima(values).into_iter().filter(|&i| prominence(values, i) >= min_prominence).collect();
    separate(values, prominent, min_distance)
}

/// The local maxima (flat tops at their middle sample), in increasing order.
fn local_maxima(values: &[f64]) -> Vec<usize> {
    let mut peaks = Vec::new();
    let mut i = 1;
    while i + 1 < values.len() {
        if values[i] > values[i - 1] {
            // Walk over a possible flat top to the first sample that differs.
            let mut end = i;
            while end + 1 < values.len() && values[end + 1] == values[i] {
                end += 1;
            }
            if end + 1 < values.len() && values[end + 1] < values[i] {
                peaks.push((i + end) / 2);
            }
            i = end + 1;
        } else {
            i += 1;
        }
    }
    peaks
}

/// Topographic prominence of the peak at `peak` (same units as `values`), as scipy defines it:
/// on each side, walk away from the peak until a strictly higher sample or the end of the signal
/// and take the lowest sample on the way (the base on that side); the prominence is the peak's
/// height above the higher of the two bases. I.e. how far one must descend from this peak before
/// one can climb to anything higher.
pub fn prominence(values: &[f64], peak: usize) -> f64 {
    let top = values[peak];
    let lowest = |iter: &mut dyn Iterator<Item = &f64>| iter.take_while(|&&v| v <= top).fold(top, |low, &v| low.min(v));
    let left_base = lowest(&mut values[..peak].iter().rev());
    let right_base = lowest(&mut values[peak + 1..].iter());
    top - left_base.max(right_base)
}

/// The top of the peak at sample `peak` refined by the parabola through it and its two
/// neighbours: (time, value) of the parabola's vertex, in the units of `times` and `values`.
///
/// Why: at 30 Hz a pendulum swing of ω ≈ 3.7 rad/s is sampled every 0.12 rad of phase, so the
/// highest sample can miss the true top by up to 1 − cos(0.062) ≈ 0.2 % of the amplitude, at
/// random from peak to peak; the vertex is exact for a parabolic top and within O((ω·Δt)⁴) for a
/// sinusoidal one. Works for non-uniform sample times. The vertex is kept between the two
/// neighbours; a flat top or a first/last sample is returned unchanged.
pub fn interpolate_peak(times: &[f64], values: &[f64], peak: usize) -> (f64, f64) {
    let unchanged = (times[peak], values[peak]);
    if peak == 0 || peak + 1 >= values.len() {
        return unchanged;
    }
    let (h1, h2) = (times[peak] - times[peak - 1], times[peak + 1] - times[peak]);
    // p(t) = y + b·s + a·s² with s = t − t_peak through the three samples (divided differences).
    let d1 = (values[peak] - values[peak - 1]) / h1;
    let d2 = (values[peak + 1] - values[peak]) / h2;
    let a = (d2 - d1) / (h1 + h2);
    let b = d1 + a * h1;
    if !(a < 0.0) {
        return unchanged;
    }
    let s = (-b / (2.0 * a)).clamp(-h1, h2);
    (times[peak] + s, values[peak] + b * s + a * s * s)
}

/// Keeps, greedily from the highest, the peaks that are at least `min_distance` samples from
/// every higher kept one.
fn separate(values: &[f64], peaks: Vec<usize>, min_distance: usize) -> Vec<usize> {
    let mut by_height = peaks;
    // Stable sort: on equal heights the earlier peak is considered first and wins.
    by_height.sort_by(|&a, &b| values[b].total_cmp(&values[a]));
    let mut kept: Vec<usize> = Vec::new();
    for p in by_height {
        if kept.iter().all(|&k| k.abs_diff(p) >= min_distance) {
            kept.push(p);
        }
    }
    kept.sort_unstable();
    kept
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    #[test]
    fn prominence_of_a_hand_made_profile() {
        //        index: 0    1    2    3    4    5    6
        let v = [0.0, 3.0, 1.0, 2.0, 0.5, 4.0, 0.0];
        // Peak 1 (3): left base 0 (signal start), right base min(1, 2, 0.5) = 0.5 before the 4.
        assert_eq!(prominence(&v, 1), 2.5);
        // Peak 3 (2): bases 1 (before the 3) and 0.5 (before the 4) → 2 − 1.
        assert_eq!(prominence(&v, 3), 1.0);
        // The highest peak descends to the signal's minimum on both sides.
        assert_eq!(prominence(&v, 5), 4.0);
        assert_eq!(find_peaks(&v, 1, 0.0), vec![1, 3, 5]);
        assert_eq!(find_peaks(&v, 1, 1.5), vec![1, 5]);
    }

    #[test]
    fn flat_tops_count_once_at_their_middle_and_ends_are_never_peaks() {
        let v = [5.0, 1.0, 2.0, 2.0, 2.0, 1.0, 3.0, 3.0, 0.0, 4.0];
        // The run 2..=4 → 3; the run 6..=7 → 6 (left middle); 0 and 9 are the ends.
        assert_eq!(find_peaks(&v, 1, 0.0), vec![3, 6]);
        // A flat top that ends in a rise is a shoulder, not a peak.
        assert_eq!(find_peaks(&[0.0, 1.0, 1.0, 2.0, 0.0], 1, 0.0), vec![3]);
    }

    /// e^(−t/5)·cos(2π t / 1.7) at 30 Hz over 20 s: maxima of a damped cosine come every period
    /// T, a fixed lead δ = atan(T/(2π·5))/(2π/T) before the multiples of T.
    #[test]
    fn one_peak_per_period_of_a_decaying_cosine() {
        let (period, tau, rate) = (1.7, 5.0, 30.0);
        let omega = TAU / period;
        let values: Vec<f64> =
            (0..600).map(|k| k as f64 / rate).map(|t| (-t / tau).exp() * (omega * t).cos()).collect();
        let peaks = find_peaks(&values, 10, 1e-3);
        let lead = (1.0 / (omega * tau)).atan() / omega;
        // t = 0 is the signal start, so the peaks are at k·T − δ for k = 1..=11 (11·1.7 < 20).
        assert_eq!(peaks.len(), 11, "{peaks:?}");
        for (k, &i) in peaks.iter().enumerate() {
            let expected = (k + 1) as f64 * period - lead;
            assert!((i as f64 / rate - expected).abs() <= 1.0 / rate, "peak {k}: {i} vs {expected}");
        }
    }

    #[test]
    fn wiggles_below_the_prominence_are_dropped() {
        // A slow sine (period 400 samples, slope ≤ 0.016 per sample) plus an alternating ±0.01
        // "noise" (steps of 0.02): a local maximum at nearly every other sample, each with a
        // prominence of at most ≈ 0.02 + 0.016 except the two true tops (prominence ≈ 2).
        let values: Vec<f64> =
            (0..800).map(|k| (TAU * k as f64 / 400.0).sin() + if k % 2 == 0 { 0.01 } else { -0.01 }).collect();
        assert!(find_peaks(&values, 1, 0.0).len() > 300);
        let peaks = find_peaks(&values, 1, 0.1);
        assert_eq!(peaks.len(), 2, "{peaks:?}");
        assert!(peaks[0].abs_diff(100) <= 1 && peaks[1].abs_diff(500) <= 1, "{peaks:?}");
    }

    #[test]
    fn min_distance_keeps_the_higher_of_close_peaks() {
        //            0    1    2    3    4    5    6    7    8    9
        let v = [0.0, 1.0, 0.0, 3.0, 0.0, 2.0, 0.0, 0.0, 0.0, 1.5, 0.0];
        assert_eq!(find_peaks(&v, 1, 0.0), vec![1, 3, 5, 9]);
        // Within 2 samples of the 3 at index 3 lie indices 1 and 5: both go; 9 stays.
        assert_eq!(find_peaks(&v, 3, 0.0), vec![3, 9]);
        // |9 − 3| = 6: distance 6 keeps index 9, distance 7 removes it.
        assert_eq!(find_peaks(&v, 6, 0.0), vec![3, 9]);
        assert_eq!(find_peaks(&v, 7, 0.0), vec![3]);
        // Equal heights: the earlier wins.
        assert_eq!(find_peaks(&[0.0, 2.0, 0.0, 2.0, 0.0], 3, 0.0), vec![1]);
    }

    #[test]
    fn interpolation_finds_the_vertex_of_a_parabola_on_uneven_samples() {
        let f = |t: f64| 3.0 - 2.0 * (t - 0.37).powi(2);
        let times = [0.0, 0.3, 0.45, 0.9];
        let values = times.map(f);
        assert_eq!(find_peaks(&values, 1, 0.0), vec![1]);
        let (t, v) = interpolate_peak(&times, &values, 1);
        assert!((t - 0.37).abs() < 1e-12 && (v - 3.0).abs() < 1e-12, "{t} {v}");
        // Ends and flat tops stay as sampled.
        assert_eq!(interpolate_peak(&times, &values, 0), (0.0, f(0.0)));
        assert_eq!(interpolate_peak(&[0.0, 1.0, 2.0], &[1.0, 1.0, 1.0], 1), (1.0, 1.0));
    }

    /// A cosine top ω = 3.74 rad/s sampled at 30 Hz, the true top 0.4 samples after a sample:
    /// the best sample is low by 1 − cos(3.74·0.4/30) = 1.24e-3, the vertex by < 1e-5.
    #[test]
    fn interpolation_of_a_sampled_cosine_top() {
        let (omega, rate, top) = (3.74, 30.0, 1.0 + 0.4 / 30.0);
        let times: Vec<f64> = (0..60).map(|k| k as f64 / rate).collect();
        let values: Vec<f64> = times.iter().map(|t| (omega * (t - top)).cos()).collect();
        let peaks = find_peaks(&values, 1, 0.0);
        assert_eq!(peaks, vec![30]);
        assert!((1.0 - values[30] - (1.0 - (omega * 0.4 / rate).cos())).abs() < 1e-15);
        let (t, v) = interpolate_peak(&times, &values, 30);
        assert!((1.0 - v).abs() < 1e-5, "{}", 1.0 - v);
        assert!((t - top).abs() < 1e-3 / rate, "{}", (t - top) * rate);
    }
}
