// The frames of a run, column by column, as the Rust side serialises them (crane_viewer::replay::
// FrameColumns): vectors flattened frame after frame, SI units, world frame W = North-East-Down.
// A crane without cylinders or ghost markers (set-point, estimated load), or a load without a
// hook, has no such columns.

const WIDTHS = {
  deck_position: 3,
  deck_attitude: 4,
  crane: 12,
  cylinders: 18,
  load: 3,
  hook: 3,
  estimated_load: 3,
  setpoint: 3,
  theta: 2,
  setpoint_error: 1,
};

export class Frames {
  constructor(columns) {
    this.columns = { time: [] };
    for (const name of Object.keys(WIDTHS)) this.columns[name] = [];
    if (columns) Object.assign(this.columns, columns);
  }

  get length() {
    return this.columns.time.length;
  }

  time(i) {
    return this.columns.time[i];
  }

  // Whether the frames hold column `name` (the ghost markers, the cylinders and the hook are
  // optional).
  has(name) {
    return this.length > 0 && this.columns[name].length > 0;
  }

  // The value(s) of column `name` in frame i: a number or an array of its components.
  get(name, i) {
    const width = WIDTHS[name];
    const column = this.columns[name];
    return width === 1 ? column[i] : column.slice(i * width, (i + 1) * width);
  }

  // Appends one frame as the live server sends it (crane_viewer::scene::Frame).
  push(frame) {
    this.columns.time.push(frame.time);
    for (const name of Object.keys(WIDTHS)) {
      const value = frame[name];
      if (Array.isArray(value)) this.columns[name].push(...value.flat());
      else if (value !== undefined && value !== null) this.columns[name].push(value);
    }
  }

  // Drops every frame (a live session was reset).
  clear() {
    for (const name of ["time", ...Object.keys(WIDTHS)]) this.columns[name].length = 0;
  }

  // The index of the last frame at or before time t (the first one before the start).
  indexAt(t) {
    const times = this.columns.time;
    let low = 0;
    let high = times.length - 1;
    if (high < 0) return -1;
    if (t <= times[0]) return 0;
    while (low < high) {
      const middle = (low + high + 1) >> 1;
      if (times[middle] <= t) low = middle;
      else high = middle - 1;
    }
    return low;
  }
}
