"""The Rust CARE solver and lqr (physics::control::lqr, run through the controller crate's `lqr`
example) against SciPy's solve_continuous_are: the thesis design of §6.2 (Q = 10·I12, R = I6 on the
linearised tip-pendulum model, l_p = 0.05-1.0 m) and random stabilisable systems."""
import json
import subprocess

import numpy as np
import pytest
from scipy.linalg import solve_continuous_are

from conftest import ROOT


def lqr_example(*args):
    out = subprocess.run(
        ["cargo", "run", "--profile", "test-release", "--quiet", "-p", "controller", "--example", "lqr", "--", *args],
        cwd=ROOT, check=True, capture_output=True, text=True,
    )
    return json.loads(out.stdout)


def relative_error(rust, reference):
    return float(np.linalg.norm(rust - reference) / np.linalg.norm(reference))


def test_the_thesis_design_matches_scipy():
    sweep = lqr_example("--json")
    for case in sweep["cases"]:
        a, b, q, r = (np.array(case[k]) for k in ("A", "B", "Q", "R"))
        s_ref = solve_continuous_are(a, b, q, r)
        k_ref = np.linalg.solve(r, b.T @ s_ref)
        s, k = np.array(case["S"]), np.array(case["K"])
        err_s, err_k = relative_error(s, s_ref), relative_error(k, k_ref)
        closed = np.linalg.eigvals(a - b @ k)
        print(f"l_p = {case['lp']:.2f} m: |S - S_scipy|/|S| = {err_s:.1e}, |K - K_scipy|/|K| = {err_k:.1e}, "
              f"max Re eig(A - BK) = {closed.real.max():.3f}, K[ay,th_x] = {k[1, 3]:+.3f}, K[ax,th_y] = {k[0, 4]:+.3f}")
        assert err_s < 1e-8 and err_k < 1e-8
        assert closed.real.max() < 0, "A - BK is Hurwitz"
        # The sign structure the delta law inherits (SPEC §4.5).
        assert k[1, 3] > 8.4 and k[0, 4] < -8.4


@pytest.mark.parametrize("seed", range(6))
def test_random_systems_match_scipy(tmp_path, seed):
    rng = np.random.default_rng(seed)
    n, m = int(rng.integers(2, 9)), int(rng.integers(1, 4))
    a = rng.normal(size=(n, n))
    b = rng.normal(size=(n, m))
    c = rng.normal(size=(n, n))
    q = c @ c.T + 0.1 * np.eye(n)
    d = rng.normal(size=(m, m))
    r = d @ d.T + 0.5 * np.eye(m)
    path = tmp_path / "problem.json"
    path.write_text(json.dumps({k: v.tolist() for k, v in {"A": a, "B": b, "Q": q, "R": r}.items()}))
    result = lqr_example("--solve", str(path))
    s, k = np.array(result["S"]), np.array(result["K"])
    s_ref = solve_continuous_are(a, b, q, r)
    g = b @ np.linalg.solve(r, b.T)

    def residual(x):
        return float(np.linalg.norm(a.T @ x + x @ a - x @ g @ x + q) / np.linalg.norm(x))

    err, cond = relative_error(s, s_ref), float(np.linalg.cond(s_ref))
    print(f"seed {seed}: n = {n}, m = {m}, cond(S) = {cond:.1e}, |S - S_scipy|/|S| = {err:.1e}, "
          f"residuals Rust {residual(s):.1e}, SciPy {residual(s_ref):.1e}")
    # Two accurate solutions of an ill-conditioned equation differ by up to ~cond(S)·eps.
    assert err < max(1e-8, 1e-14 * cond)
    assert residual(s) <= 10 * residual(s_ref) + 1e-14
    assert np.linalg.eigvals(a - b @ k).real.max() < 0
