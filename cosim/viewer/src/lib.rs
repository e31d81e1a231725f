//! The crane seen in 3D, in a browser.
//!
//! Modules, bottom up (each uses only modules above it in this list):
//! * [`error`]: why a view or a live session fails;
//! * [`scene`]: what is drawn at one instant, in the world frame W (NED), from the crane's
//!   forward kinematics and the recorded ship, load and controller variables;
//! * [`columns`]: the recorded variables a frame needs, read from any row;
//! * [`replay`]: the frames of a results table, or of a system run with those variables
//!   recorded in memory;
//! * [`page`]: one self-contained HTML page (data as JSON, the JavaScript bundle inlined).

pub mod columns;
pub mod error;
pub mod live;
pub mod page;
pub mod replay;
pub mod scene;

pub use error::ViewerError;
