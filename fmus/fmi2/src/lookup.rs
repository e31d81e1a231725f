//! Value reference -> row of the variable table, without hashing: `fmi2Get*`/`fmi2Set*` resolve
//! every element of every call here, so this is the exporter's hottest path.
//!
//! Each FMI type has its own value-reference space (Real 0 and Integer 0 are different
//! variables), hence one index per type, built once per instance from the model's table.

use crate::variables::{ValueType, Variable};

/// Rows of one FMI type, by value reference.
#[derive(Debug)]
pub enum VrIndex {
    /// `rows[vr]` is the row of `vr`, or [`VrIndex::UNKNOWN`]: one bounds check and one load.
    Dense(Box<[u32]>),
    /// `(vr, row)` sorted by vr, searched by bisection: for value references too sparse for a
    /// dense array of reasonable size.
    Sorted(Box<[(u32, u32)]>),
}

impl VrIndex {
    /// Marks a value reference below the dense array's length that names no variable.
    const UNKNOWN: u32 = u32::MAX;

    /// A dense array may hold this many slots per variable (plus [`Self::DENSE_SLACK`]) before the
    /// index falls back to the sorted table, so its memory stays a small multiple of the table's.
    const DENSE_SLOTS_PER_VARIABLE: usize = 4;
    const DENSE_SLACK: usize = 64;

    /// The index of `(vr, row)` pairs. If a value reference occurs twice (a table that
    /// [`crate::variables::check_table`] would refuse), the later row wins.
    pub fn new(pairs: impl IntoIterator<Item = (u32, usize)>) -> VrIndex {
        let pairs: Vec<(u32, u32)> = pairs.into_iter().map(|(vr, row)| (vr, row_u32(row))).collect();
        let span = pairs.iter().map(|(vr, _)| *vr as usize + 1).max().unwrap_or(0);
        if span <= Self::DENSE_SLOTS_PER_VARIABLE * pairs.len() + Self::DENSE_SLACK {
            let mut rows = vec![Self::UNKNOWN; span];
            for (vr, row) in pairs {
                rows[vr as usize] = row;
            }
            VrIndex::Dense(rows.into_boxed_slice())
        } else {
            // Reversed then stably sorted, so the first of equal vrs is the later row.
            let mut sorted: Vec<(u32, u32)> = pairs.into_iter().rev().collect();
            sorted.sort_by_key(|(vr, _)| *vr);
            sorted.dedup_by_key(|(vr, _)| *vr);
            VrIndex::Sorted(sorted.into_boxed_slice())
        }
    }

    /// The table row of `vr`, if a variable of this type has it.
    #[inline]
    pub fn row(&self, vr: u32) -> Option<usize> {
        match self {
            VrIndex::Dense(rows) => match rows.get(vr as usize) {
                Some(&row) if row != Self::UNKNOWN => Some(row as usize),
                _ => None,
            },
            VrIndex::Sorted(pairs) => pairs.binary_search_by_key(&vr, |(v, _)| *v).ok().map(|i| pairs[i].1 as usize),
        }
    }
}

/// Table rows are `u32` so a dense index stays compact; no model has 4 billion variables.
fn row_u32(row: usize) -> u32 {
    u32::try_from(row).ok().filter(|r| *r != VrIndex::UNKNOWN).expect("a variable table has fewer than 2^32 - 1 rows")
}

/// One [`VrIndex`] per FMI type over a model's table.
#[derive(Debug)]
pub struct Lookup {
    by_type: [VrIndex; 4],
}

impl Lookup {
    pub fn new<M>(table: &[Variable<M>]) -> Lookup {
        let index = |ty: ValueType| {
            VrIndex::new(table.iter().enumerate().filter(|(_, v)| v.value_type() == ty).map(|(row, v)| (v.vr, row)))
        };
        Lookup { by_type: ValueType::ALL.map(index) }
    }

    /// The table row of the `ty` variable `vr`.
    #[inline]
    pub fn row(&self, ty: ValueType, vr: u32) -> Option<usize> {
        self.by_type[ty as usize].row(vr)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every vr of 0..=limit through `index`, as (vr, row) for the known ones.
    fn resolved(index: &VrIndex, limit: u32) -> Vec<(u32, usize)> {
        (0..=limit).filter_map(|vr| index.row(vr).map(|row| (vr, row))).collect()
    }

    #[test]
    fn compact_value_references_get_a_dense_index() {
        let index = VrIndex::new([(3, 0), (0, 1), (7, 2)]);
        assert!(matches!(&index, VrIndex::Dense(rows) if rows.len() == 8), "{index:?}");
        assert_eq!(resolved(&index, 100), [(0, 1), (3, 0), (7, 2)]);
        assert_eq!(index.row(u32::MAX), None);
    }

    #[test]
    fn sparse_value_references_get_a_sorted_index() {
        let index = VrIndex::new([(1_000_000, 0), (5, 1), (70_000, 2), (u32::MAX, 3)]);
        assert!(matches!(index, VrIndex::Sorted(_)), "{index:?}");
        assert_eq!(resolved(&index, 1_000_001), [(5, 1), (70_000, 2), (1_000_000, 0)]);
        assert_eq!(index.row(u32::MAX), Some(3));
        assert_eq!(index.row(u32::MAX - 1), None);
        assert_eq!(index.row(4), None);
    }

    #[test]
    fn a_repeated_value_reference_resolves_to_the_later_row_in_both_forms() {
        assert_eq!(VrIndex::new([(2, 0), (2, 1)]).row(2), Some(1));
        let sparse = VrIndex::new([(1 << 20, 0), (9, 1), (1 << 20, 2)]);
        assert!(matches!(sparse, VrIndex::Sorted(_)));
        assert_eq!(sparse.row(1 << 20), Some(2));
    }

    #[test]
    fn an_empty_type_knows_no_value_reference() {
        let index = VrIndex::new([]);
        assert_eq!(index.row(0), None);
    }
}
