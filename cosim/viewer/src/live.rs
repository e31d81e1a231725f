//! A live, operator-in-the-loop session: the closed loop stepped at real time (× a speed
//! factor), its frames streamed to the viewer page over a WebSocket, the operator's commands
//! — load set-point moves in the world frame, compensation on/off, pause, reset — applied
//! between steps through the controller's external set-point inputs and tunable `mode`.
//!
//! The full-scale crane (systems/full_scale_ahc.json) is driven the same way with what its
//! controller `knuckle_boom_controller` offers: compensation on/off switches its tunable `mode`
//! between 2 (world-frame compensation with anti-sway) and 1 (the joints hold their start);
//! it has no external set-point, so moves are refused with the reason, and the state's
//! `setpoint` is null. Without a controller (systems/full_scale.json) only pause and reset
//! apply.

mod guard;
mod operator;
mod pacing;
mod server;

use std::cell::{Cell, RefCell};
use std::path::{Path, PathBuf};
use std::rc::Rc;
use std::sync::{Arc, Mutex, PoisonError};
use std::time::Duration;

use cosim_engine::execution::{Execution, RunError};
use cosim_engine::interrupt::Interrupt;
use cosim_engine::observer::{CsvRecorder, Observer, ObserverError};
use cosim_engine::simulator::Simulator;
use cosim_engine::system::System;
use cosim_engine::variable::VariableRef;
use crane_names::{TestScaleControl, FULL_SCALE, TEST_SCALE};
use serde::Serialize;

pub use operator::Commands;
pub use operator::{CABLE, MAX_STEP, TIP_EAST, TIP_NORTH};
pub use pacing::Pacing;
pub use server::{Command, COMMANDS_PER_SECOND, MAX_CONNECTIONS, WRITE_TIMEOUT};

use crate::columns::Columns;
use crate::error::ViewerError;
use crate::page::{self, PageData};
use crate::replay::{crane_of, resolve, view_variables, INSTANTIATE};
use crate::scene::{Crane, Frame};
use operator::{Inputs, Operator};
use pacing::Clock;
use server::{refusal, Client, Request, Server, SOCKET_PATH};

/// The names of the closed loop the operator drives.
const NAMES: crane_names::CraneNames = TEST_SCALE;
/// The test-scale controller's set-point inputs and parameters (checked when this compiles).
const CONTROL: TestScaleControl = match NAMES.test {
    Some(names) => names,
    None => panic!("the test scale's names have its controller's"),
};
/// Runs recorded per session with `--record` (the first and the resets after it); the runs
/// after these are not recorded, so that resets cannot fill the disk.
pub const MAX_RECORDINGS: u32 = 20;

/// Options of a live session.
#[derive(Debug, Clone)]
pub struct LiveOptions {
    /// Simulated seconds per wall-clock second.
    pub speed: f64,
    /// 127.0.0.1 port (0: any free one).
    pub port: u16,
    /// Record the run to this CSV (the system's recorded variables, the view's, the controller's
    /// set-point inputs and mode); each reset starts the next file, `<stem>-2.<ext>`, `-3`, …,
    /// up to [`MAX_RECORDINGS`] files.
    pub record: Option<PathBuf>,
    /// Ends the session between steps.
    pub interrupt: Option<Interrupt>,
    /// Start simulating only once the first page has connected its socket (an interrupt ends
    /// the wait), so that the operator sees the run from its start.
    pub wait_for_page: bool,
}

/// The session's state as the page shows it.
#[derive(Debug, Clone, Serialize)]
struct State {
    paused: bool,
    /// Whether the controller compensates (its `mode` 2) or not (1); null without a controller.
    compensation: Option<bool>,
    /// The load set-point (m, W); null when the controller has no set-point inputs to move
    /// (the full-scale crane's).
    setpoint: Option<[f64; 3]>,
    recording: Option<String>,
    /// Why the run is not recorded although `--record` was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    notice: Option<String>,
}

/// Latest frame of the view's variables, read after each step.
struct FrameReader {
    variables: Vec<VariableRef>,
    columns: Columns,
    latest: Rc<RefCell<Option<Frame>>>,
}

impl Observer for FrameReader {
    fn observe(&mut self, _k: u64, time: f64, slaves: &[Box<dyn Simulator>]) -> Result<(), ObserverError> {
        let mut values = vec![0.0; self.variables.len()];
        for (value, variable) in values.iter_mut().zip(&self.variables) {
            let slave = &slaves[variable.instance];
            slave.get_real(&[variable.variable.value_reference], std::slice::from_mut(value))?;
        }
        *self.latest.borrow_mut() = Some(self.columns.frame(time, |i| values[i]));
        Ok(())
    }

    fn finish(&mut self) -> Result<(), ObserverError> {
        Ok(())
    }
}

/// One run of the system from its initial state.
struct Run {
    execution: Execution,
    latest: Rc<RefCell<Option<Frame>>>,
}

/// The controller the operator drives: its instance, the inputs written before its steps and
/// the fixed set-point parameters the operator starts from (test scale only).
#[derive(Debug, Clone, Copy)]
struct Controls {
    controller: usize,
    inputs: Inputs,
    fixed: Option<[u32; 4]>,
}

impl Controls {
    /// The test-scale loop's controller: its external set-point inputs (used with `setpoint` =
    /// 2), its fixed set-point parameters and its `mode`.
    fn test_scale(system: &System) -> Result<Controls, ViewerError> {
        let controller =
            system.instance_index(NAMES.controller.0).ok_or_else(|| unknown(system, NAMES.controller.0))?;
        let setpoint = variables(system, CONTROL.setpoint_inputs)?.map(|v| v.variable.value_reference);
        let mode = resolve(system, NAMES.mode)?.variable.value_reference;
        let fixed = variables(system, CONTROL.fixed_setpoint)?.map(|v| v.variable.value_reference);
        Ok(Controls { controller, inputs: Inputs { setpoint: Some(setpoint), mode }, fixed: Some(fixed) })
    }

    /// The full-scale crane's controller, if the system has one: only its tunable `mode` (2
    /// world-frame compensation with anti-sway, 1 the joints hold their start), since it has no
    /// external set-point inputs.
    fn full_scale(system: &System) -> Result<Option<Controls>, ViewerError> {
        let Some(controller) = system.instance_index(FULL_SCALE.controller.0) else {
            return Ok(None);
        };
        let mode = resolve(system, FULL_SCALE.mode)?.variable.value_reference;
        Ok(Some(Controls { controller, inputs: Inputs { setpoint: None, mode }, fixed: None }))
    }

    /// The variables the session records besides the system's and the view's: the set-point
    /// inputs and the mode.
    fn recorded(system: &System, crane: &Crane) -> Result<Vec<VariableRef>, ViewerError> {
        match crane {
            Crane::TestScale => {
                let mut extra = variables(system, CONTROL.setpoint_inputs)?.to_vec();
                extra.push(resolve(system, NAMES.mode)?);
                Ok(extra)
            }
            Crane::FullScale { .. } if system.instance_index(FULL_SCALE.controller.0).is_some() => {
                Ok(vec![resolve(system, FULL_SCALE.mode)?])
            }
            Crane::FullScale { .. } => Ok(Vec::new()),
        }
    }
}

/// The session: the system, the operator's commands and what is recorded.
struct Session<'a> {
    system: &'a System,
    options: &'a LiveOptions,
    crane: Crane,
    controls: Option<Controls>,
    commands: Arc<Mutex<Commands>>,
    recorded: Vec<VariableRef>,
    /// Runs started so far (a reset starts one).
    runs: Cell<u32>,
}

impl Session<'_> {
    fn new<'a>(system: &'a System, options: &'a LiveOptions) -> Result<Session<'a>, ViewerError> {
        let crane = crane_of(system);
        let controls = match crane {
            Crane::TestScale => Some(Controls::test_scale(system)?),
            Crane::FullScale { .. } => Controls::full_scale(system)?,
        };
        let mut recorded = system.record.variables.clone();
        for variable in view_variables(system, &crane)?.into_iter().chain(Controls::recorded(system, &crane)?) {
            if !recorded.iter().any(|v| v.qualified_name == variable.qualified_name) {
                recorded.push(variable);
            }
        }
        let commands = Arc::new(Mutex::new(Commands { tip: [0.0; 3], lp: 0.0, mode: 2 }));
        Ok(Session { system, options, crane, controls, commands, recorded, runs: Cell::new(0) })
    }

    /// A fresh run, initialized, with the operator's commands set to the controller's fixed
    /// set-point and its start mode.
    fn start(&self) -> Result<Run, ViewerError> {
        let system = self.system;
        let mut execution = Execution::from_system(system, INSTANTIATE)?;
        if let Some(controls) = &self.controls {
            let operator = Operator { inputs: controls.inputs, commands: Arc::clone(&self.commands) };
            execution.wrap(controls.controller, operator);
        }
        let latest = Rc::new(RefCell::new(None));
        let variables = view_variables(system, &self.crane)?;
        let names: Vec<String> = variables.iter().map(|v| v.qualified_name.clone()).collect();
        let columns = Columns::find(self.crane, &names).map_err(|missing| unknown(system, missing[0]))?;
        execution.add_observer(Box::new(FrameReader { variables, columns, latest: Rc::clone(&latest) }));
        self.runs.set(self.runs.get() + 1);
        if self.options.record.is_some() && self.runs.get() == MAX_RECORDINGS + 1 {
            eprintln!("live: {}", self.notice().unwrap_or_default());
        }
        if let Some(path) = self.recording() {
            let recorder = CsvRecorder::create(&path, &self.recorded, system.record.every)
                .map_err(|source| RunError::Observer { time: system.grid.start(), source })?;
            execution.add_observer(Box::new(recorder));
        }
        execution.initialize()?;
        if let Some(controls) = &self.controls {
            *self.commands.lock().unwrap_or_else(PoisonError::into_inner) = initial_commands(controls, &execution)?;
        }
        Ok(Run { execution, latest })
    }

    /// Applies an operator's command; true when the run was paused, resumed or reset. A move
    /// out of bounds, or a command the system's controller cannot take, changes nothing and is
    /// answered to the `client` who sent it.
    fn handle(
        &self,
        command: Command,
        client: &Client,
        paused: &mut bool,
        run: &mut Run,
        server: &Server,
    ) -> Result<bool, ViewerError> {
        let mut commands = self.commands.lock().unwrap_or_else(PoisonError::into_inner);
        match command {
            Command::Move { delta } => match self.controls.and_then(|c| c.inputs.setpoint) {
                Some(_) => match commands.checked_move(delta) {
                    Ok(moved) => *commands = moved,
                    Err(why) => client.reply(&refusal(&why)),
                },
                None => client.reply(&refusal(NO_SETPOINT)),
            },
            Command::Compensation { on } => match self.controls {
                Some(_) => commands.mode = if on { 2 } else { 1 },
                None => client.reply(&refusal(NO_CONTROLLER)),
            },
            Command::Pause | Command::Resume => {
                *paused = command == Command::Pause;
                return Ok(true);
            }
            Command::Reset => {
                drop(commands);
                run.execution.terminate()?;
                run.execution.finish_observers()?;
                *run = self.start()?;
                server.announce(r#"{"reset":true}"#);
                return Ok(true);
            }
        }
        Ok(false)
    }

    fn state(&self, paused: bool) -> State {
        let commands = *self.commands.lock().unwrap_or_else(PoisonError::into_inner);
        let moves = self.controls.and_then(|c| c.inputs.setpoint).is_some();
        State {
            paused,
            compensation: self.controls.map(|_| commands.mode == 2),
            setpoint: moves.then(|| commands.load()),
            recording: self.recording().map(|p| p.display().to_string()),
            notice: self.notice(),
        }
    }

    /// Why this run is not recorded, when the session has recorded [`MAX_RECORDINGS`] already.
    fn notice(&self) -> Option<String> {
        let path = self.options.record.as_ref()?;
        (self.runs.get() > MAX_RECORDINGS).then(|| {
            format!(
                "recording stopped: {MAX_RECORDINGS} runs were recorded ({} … {}), the most per session",
                path.display(),
                numbered(path, MAX_RECORDINGS).display()
            )
        })
    }

    /// The current run's CSV: the `--record` file for the first run, `<stem>-<n>.<ext>` for the
    /// n-th, so a reset keeps what was recorded before it; none past [`MAX_RECORDINGS`].
    fn recording(&self) -> Option<PathBuf> {
        let path = self.options.record.as_ref()?;
        (self.runs.get() <= MAX_RECORDINGS).then(|| numbered(path, self.runs.get()))
    }
}

/// The refusal of a set-point move when the controller has no set-point inputs.
const NO_SETPOINT: &str = "no set-point to move: the full-scale crane's controller has no external set-point inputs \
                           (its arm holds its start or compensates, its winch holds the load's height)";
/// The refusal of a compensation switch when the system has no controller.
const NO_CONTROLLER: &str = "no compensation to switch: the system has no controller";

/// The controller's fixed set-point (if it has one) and mode after initialization.
fn initial_commands(controls: &Controls, execution: &Execution) -> Result<Commands, ViewerError> {
    let slave = &execution.simulators()[controls.controller];
    let (mut values, mut mode) = ([0.0; 4], [0]);
    let fixed = controls.fixed.map_or(Ok(()), |fixed| slave.get_real(&fixed, &mut values));
    let read = fixed.and_then(|()| slave.get_integer(&[controls.inputs.mode], &mut mode));
    read.map_err(|source| RunError::Initialize { time: execution.time(), source })?;
    Ok(Commands { tip: [values[0], values[1], values[2]], lp: values[3], mode: mode[0] })
}

/// `path` for run 1, `<stem>-<run>.<ext>` beside it for a later run.
fn numbered(path: &Path, run: u32) -> PathBuf {
    if run <= 1 {
        return path.to_path_buf();
    }
    let stem = path.file_stem().map(|s| s.to_string_lossy().into_owned()).unwrap_or_default();
    let name = match path.extension() {
        Some(ext) => format!("{stem}-{run}.{}", ext.to_string_lossy()),
        None => format!("{stem}-{run}"),
    };
    path.with_file_name(name)
}

fn unknown(system: &System, name: &str) -> ViewerError {
    ViewerError::UnknownVariable { file: system.file.clone(), name: name.to_string() }
}

/// The variables of the `"instance.variable"` `names`.
fn variables<const N: usize>(system: &System, names: [&str; N]) -> Result<[VariableRef; N], ViewerError> {
    let found: Vec<VariableRef> = names.iter().map(|name| resolve(system, name)).collect::<Result<_, _>>()?;
    Ok(found.try_into().unwrap_or_else(|_| unreachable!("one variable per name")))
}

/// Serves the page and runs the session until the system's stop time or the interrupt; calls
/// `ready` with the page's address (with the session's token) once it is served. Returns the pacing of every step taken.
pub fn run(
    system: &System,
    title: &str,
    options: &LiveOptions,
    ready: impl FnOnce(&str),
) -> Result<Pacing, ViewerError> {
    let session = Session::new(system, options)?;
    let token = guard::new_token().map_err(io("the session's token"))?;
    let socket = format!("{SOCKET_PATH}?token={token}");
    let scale = session.crane.scale();
    let html = page::html(&PageData::Live { title, scale, socket: &socket }).map_err(io("the live page"))?;
    let listening = Server::start(options.port, token.clone(), html);
    let server = listening.map_err(io(&format!("cannot listen on port {}", options.port)))?;
    ready(&format!("http://{}/?token={token}", server.address));
    let interrupted = || options.interrupt.as_ref().and_then(Interrupt::requested).is_some();
    while options.wait_for_page && !server.has_page() && !interrupted() {
        std::thread::sleep(Duration::from_millis(20));
    }
    let mut run = session.start()?;
    let realtime = pacing::request_realtime();
    let step = system.grid.nominal_step();
    let mut clock = Clock::start(run.execution.completed_steps(), step, options.speed);
    let mut paused = false;
    let mut late = Vec::new();
    let mut announced = false;
    while !run.execution.is_done() && !interrupted() {
        let mut changed = !announced;
        for Request { command, client } in server.commands.try_iter() {
            changed = true;
            // The deadlines start again from now after a pause or a reset; a set-point move
            // keeps them.
            if session.handle(command, &client, &mut paused, &mut run, &server)? {
                clock = Clock::start(run.execution.completed_steps(), step, options.speed);
            }
        }
        if changed {
            server.broadcast(&message(&session.state(paused), None)?);
            announced = true;
        }
        if paused {
            std::thread::sleep(Duration::from_millis(10));
            clock = Clock::start(run.execution.completed_steps(), step, options.speed);
            continue;
        }
        run.execution.step()?;
        late.push(Clock::wait(clock.deadline(run.execution.completed_steps())));
        let frame = *run.latest.borrow();
        server.broadcast(&message(&session.state(paused), frame.as_ref())?);
    }
    run.execution.terminate()?;
    run.execution.finish_observers()?;
    Ok(Pacing::of(&late, options.speed, realtime))
}

fn message(state: &State, frame: Option<&Frame>) -> Result<String, ViewerError> {
    #[derive(Serialize)]
    struct Message<'a> {
        state: &'a State,
        #[serde(skip_serializing_if = "Option::is_none")]
        frame: Option<&'a Frame>,
    }
    serde_json::to_string(&Message { state, frame }).map_err(io("a frame"))
}

fn io<E: Into<Box<dyn std::error::Error + Send + Sync>>>(what: &str) -> impl Fn(E) -> ViewerError + '_ {
    move |e| ViewerError::Io { what: what.to_string(), source: std::io::Error::other(e) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn each_run_after_the_first_records_to_the_next_numbered_file() {
        let path = Path::new("out/session.csv");
        assert_eq!(numbered(path, 1), path);
        assert_eq!(numbered(path, 2), Path::new("out/session-2.csv"));
        assert_eq!(numbered(path, 12), Path::new("out/session-12.csv"));
        assert_eq!(numbered(Path::new("rec"), 3), Path::new("rec-3"));
    }
}
