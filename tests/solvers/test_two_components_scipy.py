#!/usr/bin/python3
"""Two horizontal components at once against an independent computation (scipy, no code shared).

    tests/solvers/test_two_components_scipy.py POUNDING [OUT] [--quick]

--quick runs checks 1, 2 and 11 only (small scenes: the sanitizer pass runs these).

A one-storey building with two column lines of different size (x = 0: three 0.40 m columns,
x = 16 m: three 0.60 m columns) and its centre of mass 1 m off the plan centre, shaken by a pair:
H1 sampled every 0.01 s in m/s2 for 4 s, H2 every 0.0075 s in cm/s2 for 3.5 s (the grids meet only
every 0.03 s, and H2 ends first), H1 along beta = 30 degrees and H2 along 120 degrees, the pair
scaled by one factor to a peak of 0.3 g in its larger component. A second, elastic building stands
10 m away (no contact). The peer assembles its own K, Rayleigh damping and loads
-M (r1 a1(t) + r2 a2(t)), each a_c interpolated on its own samples (np.interp), and integrates
with DOP853 over the union of both grids, up to where H2 ends. Checked:
  1. u, v, phi of the eccentric building at every history row, for cvode-bdf at rtol 1e-10 and
     for the exact path: within 1e-8 m and 1e-9 rad;
  2. the pair's scaling: the larger processed peak is 0.3 g to round-off.
Then the pair against closed forms, on the paper scene at gap 0.05 m (impacts) with the exact path:
  3. H2 = 0 (a zero record on H1's grid) gives the one-component run bit for bit (impacts.csv
     identical on exact, cvode-bdf and arkode-erk);
  4. H1 = H2 = a at beta is one component of sqrt(2) a at beta + 45 degrees: the same impacts,
     within 1e-9 s;
  5. the Kobe pair example (examples/beyond-paper/two-components.toml) on cvode-bdf and arkode-erk
     at rtol 1e-10 agrees with the exact path impact by impact within 1e-7 s;
  6. `pounding gap` on the pair: at its needed gap + 1e-5 m the buildings do not meet, at
     - 1e-5 m they strike;
  7. the pair given on the command line (--record2, --record2-column) runs as the scene's
     [excitation.second] does (the same impacts, bit for bit), and --record2-column without a
     second component is refused naming the option.
Spectral scaling (--scale-to-sa), against the peer's own SDOF x'' + 2 zeta w x' + w^2 x = -a(t)
(DOP853 at rtol 1e-12 on each record interval, extrema located by events on x' = 0):
  8. one component at B1's first period (0.765 s from `pounding modes`): the record factor makes
     the 5 %-damped PSA the target within 1e-7 (relative);
  11. [excitation.second] reads what it leaves out as H1 does: a four-column file (index, t, H1,
     H2) with H1 at time_column 2 gives H2 its peak at its own time, and a column H2's file lacks
     is refused naming excitation.second.accel_column;
  10. (`gap --all-angles` on the Kobe pair: superposed, never below the record angle's needed gap;
     tests/analysis/test_all_angles.py checks it against single-angle runs.)
  12. over a range, "asce7(SDS=1.0,SD1=0.6,TL=8)@0.2-2B1": the record factor is the geometric mean
     of the ASCE 7-16 design spectrum (written here) over the peer's PSA at the 50 log-spaced
     periods of [0.2, 2] x 0.765 s, within 1e-7;
  9. the Kobe pair at 1.0 s: RotD100 = max_t |(x1, x2)| (extrema of x1^2 + x2^2 as events) is the
     target within 1e-6 (the program searches angles in 0.1 degree steps: cos 0.05 deg = 1 - 4e-7).
"""
import csv
import json
import math
import subprocess
import sys
import tempfile
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

ROOT = Path(__file__).resolve().parents[2]
E_KPA, HEIGHT_M, MASS_T, ZETA = 3.0e7, 3.5, 400.0, 0.05
SLAB = (0.0, 0.0, 16.0, 10.0)
CM = np.array([9.0, 5.0])
COLUMNS = [((0.0, y), 0.40) for y in (0.0, 5.0, 10.0)] + [((16.0, y), 0.60) for y in (0.0, 5.0, 10.0)]
BETA_DEG, PGA_G, G = 30.0, 0.3, 9.81
H1_DT, H1_END, H2_DT, H2_END = 0.01, 4.0, 0.0075, 3.5


def h1_record():
    t = np.round(np.arange(0.0, H1_END + H1_DT / 2, H1_DT), 10)
    return t, 2.0 * np.sin(2 * np.pi * 1.3 * t) * np.exp(-0.3 * t) + 0.8 * np.sin(2 * np.pi * 4.1 * t + 0.4)


def h2_record():  # cm/s2
    t = np.round(np.arange(0.0, H2_END + H2_DT / 2, H2_DT), 10)
    return t, 250.0 * np.sin(2 * np.pi * 0.9 * t + 1.0) * np.exp(-0.2 * t) - 120.0 * np.sin(2 * np.pi * 2.7 * t)


def write_columns(path, t, a):
    path.write_text("".join(f"{ti:.10g} {ai:.17g}\n" for ti, ai in zip(t, a)))


def scene_text(h1, h2):
    columns = ", ".join(f"[{x}, {y}, {s}, {s}]" for (x, y), s in COLUMNS)
    x0, y0, x1, y1 = SLAB
    return f"""name = "pair-peer"
[[building]]
name = "Y"
storeys = 1
storey_height_m = {HEIGHT_M}
slab = [[{x0}, {y0}], [{x1}, {y0}], [{x1}, {y1}], [{x0}, {y1}]]
centre_of_mass = [{CM[0]}, {CM[1]}]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA}
frame_factor = 1.0
columns = [{columns}]
[building.damping]
ratio = {ZETA}
modes = [1, 3]

[[building]]
name = "E"
storeys = 1
storey_height_m = {HEIGHT_M}
slab = [[26.0, 0.0], [36.0, 0.0], [36.0, 10.0], [26.0, 10.0]]
centre_of_mass = [31.0, 5.0]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA}
frame_factor = 1.0
columns = [[26.0, 0.0, 0.5, 0.5], [36.0, 0.0, 0.5, 0.5], [26.0, 10.0, 0.5, 0.5], [36.0, 10.0, 0.5, 0.5]]

[excitation]
file = "{h1}"
format = "columns"
units = "m/s2"
scale_to_pga_g = {PGA_G}
g_mps2 = {G}
direction_deg = {BETA_DEG}

[excitation.second]
file = "{h2}"
units = "cm/s2"

[contact]
gap_m = 10.0
restitution = 0.5
"""


class Peer:
    """The eccentric building alone: q = (u, v, phi) of its slab about the CM."""

    def __init__(self):
        x0, y0, x1, y1 = SLAB
        a, b = x1 - x0, y1 - y0
        m = np.array([MASS_T, MASS_T, MASS_T * (a * a + b * b) / 12.0])  # "uniform" J about the centroid
        rows, ks = [], []
        for (x, y), s in COLUMNS:
            k = 12.0 * E_KPA * s ** 4 / 12.0 / HEIGHT_M ** 3
            arm = np.array([x, y]) - CM
            rows += [np.array([1.0, 0.0, -arm[1]]), np.array([0.0, 1.0, arm[0]])]
            ks += [k, k]
        rows, ks = np.array(rows), np.array(ks)
        self.m, self.K = m, (rows.T * ks) @ rows
        w = np.sqrt(np.sort(eigh(self.K, np.diag(m))[0]))
        a0, a1 = 2 * ZETA * w[0] * w[2] / (w[0] + w[2]), 2 * ZETA / (w[0] + w[2])
        self.C = a0 * np.diag(m) + a1 * self.K
        beta = math.radians(BETA_DEG)
        self.r1 = np.array([math.cos(beta), math.sin(beta), 0.0])
        self.r2 = np.array([-math.sin(beta), math.cos(beta), 0.0])

    def run(self, h1, h2, out_times):
        (t1, a1), (t2, a2) = h1, h2
        rhs = lambda t, y: np.concatenate(
            [y[3:], (-self.K @ y[:3] - self.C @ y[3:]) / self.m - self.r1 * np.interp(t, t1, a1)
             - self.r2 * np.interp(t, t2, a2)])
        end = min(t1[-1], t2[-1])
        grid = np.union1d(t1[t1 <= end], t2[t2 <= end])
        y, rows, k = np.zeros(6), [], 0
        for a, b in zip(grid[:-1], grid[1:]):
            if b - a < 1e-12:
                continue
            sol = solve_ivp(rhs, (a, b), y, method="DOP853", rtol=1e-12, atol=1e-14, dense_output=True)
            while k < len(out_times) and out_times[k] <= b + 1e-12:
                rows.append(sol.sol(min(out_times[k], b))[:3])
                k += 1
            y = sol.y[:, -1]
        return np.array(rows)


def history(folder):
    with open(folder / "history.csv") as f:
        rows = list(csv.DictReader(f))
    return (np.array([float(r["t_s"]) for r in rows]),
            np.array([[float(r[f"B1_f1_{q}"]) for q in ("u_m", "v_m", "phi_rad")] for r in rows]))


def impacts(folder):
    with open(folder / "impacts.csv") as f:
        return [((r["level"], r["striking_building"], r["vertex"], r["struck_edge"]), float(r["t_s"]))
                for r in csv.DictReader(f)]


def run(program, scene, folder, *options):
    done = subprocess.run([program, "run", str(scene), "--out", str(folder), "--no-progress", *options],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    return json.loads((folder / "summary.json").read_text())


def check_peer(program, out, failures):
    h1, h2 = h1_record(), h2_record()
    write_columns(out / "h1.txt", *h1)
    write_columns(out / "h2.txt", *h2)
    scene = out / "pair.toml"
    scene.write_text(scene_text(out / "h1.txt", out / "h2.txt"))
    # 2. one factor for the pair, from its larger peak over the span both cover
    span = lambda t, a: np.abs(a[t <= H2_END + 1e-12]).max()
    factor = PGA_G * G / max(span(*h1), 0.01 * span(*h2))
    peer_h1, peer_h2 = (h1[0], factor * h1[1]), (h2[0], factor * 0.01 * h2[1])
    check = subprocess.run([program, "check", str(scene)], capture_output=True, text=True)
    assert check.returncode == 0, check.stderr
    peaks = [float(line.split("=")[2].split("g")[0]) for line in check.stdout.splitlines() if "peak |a_g|" in line]
    print(f"pair peaks printed by check: {peaks} g")
    if len(peaks) != 2 or abs(max(peaks) - PGA_G) > 1e-4:
        failures.append(f"the pair's larger peak is not {PGA_G} g: {peaks}")
    peer = Peer()
    for method, options in (("cvode-bdf", ["--rtol", "1e-10", "--atol", "1e-12"]), ("exact", [])):
        folder = out / f"peer-{method}"
        summary = run(program, scene, folder, "--method", method, *options)
        t, q = history(folder)
        if abs(t[-1] - H2_END) > 1e-9:
            failures.append(f"{method}: the pair's run ends at {t[-1]} s, not where H2 ends ({H2_END} s)")
            continue
        expected = peer.run(peer_h1, peer_h2, t)
        du, dphi = np.abs(q[:, :2] - expected[:, :2]).max(), np.abs(q[:, 2] - expected[:, 2]).max()
        print(f"{method}: {len(t)} rows against the scipy peer: |du, dv| {du:.2e} m, |dphi| {dphi:.2e} rad "
              f"(peak |u, v| {np.abs(expected[:, :2]).max():.3e} m), status {summary['status']}")
        if du > 1e-8 or dphi > 1e-9:
            failures.append(f"{method}: the pair's response differs from the peer by {du:.2e} m / {dphi:.2e} rad")


def paper_scene(out, name, excitation):
    text = (ROOT / "examples/paper/paper.toml").read_text()
    head, rest = text.split("[excitation]", 1)
    path = out / f"{name}.toml"
    path.write_text(head + excitation + rest[rest.index("[contact]"):])
    return path


def compare(name, a, b, tolerance, failures):
    worst = max((abs(x[1] - y[1]) for x, y in zip(a, b)), default=0.0)
    print(f"{name}: {len(a)} and {len(b)} impacts, largest time difference {worst:.2e} s")
    if len(a) != len(b) or not a or any(x[0] != y[0] for x, y in zip(a, b)) or worst > tolerance:
        failures.append(f"{name}: the impacts differ (tolerance {tolerance} s)")


def check_closed_forms(program, out, failures):
    # 3. H2 = 0 on the paper record's grid (12.2 s re-spaced 0.05 s): the same run, bit for bit.
    t = np.round(np.arange(0.0, 12.2 + 1e-9, 0.05), 10)
    zero = out / "zero.txt"
    write_columns(zero, t, np.zeros_like(t))
    paper_excitation = (ROOT / "examples/paper/paper.toml").read_text().split("[excitation]", 1)[1]
    paper_excitation = "[excitation]" + paper_excitation[:paper_excitation.index("[contact]")]
    paper_excitation = paper_excitation.replace("../records/", str(ROOT / "examples/records") + "/")
    with_zero = paper_scene(out, "zero-h2", paper_excitation +
                            f'[excitation.second]\nfile = "{zero}"\nformat = "columns"\nunits = "m/s2"\n\n')
    for method in ("exact", "cvode-bdf", "arkode-erk"):
        single = run(program, ROOT / "examples/paper/paper.toml", out / f"single-{method}", "--method", method,
                     "--history", "off", "--gap", "0.05")
        run(program, with_zero, out / f"zero-h2-{method}", "--method", method, "--history", "off", "--gap", "0.05")
        same = (out / f"single-{method}/impacts.csv").read_bytes() == (out / f"zero-h2-{method}/impacts.csv").read_bytes()
        print(f"3. H2 = 0 against one component, {method}: {single['impact_count']} impacts, "
              f"impacts.csv {'identical' if same else 'DIFFERENT'}")
        if not same:
            failures.append(f"3. {method}: a pair with H2 = 0 does not give the one-component run bit for bit")
    # 4. (a, a) at beta against sqrt(2) a at beta + 45 degrees (the pair's PGA scaling is per
    # component, so both take the record's own scale: 0.32 g each, and sqrt(2) 0.32 g along 45).
    beta = 20.0
    diagonal = paper_excitation.replace("direction_deg = 0.0", f"direction_deg = {beta}")
    both = paper_scene(out, "both", diagonal + f'[excitation.second]\nfile = "{ROOT}/examples/records/'
                       'elcentro1940_ns_0.02s.AT2"\ndt_s = 0.05\n\n')
    one = paper_scene(out, "one", paper_excitation.replace("direction_deg = 0.0", f"direction_deg = {beta + 45.0}")
                      .replace("scale_to_pga_g = 0.32", f"scale_to_pga_g = {0.32 * math.sqrt(2.0)!r}"))
    run(program, both, out / "both", "--method", "exact", "--history", "off", "--gap", "0.05")
    run(program, one, out / "one", "--method", "exact", "--history", "off", "--gap", "0.05")
    compare("4. (a, a) at 20 deg against sqrt(2) a at 65 deg", impacts(out / "both"), impacts(out / "one"), 1e-9,
            failures)


def check_methods(program, out, failures):
    example = ROOT / "examples/beyond-paper/two-components.toml"
    run(program, example, out / "kobe-exact", "--method", "exact", "--history", "off")
    for method in ("cvode-bdf", "arkode-erk"):
        run(program, example, out / f"kobe-{method}", "--method", method, "--rtol", "1e-10", "--atol", "1e-12",
            "--history", "off")
        compare(f"5. Kobe pair, {method} against exact", impacts(out / "kobe-exact"),
                impacts(out / f"kobe-{method}"), 1e-7, failures)
    done = subprocess.run([program, "gap", str(example), "--out", str(out / "kobe-gap")], capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    needed = json.loads((out / "kobe-gap/gap.json").read_text())["needed_gap_m"]
    counts = []
    for offset in (1e-5, -1e-5):
        run(program, example, out / f"kobe-gap{offset:+g}", "--gap", repr(needed + offset), "--history", "off")
        counts.append(len(impacts(out / f"kobe-gap{offset:+g}")))
    kobe = ROOT / "examples/records/kobe1995_jma_ns_ew_0.005s_cms2.txt"
    run(program, example, out / "kobe-cli", "--method", "exact", "--history", "off", "--record", str(kobe),
        "--record-dt", "0.005", "--record-column", "1", "--record2", str(kobe), "--record2-column", "2")
    if impacts(out / "kobe-cli") != impacts(out / "kobe-exact"):
        failures.append("7. --record2 does not run as the scene's [excitation.second]")
    refused = subprocess.run([program, "run", str(ROOT / "examples/paper/paper.toml"), "--record2-column", "2",
                              "--out", str(out / "refused")], capture_output=True, text=True)
    print(f"7. --record2-column alone: exit {refused.returncode}: {refused.stderr.strip()}")
    if refused.returncode != 2 or "--record2-column" not in refused.stderr:
        failures.append("7. --record2-column without a second component is not refused by name")
    done = subprocess.run([program, "gap", str(example), "--all-angles", "--out", str(out / "kobe-all")],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    all_angles = json.loads((out / "kobe-all/gap.json").read_text())["all_angles"]
    print(f"10. Kobe pair, all angles: {all_angles['needed_gap_m']:.6f} m at {all_angles['angle_deg']:.2f} deg "
          f"({all_angles['method']}, {all_angles['runs']} runs); at the record's own angle {needed:.6f} m")
    if all_angles["method"] != "superposition" or all_angles["needed_gap_m"] < needed - 1e-9:
        failures.append("10. the pair's all-angles needed gap is below its needed gap at the record's angle")
    print(f"6. Kobe pair: needed gap {needed:.6f} m; impacts at +1e-5 m: {counts[0]}, at -1e-5 m: {counts[1]}")
    if counts[0] != 0 or counts[1] == 0:
        failures.append("6. the pair's needed gap does not separate striking from not striking")


def sdof_peak(records, period_s, zeta=0.05):
    """max_t |x(t)| of the 2D oscillator driven by each record (a list of (t, a) on a common grid)."""
    w = 2 * math.pi / period_s
    t = records[0][0]
    k = len(records)

    def rhs(time, y):
        out = np.empty(2 * k)
        for c, (tc, ac) in enumerate(records):
            out[c], out[k + c] = y[k + c], -2 * zeta * w * y[k + c] - w * w * y[c] - np.interp(time, tc, ac)
        return out

    def turning(time, y):
        return float(np.dot(y[:k], y[k:]))

    y, best = np.zeros(2 * k), 0.0
    for a, b in zip(t[:-1], t[1:]):
        sol = solve_ivp(rhs, (a, b), y, method="DOP853", rtol=1e-12, atol=1e-15, events=turning)
        for ye in [*sol.y_events[0], sol.y[:, -1]]:
            best = max(best, float(np.linalg.norm(ye[:k])))
        y = sol.y[:, -1]
    return best * w * w


def check_spectral_scaling(program, out, failures):
    summary = run(program, ROOT / "examples/paper/paper.toml", out / "sa-b1", "--scale-to-sa", "0.4g@B1",
                  "--history", "off", "--method", "exact")
    sa = summary["spectral_scaling"]
    at2 = (ROOT / "examples/records/elcentro1940_ns_0.02s.AT2").read_text().split("\n")
    values = np.array([float(v) for line in at2[4:] for v in line.split()])[:245] * G  # 12.2 s at 0.05 s
    t = np.round(np.arange(245) * 0.05, 10)
    psa = sdof_peak([(t, values)], sa["period_s"])
    error = abs(sa["record_factor"] * psa / (0.4 * G) - 1.0)
    print(f"8. 0.4g@B1: T = {sa['period_s']:.6f} s, record factor {sa['record_factor']:.9f}; the peer's PSA of the "
          f"scaled record is the target within {error:.1e}")
    if abs(sa["period_s"] - 0.765) > 5e-4 or sa["measure"] != "psa" or error > 1e-7:
        failures.append("8. spectral scaling of one component misses the target")
    summary = run(program, ROOT / "examples/beyond-paper/two-components.toml", out / "sa-pair", "--scale-to-sa",
                  "0.5g@1.0s", "--history", "off", "--gap", "1.0", "--method", "exact")
    sa = summary["spectral_scaling"]
    kobe = np.loadtxt(ROOT / "examples/records/kobe1995_jma_ns_ew_0.005s_cms2.txt", comments="%")[:4001] * 0.01
    t = np.round(np.arange(4001) * 0.005, 10)
    rotd100 = sdof_peak([(t, kobe[:, 0]), (t, kobe[:, 1])], 1.0)
    error = abs(sa["record_factor"] * rotd100 / (0.5 * G) - 1.0)
    print(f"9. the Kobe pair at 0.5g@1.0s: record factor {sa['record_factor']:.9f}, measure {sa['measure']}; the "
          f"peer's RotD100 of the scaled pair is the target within {error:.1e}")
    if sa["measure"] != "rotd100" or error > 1e-6:
        failures.append("9. spectral scaling of a pair misses its RotD100 target")
    summary = run(program, ROOT / "examples/paper/paper.toml", out / "sa-range", "--scale-to-sa",
                  "asce7(SDS=1.0,SD1=0.6,TL=8)@0.2-2B1", "--history", "off", "--method", "exact")
    sa = summary["spectral_scaling"]

    def asce7(period):  # ASCE 7-16 11.4.6
        sds, sd1, tl = 1.0, 0.6, 8.0
        t0, ts = 0.2 * sd1 / sds, sd1 / sds
        if period < t0:
            return sds * (0.4 + 0.6 * period / t0)
        return sds if period <= ts else (sd1 / period if period <= tl else sd1 * tl / period ** 2)

    t = np.round(np.arange(245) * 0.05, 10)
    b1 = sa["periods_s"][0] / 0.2
    periods = 0.2 * b1 * (2.0 / 0.2) ** (np.arange(50) / 49.0)
    ratios = [asce7(p) * G / sdof_peak([(t, values)], p) for p in periods]
    expected = math.exp(np.mean(np.log(ratios)))
    error = abs(sa["record_factor"] / expected - 1.0)
    print(f"12. asce7(SDS=1.0,SD1=0.6,TL=8)@0.2-2B1 over {sa['periods_s'][0]:.4f}-{sa['periods_s'][1]:.4f} s: record "
          f"factor {sa['record_factor']:.9f}, the peer's geometric mean {expected:.9f} ({error:.1e})")
    if abs(b1 - 0.765) > 5e-4 or error > 1e-7:
        failures.append("12. the range scaling is not the geometric mean of the target-to-record ratios")


def check_layout(program, out, failures):
    t = np.round(np.arange(0.0, 10.0 + 1e-9, 0.01), 10)
    h1, h2 = np.sin(2 * np.pi * t), np.where(t > 0, np.cos(2 * np.pi * 1.3 * t), 0.0)
    (out / "four.txt").write_text("".join(f"{i} {ti:.2f} {x:.17g} {y:.17g}\n" for i, (ti, x, y) in
                                          enumerate(zip(t, h1, h2))))
    excitation = (f'[excitation]\nfile = "{out / "four.txt"}"\nformat = "columns"\nunits = "m/s2"\n'
                  'time_column = 2\naccel_column = 3\n[excitation.second]\n'
                  f'file = "{out / "four.txt"}"\naccel_column = 4\n\n')
    scene = paper_scene(out, "four", excitation)
    done = subprocess.run([program, "check", str(scene)], capture_output=True, text=True)
    times = [float(line.split("at t = ")[1].split(" s")[0]) for line in done.stdout.splitlines() if "peak |a_g|" in line]
    expected = float(t[np.argmax(np.abs(h2))])
    print(f"11. four columns, H1 at time_column 2: H2 peaks at {times[1:]} s (its own {expected} s)")
    if done.returncode != 0 or len(times) != 2 or abs(times[1] - expected) > 1e-9:
        failures.append("11. [excitation.second] does not read its time column as H1 does")
    bad = paper_scene(out, "four-bad", excitation.replace("accel_column = 4", "accel_column = 7"))
    done = subprocess.run([program, "check", str(bad)], capture_output=True, text=True)
    if done.returncode != 2 or "excitation.second.accel_column = 7" not in done.stderr:
        failures.append(f"11. a column H2's file lacks is not refused by its key: {done.stderr.strip()}")


def main():
    arguments = [a for a in sys.argv[1:] if a != "--quick"]
    program = arguments[0]
    out = Path(arguments[1]) if len(arguments) > 1 else Path(tempfile.mkdtemp(prefix="pair-peer-"))
    out.mkdir(parents=True, exist_ok=True)
    failures = []
    check_peer(program, out, failures)
    check_layout(program, out, failures)
    if "--quick" not in sys.argv:
        check_closed_forms(program, out, failures)
        check_methods(program, out, failures)
        check_spectral_scaling(program, out, failures)
    program_run.finish(failures)


if __name__ == "__main__":
    main()
