//! FMI 2.0 co-simulation master.
pub mod fmi;
pub mod fmu;
pub mod names;
pub mod slave;
pub mod value;
