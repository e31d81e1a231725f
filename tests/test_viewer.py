"""The 3D viewer in a real browser: `crane-cosim view` writes a replay page that headless
Chromium (playwright-core, tests/viewer/*.cjs) opens without a network; the tip, load and ghost
markers it draws — read back from the three.js scene graph — are where the results CSV says;
its picture changes around the load as the load moves. The full-scale knuckle-boom crane's page
draws its tip, load and cylinders where the FMU's outputs say, on screen, without ghost markers;
its live page refuses set-point moves and switches the controller's mode.

`cargo xtask test` installs Chromium and playwright-core (into target/documentation-check)."""
import csv
import json
import os
import shutil
import signal
import subprocess

import pytest

from conftest import ROOT

NODE_MODULES = ROOT / "target" / "documentation-check" / "node_modules"
SCREENSHOTS = ROOT / "target" / "viewer"
SCENARIO = ROOT / "scenarios" / "demo_profile1_compensated.json"
# The columns the view draws, and the crane's own tip output to check the drawn tip against.
VIEW_COLUMNS = [
    *(f"platform.ship.{dof}" for dof in ("x", "y", "z", "roll", "pitch", "yaw")),
    *(f"crane.joint.{joint}" for joint in ("theta2z", "theta3x", "theta4x")),
    "pendulum.load.x", "pendulum.load.y", "pendulum.load.z", "pendulum.theta_x", "pendulum.theta_y",
    "controller.est.load.x", "controller.est.load.y", "controller.est.load.z",
    "controller.sp.load.x", "controller.sp.load.y", "controller.sp.load.z",
]
TIP = ["crane.tip.x", "crane.tip.y", "crane.tip.z"]
SEEK_TIMES = [0.0, 30.0, 0.01, 10.5, 12.34, 47.77, 70.0]


def node_script(script, *args):
    """What tests/viewer/<script> printed as JSON."""
    if not (NODE_MODULES / "playwright-core").exists():
        pytest.fail(f"{NODE_MODULES}/playwright-core is missing: `cargo xtask test` installs it")
    node = shutil.which("node") or pytest.fail("node is missing: `cargo xtask test` installs npm and Node.js")
    done = subprocess.run([node, str(ROOT / "tests" / "viewer" / script), *map(str, args)], capture_output=True,
                          text=True, timeout=180, env=dict(os.environ, NODE_PATH=str(NODE_MODULES)))
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def scenario_recording(tmp_path, variables, **extra):
    """The compensated profile-1 demo as a scenario file recording `variables`."""
    scenario = json.loads(SCENARIO.read_text())
    scenario["system"] = str((SCENARIO.parent / scenario["system"]).resolve())
    scenario["record"] = {"variables": variables}
    scenario.update(extra)
    path = tmp_path / "scenario.json"
    path.write_text(json.dumps(scenario))
    return path


def read_rows(path):
    with open(path, newline="") as f:
        return {float(row["time"]): {k: float(v) for k, v in row.items()} for row in csv.DictReader(f)}


@pytest.fixture
def replay(master, tmp_path):
    """A replay page of the compensated demo under ship motion, and the CSV it was made from."""
    scenario = scenario_recording(tmp_path, VIEW_COLUMNS + TIP)
    results = tmp_path / "results.csv"
    subprocess.run([master, "run", scenario, "-o", results, "-q"], check=True)
    page = tmp_path / "replay.html"
    done = subprocess.run([master, "view", results, "-o", page], capture_output=True, text=True, check=True)
    assert "wrote" in done.stdout and "7001 frames" in done.stdout, done.stdout
    return page, read_rows(results)


def test_replay_draws_the_tip_and_load_where_the_results_say(replay):
    page, rows = replay
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    seen = node_script("replay.cjs", page, SCREENSHOTS / "replay", *SEEK_TIMES)
    assert not seen["console_errors"], seen["console_errors"]
    assert not seen["outside_requests"], seen["outside_requests"]
    assert seen["range"] == [0.0, 70.0]
    for seek in seen["seeks"]:
        row = rows[seek["requested"]]
        assert seek["time"] == pytest.approx(seek["requested"], abs=1e-9)
        for drawn, columns in (("tip", TIP), ("load", ["pendulum.load.x", "pendulum.load.y", "pendulum.load.z"]),
                               ("estimated_load", ["controller.est.load.x", "controller.est.load.y",
                                                   "controller.est.load.z"]),
                               ("setpoint", ["controller.sp.load.x", "controller.sp.load.y", "controller.sp.load.z"])):
            expected = [row[c] for c in columns]
            assert seek[drawn] == pytest.approx(expected, abs=1e-6), (seek["requested"], drawn, seek[drawn], expected)
    # The load swings from θx = -23° at t = 0 to hanging still under the tip by t = 30 s: the
    # pictures differ around both of its positions, not in the empty corner.
    assert min(seen["changed_around_load"]) > 0.05, seen["changed_around_load"]
    assert seen["changed_in_corner"] == 0
    # Playing moves the shown time on (how far depends on the machine's load: not asserted).
    assert 0.0 < seen["played_to"] < 70.0, seen["played_to"]
    print(f"viewer: {len(seen['seeks'])} seeks drawn within 1e-6 m of the CSV; around the load "
          f"{[round(c, 3) for c in seen['changed_around_load']]} of the pixels changed from t = 0 to 30 s; "
          f"playback at 8x reached t = {seen['played_to']:.1f} s in 1 s; screenshots {SCREENSHOTS}/replay-*.png")


def test_a_results_file_without_the_view_columns_is_refused_with_the_missing_names(master, tmp_path):
    results = tmp_path / "plain.csv"
    subprocess.run([master, "run", scenario_recording(tmp_path, ["pendulum.load.x", "pendulum.theta_x"]),
                    "-o", results, "-q"], check=True)
    done = subprocess.run([master, "view", results, "-o", tmp_path / "x.html"], capture_output=True, text=True)
    assert done.returncode == 1
    assert "has no column platform.ship.x, platform.ship.y" in done.stderr, done.stderr
    assert "controller.sp.load.z: record them (the scenario's \"record\" variables)" in done.stderr
    assert not (tmp_path / "x.html").exists()


def test_view_of_a_scenario_runs_it_with_the_view_variables_recorded(master, tmp_path):
    page = tmp_path / "run.html"
    done = subprocess.run([master, "view", SCENARIO, "-o", page, "--stop-time", "2"], capture_output=True,
                          text=True, check=True)
    assert "(201 frames, t = 0 to 2 s)" in done.stdout, done.stdout
    data = page.read_text().split('<script id="crane-data" type="application/json">')[1].split("</script>")[0]
    frames = json.loads(data)["frames"]
    assert len(frames["time"]) == 201 and len(frames["crane"]) == 201 * 12


RIGGING = ROOT / "scenarios" / "rigging_profile1_compensated.json"
RIGGING_SEEKS = [12.0, 15.5]


def test_a_riggings_hook_is_drawn_between_the_tip_and_the_load(master, tmp_path):
    """The rigging in place of the pendulum (docs/rigging.md): `view` of its scenario records the
    hook as well, and the page draws it where the rigging says, on the rope from the tip, with the
    sling on to the load; without a rigging the page draws no hook."""
    page = tmp_path / "rigging.html"
    subprocess.run([master, "view", RIGGING, "--stop-time", "16", "-o", page], capture_output=True, text=True,
                   check=True)
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    seen = node_script("replay.cjs", page, SCREENSHOTS / "rigging", *RIGGING_SEEKS)
    assert not seen["console_errors"] and not seen["outside_requests"], seen
    for seek in seen["seeks"]:
        hook, load, tip = seek["hook"], seek["load"], seek["tip"]
        assert hook is not None, seek
        # The sling (0.2 m) and the hoist rope (the crane's 0.7 m) as the rigging's defaults.
        assert distance(hook, load) == pytest.approx(0.2, abs=1e-6), seek
        assert distance(tip, hook) == pytest.approx(0.7, abs=0.01), seek
    plain = node_script("replay.cjs", page_of_plain_run(master, tmp_path), SCREENSHOTS / "no-hook", 12.0)
    assert plain["seeks"][0]["hook"] is None, plain["seeks"][0]


def page_of_plain_run(master, tmp_path):
    page = tmp_path / "plain.html"
    subprocess.run([master, "view", SCENARIO, "--stop-time", "13", "-o", page], capture_output=True, text=True,
                   check=True)
    return page


FULL_SCALE = ROOT / "scenarios" / "full_scale_profile1.json"
FULL_SCALE_TIP = ["knuckle_boom.tip.x", "knuckle_boom.tip.y", "knuckle_boom.tip.z"]
FULL_SCALE_SEEKS = [0.0, 24.0, 8.5, 30.0]
# The knuckle_boom FMU's cylinders' pin-to-pin length at stroke 0 (m): the OSP test crane's.
CYLINDER_MIN_LENGTH = 2.1


def distance(a, b):
    return sum((p - q) ** 2 for p, q in zip(a, b)) ** 0.5


def test_full_scale_replay_draws_the_knuckle_boom_crane_where_its_fmu_says(master, tmp_path):
    """The full-scale system's own recording (systems/full_scale.json's `record` list) makes a
    page of the knuckle-boom crane: the tip and the load drawn where the CSV says, the cylinders
    as long as the FMU's strokes say, no ghost markers, and the 15 m crane on screen at a size
    one can see."""
    results = tmp_path / "full_scale.csv"
    subprocess.run([master, "run", FULL_SCALE, "--stop-time", "30", "-o", results, "-q"], check=True)
    page = tmp_path / "full_scale.html"
    done = subprocess.run([master, "view", results, "-o", page], capture_output=True, text=True, check=True)
    assert "3001 frames" in done.stdout, done.stdout
    rows = read_rows(results)
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    seen = node_script("replay.cjs", page, SCREENSHOTS / "full-scale", *FULL_SCALE_SEEKS)
    assert not seen["console_errors"], seen["console_errors"]
    assert not seen["outside_requests"], seen["outside_requests"]
    assert seen["scale"] == "full" and seen["range"] == [0.0, 30.0]
    assert "estimated load" not in seen["legend"] and "set-point" not in seen["legend"], seen["legend"]
    assert seen["plots"][3] == "tip height (m)", seen["plots"]
    worst = {"tip": 0.0, "load": 0.0, "stroke": 0.0}
    for seek in seen["seeks"]:
        row = rows[seek["requested"]]
        assert seek["time"] == pytest.approx(seek["requested"], abs=1e-9)
        assert seek["estimated_load"] is None and seek["setpoint"] is None, seek
        worst["tip"] = max(worst["tip"], distance(seek["tip"], [row[c] for c in FULL_SCALE_TIP]))
        load = [row[f"pendulum.load.{axis}"] for axis in "xyz"]
        worst["load"] = max(worst["load"], distance(seek["load"], load))
        for (barrel_pin, barrel_end, rod_start, rod_pin), cylinder in zip(seek["cylinders"], ("boom", "jib")):
            # The rod comes out where the barrel ends, and the pins are as far apart as the stroke says.
            assert distance(barrel_end, rod_start) < 1e-6, (barrel_end, rod_start)
            stroke = distance(barrel_pin, rod_pin) - CYLINDER_MIN_LENGTH
            worst["stroke"] = max(worst["stroke"], abs(stroke - row[f"knuckle_boom.stroke.{cylinder}"]))
        # The tip and the load on the canvas, the 10 m of rope between them a good part of its height.
        width, height = seek["canvas"]["width"], seek["canvas"]["height"]
        for point in (seek["tip_on_screen"], seek["load_on_screen"]):
            assert 0 < point["x"] < width and 0 < point["y"] < height, (point, width, height)
        rope = distance(*[[p["x"], p["y"]] for p in (seek["tip_on_screen"], seek["load_on_screen"])])
        assert rope > 0.15 * height, (rope, height)
    assert max(worst.values()) < 1e-6, worst
    print(f"full-scale viewer: {len(seen['seeks'])} seeks, tip within {worst['tip']:.1e} m of knuckle_boom.tip.*, "
          f"load within {worst['load']:.1e} m, cylinders within {worst['stroke']:.1e} m of the strokes; "
          f"screenshots {SCREENSHOTS}/full-scale-*.png")


def live_scenario(tmp_path):
    """The compensated closed loop in still water with the load at rest, the controller active from the start."""
    scenario = json.loads(SCENARIO.read_text())
    scenario["system"] = str((SCENARIO.parent / scenario["system"]).resolve())
    scenario["start"] = {"controller.mode": 2, "controller.feedback": 1, "controller.active_from": 0.0}
    path = tmp_path / "live.json"
    path.write_text(json.dumps(scenario))
    return path


class LiveSession:
    """`crane-cosim live` on a free port, ended with SIGINT (Ctrl-C) on leaving."""

    def __init__(self, master, scenario, *options):
        self.process = subprocess.Popen([master, "live", scenario, "--port", "0", "--stop-time", "120", *options],
                                        stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
        self.address = self.process.stdout.readline().split()[1]
        assert self.address.startswith("http://127.0.0.1:"), self.address

    def __enter__(self):
        return self

    def __exit__(self, *_):
        self.process.send_signal(signal.SIGINT)
        self.out, self.err = self.process.communicate(timeout=30)


def test_live_key_presses_move_the_setpoint_and_the_load_follows(master, tmp_path):
    record = tmp_path / "session.csv"
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    with LiveSession(master, live_scenario(tmp_path), "--record", record) as live:
        seen = node_script("live.cjs", live.address, SCREENSHOTS / "live.png")
    assert live.process.returncode == 0, live.err
    out = live.out
    assert not seen["console_errors"] and not seen["outside_requests"], seen
    before, after = seen["before"]["setpoint"], seen["after"]["setpoint"]
    assert after == pytest.approx([before[0] + 0.1, before[1], before[2] - 0.05], abs=1e-9)

    rows = read_rows(record)
    times = sorted(rows)
    moved_at = seen["moved_at"]
    at = lambda t: rows[min(times, key=lambda s: abs(s - t))]
    start, end = at(moved_at), at(moved_at + 5.0)
    # The recorded set-point moved as commanded, north and up (W z points down) ...
    assert end["controller.sp.load.x"] - start["controller.sp.load.x"] == pytest.approx(0.1, abs=1e-9)
    assert end["controller.sp.load.z"] - start["controller.sp.load.z"] == pytest.approx(-0.05, abs=1e-9)
    assert end["controller.sp_in.tip.x"] - start["controller.sp_in.tip.x"] == pytest.approx(0.1, abs=1e-9)
    # ... and within 5 s the load followed most of the way in both directions.
    north = end["pendulum.load.x"] - start["pendulum.load.x"]
    up = start["pendulum.load.z"] - end["pendulum.load.z"]
    assert north > 0.07 and up > 0.03, (north, up)
    # Compensation was switched off and on again: the controller ran in mode 1 for a while.
    # (The page learns of the switch back before the step that applies it is recorded, so the
    # order of modes is checked over the whole session, not against the page's time.)
    modes = [rows[t]["controller.mode"] for t in times]
    switches = [m for i, m in enumerate(modes) if i == 0 or m != modes[i - 1]]
    assert switches == [2.0, 1.0, 2.0] and end["controller.mode"] == 2.0, switches
    assert "pacing:" in out and "steps at 1x real time" in out
    pacing = json.loads(record.with_suffix(".summary.json").read_text())["pacing"]
    assert pacing["steps"] >= 700 and pacing["max_ms"] >= pacing["p99_ms"] >= 0.0
    print(f"live: set-point moved north 0.1 m and up 0.05 m at t = {moved_at:.2f} s; the load followed "
          f"{north * 1000:.0f} mm north and {up * 1000:.0f} mm up within 5 s; {out.strip().splitlines()[-1]}")


def test_live_pause_gamepad_and_reset(master, tmp_path):
    record = tmp_path / "session.csv"
    with LiveSession(master, live_scenario(tmp_path), "--record", record) as live:
        seen = node_script("reset.cjs", live.address)
    assert live.process.returncode == 0, live.err
    assert not seen["console_errors"], seen["console_errors"]
    assert seen["paused"]["paused"] and seen["still_paused"]["time"] == seen["paused"]["time"]
    assert not seen["resumed"]["paused"] and seen["resumed"]["time"] > seen["paused"]["time"]
    # The gamepad: the left stick forward moved the set-point north only, button A switched compensation off.
    stick, initial = seen["stick"]["setpoint"], seen["initial"]["setpoint"]
    assert stick[0] > initial[0] + 0.01 and stick[1:] == initial[1:], (stick, initial)
    assert seen["stick"]["compensation"] and not seen["button"]["compensation"]
    assert seen["moved"]["setpoint"][1] == pytest.approx(initial[1] + 0.01, abs=1e-12)
    # The reset run starts again from t = 0 with the controller's fixed set-point.
    assert seen["reset"]["time"] < seen["moved"]["time"] and seen["reset"]["time"] < 1.0
    assert seen["reset"]["setpoint"] == seen["initial"]["setpoint"]
    # The reset keeps the first run's recording and records the new run to session-2.csv.
    second = tmp_path / "session-2.csv"
    assert seen["initial"]["recording"] == str(record) and seen["reset"]["recording"] == str(second)
    first_run, second_run = read_rows(record), read_rows(second)
    assert max(first_run) >= seen["moved"]["time"] and min(second_run) == 0.0, (max(first_run), min(second_run))


def test_live_full_scale_crane_refuses_moves_and_switches_its_controllers_mode(master, tmp_path):
    """The full-scale crane live: its controller has no set-point, so a move is refused with the
    reason and the page shows none; C switches the controller between compensation (mode 2) and
    positioning (mode 1); the crane is drawn with its cylinders and without ghost markers."""
    record = tmp_path / "session.csv"
    SCREENSHOTS.mkdir(parents=True, exist_ok=True)
    scenario = ROOT / "scenarios" / "full_scale_profile1_compensated.json"
    with LiveSession(master, scenario, "--record", record) as live:
        seen = node_script("live_full_scale.cjs", live.address, SCREENSHOTS / "live-full-scale.png")
    assert live.process.returncode == 0, live.err
    assert not seen["console_errors"] and not seen["outside_requests"], seen
    assert seen["scale"] == "full"
    before, after = seen["before"], seen["after"]
    assert before["setpoint"] is None and before["compensation"] is True, before
    assert after["refused"].startswith("no set-point to move: the full-scale crane's controller"), after
    assert after["compensation"] is False and not seen["compensation_hidden"]
    assert "no set-point to move" in seen["status"] and "load set-point" not in seen["status"], seen["status"]
    drawn = seen["drawn"]
    assert drawn["estimated_load"] is None and drawn["setpoint"] is None and len(drawn["cylinders"]) == 2, drawn
    rows = read_rows(record)
    # The winch compensates the heave, so the rope is not 10 m when the page is read: the drawn
    # tip-to-load distance must be the hoist length recorded at the drawn time (within the rope's
    # travel over one 10 ms step at the winch's rated rope speed, ~0.5 m/s).
    shown_at = min(rows, key=lambda t: abs(t - drawn["time"]))
    assert abs(shown_at - drawn["time"]) < 1e-9, (shown_at, drawn["time"])
    hoist = rows[shown_at]["knuckle_boom.lp"]
    assert distance(drawn["tip"], drawn["load"]) == pytest.approx(hoist, abs=0.01), (drawn, hoist)
    modes = [rows[t]["knuckle_boom_controller.mode"] for t in sorted(rows)]
    assert modes[0] == 2.0 and modes[-1] == 1.0, (modes[0], modes[-1])
