#!/usr/bin/python3
"""Slabs whose facades stand in line (corner contacts) against an independent computation (scipy, no code shared).

    /usr/bin/python3 tests/solvers/test_street_scipy.py POUNDING OUT_DIR [CASE ...]

(CASE: names from CASES to run only those; all by default.) Exit 0 when every comparison is within
its limit, 1 otherwise; one line per comparison with its measured value and its limit.

The scenes. One-storey buildings (3 m) with rectangular slabs 10 x 8 m, facades in line, GAP_M =
0.02 m apart, so the corners meet at the ends of the facing edges: A x in [0, 10], B [10.02, 20.02],
C [20.04, 30.04], all y in [0, 8]; CMs off the plan centre in y in opposite senses, (5.0, 4.8),
(15.02, 3.2), (25.04, 4.6), so that x shaking turns the slabs in opposite senses; 150, 200, 170 t,
"uniform" J; nine square columns at the corners, edge midpoints and centre, 0.25, 0.22, 0.24 m,
E 3e7 kPa, fixed-fixed (periods A 0.398/0.389/0.269 s, B 0.593/0.581/0.402 s, C 0.456/0.450/0.314 s);
5 % Rayleigh damping at modes 1 and 3. Ground: 4 sin(2 pi t / 0.5 s) m/s2 for two periods, then
nothing, sampled every 0.01 s to 2.5 s, along 25 degrees, so the slabs also move in y and turn, and
corners slide past each other along the facade while the slabs press. Kelvin: k = 5e5 kN/m, e =
0.5 (contacts up to 10.0 mm deep); impulse law: k = 0.5 and k = 0 (hold_velocity_mps 1e-3,
hold_height_m 1e-8, the defaults). Cases (the peer's counts): A | B with the kelvin law: 15
contacts, 4 hand-overs round a corner (all to the twin); impulse k = 0.5: 14 impacts, no hold;
k = 0: 12 impacts, 5 holds, one of them handed over to its twin; the row A | B | C ([contact.gaps]):
kelvin 27 contacts (15 A:B, 12 B:C), 2 hand-overs; impulse k = 0.5: 30 impacts; k = 0: 22 impacts,
9 holds, 3 handed over; and A | B with B moved by +1 um and -1 um along y (facades in line to a
micrometre: the side edges are then facing candidates, 1 um from the other slab's corner), each
law: the same counts as in line (15 and 4; 14; 12, 5 and 1), and no contact on a side edge.

The peer (Peer) assembles each building's K (the columns about the CM), diag(m, m, J) and Rayleigh
C itself, integrates q, q' (and the input, damping, contact and constraint work, and each
candidate's impulse) with DOP853 at rtol 1e-12, atol 1e-14 over each record interval (a_g linear
between samples), every switch a terminal event, restarted there in the new contact state. Its
candidates: every vertex of one slab and every edge of the other of a neighbouring pair within the
gap plus 1 m at rest (8 a pair here: the facing edges and the side edges at the shared corners).
Gaps with exact rotation, g = (P - Q1) . n, the row G = (n, rho x n | -n, -(P - c_B) x n) and the
curvature h (g'' = G q'' + h). The contact model is the spec's (docs/model.md, corner rules):
  - onset where g falls through 0 with P on its edge (s in [-1e-9, 1 + 1e-9]), approaching: kelvin
    F = k delta + c delta', c = 2 xi sqrt(k / W) with W = G M^-1 G^T at onset, released where F turns
    tensile, acting again where it would push, ended where g opens; impulse law: every candidate
    closed then (|g| <= 1e-8 m, on its edge) and the held ones of the pairs sharing a slab, one LCP
    (enumerated), then the hold rule (separating slower than 1e-3 m/s or flying lower than 1e-8 m,
    while the physical force, without drift terms, presses above 1e-9 of the free accelerations; the
    held ones again with k = 0 until the set settles; brought to g' = 0);
  - one contact at a point: while a contact is in progress (held, or kelvin from onset until its gap
    opens) the vertex's other candidates against that slab and the candidates of the struck slab's
    corner at its point (an end of its edge within 2 (max(0, -g) + 1e-8) m of P) take no onset: a
    crossing of theirs at that instant is ignored;
  - round a corner: where the point of an acting kelvin contact or of a hold leaves its edge
    (s = -1e-9 or 1 + 1e-9), its twin (the struck corner V against the striking slab's edge at P
    that faces the struck edge back) carries it on if V projects on that edge within
    eta = 2 (|g| + 1e-8) / |F| and presses it (kelvin g < 0, hold g <= 1e-8), else the next edge
    (P against the struck slab's edge meeting the struck one at V, same conditions), else it ends
    (kelvin: its duration, impulse and peak recorded; hold: released "slid off the edge"); the same
    record, m and c kept; the impulse is the integral of F over every candidate the contact used;
  - holds: g'' = -3 g'/tau - 2 g/tau^2 (tau = 10 ms, as the program: a twin taking a hold starts at
    a few mm/s of g'), released where their force (W lambda = -(G a_free + h + drift terms)) turns
    tensile, and after every event by the held set's complementarity problem.
A gap that crossed inside the step that ended at an earlier root (a face meeting flush: two roots
1e-15 s apart, of which solve_ivp reports the first) is taken as crossed at that event. Peaks of
force and overlap are located by bounded Brent on the dense output.

Checked (limits; measured with the program of 2026-11-28 02:49 in parentheses, worst over the
cases that agree and both methods):
  1. the peer alone: g' = G q' and g'' = G q'' + h against five-point differences of g along a
     random motion, 1e-8 (3.8e-10); the program's periods (pounding modes) are the peer's, 1e-9
     (6.7e-16); energy input = kinetic + strain + damping + contact work (- constraint work) within
     1e-9 of the input (2.8e-12); at rtol 1e-13 the same contacts, instants within 1e-10 s (9.0e-13),
     impulses and approach speeds 1e-8 (1.3e-10) (A | B kelvin and impulse k = 0); each scene does
     what it is for (at least 5 contacts, none on a side edge, no touch, no twin pulling at a
     hand-over, impulse law: no vertex inside the other slab (1e-12 m, measured 5.6e-14) and no open,
     uncovered candidate overlapping on its edge; kelvin: the deepest contact about 1 to 10 mm;
     hand-overs in A | B kelvin, A | B k = 0 (a hold) and the row kelvin); without the hand-over
     rule the A | B kelvin contacts change (8 of 15 unmatched, matched impulses by up to 78 %), far
     beyond the impulses' limit;
  2. the program (cvode-bdf and arkode-erk at --rtol 1e-12 --atol 1e-14) against the peer, per case:
     completed with exit 0; its impacts (impacts.csv, by onset; as many as summary.json's) one to
     one with the peer's in time order: striking and struck building, vertex, struck edge (the
     onset's), whether a hold starts, and within
       impact instant         1e-8 s        (4.0e-10)
       approach speed         1e-6 relative (3.1e-8)
       impulse                1e-6 relative (3.1e-8; kelvin: over the whole contact, hand-overs in)
       kelvin duration        1e-8 s        (8.7e-11)
       kelvin peak force      1e-6 relative (3.9e-7: the program takes it from 17 samples a step)
       hold start, release    1e-8 s        (2.5e-10), with the same vertex and release reason
       hold impulse share     1e-6 kN s     (9.5e-10)
       u, v at history rows   1e-8 m        (1.1e-10)
       phi at history rows    1e-9 rad      (6.4e-12)
     statistics.corner_handovers equal to the peer's hand-overs; no impact on a side edge where the
     peer has none; and on the program's history (u, v, phi of every slab at every row, outlines
     rebuilt) no vertex deeper inside the other slab than 1e-6 m (impulse law; 2.1e-14) or than the
     peer's deepest overlap (kelvin: 10.0 mm; the program's 8.6 mm) plus 1e-6 m.
     (The limits are the spec's: 1e-8 s and 1e-6 relative; a missing hand-over or a contact begun
     at the wrong candidate changes impulses by percents.)

With B moved by +-1 um the program first struck side edges where nothing touches (a vertex on the
other slab's facade at the end of a side edge, mm behind that edge's line); the rules of
docs/model.md §5a ("inside means inside", a vertex sliding along the face where the slabs meet)
were written against this test. Run time about 45 s (the peers ~30 s).
"""
import json
import math
import subprocess
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import eigh
from scipy.optimize import minimize_scalar

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

# --- the scenes -----------------------------------------------------------------------------------
E_KPA, STOREY_M, ZETA = 3.0e7, 3.0, 0.05
GAP_M = 0.02  # the clear gap between facades in line
MARGIN_M = 1.0  # candidate_margin_m (default): the candidates' reach
ON_EDGE = 1e-9  # a point is on its edge within this fraction of the edge's length
CLOSED_M = 1e-8  # contact_tolerance_m: closed within this gap; the touch band of the corner rules
REOPEN_M = 1e-10  # a gap that has just been handled is watched again once it opens beyond this
HOLD_VELOCITY_MPS, HOLD_HEIGHT_M, TAU_S = 1e-3, 1e-8, 0.01
# The ground pulse: PULSE_MPS2 sin(2 pi t / PULSE_PERIOD_S) for PULSE_CYCLES periods, then nothing,
# sampled every DT_S up to DURATION_S, along BETA_DEG.
PULSE_MPS2, PULSE_PERIOD_S, PULSE_CYCLES, DT_S, DURATION_S, BETA_DEG = 4.0, 0.5, 2, 0.01, 2.5, 25.0
KELVIN_K, KELVIN_E = 5.0e5, 0.5


def building(name, x0, cm, mass, column):
    """A one-storey building: slab x in [x0, x0 + 10], y in [0, 8] (+ dy), 3 x 3 square columns at
    the slab's corners, edge midpoints and centre."""
    return dict(name=name, x=(x0, x0 + 10.0), y=(0.0, 8.0), cm=cm, mass=mass, column=column)


def street(count=2, dy=0.0):
    """A (and B, C) with facades in line, GAP_M apart; B (only) shifted by dy along y."""
    d = GAP_M
    out = [building("A", 0.0, (5.0, 4.8), 150.0, 0.25),
           building("B", 10.0 + d, (15.0 + d, 3.2), 200.0, 0.22),
           building("C", 20.0 + 2 * d, (25.0 + 2 * d, 4.6), 170.0, 0.24)][:count]
    b = out[1]
    b["y"] = (b["y"][0] + dy, b["y"][1] + dy)
    b["cm"] = (b["cm"][0], b["cm"][1] + dy)
    return out


def record():
    t = np.arange(round(DURATION_S / DT_S) + 1) * DT_S
    a = np.where(t < PULSE_CYCLES * PULSE_PERIOD_S - DT_S / 2, PULSE_MPS2 * np.sin(2 * np.pi * t / PULSE_PERIOD_S), 0.0)
    return t, a


def scene_text(buildings, law, restitution, record_path):
    parts = ['name = "street-peer"\n']
    for b in buildings:
        (x0, x1), (y0, y1) = b["x"], b["y"]
        parts.append(f"""
[[building]]
name = "{b['name']}"
storeys = 1
storey_height_m = {STOREY_M!r}
slab = [[{x0!r}, {y0!r}], [{x1!r}, {y0!r}], [{x1!r}, {y1!r}], [{x0!r}, {y1!r}]]
centre_of_mass = [{b['cm'][0]!r}, {b['cm'][1]!r}]
mass_t = {b['mass']!r}
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA!r}
frame_factor = 1.0
[[building.column_grid]]
x = [{x0!r}, {(x0 + x1) / 2!r}, {x1!r}]
y = [{y0!r}, {(y0 + y1) / 2!r}, {y1!r}]
b_m = {b['column']!r}
h_m = {b['column']!r}
[building.damping]
ratio = {ZETA!r}
modes = [1, 3]
""")
    parts.append(f"""
[excitation]
file = "{record_path}"
format = "single"
units = "m/s2"
dt_s = {DT_S!r}
direction_deg = {BETA_DEG!r}

[solver]
method = "cvode-bdf"
rtol = 1e-12
atol = 1e-14

[contact]
law = "{law}"
restitution = {restitution!r}
""")
    if law == "kelvin":
        parts.append(f"stiffness_kN_per_m = {KELVIN_K!r}\n")
    if len(buildings) == 2:
        parts.append(f"gap_m = {GAP_M!r}\n")
    else:
        parts.append("[contact.gaps]\n" + "".join(f'"{a["name"]}:{b["name"]}" = {GAP_M!r}\n'
                                                  for a, b in zip(buildings[:-1], buildings[1:])))
    return "".join(parts)


# --- the peer's model -----------------------------------------------------------------------------
def rot(phi):
    c, s = math.cos(phi), math.sin(phi)
    return np.array([[c, -s], [s, c]])


class Building:
    """One storey: q = (u, v, phi) of the slab's CM relative to the ground; K from the columns,
    diag(m, m, J) with J "uniform" (about the slab's centroid), Rayleigh C at modes 1 and 3."""

    def __init__(self, spec):
        self.name = spec["name"]
        (x0, x1), (y0, y1) = spec["x"], spec["y"]
        self.verts = [np.array(p) for p in ((x0, y0), (x1, y0), (x1, y1), (x0, y1))]  # counter-clockwise
        self.cm = np.array(spec["cm"], dtype=float)
        self.mass = spec["mass"]
        self.J = self.mass * ((x1 - x0) ** 2 + (y1 - y0) ** 2) / 12.0
        b = spec["column"]
        k = 12.0 * E_KPA * (b ** 4 / 12.0) / STOREY_M ** 3  # fixed-fixed, square: k_x = k_y
        self.K = np.zeros((3, 3))
        for x in (x0, (x0 + x1) / 2, x1):
            for y in (y0, (y0 + y1) / 2, y1):
                T = np.array([[1.0, 0.0, -(y - self.cm[1])], [0.0, 1.0, x - self.cm[0]]])
                self.K += k * T.T @ T
        self.m_diag = np.array([self.mass, self.mass, self.J])
        w = np.sqrt(np.sort(eigh(self.K, np.diag(self.m_diag), eigvals_only=True)))
        self.omega = w
        a0, a1 = 2 * ZETA * w[0] * w[2] / (w[0] + w[2]), 2 * ZETA / (w[0] + w[2])
        self.C = a0 * np.diag(self.m_diag) + a1 * self.K

    def edge(self, e):
        q1, q2 = self.verts[e], self.verts[(e + 1) % 4]
        L = float(np.linalg.norm(q2 - q1))
        t = (q2 - q1) / L
        return q1, q2, t, np.array([t[1], -t[0]]), L  # the outward normal: the direction turned clockwise


class Candidate:
    """Vertex v of building A's slab (rest point X) against edge e (Q1 -> Q2) of building B's."""

    def __init__(self, A, v, B, e, bA, bB):
        self.A, self.v, self.B, self.e = A, v, B, e
        self.X = bA.verts[v]
        self.q1, self.q2, self.t0, self.n0, self.L = bB.edge(e)
        self.rho0 = self.X - bA.cm
        self.sig0 = self.q1 - bB.cm

    def label(self, names):
        return f"{names[self.A]} v{self.v + 1} -> {names[self.B]} e{self.e + 1}"


def segment_distance(p, q1, q2):
    d = q2 - q1
    s = min(max(np.dot(p - q1, d) / np.dot(d, d), 0.0), 1.0)
    return float(np.linalg.norm(p - (q1 + s * d)))


def find_candidates(bs, pairs):
    """Every vertex of one slab against every edge of the other of a neighbouring pair that it lies
    within the gap plus the margin of, at rest (for facades in line: the facing edges and the side
    edges at the shared corners)."""
    out = []
    for a, b in pairs:
        for s, t in ((a, b), (b, a)):
            for e in range(4):
                q1, q2 = bs[t].verts[e], bs[t].verts[(e + 1) % 4]
                for v in range(4):
                    if segment_distance(bs[s].verts[v], q1, q2) <= GAP_M + MARGIN_M:
                        out.append(Candidate(s, v, t, e, bs[s], bs[t]))
    return out


def lcp(W, b):
    """w = W x + b >= 0, x >= 0, x w = 0 by enumeration of the active sets (W positive definite)."""
    n = len(b)
    scale = 1e-12 * (1.0 + np.max(np.abs(b))) if n else 0.0
    for size in range(n + 1):
        for mask in range(1 << n):
            active = [i for i in range(n) if mask >> i & 1]
            if len(active) != size:
                continue
            x = np.zeros(n)
            if active:
                x[active] = np.linalg.solve(W[np.ix_(active, active)], -b[active])
            w = W @ x + b
            if np.all(x >= -scale * 1e-3) and np.all(w >= -scale):
                return np.maximum(x, 0.0), w
    raise RuntimeError("LCP without solution")


class Peer:
    """The slabs with the documented contact model (the spec's corner rules), integrated with
    DOP853 over each record interval, every switch a terminal event and the integration restarted
    there in the new contact state.

    A candidate's mode: "above" (open, g > 0: its closing is an event), "below" (open, g < 0 after
    a crossing that was no onset: its opening is an event), "masked" (just handled at g = 0: watched
    again once g > REOPEN_M), "acting" / "released" (kelvin: a contact in progress whose force acts
    or has turned tensile), "held" (impulse law)."""

    def __init__(self, specs, law, restitution, method="DOP853", rtol=1e-12, atol=1e-14, stiffness=KELVIN_K,
                 handovers=True):
        self.specs, self.allow_handovers = specs, handovers
        self.b = [Building(s) for s in specs]
        self.names = [b.name for b in self.b]
        self.nb = len(self.b)
        self.n = 3 * self.nb
        self.m_diag = np.concatenate([b.m_diag for b in self.b])
        self.K = np.zeros((self.n, self.n))
        self.C = np.zeros((self.n, self.n))
        for i, b in enumerate(self.b):
            self.K[3 * i:3 * i + 3, 3 * i:3 * i + 3] = b.K
            self.C[3 * i:3 * i + 3, 3 * i:3 * i + 3] = b.C
        beta = math.radians(BETA_DEG)
        self.r = np.tile([math.cos(beta), math.sin(beta), 0.0], self.nb)
        self.mr = self.m_diag * self.r
        self.law, self.k, self.stiffness = law, restitution, stiffness
        ln_e = math.log(restitution) if restitution > 0 else -math.inf
        self.xi = 1.0 if restitution == 0 else -ln_e / math.sqrt(math.pi ** 2 + ln_e ** 2)
        self.method, self.rtol, self.atol = method, rtol, atol
        self.pairs = [(i, i + 1) for i in range(self.nb - 1)]
        self.cands = find_candidates(self.b, self.pairs)
        nc = len(self.cands)
        self.mode = ["above"] * nc
        self.contact = [None] * nc  # the contact (a dict) candidate i carries now
        self.held = []  # held candidates, in order
        self.contacts, self.impacts, self.holds = [], [], []
        self.handovers = []
        self.n_aug = 4 + nc  # input, damping, contact work (kelvin), constraint work (holds); impulse per candidate
        self.links()

    # --- geometry -----------------------------------------------------------------------------
    def links(self):
        """Per candidate and end of its edge (0: Q1, 1: Q2): its twin and its next-edge candidate."""
        index = {(c.A, c.v, c.B, c.e): i for i, c in enumerate(self.cands)}
        self.twin, self.next = [], []
        for c in self.cands:
            tw, nx = [None, None], [None, None]
            for end in (0, 1):
                V = (c.e + end) % 4  # the struck slab's corner at that end
                # the striking slab's edges at P: the one facing the struck edge back
                for F in ((c.v - 1) % 4, c.v):
                    nF = self.b[c.A].edge(F)[3]
                    if np.dot(nF, c.n0) < -math.cos(math.radians(45.0)):
                        tw[end] = index.get((c.B, V, c.A, F))
                other = (c.e - 1) % 4 if end == 0 else (c.e + 1) % 4  # the struck edge meeting it at V
                nx[end] = index.get((c.A, c.v, c.B, other))
            self.twin.append(tw)
            self.next.append(nx)

    def kin(self, i, y):
        """g, g', the gap row G, P (now), s, and the curvature h (g'' = G q'' + h), exact rotation."""
        c, n = self.cands[i], self.n
        A, B = 3 * c.A, 3 * c.B
        bA, bB = self.b[c.A], self.b[c.B]
        ca, sa = math.cos(y[A + 2]), math.sin(y[A + 2])
        rx, ry = ca * c.rho0[0] - sa * c.rho0[1], sa * c.rho0[0] + ca * c.rho0[1]
        px, py = bA.cm[0] + y[A] + rx, bA.cm[1] + y[A + 1] + ry
        cb, sb = math.cos(y[B + 2]), math.sin(y[B + 2])
        nx, ny = cb * c.n0[0] - sb * c.n0[1], sb * c.n0[0] + cb * c.n0[1]
        tx, ty = -ny, nx
        sx, sy = cb * c.sig0[0] - sb * c.sig0[1], sb * c.sig0[0] + cb * c.sig0[1]
        dx, dy = px - (bB.cm[0] + y[B] + sx), py - (bB.cm[1] + y[B + 1] + sy)
        g = dx * nx + dy * ny
        s = (dx * tx + dy * ty) / c.L
        wa, wb = y[n + A + 2], y[n + B + 2]
        ddx = (y[n + A] - wa * ry) - (y[n + B] - wb * sy)
        ddy = (y[n + A + 1] + wa * rx) - (y[n + B + 1] + wb * sx)
        gd = ddx * nx + ddy * ny + wb * (dx * tx + dy * ty)
        G = np.zeros(n)
        G[A:A + 3] = (nx, ny, rx * ny - ry * nx)
        G[B:B + 3] = (-nx, -ny, -((sx + dx) * ny - (sy + dy) * nx))
        h = (-wa * wa * (rx * nx + ry * ny) + wb * wb * (sx * nx + sy * ny) - wb * wb * g
             + 2 * wb * (ddx * tx + ddy * ty))
        return g, gd, G, (px, py), s, h

    def gap(self, i, y):
        return self.kin(i, y)[0]

    def vertex_now(self, b, v, y):
        bb = self.b[b]
        return bb.cm + y[3 * b:3 * b + 2] + rot(y[3 * b + 2]) @ (bb.verts[v] - bb.cm)

    def outline_now(self, b, q):
        bb = self.b[b]
        R = rot(q[3 * b + 2])
        return [bb.cm + q[3 * b:3 * b + 2] + R @ (p - bb.cm) for p in bb.verts]

    def in_progress(self, i):
        return self.mode[i] in ("acting", "released", "held")

    def covered(self, j, y):
        """The corner rule 2: a contact in progress covers its vertex's other candidates against the
        same slab, and the candidates of a corner of its struck slab that lies at its point."""
        cj = self.cands[j]
        for i, ci in enumerate(self.cands):
            if i == j or not self.in_progress(i):
                continue
            if (ci.A, ci.v, ci.B) == (cj.A, cj.v, cj.B):
                return True
            if (cj.A, cj.B) == (ci.B, ci.A) and cj.v in (ci.e, (ci.e + 1) % 4):
                g, _, _, P, _, _ = self.kin(i, y)
                V = self.vertex_now(cj.A, cj.v, y)
                if math.hypot(V[0] - P[0], V[1] - P[1]) <= 2.0 * (max(0.0, -g) + CLOSED_M):
                    return True
        return False

    # --- forces ---------------------------------------------------------------------------------
    def kelvin(self, i, g, gd):
        return self.stiffness * (-g) + self.contact[i]["c"] * (-gd)

    def free_accel(self, t, y):
        q, qd = y[:self.n], y[self.n:2 * self.n]
        return (-self.K @ q - self.C @ qd) / self.m_diag - self.r * self.ag(t)

    def hold_forces(self, t, y, held, drift=True, a_free=None):
        """The forces keeping the held gaps at g'' = -3 g'/tau - 2 g/tau^2 (drift=False: g'' = 0)."""
        if a_free is None:
            a_free = self.free_accel(t, y)
        rows, bias = [], []
        for i in held:
            g, gd, G, _, _, h = self.kin(i, y)
            rows.append(G)
            bias.append(G @ a_free + h + ((3.0 * gd / TAU_S + 2.0 * g / TAU_S ** 2) if drift else 0.0))
        Gm = np.array(rows)
        W = Gm @ (Gm.T / self.m_diag[:, None])
        return np.linalg.solve(W, -np.array(bias)), Gm, W, np.array(bias)

    def rhs(self, t, y):
        n = self.n
        qd = y[n:2 * n]
        acc = self.free_accel(t, y)
        aug = np.zeros(self.n_aug)
        a = self.ag(t)
        aug[0] = -qd @ self.mr * a
        aug[1] = qd @ self.C @ qd
        if self.law == "kelvin":
            for i in self.acting:
                g, gd, G, _, _, _ = self.kin(i, y)
                F = self.kelvin(i, g, gd)
                acc = acc + F * G / self.m_diag
                aug[2] += -F * gd
                aug[4 + i] = F
        elif self.held:
            lam, Gm, _, _ = self.hold_forces(t, y, self.held, a_free=acc)
            acc = acc + (Gm.T @ lam) / self.m_diag
            for r, i in enumerate(self.held):
                aug[3] += lam[r] * (Gm[r] @ qd)
                aug[4 + i] = lam[r]
        return np.concatenate([qd, acc, aug])

    # --- events ---------------------------------------------------------------------------------
    def event_functions(self):
        fs, tags = [], []

        def add(f, direction, tag):
            f.terminal, f.direction = True, direction
            fs.append(f)
            tags.append(tag)
        for i in range(len(self.cands)):
            m = self.mode[i]
            if m == "above":
                add(lambda t, y, i=i: self.gap(i, y), -1, ("onset", i))
            elif m == "below":
                add(lambda t, y, i=i: self.gap(i, y), 1, ("up", i))
            elif m == "masked":
                add(lambda t, y, i=i: self.gap(i, y) - REOPEN_M, 1, ("up", i))
            elif m in ("acting", "released"):
                add(lambda t, y, i=i: self.gap(i, y), 1, ("opens", i))
                if m == "acting":
                    add(lambda t, y, i=i: self.kelvin(i, *self.kin(i, y)[:2]), -1, ("release", i))
                    add(lambda t, y, i=i: self.kin(i, y)[4] + ON_EDGE, -1, ("edge", i))
                    add(lambda t, y, i=i: 1.0 + ON_EDGE - self.kin(i, y)[4], -1, ("edge", i))
                else:
                    add(lambda t, y, i=i: self.kelvin(i, *self.kin(i, y)[:2]), 1, ("acts again", i))
            elif m == "held":
                r = self.held.index(i)
                add(lambda t, y, r=r: self.hold_forces(t, y, self.held)[0][r], -1, ("tensile", i))
                add(lambda t, y, i=i: self.kin(i, y)[4] + ON_EDGE, -1, ("edge", i))
                add(lambda t, y, i=i: 1.0 + ON_EDGE - self.kin(i, y)[4], -1, ("edge", i))
        return fs, tags

    @property
    def acting(self):
        return [i for i, m in enumerate(self.mode) if m == "acting"]

    def successor(self, i, y):
        """Rule 3: the candidate that carries contact i on, its point having slid off its edge."""
        g, _, _, _, s, _ = self.kin(i, y)
        end = 0 if s < 0.5 else 1
        for kind, j in (("twin", self.twin[i][end]), ("next", self.next[i][end])):
            if j is None or self.in_progress(j):
                continue
            gj, _, _, _, sj, _ = self.kin(j, y)
            eta = 2.0 * (abs(g) + CLOSED_M) / self.cands[j].L
            touching = gj < 0.0 if self.law == "kelvin" else gj <= CLOSED_M
            if touching and -eta <= sj <= 1.0 + eta:
                return kind, j
        return None, None

    def reopen(self, i, y):
        """Candidate i, just handled, open again: armed if its gap is open beyond REOPEN_M, masked
        (armed once it opens beyond it) near zero, else waiting for its gap to open."""
        g = self.gap(i, y)
        self.mode[i] = "above" if g > REOPEN_M else "masked" if g > -REOPEN_M else "below"

    def on_edge(self, s):
        return -ON_EDGE <= s <= 1.0 + ON_EDGE

    def round_off(self, i, y):
        _, _, G, _, _, _ = self.kin(i, y)
        return 1e-15 + 1e-9 * float(np.abs(G) @ np.abs(y[self.n:2 * self.n]))

    def handle(self, t, y, tags):
        """The events at t (tags), in the order: edges, forces, gaps."""
        order = {"edge": 0, "release": 1, "acts again": 1, "tensile": 1, "opens": 2, "up": 2, "onset": 2}
        tags = sorted(set(tags), key=lambda tg: (order[tg[0]], tg[1]))
        onsets = []
        for kind, i in tags:
            if kind == "edge":
                if self.mode[i] not in ("acting", "held"):
                    continue
                how, j = self.successor(i, y) if self.allow_handovers else (None, None)
                if j is not None:
                    self.hand_over(t, y, i, j, how)
                elif self.law == "kelvin":
                    self.end_contact(t, y, i, "slid off")
                else:
                    self.release(t, y, i, "slid off the edge")
            elif kind == "release":
                if self.mode[i] == "acting":
                    self.mode[i] = "released"
                    self.contact[i]["release"] = t
            elif kind == "acts again":
                if self.mode[i] == "released" and self.gap(i, y) < 0.0:
                    self.mode[i] = "acting"
                    self.contact[i]["acts_again"] += 1
            elif kind == "tensile":
                if self.mode[i] == "held":
                    self.release(t, y, i, "tensile force")
            elif kind == "opens":
                if self.mode[i] in ("acting", "released"):
                    self.end_contact(t, y, i, "gap opens")
            elif kind == "up":
                if self.mode[i] in ("below", "masked"):
                    self.mode[i] = "above"
            elif kind == "onset":
                if self.mode[i] != "above":
                    continue
                g, gd, _, _, s, _ = self.kin(i, y)
                if not self.on_edge(s):
                    self.passed_beside += 1
                    self.mode[i] = "below"
                elif self.covered(i, y):
                    self.covered_crossings.append((t, self.cands[i].label(self.names)))
                    self.mode[i] = "below"
                elif gd >= -self.round_off(i, y):
                    self.touches.append((t, i))
                    self.mode[i] = "masked"
                else:
                    onsets.append(i)
        if self.law == "kelvin":
            for i in onsets:
                self.begin_contact(t, y, i)
        else:
            if onsets:
                self.impact(t, y, onsets)
            self.settle(t, y)

    # kelvin ------------------------------------------------------------------------------------
    def begin_contact(self, t, y, i):
        g, gd, G, P, s, _ = self.kin(i, y)
        W = float(np.sum(G * G / self.m_diag))
        self.contact[i] = dict(cand=i, t_s=t, approach=-gd, W=W, c=2.0 * self.xi * math.sqrt(self.stiffness / W),
                               impulse=0.0, base=y[2 * self.n + 4 + i], peak=0.0, acts_again=0, handovers=[],
                               point=P, s=s, release=None, path=[i])
        self.mode[i] = "acting"

    def close_share(self, y, i):
        """The impulse candidate i has given its contact since it took it."""
        rec = self.contact[i]
        rec["impulse"] += y[2 * self.n + 4 + i] - rec["base"]

    def end_contact(self, t, y, i, reason):
        rec = self.contact[i]
        self.close_share(y, i)
        if self.mode[i] == "acting":
            rec["release"] = t
        rec["duration"] = rec["release"] - rec["t_s"]
        rec["end"], rec["reason"] = t, reason
        self.contacts.append(rec)
        self.contact[i] = None
        self.reopen(i, y)

    def hand_over(self, t, y, i, j, how):
        gi, gj = self.gap(i, y), self.gap(j, y)
        rec = self.contact[i]
        self.handovers.append(dict(t=t, frm=i, to=j, how=how, g_from=gi, g_to=gj))
        if self.law == "kelvin":
            self.close_share(y, i)
            rec["base"] = y[2 * self.n + 4 + j]
            rec["handovers"].append((t, i, j, how))
            rec["path"].append(j)
            self.contact[j], self.contact[i] = rec, None
            self.mode[j] = "acting"
            _, gdj, _, _, _, _ = self.kin(j, y)
            if self.kelvin(j, gj, gdj) < 0.0:  # the twin pulls: released at once
                self.tensile_handovers.append((t, j))
                self.mode[j] = "released"
                rec["release"] = t
        else:
            hold = self.holds[self.hold_of[i]]
            hold["handovers"].append((t, i, j, how))
            self.hold_of[j], self.hold_of[i] = self.hold_of[i], None
            self.held[self.held.index(i)] = j
            self.mode[j] = "held"
        self.reopen(i, y)

    # impulse law -------------------------------------------------------------------------------
    def takes_part(self, i, y, fired):
        if self.mode[i] == "held" or i in fired:
            return True
        g, _, _, _, s, _ = self.kin(i, y)
        return abs(g) <= CLOSED_M and self.on_edge(s)

    def group(self, y, fired):
        """The candidates of one impact problem: the fired ones' pairs, and every pair sharing a slab
        with those that has a contact closed now or held; each such candidate of those pairs."""
        pairs = {tuple(sorted((self.cands[i].A, self.cands[i].B))) for i in fired}
        part = [i for i in range(len(self.cands)) if self.takes_part(i, y, fired)]
        grew = True
        while grew:
            grew = False
            slabs = {b for p in pairs for b in p}
            for i in part:
                p = tuple(sorted((self.cands[i].A, self.cands[i].B)))
                if p not in pairs and slabs & set(p):
                    pairs.add(p)
                    grew = True
        return [i for i in part if tuple(sorted((self.cands[i].A, self.cands[i].B))) in pairs]

    def gap_accels(self, t, y, members, held_others):
        """g'' of each member with the held contacts outside the group kept closed."""
        acc = self.free_accel(t, y)
        if held_others:
            lam, Gm, _, _ = self.hold_forces(t, y, held_others, a_free=acc)
            acc = acc + (Gm.T @ lam) / self.m_diag
        out = []
        for i in members:
            _, _, G, _, _, h = self.kin(i, y)
            out.append(G @ acc + h)
        return np.array(out)

    def pressing(self, t, y, trial):
        """Whether each of trial's contacts is pressed: its physical force (g'' = 0, no drift terms)
        has a gap acceleration above the round-off of the free accelerations it balances."""
        a_free = self.free_accel(t, y)
        lam, Gm, W, bias = self.hold_forces(t, y, trial, drift=False, a_free=a_free)
        size = np.abs(Gm) @ np.abs(a_free)
        out = []
        for k in range(len(trial)):
            h = bias[k] - Gm[k] @ a_free
            out.append(W[k, k] * lam[k] > 1e-9 * (1.0 + size[k] + abs(h)))
            self.margin_pressing = min(self.margin_pressing, abs(W[k, k] * lam[k]) / (1.0 + size[k]))
        return out

    def impact(self, t, y, fired):
        n = self.n
        members = self.group(y, fired)
        rows = np.array([self.kin(i, y)[2] for i in members])
        v = y[n:2 * n].copy()
        W = rows @ (rows.T / self.m_diag[:, None])
        before = rows @ v
        were_held = [self.mode[i] == "held" for i in members]
        pairs = {tuple(sorted((self.cands[i].A, self.cands[i].B))) for i in members}
        others = [i for i in self.held if tuple(sorted((self.cands[i].A, self.cands[i].B))) not in pairs]
        holding = [False] * len(members)
        y_after = y.copy()
        for _ in range(len(members) + 1):
            kk = np.where(holding, 0.0, self.k)
            imp, _ = lcp(W, before + kk * np.minimum(before, 0.0))
            v_after = v + (rows.T @ imp) / self.m_diag
            y_after = y.copy()
            y_after[n:2 * n] = v_after
            after = rows @ v_after
            accel = self.gap_accels(t, y_after, members, others)
            slow = []
            for k in range(len(members)):
                apex = after[k] ** 2 / (-2.0 * accel[k]) if accel[k] < 0.0 else math.inf
                if not holding[k] and not were_held[k]:
                    self.margin_hold = min(self.margin_hold, abs(after[k] / HOLD_VELOCITY_MPS - 1.0),
                                           abs(apex / HOLD_HEIGHT_M - 1.0))
                if after[k] < HOLD_VELOCITY_MPS or apex < HOLD_HEIGHT_M:
                    slow.append(k)
            proposal = [False] * len(members)
            if slow:
                press = self.pressing(t, y_after, others + [members[k] for k in slow])
                for s_, k in enumerate(slow):
                    proposal[k] = press[len(others) + s_]
            if proposal == holding:
                break
            holding = proposal
        hk = [k for k in range(len(members)) if holding[k]]
        if hk:  # the held ones brought to zero gap rate
            Gh = rows[hk]
            Wh = Gh @ (Gh.T / self.m_diag[:, None])
            closing = np.linalg.lstsq(Wh, -(Gh @ v_after), rcond=None)[0]
            v_after = v_after + (Gh.T @ closing) / self.m_diag
            imp[hk] += closing
        after = rows @ v_after
        self.loss += 0.5 * v @ (self.m_diag * v) - 0.5 * v_after @ (self.m_diag * v_after)
        for k, i in enumerate(members):
            if were_held[k]:
                self.holds[self.hold_of[i]]["impulse"] += imp[k]
                continue
            if imp[k] > 0.0 and before[k] < -self.round_off(i, y):
                _, _, _, P, s, _ = self.kin(i, y)
                self.impacts.append(dict(t_s=t, cand=i, approach=-before[k], separation=after[k], impulse=imp[k],
                                         holds=holding[k], point=P, s=s))
            elif i in fired:
                self.touches.append((t, i))
        y[n:2 * n] = v_after
        for k, i in enumerate(members):
            if holding[k] and not were_held[k]:
                self.held.append(i)
                self.mode[i] = "held"
                self.hold_of[i] = len(self.holds)
                self.holds.append(dict(cand=i, start=t, release=None, reason=None, impulse=0.0, handovers=[]))
            elif not holding[k] and were_held[k]:
                self.release(t, y, i, "separated by an impact")
            elif not holding[k]:
                self.reopen(i, y)

    def release(self, t, y, i, reason):
        hold = self.holds[self.hold_of[i]]
        hold["release"], hold["reason"] = t, reason
        self.hold_of[i] = None
        self.held.remove(i)
        self.reopen(i, y)

    def settle(self, t, y):
        """After every event: the held contacts' forces as one complementarity problem; those left
        without force while their gap would open are released."""
        if not self.held:
            return
        held = list(self.held)
        a_free = self.free_accel(t, y)
        _, Gm, W, bias = self.hold_forces(t, y, held, a_free=a_free)
        x, w = lcp(W, bias)
        round_off = 1e-9 * (1.0 + np.max(np.abs(w)))
        for r, i in enumerate(held):
            if x[r] <= 0.0 and w[r] > round_off:
                self.release(t, y, i, "tensile force")

    def step_past_root(self, t0, y, funcs, tags):
        t_past = t0 + 1e-12 * max(1.0, abs(t0))
        sol = solve_ivp(self.rhs, (t0, t_past), y, method=self.method, rtol=self.rtol, atol=self.atol,
                        dense_output=True, first_step=t_past - t0, max_step=t_past - t0)
        t_end, y_end = sol.t[-1], sol.y[:, -1].copy()
        self.track(sol, t0, t_end)
        self.segments.append((t0, t_end, sol.sol))
        fired = [tags[k] for k, f in enumerate(funcs) if -f.direction * f(t0, y) > 0.0 >= -f.direction * f(t_end, y_end)]
        if fired:
            self.events += 1
            self.handle(t_end, y_end, fired)
        return t_end, y_end

    # --- the run --------------------------------------------------------------------------------
    def run(self, times, accel):
        self.ag = lambda t: float(np.interp(t, times, accel))
        n = self.n
        y = np.zeros(2 * n + self.n_aug)
        self.segments = []
        self.passed_beside, self.touches, self.covered_crossings, self.tensile_handovers = 0, [], [], []
        self.loss, self.hold_of = 0.0, [None] * len(self.cands)
        self.margin_hold, self.margin_pressing = math.inf, math.inf
        self.deepest = 0.0  # the deepest vertex inside the other slab on the dense output (m)
        self.deepest_contact = 0.0  # the largest overlap -g of a kelvin contact while its force acts (m)
        self.unexplained = []  # open, uncovered candidates on their edge and overlapping on the dense output
        self.events, self.late_roots = 0, 0
        for a, b in zip(times[:-1], times[1:]):
            t0 = a
            while b - t0 > 1e-13:
                funcs, tags = self.event_functions()
                y_start = y
                try:
                    sol = solve_ivp(self.rhs, (t0, b), y, method=self.method, rtol=self.rtol, atol=self.atol,
                                    events=funcs or None, dense_output=True)
                except ValueError:
                    # A root at t0 within round-off (a function at 1e-15 and falling): on some CPUs
                    # scipy locates it at t0 itself and cannot build the dense output. Step 1e-12 s
                    # past it without events and take what crossed there as fired.
                    t0, y = self.step_past_root(t0, y, funcs, tags)
                    continue
                assert sol.status >= 0, sol.message
                t_end = sol.t[-1]
                self.track(sol, t0, t_end)
                self.segments.append((t0, t_end, sol.sol))
                y = sol.y[:, -1].copy()
                t0 = t_end
                if sol.status != 1:
                    break
                hit = [k for k, te in enumerate(sol.t_events) if len(te)]
                first = min(sol.t_events[k][0] for k in hit)
                fired = [tags[k] for k in hit if sol.t_events[k][0] <= first + 1e-14]
                # solve_ivp reports the first terminal root of a step only: a function that crossed
                # as well (a face meeting flush: two gap roots 1e-15 s apart) is past its zero here.
                for k, f in enumerate(funcs):
                    if tags[k] not in fired and -f.direction * f(t0, y_start) > 0.0 >= -f.direction * f(t_end, y):
                        fired.append(tags[k])
                        self.late_roots += 1
                self.events += 1
                if self.events > 20000:
                    raise RuntimeError(f"peer: more than 20000 events by {t_end} s")
                self.handle(t_end, y, fired)
        self.y_end = y
        for i, m in enumerate(self.mode):
            if m in ("acting", "released"):
                self.end_contact(times[-1], y, i, "end of run")
        for i in list(self.held):
            self.release(times[-1], y, i, "end of run")
        self.contacts.sort(key=lambda r: r["t_s"])
        q, qd = y[:n], y[n:2 * n]
        e = dict(input=y[2 * n], damping=y[2 * n + 1], kinetic=0.5 * qd @ (self.m_diag * qd),
                 strain=0.5 * q @ self.K @ q,
                 contact=y[2 * n + 2] if self.law == "kelvin" else self.loss, constraint=y[2 * n + 3])
        e["residual"] = e["input"] + e["constraint"] - e["kinetic"] - e["strain"] - e["damping"] - e["contact"]
        self.energy = e
        return self

    def track(self, sol, t0, t1):
        """On the dense output of [t0, t1]: each acting contact's largest force (bounded Brent near the
        largest of 9 samples), the deepest vertex inside the other slab, and open uncovered
        candidates overlapping on their edge (which the rules cannot explain)."""
        if t1 <= t0:
            return
        for i in range(len(self.cands)):
            if self.mode[i] not in ("acting", "released"):
                continue

            def force(t):
                g, gd = self.kin(i, sol.sol(t))[:2]
                return self.kelvin(i, g, gd)

            def overlap(t):
                return -self.gap(i, sol.sol(t))
            if self.mode[i] != "acting":
                continue
            for f, key in ((force, "peak"), (overlap, "deepest")):
                ts = np.linspace(t0, t1, 9)
                fs = [f(t) for t in ts]
                k = int(np.argmax(fs))
                res = minimize_scalar(lambda t: -f(t), bounds=(ts[max(k - 1, 0)], ts[min(k + 1, 8)]),
                                      method="bounded", options={"xatol": 1e-13})
                if key == "peak":
                    self.contact[i]["peak"] = max(self.contact[i]["peak"], fs[k], -res.fun)
                else:
                    self.deepest_contact = max(self.deepest_contact, fs[k], -res.fun)
        steps = np.concatenate([sol.t[sol.t < t1], [t1]])
        ts = np.unique(np.concatenate([np.linspace(p, q, 4, endpoint=False) for p, q in zip(steps[:-1], steps[1:])]
                                      + [[t1]]))
        ys = sol.sol(ts)
        for k in range(len(ts)):
            yk = ys[:, k]
            self.deepest = max(self.deepest, self.max_depth(yk[:self.n]))
            for i in range(len(self.cands)):
                if self.mode[i] in ("above", "below", "masked"):
                    g, _, _, _, s, _ = self.kin(i, yk)
                    if g < -1e-7 and 1e-6 < s < 1 - 1e-6 and not self.covered(i, yk):
                        self.unexplained.append((ts[k], self.cands[i].label(self.names), g, s))

    def max_depth(self, q):
        worst = 0.0
        outlines = [self.outline_now(b, q) for b in range(self.nb)]
        for a, b in self.pairs:
            for s, t in ((a, b), (b, a)):
                for p in outlines[s]:
                    worst = max(worst, depth_inside(outlines[t], p))
        return worst

    def at(self, ts):
        starts = np.array([s[0] for s in self.segments])
        out = []
        for t in ts:
            k = max(int(np.searchsorted(starts, t, side="right")) - 1, 0)
            t0, t1, sol = self.segments[k]
            out.append(sol(min(max(t, t0), t1))[:self.n])
        return np.array(out)


def depth_inside(outline, p):
    """How deep p lies inside the convex counter-clockwise outline: its distance to the nearest edge
    (0 outside or on it)."""
    depth = math.inf
    for k in range(len(outline)):
        q1, q2 = outline[k], outline[(k + 1) % len(outline)]
        t = (q2 - q1) / np.linalg.norm(q2 - q1)
        inward = -((p[0] - q1[0]) * t[1] - (p[1] - q1[1]) * t[0])  # -(P - Q1) . n, n = (t_y, -t_x)
        if inward <= 0.0:
            return 0.0
        depth = min(depth, inward)
    return depth


# --- the peer's own checks ------------------------------------------------------------------------
def check_kinematics(failures, out):
    """The gap row G is the gradient of g, and g'' = G q'' + h: g's first and second time derivatives
    along a random motion (central differences of g itself, at rotations of 0.02 rad)."""
    peer = Peer(street(3), "kelvin", 0.5)
    rng = np.random.default_rng(11)
    worst_G, worst_h = 0.0, 0.0
    for _ in range(3):
        q0, v0, a0 = rng.normal(0, 0.02, peer.n), rng.normal(0, 0.3, peer.n), rng.normal(0, 3.0, peer.n)
        q0[2::3], v0[2::3] = rng.normal(0, 0.02, peer.nb), rng.normal(0, 0.05, peer.nb)
        a0[2::3] = rng.normal(0, 0.5, peer.nb)

        def state(t):
            return np.concatenate([q0 + v0 * t + 0.5 * a0 * t * t, v0 + a0 * t])
        for i in range(len(peer.cands)):
            g, gd, G, _, _, h = peer.kin(i, state(0.0))
            e = 3e-3  # five-point stencils: truncation O(e^4), round-off ~1e-16 |g| / e^2 (|g| up to a metre)
            gs = [peer.gap(i, state(k * e)) for k in (-2, -1, 1, 2)]
            fd1 = (gs[0] - 8 * gs[1] + 8 * gs[2] - gs[3]) / (12 * e)
            fd2 = (-gs[0] + 16 * gs[1] - 30 * g + 16 * gs[2] - gs[3]) / (12 * e * e)
            worst_G = max(worst_G, abs(fd1 - G @ v0), abs(gd - G @ v0))
            worst_h = max(worst_h, abs(fd2 - (G @ a0 + h)) / (1.0 + abs(G @ a0)))
    line(out, "peer: g' = G q' and g'' = G q'' + h against five-point differences of g along a random motion "
         "(m/s, relative)", max(worst_G, worst_h), 1e-8, failures)


REPRODUCE = {}  # per program run (case, method): its command line


def line(out, label, value, limit, failures):
    """One comparison: its measured value and its limit, passed when value <= limit."""
    if value <= limit:
        out.append(f"  ok {label}: {value:.2e} (limit {limit:.0e})")
        print(out[-1])
    else:
        fail(failures, out, f"{label}: {value:.2e} (limit {limit:.0e})")


def fail(failures, out, message):
    failures.append(message)
    out.append("FAIL " + message)
    print(out[-1])


def check_modes(program, folder, specs, failures, out):
    """The program's periods (pounding modes) are the peer's 2 pi / omega: the same K, M."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "record.txt").write_text("\n".join(repr(a) for a in record()[1]) + "\n")
    (folder / "scene.toml").write_text(scene_text(specs, "kelvin", 0.5, folder / "record.txt"))
    run = subprocess.run([program, "modes", str(folder / "scene.toml"), "--json", str(folder / "modes.json")],
                         capture_output=True, text=True)
    if run.returncode != 0:
        fail(failures, out, f"modes: exit {run.returncode}: {run.stderr.strip()[-300:]}")
        return
    modes = json.loads((folder / "modes.json").read_text())["buildings"]
    worst = 0.0
    for b, spec in zip(modes, specs):
        own = np.sort(2 * np.pi / Building(spec).omega)[::-1]
        worst = max(worst, float(np.max(np.abs(np.array(b["periods_s"]) / own - 1.0))))
    periods = ", ".join(f"{b['name']} " + "/".join(f"{p:.3f}" for p in b["periods_s"]) for b in modes)
    line(out, f"modes: the program's periods ({periods} s) against the peer's (relative)", worst, 1e-9, failures)


# --- the program ----------------------------------------------------------------------------------
METHODS = {"cvode-bdf": ["--method", "cvode-bdf", "--rtol", "1e-12", "--atol", "1e-14"],
           "arkode-erk": ["--method", "arkode-erk", "--rtol", "1e-12", "--atol", "1e-14"]}


def run_program(program, folder, specs, law, restitution, options):
    cmd = [program, "run", str(folder / "scene.toml"), "--out", str(folder / "run"), "--no-progress", *options]
    _, a = record()
    cols = [f"B{b + 1}_f1_{c}" for b in range(len(specs)) for c in ("u_m", "v_m", "phi_rad")]
    run, message = program_run.run_scene(program, folder, lambda path: scene_text(specs, law, restitution, path), a,
                                         options, cols, record_name="record.txt", accept_any_exit=True)
    return (None, message, cmd) if run is None else ((run.summary, run.impacts, run.t, run.q), None, cmd)


def peer_events(peer):
    """The peer's impacts (kelvin: its contacts) as the program's rows would give them."""
    out = []
    rows = peer.contacts if peer.law == "kelvin" else peer.impacts
    for r in rows:
        c = peer.cands[r["cand"]]
        out.append(dict(t=r["t_s"], striking=c.A + 1, struck=c.B + 1, vertex=c.v + 1, edge=c.e + 1,
                        approach=r["approach"], impulse=r["impulse"], duration=r.get("duration", 0.0),
                        peak=r.get("peak", 0.0), holds=r.get("holds", False), side=abs(c.n0[0]) < 0.5))
    return out


def program_events(impacts):
    out = []
    for r in impacts:
        striking = int(r["striking_building"])
        struck = int(r["struck_building"]) if "struck_building" in r else 3 - striking
        out.append(dict(t=float(r["t_s"]), striking=striking, struck=struck, vertex=int(r["vertex"]),
                        edge=int(r["struck_edge"]), approach=float(r["approach_velocity_mps"]),
                        impulse=float(r["impulse_kNs"]), duration=float(r["duration_s"]),
                        peak=float(r["peak_force_kN"]), holds=r["starts_sustained_contact"] in ("1", "true")))
    return out


def describe(e, names):
    return (f"{e['t']:.9f} s {names[e['striking'] - 1]} v{e['vertex']} -> {names[e['struck'] - 1]} e{e['edge']} "
            f"(approach {e['approach']:.6f} m/s, impulse {e['impulse']:.6f} kN s"
            + (f", duration {e['duration']:.6f} s, peak {e['peak']:.3f} kN" if e["duration"] else "")
            + (", held after" if e["holds"] else "") + ")")


# The limits of each comparison (measured values in the docstring): impact instants and kelvin
# durations (s), approach speeds, impulses and peak forces (relative), holds' start and release (s)
# and impulse shares (kN s), u and v (m) and phi (rad) at every history row.
LIMITS = dict(t=1e-8, duration=1e-8, approach=1e-6, impulse=1e-6, peak=1e-6, hold_t=1e-8, share=1e-6, uv=1e-8,
              phi=1e-9, depth=1e-6)


def compare(program, folder, case, peer, method, failures, out):
    name = f"{case['name']}, {method}"
    result, error, cmd = run_program(program, folder, peer.specs, case["law"], case["k"], METHODS[method])
    REPRODUCE[name] = " ".join(cmd)
    if result is None:
        fail(failures, out, f"{name}: the program failed: {error}")
        return
    summary, impacts, t_out, q = result
    names = peer.names
    status = summary["status"]
    if status != "completed" or summary["exit_code"] != 0:
        fail(failures, out, f"{name}: exit {summary['exit_code']}, status {status}: {summary.get('status_detail')}")
    mine, theirs = peer_events(peer), program_events(impacts)
    if len(summary["impacts"]) != len(impacts):
        fail(failures, out, f"{name}: summary.json has {len(summary['impacts'])} impacts, impacts.csv {len(impacts)}")
    side = [e for e in theirs if any(c.A + 1 == e["striking"] and c.v + 1 == e["vertex"] and c.B + 1 == e["struck"]
                                     and c.e + 1 == e["edge"] and abs(c.n0[0]) < 0.5 for c in peer.cands)]
    ident = ("striking", "struck", "vertex", "edge", "holds")
    first = next((k for k in range(min(len(mine), len(theirs)))
                  if any(mine[k][f] != theirs[k][f] for f in ident) or abs(mine[k]["t"] - theirs[k]["t"]) > 1e-6),
                 None)
    if first is not None or len(mine) != len(theirs):
        k = first if first is not None else min(len(mine), len(theirs))
        t_k = min(mine[k]["t"] if k < len(mine) else math.inf, theirs[k]["t"] if k < len(theirs) else math.inf)

        def at_k(events):  # the k-th event and those at its instant
            return "; ".join(describe(e, names) for e in events[k:] if e["t"] < events[k]["t"] + 1e-6) \
                if k < len(events) else "none"
        fail(failures, out,
             f"{name}: the program has {len(theirs)} impacts ({len(side)} on side edges), the peer {len(mine)}; the "
             f"first {k} agree, then: peer {at_k(mine)} | program {at_k(theirs)}")
        while k > 0 and abs(mine[k - 1]["t"] - t_k) < 1e-6:  # an impact at that instant is part of the difference
            k -= 1
        first = k
    n = first if first is not None else min(len(mine), len(theirs))
    d = dict(t=0.0, duration=0.0, approach=0.0, impulse=0.0, peak=0.0)
    for a, b in zip(mine[:n], theirs[:n]):
        d["t"] = max(d["t"], abs(a["t"] - b["t"]))
        d["approach"] = max(d["approach"], abs(b["approach"] / a["approach"] - 1.0))
        d["impulse"] = max(d["impulse"], abs(b["impulse"] / a["impulse"] - 1.0))
        if case["law"] == "kelvin":
            d["duration"] = max(d["duration"], abs(a["duration"] - b["duration"]))
            d["peak"] = max(d["peak"], abs(b["peak"] / a["peak"] - 1.0))
    agreed = f"{n} of {len(mine)}" if n < len(mine) or len(mine) != len(theirs) else f"all {n}"
    line(out, f"{name}: impact instants ({agreed} impacts) (s)", d["t"], LIMITS["t"], failures)
    line(out, f"{name}: approach speeds (relative)", d["approach"], LIMITS["approach"], failures)
    what = " (the integral of F over each contact, hand-overs included)" if case["law"] == "kelvin" else ""
    line(out, f"{name}: impulses{what} (relative)", d["impulse"], LIMITS["impulse"], failures)
    if case["law"] == "kelvin":
        line(out, f"{name}: durations (s)", d["duration"], LIMITS["duration"], failures)
        line(out, f"{name}: peak forces (relative)", d["peak"], LIMITS["peak"], failures)
    handovers = summary["statistics"].get("corner_handovers")
    if handovers == len(peer.handovers):
        out.append(f"  ok {name}: corner hand-overs: program {handovers}, peer {len(peer.handovers)}")
        print(out[-1])
    else:
        fail(failures, out, f"{name}: corner hand-overs: program {handovers}, peer {len(peer.handovers)}")
    if side and not any(e["side"] for e in mine):
        fail(failures, out, f"{name}: the program strikes side edges where the peer has no contact: "
             + "; ".join(describe(e, names) for e in side))
    if case["law"] == "impulse":
        compare_holds(name, peer, summary, failures, out)
    # the histories, up to the first disagreement in the impacts
    t_stop = min(mine[n]["t"] if n < len(mine) else math.inf, theirs[n]["t"] if n < len(theirs) else math.inf)
    rows = t_out < t_stop - 1e-9
    diff = np.abs(q[rows] - peer.at(t_out[rows]))
    before = " before the first disagreement" if t_stop < math.inf else ""
    line(out, f"{name}: u, v at {int(np.sum(rows))} history rows{before} (m)",
         float(np.max(diff[:, [k for k in range(q.shape[1]) if k % 3 != 2]])), LIMITS["uv"], failures)
    line(out, f"{name}: phi at the same rows (rad)", float(np.max(diff[:, 2::3])), LIMITS["phi"], failures)
    depth = max(peer.max_depth(row) for row in q)
    own = max(peer.deepest_contact, peer.deepest) if case["law"] == "kelvin" else 0.0
    line(out, f"{name}: deepest vertex inside the other slab on the program's history ({depth:.3e} m), beyond the "
         f"peer's deepest ({own:.3e} m) (m)", max(0.0, depth - own), LIMITS["depth"], failures)


def compare_holds(name, peer, summary, failures, out):
    theirs = sorted(summary.get("sustained_contacts", []), key=lambda h: h["start_s"])
    mine = peer.holds
    names = peer.names

    def desc(h, prog):
        if prog:
            return (f"{names[h['striking_building'] - 1]} v{h['vertex']} from {h['start_s']:.9f} to "
                    f"{h['release_s']:.9f} s ({h['release_reason']}, share {h['impulse_kNs']:.6f} kN s)")
        c = peer.cands[h["cand"]]
        return (f"{names[c.A]} v{c.v + 1} from {h['start']:.9f} to {h['release']:.9f} s ({h['reason']}, share "
                f"{h['impulse']:.6f} kN s, {len(h['handovers'])} hand-overs)")
    n = min(len(mine), len(theirs))
    first = next((k for k in range(n) if abs(mine[k]["start"] - theirs[k]["start_s"]) > 1e-6
                  or abs(mine[k]["release"] - theirs[k]["release_s"]) > 1e-6
                  or mine[k]["reason"] != theirs[k]["release_reason"]
                  or (peer.cands[mine[k]["cand"]].A + 1, peer.cands[mine[k]["cand"]].v + 1)
                  != (theirs[k]["striking_building"], theirs[k]["vertex"])), None)
    if first is not None or len(mine) != len(theirs):
        k = first if first is not None else n
        fail(failures, out, f"{name}: the program has {len(theirs)} holds, the peer {len(mine)}; the first {k} agree, "
             f"then: peer {desc(mine[k], False) if k < len(mine) else 'none'} | program "
             f"{desc(theirs[k], True) if k < len(theirs) else 'none'}")
        n = k
    dt = max([max(abs(a["start"] - b["start_s"]), abs(a["release"] - b["release_s"]))
              for a, b in zip(mine[:n], theirs[:n])] or [0.0])
    ds = max([abs(a["impulse"] - b["impulse_kNs"]) for a, b in zip(mine[:n], theirs[:n])] or [0.0])
    line(out, f"{name}: holds' start and release ({n} of {len(mine)} holds) (s)", dt, LIMITS["hold_t"], failures)
    line(out, f"{name}: holds' impulse shares (kN s)", ds, LIMITS["share"], failures)


# --- the cases ------------------------------------------------------------------------------------
CASES = [
    dict(name="two, kelvin", count=2, dy=0.0, law="kelvin", k=KELVIN_E),
    dict(name="two, impulse k = 0.5", count=2, dy=0.0, law="impulse", k=0.5),
    dict(name="two, impulse k = 0", count=2, dy=0.0, law="impulse", k=0.0),
    dict(name="row of three, kelvin", count=3, dy=0.0, law="kelvin", k=KELVIN_E),
    dict(name="row of three, impulse k = 0.5", count=3, dy=0.0, law="impulse", k=0.5),
    dict(name="row of three, impulse k = 0", count=3, dy=0.0, law="impulse", k=0.0),
    dict(name="two, B +1 um, kelvin", count=2, dy=1e-6, law="kelvin", k=KELVIN_E),
    dict(name="two, B -1 um, kelvin", count=2, dy=-1e-6, law="kelvin", k=KELVIN_E),
    dict(name="two, B +1 um, impulse k = 0.5", count=2, dy=1e-6, law="impulse", k=0.5),
    dict(name="two, B -1 um, impulse k = 0.5", count=2, dy=-1e-6, law="impulse", k=0.5),
    dict(name="two, B +1 um, impulse k = 0", count=2, dy=1e-6, law="impulse", k=0.0),
    dict(name="two, B -1 um, impulse k = 0", count=2, dy=-1e-6, law="impulse", k=0.0),
]


def summarise(case, peer):
    ev = peer_events(peer)
    holds = len(peer.holds)
    held_handovers = sum(len(h["handovers"]) for h in peer.holds)
    text = (f"peer, {case['name']}: {len(ev)} {'contacts' if case['law'] == 'kelvin' else 'impacts'} ("
            + ", ".join(f"{sum(1 for e in ev if {e['striking'], e['struck']} == {p[0] + 1, p[1] + 1})}"
                        f" {peer.names[p[0]]}:{peer.names[p[1]]}" for p in peer.pairs)
            + f"; {sum(e['side'] for e in ev)} on side edges), {len(peer.handovers)} corner hand-overs"
            + (f" ({', '.join(sorted(set(h['how'] for h in peer.handovers)))})" if peer.handovers else "")
            + (f", {holds} holds ({held_handovers} handed over)" if case["law"] == "impulse" else "")
            + f"; approach speeds {min(e['approach'] for e in ev):.3f} to {max(e['approach'] for e in ev):.3f} m/s; "
            + (f"deepest contact {peer.deepest_contact * 1e3:.2f} mm; " if case["law"] == "kelvin" else
               f"deepest vertex inside the other slab {peer.deepest:.1e} m; ")
            + f"{peer.passed_beside} crossings beside an edge, {len(peer.covered_crossings)} covered, "
            + f"{peer.late_roots} roots found past their zero; energy residual "
            + f"{peer.energy['residual'] / peer.energy['input']:.1e} of the input")
    print(text)
    return ev


def check_peer_case(case, peer, failures, out):
    """What the scene is for, and the peer's own consistency."""
    ev = summarise(case, peer)
    line(out, f"peer, {case['name']}: energy balance (relative to the input)",
         abs(peer.energy["residual"]) / peer.energy["input"], 1e-9, failures)
    bad = []
    if len(ev) < 5:
        bad.append(f"only {len(ev)} contacts")
    if peer.touches or peer.tensile_handovers:
        bad.append(f"touches {peer.touches}, hand-overs to a pulling twin {peer.tensile_handovers}")
    if case["law"] == "impulse" and (peer.unexplained or peer.deepest > 1e-12):
        bad.append(f"overlaps no rule explains: deepest {peer.deepest:.1e} m, {peer.unexplained[:3]}")
    if case["law"] == "kelvin" and not 5e-4 <= peer.deepest_contact <= 1.5e-2:
        bad.append(f"deepest contact {peer.deepest_contact:.2e} m, not about 1 to 10 mm")
    if any(e["side"] for e in ev):
        bad.append("contacts on side edges")
    if case["name"] in ("two, kelvin", "two, impulse k = 0", "row of three, kelvin") and not peer.handovers:
        bad.append("no corner hand-over")
    if case["name"] == "two, impulse k = 0" and not any(h["handovers"] for h in peer.holds):
        bad.append("no hold handed over")
    if bad:
        fail(failures, out, f"peer, {case['name']}: the scene no longer does what it was chosen for: " + "; ".join(bad))


def check_convergence(case, peer, times, accel, failures, out):
    """The peer at rtol 1e-13, atol 1e-15 against itself at 1e-12, 1e-14."""
    fine = Peer(peer.specs, case["law"], case["k"], rtol=1e-13, atol=1e-15).run(times, accel)
    a, b = peer_events(peer), peer_events(fine)
    same = len(a) == len(b) and all(x[f] == y[f] for x, y in zip(a, b) for f in ("striking", "vertex", "edge", "holds"))
    if not same or len(peer.handovers) != len(fine.handovers):
        fail(failures, out, f"peer, {case['name']}: at rtol 1e-13 {len(b)} contacts and {len(fine.handovers)} "
             f"hand-overs, at 1e-12 {len(a)} and {len(peer.handovers)}")
        return
    dt = max(abs(x["t"] - y["t"]) for x, y in zip(a, b))
    di = max(max(abs(x["impulse"] / y["impulse"] - 1), abs(x["approach"] / y["approach"] - 1)) for x, y in zip(a, b))
    line(out, f"peer, {case['name']}: rtol 1e-12 against 1e-13: instants (s)", dt, 1e-10, failures)
    line(out, f"peer, {case['name']}: rtol 1e-12 against 1e-13: impulses, approach speeds (relative)", di, 1e-8,
         failures)


def check_discrimination(case, peer, times, accel, failures, out):
    """What the comparison would see if the program lacked the hand-over (rule 3): the peer without
    it, its contacts matched to the full peer's by onset; the largest relative change of an impulse."""
    bare = Peer(peer.specs, case["law"], case["k"], handovers=False).run(times, accel)
    a, b = peer_events(peer), peer_events(bare)
    worst, unmatched = 0.0, 0
    for x in a:
        near = [y for y in b if (y["striking"], y["vertex"], y["edge"]) == (x["striking"], x["vertex"], x["edge"])
                and abs(y["t"] - x["t"]) < 1e-3]
        if near:
            worst = max(worst, abs(near[0]["impulse"] / x["impulse"] - 1.0))
        else:
            unmatched += 1
    msg = (f"peer, {case['name']}, without hand-overs: {len(b)} contacts (with: {len(a)}, {unmatched} of them without "
           f"a match); the largest change of a matched contact's impulse {worst:.1%}, "
           f"{worst / LIMITS['impulse']:.0e} times the impulses' limit")
    if worst > 0.01:
        out.append("  ok " + msg)
        print(out[-1])
    else:
        fail(failures, out, msg + ": the comparison would not tell a missing hand-over")


def main():
    started = time.time()
    program = sys.argv[1]
    out_dir = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    out_dir.mkdir(parents=True, exist_ok=True)
    only = sys.argv[3:]  # case names to run (all by default)
    times, accel = record()
    failures, out = [], []
    check_kinematics(failures, out)
    check_modes(program, out_dir / "modes", street(3), failures, out)
    for case in CASES:
        if only and case["name"] not in only:
            continue
        peer = Peer(street(case["count"], case["dy"]), case["law"], case["k"]).run(times, accel)
        check_peer_case(case, peer, failures, out)
        if case["name"] in ("two, kelvin", "two, impulse k = 0"):
            check_convergence(case, peer, times, accel, failures, out)
        if case["name"] == "two, kelvin":
            check_discrimination(case, peer, times, accel, failures, out)
        for method in METHODS:
            folder = out_dir / (case["name"].replace(", ", "-").replace(" ", "_").replace("=", "") + "-" + method)
            compare(program, folder, case, peer, method, failures, out)
    print()
    runs = sorted({name for name in REPRODUCE if any(f.startswith(name + ":") for f in failures)})
    if runs:
        print("To reproduce the failing program runs (the scene and record are in each folder):")
        for name in runs:
            print(f"  {name}: {REPRODUCE[name]}")
    program_run.finish(failures, started, width=400)


if __name__ == "__main__":
    main()
