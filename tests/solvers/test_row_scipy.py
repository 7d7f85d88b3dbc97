#!/usr/bin/python3
"""A row of three buildings against an independent computation (scipy with events, no code shared).

    tests/solvers/test_row_scipy.py POUNDING [OUT]

A row of three buildings along x, B1 (-x side), B2 in the middle, B3 (+x side), all with 3 m
storeys, so that the floors at 3 m (B1:B2, B2:B3) and 6 m (B1:B2) are levels: B1, two storeys
(slab 8 x 6 m at x in [-8, 0], y in [0, 6], CM 0.4 and 0.3 m off the plan centre, 200 t a floor,
nine 0.28 m columns; T1 0.588 s), B2, two storeys (8 x 8 m at x in [0.03, 8.03], y in [1.5, 9.5],
CM 0.3 m and -0.3 m off, 250 t, nine 0.30 m columns; T1 0.569 s), B3, one storey (6 x 6 m at
x in [8.08, 14.08], y in [7.2, 13.2], CM 0.2 and 0.4 m off, 180 t, nine 0.45 m columns;
T1 0.134 s); E 3e7 kPa, 5 % Rayleigh damping at modes 1 and 3; gaps 0.03 m (B1:B2) and 0.05 m
(B2:B3), given per pair ([contact.gaps]); kelvin, k = 93500 kN/m, restitution 0.6; under
a_g = 4.5 m/s2 sin(2 pi t / 0.5 s) for 1.5 s (then 0, sampled every 0.005 s for 2.5 s) along
15 degrees, so the slabs also turn. The candidates, found here by the rule of docs/model.md §4
applied to each facing pair: at 3 m and at 6 m B1's vertex 3 (0, 6) against B2's edge 4 and
B2's vertex 1 (0.03, 1.5) against B1's edge 2; at 3 m B2's vertex 3 (8.03, 9.5) against B3's
edge 4 and B3's vertex 1 (8.08, 7.2) against B2's edge 2 (six in all; B2's roof stands above
B3's, and meets nothing); B1 and
B3 share no y range within the margin, so that pair has none whatever gap it is given. The
peer: 16 contacts, 8 on each side of B2, at 5 of the 6 candidates, approach speeds 0.22 to
1.01 m/s, and in 10 pairs of contacts B2 is pressed by both neighbours at once (a B1:B2 and a
B2:B3 contact acting at overlapping times); its closest approach without contact is 6 mm (no
graze that an integrator could step over or not).

The peer assembles its own K (columns, block-tridiagonal), "uniform" J (about the slab's
centroid), Rayleigh C per building, candidates, exact finite-rotation gaps g = (P - Q1) . n and
gap rows G (the force enters as F G^T: (n, rho x n) on the striking floor, -(n, (P - c_B) x n)
on the struck one) and kelvin's F = k delta + c delta', c = 2 xi sqrt(k / W), W = G M^-1 G^T at
onset, xi = -ln e / sqrt(pi^2 + ln^2 e); it integrates the 15 DOF with scipy's DOP853 at rtol
1e-13, atol 1e-15 over each record interval; every onset (g = 0 falling), release (F = 0
falling), return of the force and gap opening (g = 0 rising) is a terminal event, the
integration restarted there in the new contact state; the input, damping and contact work and
each impulse are integrated with the motion, the peak force located on the dense output (bounded
Brent), and every open gap is sampled on the dense output (a dip below zero that the events
stepped over is counted and must not occur). Checked:
  1. the peer alone: without contact it is the exact propagation of the linear system (expm over
     each record piece) within 1e-11 m and 1e-12 rad (measured 1.2e-15 m, 1.4e-16 rad); its gap
     row is the central difference of its gap at rotations of 0.02 rad (1e-8; 1.0e-9); with
     contact its energy balance, input = kinetic + strain + damping + contact work, closes
     (1e-12 of the input; 4.9e-17), and Radau at rtol 1e-11 finds the same contacts (onsets and
     durations within 1e-10 s, peak forces and impulses 1e-9 relative; measured 6.5e-14 s,
     2.2e-13 s, 3.4e-12, 1.6e-12); the scene still makes the contacts it was chosen for (3 to 15
     on each side of B2, at least 3 overlapping pairs, no touch, no crossing beside an edge, no
     missed dip);
  2. the row, per program tolerance (cvode-bdf at the scene's rtol 1e-10, atol 1e-12, and at
     rtol 1e-12, atol 1e-14): the program's candidates (summary.json) are the peer's; it has as
     many impacts as the peer has contacts, each matched by striking building, struck building
     (the new column struck_building, present for rows only), vertex, struck edge, elevation and
     onset, with vertex_rest the vertex, floors_b1 and floors_b2 the floors of the pair's
     lower-numbered and higher-numbered building, and its level one that summary.json's levels
     give with the pair's buildings, floors and elevation; and within (measured):
                          rtol 1e-10 (the scene's)     rtol 1e-12
       onset              1e-7 s (1.6e-9)              2e-9 s (5.9e-11)
       duration           1e-7 s (8.9e-10)             2e-9 s (6.4e-11)
       peak force         1e-5   (1.0e-7)              1e-6   (7.0e-8)
       impulse            1e-5   (9.8e-8)              3e-7   (3.5e-9)
       approach speed     1e-5   (7.8e-8)              2e-7   (1.8e-9)
       contact point      1e-7 m (1.1e-9)              2e-9 m (5.2e-11)
       u, v of 5 floors   5e-8 m (3.8e-10)             2e-9 m (3.2e-11)
       phi                3e-9 rad (7.2e-11)           1e-10 rad (3.3e-12)
     (relative for forces, impulses and speeds; the histories at every history row, the event
     rows included, the peer evaluated there on its dense output); its energy audit closes
     (relative residual 2e-7 at rtol 1e-10, 1e-8 at 1e-12; measured -2.9e-10, -7.9e-11) and its
     impact loss is the peer's contact work (1e-5, 3e-7; measured 6.1e-9, 5.0e-10). The
     differences fall tenfold to thirtyfold from rtol 1e-10 to 1e-12, all but the peak force,
     which the program takes from 17 samples a step;
  3. a row refuses [contact] gap_m (its gaps are per pair): exit 2, the message naming gap_m (the
     impulse law, once refused here too, runs rows: tests/solvers/test_row_impulse_scipy.py);
  4. each pair alone, B1 and B2 with gap_m = 0.03 and B2 and B3 with gap_m = 0.05 (today's
     two-building scenes), against the peer with the third building removed, at rtol 1e-12 with
     the limits of 2 (5 and 8 impacts; measured onsets 1.5e-10 / 6.0e-11 s, durations 8.6e-11 /
     5.2e-11 s, peak forces 1.3e-7 / 7.0e-8, impulses 6.9e-9 / 3.0e-9, approach speeds 3.6e-9 /
     1.8e-9, contact points 3.0e-10 / 5.1e-12 m, u, v 1.6e-10 / 6.0e-11 m, phi 8.2e-12 / 5.8e-12
     rad, audits -8.5e-10 / -2.7e-10, losses 2.2e-9 / 1.1e-9; at rtol 1e-10: 5.6e-9 s, 5.9e-9 m,
     impulses 3.0e-7), and without the column struck_building.
The peer's contact point at onset is its vertex P (the program's `point`). Run time about 18 s.
"""
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import eigh, expm
from scipy.optimize import minimize_scalar

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

ZETA, RESTITUTION, MARGIN_M, LEVEL_TOL_M, KELVIN_K = 0.05, 0.6, 1.0, 1e-3, 93500.0
PULSE_MPS2, PULSE_PERIOD_S, PULSE_END_S, DT_S, DURATION_S, BETA_DEG = 4.5, 0.5, 1.5, 0.005, 2.5, 15.0
# name, storey heights, slab (counter-clockwise), CM, floor masses, column grid (x, y), section (b, h), E (kPa)
BUILDINGS = [
    dict(name="B1", heights=[3.0, 3.0], slab=[(-8.0, 0.0), (0.0, 0.0), (0.0, 6.0), (-8.0, 6.0)], cm=(-3.6, 3.3),
         mass=[200.0, 200.0], grid=([-8.0, -4.0, 0.0], [0.0, 3.0, 6.0]), section=(0.28, 0.28), E=3.0e7),
    dict(name="B2", heights=[3.0, 3.0], slab=[(0.03, 1.5), (8.03, 1.5), (8.03, 9.5), (0.03, 9.5)], cm=(4.33, 5.2),
         mass=[250.0, 250.0], grid=([0.03, 4.03, 8.03], [1.5, 5.5, 9.5]), section=(0.30, 0.30), E=3.0e7),
    dict(name="B3", heights=[3.0], slab=[(8.08, 7.2), (14.08, 7.2), (14.08, 13.2), (8.08, 13.2)], cm=(11.28, 10.6),
         mass=[180.0], grid=([8.08, 11.08, 14.08], [7.2, 10.2, 13.2]), section=(0.45, 0.45), E=3.0e7),
]
# The clear gaps of the facing pairs (by index in BUILDINGS), as the outlines show them.
GAPS = {(0, 1): 0.03, (1, 2): 0.05}


def scene_text(record, buildings=BUILDINGS, gaps=GAPS):
    parts = ['name = "row-peer"\n']
    for b in buildings:
        slab = ", ".join(f"[{x!r}, {y!r}]" for x, y in b["slab"])
        heights = b["heights"][0] if len(set(b["heights"])) == 1 else b["heights"]
        parts.append(f"""
[[building]]
name = "{b['name']}"
storeys = {len(b['heights'])}
storey_height_m = {heights!r}
slab = [{slab}]
centre_of_mass = [{b['cm'][0]!r}, {b['cm'][1]!r}]
mass_t = {b['mass'][0]!r}
polar_moment_tm2 = "uniform"
E_kPa = {b['E']!r}
frame_factor = 1.0
[[building.column_grid]]
x = {list(b['grid'][0])!r}
y = {list(b['grid'][1])!r}
b_m = {b['section'][0]!r}
h_m = {b['section'][1]!r}
[building.damping]
ratio = {ZETA!r}
modes = [1, 3]
""")
    if len(buildings) == 2:
        gap_lines = f"gap_m = {gaps[(0, 1)]!r}\n"
    else:
        gap_lines = "[contact.gaps]\n" + "".join(f'"{buildings[a]["name"]}:{buildings[b]["name"]}" = {g!r}\n'
                                                 for (a, b), g in sorted(gaps.items()))
    floors = "".join(f"{b['name']} = {list(range(1, len(b['heights']) + 1))!r}\n" for b in buildings)
    parts.append(f"""
[excitation]
file = "{record}"
format = "single"
units = "m/s2"
dt_s = {DT_S!r}
direction_deg = {BETA_DEG!r}

[solver]
method = "cvode-bdf"
rtol = 1e-10
atol = 1e-12

[output.floor_history]
{floors}
[contact]
restitution = {RESTITUTION!r}
law = "kelvin"
stiffness_kN_per_m = {KELVIN_K!r}
{gap_lines}""")
    return "".join(parts)


def record(amplitude=PULSE_MPS2):
    t = np.arange(round(DURATION_S / DT_S) + 1) * DT_S
    return t, np.where(t < PULSE_END_S - DT_S / 2, amplitude * np.sin(2 * np.pi * t / PULSE_PERIOD_S), 0.0)


def rot(phi):
    c, s = math.cos(phi), math.sin(phi)
    return np.array([[c, -s], [s, c]])


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


class Building:
    """Its own K (columns, block-tridiagonal), diagonal M ("uniform" J) and Rayleigh C."""

    def __init__(self, spec):
        self.name, self.heights = spec["name"], np.array(spec["heights"])
        self.n = len(self.heights)
        self.z = np.concatenate([[0.0], np.cumsum(self.heights)])  # z[0] the ground, z[k] floor k
        self.slab = [np.array(p, dtype=float) for p in spec["slab"]]
        self.cm = np.array(spec["cm"], dtype=float)
        xs, ys = [p[0] for p in self.slab], [p[1] for p in self.slab]
        a, b = max(xs) - min(xs), max(ys) - min(ys)  # the slabs are rectangles
        self.mass = np.array(spec["mass"])
        self.J = self.mass * (a * a + b * b) / 12.0
        columns = [np.array([x, y]) for x in spec["grid"][0] for y in spec["grid"][1]]
        bs, hs = spec["section"]
        n3 = 3 * self.n
        self.K = np.zeros((n3, n3))
        for s in range(self.n):
            kx = 12.0 * spec["E"] * (hs * bs ** 3 / 12.0) / self.heights[s] ** 3
            ky = 12.0 * spec["E"] * (bs * hs ** 3 / 12.0) / self.heights[s] ** 3
            ks = np.zeros((3, 3))
            for c in columns:
                arm = c - self.cm
                T = np.array([[1.0, 0.0, -arm[1]], [0.0, 1.0, arm[0]]])
                ks += T.T @ np.diag([kx, ky]) @ T
            i = 3 * s
            self.K[i:i + 3, i:i + 3] += ks
            if s > 0:
                self.K[i - 3:i, i - 3:i] += ks
                self.K[i - 3:i, i:i + 3] -= ks
                self.K[i:i + 3, i - 3:i] -= ks
        self.m_diag = np.concatenate([[m, m, J] for m, J in zip(self.mass, self.J)])
        w2 = np.sort(eigh(self.K, np.diag(self.m_diag), eigvals_only=True))
        self.omega = np.sqrt(w2)
        w1, w3 = self.omega[0], self.omega[2]
        self.a0, self.a1 = 2 * ZETA * w1 * w3 / (w1 + w3), 2 * ZETA / (w1 + w3)
        self.C = self.a0 * np.diag(self.m_diag) + self.a1 * self.K

    def edges(self):
        """(Q1, Q2, unit tangent, outward normal, length) of every slab edge, in outline order."""
        out = []
        for k in range(len(self.slab)):
            q1, q2 = self.slab[k], self.slab[(k + 1) % len(self.slab)]
            length = np.linalg.norm(q2 - q1)
            t = (q2 - q1) / length
            out.append((q1, q2, t, np.array([t[1], -t[0]]), length))
        return out


class Candidate:
    """Vertex X (number vertex_index) of floor fa of building A against edge Q1->Q2 of floor fb of B."""

    def __init__(self, A, fa, B, fb, vertex_index, X, edge_index, edge, elevation):
        self.A, self.fa, self.B, self.fb = A, fa, B, fb
        self.vertex_index, self.X, self.edge_index = vertex_index, X, edge_index
        self.q1, self.q2, self.t_rest, self.n_rest, self.length = edge
        self.elevation = elevation


def find_candidates(buildings, gaps):
    """docs/model.md §4's rule, written out, for every pair of buildings the scene gives a gap for:
    at each common level, each vertex of one slab against each edge of the other whose outward
    normal faces a vertex of the first, when it lies in front of the edge within gap + margin and
    projects onto it or within the margin beyond an end; both ways round."""
    cands = []
    for (a, b), gap in sorted(gaps.items()):
        A, B = buildings[a], buildings[b]
        for fa in range(1, A.n + 1):
            for fb in range(1, B.n + 1):
                if abs(A.z[fa] - B.z[fb]) > LEVEL_TOL_M:
                    continue
                for s, fs, t, ft in ((a, fa, b, fb), (b, fb, a, fa)):
                    S, T = buildings[s], buildings[t]
                    for e, edge in enumerate(T.edges()):
                        q1, q2, tang, n, length = edge
                        if not any(np.dot(v - q1, n) > 0 for v in S.slab):
                            continue
                        for v, X in enumerate(S.slab):
                            d, along = np.dot(X - q1, n), np.dot(X - q1, tang)
                            if -1e-9 <= d <= gap + MARGIN_M and -MARGIN_M <= along <= length + MARGIN_M:
                                cands.append(Candidate(s, fs, t, ft, v, X, e, edge, A.z[fa]))
    return cands


class Peer:
    """The buildings' floors (q relative to the ground, building by building, floor 1 first) with
    kelvin contacts at the vertex-edge candidates, integrated with DOP853 over each record interval,
    every switch a root located by solve_ivp's events and the integration restarted there in the
    new contact state."""

    def __init__(self, contact=True, rtol=1e-13, atol=1e-15, method="DOP853", buildings=BUILDINGS, gaps=GAPS):
        self.b = [Building(s) for s in buildings]
        self.off = list(np.cumsum([0] + [3 * b.n for b in self.b])[:-1])
        self.n = 3 * sum(b.n for b in self.b)
        self.m_diag = np.concatenate([b.m_diag for b in self.b])
        self.K = np.zeros((self.n, self.n))
        self.C = np.zeros((self.n, self.n))
        for b, o in zip(self.b, self.off):
            k = 3 * b.n
            self.K[o:o + k, o:o + k], self.C[o:o + k, o:o + k] = b.K, b.C
        beta = math.radians(BETA_DEG)
        self.r = np.tile([math.cos(beta), math.sin(beta), 0.0], self.n // 3)
        self.rtol, self.atol, self.method = rtol, atol, method
        self.cands = find_candidates(self.b, gaps) if contact else []
        self.zeta = -math.log(RESTITUTION) / math.sqrt(math.pi ** 2 + math.log(RESTITUTION) ** 2)
        self.state = ["open"] * len(self.cands)
        self.current = [None] * len(self.cands)  # the open contact's record
        self.contacts = []
        self.n_aug = 3 + len(self.cands)  # input, damping, contact loss, impulse per candidate

    # --- kinematics -------------------------------------------------------------------------
    def dofs(self, b, k):
        o = self.off[b] + 3 * (k - 1)
        return slice(o, o + 3)

    def gap(self, c, q, qd):
        """g, g rate, G (the gap's row over q), P, and the projection parameter of P on the edge."""
        A, B = self.b[c.A], self.b[c.B]
        qa, qb = q[self.dofs(c.A, c.fa)], q[self.dofs(c.B, c.fb)]
        rho = rot(qa[2]) @ (c.X - A.cm)
        P = A.cm + qa[:2] + rho
        Rb = rot(qb[2])
        n = Rb @ c.n_rest
        cm_b = B.cm + qb[:2]
        Q1 = cm_b + Rb @ (c.q1 - B.cm)
        G = np.zeros(self.n)
        G[self.dofs(c.A, c.fa)] = [n[0], n[1], cross(rho, n)]
        G[self.dofs(c.B, c.fb)] = [-n[0], -n[1], -cross(P - cm_b, n)]
        g = np.dot(P - Q1, n)
        s = np.dot(P - Q1, Rb @ c.t_rest) / c.length
        return g, G @ qd, G, P, s

    def force(self, i, delta, rate):
        """Kelvin's force (kN) of candidate i's open contact; it is also its switch function."""
        return KELVIN_K * delta + self.current[i]["c"] * rate

    # --- equations of motion ----------------------------------------------------------------
    def rhs(self, t, y, ag):
        q, qd = y[:self.n], y[self.n:2 * self.n]
        a = ag(t)
        gen = np.zeros(self.n)
        power = 0.0
        forces = np.zeros(len(self.cands))
        for i, c in enumerate(self.cands):
            if self.state[i] != "acting":
                continue
            g, gd, G, _, _ = self.gap(c, q, qd)
            F = self.force(i, -g, -gd)
            gen += F * G
            power += -F * gd
            forces[i] = F
        qdd = (-self.K @ q - self.C @ qd + gen) / self.m_diag - self.r * a
        aug = np.concatenate([[-qd @ (self.m_diag * self.r) * a, qd @ self.C @ qd, power], forces])
        return np.concatenate([qd, qdd, aug])

    def events(self):
        fs = []
        for i, c in enumerate(self.cands):
            st = self.state[i]
            if st == "open":
                def e(t, y, _ag, c=c):
                    return self.gap(c, y[:self.n], y[self.n:2 * self.n])[0]
                fs.append((e, ("onset", i)))
            else:
                def e_gap(t, y, _ag, c=c):
                    return -self.gap(c, y[:self.n], y[self.n:2 * self.n])[0]
                fs.append((e_gap, ("opens", i)))
                sign = 1.0 if st == "acting" else -1.0

                def e_sw(t, y, _ag, i=i, c=c, sign=sign):
                    g, gd = self.gap(c, y[:self.n], y[self.n:2 * self.n])[:2]
                    return sign * self.force(i, -g, -gd)
                fs.append((e_sw, ("release" if st == "acting" else "acts again", i)))
        funcs = []
        for f, _ in fs:
            f.terminal, f.direction = True, -1
            funcs.append(f)
        return funcs, [tag for _, tag in fs]

    def energies(self, y):
        q, qd = y[:self.n], y[self.n:2 * self.n]
        return 0.5 * qd @ (self.m_diag * qd), 0.5 * q @ self.K @ q

    def switch(self, t, y, tag):
        kind, i = tag
        c = self.cands[i]
        q, qd = y[:self.n], y[self.n:2 * self.n]
        g, gd, G, P, s = self.gap(c, q, qd)
        if kind == "onset":
            if not (-1e-12 <= s <= 1 + 1e-12):
                self.passed_beside += 1
                return
            if gd >= 0.0:
                self.touches += 1
                return
            W = np.sum(G * G / self.m_diag)
            rec = dict(candidate=i, t_s=t, approach=-gd, W=W, imp0=y[2 * self.n + 3 + i], peak=0.0, acts_again=0,
                       elevation=c.elevation, pair=tuple(sorted((c.A, c.B))), point=P)
            rec["c"] = 2.0 * self.zeta * math.sqrt(KELVIN_K / W)
            self.current[i] = rec
            self.state[i] = "acting"
        elif kind == "release":
            self.state[i] = "released"
            self.current[i]["release"] = t
            self.current[i]["released_by"] = "force"
        elif kind == "acts again":
            self.state[i] = "acting"
            self.current[i]["acts_again"] += 1
            self.current[i].pop("release")
            self.current[i].pop("released_by")
        elif kind == "opens":
            rec = self.current[i]
            if self.state[i] == "acting":
                rec["release"] = t
                rec["released_by"] = "gap"
            rec["end"] = t
            rec["duration"] = rec["release"] - rec["t_s"]
            rec["impulse"] = y[2 * self.n + 3 + i] - rec["imp0"]
            self.contacts.append(rec)
            self.current[i] = None
            self.state[i] = "open"

    def track_peaks(self, sol, t0, t1):
        """The largest force of every acting contact over [t0, t1], located on the dense output."""
        for i, c in enumerate(self.cands):
            if self.state[i] != "acting" or t1 <= t0:
                continue

            def force_at(t):
                y = sol(t)
                g, gd = self.gap(c, y[:self.n], y[self.n:2 * self.n])[:2]
                return self.force(i, -g, -gd)
            ts = np.linspace(t0, t1, 9)
            fs = [force_at(t) for t in ts]
            k = int(np.argmax(fs))
            res = minimize_scalar(lambda t: -force_at(t), bounds=(ts[max(k - 1, 0)], ts[min(k + 1, len(ts) - 1)]),
                                  method="bounded", options={"xatol": 1e-13})
            best = max(fs[k], -res.fun)
            self.current[i]["peak"] = max(self.current[i]["peak"], best)

    def track_open_gaps(self, sol, t0, t1):
        """Open gaps sampled on the dense output (the steps' ends and three points inside each):
        a gap below zero is a contact the events stepped over (self.missed); a gap that turns from
        closing to opening above zero is a near miss, the smallest kept (self.near_miss, m)."""
        open_ = [i for i in range(len(self.cands)) if self.state[i] == "open"]
        if not open_ or t1 <= t0:
            return
        ts = np.unique(np.concatenate([np.linspace(a, b, 4, endpoint=False) for a, b in zip(sol.t[:-1], sol.t[1:])]
                                      + [[t1]]))
        ys = sol.sol(ts)
        for i in open_:
            g = np.array([self.gap(self.cands[i], y[:self.n], y[self.n:2 * self.n])[0] for y in ys.T])
            self.missed += int(np.sum(g[1:-1] < 0.0))
            turns = np.nonzero((g[1:-1] < g[:-2]) & (g[1:-1] <= g[2:]))[0] + 1
            if len(turns):
                self.near_miss = min(self.near_miss, float(np.min(g[turns])))

    def run(self, times, accel, out_times=()):
        ag = lambda t: np.interp(t, times, accel)
        y = np.zeros(2 * self.n + self.n_aug)
        rows, k_out = [], 0
        out_times = np.asarray(out_times)
        self.touches, self.passed_beside, self.steps, self.missed, self.near_miss = 0, 0, 0, 0, math.inf
        self.segments = []  # (t0, t1, dense output) of every integration, in time order
        self.edge_margin = math.inf  # smallest distance of an acting P from its edge's ends (edge lengths)
        for a, b in zip(times[:-1], times[1:]):
            t0 = a
            while b - t0 > 1e-13:
                funcs, tags = self.events()
                sol = solve_ivp(self.rhs, (t0, b), y, method=self.method, rtol=self.rtol, atol=self.atol,
                                events=funcs or None, args=(ag,), dense_output=True)
                assert sol.status >= 0, sol.message
                self.steps += len(sol.t) - 1
                t_end = sol.t[-1]
                while k_out < len(out_times) and out_times[k_out] <= t_end + 1e-12:
                    rows.append(sol.sol(min(out_times[k_out], t_end))[:self.n])
                    k_out += 1
                self.track_peaks(sol.sol, t0, t_end)
                self.track_open_gaps(sol, t0, t_end)
                self.segments.append((t0, t_end, sol.sol))
                for i in range(len(self.cands)):
                    if self.state[i] == "acting":
                        for t in np.linspace(t0, t_end, 5):
                            yy = sol.sol(t)
                            s = self.gap(self.cands[i], yy[:self.n], yy[self.n:2 * self.n])[4]
                            self.edge_margin = min(self.edge_margin, s, 1.0 - s)
                y = sol.y[:, -1].copy()
                if sol.status != 1:
                    break
                hit = [k for k, te in enumerate(sol.t_events) if len(te)]
                first = min(sol.t_events[k][0] for k in hit)
                for k in hit:
                    if sol.t_events[k][0] <= first + 1e-14:
                        self.switch(t_end, y, tags[k])
                t0 = t_end
        while k_out < len(out_times):
            rows.append(y[:self.n])
            k_out += 1
        self.y_end = y
        for i, rec in enumerate(self.current):  # contacts still open at the end
            if rec is not None:
                rec.setdefault("release", times[-1])
                rec["duration"] = rec["release"] - rec["t_s"]
                rec["impulse"] = y[2 * self.n + 3 + i] - rec["imp0"]
                rec["end"] = None
                self.contacts.append(rec)
        self.contacts.sort(key=lambda r: r["t_s"])
        kin, strain = self.energies(y)
        e_in, e_damp, e_contact = y[2 * self.n:2 * self.n + 3]
        self.energy = dict(input=e_in, kinetic=kin, strain=strain, damping=e_damp, contact=e_contact,
                           residual=e_in - kin - strain - e_damp - e_contact)
        return np.array(rows)

    def at(self, ts):
        """q at the instants ts (within the run), from the dense output of the integration that covers each."""
        starts = np.array([s[0] for s in self.segments])
        rows = []
        for t in ts:
            k = max(int(np.searchsorted(starts, t, side="right")) - 1, 0)
            t0, t1, sol = self.segments[k]
            rows.append(sol(min(max(t, t0), t1))[:self.n])
        return np.array(rows)

    def overlapping(self):
        """Pairs of contacts, one between B1 and B2 and one between B2 and B3, acting at overlapping times."""
        left = [c for c in self.contacts if c["pair"] == (0, 1)]
        right = [c for c in self.contacts if c["pair"] == (1, 2)]
        return [(l, r) for l in left for r in right
                if l["t_s"] < r["t_s"] + r["duration"] and r["t_s"] < l["t_s"] + l["duration"]]


def exact_free_response(peer, times, accel, out_times):
    """The contact-free motion propagated exactly over each linear piece of the record: the
    first-order system z = (q, q', a_g, a_g') with a_g' constant on the piece, advanced by expm."""
    n = peer.n
    A = np.zeros((2 * n + 2, 2 * n + 2))
    A[:n, n:2 * n] = np.eye(n)
    A[n:2 * n, :n] = -peer.K / peer.m_diag[:, None]
    A[n:2 * n, n:2 * n] = -peer.C / peer.m_diag[:, None]
    A[n:2 * n, 2 * n] = -peer.r
    A[2 * n, 2 * n + 1] = 1.0
    z = np.zeros(2 * n + 2)
    rows, k = [], 0
    for i in range(len(times) - 1):
        a, b = times[i], times[i + 1]
        z[2 * n], z[2 * n + 1] = accel[i], (accel[i + 1] - accel[i]) / (b - a)
        while k < len(out_times) and out_times[k] <= b:
            rows.append((expm(A * (out_times[k] - a)) @ z)[:n])
            k += 1
        z = expm(A * (b - a)) @ z
    return np.array(rows)


def translation_columns(peer):
    return [i for i in range(peer.n) if i % 3 != 2], list(range(2, peer.n, 3))


def check_peer(times, accel, failures):
    """Check 1a, b: the peer alone, without contact and its gap rows."""
    t_out = np.arange(0, round(DURATION_S / 0.01) + 1) * 0.01
    free = Peer(contact=False)
    peer_q = free.run(times, accel, t_out)
    exact_q = exact_free_response(free, times, accel, t_out)
    uv, ph = translation_columns(free)
    du, dphi = np.max(np.abs(peer_q - exact_q)[:, uv]), np.max(np.abs(peer_q - exact_q)[:, ph])
    print(f"peer without contact against expm: largest |u, v| difference {du:.2e} m, |phi| {dphi:.2e} rad "
          f"({free.n} DOF); energy residual {free.energy['residual']:.1e} kJ of {free.energy['input']:.1f}")
    if du > 1e-11 or dphi > 1e-12:
        failures.append("peer: the contact-free motion is not the exact one")
    peer = Peer()
    rng = np.random.default_rng(7)
    q = rng.normal(0.0, 0.03, peer.n)
    q[2::3] = rng.normal(0.0, 0.02, peer.n // 3)
    worst = 0.0
    for c in peer.cands:
        G = peer.gap(c, q, np.zeros(peer.n))[2]
        for k in range(peer.n):
            e = np.zeros(peer.n)
            e[k] = 1e-6
            fd = (peer.gap(c, q + e, e)[0] - peer.gap(c, q - e, e)[0]) / 2e-6
            worst = max(worst, abs(fd - G[k]) / max(1.0, abs(G[k])))
    print(f"gap row against the gap's central difference (rotations of 0.02 rad): largest difference {worst:.1e}")
    if worst > 1e-8:
        failures.append("peer: the gap row is not the gap's gradient")


def contact_differences(pairs):
    """Largest differences over (peer contact, program row) pairs: onset and duration absolute (s),
    the rest relative."""
    d = dict(t_s=0.0, duration_s=0.0, peak_force_kN=0.0, impulse_kNs=0.0, approach_velocity_mps=0.0)
    for c, r in pairs:
        d["t_s"] = max(d["t_s"], abs(float(r["t_s"]) - c["t_s"]))
        d["duration_s"] = max(d["duration_s"], abs(float(r["duration_s"]) - c["duration"]))
        d["peak_force_kN"] = max(d["peak_force_kN"], abs(float(r["peak_force_kN"]) / c["peak"] - 1.0))
        d["impulse_kNs"] = max(d["impulse_kNs"], abs(float(r["impulse_kNs"]) / c["impulse"] - 1.0))
        d["approach_velocity_mps"] = max(d["approach_velocity_mps"],
                                         abs(float(r["approach_velocity_mps"]) / c["approach"] - 1.0))
    return d


def check_peer_contacts(peer, times, accel, failures):
    """Check 1c: the peer's energy balance closes with contact; Radau (implicit) at rtol 1e-11 finds
    the same contacts as DOP853 at 1e-13; the scene makes the contacts it was chosen for."""
    e = peer.energy
    rel = abs(e["residual"]) / e["input"]
    print(f"peer: {len(peer.contacts)} contacts, energy input {e['input']:.3f} kJ, kinetic {e['kinetic']:.3f}, "
          f"strain {e['strain']:.3f}, damping {e['damping']:.3f}, contact {e['contact']:.4f}; residual {rel:.1e}")
    if rel > 1e-12 or e["contact"] <= 0.0:
        failures.append("peer: the energy balance does not close")
    left = sum(c["pair"] == (0, 1) for c in peer.contacts)
    both = peer.overlapping()
    used = len(set(c['candidate'] for c in peer.contacts))
    print(f"peer: {left} contacts B1-B2, {len(peer.contacts) - left} B2-B3, at {used} "
          f"of {len(peer.cands)} candidates; {len(both)} pairs of a B1-B2 and a B2-B3 contact acting at once; "
          f"approach speeds {min(c['approach'] for c in peer.contacts):.3f} to "
          f"{max(c['approach'] for c in peer.contacts):.3f} m/s; touches {peer.touches}, crossings beside an edge "
          f"{peer.passed_beside}; acting points stay {peer.edge_margin:.2f} edge lengths inside their edges; "
          f"dips below zero stepped over {peer.missed}, closest approach without contact {peer.near_miss * 1e3:.1f} mm")
    if (not 3 <= left <= 15 or not 3 <= len(peer.contacts) - left <= 15 or len(both) < 3 or peer.touches
            or peer.passed_beside or peer.edge_margin <= 0.0 or peer.missed or peer.near_miss < 1e-3):
        failures.append("peer: the scene no longer makes the contacts it was chosen for")
    other = Peer(rtol=1e-11, atol=1e-13, method="Radau")
    other.run(times, accel)
    if len(other.contacts) != len(peer.contacts):
        failures.append(f"peer: Radau finds {len(other.contacts)} contacts, DOP853 {len(peer.contacts)}")
        return
    d = contact_differences(zip(peer.contacts, [dict(t_s=r["t_s"], duration_s=r["duration"], peak_force_kN=r["peak"],
                                                     impulse_kNs=r["impulse"], approach_velocity_mps=r["approach"])
                                                for r in other.contacts]))
    print(f"peer, Radau at rtol 1e-11 against DOP853 at 1e-13: onsets {d['t_s']:.1e} s, durations "
          f"{d['duration_s']:.1e} s, peak forces {d['peak_force_kN']:.1e}, impulses {d['impulse_kNs']:.1e}, "
          f"approach speeds {d['approach_velocity_mps']:.1e} (relative)")
    if d["t_s"] > 1e-10 or d["duration_s"] > 1e-10 or max(d["peak_force_kN"], d["impulse_kNs"]) > 1e-9:
        failures.append("peer: Radau and DOP853 disagree")


def run_program(program, folder, accel, options, buildings, gaps):
    """Writes the record and the scene into folder, runs it with options; (history times, the
    (u, v, phi) columns of every floor in the peer's order, impacts by onset, summary.json), or
    None and the program's message."""
    names = [f"B{b + 1}_f{fl}_{comp}" for b, spec in enumerate(buildings) for fl in range(1, len(spec["heights"]) + 1)
             for comp in ("u_m", "v_m", "phi_rad")]
    run, message = program_run.run_scene(program, folder, lambda record: scene_text(record, buildings, gaps), accel,
                                         options, names)
    return (None, message) if run is None else ((run.t, run.q, run.impacts, run.summary), None)


# Per program tolerance: limits on |u, v| (m), |phi| (rad), onset and duration (s), peak force,
# impulse and approach speed (relative), the audit's relative residual and the impact loss
# against the peer's contact work (relative). Measured values are in the docstring.
RUNS = {
    "rtol 1e-10 (the scene's)": ([], dict(history_m=5e-8, history_rad=3e-9, t_s=1e-7, duration_s=1e-7,
                                          peak_force_kN=1e-5, impulse_kNs=1e-5, approach_velocity_mps=1e-5,
                                          point_m=1e-7, residual=2e-7, loss=1e-5)),
    "rtol 1e-12": (["--rtol", "1e-12", "--atol", "1e-14"],
                   dict(history_m=2e-9, history_rad=1e-10, t_s=2e-9, duration_s=2e-9, peak_force_kN=1e-6,
                        impulse_kNs=3e-7, approach_velocity_mps=2e-7, point_m=2e-9, residual=1e-8, loss=3e-7)),
}


def check_program(program, out, label, peer, accel, failures, buildings=BUILDINGS, gaps=GAPS, name_prefix="row"):
    """Checks 2 and 3 at one program tolerance against a peer that has already run the scene
    (at the program's history instants)."""
    options, tol = RUNS[label]
    name = f"{name_prefix} at {label}"
    rows_ok = len(buildings) > 2
    folder = out / f"{name_prefix.replace(' ', '-')}-{label.split()[1]}"
    result, error = run_program(program, folder, accel, options, buildings, gaps)
    if result is None:
        failures.append(f"{name}: the program refused the scene or failed: {error.strip()}")
        return
    t_out, program_q, impacts, summary = result
    if impacts and ("struck_building" in impacts[0]) != rows_ok:
        failures.append(f"{name}: impacts.csv {'lacks' if rows_ok else 'has'} the column struck_building")
    peer_q = peer.at(t_out)
    diff = np.abs(program_q - peer_q)
    uv, ph = translation_columns(peer)
    du, dphi = np.max(diff[:, uv]), np.max(diff[:, ph])
    worst = np.unravel_index(np.argmax(diff[:, uv]), diff[:, uv].shape)
    print(f"{name}: largest |u, v| difference {du:.2e} m (at {t_out[worst[0]]:.2f} s, DOF {uv[worst[1]]}), "
          f"|phi| {dphi:.2e} rad over {len(t_out)} rows of {peer.n // 3} floors; peak |u| "
          f"{np.max(np.abs(peer_q[:, 0::3])):.4f} m, |phi| {np.max(np.abs(peer_q[:, ph])):.2e} rad")
    if du > tol["history_m"] or dphi > tol["history_rad"]:
        failures.append(f"{name}: history differs by {du:.2e} m, {dphi:.2e} rad (limits {tol['history_m']:.0e}, "
                        f"{tol['history_rad']:.0e})")
    listed = sorted((c["elevation_m"], tuple(c["vertex_rest"]), c["striking_building"], c["vertex"],
                     c["struck_building"], c["edge"]) for c in summary["candidates"])
    own = sorted((c.elevation, tuple(c.X), c.A + 1, c.vertex_index + 1, c.B + 1, c.edge_index + 1) for c in peer.cands)
    flat = lambda x: [x[0], *x[1], *x[2:]]
    if len(listed) != len(own) or not np.allclose([flat(x) for x in listed], [flat(x) for x in own], rtol=0, atol=1e-9):
        failures.append(f"{name}: the program's candidates {listed}, the peer's {own}")
    # The program's impacts matched to the peer's contacts by the pair of buildings, the striking
    # vertex, the struck edge, the level's elevation and the onset.
    matched = []
    for c in peer.contacts:
        cand = peer.cands[c["candidate"]]
        near = [r for r in impacts if int(r["striking_building"]) == cand.A + 1
                and (int(r["struck_building"]) if rows_ok else 3 - int(r["striking_building"])) == cand.B + 1
                and int(r["vertex"]) == cand.vertex_index + 1 and int(r["struck_edge"]) == cand.edge_index + 1
                and abs(float(r["elevation_m"]) - c["elevation"]) < 1e-9 and abs(float(r["t_s"]) - c["t_s"]) < 1e-3]
        if len(near) != 1:
            failures.append(f"{name}: the peer's contact at {c['t_s']:.9f} s, {peer.b[cand.A].name} vertex "
                            f"{cand.vertex_index + 1} on {peer.b[cand.B].name} edge {cand.edge_index + 1} at "
                            f"{c['elevation']} m, has {len(near)} program impacts near it")
            continue
        r = near[0]
        matched.append((c, r))
        lower, higher = sorted([(cand.A, cand.fa), (cand.B, cand.fb)])
        got = [float(r["vertex_rest_x_m"]), float(r["vertex_rest_y_m"]), int(r["floors_b1"]), int(r["floors_b2"])]
        want = [cand.X[0], cand.X[1], lower[1], higher[1]]
        if not rows_ok:
            got.append(int(r["level"]))
            want.append(1 + [z for z in sorted({x.elevation for x in peer.cands})].index(c["elevation"]))
        else:  # the level as summary.json's levels describe it: the pair's buildings, floors and elevation
            level = [v for v in summary.get("levels", []) if v.get("level") == int(r["level"])]
            if len(level) != 1 or (level[0].get("buildings"), level[0].get("floors"), level[0].get("elevation_m")) != (
                    [lower[0] + 1, higher[0] + 1], [lower[1], higher[1]], c["elevation"]):
                failures.append(f"{name}: the contact at {c['t_s']:.9f} s is on level {r['level']}, which "
                                f"summary.json gives as {level}; expected buildings {[lower[0] + 1, higher[0] + 1]}, "
                                f"floors {[lower[1], higher[1]]} at {c['elevation']} m")
        if not np.allclose(got, want, rtol=0, atol=1e-9):
            failures.append(f"{name}: the contact at {c['t_s']:.9f} s: (vertex_rest, floors_b1, floors_b2"
                            f"{', level' if not rows_ok else ''}) {got}, expected {want}")
    extra = [r for r in impacts if not any(r is m for _, m in matched)]
    print(f"{name}: the program has {len(impacts)} impacts, the peer {len(peer.contacts)} contacts "
          f"({sum(c.get('released_by') == 'force' for c in peer.contacts)} released by the force, "
          f"{sum(c['acts_again'] for c in peer.contacts)} acting again before the gap opened)")
    if len(impacts) != len(peer.contacts) or len(matched) != len(peer.contacts):
        failures.append(f"{name}: {len(impacts)} impacts, the peer {len(peer.contacts)}; unmatched program impacts: "
                        + "; ".join(f"{r['t_s']} s building {r['striking_building']} vertex {r['vertex']} edge "
                                    f"{r['struck_edge']} at {r['elevation_m']} m" for r in extra))
    print(f"   {'t_s':>12} {'z_m':>4} {'strikes':>7} {'vertex->edge':>13} {'onset diff':>10} {'duration':>9} "
          f"{'diff':>9} "
          f"{'peak_kN':>9} {'rel diff':>9} {'impulse':>9} {'rel diff':>9} {'v0_mps':>7} {'rel diff':>9} {'point':>8}")
    dpoint = 0.0
    for c, r in matched:
        cand = peer.cands[c["candidate"]]
        dp = math.hypot(float(r["point_x_m"]) - c["point"][0], float(r["point_y_m"]) - c["point"][1])
        dpoint = max(dpoint, dp)
        print(f"   {c['t_s']:12.9f} {c['elevation']:4.1f} {f'{peer.b[cand.A].name}->{peer.b[cand.B].name}':>7} "
              f"{f'v{cand.vertex_index + 1}->e{cand.edge_index + 1}':>13} "
              f"{float(r['t_s']) - c['t_s']:10.1e} {c['duration']:9.6f} {float(r['duration_s']) - c['duration']:9.1e} "
              f"{c['peak']:9.3f} {float(r['peak_force_kN']) / c['peak'] - 1:9.1e} {c['impulse']:9.5f} "
              f"{float(r['impulse_kNs']) / c['impulse'] - 1:9.1e} {c['approach']:7.4f} "
              f"{float(r['approach_velocity_mps']) / c['approach'] - 1:9.1e} {dp:8.1e}")
    d = contact_differences(matched)
    d["point_m"] = dpoint
    print(f"{name}: largest differences: onset {d['t_s']:.1e} s, duration {d['duration_s']:.1e} s, peak force "
          f"{d['peak_force_kN']:.1e}, impulse {d['impulse_kNs']:.1e}, approach speed {d['approach_velocity_mps']:.1e} "
          f"(relative), contact point {d['point_m']:.1e} m")
    for key in d:
        if d[key] > tol[key]:
            failures.append(f"{name}: {key} differs by {d[key]:.2e} (limit {tol[key]:.0e})")
    energy = summary["energy"]
    loss = abs(energy["impact_loss_kJ"] / peer.energy["contact"] - 1.0)
    print(f"{name}: energy input {energy['input_kJ']:.4f} kJ (peer {peer.energy['input']:.4f}), impact loss "
          f"{energy['impact_loss_kJ']:.6f} kJ (peer's contact work {peer.energy['contact']:.6f}, {loss:.1e} apart), "
          f"relative residual {energy['relative_residual']:.1e}")
    if abs(energy["relative_residual"]) > tol["residual"]:
        failures.append(f"{name}: the energy audit does not close ({energy['relative_residual']:.1e})")
    if loss > tol["loss"]:
        failures.append(f"{name}: the impact loss differs from the peer's contact work by {loss:.1e}")


def check_refusals(program, out, failures):
    """Check 3: a row refuses [contact] gap_m (its gaps are per pair)."""
    folder = out / "refusals"
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "pulse.txt").write_text("\n".join(f"{a!r}" for a in record()[1]) + "\n")
    text = scene_text(folder / "pulse.txt")
    cases = {"gap_m": text.replace("[contact.gaps]\n", f"gap_m = {GAPS[(0, 1)]!r}\n[contact.gaps]\n")}
    message_keys = []
    for key, scene in cases.items():
        (folder / f"scene-{len(message_keys)}.toml").write_text(scene)
        run = subprocess.run([program, "check", str(folder / f"scene-{len(message_keys)}.toml")], capture_output=True,
                             text=True)
        message_keys.append(key)
        message = run.stderr.strip().splitlines()[0] if run.stderr.strip() else ""
        print(f"row with {key}: exit {run.returncode}: {message[:140]}")
        if run.returncode != 2 or key not in run.stderr:
            failures.append(f"a row with {key} is not refused (exit {run.returncode}, expected 2 naming {key})")


def run_peer(times, accel, buildings=BUILDINGS, gaps=GAPS):
    peer = Peer(buildings=buildings, gaps=gaps)
    peer.run(times, accel)
    return peer


def main():
    started = time.time()
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    out.mkdir(parents=True, exist_ok=True)
    times, accel = record()
    failures = []
    check_peer(times, accel, failures)
    peer = run_peer(times, accel)
    check_peer_contacts(peer, times, accel, failures)
    for label in RUNS:
        check_program(program, out, label, peer, accel, failures)
    check_refusals(program, out, failures)
    for first, label in ((0, "B1 and B2 alone"), (1, "B2 and B3 alone")):
        pair = run_peer(times, accel, BUILDINGS[first:first + 2], {(0, 1): GAPS[(first, first + 1)]})
        print(f"peer of {label}: {len(pair.contacts)} contacts")
        check_program(program, out, "rtol 1e-12", pair, accel, failures, BUILDINGS[first:first + 2],
                      {(0, 1): GAPS[(first, first + 1)]}, label)
    program_run.finish(failures, started)


if __name__ == "__main__":
    main()
