//! [`ship_inputs!`](crate::ship_inputs): the rows of the ship (deck) motion inputs, one place for
//! the models that take the platform's outputs (the test-scale crane, the full-scale crane and
//! its controller).

/// The ship motion input rows, value references 110–127, as an array for a table group: the
/// ship frame origin `ship.x|y|z` (m, W, 110–112), its attitude `ship.roll|pitch|yaw` (rad, the
/// Z-Y-X sequence, 113–115), the origin's velocity `ship.vx|vy|vz` (m/s, W, 116–118) and the
/// angular velocity `ship.wx|wy|wz` (rad/s, ship frame B, 122–124); with `accelerations`, also
/// `ship.ax|ay|az` (m/s², W, 119–121) and `ship.alphax|alphay|alphaz` (rad/s², B, 125–127).
/// All are held inputs starting at 0 (a ship at rest), built with the caller's `Real` (its
/// `type Real = fmu_model::Real<Model>` alias, as for [`xyz!`](crate::xyz)). The model names where its ship motion
/// lives (`m => m.ship`, a `physics::motion::ShipMotion`) and has a method
/// `set_ship(&mut self, impl FnOnce(&mut ShipMotion))` through which every row writes.
///
/// ```text
/// &ship_inputs!(m => m.loads.ship),                 // position, attitude, velocities
/// &ship_inputs!(accelerations, m => m.loads.ship),  // and the accelerations
/// ```
#[macro_export]
macro_rules! ship_inputs {
    ($m:ident => $ship:expr) => {
        $crate::ship_inputs!(@rows $m => $ship; []; [])
    };
    (accelerations, $m:ident => $ship:expr) => {
        $crate::ship_inputs!(@rows $m => $ship; [
            $crate::ship_inputs!(@row 119, "ship.ax", "m/s2", "Ship frame origin acceleration, W x", $m => $ship, acc.x),
            $crate::ship_inputs!(@row 120, "ship.ay", "m/s2", "Ship frame origin acceleration, W y", $m => $ship, acc.y),
            $crate::ship_inputs!(@row 121, "ship.az", "m/s2", "Ship frame origin acceleration, W z", $m => $ship, acc.z),
        ]; [
            $crate::ship_inputs!(@row 125, "ship.alphax", "rad/s2", "Ship angular acceleration, B x", $m => $ship, alpha.x),
            $crate::ship_inputs!(@row 126, "ship.alphay", "rad/s2", "Ship angular acceleration, B y", $m => $ship, alpha.y),
            $crate::ship_inputs!(@row 127, "ship.alphaz", "rad/s2", "Ship angular acceleration, B z", $m => $ship, alpha.z),
        ])
    };
    // The rows in value-reference order, the accelerations (if any) after their velocities.
    (@rows $m:ident => $ship:expr; [$($acc:expr,)*]; [$($alpha:expr,)*]) => {
        [
            $crate::ship_inputs!(@row 110, "ship.x", "m", "Ship frame origin, W x (surge)", $m => $ship, pos.x),
            $crate::ship_inputs!(@row 111, "ship.y", "m", "Ship frame origin, W y (sway)", $m => $ship, pos.y),
            $crate::ship_inputs!(@row 112, "ship.z", "m", "Ship frame origin, W z (heave, down)", $m => $ship, pos.z),
            $crate::ship_inputs!(@row 113, "ship.roll", "rad", "Ship roll (Z-Y-X sequence, applied last)", $m => $ship, roll),
            $crate::ship_inputs!(@row 114, "ship.pitch", "rad", "Ship pitch (Z-Y-X sequence)", $m => $ship, pitch),
            $crate::ship_inputs!(@row 115, "ship.yaw", "rad", "Ship yaw (Z-Y-X sequence, applied first)", $m => $ship, yaw),
            $crate::ship_inputs!(@row 116, "ship.vx", "m/s", "Ship frame origin velocity, W x", $m => $ship, vel.x),
            $crate::ship_inputs!(@row 117, "ship.vy", "m/s", "Ship frame origin velocity, W y", $m => $ship, vel.y),
            $crate::ship_inputs!(@row 118, "ship.vz", "m/s", "Ship frame origin velocity, W z", $m => $ship, vel.z),
            $($acc,)*
            $crate::ship_inputs!(@row 122, "ship.wx", "rad/s", "Ship angular velocity, ship frame B x", $m => $ship, omega.x),
            $crate::ship_inputs!(@row 123, "ship.wy", "rad/s", "Ship angular velocity, B y", $m => $ship, omega.y),
            $crate::ship_inputs!(@row 124, "ship.wz", "rad/s", "Ship angular velocity, B z", $m => $ship, omega.z),
            $($alpha,)*
        ]
    };
    (@row $vr:literal, $name:literal, $unit:literal, $doc:literal, $m:ident => $ship:expr, $($field:ident).+) => {
        // The caller's `Real` (its `fmu_model::Real<Model>` alias), which fixes the model type.
        Real::held_input($vr, $name)
            .unit($unit)
            .start(0.0)
            .doc($doc)
            .get(|$m| $ship.$($field).+)
            .set(|$m, v| $m.set_ship(|s| s.$($field).+ = v))
    };
}
