"""The crane_cosim wheel (`cargo xtask wheel`, target/wheels/): `run` gives the numbers of
`crane-cosim run`'s CSV bit for bit and its units, the FMUs shipped inside open in FMPy, and an
error is a SimulationError with the message the command prints.

The wheel is installed (without its dependencies, which this venv has) into a temporary folder
put first on sys.path, so this venv is left as it was. CRANE_COSIM_WHEEL names the wheel; by
default the one wheel in target/wheels/.
"""
import csv
import json
import os
import pathlib
import struct
import subprocess
import sys
import threading
import time

import fmpy
import pytest

from conftest import ROOT, fmu_names

SCENARIO = ROOT / "scenarios" / "demo_still_compensated.json"


def wheel() -> pathlib.Path:
    if "CRANE_COSIM_WHEEL" in os.environ:
        return pathlib.Path(os.environ["CRANE_COSIM_WHEEL"])
    wheels = sorted((ROOT / "target" / "wheels").glob("crane_cosim-*.whl"))
    if len(wheels) != 1:
        pytest.fail(f"expected one wheel in target/wheels, found {len(wheels)}: run `cargo xtask wheel` first")
    return wheels[0]


@pytest.fixture(scope="module")
def crane_cosim(tmp_path_factory):
    folder = tmp_path_factory.mktemp("wheel")
    subprocess.run(
        [sys.executable, "-m", "pip", "install", "--quiet", "--no-deps", "--no-index", "--target", folder, wheel()],
        check=True,
    )
    sys.path.insert(0, str(folder))
    try:
        import crane_cosim

        assert pathlib.Path(crane_cosim.__file__).is_relative_to(folder), "imported a crane_cosim not from the wheel"
        yield crane_cosim
    finally:
        sys.path.remove(str(folder))
        for name in [name for name in sys.modules if name == "crane_cosim" or name.startswith("crane_cosim.")]:
            del sys.modules[name]


def bits(value: float) -> bytes:
    return struct.pack("<d", value)


def cli_csv(master, tmp_path, system, *options):
    """The CSV `crane-cosim run` writes (header, rows as text) and its summary's units."""
    output = tmp_path / "cli.csv"
    subprocess.run([master, "run", system, "-o", output, "-q", *options], check=True, cwd=ROOT)
    with output.open(newline="") as file:
        rows = list(csv.reader(file))
    summary = json.loads(output.with_suffix(".summary.json").read_text())
    return rows[0], rows[1:], {column["name"]: column["unit"] for column in summary["columns"]}


def assert_same_bits(frame, header, rows):
    assert list(frame.columns) == header
    assert len(frame) == len(rows)
    for index, name in enumerate(header):
        column = frame[name].to_numpy()
        differing = [i for i, row in enumerate(rows) if bits(float(row[index])) != bits(float(column[i]))]
        assert not differing, f"{name}: {len(differing)} rows differ from the CSV, first at row {differing[0]}"
    print(f"{len(rows)} rows x {len(header)} columns equal to the CSV bit for bit")


def test_run_is_the_cli_csv_bit_for_bit(crane_cosim, master, tmp_path):
    header, rows, units = cli_csv(master, tmp_path, SCENARIO, "--stop-time", "12")
    frame = crane_cosim.run(SCENARIO, stop_time=12)
    assert_same_bits(frame, header, rows)
    assert frame.attrs["units"] == {"time": "s", **units}


def test_overrides_are_the_cli_options(crane_cosim, master, tmp_path):
    options = ["--stop-time", "3", "--start", "pendulum.theta_x0=-0.2", "--record", "crane.joint.*"]
    header, rows, _ = cli_csv(master, tmp_path, SCENARIO, *options)
    frame = crane_cosim.run(SCENARIO, stop_time=3, start={"pendulum.theta_x0": -0.2}, record=["crane.joint.*"])
    assert_same_bits(frame, header, rows)


def test_one_fmu_alone_is_the_cli_run(crane_cosim, master, tmp_path):
    fmu = crane_cosim.fmu_path("pendulum")
    header, rows, _ = cli_csv(master, tmp_path, fmu, "--stop-time", "5", "--start", "theta_x0=-0.4", "--record", "theta_*")
    frame = crane_cosim.run(fmu, stop_time=5, start={"theta_x0": -0.4}, record=["theta_*"])
    assert_same_bits(frame, header, rows)


@pytest.mark.parametrize("fmi_version", [2, 3])
def test_shipped_fmus_open_in_fmpy(crane_cosim, fmi_version):
    # Every packaged FMU (the test-scale rig, the full-scale crane and the rigging), in both versions.
    assert crane_cosim.fmu_names(fmi_version) == sorted(fmu_names())
    for name in crane_cosim.fmu_names(fmi_version):
        description = fmpy.read_model_description(str(crane_cosim.fmu_path(name, fmi_version)))
        assert description.fmiVersion == f"{fmi_version}.0"
        assert description.coSimulation.modelIdentifier == name
    with pytest.raises(FileNotFoundError, match="no FMI 2 FMU named 'pendulm'.*pendulum"):
        crane_cosim.fmu_path("pendulm")


@pytest.mark.parametrize(
    "start, option",
    [({"pendulum.theta_x0": "abc"}, "pendulum.theta_x0=abc"), ({"pendlum.theta_x0": 1}, "pendlum.theta_x0=1")],
)
def test_errors_are_the_cli_messages(crane_cosim, master, tmp_path, start, option):
    cli = subprocess.run(
        [master, "run", SCENARIO, "-o", tmp_path / "x.csv", "-q", "--stop-time", "1", "--start", option],
        capture_output=True,
        text=True,
        cwd=ROOT,
    )
    assert cli.returncode == 1
    with pytest.raises(crane_cosim.SimulationError) as raised:
        crane_cosim.run(SCENARIO, stop_time=1, start=start)
    # The same message, each front end naming the setting its own way.
    (name,) = start
    assert f"--start {name}" in cli.stderr
    assert f"error: {raised.value}\n" == cli.stderr.replace(f"--start {name}", f'start={{"{name}": …}}')
    print(raised.value)


def test_the_interpreter_runs_other_threads_during_a_run(crane_cosim):
    ticks = []
    done = threading.Event()

    def tick():
        while not done.is_set():
            ticks.append(time.perf_counter())
            time.sleep(0.005)

    ticker = threading.Thread(target=tick)
    ticker.start()
    try:
        began = time.perf_counter()
        crane_cosim.run(SCENARIO, stop_time=600)
        ended = time.perf_counter()
    finally:
        done.set()
        ticker.join()
    during = [t for t in ticks if began < t < ended]
    print(f"{len(during)} ticks of another thread during a run of {ended - began:.2f} s")
    assert len(during) >= 10


PROFILE1 = ROOT / "scenarios" / "demo_profile1_compensated.json"


def same_frames(frame, reference):
    """Equal columns, units and bits."""
    assert list(frame.columns) == list(reference.columns)
    assert frame.attrs["units"] == reference.attrs["units"]
    assert frame.shape == reference.shape
    differing = (frame.to_numpy().view("<u8") != reference.to_numpy().view("<u8")).any(axis=1)
    assert not differing.any(), f"{differing.sum()} rows differ, first at t = {frame['time'][differing.argmax()]}"


def test_stepping_in_pieces_records_the_one_shot_run(crane_cosim):
    # Ship profile 1, compensation and sensor noise: every instance's state carries through.
    reference = crane_cosim.run(PROFILE1, stop_time=12)
    with crane_cosim.Simulation(PROFILE1, stop_time=12) as simulation:
        assert (simulation.steps, simulation.step_size, simulation.stop_time) == (1200, 0.01, 12.0)
        assert simulation.step(7) == pytest.approx(0.07)
        assert simulation.advance_to(10.005) == pytest.approx(10.01)
        while not simulation.done:
            simulation.step()
            simulation.get_reals(["pendulum.theta_x", "controller.est.theta_x"])
        assert simulation.time == 12.0
        same_frames(simulation.results(), reference)
        with pytest.raises(crane_cosim.SimulationError, match="nothing left to step"):
            simulation.step()


def test_a_restored_simulation_continues_bit_for_bit(crane_cosim):
    reference = crane_cosim.run(PROFILE1, stop_time=12)
    with crane_cosim.Simulation(PROFILE1, stop_time=12) as simulation:
        simulation.advance_to(10.5)
        saved = simulation.save()
        assert (saved.time, saved.steps_completed) == (10.5, 1050)
        assert len(saved.instance_states()) == 6
        # A fixed parameter cannot change after initialization: the FMU refuses, the message says so.
        with pytest.raises(crane_cosim.SimulationError, match="cannot set pendulum.theta_x0"):
            simulation.set({"pendulum.theta_x0": 0.3})
        # Run on to the end, then go back: every instance and the master return to 10.5 s.
        simulation.run()
        simulation.restore(saved)
        assert simulation.time == 10.5 and len(simulation.results()) == 1051
        simulation.run()
        same_frames(simulation.results(), reference)
        # Restored into a second simulation of the same system, it continues the same way.
        with crane_cosim.Simulation(PROFILE1, stop_time=12) as other:
            other.restore(saved)
            other.run()
            assert other.get("pendulum.theta_x") == reference["pendulum.theta_x"].iloc[-1]


def test_variables_are_read_and_written_by_name(crane_cosim):
    fmu = crane_cosim.fmu_path("pendulum")
    with crane_cosim.Simulation(fmu, stop_time=2, start={"theta_x0": -0.4}) as pendulum:
        assert pendulum.get("theta_x0") == -0.4 and pendulum.get("pendulum.theta_x") == -0.4
        assert ("pendulum.theta_x", "output", "real", "rad") in pendulum.variables()
        with pytest.raises(crane_cosim.SimulationError, match="instance 'pendulum' has no variable 'theta_z'"):
            pendulum.get("theta_z")
        pendulum.run()
        swing = pendulum.get("theta_x")
    # The free pendulum's small-angle period is 2*pi*sqrt(l/g): it has swung away from -0.4 rad.
    assert -0.4 < swing < 0.4
    with crane_cosim.Simulation(SCENARIO, stop_time=1) as loop:
        assert isinstance(loop.get("controller.active"), bool)
        assert isinstance(loop.get("controller.mode"), int)
        with pytest.raises(crane_cosim.SimulationError, match="unknown instance 'pendlum'.*platform, crane"):
            loop.get("pendlum.theta_x")
    with pytest.raises(crane_cosim.SimulationError, match="closed"):
        loop.step()


def test_the_campaign_is_the_clis(crane_cosim, master, tmp_path):
    # Table 7.2's profile-1 pair in both variants: the metrics are those of `crane-cosim campaign`.
    selection = ["--tests", "81,89", "--variants", "1,2", "-q"]
    subprocess.run([master, "campaign", *selection, "-o", tmp_path / "cli"], check=True, cwd=ROOT)
    result = crane_cosim.campaign("81,89", (1, 2), output=tmp_path / "python", system=ROOT / "systems" / "closed_loop.json")
    assert result.failures == []
    cli_metrics = (tmp_path / "cli" / "metrics.csv").read_text()
    python_metrics = (tmp_path / "python" / "metrics.csv").read_text()
    wall = [i for i, name in enumerate(cli_metrics.splitlines()[0].split(",")) if "wall" in name]

    def without_wall_times(text):
        return [[cell for i, cell in enumerate(line.split(",")) if i not in wall] for line in text.splitlines()]

    assert without_wall_times(python_metrics) == without_wall_times(cli_metrics)
    assert list(result.runs["id"]) == ["081-1", "081-2", "089-1", "089-2"]
    rows = result.tables[result.tables["table"].str.contains("ship motion")]
    print(rows[["metric", "variant", "thesis", "reduction", "pairs", "band", "met"]].to_string(index=False))
    # Eq. 7.1 on the one pair: the RMSE reduction of 089 (compensated) against 081 (inverse kinematics).
    for variant in (1, 2):
        rmse = result.runs.set_index("id")["rmse_m"]
        expected = 100.0 * (rmse[f"081-{variant}"] - rmse[f"089-{variant}"]) / rmse[f"081-{variant}"]
        row = rows[(rows["metric"] == "rmse") & (rows["variant"] == variant)].iloc[0]
        assert row["pairs"] == 1 and row["reduction"] == pytest.approx(expected, rel=1e-9)
    with pytest.raises(crane_cosim.SimulationError, match="variant 4"):
        crane_cosim.campaign("81", (4,), output=tmp_path / "bad")
    # Every option of the command, refused in the package's own words.
    with pytest.raises(crane_cosim.SimulationError, match='attitude_filter "kalman"'):
        crane_cosim.campaign("81", (2,), output=tmp_path / "bad", attitude_filter="kalman")
    with pytest.raises(crane_cosim.SimulationError, match="cannot read start_file .*nowhere.json"):
        crane_cosim.campaign("81", (1,), output=tmp_path / "bad", start_file=tmp_path / "nowhere.json")
    # The one pair 081/089 judges only the bands with data: the RMSE ones; a check with no pair at
    # all must fail rather than pass.
    with pytest.raises(crane_cosim.SimulationError, match="^check: no acceptance band.*tests=\"20,60\""):
        crane_cosim.campaign("81", (1,), output=tmp_path / "one", thesis_init=True, check=True)


def test_a_campaign_on_a_catalogue_crane_is_the_clis(crane_cosim, master, tmp_path):
    # The full-scale still-water pair 097/101 (variant 1) on the 10 t AHC crane: `crane=` gives
    # both FMUs the description as `--crane` does, and the metrics differ from the default crane's.
    selection = ["--scale", "full", "--tests", "97,101", "--variants", "1", "-q"]
    subprocess.run([master, "campaign", *selection, "--crane", "ahc_10t", "-o", tmp_path / "cli"], check=True, cwd=ROOT)
    subprocess.run([master, "campaign", *selection, "-o", tmp_path / "default"], check=True, cwd=ROOT)
    result = crane_cosim.campaign("97,101", (1,), output=tmp_path / "python", full_scale=True, crane="ahc_10t",
                                  system=ROOT / "systems" / "full_scale_ahc.json")
    assert result.failures == []
    metrics = {name: (tmp_path / name / "metrics.csv").read_text() for name in ("cli", "python", "default")}
    wall = [i for i, name in enumerate(metrics["cli"].splitlines()[0].split(",")) if "wall" in name]

    def without_wall_times(text):
        return [[cell for i, cell in enumerate(line.split(",")) if i not in wall] for line in text.splitlines()]

    assert without_wall_times(metrics["python"]) == without_wall_times(metrics["cli"])
    assert without_wall_times(metrics["python"]) != without_wall_times(metrics["default"])
    assert '"ahc_10t"' in (tmp_path / "python" / "report.md").read_text()
    with pytest.raises(crane_cosim.SimulationError, match=r"crane description \(crane\).*add full_scale=True"):
        crane_cosim.campaign("97", (1,), output=tmp_path / "bad", crane="ahc_10t")


def test_a_sweep_is_the_clis(crane_cosim, master, tmp_path):
    # tests/sweep/study.json: eight short closed-loop cases over two parameters, three metrics.
    study = ROOT / "tests" / "sweep" / "study.json"
    subprocess.run([master, "sweep", "run", study, "-o", tmp_path / "cli", "-q"], check=True)
    subprocess.run([master, "sweep", "collect", tmp_path / "cli"], check=True, capture_output=True)
    result = crane_cosim.sweep(study, output=tmp_path / "python", jobs=1)
    assert (result.done, result.failed, result.skipped) == (8, 0, 0)
    assert (tmp_path / "python" / "results.csv").read_text() == (tmp_path / "cli" / "results.csv").read_text()
    assert list(result.cases.columns[:3]) == ["case", "seed", "status"] and len(result.cases) == 8
    again = crane_cosim.sweep(study, output=tmp_path / "python")
    assert (again.done, again.skipped) == (0, 8)
    with pytest.raises(crane_cosim.SimulationError, match="nowhere.json"):
        crane_cosim.sweep(tmp_path / "nowhere.json", output=tmp_path / "none")


def test_a_tuning_is_the_clis(crane_cosim, master, tmp_path):
    # The repository's reduced tuning cut to two generations, its system given absolutely.
    tuning = json.loads((ROOT / "studies" / "tuning" / "reduced.json").read_text())
    tuning["system"] = str(ROOT / "systems" / "closed_loop.json")
    tuning["optimizer"]["generations"] = 2
    file = tmp_path / "tuning.json"
    file.write_text(json.dumps(tuning))
    subprocess.run([master, "tune", file, "-o", tmp_path / "cli", "-q"], check=True, cwd=ROOT)
    result = crane_cosim.tune(file, output=tmp_path / "python", jobs=1)
    cli_best = json.loads((tmp_path / "cli" / "best.json").read_text())
    python_best = json.loads((tmp_path / "python" / "best.json").read_text())
    assert python_best["start"] == cli_best["start"] and result.report == tmp_path / "python" / "report.md"
    assert f"candidate {result.best} of" in cli_best["description"] and result.report.is_file()
    with pytest.raises(crane_cosim.SimulationError, match="nowhere.json"):
        crane_cosim.tune(tmp_path / "nowhere.json", output=tmp_path / "none")
