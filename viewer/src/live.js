// The operator's side of a live session: frames and state from the server, commands to it.
//
// Keys: arrows move the load set-point north/south/east/west (world frame), PageUp/PageDown
// raise/lower it; C switches compensation on/off; Space pauses/resumes; R resets the run.
// A gamepad (when the browser offers one): left stick north/south/east/west, right stick up/
// down, button A compensation, Start pause.

// Set-point step per key press (m).
const KEY_STEP = 0.01;
const KEYS = {
  ArrowUp: [KEY_STEP, 0, 0],
  ArrowDown: [-KEY_STEP, 0, 0],
  ArrowRight: [0, KEY_STEP, 0],
  ArrowLeft: [0, -KEY_STEP, 0],
  PageUp: [0, 0, -KEY_STEP], // W z points down
  PageDown: [0, 0, KEY_STEP],
};
// Moves are gathered and sent at most every MOVE_PERIOD ms, each at most MAX_MOVE m per axis
// (the rest follows in the next ones): the server refuses more than 20 commands a second and
// larger moves, and a stick polled every animation frame or a held key would exceed them.
const MOVE_PERIOD = 60;
const MAX_MOVE = 0.1;
// Gamepad set-point speed at full stick (m/s), and the dead zone of the sticks.
const STICK_SPEED = 0.1;
const DEAD_ZONE = 0.15;

export function connectLive(path, ui, handlers) {
  const socket = new WebSocket(`ws://${location.host}${path}`);
  let state = { connected: false };
  // The server's answer to the last command it refused (shown until the next one is accepted
  // or refused).
  let refused = null;
  const status = document.createElement("div");
  status.id = "operator";
  ui.header.append(status);
  const compensation = document.createElement("button");
  compensation.id = "compensation";
  const reset = document.createElement("button");
  reset.id = "reset";
  reset.textContent = "reset";
  ui.controls.append(compensation, reset);

  function send(command) {
    if (socket.readyState === WebSocket.OPEN) socket.send(JSON.stringify(command));
  }
  let pending = [0, 0, 0];
  let flushing = null;
  // Sends the gathered move (up to MAX_MOVE per axis); true when some is left for later.
  function sendPart() {
    const delta = pending.map((v) => Math.max(-MAX_MOVE, Math.min(MAX_MOVE, v)));
    pending = pending.map((v, i) => v - delta[i]);
    send({ command: "move", delta });
    if (pending.some((v) => Math.abs(v) > 1e-12)) return true;
    pending = [0, 0, 0];
    return false;
  }
  function flush() {
    flushing = sendPart() ? setTimeout(flush, MOVE_PERIOD) : null;
  }
  // Another command follows the moves before it.
  function command(message) {
    if (flushing !== null) {
      clearTimeout(flushing);
      flushing = null;
      while (sendPart());
    }
    send(message);
  }
  function move(delta) {
    pending = pending.map((v, i) => v + delta[i]);
    if (flushing === null) flushing = setTimeout(flush, MOVE_PERIOD);
  }
  const togglePause = () => command({ command: state.paused ? "resume" : "pause" });
  const toggleCompensation = () => command({ command: "compensation", on: !state.compensation });
  compensation.addEventListener("click", toggleCompensation);
  reset.addEventListener("click", () => command({ command: "reset" }));

  // The full-scale crane's controller has no set-point to move (setpoint null); a system
  // without a controller has no compensation to switch (compensation null).
  function describe() {
    ui.play.textContent = state.paused ? "resume" : "pause";
    const switchable = state.compensation !== null && state.compensation !== undefined;
    compensation.hidden = !switchable && state.connected;
    compensation.textContent = `compensation ${state.compensation ? "on" : "off"}`;
    compensation.className = state.compensation ? "on" : "";
    const movable = Array.isArray(state.setpoint);
    const sp = movable ? ` · load set-point (${state.setpoint.map((v) => v.toFixed(3)).join(", ")}) m` : "";
    const keys = [
      movable ? "arrows: north/south/east/west, PageUp/PageDown: up/down" : "no set-point to move",
      switchable ? "C: compensation" : null,
      "Space: pause, R: reset",
    ];
    status.textContent =
      `${state.connected ? "live" : "disconnected"}${state.paused ? " (paused)" : ""}${sp}` +
      `${state.recording ? ` · recording to ${state.recording}` : ""}` +
      `${state.notice ? ` · ${state.notice}` : ""}` +
      `${refused ? ` · refused: ${refused}` : ""}` +
      ` · ${keys.filter(Boolean).join(", ")}`;
  }

  socket.addEventListener("open", () => {
    state.connected = true;
    describe();
  });
  socket.addEventListener("close", () => {
    state.connected = false;
    describe();
  });
  socket.addEventListener("message", (event) => {
    const message = JSON.parse(event.data);
    if (message.reset) handlers.reset();
    if (message.refused) {
      refused = message.refused;
      describe();
    }
    if (message.state) {
      state = { ...message.state, connected: true };
      describe();
    }
    if (message.frame) handlers.frame(message.frame);
  });

  window.addEventListener("keydown", (event) => {
    if (event.target instanceof HTMLInputElement || event.target instanceof HTMLSelectElement) return;
    if (KEYS[event.key]) move(KEYS[event.key]);
    else if (event.key === "c" || event.key === "C") toggleCompensation();
    else if (event.key === " ") togglePause();
    else if (event.key === "r" || event.key === "R") command({ command: "reset" });
    else return;
    event.preventDefault();
  });

  let lastPoll = null;
  const pressed = new Set();
  function pollGamepad(wall) {
    const pads = navigator.getGamepads ? [...navigator.getGamepads()].filter(Boolean) : [];
    const dt = lastPoll === null ? 0 : (wall - lastPoll) / 1000;
    lastPoll = wall;
    if (pads.length === 0) return;
    const pad = pads[0];
    const axis = (i) => (Math.abs(pad.axes[i] ?? 0) > DEAD_ZONE ? pad.axes[i] : 0);
    // Stick up is negative; up moves north (left stick) or raises the load (right stick).
    const delta = [-axis(1), axis(0), axis(3)].map((v) => v * STICK_SPEED * dt);
    if (delta.some((v) => v !== 0)) move(delta);
    const edge = (i) => {
      const down = Boolean(pad.buttons[i]?.pressed);
      const rising = down && !pressed.has(i);
      if (down) pressed.add(i);
      else pressed.delete(i);
      return rising;
    };
    if (edge(0)) toggleCompensation();
    if (edge(9)) togglePause();
  }

  return { state: () => (refused ? { ...state, refused } : state), togglePause, pollGamepad };
}
