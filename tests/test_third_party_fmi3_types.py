"""An FMI 3.0 FMU with arrays and every numeric type runs in crane-cosim element by element, as in FMPy.

`types3.fmu` is compiled here with gcc from third_party/types3.c against FMPy's FMI 3.0 headers: a
Co-Simulation-only FMU exporting every function of fmi3Functions.h, with a Float64 input array
`u` (3), a Float64 output matrix `m` (2x2), a Float32 parameter and output, Int8, UInt8, Int16 and
UInt16 parameters and outputs, UInt32, Int64 and UInt64 outputs within a 32-bit signed integer, an
Int64 output `big` that leaves it once the time reaches the parameter `overflow_time`, an
Enumeration output and an Int32 parameter array `offsets` (2). FMPy validates it, and its results
equal, bit for bit, those of a model of the FMU written here in Python.

crane-cosim shows an array `x` element by element, `x[1]`, `x[2]`, … (1-based; `m[1,1]`,
`m[1,2]`, `m[2,1]`, `m[2,2]` row-major), recorded, set with `--start 'x[2]=…'`, fed from an
inputs file and connected in system files; Float32 reads as a Real (exactly widened) and every
integer type as an Integer. Run alone, with the inputs from a CSV file and start values, it
records FMPy's values bit for bit (Float32 widened to float64). It refuses, naming the variable
and the value: a Float32 start value that is not exactly a float32, an integer start value outside
the variable's type, and an Int64 output beyond a 32-bit signed integer (the run ends with an
error at the step it occurs). It refuses an FMU with a Binary or Clock variable, or an array
whose dimension is a structural parameter, naming the variable.
"""
import csv
import itertools
import json
import math
import pathlib
import re
import subprocess

import fmpy
import numpy as np
import pytest
from fmpy import read_model_description, simulate_fmu
from fmpy.validation import validate_fmu

from test_third_party import compile_fmu, exported_functions
from test_third_party_fmi3 import assert_refused, with_variable

TYPES3 = "types3"
X86_64_LINUX = "x86_64-linux"
STEP, STOP = 0.1, 2.0
TIMES = np.arange(round(STOP / STEP) + 1) * STEP  # k·h, as FMPy and crane-cosim step
# u on the grid: the inputs file has a row on every communication point, so both masters set
# exactly these values (linear interpolation at a row's time gives its value).
U = np.stack([np.sin(TIMES), np.cos(3 * TIMES), TIMES * TIMES - 1], axis=1)
# The FMU's defaults (types3.xml) and the start values of the second run (extremes of the types:
# k_i8 - 20 = -128, k_u8 + 20 = 255, 20 k_i16 = 32000, k_u16 + 20 000 = 65 535 at t = 2 s).
DEFAULTS = {"gain": 1.5, "k_i8": -100, "k_u8": 200, "k_i16": -1000, "k_u16": 40000, "overflow_time": 10.0,
            "offsets": [3, -4]}
CHANGED = {"gain": 0.5, "k_i8": -108, "k_u8": 235, "k_i16": 1600, "k_u16": 45535, "offsets[2]": 7}
INTEGER_TYPES = {"Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32", "Int64", "UInt64", "Enumeration"}


@pytest.fixture(scope="module")
def fmu(tmp_path_factory):
    return compile_fmu(tmp_path_factory.mktemp("types3"), TYPES3, "fmi3Functions.h", X86_64_LINUX)


def header_functions():
    """The function names fmi3Functions.h declares (FMI3_Export fmi3…TYPE fmi3…;)."""
    header = pathlib.Path(fmpy.__file__).parent / "c-code" / "fmi3Functions.h"
    return re.findall(r"^FMI3_Export\s+\w+TYPE\s+(\w+);", header.read_text(), re.MULTILINE)


def elements(variable):
    """[(crane-cosim's name of each element, its index in FMPy's array or None)] of a variable:
    `name` for a scalar, `name[i]` / `name[i,j]` (1-based, row-major) for an array."""
    if not variable.shape:
        return [(variable.name, None)]
    return [(f"{variable.name}[{','.join(str(i + 1) for i in index)}]", index)
            for index in itertools.product(*(range(n) for n in variable.shape))]


def outputs(model):
    return [v for v in model.modelVariables if v.causality == "output"]


def output_elements(model):
    """[(element name, variable, index)] of every output element, in the description's order."""
    return [(name, v, index) for v in outputs(model) for name, index in elements(v)]


def fmpy_value(result_row, variable, index):
    """An element of FMPy's result row as a Python float (exactly widened) or int."""
    value = result_row[variable.name]
    if index is not None:
        value = value[index]
    return int(value) if variable.type in INTEGER_TYPES else float(np.float64(value))


def csv_value(text, variable):
    return int(text) if variable.type in INTEGER_TYPES else float(text)


def fmpy_start(start):
    """crane-cosim's start values (`offsets[2]`) as FMPy takes them (`offsets`, the whole array)."""
    values = {name: value for name, value in start.items() if "[" not in name}
    for name, value in start.items():
        if "[" in name:
            array, index = name[:-1].split("[")
            values.setdefault(array, list(DEFAULTS[array]))[int(index) - 1] = value
    return values


def run_fmpy(fmu, start, u=U, stop=STOP):
    model = read_model_description(str(fmu))
    signal = np.zeros(len(TIMES), dtype=[("time", np.float64), ("u", np.float64, (3,))])
    signal["time"], signal["u"] = TIMES, u
    return simulate_fmu(str(fmu), start_time=0.0, stop_time=stop, step_size=STEP, output_interval=STEP,
                        input=signal, start_values=fmpy_start(start), output=[v.name for v in outputs(model)])


def model_rows(start, u=U, times=TIMES):
    """The FMU's outputs at each communication point, computed here as types3.c computes them:
    {element name: value} per row. The FMU's time after a step is t_k + (t_{k+1} - t_k)."""
    p = {**DEFAULTS, **fmpy_start(start)}
    gain = np.float32(p["gain"])
    offsets = p["offsets"]
    x, held, time, rows = [0.0] * 3, [0.0] * 3, float(times[0]), []
    for k, t in enumerate(times):
        if k > 0:
            h = float(times[k] - times[k - 1])
            held = [float(u[k - 1][j]) for j in range(3)]
            x = [x[j] + held[j] * h for j in range(3)]
            time = float(times[k - 1]) + h
        rows.append({
            "m[1,1]": x[0] + offsets[0] * time, "m[1,2]": x[1] * time,
            "m[2,1]": x[2] - math.sin(time), "m[2,2]": held[0] * held[2] + offsets[1],
            "scaled": float(gain * np.float32(x[0])),
            "y_i8": p["k_i8"] - k, "y_u8": p["k_u8"] + k, "y_i16": p["k_i16"] * k, "y_u16": p["k_u16"] + 1000 * k,
            "y_u32": 2_000_000_000 + 1000 * k, "y_i64": -2**31 + 1000 * k, "y_u64": 2**31 - 1 - 3 * k,
            "big": 3_000_000_000 + k if time >= p["overflow_time"] - 1e-9 else k, "mode": 1 + k % 3,
        })
    return rows


def inputs_csv(path, u=U, prefix=""):
    with open(path, "w", newline="") as f:
        f.write(f"time,{prefix}u[1],{prefix}u[2],{prefix}u[3]\n")
        for t, values in zip(TIMES, u):
            f.write(",".join(repr(float(v)) for v in (t, *values)) + "\n")


def run_crane(master, tmp_path, fmu, start, record=None, stop=STOP):
    """`crane-cosim run FMU --start … --input in.csv [--record …]`: (process, rows or None, summary or None)."""
    inputs_csv(tmp_path / "in.csv")
    out, summary = tmp_path / "out.csv", tmp_path / "summary.json"
    args = [str(master), "run", str(fmu), "--stop-time", str(stop), "--step-size", str(STEP),
            "--input", str(tmp_path / "in.csv"), "--output", str(out), "--summary", str(summary)]
    for name, value in start.items():
        args += ["--start", f"{name}={json.dumps(value)}"]
    for name in record or []:
        args += ["--record", name]
    process = subprocess.run(args, capture_output=True, text=True)
    rows = None
    if out.exists():
        with open(out, newline="") as f:
            rows = list(csv.DictReader(f))
    return process, rows, json.loads(summary.read_text()) if summary.exists() else None


def test_types3_is_a_valid_fmu_exporting_every_fmi3_function(fmu, tmp_path):
    assert validate_fmu(str(fmu)) == []
    model = read_model_description(str(fmu))
    assert model.fmiVersion == "3.0" and model.coSimulation is not None and model.modelExchange is None
    assert {v.type for v in model.modelVariables} == {
        "Float32", "Float64", "Int8", "UInt8", "Int16", "UInt16", "Int32", "UInt32", "Int64", "UInt64",
        "Enumeration"}
    shapes = {v.name: v.shape for v in model.modelVariables if v.shape}
    assert shapes == {"u": (3,), "m": (2, 2), "offsets": (2,)}
    library = exported_functions(fmu, tmp_path, TYPES3, X86_64_LINUX)
    functions = header_functions()
    assert len(functions) == 75
    assert [name for name in functions if not hasattr(library, name)] == []
    assert not hasattr(library, "fmi2DoStep")
    names = [name for name, _, _ in output_elements(model)]
    assert names[:4] == ["m[1,1]", "m[1,2]", "m[2,1]", "m[2,2]"] and len(names) == 14
    print(f"types3.fmu: FMPy validates it; it exports all {len(functions)} functions of fmi3Functions.h; "
          f"{len(names)} output elements")


@pytest.mark.parametrize("start", [{}, CHANGED], ids=["defaults", "changed"])
def test_types3_in_fmpy_equals_the_model_bit_for_bit(fmu, start):
    """FMPy's side alone (runs without crane-cosim): FMPy's results are the FMU's dynamics."""
    model = read_model_description(str(fmu))
    result = run_fmpy(fmu, start)
    expected = model_rows(start)
    assert len(result) == len(TIMES) == len(expected)
    assert list(result["time"]) == list(TIMES)
    for row, want in zip(result, expected):
        assert {name: fmpy_value(row, v, index) for name, v, index in output_elements(model)} == want
    # The integer outputs stay within int32, at its bounds at times, and the small types at theirs.
    last = expected[-1]
    assert expected[0]["y_i64"] == -2**31 and expected[0]["y_u64"] == 2**31 - 1
    assert max(abs(r[n]) for r in expected for n in ("y_u32", "y_i64", "y_u64", "big")) <= 2**31
    if start:
        assert (last["y_i8"], last["y_u8"], last["y_i16"], last["y_u16"]) == (-128, 255, 32000, 65535)
    assert {r["mode"] for r in expected} == {1, 2, 3}
    assert len({r["scaled"] for r in expected}) > 10, "scaled moves"
    print(f"types3 ({'changed' if start else 'defaults'}): FMPy = the model bit for bit, {len(result)} rows x "
          f"{len(output_elements(model))} elements")


@pytest.mark.parametrize("start", [{}, CHANGED], ids=["defaults", "changed"])
def test_types3_crane_cosim_records_fmpys_values_element_by_element_bit_for_bit(master, fmu, tmp_path, start):
    model = read_model_description(str(fmu))
    elements_ = output_elements(model)
    record = [name for name, _, _ in elements_]
    process, rows, summary = run_crane(master, tmp_path, fmu, start, record)
    assert process.returncode == 0, process.stderr
    assert "panicked" not in process.stderr
    assert summary["status"] == "completed" and summary["error"] is None
    reference = run_fmpy(fmu, start)
    assert len(rows) == len(reference) == len(TIMES)
    assert list(rows[0]) == ["time"] + [f"{TYPES3}.{name}" for name in record]
    compared = 0
    for row, expected in zip(rows, reference):
        assert float(row["time"]) == pytest.approx(expected["time"], abs=1e-12)
        got = {name: csv_value(row[f"{TYPES3}.{name}"], v) for name, v, _ in elements_}
        want = {name: fmpy_value(expected, v, index) for name, v, index in elements_}
        assert got == want, {n: (got[n], want[n]) for n in got if got[n] != want[n]}
        compared += len(got)
    assert rows[-1][f"{TYPES3}.y_i64"] == str(-2**31 + 20000) and rows[0][f"{TYPES3}.y_u64"] == str(2**31 - 1)
    print(f"types3 ({'changed' if start else 'defaults'}): crane-cosim = FMPy bit for bit, {len(rows)} rows x "
          f"{len(elements_)} elements = {compared} values (Float32 widened, m row-major)")


def test_types3_records_every_output_element_by_default(master, fmu, tmp_path):
    model = read_model_description(str(fmu))
    process, rows, _ = run_crane(master, tmp_path, fmu, {})
    assert process.returncode == 0, process.stderr
    assert set(rows[0]) == {"time"} | {f"{TYPES3}.{name}" for name, _, _ in output_elements(model)}
    # The inputs file drives u element by element: m[1,1] integrates u[1].
    assert float(rows[-1][f"{TYPES3}.m[1,1]"]) == model_rows({})[-1]["m[1,1]"]


def test_types3_arrays_connect_element_by_element_in_a_system(master, fmu, tmp_path):
    """Instance "a" is fed from the inputs file; "b" gets a.m[1,1], a.scaled (Float32) and a.m[2,2]
    as u[1], u[2] and u[3]. Jacobi: b's inputs over a step are a's outputs at the step's start
    (types3 has no direct feedthrough)."""
    inputs_csv(tmp_path / "in.csv")
    system = {
        "fmus": {"t": str(fmu)},
        "instances": [{"name": "a", "fmu": "t", "start": {"offsets[2]": 5}},
                      {"name": "b", "fmu": "t", "start": {"gain": 0.25, "k_u16": 7}}],
        "connections": [{"from": "a.m[1,1]", "to": "b.u[1]"}, {"from": "a.scaled", "to": "b.u[2]"},
                        {"from": "a.m[2,2]", "to": "b.u[3]"}],
        "inputs": [{"instance": "a", "file": "in.csv"}],
        "start_time": 0.0, "stop_time": STOP, "step_size": STEP, "algorithm": "jacobi",
        "record": {"variables": [f"{i}.{n}" for i in "ab" for n in ("m[1,1]", "m[1,2]", "m[2,1]", "m[2,2]",
                                                                     "scaled", "y_u16")]},
    }
    (tmp_path / "system.json").write_text(json.dumps(system))
    out = tmp_path / "out.csv"
    process = subprocess.run([str(master), "run", str(tmp_path / "system.json"), "--output", str(out)],
                             capture_output=True, text=True)
    assert process.returncode == 0, process.stderr
    with open(out, newline="") as f:
        rows = list(csv.DictReader(f))
    a = model_rows({"offsets[2]": 5})
    b = model_rows({"gain": 0.25, "k_u16": 7}, u=[[r["m[1,1]"], r["scaled"], r["m[2,2]"]] for r in a])
    assert len(rows) == len(TIMES)
    for row, ra, rb in zip(rows, a, b):
        for instance, expected in (("a", ra), ("b", rb)):
            for name in ("m[1,1]", "m[1,2]", "m[2,1]", "m[2,2]", "scaled"):
                assert float(row[f"{instance}.{name}"]) == expected[name], (row["time"], instance, name)
            assert int(row[f"{instance}.y_u16"]) == expected["y_u16"]
    print(f"types3 a -> b (m[1,1], scaled, m[2,2] -> u[1..3]): {len(rows)} rows = the model bit for bit")


def test_an_int64_output_beyond_int32_ends_the_run_naming_it_and_the_value(master, fmu, tmp_path):
    # big = 3 000 000 000 + k from t = 1.1 s (k = 11) on; FMPy reads it.
    start = {"overflow_time": 1.05}
    reference = run_fmpy(fmu, start)
    big = [int(v) for v in reference["big"]]
    assert big[:11] == list(range(11)) and big[11] == 3_000_000_011
    process, rows, summary = run_crane(master, tmp_path, fmu, start)
    assert process.returncode == 1, process.stdout + process.stderr
    assert "panicked" not in process.stderr
    assert "big" in process.stderr, process.stderr
    assert "3000000011" in process.stderr, process.stderr
    # The rows before are FMPy's.
    assert rows is not None and 1 <= len(rows) <= 11
    for row, expected in zip(rows, reference):
        assert int(row[f"{TYPES3}.big"]) == int(expected["big"])
        assert float(row[f"{TYPES3}.m[2,1]"]) == float(expected["m"][1][0])
    if summary is not None:
        assert summary["status"] == "failed" and "3000000011" in summary["error"]
    print(f"big = 3000000011 at t = 1.1 s: crane-cosim kept {len(rows)} rows and said: "
          f"{process.stderr.strip().splitlines()[-1]}")


# --start values crane-cosim must refuse (naming the variable; the value too for Float32) or take.
STARTS = {
    "gain=0.1": ({"gain": 0.1}, "0.1"),
    "gain=16777217": ({"gain": 16777217}, "16777217"),
    "k_i8=-129": ({"k_i8": -129}, None),
    "k_u8=256": ({"k_u8": 256}, None),
    "k_u8=-1": ({"k_u8": -1}, None),
    "k_i16=32768": ({"k_i16": 32768}, None),
    "k_u16=65536": ({"k_u16": 65536}, None),
}


@pytest.mark.parametrize("case", STARTS)
def test_start_values_a_type_cannot_hold_are_refused_naming_the_variable(master, fmu, tmp_path, case):
    start, value = STARTS[case]
    (name,) = start
    process, _, _ = run_crane(master, tmp_path, fmu, start)
    assert process.returncode == 1, process.stdout + process.stderr
    assert "panicked" not in process.stderr
    assert name in process.stderr, process.stderr
    if value is not None:
        assert value in process.stderr, process.stderr
    print(f"{case}: {process.stderr.strip().splitlines()[-1]}")


ACCEPTED = {"gain": [0.5, 16777216.0, -0.375], "k_i8": [-128, 127], "k_u8": [0, 255], "k_i16": [-32768, 32767],
            "k_u16": [0, 65535]}
# The output and the row showing each parameter: y_i8, y_u8 and y_u16 at t = 0 (k = 0), y_i16 =
# k_i16 k at k = 1, scaled = gain * (float)x_1 at t = 0.2 s (x_1 = sin(0) h = 0 until then).
SHOWN_BY = {"gain": ("scaled", 2), "k_i8": ("y_i8", 0), "k_u8": ("y_u8", 0), "k_i16": ("y_i16", 1),
            "k_u16": ("y_u16", 0)}


@pytest.mark.parametrize("name, value", [(n, v) for n, values in ACCEPTED.items() for v in values])
def test_start_values_a_type_holds_are_taken(master, fmu, tmp_path, name, value):
    process, rows, _ = run_crane(master, tmp_path, fmu, {name: value}, stop=0.2)
    assert process.returncode == 0, process.stderr
    assert len(rows) == 3
    output, index = SHOWN_BY[name]
    expected = model_rows({name: value})[index][output]
    assert expected == value if name != "gain" else expected != 0
    got = rows[index][f"{TYPES3}.{output}"]
    assert (float(got) if name == "gain" else int(got)) == expected


# Variables crane-cosim refuses, each added to types3's description (FMPy validates the result).
REFUSED = {
    "binary": ('<Binary name="blob" valueReference="20" causality="parameter" variability="fixed" '
               'initial="exact"><Start value="0a0b0c"/></Binary>', "blob"),
    "clock": ('<Clock name="tick" valueReference="20" causality="input" intervalVariability="triggered"/>', "tick"),
    "structural dimension": (
        '<UInt64 name="n" valueReference="20" causality="structuralParameter" variability="fixed" '
        'initial="exact" start="3"/>\n    <Float64 name="w" valueReference="21" causality="parameter" '
        'variability="fixed" initial="exact" start="1 2 3"><Dimension valueReference="20"/></Float64>', "w"),
}


@pytest.mark.parametrize("case", REFUSED)
def test_binary_clock_and_structurally_sized_variables_are_refused_naming_them(master, fmu, tmp_path, case):
    variable, name = REFUSED[case]
    assert name in variable
    copy = with_variable(fmu, TYPES3, tmp_path / f"{TYPES3}.fmu", variable)
    stderr = assert_refused(master, copy, tmp_path, f'"{name}"')
    print(f"{case}: {stderr.strip().splitlines()[-1]}")
