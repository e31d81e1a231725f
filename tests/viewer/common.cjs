// Shared by the browser checks: headless Debian Chromium with WebGL in software (SwiftShader)
// for the viewer, a page that records console errors and every request leaving `allowed` (also
// used by tests/documentation/inspect.cjs), and
// the fraction of pixels of the 3D view that differ between two moments around a point.
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

module.exports = { launch, watchedPage, sameServer };
