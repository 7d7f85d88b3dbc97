#!/usr/bin/python3
"""`pounding spectrum` against an independent computation: scipy integrates each SDOF
x'' + 2ζωx' + ω²x = −a_g(t) interval by interval (DOP853, rtol 1e-12) on a random
piecewise-linear record and finds the peak |x| at the end points and at the zeros of ẋ
(events); the program's Sd must agree to 1e-7 relative (its closed form is exact to round-off,
scipy's solution is good to ~1e-9). Also: a pair from one file (--record-column 1,2) with the
second column all zero gives RotD100 = Sd of the first; PSA at a very short period tends to
the PGA (within 2 %) (CTest: test_spectrum_scipy).

    tests/excitation/test_spectrum_scipy.py build/apps/pounding
"""
import json
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

G = 9.81


def check(condition, message):
    if not condition:
        sys.exit(f"FAILED: {message}")


def peak_displacement(t, a, period, zeta):
    """max |x| of the SDOF under the piecewise-linear a(t) (m/s²), from rest at t[0]."""
    w = 2 * np.pi / period
    state = np.zeros(2)
    peak = 0.0
    for i in range(len(t) - 1):
        t0, t1, a0, a1 = t[i], t[i + 1], a[i], a[i + 1]

        def rhs(s, y):
            ag = a0 + (a1 - a0) * (s - t0) / (t1 - t0)
            return [y[1], -ag - 2 * zeta * w * y[1] - w * w * y[0]]

        def turning(s, y):
            return y[1]

        sol = solve_ivp(rhs, (t0, t1), state, method="DOP853", rtol=1e-12, atol=1e-15, events=turning)
        for ys in sol.y_events[0]:
            peak = max(peak, abs(ys[0]))
        state = sol.y[:, -1]
        peak = max(peak, abs(state[0]))
    return peak


def main():
    pounding = sys.argv[1]
    rng = np.random.default_rng(20261124)
    dt = 0.02
    t = np.arange(0, 4.0 + dt / 2, dt)
    accel_g = 0.3 * rng.standard_normal(t.size) * np.exp(-0.5 * t)
    accel_g[0] = 0.0  # from rest: a first sample ≠ 0 would be a step, whose overshoot is no PGA
    periods = [0.03, 0.17, 0.5, 1.3, 3.0]
    zeta = 0.05
    with tempfile.TemporaryDirectory() as scratch:
        scratch = Path(scratch)
        record = scratch / "record.txt"
        record.write_text("".join(f"{ti:.6f} {ai:.17g} 0\n" for ti, ai in zip(t, accel_g)))
        out = scratch / "spectrum"
        subprocess.run([pounding, "spectrum", str(record), str(record), "--format", "columns",
                        "--record-column", "2,3", "--rotd", "--damping", str(zeta),
                        "--periods", ",".join(map(str, periods + [0.001])), "--no-plot", "--out", str(out)],
                       check=True, stdout=subprocess.DEVNULL)
        report = json.loads((out / "spectrum.json").read_text())
        ordinates = report["records"][0]["ordinates"]
        for o in ordinates:
            if o["period_s"] < 0.01:
                continue
            expected = peak_displacement(t, accel_g * G, o["period_s"], zeta)
            error = abs(o["sd_m"] - expected) / expected
            print(f"T = {o['period_s']:5.2f} s: Sd {o['sd_m']:.12e} m, scipy {expected:.12e} m, relative {error:.1e}")
            check(error < 1e-7, f"Sd at T = {o['period_s']} s is {o['sd_m']}, scipy says {expected}")
        for o, r in zip(ordinates, report["rotd"]):
            check(abs(r["rotd100_sd_m"] - o["sd_m"]) <= 1e-12 * o["sd_m"],
                  f"RotD100 {r['rotd100_sd_m']} of a pair with a zero second component is not Sd {o['sd_m']}")
        pga_g = report["records"][0]["peak_accel_g"]
        # At T → 0, x → −a_g/ω², so PSA → PGA; each kink of the record (a slope change of about
        # a/dt) adds a transient of relative size ~T/(2π dt) ≈ 0.8 % here: 2 % allowed.
        short = ordinates[0]  # 0.001 s, the periods are sorted
        check(abs(short["psa_g"] - pga_g) < 0.02 * pga_g,
              f"PSA at {short['period_s']} s = {short['psa_g']} g is not the PGA {pga_g} g")
        # Bad input: exit 2 and a message naming the option and the value.
        for arguments, words in ((["--damping", "1"], "--damping = 1"), (["--periods", "0.5,-1"], "--periods = -1"),
                                 (["--rotd"], "--rotd"), (["--record-column", "1,2,3"], "--record-column")):
            done = subprocess.run([pounding, "spectrum", str(record), "--format", "columns", "--no-plot",
                                   "--out", str(out)] + arguments, capture_output=True, text=True)
            check(done.returncode == 2 and words in done.stderr, f"{arguments}: exit {done.returncode}, {done.stderr!r}")
        done = subprocess.run([pounding, "spectrum", str(scratch / "missing.txt"), "--out", str(out)],
                              capture_output=True, text=True)
        check(done.returncode == 2 and "missing.txt" in done.stderr, f"missing record: {done.stderr!r}")
    print("1 passed, 0 failed")


if __name__ == "__main__":
    main()
