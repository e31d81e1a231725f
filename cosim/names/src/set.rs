//! The shapes a name takes in [`crate::CraneNames`] and how each lists its names, so that the
//! struct's `all()` is generated from its fields rather than kept by hand.

use serde::Serialize;

/// An `"instance.variable"` triple `<prefix>x`, `<prefix>y`, `<prefix>z`, with its prefix (the
/// form the campaign's traces read).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub struct Xyz {
    /// The common prefix, e.g. `"pendulum.load."`.
    pub prefix: &'static str,
    /// The three names.
    pub axes: [&'static str; 3],
}

/// [`Xyz`] of a literal prefix.
#[macro_export]
macro_rules! xyz {
    ($prefix:literal) => {
        $crate::Xyz { prefix: $prefix, axes: [concat!($prefix, "x"), concat!($prefix, "y"), concat!($prefix, "z")] }
    };
}

/// A field of names: one name, several, a triple, or names a scale may not have.
pub trait NameSet {
    /// Appends every name of the field to `out`.
    fn names_into(&self, out: &mut Vec<&'static str>);
}

impl NameSet for &'static str {
    fn names_into(&self, out: &mut Vec<&'static str>) {
        out.push(self);
    }
}

impl<const N: usize> NameSet for [&'static str; N] {
    fn names_into(&self, out: &mut Vec<&'static str>) {
        out.extend(self);
    }
}

impl NameSet for &'static [&'static str] {
    fn names_into(&self, out: &mut Vec<&'static str>) {
        out.extend(self.iter());
    }
}

impl NameSet for Xyz {
    fn names_into(&self, out: &mut Vec<&'static str>) {
        out.extend(self.axes);
    }
}

impl<T: NameSet> NameSet for Option<T> {
    fn names_into(&self, out: &mut Vec<&'static str>) {
        if let Some(set) = self {
            set.names_into(out);
        }
    }
}

/// A struct of named fields whose `all()` lists every name of every field, in field order.
macro_rules! name_struct {
    ($(#[$meta:meta])* pub struct $name:ident { $($(#[$field_meta:meta])* pub $field:ident: $type:ty,)* }) => {
        $(#[$meta])*
        #[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
        pub struct $name {
            $($(#[$field_meta])* pub $field: $type,)*
        }

        impl $crate::NameSet for $name {
            fn names_into(&self, out: &mut Vec<&'static str>) {
                $($crate::NameSet::names_into(&self.$field, out);)*
            }
        }

        impl $name {
            /// Every qualified name of the set, in field order.
            pub fn all(&self) -> Vec<&'static str> {
                let mut out = Vec::new();
                $crate::NameSet::names_into(self, &mut out);
                out
            }
        }
    };
}

pub(crate) use name_struct;

/// An instance name (not a variable): listed by [`crate::CraneNames::instances`], not by `all()`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(transparent)]
pub struct Instance(pub &'static str);

impl NameSet for Instance {
    fn names_into(&self, _: &mut Vec<&'static str>) {}
}
