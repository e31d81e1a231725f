// Shared by the browser checks: headless Debian Chromium with WebGL in software (SwiftShader)
// for the viewer, a page that records console errors and every request leaving `allowed` (also
// used by tests/documentation/inspect.cjs), and
// the fraction of pixels of the 3D view that differ between two moments around a point, and the
// frame of the scripts that drive a live session.
const { chromium } = require("playwright-core");

async function launch() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || "/usr/bin/chromium",
    args: [
      "--headless",
      "--no-sandbox",
      "--disable-background-networking",
      "--use-angle=swiftshader",
      "--enable-unsafe-swiftshader",
    ],
  });
}

// A page that notes console errors and any request whose URL does not start with `allowed`.
async function watchedPage(browser, allowed) {
  const page = await browser.newPage({ viewport: { width: 1280, height: 900 } });
  const console_errors = [];
  const outside_requests = [];
  page.on("console", (message) => message.type() === "error" && console_errors.push(message.text()));
  page.on("pageerror", (error) => console_errors.push(String(error)));
  page.on("request", (request) => {
    if (!allowed.some((prefix) => request.url().startsWith(prefix))) outside_requests.push(request.url());
  });
  return { page, console_errors, outside_requests };
}

// The prefixes of a live session's own page and socket (whatever their query, e.g. the token).
function sameServer(url) {
  const origin = new URL(url).origin;
  return [`${origin}/`, `${origin.replace("http", "ws")}/`];
}

// Opens the page of the live session at `url` in a watched page (after `init(page)`, if given),
// runs `drive` on it and closes the browser; a failure is printed with its stack and ends the
// process with status 1. `drive` gets the page, the console errors and outside requests it
// records, and `session()` (the viewer's session state), `until(condition, argument)` (waits up
// to 60 s for `condition(argument)` in the page) and `started(t)` (waits for the session to be
// connected and its simulated time to reach `t` s).
function driveLive(url, drive, init) {
  const run = async () => {
    const browser = await launch();
    try {
      const { page, console_errors, outside_requests } = await watchedPage(browser, sameServer(url));
      if (init) await init(page);
      await page.goto(url);
      const session = () => page.evaluate(() => craneViewer.session());
      const until = (condition, argument) => page.waitForFunction(condition, argument, { timeout: 60_000 });
      const started = (t) =>
        until((t) => window.craneViewer && craneViewer.session().connected && craneViewer.time() >= t, t);
      await drive({ page, console_errors, outside_requests, session, until, started });
    } finally {
      await browser.close();
    }
  };
  run().catch((error) => {
    console.error(error.stack || String(error));
    process.exit(1);
  });
}

module.exports = { launch, watchedPage, sameServer, driveLive };
