"""The win64 binary of every FMU, run for real: tests/windows/driver.c is compiled natively and for
Windows (MinGW-w64), the Windows build loads `binaries/win64/<model>.dll` under Wine and the
Linux build `binaries/linux64/<model>.so`, both with the same calling sequence on the
cross-check files (<model>_in.csv, _ref.opt). The DLL must reproduce the Linux results and the
reference file to ≤ 1e-12·max(1, |value|), need no DLL beyond Windows' own, and `fmpy info` must
list both platforms (FMPy names no aarch64 Linux platform). The driver and the plan are shared with
tests/aarch64/test_aarch64.py (tests/cdriver.py).

`cargo xtask test` installs MinGW-w64 and Wine (`wine64`) before packaging, so a missing tool
here is a failure, not a skip."""
import os
import subprocess
import sys
import zipfile

import pytest

from cdriver import DRIVER, FLAGS, TOLERANCE, as_array, load, run, worst_difference, write_plan
from cdriver import tool as installed
from conftest import ROOT, fmu_names, fmu_path

MODELS = fmu_names()
# DLLs every 64-bit Windows has (besides the api-ms-win-* API sets). Anything else
# (libgcc_s_seh-1.dll, libwinpthread-1.dll, a Rust std DLL) would make the FMU fail to load on a
# machine without MinGW.
SYSTEM_DLLS = {"kernel32.dll", "ntdll.dll", "msvcrt.dll", "advapi32.dll", "bcrypt.dll", "bcryptprimitives.dll",
               "userenv.dll", "ws2_32.dll", "user32.dll", "shell32.dll", "ole32.dll"}


def tool(name):
    return installed(name, "MinGW-w64 and Wine from apt")


@pytest.fixture(scope="module")
def drivers(tmp_path_factory):
    """(native driver, Windows driver): the same C source built for both platforms."""
    out = tmp_path_factory.mktemp("driver")
    native, windows = out / "driver", out / "driver.exe"
    subprocess.run([tool("gcc"), *FLAGS, str(DRIVER), "-o", str(native), "-ldl"], check=True)
    subprocess.run([tool("x86_64-w64-mingw32-gcc"), *FLAGS, "-static", str(DRIVER), "-o", str(windows)], check=True)
    return native, windows


@pytest.fixture(scope="module")
def wine_env():
    """A Wine prefix of its own under target/ (its first start takes ~15 s; later runs reuse it),
    without the Mono and Gecko installers, which would try to download."""
    env = dict(os.environ, WINEPREFIX=str(ROOT / "target" / "wine"), WINEARCH="win64", WINEDEBUG="-all",
               WINEDLLOVERRIDES="mscoree,mshtml=")
    env.pop("DISPLAY", None)
    return env


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
    reference = as_array(ref)
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
