// Four time plots under the scene — θx, θy (deg), load height (m, up) and, for the test-scale
// crane, the load's distance to its set-point (mm) or, for the full-scale crane (whose
// controller has no load set-point), the tip's height (m, up) — with a cursor at the time shown
// in 3D.

const COMMON = [
  { title: "θx (deg)", value: (f, i) => (f.get("theta", i)[0] * 180) / Math.PI, colour: "#1f6feb" },
  { title: "θy (deg)", value: (f, i) => (f.get("theta", i)[1] * 180) / Math.PI, colour: "#8250df" },
  // W z points down: the height above the deck's rest plane is −z.
  { title: "load height (m)", value: (f, i) => -f.get("load", i)[2], colour: "#1a7f37" },
];
const LAST = {
  test: { title: "set-point error (mm)", value: (f, i) => f.get("setpoint_error", i) * 1000, colour: "#cf222e" },
  // The tip is the crane column's fourth point.
  full: { title: "tip height (m)", value: (f, i) => -f.get("crane", i)[11], colour: "#cf222e" },
};

const MARGIN = { left: 48, right: 8, top: 18, bottom: 18 };

export function createPlots(container, scale) {
  const PANELS = [...COMMON, LAST[scale] || LAST.test];
  const canvases = PANELS.map((panel) => {
    const canvas = document.createElement("canvas");
    canvas.title = panel.title;
    container.appendChild(canvas);
    return canvas;
  });
  let cache = null; // the curves drawn once per data change, the cursor on top each frame

  function size(canvas) {
    const ratio = window.devicePixelRatio || 1;
    const width = Math.max(canvas.clientWidth, 50);
    const height = Math.max(canvas.clientHeight, 40);
    if (canvas.width !== Math.round(width * ratio)) canvas.width = Math.round(width * ratio);
    if (canvas.height !== Math.round(height * ratio)) canvas.height = Math.round(height * ratio);
    return { width, height, ratio };
  }

  // The curves of frames first..last, with their axes, into an image per panel.
  function drawCurves(frames, first, last) {
    const t0 = frames.time(first);
    const t1 = Math.max(frames.time(last), t0 + 1e-9);
    return PANELS.map((panel, p) => {
      const canvas = canvases[p];
      const { width, height, ratio } = size(canvas);
      const image = document.createElement("canvas");
      image.width = canvas.width;
      image.height = canvas.height;
      const g = image.getContext("2d");
      g.scale(ratio, ratio);
      let low = Infinity;
      let high = -Infinity;
      for (let i = first; i <= last; i++) {
        const v = panel.value(frames, i);
        if (Number.isFinite(v)) {
          low = Math.min(low, v);
          high = Math.max(high, v);
        }
      }
      if (!(high > low)) {
        low = (Number.isFinite(low) ? low : 0) - 1;
        high = low + 2;
      }
      const x = (t) => MARGIN.left + ((t - t0) / (t1 - t0)) * (width - MARGIN.left - MARGIN.right);
      const y = (v) => height - MARGIN.bottom - ((v - low) / (high - low)) * (height - MARGIN.top - MARGIN.bottom);
      g.fillStyle = "#ffffff";
      g.fillRect(0, 0, width, height);
      g.strokeStyle = "#d0d7de";
      g.strokeRect(MARGIN.left, MARGIN.top, width - MARGIN.left - MARGIN.right, height - MARGIN.top - MARGIN.bottom);
      g.fillStyle = "#24292f";
      g.font = "11px sans-serif";
      g.fillText(panel.title, MARGIN.left, 12);
      g.fillText(high.toPrecision(3), 2, MARGIN.top + 8);
      g.fillText(low.toPrecision(3), 2, height - MARGIN.bottom);
      g.fillText(`${t0.toFixed(1)} s`, MARGIN.left, height - 4);
      g.fillText(`${t1.toFixed(1)} s`, width - MARGIN.right - 40, height - 4);
      g.strokeStyle = panel.colour;
      g.lineWidth = 1.2;
      g.beginPath();
      for (let i = first; i <= last; i++) {
        const v = panel.value(frames, i);
        if (i === first) g.moveTo(x(frames.time(i)), y(v));
        else g.lineTo(x(frames.time(i)), y(v));
      }
      g.stroke();
      return { image, x };
    });
  }

  // Draws the plots of frames first..last with a cursor at frame `current`; the curves are
  // redrawn only when `version` (the data or the window) changed.
  function show(frames, first, last, current, version) {
    if (frames.length === 0) return;
    if (!cache || cache.version !== version) cache = { version, panels: drawCurves(frames, first, last) };
    cache.panels.forEach(({ image, x }, p) => {
      const canvas = canvases[p];
      const { height, ratio } = size(canvas);
      const g = canvas.getContext("2d");
      g.setTransform(1, 0, 0, 1, 0, 0);
      g.drawImage(image, 0, 0);
      g.scale(ratio, ratio);
      g.strokeStyle = "#57606a";
      g.beginPath();
      const at = x(frames.time(current));
      g.moveTo(at, MARGIN.top);
      g.lineTo(at, height - MARGIN.bottom);
      g.stroke();
    });
  }

  return { show, invalidate: () => (cache = null) };
}
