#!/usr/bin/python3
"""An independent solution of the paper scene: scipy's DOP853 with event location.

Written from the model's equations alone (docs and the published example's data), sharing no
code with `pounding`: the buildings, damping, record processing, contact candidates, signed gaps
with exact rotation and the restitution impulse are all built here. It serves two purposes:

- a peer for speed comparisons (issue 12: `pounding` must beat it by a wide margin), and
- a check of `pounding`'s impact times (--compare FOLDER: the impacts.csv of a `pounding run`
  of examples/paper/paper.toml at the same gap).

It follows the flight up to the first impact that would be held in sustained contact
(post-impact separation speed below `--hold-velocity`), the stretch where impact times are
defined without a contact-holding model, and prints the impacts it found.

    bench/peers/scipy_paper.py [--gap 0.20] [--rtol 1e-10] [--compare out/paper]
    bench/peers/scipy_paper.py --manifest validation/peers/scipy-paper.verify.toml   (the check cases for verify)
"""
import argparse
import csv
import math
import sys
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "tools"))
from peer_manifest import manifest_is_current  # noqa: E402  (the check behind scipy_peer_current)
RECORD = ROOT / "examples/records/elcentro1940_ns_0.02s.AT2"
E_KPA, STOREY_M, ZETA = 3.15e7, 3.0, 0.05


def building(storeys, outline, cm, mass_t, top_mass_t, xs, ys, b_m, frame_factor):
    """M, K, C (3N, floor by floor: u, v, φ about the CM) and the slab geometry."""
    n = 3 * storeys
    masses = [mass_t] * (storeys - 1) + [top_mass_t]
    lx = max(p[0] for p in outline) - min(p[0] for p in outline)
    ly = max(p[1] for p in outline) - min(p[1] for p in outline)
    m = np.zeros((n, n))
    for j, mj in enumerate(masses):
        m[3 * j:3 * j + 3, 3 * j:3 * j + 3] = np.diag([mj, mj, mj * (lx**2 + ly**2) / 12])
    k_col = frame_factor * 12 * E_KPA * (b_m**4 / 12) / STOREY_M**3  # square section: kx = ky
    ks = np.zeros((3, 3))
    for x in xs:
        for y in ys:
            t = np.array([[1, 0, -(y - cm[1])], [0, 1, x - cm[0]]])
            ks += k_col * t.T @ t
    k = np.zeros((n, n))
    for j in range(storeys):  # storey j joins floor j-1 (ground for j = 0) and floor j
        k[3 * j:3 * j + 3, 3 * j:3 * j + 3] += ks
        if j > 0:
            k[3 * j - 3:3 * j, 3 * j - 3:3 * j] += ks
            k[3 * j:3 * j + 3, 3 * j - 3:3 * j] -= ks
            k[3 * j - 3:3 * j, 3 * j:3 * j + 3] -= ks
    w = np.sqrt(eigh(k, m, eigvals_only=True))
    a1 = 2 * ZETA / (w[0] + w[2])  # Rayleigh, ζ at modes 1 and 3
    a0 = a1 * w[0] * w[2]
    return dict(m=m, k=k, c=a0 * m + a1 * k, cm=np.array(cm), outline=outline, storeys=storeys,
                period_s=2 * math.pi / w[0])


def record():
    """The paper's reading: the first 245 samples re-spaced 0.05 s apart, peak 0.32 g, in m/s²."""
    lines = RECORD.read_text().splitlines()[4:]
    values = [float(v) for line in lines for v in line.split()][:245]
    a = np.array(values)
    return np.arange(len(a)) * 0.05, a * (0.32 * 9.81 / np.max(np.abs(a)))


class Pair:
    """A vertex of slab `a` (building ia, floor f) against an edge q1→q2 of slab `b`."""

    def __init__(self, floor, ia, vertex, ib, q1, q2, outward):
        self.floor, self.ia, self.ib = floor, ia, ib
        self.p, self.q1, self.q2, self.normal = map(np.array, (vertex, q1, q2, outward))


def rot(phi):
    c, s = math.cos(phi), math.sin(phi)
    return np.array([[c, -s], [s, c]])


class Scene:
    def __init__(self, gap_m, restitution):
        d = gap_m
        self.b = [building(7, [(-24, 0), (0, 0), (0, 20), (-24, 20)], (-10.8, 11.0), 555, 530,
                           [-24, -18, -12, -6, 0], [0, 5, 10, 15, 20], 0.45, 0.746251),
                  building(10, [(d, 8), (d + 28, 8), (d + 28, 33), (d, 33)], (d + 12.6, 19.25), 845, 810,
                           [d, d + 7, d + 14, d + 21, d + 28], [8, 13, 18, 23, 28, 33], 0.50, 0.572683)]
        self.k = restitution
        self.n1, n = 21, 51
        self.n = n
        m = np.zeros((n, n)); kk = np.zeros((n, n)); c = np.zeros((n, n))
        for off, b in ((0, self.b[0]), (21, self.b[1])):
            s = slice(off, off + 3 * b["storeys"])
            m[s, s], kk[s, s], c[s, s] = b["m"], b["k"], b["c"]
        self.m_diag = np.diag(m).copy()
        self.a = np.block([[np.zeros((n, n)), np.eye(n)], [-np.linalg.solve(m, kk), -np.linalg.solve(m, c)]])
        self.r = np.zeros(n)
        self.r[0::3] = 1.0  # every u along x (β = 0)
        # The only pairs the geometry allows (floors 1..7): B1's corner (0, 20) on B2's edge x = d
        # (outward normal −x), and B2's corner (d, 8) on B1's edge x = 0 (outward normal +x).
        self.pairs = []
        for f in range(7):
            self.pairs.append(Pair(f, 0, (0, 20), 1, (d, 33), (d, 8), (-1, 0)))
            self.pairs.append(Pair(f, 1, (d, 8), 0, (0, 0), (0, 20), (1, 0)))

    def dof(self, building, floor):
        return (0 if building == 0 else self.n1) + 3 * floor

    def point(self, y, building, floor, rest):
        """Position and velocity of the slab point at rest position `rest`."""
        i = self.dof(building, floor)
        u, v, phi = y[i:i + 3]
        du, dv, dphi = y[self.n + i:self.n + i + 3]
        rho = rot(phi) @ (rest - self.b[building]["cm"])
        pos = self.b[building]["cm"] + np.array([u, v]) + rho
        vel = np.array([du, dv]) + dphi * np.array([-rho[1], rho[0]])
        return pos, vel

    def gap(self, y, pair):
        """Signed gap, its rate, the projection parameter on the edge, the normal, the lever arms."""
        pa, va = self.point(y, pair.ia, pair.floor, pair.p)
        q1, v1 = self.point(y, pair.ib, pair.floor, pair.q1)
        q2, _ = self.point(y, pair.ib, pair.floor, pair.q2)
        phi_b = y[self.dof(pair.ib, pair.floor) + 2]
        dphi_b = y[self.n + self.dof(pair.ib, pair.floor) + 2]
        n = rot(phi_b) @ pair.normal
        g = (pa - q1) @ n
        # Rate: the struck slab's material point under P moves with v_B(P); n rotates with φ_b.
        _, vb_at_p = self.point_velocity_at(y, pair.ib, pair.floor, pa)
        gdot = (va - vb_at_p) @ n
        s = (pa - q1) @ (q2 - q1) / ((q2 - q1) @ (q2 - q1))
        return g, gdot, s, n, pa

    def point_velocity_at(self, y, building, floor, position):
        i = self.dof(building, floor)
        centre = self.b[building]["cm"] + y[i:i + 2]
        rho = position - centre
        dphi = y[self.n + i + 2]
        return rho, y[self.n + i:self.n + i + 2] + dphi * np.array([-rho[1], rho[0]])

    def impulse(self, y, pair, n, pa, gdot, restitution):
        """Newton restitution: velocities after a single frictionless impact (DESIGN §2)."""
        y = y.copy()
        parts = []
        for building, sign in ((pair.ia, 1.0), (pair.ib, -1.0)):
            rho, _ = self.point_velocity_at(y, building, pair.floor, pa)
            g_row = sign * np.array([n[0], n[1], rho[0] * n[1] - rho[1] * n[0]])
            parts.append((self.dof(building, pair.floor), g_row))
        a = sum(np.sum(g_row**2 / self.m_diag[i:i + 3]) for i, g_row in parts)
        impulse = (1 + restitution) * (-gdot) / a
        for i, g_row in parts:
            y[self.n + i:self.n + i + 3] += g_row * impulse / self.m_diag[i:i + 3]
        return y, impulse


REOPEN_M = 1e-9  # a pair just struck is masked until its gap has re-opened by this much


def gap_events(scene, masked):
    """Closing events for every pair, and a re-opening event for the masked ones (DESIGN §3: a
    root just handled sits at g ≈ 0 and would be found again at once)."""
    events = []
    for index, pair in enumerate(scene.pairs):
        if index in masked:
            def event(t_, y_, pair=pair):
                return scene.gap(y_, pair)[0] - REOPEN_M
            event.direction = 1
        else:
            def event(t_, y_, pair=pair):
                return scene.gap(y_, pair)[0]
            event.direction = -1
        event.terminal = True
        events.append(event)
    return events


def solve(scene, t_rec, a_rec, rtol, atol, hold_velocity):
    """Impacts up to the first one that would be held, or to the end of the record."""
    y = np.zeros(2 * scene.n)
    t = 0.0
    impacts = []
    masked = set()
    b = np.concatenate([np.zeros(scene.n), -scene.r])
    bounded_until, bound = 0.0, np.inf  # after an impact: steps short against the next flight
    knot = 1
    while knot < len(t_rec):
        t0, t1, a0, a1 = t_rec[knot - 1], t_rec[knot], a_rec[knot - 1], a_rec[knot]
        slope = (a1 - a0) / (t1 - t0)

        def rhs(tt, yy):
            return scene.a @ yy + b * (a0 + slope * (tt - t0))

        end = min(t1, bounded_until) if t < bounded_until else t1
        sol = solve_ivp(rhs, (t, end), y, method="DOP853", rtol=rtol, atol=atol,
                        max_step=bound if t < bounded_until else np.inf, events=gap_events(scene, masked))
        y, t = sol.y[:, -1], sol.t[-1]
        if sol.status != 1:
            if t >= t1:
                knot += 1
            continue
        k = next(k for k, te in enumerate(sol.t_events) if len(te))
        if k in masked:
            masked.discard(k)
            continue
        g, gdot, s, n, pa = scene.gap(y, scene.pairs[k])
        if not 0.0 <= s <= 1.0 or gdot >= 0.0:
            sys.exit(f"event at t = {t} that is not an impact (s = {s}, gdot = {gdot}); not handled")
        # A pair that would separate slower than hold_velocity is held: that impact is plastic.
        held = -scene.k * gdot < hold_velocity
        y, impulse = scene.impulse(y, scene.pairs[k], n, pa, gdot, 0.0 if held else scene.k)
        impacts.append(dict(t_s=t, floor=scene.pairs[k].floor + 1, striking=scene.pairs[k].ia + 1,
                            approach_mps=-gdot, impulse_kNs=impulse))
        if held:
            return impacts, t, "held"
        masked.add(k)
        flight_s = predicted_flight_s(scene, rhs, t, y, scene.pairs[k])
        bounded_until, bound = t + 2 * flight_s, flight_s / 8
    return impacts, t, "end"


def predicted_flight_s(scene, rhs, t, y, pair):
    """2 ġ⁺/|g̈| (DESIGN §3: the next flight may be far shorter than the last step)."""
    h = 1e-7
    gdot = scene.gap(y, pair)[1]
    gddot = (scene.gap(y + h * rhs(t, y), pair)[1] - gdot) / h
    return 2 * gdot / max(abs(gddot), 1e-9)


def read_pounding_impacts(folder):
    """`pounding run`'s impacts up to and including the first that starts a sustained contact."""
    rows = []
    with open(Path(folder) / "impacts.csv") as handle:
        for row in csv.DictReader(handle):
            rows.append(dict(t_s=float(row["t_s"]), impulse_kNs=float(row["impulse_kNs"])))
            if row["starts_sustained_contact"] == "1":
                break
    return rows


def compare(impacts, theirs):
    """Largest impact-time difference (s) and relative impulse difference; None if the counts differ."""
    if len(theirs) != len(impacts):
        return None
    dt = max((abs(a["t_s"] - i["t_s"]) for a, i in zip(theirs, impacts)), default=0.0)
    di = max((abs(a["impulse_kNs"] - i["impulse_kNs"]) / i["impulse_kNs"] for a, i in zip(theirs, impacts)),
             default=0.0)
    return dt, di


# (gap m, restitution): held accumulations (0.5), none (1.0, 0.8: the whole record), k = 0, one impact.
CHECK_CASES = [(0.20, 0.5), (0.30, 0.5), (0.35, 0.5), (0.20, 1.0), (0.20, 0.8), (0.20, 0.0)]


def check(pounding, method, time_tol_s, impulse_tol, args):
    """Runs `pounding` on examples/paper/paper.toml for every case and compares; exit 1 on a mismatch."""
    import subprocess
    import tempfile
    t_rec, a_rec = record()
    failures = 0
    with tempfile.TemporaryDirectory() as scratch:
        for gap, k in CHECK_CASES:
            out = Path(scratch) / f"g{gap}-k{k}"
            subprocess.run([pounding, "run", str(ROOT / "examples/paper/paper.toml"), "--method", method,
                            "--gap", repr(gap), "--restitution", repr(k), "--out", str(out), *args.pounding_arg],
                           check=True, stdout=subprocess.DEVNULL)
            impacts, _, _ = solve(Scene(gap, k), t_rec, a_rec, args.rtol, args.atol, args.hold_velocity)
            theirs = read_pounding_impacts(out)
            result = compare(impacts, theirs)
            ok = result is not None and result[0] <= time_tol_s and result[1] <= impulse_tol
            failures += not ok
            detail = (f"{len(theirs)} impacts against {len(impacts)}" if result is None else
                      f"{len(impacts)} impacts, times within {result[0]:.2e} s, impulses within {result[1]:.2e}")
            print(f"gap {gap} m, k = {k}: {detail}: {'ok' if ok else 'MISMATCH'}")
    print(f"{method} against DOP853 (rtol {args.rtol}) on {len(CHECK_CASES)} cases: "
          f"{'all agree' if not failures else f'{failures} disagree'} (tolerance {time_tol_s} s, {impulse_tol} relative)")
    return 1 if failures else 0


MANIFEST_METHODS = [("exact", "", 1e-9, 1e-6),
                    ("cvode-bdf", "settings = { rtol = 1e-12, atol = 1e-14 }", 1e-9, 1e-5)]


def write_manifest(path, args):
    """A `pounding verify` manifest of CHECK_CASES on the exact path and CVODE BDF (rtol 1e-12):
    this solver's impact times and impulses written as the expected ones, over the stretch it
    covers (up to the first held contact), with --check's tolerances."""
    t_rec, a_rec = record()
    lines = ["# Written by bench/peers/scipy_paper.py --manifest (an independent solution of the paper",
             "# scene: scipy DOP853 with events, sharing no code with pounding): its impact times and",
             "# impulses up to the first held contact, as `pounding verify` cases (CTest verify_scipy_peer).",
             f"# DOP853 rtol {args.rtol}, atol {args.atol}, hold velocity {args.hold_velocity} m/s.",
             'name = "scipy-peer"', ""]
    for gap, k in CHECK_CASES:
        impacts, t_end, reason = solve(Scene(gap, k), t_rec, a_rec, args.rtol, args.atol, args.hold_velocity)
        # Up to and including the impact that starts the first held contact (then pounding holds it).
        window = f", before_s = {impacts[-1]['t_s'] + 1e-6!r}" if reason == "held" else ""
        for method, settings, time_tol, impulse_tol in MANIFEST_METHODS:
            lines += ["[[case]]", f'name = "gap{gap:g}-k{k:g}-{method}"', 'scene = "../../examples/paper/paper.toml"',
                      f"gap_m = {gap!r}", f"restitution = {k!r}", f'method = "{method}"', *([settings] if settings else []),
                      "[case.checks]", f"impact_times = {{ abs_s = {time_tol!r}{window} }}",
                      f"impulses = {{ rel = {impulse_tol!r}{window} }}", "[case.expected]",
                      f"impact_times_s = [{', '.join(repr(i['t_s']) for i in impacts)}]",
                      f"impulses_kNs = [{', '.join(repr(i['impulse_kNs']) for i in impacts)}]", ""]
    Path(path).write_text("\n".join(lines))
    print(f"Wrote {path}: {len(CHECK_CASES)} cases x {len(MANIFEST_METHODS)} methods")


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--gap", type=float, default=0.20)
    parser.add_argument("--restitution", type=float, default=0.5)
    parser.add_argument("--rtol", type=float, default=1e-10)
    parser.add_argument("--atol", type=float, default=1e-12)
    parser.add_argument("--hold-velocity", type=float, default=1e-3)
    parser.add_argument("--compare", help="a `pounding run` output folder of the same scene, gap and k")
    parser.add_argument("--check", metavar="POUNDING", help="run this `pounding` program on the check cases")
    parser.add_argument("--method", default="exact", help="with --check: the method to check (default exact)")
    parser.add_argument("--pounding-arg", action="append", default=[],
                        help="with --check: one more argument for `pounding run` (repeat it)")
    parser.add_argument("--time-tol", type=float, default=1e-9, help="with --check: impact times (s)")
    parser.add_argument("--impulse-tol", type=float, default=1e-6, help="with --check: relative impulses")
    parser.add_argument("--manifest", help="write the check cases as a `pounding verify` manifest to this file")
    parser.add_argument("--manifest-current", metavar="COMMITTED",
                        help="with --manifest: exit 1 unless COMMITTED holds the same expected impacts "
                             "(within a tenth of its checks' tolerances: tools/peer_manifest.py)")
    args = parser.parse_args()
    if args.manifest:
        write_manifest(args.manifest, args)
        sys.exit(0 if not args.manifest_current or manifest_is_current(args.manifest_current, args.manifest) else 1)
    if args.check:
        sys.exit(check(args.check, args.method, args.time_tol, args.impulse_tol, args))
    scene = Scene(args.gap, args.restitution)
    print(f"T1 = {scene.b[0]['period_s']:.4f} s (B1), {scene.b[1]['period_s']:.4f} s (B2)")
    t_rec, a_rec = record()
    start = time.process_time()
    impacts, t_end, reason = solve(scene, t_rec, a_rec, args.rtol, args.atol, args.hold_velocity)
    cpu_s = time.process_time() - start
    print(f"DOP853 rtol {args.rtol}, atol {args.atol}: {len(impacts)} impacts up to t = {t_end:.6f} s "
          f"({'first held contact' if reason == 'held' else 'end of record'}); CPU {cpu_s:.3f} s")
    for i in impacts:
        print(f"  t = {i['t_s']:.9f} s floor {i['floor']} B{i['striking']} strikes, approach "
              f"{i['approach_mps']:.5f} m/s, impulse {i['impulse_kNs']:.3f} kN·s")
    if args.compare:
        result = compare(impacts, read_pounding_impacts(args.compare))
        if result is None:
            sys.exit(f"{args.compare} has a different number of impacts before its first sustained contact")
        print(f"against {args.compare}: impact times within {result[0]:.3e} s, impulses within "
              f"{result[1]:.3e} (relative), {len(impacts)} impacts")


if __name__ == "__main__":
    main()
