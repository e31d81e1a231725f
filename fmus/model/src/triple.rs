//! [`xyz!`](crate::xyz): the three rows of a vector's x, y and z components.

/// The rows of the x, y and z components of a vector, as an array `[x, y, z]` for a table group.
/// Value references are `vr`, `vr + 1`, `vr + 2`; names are the prefix followed by `x`, `y`, `z`
/// (`"tip."` gives `tip.x`, `"tip.v"` gives `tip.vx`; a `concat!` of literals where a macro
/// builds the prefix); the getter and setter name the vector and the component is appended. The descriptions are either one text around the axis name,
/// `doc: ("Load velocity " + axis + ", W")` (or `("Gyroscope bias, " + axis)`), so that the three
/// cannot drift apart, or three texts where they differ by more than the axis.
///
/// ```text
/// xyz!(Real::held_input(110, "ship."),
///     unit: "m",
///     start: [0.0; 3],                   // parameters and inputs; an array indexed by axis
///     range: (-1.0, 1.0),                // optional, the same for every axis
///     doc: ["Ship surge, W x", "Ship sway, W y", "Ship heave, W z"], // or ("Ship, W " + axis)
///     get: |m| m.ship.pos,               // reads m.ship.pos.x, .y, .z
///     set: |m, v| m.ship.pos)            // writes m.ship.pos.x = v, …; last, no trailing comma
/// ```
///
/// A setter that goes through a method taking a closure is written as
/// `set: |m, v| m.set_ship(|s| s.pos)`, which becomes `m.set_ship(|s| s.pos.x = v)`.
///
/// A vector that the model reads and writes in place and starts at the same place of the
/// constant it is created with names that place once, as [`field!`](crate::field) does for one
/// row: `field: (m.inputs, INPUTS).imu1.mag` stands for `start: components(&INPUTS.imu1.mag)`,
/// `get: |m| m.inputs.imu1.mag` and `set: |m, v| m.inputs.imu1.mag` (`physics::math::components`
/// in the caller's scope, as for [`tip_motion_inputs!`](crate::tip_motion_inputs)).
#[macro_export]
macro_rules! xyz {
    (
        $($kind:ident)::+ ($vr:expr, $prefix:expr),
        unit: $unit:expr,
        $(range: ($lo:expr, $hi:expr),)?
        doc: $doc:tt,
        field: ($m:ident $(. $root:ident)*, $start:expr) $($path:tt)+
    ) => {
        $crate::xyz!($($kind)::+($vr, $prefix),
            unit: $unit,
            start: components(&$start $($path)+),
            $(range: ($lo, $hi),)?
            doc: $doc,
            get: |$m| $m $(.$root)* $($path)+,
            set: |$m, v| $m $(.$root)* $($path)+)
    };
    (
        $($kind:ident)::+ ($vr:expr, $prefix:expr),
        unit: $unit:expr,
        $(start: $start:expr,)?
        $(range: ($lo:expr, $hi:expr),)?
        doc: $doc:tt,
        get: |$g:ident| $get:expr
        $(, set: |$s:ident, $v:ident| $($set:tt)+)?
    ) => {
        [
            $($kind)::+($vr, concat!($prefix, "x")).unit($unit)$(.start($start[0]))?$(.range($lo, $hi))?
                .doc($crate::xyz!(@doc 0 "x" $doc)).get(|$g| $get.x)$(.set($crate::xyz!(@set x |$s, $v| $($set)+)))?,
            $($kind)::+($vr + 1, concat!($prefix, "y")).unit($unit)$(.start($start[1]))?$(.range($lo, $hi))?
                .doc($crate::xyz!(@doc 1 "y" $doc)).get(|$g| $get.y)$(.set($crate::xyz!(@set y |$s, $v| $($set)+)))?,
            $($kind)::+($vr + 2, concat!($prefix, "z")).unit($unit)$(.start($start[2]))?$(.range($lo, $hi))?
                .doc($crate::xyz!(@doc 2 "z" $doc)).get(|$g| $get.z)$(.set($crate::xyz!(@set z |$s, $v| $($set)+)))?,
        ]
    };
    (@doc 0 $axis:literal [$dx:expr, $dy:expr, $dz:expr $(,)?]) => { $dx };
    (@doc 1 $axis:literal [$dx:expr, $dy:expr, $dz:expr $(,)?]) => { $dy };
    (@doc 2 $axis:literal [$dx:expr, $dy:expr, $dz:expr $(,)?]) => { $dz };
    (@doc $i:tt $axis:literal ($before:literal + axis $(+ $after:literal)?)) => {
        concat!($before, $axis $(, $after)?)
    };
    (@set $axis:ident |$m:ident, $v:ident| $recv:ident . $method:ident (|$inner:ident| $place:expr)) => {
        |$m, $v| $recv.$method(|$inner| $place.$axis = $v)
    };
    (@set $axis:ident |$m:ident, $v:ident| $place:expr) => {
        |$m, $v| $place.$axis = $v
    };
}
