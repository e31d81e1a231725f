//! Motion compensation and joint control (thesis Chapter 6).
//!
//! - [`pid`]: the discrete joint PID of §6.1 (trapezoidal integral with anti-windup, derivative
//!   on the measurement, error deadband, saturation and deadband jump; Table 6.1);
//! - [`lqr`]: a continuous algebraic Riccati solver, `lqr(A, B, Q, R)` and the linearised
//!   pendulum–tip model it is applied to (§6.2, eqs. 6.12–6.25);
//! - [`compensation`]: the LQR-based delta law of §6.2 that offsets the world-frame tip and
//!   length set-points from the measured state (eqs. 6.27–6.31, error deadbands, the l_pd
//!   correction);
//! - [`setpoint`]: the desired tip position and pendulum length over time (fixed, or the
//!   pick-and-place profile);
//! - [`controller`]: the myRIO software, estimation to commands once per sample;
//! - [`joints`]: from the world-frame set-point to actuator extensions and the winch angle
//!   (frames, crane and mechanism inverse kinematics, eqs. 3.1–3.4 with the controller's drum).

pub mod compensation;
pub mod controller;
pub mod joints;
pub mod lqr;
pub mod pid;
pub mod setpoint;
