//! Ship motion for the motion platform: synthesized sea-keeping motion of a ~120 m vessel, its
//! test-scale version, a sinusoid and recorded motion from a file (SPEC §4.1, §8.2; thesis §3.3).
//!
//! - [`spectrum`]: JONSWAP wave spectrum (DNV form) and its seeded random-phase components;
//! - [`rao`]: closed-form response amplitude operators of the hull (Jensen, Mansour & Olsen 2004);
//! - [`motion`]: the harmonic sum that generates the six-degree-of-freedom deck motion
//!   ([`crate::motion::DeckMotion`]) with exact derivatives;
//! - [`phasors`]: the same sum on the 10 ms communication grid by phasor rotation;
//! - [`profiles`]: ship motion profiles 1–3 and the test-scale conversion of §3.3;
//! - [`spline`], [`table`]: motion read from a CSV file through natural cubic splines;
//! - [`source`]: the platform's motion sources (still water, profiles, sine, file);
//! - [`window`]: rest until a start time, then a C² fade-in of the motion.
//!
//! Frames and units: the ship frame B (x bow, y starboard, z down) is aligned with the world frame
//! W (North-East-Down) at rest; the ship heads north at zero speed. Surge, sway and heave are the
//! position of B's origin in W (m; heave positive down), roll, pitch and yaw the Z–Y–X angles of B
//! (rad). Every source is a deterministic function of time and its parameters.

pub mod motion;
pub mod phasors;
pub mod profiles;
pub mod rao;
pub mod source;
pub mod spectrum;
pub mod spline;
pub mod table;
pub mod window;
