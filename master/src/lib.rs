//! FMI 2.0 co-simulation master.
pub mod fmi;
pub mod fmu;
pub mod input;
pub mod names;
pub mod slave;
pub mod system;
pub mod time;
pub mod value;
