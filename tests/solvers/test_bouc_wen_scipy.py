#!/usr/bin/python3
"""Bouc-Wen columns against an independent computation (scipy, no code shared with the program).

    tests/solvers/test_bouc_wen_scipy.py POUNDING [OUT]

The plan-asymmetric one-storey building of test_yielding_scipy.py (two column lines of different
size, the centre of mass 1 m off the plan centre, a half-sine pulse along y) with Bouc-Wen columns
instead of bilinear ones: yield drift 8 mm, hardening 5 %, A = 1, beta = 0.6, gamma = 0.4, n = 3
(beta != gamma, so loading and unloading differ). The peer integrates, with scipy's DOP853 over
each record interval,
    M q'' + C q' + sum_j t_j (alpha k_j t_j.q + (1 - alpha) k_j d_y z_j) = -M r a_g,
    z_j' = (d_j'/d_y) (A - |z_j|^n (beta sgn(d_j' z_j) + gamma)),
    E_j' = (1 - alpha) k_j d_y d_j' z_j |z_j|^n (beta sgn(d_j' z_j) + gamma) / A   (dissipated),
with its own K, Rayleigh fit (initial stiffness) and first-yield events (|d| reaching d_y).
Checked:
  1. u, v, phi at every history row: within 1e-8 m, 2e-9 rad;
  2. per spring the first yield (within 1e-7 s) and the final slip d - d_y z (within 1e-8 m);
  3. the hysteretic energy, per spring and in all (1e-6 of the total), and the energy audit
     closes (relative residual below 1e-6).
Then Bouc-Wen with impacts, against a second method: the paper's buildings with Bouc-Wen columns
(yield drift 0.2 % of the storey, 5 % hardening, n = 2) at gap 0.05 m, run on cvode-bdf and
arkode-erk at rtol 1e-10:
  4. the same impacts, pair by pair, at times within 1e-6 s, and both audits close to 1e-6.
And `pounding gap` on examples/paper/paper-bouc-wen.toml (the contact-free run carrying z):
  5. at its needed gap G + 1e-5 m the buildings do not meet, at G - 1e-5 m they strike.
"""
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parent))
from test_yielding_scipy import (ALPHA, COLUMNS, YIELD_DRIFT_M, Peer, check_needed_gap_brackets,  # noqa: E402
                                 check_second_method, paper_with_yielding, run_one_storey)

A, BETA, GAMMA, N = 1.0, 0.6, 0.4, 3.0
LAW = f'law = "bouc-wen"\nyield_drift_m = {YIELD_DRIFT_M}\nhardening_ratio = {ALPHA}\n' \
      f'a = {A}\nbeta = {BETA}\ngamma = {GAMMA}\nn = {N}\n'


class BoucWenPeer(Peer):
    """The bilinear peer's building (mass, springs, K, C), with state (q, q', z, E)."""

    def rhs(self, t, y, ag):
        q, qd, z = y[:3], y[3:6], y[6:6 + len(self.k)]
        d_rate = self.t @ qd
        sign = np.sign(d_rate * z)
        spring_force = self.t.T @ (ALPHA * self.k * (self.t @ q) + (1.0 - ALPHA) * self.k * YIELD_DRIFT_M * z)
        qdd = (-spring_force - self.C @ qd) / self.m - self.r * ag(t)
        z_rate = d_rate / YIELD_DRIFT_M * (A - np.abs(z) ** N * (BETA * sign + GAMMA))
        power = (1.0 - ALPHA) * self.k * YIELD_DRIFT_M * d_rate * z * np.abs(z) ** N * (BETA * sign + GAMMA) / A
        return np.concatenate([qd, qdd, z_rate, power])

    def yield_events(self):
        events = []
        for j in range(len(self.k)):
            for side in (1.0, -1.0):
                def f(t, y, _ag, j=j, side=side):
                    return YIELD_DRIFT_M - side * (self.t[j] @ y[:3])
                f.direction = -1
                events.append(f)
        return events

    def run(self, times, accel, out_times):
        ag = lambda t: np.interp(t, times, accel)
        count = len(self.k)
        y = np.zeros(6 + 2 * count)
        rows, k_out = [], 0
        events = self.yield_events()
        for a, b in zip(times[:-1], times[1:]):
            sol = solve_ivp(self.rhs, (a, b), y, method="DOP853", rtol=1e-11, atol=1e-13, events=events, args=(ag,),
                            dense_output=True)
            for e, hits in enumerate(sol.t_events):
                j = e // 2
                if len(hits) and np.isnan(self.first_yield[j]):
                    self.first_yield[j] = hits[0]
            while k_out < len(out_times) and out_times[k_out] <= b + 1e-12:
                rows.append(sol.sol(out_times[k_out])[:3])
                k_out += 1
            y = sol.y[:, -1]
        self.final_drift = self.t @ y[:3]
        self.slip = self.final_drift - YIELD_DRIFT_M * y[6:6 + count]
        self.dissipated = y[6 + count:]
        return np.array(rows)


def check_one_storey(program, out, failures):
    times, accel, t_out, program_q, springs, summary = run_one_storey(program, out, LAW)

    peer = BoucWenPeer()
    peer_q = peer.run(times, accel, t_out)
    du = np.max(np.abs(program_q[:, :2] - peer_q[:, :2]))
    dphi = np.max(np.abs(program_q[:, 2] - peer_q[:, 2]))
    print(f"Bouc-Wen one-storey building: largest |u, v| difference {du:.3e} m, |phi| {dphi:.3e} rad over "
          f"{len(t_out)} rows; peak |v| {np.max(np.abs(peer_q[:, 1])):.4f} m")
    if du > 1e-8 or dphi > 2e-9:
        failures.append("Bouc-Wen history differs")
    assert len(springs) == len(COLUMNS) * 2, len(springs)
    worst_t, worst_slip, worst_energy, yielded = 0.0, 0.0, 0.0, 0
    total = float(np.sum(peer.dissipated))
    for j, s in enumerate(springs):
        first = s["first_yield_t_s"]
        if np.isnan(peer.first_yield[j]) != (first == ""):
            failures.append(f"spring {j}: first yield {first!r}, peer {peer.first_yield[j]!r}")
        elif first != "":
            yielded += 1
            worst_t = max(worst_t, abs(float(first) - peer.first_yield[j]))
        worst_slip = max(worst_slip, abs(float(s["final_slip_m"]) - peer.slip[j]))
        worst_energy = max(worst_energy, abs(float(s["hysteretic_kJ"]) - peer.dissipated[j]))
    energy = summary["energy"]
    print(f"{yielded} of {len(springs)} springs passed d_y; largest first-yield difference {worst_t:.2e} s, "
          f"final-slip difference {worst_slip:.2e} m, per-spring energy difference {worst_energy:.2e} kJ; "
          f"hysteretic {energy['hysteretic_kJ']:.6f} kJ, peer {total:.6f} kJ; audit residual "
          f"{energy['relative_residual']:.2e}")
    if yielded < 6:
        failures.append("the scene should make both column lines pass their yield drift")
    if worst_t > 1e-7 or worst_slip > 1e-8:
        failures.append("Bouc-Wen first yields or final slips differ")
    if worst_energy > 1e-6 * total or abs(energy["hysteretic_kJ"] - total) > 1e-6 * total:
        failures.append("Bouc-Wen hysteretic energy differs")
    if abs(energy["relative_residual"]) > 1e-6:
        failures.append("Bouc-Wen energy audit does not close")


def main():
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    out.mkdir(parents=True, exist_ok=True)
    failures = []
    check_one_storey(program, out, failures)
    law = 'law = "bouc-wen"\nyield_drift_ratio = 0.002\nhardening_ratio = 0.05\nn = 2\n'
    check_second_method(program, out, failures, paper_with_yielding(out, law, "paper-bouc-wen.toml"), "Bouc-Wen",
                        residual_limit=1e-6)
    root = Path(__file__).resolve().parents[2]
    check_needed_gap_brackets(program, out, root / "examples/paper/paper-bouc-wen.toml", failures)
    program_run.finish(failures)


if __name__ == "__main__":
    main()
