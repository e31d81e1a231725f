// The crane viewer: a replay of a recorded run (frames embedded in the page) or a live session
// (frames streamed over a WebSocket by `crane-cosim live`). window.craneViewer is a read-only
// API for tests and scripts: the crane's scale, the time shown, seek(t), and where the tip, load,
// ghost markers and cylinders are drawn, read back from the three.js scene graph (W =
// North-East-Down, m).
import { Frames } from "./frames.js";
import { createScene } from "./scene.js";
import { createPlots } from "./plots.js";
import { connectLive } from "./live.js";

const STYLE = `
  html, body { margin: 0; height: 100%; font: 14px system-ui, sans-serif; color: #24292f; background: #f6f8fa; }
  #crane { display: grid; grid-template-rows: auto 1fr auto 30%; height: 100vh; }
  header { padding: 6px 12px; display: flex; flex-wrap: wrap; gap: 4px 16px; align-items: baseline; }
  header h1 { font-size: 16px; margin: 0; }
  #legend span { margin-right: 12px; }
  #view { position: relative; min-height: 200px; }
  #controls { display: flex; gap: 8px; align-items: center; padding: 6px 12px; flex-wrap: wrap; }
  #controls input[type=range] { flex: 1; min-width: 200px; }
  #clock { font-variant-numeric: tabular-nums; min-width: 90px; }
  #plots { display: grid; grid-template-columns: 1fr 1fr; gap: 4px; padding: 0 12px 8px; }
  #plots canvas { width: 100%; height: 100%; min-height: 60px; background: #fff; }
  #operator { color: #57606a; font-size: 13px; }
  button.on { background: #dafbe1; }
`;

const SPEEDS = [0.25, 0.5, 1, 2, 4, 8];

function element(tag, attributes = {}, text = "") {
  const e = document.createElement(tag);
  Object.assign(e, attributes);
  if (text) e.textContent = text;
  return e;
}

// The legend of each crane's scene: the full-scale crane's controller has no load estimate nor
// set-point to show.
const LEGENDS = {
  test:
    '<span style="color:#1f6feb">● load</span><span style="color:#2da44e">● estimated load</span>' +
    '<span style="color:#d1242f">◇ set-point</span><span>▲ bow (north at rest)</span>',
  full:
    '<span style="color:#1f6feb">● load (10 m of rope)</span><span style="color:#52606d">▮ luffing cylinders</span>' +
    "<span>▲ bow (north at rest)</span>",
};

function layout(title, live, scale) {
  document.head.appendChild(element("style", {}, STYLE));
  const root = element("div", { id: "crane" });
  const header = element("header");
  header.append(element("h1", {}, title));
  const legend = element("div", { id: "legend" });
  legend.innerHTML = LEGENDS[scale] || LEGENDS.test;
  header.append(legend);
  const view = element("div", { id: "view" });
  const controls = element("div", { id: "controls" });
  const play = element("button", { id: "play" }, live ? "pause" : "play");
  const speed = element("select", { id: "speed", title: "playback speed" });
  for (const s of SPEEDS) speed.append(element("option", { value: s, selected: s === 1 }, `${s}×`));
  const slider = element("input", { id: "slider", type: "range", min: 0, max: 0, step: 1, value: 0 });
  const clock = element("span", { id: "clock" }, "t = 0.00 s");
  controls.append(play, speed, slider, clock);
  const plots = element("div", { id: "plots" });
  root.append(header, view, controls, plots);
  document.body.append(root);
  return { root, header, view, controls, play, speed, slider, clock, plots };
}

function main() {
  const data = JSON.parse(document.getElementById("crane-data").textContent);
  const live = data.mode === "live";
  // "test" (the thesis' rig) or "full" (the knuckle-boom crane): the scene's size and camera.
  const scale = (live ? data.scale : data.frames.scale) || "test";
  const ui = layout(data.title, live, scale);
  const frames = new Frames(live ? null : data.frames);
  const scene = createScene(ui.view, scale);
  const plots = createPlots(ui.plots, scale);
  const state = { index: 0, playing: false, speed: 1, follow: live, version: 0, lastWall: null, time: null };

  function show(index) {
    if (frames.length === 0) return;
    state.index = Math.min(Math.max(index, 0), frames.length - 1);
    state.time = frames.time(state.index);
    scene.show(frames, state.index);
    scene.render();
    ui.slider.max = frames.length - 1;
    ui.slider.value = state.index;
    ui.clock.textContent = `t = ${state.time.toFixed(2)} s`;
    // Live: the last 30 s; replay: the whole run.
    const first = live ? frames.indexAt(frames.time(frames.length - 1) - 30) : 0;
    plots.show(frames, first, frames.length - 1, state.index, state.version);
  }

  ui.slider.addEventListener("input", () => {
    state.follow = live && Number(ui.slider.value) === frames.length - 1;
    show(Number(ui.slider.value));
  });
  ui.speed.addEventListener("change", () => (state.speed = Number(ui.speed.value)));
  window.addEventListener("resize", () => {
    state.version++;
    show(state.index);
  });

  let session = null;
  if (live) {
    session = connectLive(data.socket, ui, {
      frame(frame) {
        frames.push(frame);
        if (frames.length % 10 === 0) state.version++;
        if (state.follow) state.pending = true;
      },
      reset() {
        frames.clear();
        state.version++;
        state.follow = true;
      },
    });
    ui.play.addEventListener("click", () => session.togglePause());
    ui.speed.disabled = true;
    ui.speed.title = "the pace is set by `crane-cosim live --speed`";
  } else {
    ui.play.addEventListener("click", () => {
      state.playing = !state.playing;
      if (state.playing && state.index >= frames.length - 1) show(0);
      ui.play.textContent = state.playing ? "pause" : "play";
      state.lastWall = null;
    });
  }

  function tick(wall) {
    if (live) {
      session.pollGamepad(wall);
      if (state.pending) {
        state.pending = false;
        show(frames.length - 1);
      }
    } else if (state.playing && frames.length > 0) {
      const elapsed = state.lastWall === null ? 0 : (wall - state.lastWall) / 1000;
      const target = state.time + elapsed * state.speed;
      const index = frames.indexAt(target);
      show(index);
      state.time = target; // keep fractional progress between frames
      if (index >= frames.length - 1) {
        state.playing = false;
        ui.play.textContent = "play";
      }
    }
    state.lastWall = wall;
    requestAnimationFrame(tick);
  }

  show(0);
  requestAnimationFrame(tick);

  window.craneViewer = Object.freeze({
    mode: data.mode,
    scale,
    frames: () => frames.length,
    range: () => (frames.length ? [frames.time(0), frames.time(frames.length - 1)] : null),
    time: () => (frames.length ? frames.time(state.index) : null),
    // Stops playback and shows the last frame at or before t; returns its time.
    seek(t) {
      state.playing = false;
      state.follow = false;
      ui.play.textContent = live ? ui.play.textContent : "play";
      show(frames.indexAt(t));
      return frames.time(state.index);
    },
    // Where the tip, the load, the ghost markers (null when not drawn) and the cylinders (null
    // for the test-scale crane) are drawn now (W, NED, m), and the canvas size (px).
    drawn: () => ({ time: frames.time(state.index), ...scene.drawn() }),
    // Where "tip", "load", "estimated_load" or "setpoint" is drawn on the 3D view's canvas (px).
    onScreen: (name) => scene.onScreen(name),
    // Live only: the session state last reported by the server.
    session: () => (session ? session.state() : null),
  });
}

main();
