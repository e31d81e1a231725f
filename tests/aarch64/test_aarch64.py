"""The aarch64 Linux binary of every FMU, run for real: tests/windows/driver.c is compiled natively
and with the aarch64 cross GCC, the aarch64 build loads `binaries/aarch64-linux/<model>.so` of the
FMI 3.0 archive under QEMU's user-mode emulator (`qemu-aarch64 -L /usr/aarch64-linux-gnu`) and the
native build `binaries/linux64/<model>.so`, both with the same calling sequence (the fmi2 API) on
the cross-check files (<model>_in.csv, _ref.opt). The aarch64 library must be an AArch64 ELF
shared object, the same bytes in the FMI 2.0 archive (`binaries/aarch64-linux/`, see
`Version::platform_folder` in xtask/src/package.rs) and reproduce the x86_64 results and the
reference file to ≤ 1e-12·max(1, |value|).

Measured (Debian 12, glibc 2.36 for both machines, an x86_64 CPU with FMA), aarch64 vs x86_64:
controller 1.9e-14 (211 of 40,040 values differ), knuckle_boom 1.5e-14 (7,777 of 26,065),
knuckle_boom_controller 4.4e-16 (406 of 25,025); crane, imu, pendulum, platform and rigging
bit-identical. The cause is glibc's `hypot` alone. Rust neither contracts a*b+c into an FMA nor
reorders floating-point arithmetic, so the FMUs' own code gives the same bits on both machines
(QEMU emulates aarch64 floating point bit-exactly). Of the libm functions they call, sin, cos,
sincos, tan, exp, expm1, log, pow, atan, atan2, asin, acos and tanh agree bit for bit on 200,000
arguments each: on an x86_64 CPU with FMA glibc picks its variants compiled with FMA, which
compute what the aarch64 build computes. Its hypot takes an FMA path only when compiled for FMA (`__FP_FAST_FMA`, always on aarch64)
and has no x86_64 FMA variant: it differs by 1 ulp on 12.6 % of those arguments. With one hypot
for both (an LD_PRELOAD shim), all eight FMUs are bit-identical. On an x86_64 CPU without FMA
(`GLIBC_TUNABLES=glibc.cpu.hwcaps=-AVX2,-FMA`) the other functions differ as well (rigging 4.4e-15,
crane 1.1e-16 against aarch64), still far inside the tolerance.

`cargo xtask test` installs the cross GCC, the aarch64 glibc and QEMU before packaging, so a
missing tool here is a failure, not a skip."""
import struct
import subprocess
import zipfile

import numpy as np
import pytest

from cdriver import DRIVER, FLAGS, TOLERANCE, as_array, load, run, worst_difference, write_plan
from cdriver import tool as installed
from conftest import fmu_dir, fmu_entry, fmu_names, fmu_path

MODELS = fmu_names()
PLATFORM = "aarch64-linux"
# Debian's cross packages put the aarch64 glibc here (libc6-arm64-cross); QEMU loads the driver's
# dynamic loader and libraries from it.
SYSROOT = "/usr/aarch64-linux-gnu"
EM_AARCH64, EM_X86_64 = 183, 62


def tool(name):
    return installed(name, "gcc-aarch64-linux-gnu, libc6-dev-arm64-cross and qemu-user from apt")


@pytest.fixture(scope="module")
def drivers(tmp_path_factory):
    """(native driver, aarch64 driver): the same C source built for both machines, both linked
    dynamically against their glibc (dlopen needs it)."""
    out = tmp_path_factory.mktemp("driver")
    native, arm = out / "driver", out / "driver-aarch64"
    subprocess.run([tool("gcc"), *FLAGS, str(DRIVER), "-o", str(native), "-ldl"], check=True)
    subprocess.run([tool("aarch64-linux-gnu-gcc"), *FLAGS, str(DRIVER), "-o", str(arm), "-ldl"], check=True)
    assert elf_machine(arm.read_bytes()) == EM_AARCH64
    return native, arm


def elf_machine(data):
    """e_machine of a 64-bit little-endian ELF file (and that it is one)."""
    assert data[:4] == b"\x7fELF", data[:4]
    assert data[4] == 2 and data[5] == 1, "ELFCLASS64, ELFDATA2LSB"
    return struct.unpack_from("<H", data, 18)[0]


def fmi3_archive(name):
    return zipfile.ZipFile(fmu_dir() / fmu_entry(name)["fmi3_archive"])


@pytest.mark.parametrize("name", MODELS)
def test_both_archives_carry_the_same_aarch64_shared_object(name):
    entry = fmu_entry(name)
    assert PLATFORM in entry["fmi3_platforms"] and PLATFORM in entry["platforms"], entry
    library = f"binaries/{PLATFORM}/{name}.so"
    fmi3 = fmi3_archive(name).read(library)
    assert zipfile.ZipFile(fmu_path(name)).read(library) == fmi3, "one library in both archives"
    assert elf_machine(fmi3) == EM_AARCH64
    assert struct.unpack_from("<H", fmi3, 16)[0] == 3, "ET_DYN: a shared object"
    assert elf_machine(fmi3_archive(name).read(f"binaries/x86_64-linux/{name}.so")) == EM_X86_64
    print(f"{name}.so for {PLATFORM}: ELF64 AArch64 shared object, {len(fmi3)} bytes, the same in both archives")


@pytest.mark.parametrize("name", MODELS)
def test_aarch64_library_reproduces_x86_64_results_under_qemu(name, drivers, tmp_path):
    fmi3_archive(name).extract(f"binaries/{PLATFORM}/{name}.so", tmp_path)
    zipfile.ZipFile(fmu_path(name)).extract(f"binaries/linux64/{name}.so", tmp_path)
    plan = tmp_path / "plan.txt"
    inputs, ref = write_plan(name, plan)
    native, arm = drivers
    run([str(native), str(tmp_path / f"binaries/linux64/{name}.so"), str(plan), inputs, str(tmp_path / "x86_64.csv")])
    run([tool("qemu-aarch64"), "-L", SYSROOT, str(arm), str(tmp_path / f"binaries/{PLATFORM}/{name}.so"), str(plan),
         inputs, str(tmp_path / "aarch64.csv")])
    x86, arm64 = load(tmp_path / "x86_64.csv"), load(tmp_path / "aarch64.csv")
    versus_x86, versus_reference = worst_difference(arm64, x86), worst_difference(arm64, as_array(ref))
    differing = int(np.count_nonzero(arm64 != x86))
    print(f"{name}.so on aarch64 (QEMU), {len(arm64)} rows x {arm64.shape[1] - 1} outputs: aarch64 vs x86_64 "
          f"max relative difference {versus_x86:.3e} ({differing} of {arm64.size} values differ), "
          f"{versus_reference:.3e} to {name}_ref.csv")
    assert versus_x86 <= TOLERANCE
    assert versus_reference <= TOLERANCE
