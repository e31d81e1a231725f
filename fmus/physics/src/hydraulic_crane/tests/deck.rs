//! A sanity run on a moving deck: the crane holds 5 t with centred spools while the deck rolls
//! 3° and heaves 1 m at 0.6 rad/s. With closed load-holding chambers the arm is a stiff body
//! on the deck, so the tip follows the deck's rigid motion; what it leaves is the oil springs'
//! give under the changing weight and inertia loads (a few mm per MPa of pressure change).

use super::*;
use crate::motion::{AxisMotion, DeckMotion, HEAVE, ROLL};

/// Roll amplitude (rad), heave amplitude (m) and frequency (rad/s): a beam sea of an offshore
/// vessel's working limits (our choice, near the sea states of the thesis' profiles).
const ROLL_AMPLITUDE: f64 = 3.0 * std::f64::consts::PI / 180.0;
const HEAVE_AMPLITUDE: f64 = 1.0;
const FREQUENCY: f64 = 0.6;
/// The heave leads the roll by a quarter period: in phase, the 3° roll lifts the tip 18 m out to
/// port by about as much as the heave lowers it, and the tip would hardly move in W.
const HEAVE_PHASE: f64 = std::f64::consts::FRAC_PI_2;

/// a·sin(ωt + φ) with its exact first and second derivatives.
fn sine(amplitude: f64, phase: f64, t: f64) -> AxisMotion {
    let (s, c) = (FREQUENCY * t + phase).sin_cos();
    AxisMotion { pos: amplitude * s, vel: amplitude * FREQUENCY * c, acc: -amplitude * FREQUENCY * FREQUENCY * s }
}

/// The deck at t: roll and heave, the body rates from the Z–Y–X kinematic equation.
fn deck(t: f64) -> ShipMotion {
    let mut d = DeckMotion::default();
    d.dof[ROLL] = sine(ROLL_AMPLITUDE, 0.0, t);
    d.dof[HEAVE] = sine(HEAVE_AMPLITUDE, HEAVE_PHASE, t);
    d.to_ship_motion()
}

#[test]
fn on_a_rolling_heaving_deck_the_tip_follows_the_deck() {
    let params = CraneParams::DEFAULT;
    let load = |t: f64| Loads { ship: deck(t), ..hanging(5.0) };
    let start = at_rest(&params, &load(0.0));
    // The initial tip in K, carried by the deck: where a rigid crane's tip would be.
    let tip_on_deck = params.arm.base + params.arm.tip_in_base(&start.q, &[0.0; 3], &[0.0; 3]).pos;
    let (mut worst, mut worst_t, mut finite) = (0.0f64, 0.0, true);
    let (mut deck_travel, mut q_spread) = (0.0f64, [0.0f64; 3]);
    let end = run(
        &params,
        start,
        60.0,
        |_| Spools::default(),
        load,
        |t, s| {
            let ship = deck(t);
            let rigid = ship.pos + ship.attitude() * tip_on_deck;
            let deviation = (tip(&params, s, &ship) - rigid).norm();
            if deviation > worst {
                (worst, worst_t) = (deviation, t);
            }
            deck_travel = deck_travel.max((rigid - tip(&params, &start, &deck(0.0))).norm());
            q_spread = std::array::from_fn(|i| q_spread[i].max((s.q[i] - start.q[i]).abs()));
            finite &= s.is_finite();
        },
    );
    println!(
        "moving deck, 60 s: the rigidly carried tip travels up to {deck_travel:.3} m; the tip leaves it by at most \
         {worst:.4} m (at {worst_t:.2} s); joints within {q_spread:.6?} rad of the start"
    );
    assert!(finite && end.is_finite());
    assert!(deck_travel > 0.5, "the deck hardly moved the tip: {deck_travel} m");
    assert!(worst < 0.05, "the tip left the deck's motion by {worst} m");
}
