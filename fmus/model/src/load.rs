//! The rows of a load hanging from the crane tip, one place for the pendulum FMU and the rigging
//! FMU that replaces it: [`tip_motion_inputs!`](crate::tip_motion_inputs) (what drives the load),
//! [`load_outputs!`](crate::load_outputs) (what it shows),
//! [`pendulum_parameters!`](crate::pendulum_parameters) (what it is and how it starts), and the pieces these are
//! made of, [`swing_parameters!`](crate::swing_parameters) (a rope's initial angles),
//! [`swing_outputs!`](crate::swing_outputs) (a rope's angles) and
//! [`body_outputs!`](crate::body_outputs) (a body's motion), which the rigging also uses for its
//! hook and sling. Sharing the rows keeps the rigging a drop-in replacement: the names, value
//! references, units and interpolation of the pendulum's ports cannot drift apart.
//!
//! Like [`ship_inputs!`](crate::ship_inputs), the rows are built with the caller's `Real` (its
//! `type Real = fmu_model::Real<Model>` alias, which fixes the model type) and read the model
//! through the expressions the caller names after `m =>`.

/// The tip motion input rows, value references 100–111, as an array for a table group: the crane
/// tip's position `tip.x|y|z` (m), velocity `tip.vx|vy|vz` (m/s) and acceleration
/// `tip.ax|ay|az` (m/s²), all in W, and the hoist length `lp` (m) with its rate `lp_dot` and
/// acceleration `lp_ddot`. Every row is an interpolated input: its derivative is the value's rate
/// for the coming step (0 when the importer sets none), and the velocity rows also record in
/// `slopes` (a `physics::pendulum::VelocitySlopes`) whether they have one, for the acceleration
/// reconciliation of `TipMotion::reconciled`.
///
/// The model names its inputs, their rates (both `physics::pendulum::TipMotion`) and the slopes,
/// the start values (a `TipMotion` constant, read in the const context of the table with
/// `physics::math::components`, which the caller has in scope) and the description of `lp`, the
/// one row whose meaning differs (what the rope runs to).
///
/// ```text
/// &tip_motion_inputs!(m => m.input, rate: m.input_rate, slopes: m.slopes, start: INPUT,
///     lp: "Cable (pendulum) length, tip to load"),
/// ```
#[macro_export]
macro_rules! tip_motion_inputs {
    ($m:ident => $input:expr, rate: $rate:expr, slopes: $slopes:expr, start: $start:expr, lp: $lp_doc:expr $(,)?) => {
        $crate::tip_motion_inputs!(@rows $m => $input, $rate;
            100, "tip.x", "m", components(&$start.pos)[0], "Crane tip position x (north), W" => pos.x;
            101, "tip.y", "m", components(&$start.pos)[1], "Crane tip position y (east), W" => pos.y;
            102, "tip.z", "m", components(&$start.pos)[2], "Crane tip position z (down), W" => pos.z;
            103, "tip.vx", "m/s", components(&$start.vel)[0], "Crane tip velocity x, W" => vel.x, $slopes.tip[0];
            104, "tip.vy", "m/s", components(&$start.vel)[1], "Crane tip velocity y, W" => vel.y, $slopes.tip[1];
            105, "tip.vz", "m/s", components(&$start.vel)[2], "Crane tip velocity z, W" => vel.z, $slopes.tip[2];
            106, "tip.ax", "m/s2", components(&$start.acc)[0], "Crane tip acceleration x, W" => acc.x;
            107, "tip.ay", "m/s2", components(&$start.acc)[1], "Crane tip acceleration y, W" => acc.y;
            108, "tip.az", "m/s2", components(&$start.acc)[2], "Crane tip acceleration z, W" => acc.z;
            109, "lp", "m", $start.lp, $lp_doc => lp;
            110, "lp_dot", "m/s", $start.lp_dot, "Rate of lp" => lp_dot, $slopes.lp;
            111, "lp_ddot", "m/s2", $start.lp_ddot, "Acceleration of lp" => lp_ddot;
        )
    };
    // Each row: value reference, name, unit, start, description => the field of the inputs (and
    // of their rates) it reads and writes, and for a velocity the slope flag it sets.
    (@rows $m:ident => $input:expr, $rate:expr;
        $($vr:literal, $name:literal, $unit:literal, $start:expr, $doc:expr => $($field:ident).+ $(, $slope:expr)?;)*
    ) => {
        [$(
            // The caller's `Real` (its `fmu_model::Real<Model>` alias), which fixes the model type.
            Real::input($vr, $name)
                .unit($unit)
                .start($start)
                .doc($doc)
                .get(|$m| $input.$($field).+)
                .set(|$m, v| $input.$($field).+ = v)
                .derivative($crate::tip_motion_inputs!(@derivative $m => $rate.$($field).+ $(, $slope)?)),
        )*]
    };
    (@derivative $m:ident => $rate:expr) => {
        |$m, d| $rate = d.unwrap_or(0.0)
    };
    (@derivative $m:ident => $rate:expr, $slope:expr) => {
        |$m, d| ($rate, $slope) = (d.unwrap_or(0.0), d.is_some())
    };
}

/// The four output rows of a rope's X-Y angles and their rates, value references `vr` to
/// `vr + 3`: `theta_x`, `theta_y` (rad), `omega_x`, `omega_y` (rad/s), each name after the prefix
/// (`""` for the pendulum's cable, `"sling."` for the rigging's sling). The model names its
/// `physics::pendulum::Swing` and the descriptions of the two angles (the rates are "Rate of"
/// their angle).
///
/// ```text
/// &swing_outputs!(246, "sling.", m => m.out.sling.swing,
///     ["Sling angle about x (X-Y sequence, chord hook to load, relative to W)", "Sling angle about y"]),
/// ```
#[macro_export]
macro_rules! swing_outputs {
    ($vr:expr, $prefix:literal, $m:ident => $swing:expr, [$theta_x_doc:expr, $theta_y_doc:expr $(,)?]) => {
        [
            Real::output($vr, concat!($prefix, "theta_x")).unit("rad").doc($theta_x_doc).get(|$m| $swing.theta_x),
            Real::output($vr + 1, concat!($prefix, "theta_y")).unit("rad").doc($theta_y_doc).get(|$m| $swing.theta_y),
            Real::output($vr + 2, concat!($prefix, "omega_x"))
                .unit("rad/s")
                .doc(concat!("Rate of ", $prefix, "theta_x"))
                .get(|$m| $swing.omega_x),
            Real::output($vr + 3, concat!($prefix, "omega_y"))
                .unit("rad/s")
                .doc(concat!("Rate of ", $prefix, "theta_y"))
                .get(|$m| $swing.omega_y),
        ]
    };
}

/// The 16 output rows of a body's motion in W, value references `vr` to `vr + 15`: its position
/// `<name>.x|y|z` (m), velocity `<name>.vx|vy|vz` (m/s), acceleration `<name>.ax|ay|az` (m/s²),
/// orientation W←body `<name>.q0..q3` (a unit quaternion, scalar part first) and angular velocity
/// `<name>.wx|wy|wz` (rad/s, body frame). The model names the body's motion (anything with `pos`,
/// `vel` and `acc` vectors), its orientation (a `Quat`) and its angular velocity, and describes the
/// position (as [`xyz!`](crate::xyz) does: one text around the axis or three), the orientation's
/// scalar part (what rotation it is) and the angular velocity (which frame, as `xyz!`); the other
/// descriptions are the body's title followed by what the row is.
///
/// ```text
/// &body_outputs!(230, "hook", "Hook", m => {
///     motion: motion(m).hook, ("Hook position " + axis + ", W"),
///     orientation: m.out.hoist.orientation, "Hook orientation W<-hook Rx(theta_x)Ry(theta_y), scalar part",
///     angular_velocity: m.out.hoist.angular_velocity, ("Hook angular velocity " + axis + ", hook frame"),
/// }),
/// ```
#[macro_export]
macro_rules! body_outputs {
    // The velocity and acceleration rows, described alike for every body.
    (@rates $vr:expr, $prefix:expr, $unit:literal, $title:literal, $what:literal, $m:ident => $get:expr) => {
        $crate::xyz!(Real::output($vr, $prefix),
            unit: $unit,
            doc: [
                concat!($title, " ", $what, " x, W"),
                concat!($title, " ", $what, " y, W"),
                concat!($title, " ", $what, " z, W"),
            ],
            get: |$m| $get)
    };
    ($vr:expr, $name:literal, $title:literal, $m:ident => {
        motion: $motion:expr, $position_doc:tt,
        orientation: $q:expr, $q0_doc:expr,
        angular_velocity: $w:expr, $w_doc:tt $(,)?
    }) => {
        $crate::table::<_, 16>(&[
            &$crate::xyz!(Real::output($vr, concat!($name, ".")),
                unit: "m",
                doc: $position_doc,
                get: |$m| $motion.pos),
            &$crate::body_outputs!(@rates $vr + 3, concat!($name, ".v"), "m/s", $title, "velocity", $m => $motion.vel),
            &$crate::body_outputs!(@rates $vr + 6, concat!($name, ".a"), "m/s2", $title, "acceleration",
                $m => $motion.acc),
            &[
                Real::output($vr + 9, concat!($name, ".q0")).unit("1").doc($q0_doc).get(|$m| $q.w),
                Real::output($vr + 10, concat!($name, ".q1"))
                    .unit("1")
                    .doc(concat!($title, " orientation, x part"))
                    .get(|$m| $q.i),
                Real::output($vr + 11, concat!($name, ".q2"))
                    .unit("1")
                    .doc(concat!($title, " orientation, y part"))
                    .get(|$m| $q.j),
                Real::output($vr + 12, concat!($name, ".q3"))
                    .unit("1")
                    .doc(concat!($title, " orientation, z part"))
                    .get(|$m| $q.k),
            ],
            &$crate::xyz!(Real::output($vr + 13, concat!($name, ".w")), unit: "rad/s", doc: $w_doc, get: |$m| $w),
        ])
    };
}

/// The pendulum's 28 output rows, value references 200–227, as an array for a table group: the
/// cable's angles [`swing_outputs!`](crate::swing_outputs) (200–203), the load's motion
/// [`body_outputs!`](crate::body_outputs) (`load.*`, 204–219), the cable `tension` (N, 220), the
/// force of the cable on the tip `cable.fx|fy|fz` (N, W, 221–223), that force for an unaccelerated
/// tip and a steady length `cable.f0x|f0y|f0z` (N, W, 224–226) and the mass along the cable that
/// goes with it, `cable.mass` (kg, 227). The model names what each row reads and describes the
/// rows whose meaning depends on the model (a cable to the load, a hoist rope to a hook).
///
/// ```text
/// &load_outputs!(m => {
///     swing: m.swing, ["Cable angle about x (X-Y sequence, relative to W at the tip)", "Cable angle about y"],
///     load: m.load, ("Load position " + axis + ", W"),
///     orientation: m.load.orientation, "Load orientation W<-load Rx(theta_x)Ry(theta_y), scalar part",
///     angular_velocity: m.load.angular_velocity, ("Load angular velocity " + axis + ", load frame"),
///     tension: m.load.tension, "Cable tension",
///     cable_force: m.load.cable_force, ("Force of the cable on the crane tip, W " + axis),
///     free_cable_force: m.load.free_cable_force, ("Cable force on the tip for an unaccelerated tip, W " + axis),
///     cable_mass: m.params.mass, "The load mass m_p",
/// }),
/// ```
#[macro_export]
macro_rules! load_outputs {
    ($m:ident => {
        swing: $swing:expr, $theta_docs:tt,
        load: $load:expr, $position_doc:tt,
        orientation: $q:expr, $q0_doc:expr,
        angular_velocity: $w:expr, $w_doc:tt,
        tension: $tension:expr, $tension_doc:expr,
        cable_force: $force:expr, $force_doc:tt,
        free_cable_force: $free_force:expr, $free_force_doc:tt,
        cable_mass: $mass:expr, $mass_doc:expr $(,)?
    }) => {
        $crate::table::<_, 28>(&[
            &$crate::swing_outputs!(200, "", $m => $swing, $theta_docs),
            &$crate::body_outputs!(204, "load", "Load", $m => {
                motion: $load, $position_doc,
                orientation: $q, $q0_doc,
                angular_velocity: $w, $w_doc,
            }),
            &[Real::output(220, "tension").unit("N").doc($tension_doc).get(|$m| $tension)],
            &$crate::xyz!(Real::output(221, "cable.f"), unit: "N", doc: $force_doc, get: |$m| $force),
            &$crate::xyz!(Real::output(224, "cable.f0"), unit: "N", doc: $free_force_doc, get: |$m| $free_force),
            &[Real::output(227, "cable.mass").unit("kg").doc($mass_doc).get(|$m| $mass)],
        ])
    };
}

/// The three parameter rows of a sling below the hook that a controller accounts for (a
/// `physics::control::controller::SlingConfig` named after `m =>`), value references `vr` to
/// `vr + 2`: `sling.length` (m), `sling.hook_fraction` (1) and `sling.notch_damping` (1), one
/// place for the test-scale and the full-scale controller. The caller gives the start values (its
/// configuration constant's `SlingConfig`) and what the notch acts on.
///
/// ```text
/// &sling_parameters!(24, m => m.config.sling, start: CONFIG.sling, notch_on: "the load IMU's angles"),
/// ```
#[macro_export]
macro_rules! sling_parameters {
    ($vr:expr, $m:ident => $sling:expr, start: $start:expr, notch_on: $on:literal) => {
        [
            $crate::field!(Real::parameter($vr, "sling.length"), unit: "m", start: $start.length, range: (0.0, 100.0),
                doc: concat!(
                    "Sling length from the hook to the load (the rigging FMU's sling.length): the load's set-point ",
                    "hangs this far below the hoist rope's end, and the hook-load mode is notched out of ",
                    $on,
                    "; 0 = the load on the hook, no notch"
                ),
                field: $m => $sling.length),
            $crate::field!(Real::parameter($vr + 1, "sling.hook_fraction"), unit: "1", start: $start.hook_fraction,
                range: (0.0, 1.0),
                doc: "The hook's share of the hanging mass, hook/(hook + load): with the lengths it places the hook-load mode",
                field: $m => $sling.hook_fraction),
            $crate::field!(Real::parameter($vr + 2, "sling.notch_damping"), unit: "1", start: $start.notch_damping,
                range: (0.0, 10.0),
                doc: concat!(
                    "Damping ratio of the notch at the hook-load mode on ",
                    $on,
                    " (band 2 zeta times the mode's frequency); 0 = no notch"
                ),
                field: $m => $sling.notch_damping),
        ]
    };
}

/// The four parameter rows of a rope's initial angles and their rates, value references `vr` to
/// `vr + 3`, for a `physics::pendulum::Swing` named after `m =>`: the two angles (rad, within
/// ±1.5 rad) and the two rates (rad/s), with the start values of the caller's `Swing` constant.
/// One place for the pendulum's cable, the rigging's hoist rope (the pendulum's rows, through
/// [`pendulum_parameters!`](crate::pendulum_parameters)) and the rigging's sling, so that the
/// three cannot drift apart in unit, range or which field they set. The names and descriptions
/// are the caller's, in the order `theta_x`, `theta_y`, `omega_x`, `omega_y`.
///
/// ```text
/// &swing_parameters!(13, m => m.sling_initial, start: INITIAL,
///     names: ["sling.dtheta_x0", "sling.dtheta_y0", "sling.omega_x0", "sling.omega_y0"],
///     docs: ["Initial sling angle about x minus theta_x0", "…", "…", "…"]),
/// ```
#[macro_export]
macro_rules! swing_parameters {
    ($vr:expr, $m:ident => $swing:expr, start: $start:expr,
        names: [$($name:literal),+ $(,)?], docs: [$($doc:expr),+ $(,)?] $(,)?
    ) => {
        $crate::swing_parameters!(@rows $vr, $m => $swing, $start;
            [$($name),+]; [$($doc),+]; [theta_x, theta_y, omega_x, omega_y]; [0, 1, 2, 3])
    };
    (@rows $vr:expr, $m:ident => $swing:expr, $start:expr;
        [$($name:literal),+]; [$($doc:expr),+]; [$($field:ident),+]; [$($i:literal),+]
    ) => {
        [$(
            $crate::swing_parameters!(@row $vr + $i, $name, $doc, $m => $swing, $start, $field)
        ),+]
    };
    // The angles have a range (a rope beyond ±1.5 rad from the vertical is not a hanging load),
    // the rates none.
    (@row $vr:expr, $name:literal, $doc:expr, $m:ident => $swing:expr, $start:expr, theta_x) => {
        $crate::swing_parameters!(@angle $vr, $name, $doc, $m => $swing, $start, theta_x)
    };
    (@row $vr:expr, $name:literal, $doc:expr, $m:ident => $swing:expr, $start:expr, theta_y) => {
        $crate::swing_parameters!(@angle $vr, $name, $doc, $m => $swing, $start, theta_y)
    };
    (@row $vr:expr, $name:literal, $doc:expr, $m:ident => $swing:expr, $start:expr, $field:ident) => {
        $crate::field!(Real::parameter($vr, $name), unit: "rad/s", start: $start.$field, doc: $doc,
            field: $m => $swing.$field)
    };
    (@angle $vr:expr, $name:literal, $doc:expr, $m:ident => $swing:expr, $start:expr, $field:ident) => {
        $crate::field!(Real::parameter($vr, $name), unit: "rad", start: $start.$field, range: (-1.5, 1.5), doc: $doc,
            field: $m => $swing.$field)
    };
}

/// The pendulum's nine parameter rows, value references 0–8, which the rigging keeps with the
/// same names and meaning for its hoist rope and load: the initial swing `theta_x0`, `theta_y0`,
/// `omega_x0`, `omega_y0` ([`swing_parameters!`](crate::swing_parameters), 0–3), the load's
/// `mass` (kg), drag rates `kappa_x`, `kappa_y` (1/s) and `g` (m/s², all of a
/// `physics::pendulum::PendulumParams`, 4–7) and the `release_time` (s, 8). The model names what
/// each row reads and writes and its start value, and describes the rows whose meaning differs
/// (what the rope runs to, how the load's drag is taken). The two drag rates are described as
/// [`xyz!`](crate::xyz) does: two texts, or one around the axis (`("… theta_" + axis)`).
///
/// ```text
/// &pendulum_parameters!(m => {
///     swing: m.initial, INITIAL, ["Initial cable angle about x (X-Y sequence)", "Initial cable angle about y"],
///     load: m.params, PARAMS, "Load mass m_p (enters the cable tension)", ["…", "…"], // or ("…" + axis + "…")
///     release_time: m.release_time, RELEASE_TIME, "The load is held at its initial angles (rates zero) until this time",
/// }),
/// ```
#[macro_export]
macro_rules! pendulum_parameters {
    ($m:ident => {
        swing: $swing:expr, $swing_start:expr, [$theta_x_doc:expr, $theta_y_doc:expr $(,)?],
        load: $load:expr, $load_start:expr, $mass_doc:expr, $kappa_doc:tt,
        release_time: $release:expr, $release_start:expr, $release_doc:expr $(,)?
    }) => {
        $crate::table::<_, 9>(&[
            &$crate::swing_parameters!(0, $m => $swing, start: $swing_start,
                names: ["theta_x0", "theta_y0", "omega_x0", "omega_y0"],
                docs: [
                    $theta_x_doc,
                    $theta_y_doc,
                    "Initial rate of theta_x (at release)",
                    "Initial rate of theta_y (at release)",
                ]),
            &$crate::pendulum_parameters!(@rows $m;
                4, "mass", "kg", (1e-6, 1e6), $mass_doc => $load.mass, $load_start.mass;
                5, "kappa_x", "1/s", (0.0, 1e3), $crate::pendulum_parameters!(@doc 0 "x" $kappa_doc) => $load.kappa_x,
                    $load_start.kappa_x;
                6, "kappa_y", "1/s", (0.0, 1e3), $crate::pendulum_parameters!(@doc 1 "y" $kappa_doc) => $load.kappa_y,
                    $load_start.kappa_y;
                7, "g", "m/s2", (1e-6, 1e3), "Gravitational acceleration" => $load.g, $load_start.g;
                8, "release_time", "s", (), $release_doc => $release, $release_start;
            ),
        ])
    };
    // The description of one drag rate: one of two texts, or `xyz!`'s text around the axis.
    (@doc 0 $axis:literal [$dx:expr, $dy:expr $(,)?]) => { $dx };
    (@doc 1 $axis:literal [$dx:expr, $dy:expr $(,)?]) => { $dy };
    (@doc $i:tt $axis:literal $doc:tt) => { $crate::xyz!(@doc $i $axis $doc) };
    // Each row: value reference, name, unit, range (`()` for none), description => the place it
    // reads and writes, its start.
    (@rows $m:ident; $($vr:literal, $name:literal, $unit:literal, ($($lo:expr, $hi:expr)?), $doc:expr
        => $place:expr, $start:expr;)*) => {
        [$(
            $crate::field!(Real::parameter($vr, $name), unit: $unit, start: $start, $(range: ($lo, $hi),)? doc: $doc,
                field: $m => $place),
        )*]
    };
}
