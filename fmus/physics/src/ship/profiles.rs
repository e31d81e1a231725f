//! Ship motion profiles 1–3 (SPEC §8.2) and their conversion to test scale (thesis §3.3).
//!
//! Full scale: the response of the default [`Hull`] to a seeded JONSWAP sea (200 components) at
//! the profile's heading. Test scale, as §3.3 prepares the recorded profiles: one scale factor s on
//! surge, sway and heave, the angles unscaled, yaw zero, and every degree of freedom centred on
//! its mean over the 120 s test window. s is the largest factor for which the platform's exact
//! inverse kinematics keeps every actuator inside its stroke and below its speed limit over the
//! window, with the crane at the port side and at the stern, with a margin: the used share of
//! the range ([`PlatformGeometry::usage`]) is [`MARGIN`].
//!
//! The search bounds a maximum over 120 s of exact inverse kinematics at some eight trial factors.
//! Evaluated at every sample that cost 0.77·10⁹ instructions; it now screens the window every
//! 0.1 s and evaluates exactly only where the maximum can be (`Screened`), some 0.05·10⁹, with
//! the same result bit for bit. The factors it finds for profiles 1–3 with their own seeds, the
//! default hull and the default geometry are still stored bit for bit ([`KNOWN_SCALES`]) and used
//! when a fingerprint of every input of the search matches, so those runs pay nothing; any other
//! input is searched, and a test repeats the search to keep the table exact.

use super::motion::HarmonicMotion;
use super::phasors::uniform_samples;
use super::rao::Hull;
use super::spectrum::{components, SeaState, COMPONENTS};
use crate::motion::DeckMotion;
use crate::motion::{AxisMotion, HEAVE, SURGE, SWAY, YAW};
use crate::platform::kinematics::{exact_inverse_rates, PlatformError, PlatformGeometry};
use crate::platform::CraneLocation;
use serde::{Deserialize, Serialize};

/// Length of the test window (s): the profiles are prepared for t = 0 … 120 s.
pub const WINDOW: f64 = 120.0;
/// Share of the actuators' stroke and speed range the scaled profile uses at most.
pub const MARGIN: f64 = 0.95;
/// Sampling step of the scale search (s).
const SEARCH_STEP: f64 = 0.02;
/// Sampling step of the final check of the chosen scale (s): half the search's, so the check
/// reuses every sample of the search ([`refined`]).
const CHECK_STEP: f64 = SEARCH_STEP / 2.0;

/// A ship motion profile: sea state, wave heading and the seed of its random phases.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Profile {
    /// The number the thesis and the specification call the profile by (for labels).
    pub number: i32,
    pub description: &'static str,
    pub sea: SeaState,
    /// Wave heading β (deg): from the bow to the direction the waves travel, toward starboard
    /// positive (180° head seas, 90° beam seas from port).
    pub heading: f64,
    pub seed: u64,
}

/// Profiles 1–3 (SPEC §8.2).
pub const PROFILES: [Profile; 3] = [
    Profile {
        number: 1,
        description: "sea state 4 (Hs 1.88 m, Tp 8.8 s), bow-quartering seas 45 deg off the port bow",
        sea: SeaState { hs: 1.88, tp: 8.8 },
        heading: 135.0,
        seed: 1,
    },
    Profile {
        number: 2,
        description: "sea state 5 (Hs 3.25 m, Tp 9.7 s), beam seas from port",
        sea: SeaState { hs: 3.25, tp: 9.7 },
        heading: 90.0,
        seed: 2,
    },
    Profile {
        number: 3,
        description: "sea state 5 (Hs 3.25 m, Tp 9.7 s), head seas",
        sea: SeaState { hs: 3.25, tp: 9.7 },
        heading: 180.0,
        seed: 3,
    },
];

/// One of the ship motion profiles 1–3.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize, Deserialize)]
pub enum ProfileId {
    /// Profile 1: sea state 4, bow-quartering seas.
    One,
    /// Profile 2: sea state 5, beam seas.
    Two,
    /// Profile 3: sea state 5, head seas.
    Three,
}

impl ProfileId {
    pub const ALL: [ProfileId; 3] = [ProfileId::One, ProfileId::Two, ProfileId::Three];

    /// The profile's sea state, heading and seed.
    pub fn profile(self) -> &'static Profile {
        match self {
            ProfileId::One => &PROFILES[0],
            ProfileId::Two => &PROFILES[1],
            ProfileId::Three => &PROFILES[2],
        }
    }
}

impl Profile {
    /// The full-scale motion of `hull` in this profile's sea, with the random phases of `seed`.
    pub fn full_scale(&self, hull: &Hull, seed: u64) -> HarmonicMotion {
        let waves = components(&self.sea, COMPONENTS, seed);
        HarmonicMotion::from_waves(hull, &waves, self.heading.to_radians())
    }
}

/// A test-scale profile.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TestScale {
    /// The test-scale motion (the full-scale harmonics with gains and offsets).
    pub motion: HarmonicMotion,
    /// The scale factor s on surge, sway and heave.
    pub scale: f64,
    /// The share of the actuator range used over the window (≤ [`MARGIN`] up to sampling).
    pub usage: f64,
}

/// `full` scaled by `factors` per degree of freedom and centred on the window mean `mean`.
fn transformed(full: &HarmonicMotion, factors: [f64; 6], mean: &[f64; 6]) -> HarmonicMotion {
    let mut m = full.clone();
    for j in 0..6 {
        m.gains[j] = factors[j] * full.gains[j];
        m.offsets[j] = factors[j] * (full.offsets[j] + mean[j]);
    }
    m
}

fn factors(scale: f64) -> [f64; 6] {
    let mut f = [1.0; 6];
    f[SURGE] = scale;
    f[SWAY] = scale;
    f[HEAVE] = scale;
    f[YAW] = 0.0;
    f
}

/// The share of the platform's range one `sample` (centred, translations at unit scale) uses with
/// translations scaled by `scale`, for the crane at the port side and at the stern.
fn sample_usage(geom: &PlatformGeometry, sample: &DeckMotion, scale: f64) -> Result<f64, PlatformError> {
    let mut m = *sample;
    for j in [SURGE, SWAY, HEAVE] {
        let a = m.dof[j];
        m.dof[j] = AxisMotion { pos: scale * a.pos, vel: scale * a.vel, acc: scale * a.acc };
    }
    let mut worst: f64 = 0.0;
    for location in [CraneLocation::Port, CraneLocation::Stern] {
        let p = location.resolve(&m);
        let pose = [0, 1, 2, 3, 4].map(|j| p.dof[j]);
        worst = worst.max(geom.usage(&exact_inverse_rates(geom, &pose)?));
    }
    Ok(worst)
}

/// Check-grid points (every [`CHECK_STEP`]) between two screening points: 0.1 s.
const SCREEN_STRIDE: usize = 10;
/// How far (as a share of the largest screened usage) below the largest screened usage an
/// interval between two screening points may start and still hold the largest usage of the
/// grid. Between two screening points h = 0.1 s apart each limit's share (a leg's stroke or
/// speed, linear in the platform's motion up to the chain's small nonlinearity) rises above the
/// larger of its two end values by at most |f''| h²/8 ≤ (ω h)²/8 of its peak (the error of linear
/// interpolation, with |f''| ≤ ω² max |f| for a signal of frequencies up to ω): 0.6 % for the
/// 3 ω_p = 2.2 rad/s the spectrum reaches ([`BAND`](super::spectrum::BAND)), 2.3 % if the chain
/// doubled it. The usage is the largest of these shares, so the same bound holds for it; 3 % is
/// five times the bound, and the test `screening_misses_no_sample` measures the real excess
/// (0.07 % of the peak for five new seeds, at the factor found and at zero).
const SCREEN_SLACK: f64 = 0.03;

/// The usage over the search or the check grid, evaluated where it can be largest only.
///
/// The usage is a maximum over samples, and at any scale only a few short stretches of the
/// window come close to it. So every [`SCREEN_STRIDE`]-th check-grid point is sampled once by
/// phasor rotation ([`uniform_samples`], the recurrence the platform steps with; within about
/// 1e-14 of the direct sum), and at each scale the usage of these screening points picks the intervals between them
/// within [`SCREEN_SLACK`] of the largest; only the grid points of those intervals are sampled
/// exactly, by [`HarmonicMotion::sample`] at the same times as [`samples`] and [`refined`] (each
/// once, kept for the next scale), and their largest usage is the result. It is the same
/// maximum, bit for bit, as over every grid point: the largest sample is among those evaluated
/// exactly (the screening points are grid points, and no interval left out can exceed the
/// screened maximum, see [`SCREEN_SLACK`]), and a maximum does not depend on which smaller values
/// it also saw. A kinematic error is only found at the points evaluated.
struct Screened<'a> {
    geom: &'a PlatformGeometry,
    unit: &'a HarmonicMotion,
    /// The screening points: every [`SCREEN_STRIDE`]-th check-grid point and the last one.
    points: Vec<usize>,
    /// The motion at the screening points, by phasor rotation.
    screen: Vec<DeckMotion>,
    /// The exact samples of the check grid computed so far (index m: t = m [`CHECK_STEP`]).
    exact: Vec<Option<DeckMotion>>,
}

/// The grids the search evaluates the usage on: every [`SEARCH_STEP`] or every [`CHECK_STEP`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Grid {
    Search,
    Check,
}

impl<'a> Screened<'a> {
    fn new(geom: &'a PlatformGeometry, unit: &'a HarmonicMotion) -> Screened<'a> {
        let last = (WINDOW / CHECK_STEP).round() as usize;
        let mut points: Vec<usize> = (0..=last).step_by(SCREEN_STRIDE).collect();
        if points.last() != Some(&last) {
            points.push(last);
        }
        // Every screening point but perhaps the last lies on the uniform grid of the stride.
        let stride = SCREEN_STRIDE as f64 * CHECK_STEP;
        let mut screen = uniform_samples(unit, stride, last / SCREEN_STRIDE);
        if screen.len() < points.len() {
            screen.push(unit.sample(last as f64 * CHECK_STEP));
        }
        Screened { geom, unit, points, screen, exact: vec![None; last + 1] }
    }

    /// The exact sample at check-grid point `m`: an even m is search-grid point m/2 and sampled at
    /// (m/2) [`SEARCH_STEP`], as [`samples`] does, an odd m at m [`CHECK_STEP`], as [`refined`].
    fn exact(&mut self, m: usize) -> DeckMotion {
        let unit = self.unit;
        *self.exact[m].get_or_insert_with(|| {
            let t = if m.is_multiple_of(2) { (m / 2) as f64 * SEARCH_STEP } else { m as f64 * CHECK_STEP };
            unit.sample(t)
        })
    }

    /// [`usage`] of the `grid`'s samples at `scale`, bit for bit.
    fn usage(&mut self, scale: f64, grid: Grid) -> Result<f64, PlatformError> {
        let screened =
            self.screen.iter().map(|s| sample_usage(self.geom, s, scale)).collect::<Result<Vec<f64>, _>>()?;
        let threshold = (1.0 - SCREEN_SLACK) * screened.iter().copied().fold(0.0, f64::max);
        let stride = if grid == Grid::Search { 2 } else { 1 };
        let mut worst: f64 = 0.0;
        for j in 0..self.points.len() - 1 {
            if screened[j].max(screened[j + 1]) < threshold {
                continue;
            }
            let (first, end) = (self.points[j], self.points[j + 1]);
            // The search grid is the even check-grid points.
            for m in (first + first % stride..=end).step_by(stride) {
                worst = worst.max(sample_usage(self.geom, &self.exact(m), scale)?);
            }
        }
        Ok(worst)
    }
}

/// A search result stored bit for bit: the fingerprint of its inputs ([`fingerprint`]) and the
/// `f64::to_bits` of the scale factor and of the usage it reached.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct KnownScale {
    pub fingerprint: u64,
    pub scale: u64,
    pub usage: u64,
}

/// [`search_test_scale`]'s results for profiles 1–3 (in order) with their own seeds, the default
/// hull and the default platform geometry; `known_scales_are_what_the_search_finds` recomputes
/// them.
pub const KNOWN_SCALES: [KnownScale; 3] = [
    // 0.07075311905295226, usage 0.95
    KnownScale { fingerprint: 0xc1c2b24db4660062, scale: 0x3fb21ce05c6c2402, usage: 0x3fee666666666666 },
    // 0.010402993084675134, usage 0.9500351553445774
    KnownScale { fingerprint: 0xbbd36bc45140f112, scale: 0x3f854e2a18a23064, usage: 0x3fee66b020482aec },
    // 0.060414657193261154, usage 0.9499999999999997
    KnownScale { fingerprint: 0xe440f0de17a4ecbd, scale: 0x3faeeeab81b02ee6, usage: 0x3fee666666666664 },
];

/// FNV-1a (64 bit) over the bits of every input the search depends on: the full-scale harmonics
/// (so the sea state, heading, seed, hull and the spectrum and RAO code), their gains and offsets,
/// the platform geometry and the search's constants. The crane locations it checks are fixed in
/// `usage`.
pub fn fingerprint(full: &HarmonicMotion, geom: &PlatformGeometry) -> u64 {
    let harmonics = full
        .harmonics
        .iter()
        .flat_map(|h| [h.omega, h.phase].into_iter().chain(h.amplitude.iter().flat_map(|c| [c.re, c.im])));
    let g = geom;
    let geometry = g.leg_angles.into_iter().chain([
        g.base_radius,
        g.deck_radius,
        g.joint_depth,
        g.pin_length,
        g.nominal,
        g.stroke,
        g.max_speed,
    ]);
    let constants = [WINDOW, MARGIN, SEARCH_STEP, CHECK_STEP];
    let words = std::iter::once(full.harmonics.len() as u64)
        .chain(harmonics.chain(full.gains).chain(full.offsets).chain(geometry).chain(constants).map(f64::to_bits));
    const OFFSET: u64 = 0xcbf2_9ce4_8422_2325;
    const PRIME: u64 = 0x0000_0100_0000_01b3;
    words.flat_map(u64::to_le_bytes).fold(OFFSET, |hash, byte| (hash ^ u64::from(byte)).wrapping_mul(PRIME))
}

/// The test-scale version of `full` (thesis §3.3): translations scaled by the largest factor that
/// keeps the platform within [`MARGIN`] of its limits over the window, angles unscaled, yaw zero,
/// every degree of freedom centred on its window mean. The factor comes from [`KNOWN_SCALES`] when
/// the inputs' fingerprint is there, else from [`search_test_scale`]; both give the same bits.
pub fn test_scale(full: &HarmonicMotion, geom: &PlatformGeometry) -> Result<TestScale, String> {
    let key = fingerprint(full, geom);
    let Some(known) = KNOWN_SCALES.iter().find(|k| k.fingerprint == key) else {
        return search_test_scale(full, geom);
    };
    let (scale, usage) = (f64::from_bits(known.scale), f64::from_bits(known.usage));
    let mean = full.window_mean(0.0, WINDOW);
    Ok(TestScale { motion: transformed(full, factors(scale), &mean), scale, usage })
}

/// [`test_scale`] by the search itself: bracket, then regula falsi on the usage over the window
/// sampled every `SEARCH_STEP`, then a check of the chosen factor every `CHECK_STEP`, each
/// usage evaluated where it can be largest only (`Screened`).
pub fn search_test_scale(full: &HarmonicMotion, geom: &PlatformGeometry) -> Result<TestScale, String> {
    let mean = full.window_mean(0.0, WINDOW);
    let unit = transformed(full, factors(1.0), &mean);
    let mut grid = Screened::new(geom, &unit);
    let (scale, usage) = find_scale(|s, g| grid.usage(s, g))?;
    Ok(TestScale { motion: transformed(full, factors(scale), &mean), scale, usage })
}

/// The largest scale factor whose usage on the search grid (`usage(s, Grid::Search)`) is at most
/// [`MARGIN`], and its usage on the check grid (`usage(s, Grid::Check)`).
fn find_scale(mut usage: impl FnMut(f64, Grid) -> Result<f64, PlatformError>) -> Result<(f64, f64), String> {
    let kinematics = |e: PlatformError| format!("test-scale conversion: {e}");
    let mut h = |s: f64| usage(s, Grid::Search).map(|u| u - MARGIN).map_err(kinematics);
    let angles_only = h(0.0)?;
    if angles_only >= 0.0 {
        return Err(format!(
            "the profile's roll and pitch alone use {:.0} % of the platform's range (limit {:.0} %)",
            100.0 * (angles_only + MARGIN),
            100.0 * MARGIN
        ));
    }
    // Bracket the root of h by doubling, then the Illinois variant of regula falsi. `lo` is
    // always feasible (h ≤ 0); `h_lo`/`h_hi` are the (possibly halved) end values it works with.
    let (mut lo, mut h_lo, mut lo_true): (f64, f64, f64) = (0.0, angles_only, angles_only);
    // First guess: the usage grows about linearly with the scale.
    let probe = 0.01;
    let h_probe = h(probe)?;
    let mut hi =
        if h_probe > 0.0 { probe } else { (probe * -angles_only / (h_probe - angles_only).max(1e-12)).min(1.0) };
    let mut h_hi = if hi == probe { h_probe } else { h(hi)? };
    if h_probe <= 0.0 && hi != probe {
        (lo, h_lo, lo_true) = (probe, h_probe, h_probe);
    }
    while h_hi <= 0.0 {
        if hi >= 1.0 {
            return Err("the full-scale motion already fits the platform: no test scale below 1 is needed".into());
        }
        (lo, h_lo, lo_true) = (hi, h_hi, h_hi);
        hi = (1.5 * hi).min(1.0);
        h_hi = h(hi)?;
    }
    let mut last_side = 0;
    for _ in 0..100 {
        if lo_true > -1e-6 || hi - lo < 1e-12 * hi {
            break;
        }
        let s = (lo * h_hi - hi * h_lo) / (h_hi - h_lo);
        let h_s = h(s)?;
        if h_s <= 0.0 {
            (lo, h_lo, lo_true) = (s, h_s, h_s);
            if last_side == -1 {
                h_hi /= 2.0;
            }
            last_side = -1;
        } else {
            (hi, h_hi) = (s, h_s);
            if last_side == 1 {
                h_lo /= 2.0;
            }
            last_side = 1;
        }
    }
    let scale = lo;
    let used = usage(scale, Grid::Check).map_err(kinematics)?;
    if used > 1.0 {
        return Err(format!("test-scale conversion: the platform would use {:.1} % of its range", 100.0 * used));
    }
    Ok((scale, used))
}

#[cfg(test)]
mod tests;
