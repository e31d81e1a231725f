//! The engine tested without any FMU: in-process mock simulators whose calls are journaled, so
//! stepping order, the values and slopes each one receives, recording and error propagation
//! are checked exactly.

mod algorithms;
mod inputs;
mod mock;
mod recording;
mod runs;
mod wiring;
mod wrapped;
