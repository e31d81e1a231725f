//! State estimation from the two IMUs, the crane sensors and the ship position (thesis Chapter 5).
//!
//! - [`complementary`]: the quaternion complementary filter adapted from Valenti et al.
//!   (eqs. 5.8–5.28): gyro integration by the quaternion exponential of the averaged rate,
//!   accelerometer (roll/pitch) correction with an adaptive gain, magnetometer (yaw-only)
//!   correction with an exponential gain, LERP/SLERP interpolation of each correction;
//! - [`madgwick`]: Madgwick's gradient-descent MARG filter (2010), a second estimator to compare
//!   with the complementary filter;
//! - [`attitude`]: the choice between the two, with one interface;
//! - [`calibration`]: at-rest calibration of the gyro biases (and the load's heading) during the
//!   initialisation, beyond the thesis (§8.3);
//! - [`euler`]: ship yaw–pitch–roll (Z–Y–X, eqs. 5.35–5.37) and pendulum θx, θy, θz (X–Y–Z,
//!   eqs. 5.59–5.61) from an orientation quaternion, and the forward rotations they invert;
//! - [`pose`]: the crane tip in the world frame from the ship pose and the crane's forward
//!   kinematics (eq. 5.65), and the load position from the tip, the cable length and the pendulum
//!   angles (eqs. 5.62–5.64);
//! - [`filters`]: the first-order low-pass filters of §5.3 (bias removal during initialisation,
//!   smoothing of the output angles);
//! - [`notch`]: a notch filter that removes the hook–load mode from the load angles when a sling
//!   hangs below the hook (beyond the thesis, docs/rigging.md);
//! - [`linear_motion`]: surge, sway and heave from the deck IMU (§5.1.3): world-frame
//!   acceleration (eq. 5.40), FFT and peak detection, an EKF of undamped oscillators per axis.
//!
//! Frames as in [`crate::imu`]: W North-East-Down, quaternions scalar first, W←sensor. An IMU at
//! rest reads the specific force (0, 0, −g) when level, so the measured gravity direction in W is
//! ĝ = (0, 0, −1) (§5.1.1) and the magnetic field points north, η̂ along +x.

pub mod attitude;
pub mod calibration;
pub mod complementary;
pub mod euler;
pub mod filters;
pub mod linear_motion;
pub mod madgwick;
pub mod notch;
pub mod pose;
#[cfg(test)]
mod scenarios;
