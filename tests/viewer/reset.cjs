// Pauses, resumes and resets a live session of `crane-cosim live` from its page in headless
// Chromium, and drives it with a gamepad: Space must stop the simulated time and Space again
// restart it; the left stick pushed forward must move the load set-point north and button A
// switch compensation off; after a set-point move, R must start the run again from t = 0 with
// the controller's fixed set-point. Prints, as JSON, what the page showed at each stage.
//
// Headless Chromium has no gamepad: the page gets a stand-in through navigator.getGamepads()
// (the standard mapping: axes[1] < 0 is the left stick forward, buttons[0] is A).
//
//   node reset.cjs <page URL>
const { driveLive } = require("./common.cjs");

// The stand-in gamepad, before the page's own scripts run.
const gamepad = (page) =>
  page.addInitScript(() => {
    window.pad = { axes: [0, 0, 0, 0], buttons: Array.from({ length: 16 }, () => ({ pressed: false })) };
    navigator.getGamepads = () => [window.pad];
  });

const [url] = process.argv.slice(2);
driveLive(
  url,
  async ({ page, console_errors, until, started }) => {
    const look = () => page.evaluate(() => ({ time: craneViewer.time(), ...craneViewer.session() }));
    await started(1.0);
    const initial = await look();
    await page.keyboard.press(" ");
    await until(() => craneViewer.session().paused);
    const paused = await look();
    await page.waitForTimeout(1000);
    const still_paused = await look();
    await page.keyboard.press(" ");
    await until((t) => craneViewer.time() > t + 0.5, still_paused.time);
    const resumed = await look();
    await page.evaluate(() => (window.pad.axes[1] = -1));
    await until((x) => craneViewer.session().setpoint[0] > x + 0.01, resumed.setpoint[0]);
    await page.evaluate(() => (window.pad.axes[1] = 0));
    const stick = await look();
    await page.evaluate(() => (window.pad.buttons[0].pressed = true));
    await until(() => craneViewer.session().compensation === false);
    await page.evaluate(() => (window.pad.buttons[0].pressed = false));
    const button = await look();
    await page.keyboard.press("ArrowRight");
    await until((y) => craneViewer.session().setpoint[1] > y, initial.setpoint[1]);
    const moved = await look();
    await page.keyboard.press("r");
    // Right after the reset the page holds no frame yet and time() is null, which JavaScript
    // compares as 0: wait for the first frame of the new run.
    await until((t) => {
      const now = craneViewer.time();
      return typeof now === "number" && now < t;
    }, moved.time);
    const reset = await look();
    process.stdout.write(JSON.stringify({ initial, paused, still_paused, resumed, stick, button, moved, reset, console_errors }));
  },
  gamepad,
);
