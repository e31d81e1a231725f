"""The win64 binary of every FMU, run for real: tests/windows/driver.c is compiled natively and for
Windows (MinGW-w64), the Windows build loads `binaries/win64/<model>.dll` under Wine and the
Linux build `binaries/linux64/<model>.so`, both with the same calling sequence on the
cross-check files (<model>_in.csv, _ref.opt). The DLL must reproduce the Linux results and the
reference file to ≤ 1e-12·max(1, |value|), need no DLL beyond Windows' own, and `fmpy info` must
list both platforms.

`cargo xtask test` installs MinGW-w64 and Wine (`wine64`) before packaging, so a missing tool
here is a failure, not a skip."""
import os
import shutil
import subprocess
import sys
import zipfile

import numpy as np
import pytest
from fmpy import read_model_description
from fmpy.util import read_csv

from conftest import ROOT, fmu_dir, fmu_names, fmu_path

MODELS = fmu_names()
DRIVER = ROOT / "tests" / "windows" / "driver.c"
TOLERANCE = 1e-12
# DLLs every 64-bit Windows has (besides the api-ms-win-* API sets). Anything else
# (libgcc_s_seh-1.dll, libwinpthread-1.dll, a Rust std DLL) would make the FMU fail to load on a
# machine without MinGW.
SYSTEM_DLLS = {"kernel32.dll", "ntdll.dll", "msvcrt.dll", "advapi32.dll", "bcrypt.dll", "bcryptprimitives.dll",
               "userenv.dll", "ws2_32.dll", "user32.dll", "shell32.dll", "ole32.dll"}


def tool(name):
    path = shutil.which(name)
    if path is None:
        pytest.fail(f"{name} is missing: `cargo xtask test` installs it (MinGW-w64 and Wine from apt)")
    return path


@pytest.fixture(scope="module")
def drivers(tmp_path_factory):
    """(native driver, Windows driver): the same C source built for both platforms."""
    out = tmp_path_factory.mktemp("driver")
    flags = ["-std=c99", "-O2", "-Wall", "-Wextra", "-Werror"]
    native, windows = out / "driver", out / "driver.exe"
    subprocess.run([tool("gcc"), *flags, str(DRIVER), "-o", str(native), "-ldl"], check=True)
    subprocess.run([tool("x86_64-w64-mingw32-gcc"), *flags, "-static", str(DRIVER), "-o", str(windows)], check=True)
    return native, windows


@pytest.fixture(scope="module")
def wine_env():
    """A Wine prefix of its own under target/ (its first start takes ~15 s; later runs reuse it),
    without the Mono and Gecko installers, which would try to download."""
    env = dict(os.environ, WINEPREFIX=str(ROOT / "target" / "wine"), WINEARCH="win64", WINEDEBUG="-all",
               WINEDLLOVERRIDES="mscoree,mshtml=")
    env.pop("DISPLAY", None)
    return env


def write_plan(name, path):
    """The driver's plan: GUID, experiment, input value references in _in.csv's column order and
    typed output value references in _ref.csv's column order."""
    md = read_model_description(str(fmu_path(name)))
    by_name = {v.name: v for v in md.modelVariables}
    opt = dict(line.split(",", 1) for line in (fmu_dir() / f"{name}_ref.opt").read_text().splitlines() if line)
    opt = {key.strip(): float(value) for key, value in opt.items()}
    ref = read_csv(fmu_dir() / f"{name}_ref.csv")
    inputs_csv = fmu_dir() / f"{name}_in.csv"
    inputs = read_csv(inputs_csv).dtype.names[1:] if inputs_csv.exists() else ()
    letter = {"Real": "r", "Integer": "i", "Boolean": "b"}
    outputs = [f"{letter[by_name[n].type]}{by_name[n].valueReference}" for n in ref.dtype.names[1:]]
    path.write_text(f"guid {md.guid}\n"
                    f"experiment {opt['StartTime']!r} {opt['StopTime']!r} {opt['StepSize']!r}\n"
                    f"inputs {' '.join(str(by_name[n].valueReference) for n in inputs)}\n"
                    f"outputs {' '.join(outputs)}\n")
    return (str(inputs_csv) if inputs else "-"), ref


def run(command, env=None):
    done = subprocess.run(command, capture_output=True, text=True, env=env, timeout=300)
    assert done.returncode == 0, f"{command}: {done.stderr}"


def load(path):
    return np.loadtxt(path, delimiter=",", ndmin=2)


def worst_difference(a, b):
    assert a.shape == b.shape, (a.shape, b.shape)
    return float(np.max(np.abs(a - b) / np.maximum(1.0, np.abs(b))))


def dll_imports(dll):
    dump = subprocess.run([tool("x86_64-w64-mingw32-objdump"), "-p", str(dll)], capture_output=True, text=True,
                          check=True).stdout
    return {line.split(":", 1)[1].strip().lower() for line in dump.splitlines() if "DLL Name:" in line}


@pytest.mark.parametrize("name", MODELS)
def test_win64_dll_reproduces_linux_results_under_wine(name, drivers, wine_env, tmp_path):
    archive = zipfile.ZipFile(fmu_path(name))
    assert f"binaries/win64/{name}.dll" in archive.namelist(), f"{name}.fmu has no win64 binary"
    archive.extractall(tmp_path, [f"binaries/win64/{name}.dll", f"binaries/linux64/{name}.so"])
    plan = tmp_path / "plan.txt"
    inputs, ref = write_plan(name, plan)
    native, windows = drivers
    run([str(native), str(tmp_path / f"binaries/linux64/{name}.so"), str(plan), inputs, str(tmp_path / "linux.csv")])
    run([tool("wine"), str(windows), str(tmp_path / f"binaries/win64/{name}.dll"), str(plan), inputs,
         str(tmp_path / "windows.csv")], env=wine_env)
    linux, win = load(tmp_path / "linux.csv"), load(tmp_path / "windows.csv")
    reference = np.column_stack([ref[n].astype(float) for n in ref.dtype.names])
    versus_linux, versus_reference = worst_difference(win, linux), worst_difference(win, reference)
    print(f"{name}.dll under Wine, {len(win)} rows x {win.shape[1] - 1} outputs: max relative difference "
          f"{versus_linux:.3e} to {name}.so, {versus_reference:.3e} to {name}_ref.csv")
    assert versus_linux <= TOLERANCE
    assert versus_reference <= TOLERANCE


@pytest.mark.parametrize("name", MODELS)
def test_win64_dll_needs_only_system_dlls(name, tmp_path):
    zipfile.ZipFile(fmu_path(name)).extract(f"binaries/win64/{name}.dll", tmp_path)
    imports = dll_imports(tmp_path / f"binaries/win64/{name}.dll")
    print(f"{name}.dll imports {sorted(imports)}")
    foreign = {dll for dll in imports if dll not in SYSTEM_DLLS and not dll.startswith("api-ms-win-")}
    assert "kernel32.dll" in imports and not foreign, sorted(foreign)


@pytest.mark.parametrize("name", MODELS)
def test_fmpy_info_lists_both_platforms(name):
    info = subprocess.run([sys.executable, "-m", "fmpy", "info", str(fmu_path(name))], capture_output=True,
                          text=True, check=True).stdout
    platforms = next(line for line in info.splitlines() if line.strip().startswith("Platforms"))
    assert platforms.split()[1:] == ["linux64,", "win64"], platforms
