//! FMU instances are simulators: [`Slave`] forwards every call to the FMU's C functions.

use fmu_import::slave::Slave;

use super::{Simulator, SimulatorError};

impl Simulator for Slave {
    fn name(&self) -> &str {
        Slave::name(self)
    }

    fn setup_experiment(&mut self, start: f64, stop: Option<f64>) -> Result<(), SimulatorError> {
        Ok(Slave::setup_experiment(self, None, start, stop)?)
    }

    fn enter_initialization_mode(&mut self) -> Result<(), SimulatorError> {
        Ok(Slave::enter_initialization_mode(self)?)
    }

    fn exit_initialization_mode(&mut self) -> Result<(), SimulatorError> {
        Ok(Slave::exit_initialization_mode(self)?)
    }

    fn do_step(&mut self, current: f64, step: f64) -> Result<(), SimulatorError> {
        Ok(Slave::do_step(self, current, step)?)
    }

    fn terminated(&self) -> Result<bool, SimulatorError> {
        Ok(Slave::terminated(self)?)
    }

    fn last_successful_time(&self) -> Result<f64, SimulatorError> {
        Ok(Slave::last_successful_time(self)?)
    }

    fn terminate(&mut self) -> Result<(), SimulatorError> {
        Ok(Slave::terminate(self)?)
    }

    fn set_time_hint(&mut self, time: f64) {
        Slave::set_time_hint(self, time)
    }

    fn save_state(&mut self) -> Result<Vec<u8>, SimulatorError> {
        let state = self.get_fmu_state()?;
        let bytes = self.serialize_fmu_state(&state);
        // Freed whether or not it serialized; the serialization's error comes first.
        let freed = self.free_fmu_state(state);
        Ok(bytes.and_then(|bytes| freed.map(|()| bytes))?)
    }

    fn restore_state(&mut self, bytes: &[u8]) -> Result<(), SimulatorError> {
        let state = self.deserialize_fmu_state(bytes)?;
        let set = self.set_fmu_state(&state);
        let freed = self.free_fmu_state(state);
        Ok(set.and(freed)?)
    }

    fn get_real(&self, vrs: &[u32], values: &mut [f64]) -> Result<(), SimulatorError> {
        Ok(Slave::get_real(self, vrs, values)?)
    }

    fn get_integer(&self, vrs: &[u32], values: &mut [i32]) -> Result<(), SimulatorError> {
        Ok(Slave::get_integer(self, vrs, values)?)
    }

    fn get_boolean(&self, vrs: &[u32], values: &mut [bool]) -> Result<(), SimulatorError> {
        Ok(Slave::get_boolean(self, vrs, values)?)
    }

    fn get_string(&self, vrs: &[u32]) -> Result<Vec<String>, SimulatorError> {
        Ok(Slave::get_string(self, vrs)?)
    }

    fn set_real(&mut self, vrs: &[u32], values: &[f64]) -> Result<(), SimulatorError> {
        Ok(Slave::set_real(self, vrs, values)?)
    }

    fn set_integer(&mut self, vrs: &[u32], values: &[i32]) -> Result<(), SimulatorError> {
        Ok(Slave::set_integer(self, vrs, values)?)
    }

    fn set_boolean(&mut self, vrs: &[u32], values: &[bool]) -> Result<(), SimulatorError> {
        Ok(Slave::set_boolean(self, vrs, values)?)
    }

    fn set_string(&mut self, vrs: &[u32], values: &[&str]) -> Result<(), SimulatorError> {
        Ok(Slave::set_string(self, vrs, values)?)
    }

    fn set_real_input_derivatives(&mut self, vrs: &[u32], slopes: &[f64]) -> Result<(), SimulatorError> {
        let orders = vec![1; vrs.len()];
        Ok(Slave::set_real_input_derivatives(self, vrs, &orders, slopes)?)
    }
}
