#!/usr/bin/python3
"""Columns at a slab corner, facades in line (docs/model.md §5a for column points), against an independent computation.

    /usr/bin/python3 tests/solvers/test_column_corner_scipy.py POUNDING OUT_DIR

Exit 0 when every comparison is within its limit, 1 otherwise; one line per check ("ok ..." or
"FAIL ..."), with its measured value and its limit. The scene and its record are written into
OUT_DIR/<method>/ (scene.toml, pulse.txt), the program's outputs into OUT_DIR/<method>/run/.

Why the facades lean. A column point that slides off the end of the slab edge it presses is handed
to the next edge round that corner only if it overlaps that edge (§5a, rule 2). Past a right-angled
corner it never does: at the edge root the point lies 1e-9 of the edge beyond the corner, on the
line of the side edge and outside it (g = +1e-9 L), so with rectangular slabs in line a column
contact can only end at the corner. Past an obtuse corner of angle pi - theta the point is still
inside, the depth falls from delta to delta cos(theta). So the facing facades here are parallel
and lean, and the side facades stand in line.

The scene. B1: one storey of 4.5 m, slab the trapezoid (-10, 0), (0, 0), (4, 8), (-10, 8), CM
(-4, 4.8), 300 t, "uniform" J; nine 0.40 m square columns at (-10, 0), (-10, 4), (-10, 8), (-5, 0),
(-3, 4), (-1, 8), (0, 0), (2, 4), (4, 8). B2: two storeys of 3 m, slab the parallelogram (0.02, 0),
(8.02, 0), (12.02, 8), (4.02, 8) (B1's facade moved by the gap, 0.02 m along x), CM (6.32, 3.0),
250 t a floor; nine 0.35 m square columns at (0.02 + dx + 4 f, 8 f), dx in {0, 4, 8}, f in {0, 1/2,
1}. E 3e7 kPa, frame factor 1, 5 % Rayleigh damping at modes 1 and 3. Both slabs span y in [0, 8]:
their side facades y = 0 and y = 8 stand in line; B1's corner (0, 0) and B2's (4.02, 8) are obtuse
(116.6 degrees), B1's (4, 8) and B2's (0.02, 0) acute. No floors share an elevation: B1's slab
(4.5 m) meets B2's storey-2 columns at xi = 1/2, B2's floor 1 (3 m) meets B1's storey-1 columns at
xi = 2/3, B2's floor 2 stands above B1's roof. Ground: 3 m/s2 sin(2 pi t / 0.45 s) for three
periods, then nothing, sampled every 0.005 s to 3 s, along 30 degrees; the eccentric masses turn
the slabs, and the column points slide along the facades while they press. Kelvin, k = 93 500
kN/m, restitution 0.6 (square columns: the local flexibility in series, which a handed-over contact
keeps with the law's other constants, is the same along every normal). Candidates (10, by the rules
written out): the column points (0.02, 0), (2.02, 4), (4.02, 8) against B1's facing edge 2, and
(0, 0), (2, 4), (4, 8) against B2's facing edge 4; the corner candidates (0.02, 0) against B1's side
edge 1 (y = 0), (4.02, 8) against B1's edge 3 (y = 8), (0, 0) against B2's edge 1, (4, 8) against
B2's edge 3.

The peer assembles its own K (columns about the CM, block-tridiagonal), J (the slab's second moments
about its centroid), Rayleigh C, candidates, exact finite-rotation gaps of the column point
N1 p_j + N2 p_j+1 (the fixed-fixed cubic), gap rows G and the kelvin law with the column's local
flexibility a^3 b^3 / (3 E I L^3) in series, and integrates the 9 DOF with DOP853 at rtol 1e-12,
atol 1e-14 over each record interval, every switch a terminal event of solve_ivp, restarted there in
the new contact state. The rules, from docs/model.md §4, §5a, §6a and §6b:
  - onset where g falls through 0 with the point on its edge (within 1e-9 of it), approaching, and
    no other contact in progress at that point; W = G M^-1 G^T, c = 2 xi sqrt(k_s / W) at onset;
    released where F = k_s delta + c delta' turns tensile, pushing again where it would push, over
    where the gap opens; a facing candidate whose point crosses its line beside the edge is watched
    again once g > 1e-10;
  - a corner candidate is dormant (no onset) while its point lies beside its edge, or over it but
    behind it beyond the touch band (1e-8 m): it arms when its point projects onto its edge from in
    front. Its edge is taken 1e-6 m short of either end (include/pounding/contact/gap.hpp,
    kCornerEdgeInset_m; §5a does not say so, and without it this scene's impulses and durations
    move by 1.2e-3, onsets by 1.4e-6 s);
  - one contact at a point: a contact in progress covers the column point's other candidates on
    that slab;
  - round a corner: where the point of an acting contact leaves its edge (s = -1e-9 or 1 + 1e-9),
    the same point against the slab's edge that meets it at that end carries the contact on if it
    overlaps that edge and projects on it within 2 (|g| + 1e-8) / L + 1e-9, with the contact's
    record, k_s and c; else the contact ends there. A column point has no twin. The element cannot
    pull (§6a): a contact handed onto an edge where its force is tensile (here the depth falls to
    delta sin 26.6 degrees while the point moves off that edge's line) is released at once and goes
    on without force until its gap opens, as test_street_scipy.py's peer releases a twin that pulls;
  - each contact is one record: onset, approach speed and edge where it began, its duration (to its
    last release), the impulse of its force over every candidate it used, its peak force (bounded
    Brent on the dense output).
The scene then gives (peer): 18 contacts, 12 of B1's slab on B2's columns and 6 of B2's slab on
B1's; 3 begin on a corner candidate (B1's column 7 at (0, 0), having passed beside the end of B2's
facing edge, strikes B2's side edge y = 0 from below); 4 are handed round a corner, all B2's column 1 at (0.02, 0)
off B1's facing edge past the obtuse corner (0, 0) onto B1's side edge y = 0 (a corner candidate),
the force just after 96.1, 179.1, 21.8 and -38.4 kN: the last pulls and is released there (at
2.358811011 s, in the contact begun at 2.358164386 s); 3 of the 4 corner candidates arm; approach
speeds 0.07 to 0.60 m/s, overlaps up to 13 mm; no touch, no column point inside a slab without a
contact in progress at it.

Checked (limits; measured with the program of 2026-12-01 in parentheses, cvode-bdf / arkode-erk):
  1. the peer alone: its gap row against central differences of its gap at rotations of 0.02 rad,
     1e-8 (1.0e-9); the program's periods (pounding modes) are the peer's, 1e-9 (7.8e-16); its
     energy balance closes, 1e-11 of the input (9.4e-14); at rtol 1e-13, atol 1e-15 the same
     contacts and hand-overs, instants within 1e-10 s (2.1e-13), approach speeds, impulses and peaks
     1e-8 (5.5e-11); the scene does what it is for (a hand-over that pushes on, a corner candidate
     armed and a contact begun on one, no touch, no point coming onto an edge already inside, none
     inside a slab without a contact, no released contact pushing again); and without the hand-over
     (each contact ended at its edge's end) a matched contact's impulse changes by up to 98 % (must
     exceed 1 %), and column points are left inside B1's slab with no contact there.
  2. the program (cvode-bdf and arkode-erk, --rtol 1e-12 --atol 1e-14) against the peer: completed;
     summary.json's candidates are the peer's (column point as vertex, the column's building as
     striking_building, the slab's edge, corner or not, column, storey, height ratio, local
     flexibility); its impacts one to one with the peer's contacts in onset order, with level 0,
     vertex 0, the slab's building striking and the column's struck, the column, its point
     (vertex_rest), floors_b1/b2 and struck_edge the slab edge where the contact began (a handed-over
     contact is one impact named by its first candidate), and within
       onset                        1e-9 s  (6.3e-11 / 2.6e-13)
       duration                     1e-9 s  (8.5e-11 / 6.4e-13)
       approach speed               3e-8    (2.4e-9 / 1.7e-11)
       impulse, whole contact       3e-7    (2.4e-8 / 1.7e-10)
       peak force                   5e-6    (1.8e-7 / 5.2e-7: the program takes it from 17 samples a step)
       hand-over instant            1e-9 s  (3.6e-11 / 3.8e-14), the row of contacts_history.csv at
                                            the instant naming the candidate that took the contact over,
       its force just after         2e-7    (1.3e-8 / 3.4e-11)
       u, v of the three floors     3e-10 m (2.9e-11 / 3.9e-14) at every history row
       phi                          3e-11 rad (2.9e-12 / 1.3e-14)
       impact loss vs contact work  2e-8    (1.5e-9 / 3.0e-12)
       energy audit residual        4e-9    (3.8e-10 / 5.0e-13)
     (relative for speeds, impulses, forces and the loss), each about ten times the larger measured
     value; statistics.corner_candidates, corner_candidates_armed and corner_handovers equal to the
     peer's (4, 3, 4); and no tensile force in contacts_history.csv (a kelvin element cannot pull).
     A contact outside a limit ends the comparison there: the FAIL line gives both records, and the
     histories are compared up to its onset.

Finding (2026-12-01): the program keeps pulling after a hand-over onto an edge where the force is
tensile. At 2.358811011 s B2's column 1 (0.02, 0) slides off B1's edge 2 past the corner (0, 0) onto
B1's side edge 1 with F = -38.4 kN there; CompliantEvents::hand_over (src/solvers/compliant_events.cpp)
starts the new candidate acting without looking at the law's switch, whose witness then starts
below zero and never falls through it, so the element pulls (-38.4 kN there, -43.0 kN at the next
history row) for 2.06 ms until the gap opens: that impact's duration is 0.002707 s against the
peer's 0.000647 s, its impulse 0.133540 kN s against 0.220896, and everything after it moves. The
first 12 contacts (3 of them handed over) agree within the limits above; against a peer that keeps
pulling as the program does, all 18 agree on both methods, which the test prints as a diagnosis
when it fails (the values measured above are the larger of the two comparisons: the first 12
contacts against this peer, all 18 against that one). The remedy this test expects: a contact
handed onto an edge where the law's force is tensile released at once (as a force root releases
it), its duration ending there.

Not told apart by this scene: the covering rule (no crossing that it would stop happens; a peer
without it finds the same contacts) and dormancy in the contacts (a peer whose corner candidates
are always armed finds them within 2e-11); dormancy shows in corner_candidates_armed (3 of 4, where
armed from the start all 4 would count). Run time about 25 s (five peer runs of about 4.5 s each,
one of them only after a failure).
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

# --- the scene ------------------------------------------------------------------------------------
ZETA, RESTITUTION, KELVIN_K, E_KPA = 0.05, 0.6, 93500.0, 3.0e7
GAP_M = 0.02  # the clear gap along x between the facing facades
SLANT_M = 4.0  # the facing facades run from y = 0 to y = 8 m and lean SLANT_M along +x
MARGIN_M = 1.0  # candidate_margin_m (default): the candidates' reach
LEVEL_TOL_M = 1e-3  # level_tolerance_m (default)
ON_EDGE = 1e-9  # a point is on its edge within this fraction of the edge's length
CORNER_INSET_M = 1e-6  # a corner candidate's edge is taken this much short of either end
CLOSED_M = 1e-8  # contact_tolerance_m: the touch band of the corner rules
REOPEN_M = 1e-10  # a gap that has just been handled is watched again once it opens beyond this
# The ground pulse: PULSE_MPS2 sin(2 pi t / PULSE_PERIOD_S) for PULSE_CYCLES periods, then nothing,
# sampled every DT_S up to DURATION_S, along BETA_DEG.
PULSE_MPS2, PULSE_PERIOD_S, PULSE_CYCLES, DT_S, DURATION_S, BETA_DEG = 3.0, 0.45, 3, 0.005, 3.0, 30.0


def buildings(slant=SLANT_M, gap=GAP_M):
    """B1: one storey of 4.5 m, a trapezoid x from -10 m to its facade (0, 0)-(slant, 8); B2: two
    storeys of 3 m, a parallelogram whose facade (gap, 0)-(gap + slant, 8) is B1's moved by gap
    along x. Both slabs span y in [0, 8]: their side facades stand in line. Square columns: at the
    corners and mid-points of the facades and along the back."""
    s, g = slant, gap
    b1 = dict(name="B1", heights=[4.5], slab=[(-10.0, 0.0), (0.0, 0.0), (s, 8.0), (-10.0, 8.0)], cm=(-4.0, 4.8),
              mass=[300.0], E=E_KPA, ff=1.0,
              columns=[(-10.0, 0.0), (-10.0, 4.0), (-10.0, 8.0), (-5.0, 0.0), (-5.0 + s / 2, 4.0), (-5.0 + s, 8.0),
                       (0.0, 0.0), (s / 2, 4.0), (s, 8.0)], section=(0.40, 0.40))
    b2 = dict(name="B2", heights=[3.0, 3.0], slab=[(g, 0.0), (g + 8.0, 0.0), (g + 8.0 + s, 8.0), (g + s, 8.0)],
              cm=(g + 4.0 + s / 2 + 0.3, 3.0), mass=[250.0, 250.0], E=E_KPA, ff=1.0,
              columns=[(g + dx + f * s, 8.0 * f) for dx in (0.0, 4.0, 8.0) for f in (0.0, 0.5, 1.0)],
              section=(0.35, 0.35))
    return [b1, b2]


def record(amplitude=PULSE_MPS2):
    t = np.arange(round(DURATION_S / DT_S) + 1) * DT_S
    a = np.where(t < PULSE_CYCLES * PULSE_PERIOD_S - DT_S / 2,
                 amplitude * np.sin(2 * np.pi * t / PULSE_PERIOD_S), 0.0)
    return t, a


def scene_text(specs, record_path):
    parts = ['name = "column-corner-peer"\n']
    for b in specs:
        slab = ", ".join(f"[{x!r}, {y!r}]" for x, y in b["slab"])
        cols = ", ".join(f"[{x!r}, {y!r}, {b['section'][0]!r}, {b['section'][1]!r}]" for x, y in b["columns"])
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
frame_factor = {b['ff']!r}
columns = [{cols}]
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

[contact]
gap_m = {GAP_M!r}
restitution = {RESTITUTION!r}
law = "kelvin"
stiffness_kN_per_m = {KELVIN_K!r}

[solver]
method = "cvode-bdf"
rtol = 1e-12
atol = 1e-14

[output.floor_history]
B1 = [1]
B2 = [1, 2]
""")
    return "".join(parts)


# --- the peer's model -----------------------------------------------------------------------------
def rot(phi):
    c, s = math.cos(phi), math.sin(phi)
    return np.array([[c, -s], [s, c]])


def polygon_moments(pts):
    """Area, centroid and the second moments about the centroid (I_xx = int y^2, I_yy = int x^2) of
    a counter-clockwise polygon."""
    A = cx = cy = ixx = iyy = 0.0
    for (x0, y0), (x1, y1) in zip(pts, pts[1:] + pts[:1]):
        w = x0 * y1 - x1 * y0
        A += w / 2
        cx += (x0 + x1) * w / 6
        cy += (y0 + y1) * w / 6
        ixx += (y0 * y0 + y0 * y1 + y1 * y1) * w / 12
        iyy += (x0 * x0 + x0 * x1 + x1 * x1) * w / 12
    cx, cy = cx / A, cy / A
    return A, (cx, cy), ixx - A * cy * cy, iyy - A * cx * cx


class Building:
    """Its own K (columns about the CM, block-tridiagonal), diag(m, m, J) with J "uniform" (the
    floor mass spread over the slab, about the slab's centroid) and Rayleigh C (modes 1 and 3)."""

    def __init__(self, spec):
        self.name, self.heights = spec["name"], np.array(spec["heights"])
        self.E, self.ff, self.n = spec["E"], spec["ff"], len(spec["heights"])
        self.z = np.concatenate([[0.0], np.cumsum(self.heights)])  # z[0] the ground, z[k] floor k
        self.slab = [np.array(p, dtype=float) for p in spec["slab"]]
        self.cm = np.array(spec["cm"], dtype=float)
        area, _, ixx, iyy = polygon_moments([tuple(p) for p in spec["slab"]])
        self.mass = np.array(spec["mass"], dtype=float)
        self.J = self.mass * (ixx + iyy) / area
        self.columns = [(np.array(c, dtype=float), spec["section"]) for c in spec["columns"]]
        n3 = 3 * self.n
        self.K = np.zeros((n3, n3))
        for s in range(self.n):
            ks = np.zeros((3, 3))
            for c, (bs, hs) in self.columns:
                kx = self.ff * 12.0 * self.E * (hs * bs ** 3 / 12.0) / self.heights[s] ** 3
                ky = self.ff * 12.0 * self.E * (bs * hs ** 3 / 12.0) / self.heights[s] ** 3
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
        self.omega = np.sqrt(np.sort(eigh(self.K, np.diag(self.m_diag), eigvals_only=True)))
        w1, w3 = self.omega[0], self.omega[2]
        a0, a1 = 2 * ZETA * w1 * w3 / (w1 + w3), 2 * ZETA / (w1 + w3)
        self.C = a0 * np.diag(self.m_diag) + a1 * self.K

    def edges(self):
        """(Q1, Q2, unit tangent, outward normal, length) of every slab edge, in outline order."""
        out = []
        for k in range(len(self.slab)):
            q1, q2 = self.slab[k], self.slab[(k + 1) % len(self.slab)]
            length = float(np.linalg.norm(q2 - q1))
            t = (q2 - q1) / length
            out.append((q1, q2, t, np.array([t[1], -t[0]]), length))
        return out

    def faces(self, edge, other):
        """Whether the edge's outward normal has a vertex of the other slab in front of it."""
        q1, _, _, n, _ = edge
        return any(np.dot(v - q1, n) > 0.0 for v in other.slab)


class Candidate:
    """A column point X of building B (its column `column`, storey j + 1 at height ratio xi) against
    edge `edge_index` (Q1 -> Q2) of floor f of building A's slab; a corner candidate if it is not a
    facing one."""

    def __init__(self, A, f, B, j, xi, X, column, section, edge_index, edge, corner):
        self.A, self.f, self.B, self.j, self.xi, self.X = A, f, B, j, xi, X
        self.column, self.section, self.edge_index, self.corner = column, section, edge_index, corner
        self.q1, self.q2, self.t_rest, self.n_rest, self.length = edge
        self.N = (1.0 - 3 * xi ** 2 + 2 * xi ** 3, 3 * xi ** 2 - 2 * xi ** 3)

    def key(self):
        """What names its contact point: the slab's floor, the column building and its point."""
        return (self.A, self.f, self.B, round(self.X[0], 9), round(self.X[1], 9))

    def label(self, names):
        kind = "corner " if self.corner else ""
        return (f"{names[self.B]} column {self.column + 1} ({round(self.X[0], 9) + 0.0:g}, "
                f"{round(self.X[1], 9) + 0.0:g}) -> {names[self.A]} "
                f"{kind}edge {self.edge_index + 1}")


def segment_distance(p, q1, q2):
    d = q2 - q1
    s = min(max(np.dot(p - q1, d) / np.dot(d, d), 0.0), 1.0)
    return float(np.linalg.norm(p - (q1 + s * d)))


def find_candidates(bs):
    """docs/model.md §4 and §6b written out: a floor of A between two floors of B (below B's roof)
    meets the columns of B on B's facade facing A (centre within half its larger side of a facing
    edge, projecting onto it; its point the projection, once per edge); each point against each
    edge of A's slab that faces B's slab, in front within gap + margin and projecting onto it or at
    most the margin beyond an end (facing), and against every other edge of A's slab within gap +
    margin of it (corner)."""
    cands = []
    for a in (0, 1):
        A, B = bs[a], bs[1 - a]
        for f in range(1, A.n + 1):
            z = A.z[f]
            if np.any(np.abs(B.z[1:] - z) <= LEVEL_TOL_M):
                continue  # a level: slab to slab (none here)
            below = [k for k in range(B.n) if B.z[k] < z < B.z[k + 1]]
            if not below:
                continue  # above B's roof
            j = below[0]
            xi = (z - B.z[j]) / B.heights[j]
            points = []  # (X, column, section)
            for k, (c, section) in enumerate(B.columns):
                own = []
                for edge in B.edges():
                    e1, _, tb, nb, lb = edge
                    if not B.faces(edge, A):
                        continue
                    if abs(np.dot(c - e1, nb)) > max(section) / 2:
                        continue
                    s = np.dot(c - e1, tb)
                    if s < 0 or s > lb:
                        continue
                    X = e1 + s * tb
                    if not any(np.linalg.norm(X - p) <= 1e-9 for p in own):
                        own.append(X)
                points += [(X, k, section) for X in own]
            facing = []
            for e, edge in enumerate(A.edges()):
                q1, q2, t, n, length = edge
                if not A.faces(edge, B):
                    continue
                for p, (X, k, section) in enumerate(points):
                    d, s = np.dot(X - q1, n), np.dot(X - q1, t)
                    if -1e-9 <= d <= GAP_M + MARGIN_M and -MARGIN_M <= s <= length + MARGIN_M:
                        cands.append(Candidate(a, f, 1 - a, j, xi, X, k, section, e, edge, False))
                        facing.append((e, p))
            for e, edge in enumerate(A.edges()):
                for p, (X, k, section) in enumerate(points):
                    if (e, p) not in facing and segment_distance(X, edge[0], edge[1]) <= GAP_M + MARGIN_M:
                        cands.append(Candidate(a, f, 1 - a, j, xi, X, k, section, e, edge, True))
    return cands


def depth_inside(outline, p):
    """How deep p lies inside the convex counter-clockwise outline: its distance to the nearest
    edge's line (0 outside or on it)."""
    depth = math.inf
    for k in range(len(outline)):
        q1, q2 = outline[k], outline[(k + 1) % len(outline)]
        t = (q2 - q1) / np.linalg.norm(q2 - q1)
        inward = -((p[0] - q1[0]) * t[1] - (p[1] - q1[1]) * t[0])
        if inward <= 0.0:
            return 0.0
        depth = min(depth, inward)
    return depth


class Peer:
    """B1's floor and B2's two floors (9 DOF, q relative to the ground) with kelvin contacts at the
    column points, integrated with DOP853 over each record interval; every switch a terminal event
    of solve_ivp, the integration restarted there in the new contact state.

    A candidate's mode: "armed" (open: its gap's fall through zero with the point on its edge is an
    onset, unless a contact in progress covers it), a corner candidate's dormant "beside" (its point
    beside its edge: armed when it comes over it in front of the edge) and "behind" (over its edge,
    behind it beyond the touch band: armed when it comes in front), "masked" (just handled, or its
    point crossed a facing edge's line beside the edge: watched again once g > REOPEN_M), "acting" /
    "released" (a contact in progress whose force acts, or has turned tensile while the gap is
    still closed).

    Variants, to see what the comparison tells apart: handovers=False ends a contact at its edge's
    end, corners=False drops the corner candidates, covering=False lets a point start a second
    contact, dormancy=False arms corner candidates everywhere, inset=0 takes corner candidates'
    edges whole, pull=True lets a contact handed onto a pulling edge pull (as the program does)."""

    def __init__(self, specs, method="DOP853", rtol=1e-12, atol=1e-14, handovers=True, corners=True, pull=False,
                 covering=True, dormancy=True, inset=CORNER_INSET_M):
        self.specs, self.allow_handovers, self.pull = specs, handovers, pull
        self.covering, self.dormancy, self.inset = covering, dormancy, inset
        self.b = [Building(s) for s in specs]
        self.names = [b.name for b in self.b]
        self.off = [0, 3 * self.b[0].n]
        self.n = 3 * (self.b[0].n + self.b[1].n)
        self.m_diag = np.concatenate([b.m_diag for b in self.b])
        self.K = np.zeros((self.n, self.n))
        self.C = np.zeros((self.n, self.n))
        for b, o in zip(self.b, self.off):
            k = 3 * b.n
            self.K[o:o + k, o:o + k], self.C[o:o + k, o:o + k] = b.K, b.C
        beta = math.radians(BETA_DEG)
        self.r = np.tile([math.cos(beta), math.sin(beta), 0.0], self.n // 3)
        self.mr = self.m_diag * self.r
        self.method, self.rtol, self.atol = method, rtol, atol
        self.cands = [c for c in find_candidates(self.b) if corners or not c.corner]
        self.xi = -math.log(RESTITUTION) / math.sqrt(math.pi ** 2 + math.log(RESTITUTION) ** 2)
        for c in self.cands:
            B = self.b[c.B]
            L = B.heights[c.j]
            a_, b_ = c.xi * L, L - c.xi * L
            bs, hs = c.section
            Ix, Iy = hs * bs ** 3 / 12.0, bs * hs ** 3 / 12.0
            c.flex = a_ ** 3 * b_ ** 3 / (3.0 * B.E * L ** 3) * (c.n_rest[0] ** 2 / Ix + c.n_rest[1] ** 2 / Iy)
            c.cm_a, c.cm_b = self.b[c.A].cm, B.cm
            c.sigma, c.rho = c.q1 - c.cm_a, c.X - c.cm_b  # Q1 from A's CM, X from B's, at rest
        self.groups = {}
        for i, c in enumerate(self.cands):
            self.groups.setdefault(c.key(), []).append(i)
        # Round a corner: per candidate and end of its edge (0: Q1, 1: Q2), the same point against
        # the slab's edge that meets its edge there. (A column point has no twin.)
        self.next = []
        for c in self.cands:
            size = len(self.b[c.A].slab)
            ends = [None, None]
            for end, other in ((0, (c.edge_index - 1) % size), (1, (c.edge_index + 1) % size)):
                for j in self.groups[c.key()]:
                    if self.cands[j].edge_index == other:
                        ends[end] = j
            self.next.append(ends)
        nc = len(self.cands)
        self.mode = ["armed"] * nc
        self.contact = [None] * nc
        self.contacts, self.handovers = [], []
        self.n_aug = 3 + nc  # input, damping, contact work; the impulse per candidate

    # --- kinematics ---------------------------------------------------------------------------
    def kin(self, i, y, row=False):
        """g, g', the gap row G over q (row=True; else None), P (now) and the projection parameter
        s of P on the edge (a corner candidate's: on its edge less CORNER_INSET_M at either end)."""
        c, n = self.cands[i], self.n
        oa = self.off[c.A] + 3 * (c.f - 1)
        ua, va, pa = y[oa], y[oa + 1], y[oa + 2]
        wa_u, wa_v, wa = y[n + oa], y[n + oa + 1], y[n + oa + 2]
        ca, sa = math.cos(pa), math.sin(pa)
        nx, ny = ca * c.n_rest[0] - sa * c.n_rest[1], sa * c.n_rest[0] + ca * c.n_rest[1]
        tx, ty = -ny, nx
        cax, cay = c.cm_a[0] + ua, c.cm_a[1] + va
        sx, sy = ca * c.sigma[0] - sa * c.sigma[1], sa * c.sigma[0] + ca * c.sigma[1]  # Q1 from A's CM
        px = py = vx = vy = 0.0
        arms = []
        for N, k in zip(c.N, (c.j, c.j + 1)):
            if k == 0:  # the ground: the point at rest
                px, py = px + N * c.X[0], py + N * c.X[1]
                continue
            o = self.off[c.B] + 3 * (k - 1)
            cb, sb = math.cos(y[o + 2]), math.sin(y[o + 2])
            rx, ry = cb * c.rho[0] - sb * c.rho[1], sb * c.rho[0] + cb * c.rho[1]
            px += N * (c.cm_b[0] + y[o] + rx)
            py += N * (c.cm_b[1] + y[o + 1] + ry)
            w = y[n + o + 2]
            vx += N * (y[n + o] - w * ry)
            vy += N * (y[n + o + 1] + w * rx)
            arms.append((N, o, rx, ry))
        dx, dy = px - (cax + sx), py - (cay + sy)
        g = dx * nx + dy * ny
        along = dx * tx + dy * ty
        ddx, ddy = vx - (wa_u - wa * sy), vy - (wa_v + wa * sx)
        gd = ddx * nx + ddy * ny + wa * (dx * -ny + dy * nx)
        s = (along - self.inset) / (c.length - 2 * self.inset) if c.corner else along / c.length
        G = None
        if row:
            G = np.zeros(n)
            for N, o, rx, ry in arms:
                G[o:o + 3] += (N * nx, N * ny, N * (rx * ny - ry * nx))
            G[oa:oa + 3] -= (nx, ny, (px - cax) * ny - (py - cay) * nx)
        return g, gd, G, (px, py), s

    def gap(self, i, y):
        return self.kin(i, y)[0]

    def outline_now(self, b, f, q):
        B = self.b[b]
        o = self.off[b] + 3 * (f - 1)
        qf = q[o:o + 3]
        R = rot(qf[2])
        return [B.cm + qf[:2] + R @ (p - B.cm) for p in B.slab]

    def in_progress(self, i):
        return self.mode[i] in ("acting", "released")

    def covered(self, i):
        """One contact at a point: a contact in progress covers its point's other candidates."""
        return self.covering and any(self.in_progress(j) for j in self.groups[self.cands[i].key()] if j != i)

    # --- forces -------------------------------------------------------------------------------
    def kelvin(self, i, g, gd):
        rec = self.contact[i]
        return rec["k"] * (-g) + rec["c"] * (-gd)

    @property
    def acting(self):
        return [i for i, m in enumerate(self.mode) if m == "acting"]

    def rhs(self, t, y):
        n = self.n
        q, qd = y[:n], y[n:2 * n]
        a = self.ag(t)
        gen = np.zeros(n)
        aug = np.zeros(self.n_aug)
        for i in self.acting:
            g, gd, G, _, _ = self.kin(i, y, row=True)
            F = self.kelvin(i, g, gd)
            gen += F * G
            aug[2] += -F * gd
            aug[3 + i] = F
        qdd = (-self.K @ q - self.C @ qd + gen) / self.m_diag - self.r * a
        aug[0] = -qd @ self.mr * a
        aug[1] = qd @ self.C @ qd
        return np.concatenate([qd, qdd, aug])

    # --- events -------------------------------------------------------------------------------
    def event_functions(self, y):
        fs, tags = [], []

        def add(f, direction, tag):
            f.terminal, f.direction = True, direction
            fs.append(f)
            tags.append(tag)
        for i, c in enumerate(self.cands):
            m = self.mode[i]
            if m == "armed":
                if not self.covered(i):
                    add(lambda t, y, i=i: self.gap(i, y), -1, ("onset", i))
                if c.corner and self.dormancy:  # dormant again once its point leaves its edge
                    add(lambda t, y, i=i: self.kin(i, y)[4] + ON_EDGE, -1, ("off edge", i))
                    add(lambda t, y, i=i: 1.0 + ON_EDGE - self.kin(i, y)[4], -1, ("off edge", i))
            elif m == "behind":  # over its edge, behind it: armed once in front (within the band)
                add(lambda t, y, i=i: self.gap(i, y) + CLOSED_M, 1, ("in front", i))
                add(lambda t, y, i=i: self.kin(i, y)[4] + ON_EDGE, -1, ("off edge", i))
                add(lambda t, y, i=i: 1.0 + ON_EDGE - self.kin(i, y)[4], -1, ("off edge", i))
            elif m == "beside":  # beside its edge: examined once its point comes over the edge
                add(lambda t, y, i=i: self.kin(i, y)[4] + ON_EDGE, 1, ("onto edge", i))
                add(lambda t, y, i=i: 1.0 + ON_EDGE - self.kin(i, y)[4], 1, ("onto edge", i))
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
        return fs, tags

    def open_mode(self, i, y):
        """An open candidate's mode: armed, or (a corner candidate) dormant, "beside" its edge or
        over it but "behind" it (beyond the touch band), unless its point lies over its edge in
        front of it."""
        if not self.cands[i].corner or not self.dormancy:
            return "armed"
        g, _, _, _, s = self.kin(i, y)
        return "beside" if not self.on_edge(s) else "armed" if g >= -CLOSED_M else "behind"

    def on_edge(self, s):
        return -ON_EDGE <= s <= 1.0 + ON_EDGE

    def successor(self, i, y):
        """Round a corner (docs/model.md §5a): the candidate that carries contact i on, its point
        having slid off its edge's end while it presses: the same point against the next edge at
        that end, if it lies on that edge (within twice the depth plus the touch band) and
        overlaps it."""
        g, _, _, _, s = self.kin(i, y)
        j = self.next[i][0 if s < 0.5 else 1]
        if j is None or self.in_progress(j):
            return None
        gj, _, _, _, sj = self.kin(j, y)
        slack = 2.0 * (abs(g) + CLOSED_M) / self.cands[j].length + ON_EDGE
        return j if gj < 0.0 and -slack <= sj <= 1.0 + slack else None

    def handle(self, t, y, tags):
        """The events at t (tags), in the order: edges, forces, gaps."""
        order = {"edge": 0, "release": 1, "acts again": 1, "opens": 2, "up": 2, "onset": 2, "off edge": 3,
                 "onto edge": 3, "in front": 3}
        for kind, i in sorted(set(tags), key=lambda tg: (order[tg[0]], tg[1])):
            if kind == "edge":
                if self.mode[i] != "acting":
                    continue
                j = self.successor(i, y) if self.allow_handovers else None
                if j is not None:
                    self.hand_over(t, y, i, j)
                else:
                    self.end_contact(t, y, i, "slid off its edge")
            elif kind == "release":
                if self.mode[i] == "acting":
                    self.mode[i] = "released"
                    self.contact[i]["release"] = t
            elif kind == "acts again":
                if self.mode[i] == "released" and self.gap(i, y) < 0.0:
                    self.mode[i] = "acting"
                    self.contact[i]["acts_again"] += 1
                    self.contact[i]["release"] = None
            elif kind == "opens":
                if self.in_progress(i):
                    self.end_contact(t, y, i, "gap opens")
            elif kind == "up":
                if self.mode[i] == "masked":
                    self.mode[i] = self.open_mode(i, y)
            elif kind == "off edge":
                if self.mode[i] in ("armed", "behind"):
                    self.mode[i] = "beside"
            elif kind == "in front":
                if self.mode[i] == "behind":
                    self.mode[i] = "armed"
            elif kind == "onto edge":
                if self.mode[i] != "beside":
                    continue
                g, _, _, P, _ = self.kin(i, y)
                if g >= -CLOSED_M:
                    self.mode[i] = "armed"
                    continue
                self.mode[i] = "behind"
                c = self.cands[i]
                if not self.covered(i) and depth_inside(self.outline_now(c.A, c.f, y[:self.n]), P) > 0.0:
                    # over its edge, already behind it and inside the slab: the program takes that
                    # as a contact at a step's end, an instant no root locates; the scene must not
                    self.arrivals.append((t, c.label(self.names), g))
            elif kind == "onset":
                if self.mode[i] != "armed":
                    continue
                g, gd, _, _, s = self.kin(i, y)
                c = self.cands[i]
                if not self.on_edge(s):
                    self.passed_beside += 1
                    self.mode[i] = "masked"
                elif self.covered(i):
                    self.covered_crossings.append((t, c.label(self.names)))
                elif gd >= 0.0:
                    self.touches.append((t, c.label(self.names)))
                    self.mode[i] = "masked"
                else:
                    self.begin_contact(t, y, i)

    def begin_contact(self, t, y, i):
        g, gd, G, P, s = self.kin(i, y, row=True)
        c = self.cands[i]
        W = float(np.sum(G * G / self.m_diag))
        k_s = 1.0 / (1.0 / KELVIN_K + c.flex)
        self.contact[i] = dict(cand=i, t_s=t, approach=-gd, W=W, k=k_s, c=2.0 * self.xi * math.sqrt(k_s / W),
                               impulse=0.0, base=y[2 * self.n + 3 + i], peak=0.0, acts_again=0, handovers=[],
                               release=None, path=[i])
        self.mode[i] = "acting"
        if c.corner:
            self.corner_onsets += 1

    def close_share(self, y, i):
        rec = self.contact[i]
        rec["impulse"] += y[2 * self.n + 3 + i] - rec["base"]

    def end_contact(self, t, y, i, reason):
        rec = self.contact[i]
        self.close_share(y, i)
        if self.mode[i] == "acting":
            rec["release"] = t
        rec["duration"] = rec["release"] - rec["t_s"]
        rec["end"], rec["reason"] = t, reason
        self.contacts.append(rec)
        self.contact[i] = None
        self.mode[i] = "masked"

    def hand_over(self, t, y, i, j):
        rec = self.contact[i]
        self.close_share(y, i)
        g_from, g_to = self.gap(i, y), self.gap(j, y)
        rec["base"] = y[2 * self.n + 3 + j]
        rec["handovers"].append((t, i, j))
        rec["path"].append(j)
        self.contact[j], self.contact[i] = rec, None
        self.mode[j], self.mode[i] = "acting", "masked"
        _, gdj, _, _, _ = self.kin(j, y)
        F_to = self.kelvin(j, g_to, gdj)
        self.handovers.append(dict(t=t, frm=i, to=j, g_from=g_from, g_to=g_to, force_to=F_to))
        if F_to < 0.0:  # the element cannot pull (docs/model.md §6a): released at once
            self.tensile_handovers.append((t, self.cands[j].label(self.names), F_to))
            if not self.pull:
                self.mode[j] = "released"
                rec["release"] = t

    # --- the run ------------------------------------------------------------------------------
    def run(self, times, accel):
        self.ag = lambda t: float(np.interp(t, times, accel))
        n = self.n
        y = np.zeros(2 * n + self.n_aug)
        self.segments = []
        self.passed_beside, self.corner_onsets = 0, 0
        self.touches, self.covered_crossings, self.tensile_handovers, self.arrivals = [], [], [], []
        self.mode = [self.open_mode(i, y) for i in range(len(self.cands))]
        self.unexplained = []  # a column point inside the slab with no contact in progress at it
        self.ever_live = set()  # corner candidates ever armed: open, uncovered, over their edge from in front
        self.events, self.late_roots = 0, 0
        self.deepest = 0.0
        for a, b in zip(times[:-1], times[1:]):
            t0 = a
            while b - t0 > 1e-13:
                funcs, tags = self.event_functions(y)
                y_start = y
                sol = solve_ivp(self.rhs, (t0, b), y, method=self.method, rtol=self.rtol, atol=self.atol,
                                events=funcs or None, dense_output=True)
                assert sol.status >= 0, sol.message
                t_end = sol.t[-1]
                self.track(sol, t0, t_end)
                self.segments.append((t0, t_end, sol.sol))
                y = sol.y[:, -1].copy()
                t0 = t_end
                if sol.status != 1:
                    continue
                hit = [k for k, te in enumerate(sol.t_events) if len(te)]
                first = min(sol.t_events[k][0] for k in hit)
                fired = [tags[k] for k in hit if sol.t_events[k][0] <= first + 1e-14]
                # solve_ivp reports the first terminal root of a step only: a function that
                # crossed as well is past its zero here.
                for k, f in enumerate(funcs):
                    if tags[k] not in fired and -f.direction * f(t0, y_start) > 0.0 >= -f.direction * f(t_end, y):
                        fired.append(tags[k])
                        self.late_roots += 1
                self.events += 1
                if self.events > 5000:
                    raise RuntimeError(f"peer: more than 5000 events by {t_end} s")
                self.handle(t_end, y, fired)
        self.y_end = y
        for i, m in enumerate(self.mode):
            if m in ("acting", "released"):
                self.end_contact(times[-1], y, i, "end of run")
        self.contacts.sort(key=lambda r: r["t_s"])
        q, qd = y[:n], y[n:2 * n]
        e = dict(input=y[2 * n], damping=y[2 * n + 1], kinetic=0.5 * qd @ (self.m_diag * qd),
                 strain=0.5 * q @ self.K @ q, contact=y[2 * n + 2])
        e["residual"] = e["input"] - e["kinetic"] - e["strain"] - e["damping"] - e["contact"]
        self.energy = e
        return self

    def track(self, sol, t0, t1):
        """On the dense output of [t0, t1]: each acting contact's largest force (bounded Brent near
        the largest of 9 samples); the corner candidates armed; a column point inside the other
        slab without a contact in progress there; the deepest overlap of a contact."""
        if t1 <= t0:
            return
        for i in self.acting:
            def force(t):
                g, gd = self.kin(i, sol.sol(t))[:2]
                return self.kelvin(i, g, gd)
            ts = np.linspace(t0, t1, 9)
            fs = [force(t) for t in ts]
            k = int(np.argmax(fs))
            res = minimize_scalar(lambda t: -force(t), bounds=(ts[max(k - 1, 0)], ts[min(k + 1, 8)]),
                                  method="bounded", options={"xatol": 1e-13})
            self.contact[i]["peak"] = max(self.contact[i]["peak"], fs[k], -res.fun)
        steps = np.concatenate([sol.t[sol.t < t1], [t1]])
        ts = np.unique(np.concatenate([np.linspace(p, q, 4, endpoint=False) for p, q in zip(steps[:-1], steps[1:])]
                                      + [[t1]]))
        ys = sol.sol(ts)
        for k in range(len(ts)):
            yk = ys[:, k]
            for i, c in enumerate(self.cands):
                if self.in_progress(i):
                    self.deepest = max(self.deepest, -self.gap(i, yk))
                    continue
                if c.corner and i not in self.ever_live and not self.covered(i):  # as the program sees it
                    g, _, _, _, s = self.kin(i, yk)
                    if self.on_edge(s) and g >= -CLOSED_M:
                        self.ever_live.add(i)
            for key, members in self.groups.items():
                if any(self.in_progress(i) for i in members):
                    continue
                c = self.cands[members[0]]
                P = self.kin(members[0], yk)[3]
                depth = depth_inside(self.outline_now(c.A, c.f, yk[:self.n]), P)
                if depth > 1e-7:
                    self.unexplained.append((ts[k], c.label(self.names), depth))

    def at(self, ts):
        starts = np.array([s[0] for s in self.segments])
        out = []
        for t in ts:
            k = max(int(np.searchsorted(starts, t, side="right")) - 1, 0)
            t0, t1, sol = self.segments[k]
            out.append(sol(min(max(t, t0), t1))[:self.n])
        return np.array(out)


def check_gap_row(failures):
    """The gap row G is the gradient of the gap, in a state with finite rotations (central
    differences of the gap itself)."""
    peer = Peer(buildings())
    rng = np.random.default_rng(7)
    y = np.zeros(2 * peer.n + peer.n_aug)
    y[:peer.n] = rng.normal(0.0, 0.03, peer.n)
    y[2:peer.n:3] = rng.normal(0.0, 0.02, peer.n // 3)
    y[peer.n:2 * peer.n] = rng.normal(0.0, 0.3, peer.n)
    worst = 0.0
    for i in range(len(peer.cands)):
        g, gd, G, _, _ = peer.kin(i, y, row=True)
        for k in range(peer.n):
            e = np.zeros_like(y)
            e[k] = 1e-6
            fd = (peer.gap(i, y + e) - peer.gap(i, y - e)) / 2e-6
            worst = max(worst, abs(fd - G[k]) / max(1.0, abs(G[k])))
        # g' along the motion: the gap's central difference along q' (q advanced by q' dt)
        e = np.zeros_like(y)
        e[:peer.n] = y[peer.n:2 * peer.n] * 1e-6
        worst = max(worst, abs((peer.gap(i, y + e) - peer.gap(i, y - e)) / 2e-6 - gd))
    line("peer: the gap row against the gap's central differences (rotations of 0.02 rad)", worst, 1e-8, failures)


def line(label, value, limit, failures):
    """One comparison: its measured value and its limit, passed when value <= limit."""
    if value <= limit:
        print(f"ok {label}: {value:.2e} (limit {limit:.0e})")
    else:
        fail(failures, f"{label}: {value:.2e} (limit {limit:.0e})")


def fail(failures, message):
    failures.append(message)
    print("FAIL " + message)


def check_modes(program, folder, failures):
    """The program's periods (pounding modes) are the peer's: the same K and M (the "uniform" J of
    a trapezoid and a parallelogram)."""
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "pulse.txt").write_text("\n".join(repr(a) for a in record()[1]) + "\n")
    (folder / "scene.toml").write_text(scene_text(buildings(), folder / "pulse.txt"))
    run = subprocess.run([program, "modes", str(folder / "scene.toml"), "--json", str(folder / "modes.json")],
                         capture_output=True, text=True)
    if run.returncode != 0:
        fail(failures, f"modes: exit {run.returncode}: {run.stderr.strip()[-300:]}")
        return
    modes = json.loads((folder / "modes.json").read_text())["buildings"]
    worst = 0.0
    for b, spec in zip(modes, buildings()):
        own = np.sort(2 * np.pi / Building(spec).omega)[::-1]
        worst = max(worst, float(np.max(np.abs(np.array(b["periods_s"]) / own - 1.0))))
    periods = ", ".join(f"{b['name']} " + "/".join(f"{p:.4f}" for p in b["periods_s"]) for b in modes)
    line(f"modes: the program's periods ({periods} s) against the peer's (relative)", worst, 1e-9, failures)


def peer_events(peer):
    """The peer's contacts as the program's impacts name them: the slab's building strikes, the
    column's is struck; the column, its point and the slab's edge where the contact began."""
    out = []
    for r in peer.contacts:
        c = peer.cands[r["cand"]]
        out.append(dict(t=r["t_s"], striking=c.A + 1, struck=c.B + 1, column=c.column + 1, edge=c.edge_index + 1,
                        point=tuple(c.X), approach=r["approach"], impulse=r["impulse"], duration=r["duration"],
                        peak=r["peak"], path=r["path"], handovers=r["handovers"],
                        floors=(c.f, c.j + 1) if c.A == 0 else (c.j + 1, c.f)))
    return out


def program_events(impacts):
    return [dict(t=float(r["t_s"]), striking=int(r["striking_building"]), struck=int(r["struck_building"]),
                 column=int(r["column"]), edge=int(r["struck_edge"]),
                 point=(float(r["vertex_rest_x_m"]), float(r["vertex_rest_y_m"])),
                 approach=float(r["approach_velocity_mps"]), impulse=float(r["impulse_kNs"]),
                 duration=float(r["duration_s"]), peak=float(r["peak_force_kN"]), level=int(r["level"]),
                 vertex=int(r["vertex"]), floors=(int(r["floors_b1"]), int(r["floors_b2"]))) for r in impacts]


IDENTITY = ("striking", "struck", "column", "edge", "floors")


def same_contact(a, b, dt=1e-6):
    return (all(a[f] == b[f] for f in IDENTITY) and abs(a["t"] - b["t"]) <= dt
            and math.dist(a["point"], b["point"]) <= 1e-9)


def describe(e, names):
    return (f"{e['t']:.9f} s {names[e['striking'] - 1]}'s slab edge {e['edge']} against {names[e['struck'] - 1]}'s "
            f"column {e['column']} ({round(e['point'][0], 9) + 0.0:g}, {round(e['point'][1], 9) + 0.0:g}): approach "
            f"{e['approach']:.6f} m/s, duration {e['duration']:.6f} s, peak {e['peak']:.3f} kN, impulse "
            f"{e['impulse']:.6f} kN s")


def differences(a, b):
    """Onset and duration (s, absolute), approach speed, impulse and peak force (relative) of two
    descriptions of one contact."""
    return dict(t=abs(a["t"] - b["t"]), duration=abs(a["duration"] - b["duration"]),
                approach=abs(b["approach"] / a["approach"] - 1.0), impulse=abs(b["impulse"] / a["impulse"] - 1.0),
                peak=abs(b["peak"] / a["peak"] - 1.0))


def agreement(mine, theirs, limits):
    """The contacts of two lists (in onset order) that agree: how many from the start, the largest
    differences over those, and the first that does not (its index, or None)."""
    worst = dict(t=0.0, duration=0.0, approach=0.0, impulse=0.0, peak=0.0)
    for k in range(min(len(mine), len(theirs))):
        if not same_contact(mine[k], theirs[k]):
            return k, worst
        d = differences(mine[k], theirs[k])
        if any(d[key] > limits[key] for key in d):
            return k, worst
        worst = {key: max(worst[key], d[key]) for key in worst}
    return (None if len(mine) == len(theirs) else min(len(mine), len(theirs))), worst


METHODS = {"cvode-bdf": ["--method", "cvode-bdf", "--rtol", "1e-12", "--atol", "1e-14"],
           "arkode-erk": ["--method", "arkode-erk", "--rtol", "1e-12", "--atol", "1e-14"]}
HISTORY = [(b, f, comp) for b, f in ((1, 1), (2, 1), (2, 2)) for comp in ("u_m", "v_m", "phi_rad")]
# Limits (measured values in the docstring): onsets and durations (s), approach speeds, impulses
# and peak forces (relative), hand-over instants (s) and the force just after (relative), u and v
# (m) and phi (rad) at every history row, the impact loss against the peer's contact work
# (relative) and the program's energy audit (relative residual).
LIMITS = dict(t=1e-9, duration=1e-9, approach=3e-8, impulse=3e-7, peak=5e-6, handover_t=1e-9, handover_force=2e-7,
              uv=3e-10, phi=3e-11, loss=2e-8, residual=4e-9)


def run_program(program, folder, options):
    _, accel = record()
    run, message = program_run.run_scene(program, folder, lambda path: scene_text(buildings(), path), accel, options,
                                         [f"B{b}_f{fl}_{comp}" for b, fl, comp in HISTORY], accept_any_exit=True,
                                         forces=True)
    if run is None:
        return None, message
    return dict(summary=run.summary, impacts=run.impacts, t=run.t, q=run.q, forces=run.forces), None


def candidate_key(point, striking, struck, edge):
    return (round(point[0], 9) + 0.0, round(point[1], 9) + 0.0, striking, struck, edge)


def check_candidates(name, peer, summary, failures):
    """summary.json's candidates are the peer's: the column point as the vertex, the column's building
    striking, the slab's edge, corner or not, the column, its storey, the height ratio and the local
    flexibility. Returns the program's index of each of the peer's candidates."""
    listed = sorted((candidate_key(c["vertex_rest"], c["striking_building"], c["struck_building"], c["edge"]),
                     bool(c.get("corner", False)), c["column"], c["storey"], round(c["height_ratio"], 12),
                     round(c["local_flexibility_m_per_kN"] * 1e6, 9)) for c in summary["candidates"])
    own = sorted((candidate_key(c.X, c.B + 1, c.A + 1, c.edge_index + 1), c.corner, c.column + 1, c.j + 1,
                  round(c.xi, 12), round(c.flex * 1e6, 9)) for c in peer.cands)
    if listed == own:
        print(f"ok {name}: the program's {len(listed)} candidates ({sum(c[1] for c in listed)} corner ones) are the "
              f"peer's (column point, edge, corner or not, column, storey, height ratio, local flexibility)")
    else:
        fail(failures, f"{name}: the program's candidates {listed}, the peer's {own}")
    index = {candidate_key(c["vertex_rest"], c["striking_building"], c["struck_building"], c["edge"]): k
             for k, c in enumerate(summary["candidates"])}
    return [index.get(candidate_key(c.X, c.B + 1, c.A + 1, c.edge_index + 1)) for c in peer.cands]


def compare(program, folder, method, peer, failures, quiet=False):
    """The program run with `method` against the peer. quiet: only the first disagreement, as
    (contact index or None, its message)."""
    name = method
    result, error = run_program(program, folder, METHODS[method])
    if result is None:
        if quiet:
            return 0, error
        fail(failures, f"{name}: the program failed: {error}")
        return
    summary, t_out, q = result["summary"], result["t"], result["q"]
    mine, theirs = peer_events(peer), program_events(result["impacts"])
    first, worst = agreement(mine, theirs, LIMITS)
    message = None
    if first is not None:
        a, b = (mine[first] if first < len(mine) else None), (theirs[first] if first < len(theirs) else None)
        message = (f"the program has {len(theirs)} impacts, the peer {len(mine)} contacts; the first {first} agree, "
                   f"then: peer {describe(a, peer.names) if a else 'none'}"
                   + (f" (handed round a corner at {', '.join(f'{h[0]:.9f}' for h in a['handovers'])} s)"
                      if a and a["handovers"] else "")
                   + f" | program {describe(b, peer.names) if b else 'none'}"
                   + ("; differences: " + ", ".join(f"{key} {value:.2e}" for key, value in differences(a, b).items())
                      if a and b else ""))
    if quiet:
        return first, message
    if summary["status"] != "completed" or summary["exit_code"] != 0:
        fail(failures, f"{name}: exit {summary['exit_code']}, status {summary['status']}: "
             f"{summary.get('status_detail')}")
    index = check_candidates(name, peer, summary, failures)
    wrong = [e for e in theirs if (e["level"], e["vertex"]) != (0, 0)]
    if wrong:
        fail(failures, f"{name}: impacts with a level or vertex (slab to column has neither): {wrong[:2]}")
    n = len(mine) if first is None else first
    handed = sum(len(e["path"]) > 1 for e in mine[:n])
    if message:
        fail(failures, f"{name}: {message}")
        print(f"   {name}: the first {n} of {len(mine)} contacts agree, {handed} of them handed round a corner")
    else:
        print(f"ok {name}: the program's {len(theirs)} impacts are the peer's {len(mine)} contacts one to one (column, "
              f"point, floors, the slab edge where each began, onset within 1e-6 s), {handed} of them handed round a "
              f"corner")
    line(f"{name}: onsets (s)", worst["t"], LIMITS["t"], failures)
    line(f"{name}: durations (s)", worst["duration"], LIMITS["duration"], failures)
    line(f"{name}: approach speeds (relative)", worst["approach"], LIMITS["approach"], failures)
    line(f"{name}: impulses, over each whole contact (relative)", worst["impulse"], LIMITS["impulse"], failures)
    line(f"{name}: peak forces (relative)", worst["peak"], LIMITS["peak"], failures)
    # The hand-overs in contacts_history.csv: at the instant of each, a row of the candidate that
    # took the contact over, with the force it pushes with; a kelvin element never pulls.
    dt, dforce, missing = 0.0, 0.0, []
    for h in peer.handovers:
        if h["force_to"] < 0.0:
            continue
        rows = sorted((r for r in result["forces"] if r["candidate"] == index[h["to"]] and abs(r["t"] - h["t"]) < 1e-6),
                      key=lambda r: abs(r["t"] - h["t"]))
        if not rows:
            missing.append(f"{h['t']:.9f} s to {peer.cands[h['to']].label(peer.names)}")
            continue
        dt = max(dt, abs(rows[0]["t"] - h["t"]))
        dforce = max(dforce, abs(rows[0]["force"] / h["force_to"] - 1.0))
    pushing = sum(h["force_to"] >= 0.0 for h in peer.handovers)
    if missing:
        fail(failures, f"{name}: contacts_history.csv has no row of the candidate taking the contact over at the "
             f"peer's hand-overs " + "; ".join(missing))
    line(f"{name}: the {pushing} hand-overs whose force pushes on: instants in contacts_history.csv (s)", dt,
         LIMITS["handover_t"], failures)
    line(f"{name}: the force just after them (relative)", dforce, LIMITS["handover_force"], failures)
    pulls = [r for r in result["forces"] if r["force"] < -1e-6]
    if pulls:
        r = pulls[0]
        c = summary["candidates"][r["candidate"]]
        fail(failures, f"{name}: a kelvin contact pulls (docs/model.md §6a: the element cannot pull): "
             f"contacts_history.csv has {len(pulls)} rows with a tensile force, the first at {r['t']:.9f} s, "
             f"{r['force']:.3f} kN on candidate {r['candidate']} (column {c['column']} ({c['vertex_rest'][0]:g}, "
             f"{c['vertex_rest'][1]:g}) against edge {c['edge']}, corner {c.get('corner', False)}), the largest "
             f"{min(p['force'] for p in pulls):.3f} kN"
             + "".join(f"; the peer hands that contact over at {h['t']:.9f} s onto a force of {h['force_to']:.3f} kN "
                       f"and releases it there" for h in peer.handovers
                       if h["force_to"] < 0.0 and abs(h["t"] - r["t"]) < 1e-6))
    else:
        print(f"ok {name}: no tensile force in contacts_history.csv ({len(result['forces'])} rows)")
    stats = summary["statistics"]
    got = (stats.get("corner_candidates"), stats.get("corner_candidates_armed"), stats.get("corner_handovers"))
    want = (sum(c.corner for c in peer.cands), len(peer.ever_live), len(peer.handovers))
    if got == want:
        print(f"ok {name}: corner candidates, armed, hand-overs: program {got}, peer {want}")
    else:
        fail(failures, f"{name}: corner candidates, armed, hand-overs: program {got}, peer {want}")
    t_stop = math.inf if first is None else min(mine[first]["t"] if first < len(mine) else math.inf,
                                                theirs[first]["t"] if first < len(theirs) else math.inf)
    rows = t_out < t_stop - 1e-9
    diff = np.abs(q[rows] - peer.at(t_out[rows]))
    before = f" before {t_stop:.6f} s" if t_stop < math.inf else ""
    line(f"{name}: u, v of three floors at {int(np.sum(rows))} history rows{before} (m)",
         float(np.max(diff[:, [0, 1, 3, 4, 6, 7]])), LIMITS["uv"], failures)
    line(f"{name}: phi at the same rows (rad)", float(np.max(diff[:, [2, 5, 8]])), LIMITS["phi"], failures)
    energy = summary["energy"]
    if first is None:
        line(f"{name}: impact loss {energy['impact_loss_kJ']:.6f} kJ against the peer's contact work "
             f"{peer.energy['contact']:.6f} kJ (relative)", abs(energy["impact_loss_kJ"] / peer.energy["contact"] - 1),
             LIMITS["loss"], failures)
    line(f"{name}: the energy audit's relative residual", abs(energy["relative_residual"]), LIMITS["residual"],
         failures)
    return first


def summarise(peer):
    ev = peer_events(peer)
    forces = ", ".join(f"{h['force_to']:.1f}" for h in peer.handovers)
    print(f"   peer: {len(ev)} contacts ({sum(e['striking'] == 1 for e in ev)} B1's slab on B2's columns, "
          f"{sum(e['striking'] == 2 for e in ev)} B2's on B1's), {peer.corner_onsets} begun on a corner candidate, "
          f"{len(peer.handovers)} handed round a corner (the force just after: {forces} kN), corner candidates "
          f"armed {sorted(peer.ever_live)} of {[i for i, c in enumerate(peer.cands) if c.corner]}; approach speeds "
          f"{min(e['approach'] for e in ev):.3f} to {max(e['approach'] for e in ev):.3f} m/s, deepest overlap "
          f"{peer.deepest * 1e3:.2f} mm; {peer.passed_beside} crossings beside a facing edge, "
          f"{len(peer.covered_crossings)} covered, {peer.late_roots} roots found past their zero; energy residual "
          f"{peer.energy['residual'] / peer.energy['input']:.1e} of the input")
    for e in ev:
        print("     " + describe(e, peer.names) + "".join(
            f"; at {t:.9f} s handed to {peer.cands[j].label(peer.names)}" for t, _, j in e["handovers"]))


def check_scene(peer, failures):
    """What the scene is for, and the peer's own consistency."""
    line("peer: energy input = kinetic + strain + damping + contact work (relative to the input)",
         abs(peer.energy["residual"]) / peer.energy["input"], 1e-11, failures)
    bad = []
    if not any(h["force_to"] > 0.0 for h in peer.handovers):
        bad.append("no contact handed round a corner that pushes on")
    if not peer.ever_live or not peer.corner_onsets:
        bad.append(f"corner candidates armed {sorted(peer.ever_live)}, {peer.corner_onsets} contacts begun on one")
    if peer.touches or peer.arrivals or peer.unexplained:
        bad.append(f"touches {peer.touches[:2]}, points come over an edge already inside {peer.arrivals[:2]}, "
                   f"points inside a slab with no contact {peer.unexplained[:2]}")
    if any(r["acts_again"] for r in peer.contacts):
        bad.append("a released contact pushes again")
    if bad:
        fail(failures, "peer: the scene no longer does what it was chosen for: " + "; ".join(bad))
    else:
        print(f"ok peer: the scene does what it was chosen for: {sum(h['force_to'] > 0 for h in peer.handovers)} "
              f"hand-overs that push on, {len(peer.tensile_handovers)} onto an edge where the force would pull "
              f"(released there), {len(peer.ever_live)} corner candidates armed, {peer.corner_onsets} contacts begun "
              f"on one; no touch, no point inside a slab without a contact")


def check_convergence(peer, times, accel, failures):
    """The peer at rtol 1e-13, atol 1e-15 against itself at 1e-12, 1e-14."""
    fine = Peer(buildings(), rtol=1e-13, atol=1e-15).run(times, accel)
    a, b = peer_events(peer), peer_events(fine)
    if len(a) != len(b) or not all(same_contact(x, y) and x["path"] == y["path"] for x, y in zip(a, b)):
        fail(failures, f"peer: at rtol 1e-13 {len(b)} contacts, at 1e-12 {len(a)}, or other candidates")
        return
    d = {key: max(differences(x, y)[key] for x, y in zip(a, b)) for key in ("t", "duration", "approach", "impulse",
                                                                            "peak")}
    dh = max(abs(x["t"] - y["t"]) for x, y in zip(peer.handovers, fine.handovers))
    line("peer: rtol 1e-12 against 1e-13: onsets, durations, hand-over instants (s)",
         max(d["t"], d["duration"], dh), 1e-10, failures)
    line("peer: rtol 1e-12 against 1e-13: approach speeds, impulses, peak forces (relative)",
         max(d["approach"], d["impulse"], d["peak"]), 1e-8, failures)


def check_discrimination(peer, times, accel, failures):
    """What the comparison would see if the program lacked the hand-over round a corner: the peer
    ending each contact at its edge's end instead; its contacts matched to the full peer's by
    column, edge and onset (1 ms), the largest relative change of a matched contact's impulse."""
    bare = Peer(buildings(), handovers=False).run(times, accel)
    a, b = peer_events(peer), peer_events(bare)
    worst, unmatched = 0.0, 0
    for x in a:
        near = [y for y in b if same_contact(x, y, 1e-3)]
        if near:
            worst = max(worst, abs(near[0]["impulse"] / x["impulse"] - 1.0))
        else:
            unmatched += 1
    msg = (f"peer without the hand-over: {len(b)} contacts (with it {len(a)}, {unmatched} of them without a match), "
           f"a matched contact's impulse changes by up to {worst:.1%}, {worst / LIMITS['impulse']:.0e} times the "
           f"impulses' limit; {len(bare.unexplained)} samples with a column point inside a slab and no contact there")
    if worst > 0.01 or unmatched:
        print("ok " + msg)
    else:
        fail(failures, msg + ": the comparison would not tell a missing hand-over")


def diagnose(program, out, times, accel):
    """After a disagreement: whether the program agrees with a peer whose contact, handed round a
    corner onto an edge where its force pulls, goes on pulling until the gap opens."""
    pulling = Peer(buildings(), pull=True).run(times, accel)
    for method in METHODS:
        first, message = compare(program, out / method, method, pulling, [], quiet=True)
        verdict = (f"agrees with it on all {len(pulling.contacts)} contacts within the limits" if first is None
                   else f"disagrees with it too: {message}")
        print(f"   diagnosis, {method}: against a peer whose handed-over contact keeps pulling (as a kelvin element "
              f"that cannot pull must not), the program {verdict}")


def main():
    started = time.time()
    program = sys.argv[1]
    out = (Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())).resolve()
    out.mkdir(parents=True, exist_ok=True)
    times, accel = record()
    failures = []
    check_gap_row(failures)
    check_modes(program, out / "modes", failures)
    peer = Peer(buildings()).run(times, accel)
    summarise(peer)
    check_scene(peer, failures)
    check_convergence(peer, times, accel, failures)
    check_discrimination(peer, times, accel, failures)
    disagreed = False
    for method in METHODS:
        disagreed |= compare(program, out / method, method, peer, failures) is not None
    if disagreed and peer.tensile_handovers:
        diagnose(program, out, times, accel)
    print()
    program_run.finish(failures, started, width=800)


if __name__ == "__main__":
    main()
