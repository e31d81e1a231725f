//! [`xyz!`](crate::xyz): the three rows of a vector's x, y and z components.

/// The rows of the x, y and z components of a vector, as an array `[x, y, z]` for a table group.
/// Value references are `vr`, `vr + 1`, `vr + 2`; names are the prefix followed by `x`, `y`, `z`
/// (`"tip."` gives `tip.x`, `"tip.v"` gives `tip.vx`); the getter and setter name the vector and
/// the component is appended. Descriptions are per axis, since they often differ by more than
/// the axis.
///
/// ```text
/// xyz!(Real::held_input(110, "ship."),
///     unit: "m",
///     start: [0.0; 3],                   // parameters and inputs; an array indexed by axis
///     range: (-1.0, 1.0),                // optional, the same for every axis
///     doc: ["Ship surge, W x", "Ship sway, W y", "Ship heave, W z"],
///     get: |m| m.ship.pos,               // reads m.ship.pos.x, .y, .z
///     set: |m, v| m.ship.pos)            // writes m.ship.pos.x = v, …; last, no trailing comma
/// ```
///
/// A setter that goes through a method taking a closure is written as
/// `set: |m, v| m.set_ship(|s| s.pos)`, which becomes `m.set_ship(|s| s.pos.x = v)`.
#[macro_export]
macro_rules! xyz {
    (
        $($kind:ident)::+ ($vr:expr, $prefix:literal),
        unit: $unit:expr,
        $(start: $start:expr,)?
        $(range: ($lo:expr, $hi:expr),)?
        doc: [$dx:expr, $dy:expr, $dz:expr $(,)?],
        get: |$g:ident| $get:expr
        $(, set: |$s:ident, $v:ident| $($set:tt)+)?
    ) => {
        [
            $($kind)::+($vr, concat!($prefix, "x")).unit($unit)$(.start($start[0]))?$(.range($lo, $hi))?
                .doc($dx).get(|$g| $get.x)$(.set($crate::xyz!(@set x |$s, $v| $($set)+)))?,
            $($kind)::+($vr + 1, concat!($prefix, "y")).unit($unit)$(.start($start[1]))?$(.range($lo, $hi))?
                .doc($dy).get(|$g| $get.y)$(.set($crate::xyz!(@set y |$s, $v| $($set)+)))?,
            $($kind)::+($vr + 2, concat!($prefix, "z")).unit($unit)$(.start($start[2]))?$(.range($lo, $hi))?
                .doc($dz).get(|$g| $get.z)$(.set($crate::xyz!(@set z |$s, $v| $($set)+)))?,
        ]
    };
    (@set $axis:ident |$m:ident, $v:ident| $recv:ident . $method:ident (|$inner:ident| $place:expr)) => {
        |$m, $v| $recv.$method(|$inner| $place.$axis = $v)
    };
    (@set $axis:ident |$m:ident, $v:ident| $place:expr) => {
        |$m, $v| $place.$axis = $v
    };
}
