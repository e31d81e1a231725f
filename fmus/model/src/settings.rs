//! The rows of settings that several models share, one place each so that their names, units,
//! ranges and start values cannot drift apart: a sampled model's period
//! ([`sample_period!`](crate::sample_period)) and a noisy sensor model's switch and seed
//! ([`noise_parameters!`](crate::noise_parameters)). Like [`ship_inputs!`](crate::ship_inputs),
//! they are built with the caller's `Real`, `Integer` and `Boolean` aliases.

/// The parameter row `sample_period` (s) of a sampled model's [`SampleClock`](crate::SampleClock), named after
/// `m =>`, at value reference `vr`: it starts at [`SampleClock::DEFAULT_PERIOD`](crate::SampleClock::DEFAULT_PERIOD) and is bounded to
/// 0.1 ms..1 s, the same for every sampled controller; the description is the caller's. Built
/// with the caller's `Real` (its `type Real = fmu_model::Real<Model>` alias), as [`field!`](crate::field).
///
/// ```text
/// fmu_model::sample_period!(2, m => m.clock, doc: "Sample period of the control software"),
/// ```
#[macro_export]
macro_rules! sample_period {
    ($vr:expr, $m:ident => $clock:expr, doc: $doc:expr $(,)?) => {
        $crate::field!(Real::parameter($vr, "sample_period"), unit: "s", start: $crate::SampleClock::DEFAULT_PERIOD,
            range: (1e-4, 1.0), doc: $doc, field: $m => $clock.period)
    };
}

/// The two parameter rows of a model's sensor noise, value references `vr` and `vr + 1`: `noise`
/// (Boolean, whether the readings get their random noise) and `seed` (Integer, `0..=i32::MAX`, the
/// seed of that noise, which the model keeps as a `u64`). The model names both places and their
/// start values, and describes both rows (`noise:` and `seed:`).
///
/// ```text
/// &noise_parameters!(13, m => m.noise, m.seed, start: (NOISE, SEED),
///     noise: "Add Gaussian noise to the readings",
///     seed: "Noise seed; give every noisy instance its own"),
/// ```
#[macro_export]
macro_rules! noise_parameters {
    ($vr:expr, $m:ident => $noise:expr, $seed:expr, start: ($noise_start:expr, $seed_start:expr),
        noise: $noise_doc:expr, seed: $seed_doc:expr $(,)?
    ) => {
        [
            $crate::field!(Boolean::parameter($vr, "noise"), start: $noise_start, doc: $noise_doc,
                field: $m => $noise),
            Integer::parameter($vr + 1, "seed")
                .start($seed_start)
                .range(0, i32::MAX)
                .doc($seed_doc)
                .get(|$m| $seed as i32)
                .set(|$m, v| $seed = v as u64),
        ]
    };
}
