//! Value reference -> what a call needs of the variable, without hashing: `fmi2Get*`/`fmi2Set*`
//! resolve every element of every call here, so this is the exporter's hottest path.
//!
//! Each FMI type has its own value-reference space (Real 0 and Integer 0 are different
//! variables), hence one index per type, built once per instance from the model's table. Reals,
//! which an importer exchanges every step, additionally get a [`RealSlot`] per value reference: the
//! accessors, range and settable states, so a vector call touches one compact slot per element
//! and never the table itself.

use crate::state::{self, Mask, State};
use crate::variables::{Causality, Value, ValueType, Variability, Variable};

/// What an index holds per value reference; a dense index fills the value references no variable
/// has with [`Slot::absent`], so that a lookup tests no `Option` (and an absent Real slot refuses
/// every value by itself, see [`VrIndex::first_refused_by`]).
pub trait Slot {
    fn absent() -> Self;
    fn present(&self) -> bool;
}

/// Table rows: no table has `u32::MAX` rows (see `row_u32`).
impl Slot for u32 {
    fn absent() -> u32 {
        u32::MAX
    }

    #[inline]
    fn present(&self) -> bool {
        *self != u32::MAX
    }
}

/// Values of one FMI type, by value reference.
#[derive(Debug)]
pub enum VrIndex<T> {
    /// `slots[vr]` is the value of `vr`, or [`Slot::absent`]: one bounds check and one load.
    Dense(Box<[T]>),
    /// `(vr, value)` sorted by vr, searched by bisection: for value references too sparse for a
    /// dense array of reasonable size.
    Sorted(Box<[(u32, T)]>),
}

impl<T: Slot> VrIndex<T> {
    /// A dense array may hold this many slots per variable (plus [`Self::DENSE_SLACK`]) before the
    /// index falls back to the sorted table, so its memory stays a small multiple of the table's.
    const DENSE_SLOTS_PER_VARIABLE: usize = 4;
    /// The slack lets the usual numbering, a few variables per block of a hundred or so value
    /// references (parameters from 0, outputs from 200, ...), stay dense: a bisection costs tens
    /// of instructions per element, and the slack at most 1024 slots (64 KiB of Real slots).
    const DENSE_SLACK: usize = 1024;

    /// The index of `(vr, value)` pairs. If a value reference occurs twice (a table that
    /// [`crate::variables::check_table`] would refuse), the later value wins.
    pub fn new(pairs: impl IntoIterator<Item = (u32, T)>) -> VrIndex<T> {
        let pairs: Vec<(u32, T)> = pairs.into_iter().collect();
        let span = pairs.iter().map(|(vr, _)| *vr as usize + 1).max().unwrap_or(0);
        if span <= Self::DENSE_SLOTS_PER_VARIABLE * pairs.len() + Self::DENSE_SLACK {
            let mut slots: Vec<T> = std::iter::repeat_with(T::absent).take(span).collect();
            for (vr, value) in pairs {
                slots[vr as usize] = value;
            }
            VrIndex::Dense(slots.into_boxed_slice())
        } else {
            // Reversed then stably sorted, so the first of equal vrs is the later value.
            let mut sorted: Vec<(u32, T)> = pairs.into_iter().rev().collect();
            sorted.sort_by_key(|(vr, _)| *vr);
            sorted.dedup_by_key(|(vr, _)| *vr);
            VrIndex::Sorted(sorted.into_boxed_slice())
        }
    }

    /// The value of `vr`, if a variable of this type has it.
    #[inline]
    pub fn get(&self, vr: u32) -> Option<&T> {
        match self {
            VrIndex::Dense(slots) => dense(slots, vr),
            VrIndex::Sorted(pairs) => sorted(pairs, vr),
        }
    }

    /// The position of the first element whose value reference is unknown or that `accept`
    /// refuses; `accept` sees the values of the elements before it, in order. The dense/sorted
    /// choice is made once per call, not per element, so the array stays in registers across the
    /// model calls `accept` may make.
    #[inline]
    pub fn first_refused<E>(
        &self,
        elements: impl Iterator<Item = (u32, E)>,
        mut accept: impl FnMut(&T, E) -> bool,
    ) -> Option<usize> {
        // The filler of a dense index is refused here; a sorted index holds no filler.
        self.first_refused_by(elements, |t, e| t.present() && accept(t, e))
    }

    /// As [`Self::first_refused`] for an `accept` that refuses [`Slot::absent`] values by itself
    /// (a Real slot that is settable in no state): the dense form then tests no presence.
    #[inline]
    pub fn first_refused_by<E>(
        &self,
        mut elements: impl Iterator<Item = (u32, E)>,
        mut accept: impl FnMut(&T, E) -> bool,
    ) -> Option<usize> {
        match self {
            VrIndex::Dense(slots) => elements.position(|(vr, e)| !slots.get(vr as usize).is_some_and(|t| accept(t, e))),
            VrIndex::Sorted(pairs) => elements.position(|(vr, e)| !sorted(pairs, vr).is_some_and(|t| accept(t, e))),
        }
    }

    /// Runs `f` on each element, in order, up to the first value reference out of the index's
    /// range, for elements that [`Self::first_refused_by`] accepted: the dense form tests no
    /// presence, so `f` must do nothing harmful with an absent value.
    #[inline]
    pub fn for_each_accepted<E>(&self, elements: impl Iterator<Item = (u32, E)>, mut f: impl FnMut(&T, E)) {
        self.first_refused_by(elements, |t, e| {
            f(t, e);
            true
        });
    }
}

#[inline]
fn dense<T: Slot>(slots: &[T], vr: u32) -> Option<&T> {
    slots.get(vr as usize).filter(|t| t.present())
}

#[inline]
fn sorted<T>(pairs: &[(u32, T)], vr: u32) -> Option<&T> {
    pairs.binary_search_by_key(&vr, |(v, _)| *v).ok().map(|i| &pairs[i].1)
}

/// The states in which a host may set a variable (FMI 2.0 §3.2.3 / §4.2.4); `None` for variables
/// that can never be set (outputs, constants, calculated parameters, locals).
pub fn settable_in<M>(v: &Variable<M>) -> Option<Mask> {
    match (v.causality, v.variability) {
        (Causality::Input, _) | (Causality::Parameter, Variability::Tunable) => Some(state::SET_INPUTS),
        (Causality::Parameter, Variability::Fixed) => Some(state::SET_BEFORE_STEPPING),
        _ => None,
    }
}

/// What `fmi2GetReal`, `fmi2SetReal` and `fmi2SetRealInputDerivatives` need of one Real variable,
/// copied out of its table row so that a check is a few compares and an apply a direct call.
/// Aligned to 64 bytes (a cache line): a dense index then finds a slot with one shift.
#[repr(align(64))]
pub struct RealSlot<M: 'static> {
    pub get: fn(&M) -> f64,
    /// The setter; a variable without one has a no-op here (and an empty `settable`, as
    /// `check_table` requires of the tables), so applying an accepted value needs no test.
    pub set: fn(&mut M, f64),
    pub derivative: Option<fn(&mut M, Option<f64>)>,
    /// The finite values `fmi2SetReal` accepts: the declared range clamped to the finite numbers
    /// (`-f64::MAX` / `f64::MAX` where a bound is absent or NaN), so that one pair of comparisons
    /// refuses out-of-range values, infinities and NaN alike.
    lowest: f64,
    highest: f64,
    /// The states in which the variable may be set (empty if it never may, and for an absent
    /// value reference).
    settable: Mask,
    /// False only in the filler of value references that no Real variable has.
    present: bool,
}

impl<M> Slot for RealSlot<M> {
    /// Settable in no state, so every set and derivative refuses it; never read.
    fn absent() -> RealSlot<M> {
        RealSlot {
            get: |_| f64::NAN,
            set: |_, _| (),
            derivative: None,
            lowest: f64::MAX,
            highest: f64::MIN,
            settable: Mask::NONE,
            present: false,
        }
    }

    #[inline]
    fn present(&self) -> bool {
        self.present
    }
}

impl<M> RealSlot<M> {
    fn new(v: &Variable<M>) -> Option<RealSlot<M>> {
        let Value::Real { get, set, derivative, min, max, .. } = v.value else { return None };
        Some(RealSlot {
            get,
            set: set.unwrap_or(|_, _| ()),
            derivative,
            // `f64::max`/`min` return the other operand for a NaN bound: it refuses nothing, as in
            // the descriptive check.
            lowest: min.map_or(f64::MIN, |m| m.max(f64::MIN)),
            highest: max.map_or(f64::MAX, |m| m.min(f64::MAX)),
            settable: settable_in(v).unwrap_or(Mask::NONE),
            present: true,
        })
    }

    /// Whether `fmi2SetReal` may set `value` in `state`: settable now, finite and within range.
    /// A NaN value fails both comparisons; an infinite one lies outside the finite range.
    #[inline]
    pub fn accepts(&self, state: State, value: f64) -> bool {
        self.settable.allows(state) && value >= self.lowest && value <= self.highest
    }

    /// Whether `fmi2SetRealInputDerivatives` may store `value` as derivative of order `order`.
    #[inline]
    pub fn accepts_derivative(&self, state: State, order: i32, value: f64) -> bool {
        self.settable.allows(state) && order == 1 && value.is_finite() && self.derivative.is_some()
    }
}

/// The indexes of a model's table: table rows of every type (for messages and the rarely used
/// non-Real calls) and the [`RealSlot`]s.
pub struct Lookup<M: 'static> {
    rows: [VrIndex<u32>; 4],
    reals: VrIndex<RealSlot<M>>,
    /// Whether some Real takes a derivative: if none does, `fmi2SetReal` has none to clear.
    derivatives: bool,
}

impl<M> Lookup<M> {
    pub fn new(table: &[Variable<M>]) -> Lookup<M> {
        let index = |ty: ValueType| {
            VrIndex::new(
                table.iter().enumerate().filter(|(_, v)| v.value_type() == ty).map(|(row, v)| (v.vr, row_u32(row))),
            )
        };
        Lookup {
            rows: ValueType::ALL.map(index),
            reals: VrIndex::new(table.iter().filter_map(|v| Some((v.vr, RealSlot::new(v)?)))),
            derivatives: table.iter().any(|v| matches!(v.value, Value::Real { derivative: Some(_), .. })),
        }
    }

    /// The table row of the `ty` variable `vr`.
    #[inline]
    pub fn row(&self, ty: ValueType, vr: u32) -> Option<usize> {
        self.rows[ty as usize].get(vr).map(|row| *row as usize)
    }

    /// The slots of the Real variables.
    #[inline]
    pub fn reals(&self) -> &VrIndex<RealSlot<M>> {
        &self.reals
    }

    /// Whether some Real variable takes a derivative (an interpolated input).
    #[inline]
    pub fn has_derivatives(&self) -> bool {
        self.derivatives
    }
}

/// Table rows are `u32` so a dense index stays compact; no model has 4 billion variables.
fn row_u32(row: usize) -> u32 {
    u32::try_from(row).expect("a variable table has fewer than 2^32 rows")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every vr of 0..=limit through `index`, as (vr, value) for the known ones.
    fn resolved(index: &VrIndex<u32>, limit: u32) -> Vec<(u32, u32)> {
        (0..=limit).filter_map(|vr| index.get(vr).map(|row| (vr, *row))).collect()
    }

    #[test]
    fn compact_value_references_get_a_dense_index() {
        let index = VrIndex::new([(3, 0), (0, 1), (7, 2)]);
        assert!(matches!(&index, VrIndex::Dense(slots) if slots.len() == 8), "{index:?}");
        assert_eq!(resolved(&index, 100), [(0, 1), (3, 0), (7, 2)]);
        assert_eq!(index.get(u32::MAX), None);
    }

    /// The FMUs number parameters from 0 and outputs in blocks from 200 on; with 32 Reals up to
    /// vr 234 (the platform's) a bisection per element would cost more than the whole rest of a
    /// get.
    #[test]
    fn blocks_of_value_references_a_hundred_apart_get_a_dense_index() {
        let vrs = (0..5).chain(200..227);
        let index = VrIndex::new(vrs.clone().zip(0..));
        assert!(matches!(&index, VrIndex::Dense(slots) if slots.len() == 227), "{index:?}");
        assert_eq!(resolved(&index, 300), vrs.zip(0..).collect::<Vec<_>>());
    }

    #[test]
    fn sparse_value_references_get_a_sorted_index() {
        let index = VrIndex::new([(1_000_000, 0), (5, 1), (70_000, 2), (u32::MAX, 3)]);
        assert!(matches!(index, VrIndex::Sorted(_)), "{index:?}");
        assert_eq!(resolved(&index, 1_000_001), [(5, 1), (70_000, 2), (1_000_000, 0)]);
        assert_eq!(index.get(u32::MAX), Some(&3));
        assert_eq!(index.get(u32::MAX - 1), None);
        assert_eq!(index.get(4), None);
    }

    #[test]
    fn a_repeated_value_reference_resolves_to_the_later_value_in_both_forms() {
        assert_eq!(VrIndex::new([(2, 0), (2, 1)]).get(2), Some(&1));
        let sparse = VrIndex::new([(1 << 20, 0), (9, 1), (1 << 20, 2)]);
        assert!(matches!(sparse, VrIndex::Sorted(_)));
        assert_eq!(sparse.get(1 << 20), Some(&2));
    }

    /// A Real input at value references 0 and 2 (with a derivative), nothing at 1.
    fn input(vr: u32) -> Variable<f64> {
        Variable {
            vr,
            name: "u",
            description: "",
            causality: Causality::Input,
            variability: Variability::Continuous,
            value: Value::Real {
                unit: "1",
                start: 0.0,
                min: None,
                max: None,
                get: |m| *m,
                set: Some(|m, v| *m = v),
                derivative: Some(|_, _| ()),
            },
        }
    }

    /// The filler of a value reference inside a dense index's span is refused by the checks of
    /// every Real call, in every state, although they test no presence.
    #[test]
    fn a_gap_in_a_dense_real_index_is_refused_by_every_check() {
        let lookup = Lookup::new(&[input(0), input(2)]);
        let reals = lookup.reals();
        assert!(matches!(reals, VrIndex::Dense(slots) if slots.len() == 3));
        for state in State::ALL {
            let set = reals.first_refused_by([(0, 1.0), (1, 1.0)].into_iter(), |r, v| r.accepts(state, v));
            assert_eq!(set, Some(if state::SET_INPUTS.allows(state) { 1 } else { 0 }), "{state:?}");
            let derivative = |r: &RealSlot<f64>, v| r.accepts_derivative(state, 1, v);
            let derivatives = reals.first_refused_by([(2, 1.0), (1, 1.0)].into_iter(), derivative);
            assert_eq!(derivatives, Some(if state::SET_INPUTS.allows(state) { 1 } else { 0 }), "{state:?}");
        }
        assert_eq!(reals.first_refused([(2, ()), (1, ())].into_iter(), |_, _| true), Some(1));
        assert!(reals.get(1).is_none() && reals.get(2).is_some());
    }

    #[test]
    fn an_empty_type_knows_no_value_reference() {
        let index = VrIndex::<u32>::new([]);
        assert_eq!(index.get(0), None);
    }
}
