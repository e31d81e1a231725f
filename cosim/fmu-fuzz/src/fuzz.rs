//! Seeded random FMI call sequences over one FMU library, through its FMI 2.0 entry points
//! (`fmi2`) or its FMI 3.0 ones (`fmi3`). Each sequence starts from nothing, makes up to
//! [`CALLS_PER_SEQUENCE`] calls on up to two instances (any function in any order, arguments
//! good or bad), then frees what is left, leaving some FMU states to the instance's free. A
//! violation is returned with its seed and the calls that led to it.
//!
//! Checked after every call, in both versions (`Common::check`): no `Fatal` status (every
//! panic becomes one, so this also means no panic), a status that is one of the five, `OK`
//! never with a non-finite Real / Float64, a call that is bad by construction (null instance or
//! array, unknown value reference, non-finite value, non-positive or non-finite step,
//! inconsistent experiment, unsupported function, the other version's API) never accepted, and
//! bytes an FMU serialized always accepted back. FMI 3.0 adds the state table
//! ([`crate::table`]): a call its state does not allow must be refused, a call it allows in
//! every state the instance may be in and whose arguments give no reason to refuse must be
//! accepted, and every accepted call takes the table's transition. Hangs are the caller's to
//! catch (see `progress`).

mod fmi2;
mod fmi3;

pub use crate::fmu::Api;
use crate::fmu::Fmu;
use crate::rng::Rng;
use std::collections::VecDeque;
use std::ffi::{c_int, CStr};
use std::ptr::null;
use std::sync::atomic::{AtomicU64, Ordering};
use std::time::{Duration, Instant};

/// Calls per sequence (at most).
pub const CALLS_PER_SEQUENCE: usize = 40;

/// What a run tried and saw.
#[derive(Debug, Default, Clone)]
pub struct Figures {
    pub sequences: u64,
    pub calls: u64,
    /// Calls answered with Error or Discard (or a null instance).
    pub refused: u64,
    /// Calls bad by construction, all of them refused.
    pub bad_calls: u64,
    /// FMI 3.0: calls the state table does not allow in any state the instance may be in, all
    /// of them refused.
    pub forbidden: u64,
    /// FMI 3.0: calls accepted after an fmi3Error that the strict reading of the standard
    /// (§2.3.1: the instance is in Terminated after fmi3Error) would have refused; see
    /// [`crate::table`].
    pub lenient: u64,
    /// Calls of the other version's API on an instance, all of them refused.
    pub cross_version: u64,
    /// Steps the FMU took (`DoStep` answered with OK).
    pub steps: u64,
    /// States the FMU saved but could not serialize (it accepted a value, such as an infinite
    /// stopTime, that its state image cannot hold); should be 0.
    pub unserializable: u64,
    /// The message of the first such refusal, with the seed.
    pub unserializable_example: String,
    pub slowest_call: Duration,
    pub slowest: String,
}

impl Figures {
    /// Adds the figures of the sequence with seed `seed`.
    fn add(&mut self, sequence: &Figures, seed: u64) {
        self.sequences += 1;
        self.calls += sequence.calls;
        self.refused += sequence.refused;
        self.bad_calls += sequence.bad_calls;
        self.forbidden += sequence.forbidden;
        self.lenient += sequence.lenient;
        self.cross_version += sequence.cross_version;
        self.steps += sequence.steps;
        if sequence.unserializable > 0 && self.unserializable == 0 {
            self.unserializable_example = format!("{} (seed {seed})", sequence.unserializable_example);
        }
        self.unserializable += sequence.unserializable;
        if sequence.slowest_call > self.slowest_call {
            self.slowest_call = sequence.slowest_call;
            self.slowest = format!("{} (seed {seed})", sequence.slowest);
        }
    }
}

/// Runs `sequences` sequences of `api` calls with seeds `seed`, `seed + 1`, ...; `progress`
/// counts calls (a watchdog that sees it stand still has found a hang).
pub fn run(fmu: &Fmu, api: Api, sequences: u64, seed: u64, progress: &AtomicU64) -> Result<Figures, String> {
    match api {
        Api::Fmi2 => run_sequences::<fmi2::Sequence>(fmu, sequences, seed, progress),
        Api::Fmi3 => run_sequences::<fmi3::Sequence>(fmu, sequences, seed, progress),
    }
}

/// One sequence of calls through one version's API.
trait Sequence<'a> {
    fn start(fmu: &'a Fmu, seed: u64, progress: &'a AtomicU64) -> Self;
    fn common(&self) -> &Common<'a>;
    fn common_mut(&mut self) -> &mut Common<'a>;
    /// What the library must say of itself before any instance exists (FMI 3.0: its version).
    fn check_version(&self) -> Result<(), String> {
        Ok(())
    }
    /// Instantiates and drives the new instance to step mode, as a host begins.
    fn begin_as_host(&mut self) -> Result<(), String>;
    /// One call of any function of the API (or of the other version's), arguments good or bad.
    fn one_call(&mut self) -> Result<(), String>;

    /// The calls of the sequence, in both versions alike.
    fn run(&mut self) -> Result<(), String> {
        self.check_version()?;
        // Most sequences begin as a host does, with an instance in step mode.
        if self.common_mut().rng.chance(0.7) {
            self.begin_as_host()?;
        }
        let calls = 1 + self.common_mut().rng.below(CALLS_PER_SEQUENCE);
        for _ in 0..calls {
            self.one_call()?;
        }
        Ok(())
    }
    /// Frees what the sequence holds: most states explicitly, the rest with their instances.
    fn finish(&mut self);
    /// No logger received a fatal message (a panic in the free of an instance, which returns
    /// no status, would show only there).
    fn check_logs(&self) -> Result<(), String>;
}

fn run_sequences<'a, S: Sequence<'a>>(
    fmu: &'a Fmu,
    sequences: u64,
    seed: u64,
    progress: &'a AtomicU64,
) -> Result<Figures, String> {
    let mut figures = Figures::default();
    for s in 0..sequences {
        let mut sequence = S::start(fmu, seed + s, progress);
        let result = sequence.run();
        sequence.finish();
        let result = result.and_then(|()| sequence.check_logs());
        let common = sequence.common();
        figures.add(&common.figures, seed + s);
        result.map_err(|e| {
            format!("{} ({}), seed {}: {e}\nlast calls:\n  {}", fmu.model, common.api.name(), seed + s, common.trace())
        })?;
    }
    Ok(figures)
}

/// Status values, the same in both versions.
const OK: c_int = 0;
const WARNING: c_int = 1;
const ERROR: c_int = 3;
const FATAL: c_int = 4;
const _: () = assert!(
    fmi2_sys::fmi2OK == OK
        && fmi3_sys::fmi3OK == OK
        && fmi2_sys::fmi2Warning == WARNING
        && fmi3_sys::fmi3Warning == WARNING
        && fmi2_sys::fmi2Discard == fmi3_sys::fmi3Discard
        && fmi2_sys::fmi2Error == ERROR
        && fmi3_sys::fmi3Error == ERROR
        && fmi2_sys::fmi2Fatal == FATAL
        && fmi3_sys::fmi3Fatal == FATAL
);

const SPECIAL_REALS: [f64; 18] = [
    0.0,
    -0.0,
    1.0,
    -1.0,
    0.5,
    1e-4,
    0.01,
    2.0,
    10.0,
    1e3,
    1e300,
    -1e300,
    f64::MAX,
    5e-324,
    f64::NAN,
    f64::INFINITY,
    f64::NEG_INFINITY,
    -2.5,
];
const STEP_SIZES: [f64; 5] = [0.001, 0.01, 0.01, 0.02, 0.1];
const ODD_STEP_SIZES: [f64; 11] =
    [0.0, -0.01, f64::NAN, f64::INFINITY, f64::NEG_INFINITY, 1e300, 1e9, f64::MAX, 5e-324, 2000.0, 10.0];
const START_TIMES: [f64; 10] = [0.0, 0.0, 1.0, -5.0, 1e6, 1e15, 1e300, -1e300, f64::NAN, f64::INFINITY];
const STRINGS: [&CStr; 5] = [c"", c"abc", c"/nonexistent/profile.csv", c"%s%n%x", c"\xc3\xa9t\xc3\xa9"];
const CATEGORIES: [&CStr; 4] = [c"logCalls", c"logStatusError", c"logStatusWarning", c"bogus"];

/// What the sequences of both versions share: the FMU, the random stream, the figures, the
/// recent calls, the serialized images, and the checks and argument makers that do not depend
/// on the version.
struct Common<'a> {
    fmu: &'a Fmu,
    api: Api,
    rng: Rng,
    progress: &'a AtomicU64,
    /// Bytes of serialized states, the seeds of the garbage.
    images: Vec<Vec<u8>>,
    figures: Figures,
    recent: VecDeque<String>,
}

impl<'a> Common<'a> {
    fn new(fmu: &'a Fmu, api: Api, seed: u64, progress: &'a AtomicU64) -> Self {
        Common {
            fmu,
            api,
            rng: Rng::seeded(seed),
            progress,
            images: Vec::new(),
            figures: Figures::default(),
            recent: VecDeque::new(),
        }
    }

    /// Records a call's outcome and checks the rules every call obeys. An FMI 3.0 call that is
    /// bad by construction must answer fmi3Error itself (FMI 3.0 §2.2.3: illegal arguments and
    /// calls not allowed in the current state return fmi3Error).
    fn check(&mut self, what: String, bad: bool, status: c_int, started: Instant) -> Result<(), String> {
        let took = started.elapsed();
        self.progress.fetch_add(1, Ordering::Relaxed);
        self.figures.calls += 1;
        if took > self.figures.slowest_call {
            self.figures.slowest_call = took;
            self.figures.slowest = what.clone();
        }
        self.recent.push_back(format!("{what} -> {status}"));
        if self.recent.len() > 30 {
            self.recent.pop_front();
        }
        let prefix = self.api.prefix();
        if !(OK..=FATAL).contains(&status) {
            return Err(format!("status {status} is not an {prefix}Status"));
        }
        if status == FATAL {
            return Err(format!("{prefix}Fatal: a panic or an unrecoverable error"));
        }
        if status != OK && status != WARNING {
            self.figures.refused += 1;
        }
        if bad {
            self.figures.bad_calls += 1;
            if status == OK || status == WARNING {
                return Err("a bad call was accepted".into());
            }
            if self.api == Api::Fmi3 && status != ERROR {
                return Err(format!("a bad call returned {status}, not fmi3Error"));
            }
        }
        Ok(())
    }

    fn trace(&self) -> String {
        self.recent.iter().cloned().collect::<Vec<_>>().join("\n  ")
    }

    /// Value references of one type: mostly `known` ones, some of `others` (other types) or
    /// random; and whether one of them is unknown for this type.
    fn references(&mut self, known: &[u32], others: &[u32]) -> (Vec<u32>, bool) {
        let n = self.rng.below(5);
        let only_known = !known.is_empty() && self.rng.chance(0.75);
        let vrs: Vec<u32> = (0..n)
            .map(|_| match if only_known { 9 } else { self.rng.below(10) } {
                0 if !others.is_empty() => self.rng.pick(others),
                0 | 1 => self.rng.u32(),
                _ if !known.is_empty() => self.rng.pick(known),
                _ => self.rng.u32(),
            })
            .collect();
        let unknown = vrs.iter().any(|vr| !known.contains(vr));
        (vrs, unknown)
    }

    /// A pointer to `values`, or sometimes NULL (bad when elements were announced).
    fn array<T>(&mut self, values: &[T]) -> (*const T, bool) {
        if self.rng.chance(0.05) {
            (null(), !values.is_empty())
        } else {
            (values.as_ptr(), false)
        }
    }

    fn real(&mut self) -> f64 {
        if self.rng.chance(0.7) {
            4.0 * self.rng.unit() - 2.0
        } else {
            self.rng.pick(&SPECIAL_REALS)
        }
    }

    /// A step size: mostly a usual one, some random in (0, 1), some odd.
    fn step_size(&mut self) -> f64 {
        match self.rng.below(20) {
            0..=14 => self.rng.pick(&STEP_SIZES),
            15..=16 => self.rng.unit(),
            _ => self.rng.pick(&ODD_STEP_SIZES),
        }
    }

    /// Keeps the bytes of a serialized state as a seed of the garbage.
    fn keep_image(&mut self, image: Vec<u8>) {
        if self.images.len() < 4 {
            self.images.push(image);
        }
    }

    /// Counts a refusal of the serialized size of a live state, for a live instance, whose
    /// reason (the message the FMU logged) is the state itself, not the call sequence.
    fn count_unserializable(&mut self, message: String) {
        if message.contains("cannot be serialized") {
            self.figures.unserializable += 1;
            if self.figures.unserializable_example.is_empty() {
                self.figures.unserializable_example = message;
            }
        }
    }

    /// Garbage derived from the serialized images: bytes flipped, truncated, random or zero.
    fn garbage(&mut self) -> Vec<u8> {
        let Some(image) = (!self.images.is_empty()).then(|| self.images[self.rng.below(self.images.len())].clone())
        else {
            let n = self.rng.below(64);
            return self.rng.bytes(n);
        };
        match self.rng.below(5) {
            0 => {
                let mut out = image;
                for _ in 0..1 + self.rng.below(4) {
                    let i = self.rng.below(out.len());
                    out[i] ^= 1 << self.rng.below(8);
                }
                out
            }
            1 => {
                let mut out = image;
                let i = self.rng.below(out.len());
                out[i] = self.rng.pick(&[0x00, 0xff, 0x7f, 0x80]);
                out
            }
            2 => image[..self.rng.below(image.len())].to_vec(),
            3 => self.rng.bytes(image.len()),
            _ => vec![0; image.len()],
        }
    }
}
