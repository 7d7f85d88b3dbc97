#!/usr/bin/python3
"""A row of three buildings with the impulse law against an independent computation (scipy, no code shared).

    tests/solvers/test_row_impulse_scipy.py POUNDING [OUT]

Three one-storey buildings in a row along x, B1 | B2 | B3, each with a 3 m storey, a 3 x 3 grid
of square columns at its slab's corners, edge midpoints and centre (E 3e7 kPa, frame factor 1,
fixed-fixed), the CM at the slab's centre, "uniform" J and no damping (damping.ratio = 0): B1
slab x in [0, 10], y in [0, 10], 200 t, columns 0.17 m (T 0.9723 s); B2 x in [10.03, 20.03],
y in [-1, 11] (deeper than its neighbours, so that B1's and B3's corners strike B2's faces
inside their length and B2's corners strike nothing), 300 t, 0.15 m (T 1.5295 s); B3 x in
[20.06, 30.06], y in [0, 10], 150 t, 0.45 m (T 0.1202 s); gaps 0.03 m each side; the impulse law
with hold_velocity_mps 1e-3 and hold_height_m 1e-8 (the defaults); shaking along x,
a_g = 1.0 sin(2 pi t / 1.0 s) + 0.5 sin(2 pi t / 2.0 s) m/s2 for 4 s, then 0 (free vibration) to
6 s, sampled every 0.01 s. The plans are symmetric about y = 5 and the shaking is along x, so
the motion is pure x. Each side has two coincident contacts (B1's vertices 2 and 3 on B2's
edge 4, B3's vertices 1 and 4 on B2's edge 2): the program splits the impulse or force between
them; the two impacts.csv rows of a side and instant, and the two sustained_contacts records of
a hold, are summed.

The peer: u of the three slabs relative to the ground, m_i u_i'' + k_i u_i = -m_i a_g + contact
forces, k_i = 9 * 12 E (b^4 / 12) / H^3, a_g linear between the samples (docs/scene-format.md:
linear between samples, zero outside; the run ends at the last sample); gaps g = 0.03 + u2 - u1
and 0.03 + u3 - u2. A held contact is a bilateral constraint whose force follows from equal
accelerations (W lambda = -G a_free over the held ones; g and g' of a held contact are linear
invariants, which Runge-Kutta keeps). DOP853 at rtol 1e-13, atol 1e-15 over each record
interval, with terminal events: a held contact's force turning tensile (release), an open
contact's gap closing (impact), and, for a contact standing at zero gap (just parted or
released), the apex of its gap (g' = -1e-12 m/s, falling), after which its gap is armed; a
non-terminal event at every minimum of an armed gap finds a dip below zero inside one step (the
closing is then located on the dense output; none occurs in this scene). An impact is one
linear complementarity problem (enumerated) over every contact closed then: the one that fired,
the held ones and any within 1e-8 m (the program's contact tolerance), w = g'- + W I - e >= 0,
I >= 0, I w = 0, e = -k min(g'-, 0), so B1 striking B2 while B2 is held against B3 moves all
three slabs in one impact (the "joined" impact); then docs/model.md §7's hold rule: a contact
left separating slower than hold_velocity_mps, or whose flight would rise less than
hold_height_m, is held if the force keeping it closed is compressive (here from the
complementarity problem of the accelerations over those contacts), the held ones solved again
with k = 0 until the set settles, and brought to zero gap rate exactly (that energy is impact
loss); after every event the held forces are settled as one complementarity problem. Input work
is integrated with the motion; the impact loss is the kinetic energy the impacts take.

Why every joined impact here is B1 striking B2 held against B3, never B3 striking B2 held
against B1: B1 presses B2 (both free of B3) only while -w1^2 u1 > -w2^2 u2 with u1 = u2 + 0.03,
i.e. u2 < -0.03 w1^2 / (w1^2 - w2^2) = -5.0 cm (w1^2 41.8, w2^2 16.9 1/s2), and B2:B3 would then
close only at u3 < -8 cm, while B3 (w3^2 2734 1/s2) never moves more than 2.7 cm.

Checked (all program runs at rtol 1e-12, atol 1e-14; measured values in parentheses):
  1. the peer alone: without contact it is the exact motion (each undamped storey propagated in
     closed form over the record's linear pieces) within 1e-12 m (4.0e-15), energy closing to
     1e-11 of the input (1.7e-15); with contact, input = kinetic + strain + impact loss within
     1e-11 of the input (k = 0: 2.4e-13, k = 0.5: 3.7e-13); Radau at rtol 1e-11 finds the same
     impacts and holds (k = 0 within 5e-11 s, 5e-9 kN s, 5e-11 m/s: measured 7.9e-12 s, 8.7e-10
     kN s, 7.9e-12 m/s, holds 7.9e-12 / 9.3e-13 s; k = 0.5 within 2e-8 s, 5e-6 kN s, 3e-8 m/s:
     4.4e-9 s, 8.5e-7 kN s, 5.7e-9 m/s, holds 9.2e-11 / 2.3e-11 s); the program's x-mode periods
     (pounding modes --json) are 2 pi sqrt(m / k) within 1e-9 (2.2e-16) and its Rayleigh
     coefficients are 0;
  2. the scene does what it is for: at least 5 impacts on each side (k = 0: 15 on B1:B2, 11 on
     B2:B3, 17 holds; k = 0.5: 27 and 52, 4 holds), at least 3 joined impacts in the peer and the
     same in the program, at the same instants (k = 0: 6, at 1.0195, 1.8247, 2.7900, 2.7930,
     3.7293, 4.6285 s; k = 0.5: 6, at 1.8971, 1.9161, 2.9103, 3.7604, 3.7930, 3.8154 s), whose
     impulses differ from those of the struck pair alone by at least 1 % (15.4 %); no flight
     lower than 1e-12 m, no missed dip, closest approach without contact 1e-5 m at least (6.2e-3,
     1.9e-4 m); every hold decision at least 5 % from hold_velocity_mps and from hold_height_m
     (k = 0.5: 8.9 % and 11 %) and at least 1e-3 of the accelerations from a force of zero (9.1e-2,
     1.0);
  3. the program (cvode-bdf and arkode-erk at rtol 1e-12, atol 1e-14; exact, its ground truth, at
     its defaults) against the peer, k = 0, then 4. the same with
     k = 0.5: every impact row a coincident corner (B1's vertices 2, 3 on B2's edge 4, B3's
     vertices 1, 4 on B2's edge 2, two rows an instant); the impacts matched one to one per side
     in time order, with their starts_sustained_contact, the holds likewise with their
     release_reason (all "tensile force" here), and within (measured):
                           k = 0                                k = 0.5
                           cvode-bdf         arkode-erk         cvode-bdf         arkode-erk
     impact instant        3e-9 s (9.1e-10)  5e-10 (1.7e-10)    2e-6 (4.5e-7)     3e-9 (7.4e-10)
     impulse sum           1e-6 kN s (3.6e-7) 5e-8 (1.2e-8)     3e-4 (8.9e-5)     5e-7 (1.4e-7)
     approach speed        1e-8 m/s (3.6e-9) 5e-10 (1.2e-10)    2e-6 (5.9e-7)     3e-9 (9.2e-10)
     separation speed      1e-12 m/s (3.3e-16) 1e-12 (2.2e-16)  1e-6 (3.0e-7)     2e-9 (4.6e-10)
     hold start            3e-9 s (9.1e-10)  5e-10 (1.7e-10)    3e-8 (9.7e-9)     1e-10 (1.8e-11)
     hold release          2e-9 s (4.1e-10)  1e-11 (1.5e-12)    1e-8 (2.4e-9)     2e-11 (4.2e-12)
     held side's share     5e-8 kN s (1.5e-8) 5e-10 (1.5e-10)   5e-6 (1.7e-6)     1e-8 (2.8e-9)
     u at history rows     5e-10 m (1.7e-10) 2e-12 (4.6e-13)    3e-7 (7.6e-8)     5e-10 (1.2e-10)
     energy terms / input  5e-9 (1.9e-9)     3e-11 (7.0e-12)    1e-7 (3.0e-8)     2e-10 (3.9e-11)
     audit residual        5e-9 (1.6e-9)     3e-11 (6.2e-12)    5e-9 (1.2e-9)     3e-11 (5.3e-12)
     and exact                k = 0              k = 0.5
     impact instant        1e-9 s (3.0e-10)   1e-7 (2.5e-8)
     impulse sum           1e-6 kN s (1.9e-7) 2e-5 (5.0e-6)
     approach speed        1e-8 m/s (1.9e-9)  1e-7 (3.3e-8)
     separation speed      1e-12 m/s (2.8e-16) 6e-8 (1.7e-8)
     hold start            1e-9 s (3.0e-10)   2e-9 (4.9e-10)
     hold release          5e-10 s (1.5e-10)  5e-10 (1.2e-10)
     held side's share     2e-8 kN s (5.0e-9) 3e-7 (8.5e-8)
     u at history rows     2e-10 m (5.4e-11)  2e-8 (4.2e-9)
     energy terms / input  3e-9 (8.1e-10)     6e-9 (1.7e-9)
     audit residual        3e-9 (6.6e-10)     2e-10 (3.5e-11)
     (the held side's share: sustained_contacts' impulse_kNs, what a held contact takes in the
     joined impacts, against the peer's; energy terms: input, final kinetic and strain, impact
     loss, and damping and constraint work, which should be 0); v and phi of every slab within
     1e-14 (at most 4.3e-17); the twin corners' records of a hold released within 1e-10 s of each
     other (4.0e-14 s: the program releases them in two events). With k = 0.5 the bounce
     sequences amplify every timing error (the cvode-bdf differences grow about tenfold a second
     and fall about eightfold a decade of rtol: u 5.9e-7, 7.6e-8, 9.3e-9 m at rtol 1e-11, 1e-12,
     1e-13), hence its wider limits.
The program's max_force_kN of a hold is sampled at step ends and events and is not compared.
Run time about 20 s.
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
from scipy.optimize import brentq

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

E_KPA, STOREY_M = 3.0e7, 3.0
HOLD_VELOCITY_MPS, HOLD_HEIGHT_M, CLOSED_TOL_M = 1e-3, 1e-8, 1e-8  # docs/scene-format.md defaults; see Peer.impact
ARMED_GAP_M, APEX_SHIFT_MPS = 1e-12, 1e-12  # see Peer.event_functions
# Two sines along x (direction 0) for SHAKE_END_S, then free vibration to DURATION_S; sampled every DT_S.
SINES = [(1.0, 1.0), (0.5, 2.0)]  # (amplitude m/s2, period s)
SHAKE_END_S, DT_S, DURATION_S = 4.0, 0.01, 6.0
# name, slab x range, y range, floor mass (t), square column side (m); a 3 x 3 column grid on the
# slab's corners, edge midpoints and centre; CM at the slab's centre.
BUILDINGS = [
    dict(name="B1", x=(0.0, 10.0), y=(0.0, 10.0), mass=200.0, column=0.17),
    dict(name="B2", x=(10.03, 20.03), y=(-1.0, 11.0), mass=300.0, column=0.15),
    dict(name="B3", x=(20.06, 30.06), y=(0.0, 10.0), mass=150.0, column=0.45),
]
NAMES = [b["name"] for b in BUILDINGS]
SIDES = ["B1:B2", "B2:B3"]  # the peer's contact 0 and 1: the program's levels 1 and 2


def scene_text(record, restitution):
    parts = ['name = "row-impulse-peer"\n']
    for b in BUILDINGS:
        (x0, x1), (y0, y1) = b["x"], b["y"]
        xc, yc = (x0 + x1) / 2, (y0 + y1) / 2
        parts.append(f"""
[[building]]
name = "{b['name']}"
storeys = 1
storey_height_m = {STOREY_M!r}
slab = [[{x0!r}, {y0!r}], [{x1!r}, {y0!r}], [{x1!r}, {y1!r}], [{x0!r}, {y1!r}]]
centre_of_mass = [{xc!r}, {yc!r}]
mass_t = {b['mass']!r}
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA!r}
frame_factor = 1.0
[[building.column_grid]]
x = [{x0!r}, {xc!r}, {x1!r}]
y = [{y0!r}, {yc!r}, {y1!r}]
b_m = {b['column']!r}
h_m = {b['column']!r}
[building.damping]
ratio = 0.0
""")
    parts.append(f"""
[excitation]
file = "{record}"
format = "single"
units = "m/s2"
dt_s = {DT_S!r}
direction_deg = 0.0

[solver]
method = "cvode-bdf"
rtol = 1e-10
atol = 1e-12

[contact]
law = "impulse"
restitution = {restitution!r}
hold_velocity_mps = {HOLD_VELOCITY_MPS!r}
hold_height_m = {HOLD_HEIGHT_M!r}
""")
    return "".join(parts)


def record():
    t = np.arange(round(DURATION_S / DT_S) + 1) * DT_S
    a = sum(amp * np.sin(2 * np.pi * t / period) for amp, period in SINES)
    return t, np.where(t < SHAKE_END_S - DT_S / 2, a, 0.0)


# --- the peer -----------------------------------------------------------------------------------
MASS = np.array([b["mass"] for b in BUILDINGS])
# Nine fixed-fixed columns of side b in the storey, rigid slab: 9 * 12 E (b^4 / 12) / H^3.
STIFFNESS = np.array([9 * 12.0 * E_KPA * (b["column"] ** 4 / 12.0) / STOREY_M ** 3 for b in BUILDINGS])
G = np.array([[-1.0, 1.0, 0.0], [0.0, -1.0, 1.0]])  # g_c = D_c + G_c x; contact 0 B1:B2, 1 B2:B3
D = np.array([BUILDINGS[1]["x"][0] - BUILDINGS[0]["x"][1], BUILDINGS[2]["x"][0] - BUILDINGS[1]["x"][1]])


def lcp(W, b):
    """w = W x + b >= 0, x >= 0, x w = 0, by enumerating the active sets (W positive definite: one solution)."""
    n = len(b)
    if n == 0:
        return np.zeros(0)
    scale = 1e-12 * (1.0 + np.max(np.abs(b)))
    for size in range(n + 1):
        for active in [[i for i in range(n) if mask >> i & 1] for mask in range(1 << n)]:
            if len(active) != size:
                continue
            x = np.zeros(n)
            if active:
                x[active] = np.linalg.solve(W[np.ix_(active, active)], -b[active])
            w = W @ x + b
            if np.all(x >= -scale * 1e-3) and np.all(w >= -scale):
                return np.maximum(x, 0.0)
    raise RuntimeError("LCP without solution")


def kinetic(v):
    return 0.5 * float(np.dot(MASS, v * v))


class Peer:
    """Three slabs moving along x only (u of each, relative to the ground), undamped storeys,
    plastic or Newton impacts between B1 and B2 and between B2 and B3, held contacts as bilateral
    constraints while their force is compressive. Integrated with solve_ivp over each record
    interval (a_g linear there), every gap closing (g = 0 falling) and every hold force turning
    tensile (lambda = 0 falling) a terminal event, the integration restarted there."""

    def __init__(self, restitution=0.0, contact=True, method="DOP853", rtol=1e-13, atol=1e-15):
        self.k = restitution
        self.contact = contact
        self.method, self.rtol, self.atol = method, rtol, atol
        self.held = []            # held contacts (0, 1), ascending
        self.hold_rec = [None, None]
        self.impacts = []         # dict(t, side, impulse, approach, separation, holds, joined)
        self.holds = []           # dict(side, start, release, reason, impulse (shares while held), max_force)
        self.events = 0
        self.loss = 0.0
        self.segments = []

    # --- mechanics --------------------------------------------------------------------------
    def free_acceleration(self, t, x):
        return -STIFFNESS * x / MASS - self.ag(t)

    def hold_forces(self, a_free, S):
        """The forces (kN, compressive positive) that keep the contacts S closed (g'' = 0)."""
        if not S:
            return np.zeros(0)
        Gs = G[S]
        W = Gs @ (Gs.T / MASS[:, None])
        return np.linalg.solve(W, -Gs @ a_free)

    def acceleration(self, t, x, S):
        a = self.free_acceleration(t, x)
        if S:
            a = a + (G[S].T @ self.hold_forces(a, S)) / MASS
        return a

    def rhs(self, t, y):
        x, v = y[:3], y[3:6]
        return np.concatenate([v, self.acceleration(t, x, self.held), [-self.ag(t) * float(np.dot(MASS, v))]])

    def event_functions(self, y0):
        """Terminal events, falling: a held contact's force; an open contact's gap, or, while it
        stands at zero gap (it has just parted or been released: its gap starts at 0 and may
        fall back before a step ends), the zero of its gap rate at its apex (shifted by
        APEX_SHIFT_MPS, so that a rate starting at -1e-17 is not a crossing): its gap is armed
        again there, clearly open."""
        funcs, tags = [], []
        if not self.contact:
            return funcs, tags
        for c in (0, 1):
            if c in self.held:
                r = self.held.index(c)
                S = list(self.held)

                def f(t, y, r=r, S=S):
                    return self.hold_forces(self.free_acceleration(t, y[:3]), S)[r]
                tag = ("release", c)
            elif D[c] + G[c] @ y0[:3] > ARMED_GAP_M:
                def f(t, y, c=c):
                    return D[c] + G[c] @ y[:3]
                tag = ("closes", c)

                def m(t, y, c=c):  # a minimum of the gap: a dip inside one step (see run)
                    return G[c] @ y[3:6]
                m.terminal, m.direction = False, 1
                funcs.append(m)
                tags.append(("minimum", c))
            else:
                def f(t, y, c=c):
                    return G[c] @ y[3:6] + APEX_SHIFT_MPS
                tag = ("apex", c)
            f.terminal, f.direction = True, -1
            funcs.append(f)
            tags.append(tag)
        return funcs, tags

    def settle(self, t, y):
        """After every event: the held contacts' forces as one complementarity problem; those it
        leaves without force while their gap would open are released."""
        if not self.held:
            return
        S = list(self.held)
        a_free = self.free_acceleration(t, y[:3])
        Gs = G[S]
        W = Gs @ (Gs.T / MASS[:, None])
        lam = lcp(W, Gs @ a_free)
        w = W @ lam + Gs @ a_free
        for r, c in enumerate(S):
            if lam[r] <= 0.0 and w[r] > 1e-9 * (1.0 + np.max(np.abs(w))):
                self.release(c, t, "tensile force")

    def release(self, c, t, reason):
        self.held.remove(c)
        rec = self.holds[self.hold_rec[c]]
        rec["release"], rec["reason"] = t, reason
        self.hold_rec[c] = None

    def impact(self, t, y, fired):
        """Every contact closed now (the one that fired, the held ones, any other within
        CLOSED_TOL_M) in one impulse problem; then the documented hold rule (docs/model.md §7):
        a contact left separating slower than HOLD_VELOCITY_MPS, or whose next flight would rise
        less than HOLD_HEIGHT_M, is held if the force keeping it closed is compressive (the held
        ones solved again with k = 0), and brought to zero gap rate."""
        x, v = y[:3], y[3:6].copy()
        g = D + G @ x
        P = sorted(set([fired]) | set(self.held) | {c for c in (0, 1) if abs(g[c]) <= CLOSED_TOL_M})
        were_held = [c in self.held for c in P]
        Gp = G[P]
        W = Gp @ (Gp.T / MASS[:, None])
        rate_before = Gp @ v
        others = [c for c in self.held if c not in P]
        holding = [False] * len(P)
        for _ in range(len(P) + 1):
            k = np.where(holding, 0.0, self.k)
            impulses = lcp(W, rate_before + k * np.minimum(rate_before, 0.0))
            v_after = v + (Gp.T @ impulses) / MASS
            rate_after = Gp @ v_after
            accel = Gp @ self.acceleration(t, x, others)
            slow = [j for j in range(len(P)) if rate_after[j] < HOLD_VELOCITY_MPS
                    or (accel[j] < 0.0 and rate_after[j] ** 2 / (-2.0 * accel[j]) < HOLD_HEIGHT_M)]
            for j in range(len(P)):  # how near the speed rule's threshold each decision is
                if not holding[j] and not were_held[j]:
                    self.margin["hold_velocity"] = min(self.margin["hold_velocity"],
                                                       abs(rate_after[j] / HOLD_VELOCITY_MPS - 1.0))
                    if accel[j] < 0.0:
                        self.margin["hold_height"] = min(self.margin["hold_height"], abs(
                            rate_after[j] ** 2 / (-2.0 * accel[j]) / HOLD_HEIGHT_M - 1.0))
            proposal = [False] * len(P)
            if slow:
                trial = others + [P[j] for j in slow]
                Gt = G[trial]
                Wt = Gt @ (Gt.T / MASS[:, None])
                a_free = self.free_acceleration(t, x)
                lam = lcp(Wt, Gt @ a_free)
                w = Wt @ lam + Gt @ a_free
                scale = np.max(np.abs(Gt @ a_free))
                for s, j in enumerate(slow):
                    r = len(others) + s
                    proposal[j] = lam[r] > 1e-9 * (1.0 + scale)
                    # pressed (W lam) or pulled apart (w): how far from a force of zero, of the accelerations
                    self.margin["pressing"] = min(self.margin["pressing"], max(Wt[r, r] * lam[r], w[r]) / scale)
            if proposal == holding:
                break
            holding = proposal
        h = [j for j in range(len(P)) if holding[j]]
        if h:  # the held ones to zero gap rate exactly
            Gh = Gp[h]
            Wh = Gh @ (Gh.T / MASS[:, None])
            closing = np.linalg.lstsq(Wh, -(Gh @ v_after), rcond=None)[0]
            v_after = v_after + (Gh.T @ closing) / MASS
            impulses[h] += closing
        round_off = 1e-15 + 1e-9 * (np.abs(Gp) @ np.abs(v))
        joined = any(were_held[j] for j in range(len(P)) if P[j] != fired)
        for j, c in enumerate(P):
            if were_held[j]:
                self.holds[self.hold_rec[c]]["impulse"] += impulses[j]
            elif impulses[j] > 0.0 and rate_before[j] < -round_off[j]:
                self.impacts.append(dict(t=t, side=c, impulse=impulses[j], approach=-rate_before[j],
                                         separation=float(G[c] @ v_after), holds=bool(holding[j]),
                                         joined=bool(joined and c == fired)))
        self.loss += kinetic(v) - kinetic(v_after)
        for j, c in enumerate(P):
            if holding[j] and not were_held[j]:
                self.held = sorted(self.held + [c])
                self.hold_rec[c] = len(self.holds)
                self.holds.append(dict(side=c, start=t, release=None, reason=None, impulse=0.0, max_force=0.0))
            elif not holding[j] and were_held[j]:
                self.release(c, t, "separated by an impact")
        y[3:6] = v_after

    # --- the run ------------------------------------------------------------------------------
    def run(self, times, accel):
        self.ag = lambda t: float(np.interp(t, times, accel))
        y = np.zeros(7)
        self.min_open_gap = math.inf  # the smallest open gap on the dense output (a missed closing if < 0)
        self.min_hold_force = math.inf
        self.dips = 0  # closings found from a gap's minimum inside a step
        self.near_miss = math.inf  # the smallest gap at a minimum without contact
        self.margin = dict(hold_velocity=math.inf, hold_height=math.inf, pressing=math.inf)
        self.low_apexes = []  # an apex event at a gap still below ARMED_GAP_M: a flight too low to follow
        for a, b in zip(times[:-1], times[1:]):
            t0 = a
            while b - t0 > 1e-13:
                funcs, tags = self.event_functions(y)
                sol = solve_ivp(self.rhs, (t0, b), y, method=self.method, rtol=self.rtol, atol=self.atol,
                                events=funcs or None, dense_output=True)
                assert sol.status >= 0, sol.message
                t_end = sol.t[-1]
                kinds = []
                if sol.status == 1:
                    hit = [i for i, te in enumerate(sol.t_events) if len(te) and tags[i][0] != "minimum"]
                    first = min(sol.t_events[i][0] for i in hit)
                    kinds = [tags[i] for i in hit if sol.t_events[i][0] <= first + 1e-14]
                # A gap that falls below zero and rises again inside one step has no sign change at
                # the step ends; its minimum (a rising zero of its rate) shows it: the crossing is
                # then found on the dense output, between the step's start and the minimum, and
                # taken as the event.
                for i, tag in enumerate(tags):
                    if tag[0] != "minimum":
                        continue
                    c = tag[1]
                    for tm, ym in zip(sol.t_events[i], sol.y_events[i]):
                        if tm < t_end and D[c] + G[c] @ ym[:3] >= 0.0:
                            self.near_miss = min(self.near_miss, D[c] + G[c] @ ym[:3])
                        if tm < t_end and D[c] + G[c] @ ym[:3] < 0.0:
                            ta = sol.t[max(int(np.searchsorted(sol.t, tm)) - 1, 0)]
                            tc = brentq(lambda t: D[c] + G[c] @ sol.sol(t)[:3], ta, tm, xtol=1e-16, rtol=1e-15)
                            if tc < t_end:
                                t_end, kinds = tc, [("closes", c)]
                                self.dips += 1
                            break
                self.segments.append((t0, t_end, sol.sol, list(self.held)))
                self.sample(sol, t0, t_end)
                y = sol.sol(t_end) if t_end < sol.t[-1] else sol.y[:, -1].copy()
                t0 = t_end
                if not kinds:
                    break
                self.events += 1
                for kind, c in kinds:
                    if kind == "release":
                        self.release(c, t_end, "tensile force")
                for kind, c in kinds:
                    if kind == "closes" and G[c] @ y[3:6] < 0.0:
                        self.impact(t_end, y, c)
                    elif kind == "apex" and D[c] + G[c] @ y[:3] <= ARMED_GAP_M:
                        # A flight lower than ARMED_GAP_M: the pair closes again at once (plastic
                        # with any k); counted, and the scene is chosen to have none.
                        self.low_apexes.append((t_end, c, D[c] + G[c] @ y[:3]))
                        self.impact(t_end, y, c)
                        if len(self.low_apexes) > 100:
                            raise RuntimeError(f"peer: flights of no height repeat at {t_end} s")
                self.settle(t_end, y)
        self.y_end = y
        for c in list(self.held):
            self.release(c, times[-1], "end of run")
        x, v = y[:3], y[3:6]
        self.energy = dict(input=y[6], kinetic=kinetic(v), strain=0.5 * float(np.dot(STIFFNESS, x * x)),
                           impact_loss=self.loss)
        self.energy["residual"] = (self.energy["input"] - self.energy["kinetic"] - self.energy["strain"]
                                   - self.energy["impact_loss"])
        return self

    def sample(self, sol, t0, t1):
        """Open gaps and hold forces on the dense output, 8 points a step, up to t1."""
        if t1 <= t0:
            return
        steps = np.concatenate([sol.t[sol.t < t1], [t1]])
        ts = np.unique(np.concatenate([np.linspace(p, q, 8, endpoint=False) for p, q in zip(steps[:-1], steps[1:])]
                                      + [[t1]]))
        ys = sol.sol(ts)
        for c in (0, 1):
            if c in self.held:
                S = list(self.held)
                r = S.index(c)
                f = np.array([self.hold_forces(self.free_acceleration(t, ys[:3, i]), S)[r] for i, t in enumerate(ts)])
                rec = self.holds[self.hold_rec[c]]
                rec["max_force"] = max(rec["max_force"], float(np.max(f)))
                if len(f) > 2:
                    self.min_hold_force = min(self.min_hold_force, float(np.min(f[1:-1])))
            elif self.contact:
                g = D[c] + G[c] @ ys[:3]
                if len(g) > 2:
                    self.min_open_gap = min(self.min_open_gap, float(np.min(g[1:-1])))

    def at(self, ts):
        starts = np.array([s[0] for s in self.segments])
        out = []
        for t in ts:
            k = max(int(np.searchsorted(starts, t, side="right")) - 1, 0)
            t0, t1, sol, _ = self.segments[k]
            out.append(sol(min(max(t, t0), t1))[:3])
        return np.array(out)


def exact_free(times, accel, out_times):
    """Each storey alone, undamped, exactly over each linear piece of the record:
    x'' + w^2 x = -(a0 + s tau) has x_p = -(a0 + s tau)/w^2, x_p' = -s/w^2."""
    w = np.sqrt(STIFFNESS / MASS)
    x, v = np.zeros(3), np.zeros(3)
    rows, k = [], 0

    def advance(x, v, a0, s, tau):
        xp0, vp = -a0 / w ** 2, -s / w ** 2
        c1, c2 = x - xp0, (v - vp) / w
        xt = c1 * np.cos(w * tau) + c2 * np.sin(w * tau) - (a0 + s * tau) / w ** 2
        vt = -c1 * w * np.sin(w * tau) + c2 * w * np.cos(w * tau) + vp
        return xt, vt
    for i in range(len(times) - 1):
        a, b = times[i], times[i + 1]
        s = (accel[i + 1] - accel[i]) / (b - a)
        while k < len(out_times) and out_times[k] <= b:
            rows.append(advance(x, v, accel[i], s, out_times[k] - a)[0])
            k += 1
        x, v = advance(x, v, accel[i], s, b - a)
    return np.array(rows)


# --- the program ----------------------------------------------------------------------------------
def run_program(program, folder, accel, restitution, options):
    """Writes the record and the scene into folder and runs it; (history times, u v phi of the three
    slabs, impacts.csv rows by onset, summary.json), or None and the program's message."""
    cols = [f"{n}_f1_{c}" for n in NAMES for c in ("u_m", "v_m", "phi_rad")]
    run, message = program_run.run_scene(program, folder, lambda record: scene_text(record, restitution), accel,
                                         options, cols, record_name="record.txt")
    return (None, message) if run is None else ((run.t, run.q, run.impacts, run.summary), None)


def program_side(buildings):
    """The peer's side (0 B1:B2, 1 B2:B3) of a pair of 1-based building numbers."""
    return {(1, 2): 0, (2, 3): 1}.get(tuple(sorted(buildings)))


def group_program(summary, impacts, failures, name):
    """The program's impacts and sustained contacts with the two coincident corners of a side
    summed: impacts (t, side, impulse, approach, separation, holds) per instant and side, holds
    (side, start, release, reason, impulse share, twins' release spread) per side and start."""
    levels = {lv["level"]: program_side(lv["buildings"]) for lv in summary["levels"]}
    if sorted(levels.items()) != [(1, 0), (2, 1)]:
        failures.append(f"{name}: levels {summary['levels']}, expected B1:B2 and B2:B3 at 3 m")
        return [], []
    groups = {}
    for r in impacts:
        side = levels[int(r["level"])]
        if program_side((int(r["striking_building"]), int(r["struck_building"]))) != side:
            failures.append(f"{name}: impact at {r['t_s']} s on level {r['level']} between buildings "
                            f"{r['striking_building']} and {r['struck_building']}")
        corner = (int(r["striking_building"]), int(r["vertex"]), int(r["struck_edge"]))
        if corner not in ((1, 2, 4), (1, 3, 4), (3, 1, 2), (3, 4, 2)):
            failures.append(f"{name}: impact at {r['t_s']} s: building {corner[0]} vertex {corner[1]} on edge "
                            f"{corner[2]}, not a face contact of the scene")
        groups.setdefault((side, float(r["t_s"])), []).append(r)
    out = []
    for (side, t), rows in sorted(groups.items(), key=lambda kv: kv[0][1]):
        if len(rows) != 2:
            failures.append(f"{name}: {len(rows)} impact rows at {t!r} s on {SIDES[side]} (two coincident corners)")
        out.append(dict(t=t, side=side, impulse=sum(float(r["impulse_kNs"]) for r in rows),
                        approach=float(rows[0]["approach_velocity_mps"]),
                        separation=float(rows[0]["separation_velocity_mps"]),
                        holds=all(r["starts_sustained_contact"] in ("1", "true") for r in rows)))
    hgroups = {}
    for h in summary["sustained_contacts"]:
        hgroups.setdefault((program_side(h["buildings"]), h["start_s"]), []).append(h)
    holds = []
    for (side, start), rows in sorted(hgroups.items(), key=lambda kv: kv[0][1]):
        releases = [h["release_s"] for h in rows]
        reasons = {h["release_reason"] for h in rows}
        if len(rows) != 2 or len(reasons) != 1:
            failures.append(f"{name}: hold from {start!r} s on {SIDES[side]}: {len(rows)} records, releases "
                            f"{releases}, reasons {reasons}")
        holds.append(dict(side=side, start=start, release=min(releases), spread=max(releases) - min(releases),
                          reason=rows[0]["release_reason"], impulse=sum(h["impulse_kNs"] for h in rows)))
    return out, holds


def program_joined(impacts, holds):
    """The program's impacts on one side of B2 while a hold on the other side, begun before, lasts."""
    return [i for i in impacts if any(h["side"] != i["side"] and h["start"] < i["t"] - 1e-12 <= h["release"]
                                      for h in holds)]


def compare_events(peer_list, prog_list, keys):
    """Peer and program events matched one to one per side in time order: the largest absolute
    difference of each key, and what does not match (counts, booleans, strings)."""
    d, problems = {k: 0.0 for k in keys}, []
    for side in (0, 1):
        a = [e for e in peer_list if e["side"] == side]
        b = [e for e in prog_list if e["side"] == side]
        first = next((i for i in range(min(len(a), len(b))) if abs(a[i][keys[0]] - b[i][keys[0]]) > 1e-6), None)
        if len(a) != len(b) or first is not None:
            first = min(len(a), len(b)) if first is None else first
            problems.append(f"{SIDES[side]}: the peer has {len(a)}, the program {len(b)}; first difference at "
                            f"#{first + 1}: peer {a[first] if first < len(a) else None}, program "
                            f"{b[first] if first < len(b) else None}")
            continue
        for e, f in zip(a, b):
            for k in keys:
                if isinstance(e[k], (bool, str)):
                    if e[k] != f[k]:
                        problems.append(f"{SIDES[side]} at {e[keys[0]]:.9f} s: {k} {f[k]!r}, the peer's {e[k]!r}")
                else:
                    d[k] = max(d[k], abs(f[k] - e[k]))
    return d, problems


# Program runs (options) and, per restitution and run, the limits (measured values in the docstring):
# impacts: t (s), impulse (kN s), approach and separation (m/s); holds: start and release (s), impulse
# share (kN s); u (m); |v|, |phi| (m, rad); energy terms over the input; relative residual.
RUNS = {
    "cvode-bdf": ["--method", "cvode-bdf", "--rtol", "1e-12", "--atol", "1e-14"],
    "arkode-erk": ["--method", "arkode-erk", "--rtol", "1e-12", "--atol", "1e-14"],
    "exact": ["--method", "exact"],
}
LIMITS = {
    (0.0, "cvode-bdf"): dict(t=3e-9, impulse=1e-6, approach=1e-8, separation=1e-12, start=3e-9, release=2e-9,
                             share=5e-8, u=5e-10, vphi=1e-14, energy=5e-9, residual=5e-9, spread=1e-10),
    (0.0, "arkode-erk"): dict(t=5e-10, impulse=5e-8, approach=5e-10, separation=1e-12, start=5e-10, release=1e-11,
                              share=5e-10, u=2e-12, vphi=1e-14, energy=3e-11, residual=3e-11, spread=1e-10),
    (0.5, "cvode-bdf"): dict(t=2e-6, impulse=3e-4, approach=2e-6, separation=1e-6, start=3e-8, release=1e-8,
                             share=5e-6, u=3e-7, vphi=1e-14, energy=1e-7, residual=5e-9, spread=1e-10),
    (0.0, "exact"): dict(t=1e-9, impulse=1e-6, approach=1e-8, separation=1e-12, start=1e-9, release=5e-10,
                         share=2e-8, u=2e-10, vphi=1e-14, energy=3e-9, residual=3e-9, spread=1e-10),
    (0.5, "exact"): dict(t=1e-7, impulse=2e-5, approach=1e-7, separation=6e-8, start=2e-9, release=5e-10,
                         share=3e-7, u=2e-8, vphi=1e-14, energy=6e-9, residual=2e-10, spread=1e-10),
    (0.5, "arkode-erk"): dict(t=3e-9, impulse=5e-7, approach=3e-9, separation=2e-9, start=1e-10, release=2e-11,
                              share=1e-8, u=5e-10, vphi=1e-14, energy=2e-10, residual=3e-11, spread=1e-10),
}
# Radau at rtol 1e-11 against DOP853 at 1e-13, per restitution: instants (s), impulses (kN s), speeds (m/s).
PEER_LIMITS = {0.0: dict(t=5e-11, impulse=5e-9, approach=5e-11), 0.5: dict(t=2e-8, impulse=5e-6, approach=3e-8)}
RESTITUTIONS = (0.0, 0.5)


def check_program(program, out, label, peer, accel, restitution, failures):
    """Check 3 (and 4) at one program method against the peer of that restitution."""
    name = f"k = {restitution}, {label}"
    tol = LIMITS[(restitution, label)]
    result, error = run_program(program, out / f"k{restitution}-{label}", accel, restitution, RUNS[label])
    if result is None:
        failures.append(f"{name}: the program failed: {error}")
        return
    t_out, q, impacts, summary = result
    if summary["status"] != "completed" or abs(summary["end_s"] - DURATION_S) > 1e-12:
        failures.append(f"{name}: status {summary['status']} ({summary.get('status_detail')}), "
                        f"end {summary['end_s']} s")
    prog_impacts, prog_holds = group_program(summary, impacts, failures, name)
    joined = program_joined(prog_impacts, prog_holds)
    peer_joined = [i for i in peer.impacts if i["joined"]]
    print(f"{name}: {len(prog_impacts)} impact instants ({sum(i['side'] == 0 for i in prog_impacts)} on B1:B2), "
          f"{len(prog_holds)} holds, {len(joined)} impacts while the other side of B2 is held: "
          + ", ".join(f"{j['t']:.4f} s {SIDES[j['side']]}" for j in joined))
    if len(joined) < 3 or len(joined) != len(peer_joined) or any(
            abs(a["t"] - b["t"]) > 1e-6 or a["side"] != b["side"] for a, b in zip(joined, peer_joined)):
        failures.append(f"{name}: joined impacts at {[round(j['t'], 6) for j in joined]}, the peer's at "
                        f"{[round(j['t'], 6) for j in peer_joined]} (at least 3 expected)")
    d_imp, bad = compare_events(peer.impacts, prog_impacts, ["t", "impulse", "approach", "separation", "holds"])
    failures.extend(f"{name}: impacts: {b}" for b in bad)
    peer_holds = [dict(h, share=h["impulse"]) for h in peer.holds]
    d_hold, bad = compare_events(peer_holds, [dict(h, share=h["impulse"]) for h in prog_holds],
                                 ["start", "release", "share", "reason"])
    failures.extend(f"{name}: holds: {b}" for b in bad)
    spread = max([h["spread"] for h in prog_holds] or [0.0])
    print(f"   {'t_s':>12} {'side':>5} {'approach':>9} {'dt':>9} {'dI kNs':>9} {'dv0 m/s':>9} {'holds':>5} "
          f"{'joined':>6}")
    prog_by_side = {s: [i for i in prog_impacts if i["side"] == s] for s in (0, 1)}
    peer_by_side = {s: [i for i in peer.impacts if i["side"] == s] for s in (0, 1)}
    for e in peer.impacts:
        k = peer_by_side[e["side"]].index(e)
        f = prog_by_side[e["side"]][k] if k < len(prog_by_side[e["side"]]) else None
        diffs = (f"{f['t'] - e['t']:9.1e} {f['impulse'] - e['impulse']:9.1e} {f['approach'] - e['approach']:9.1e}"
                 if f else f"{'(none)':>29}")
        print(f"   {e['t']:12.9f} {SIDES[e['side']]:>5} {e['approach']:9.6f} {diffs} {str(e['holds']):>5} "
              f"{str(e['joined']):>6}")
    peer_q = peer.at(t_out)
    du = float(np.max(np.abs(q[:, 0::3] - peer_q)))
    dvphi = float(np.max(np.abs(q[:, [1, 2, 4, 5, 7, 8]])))
    e = summary["energy"]
    de = max(abs(e[pk] - peer.energy[k]) for k, pk in (("input", "input_kJ"), ("kinetic", "kinetic_final_kJ"),
             ("strain", "strain_final_kJ"), ("impact_loss", "impact_loss_kJ"))) / peer.energy["input"]
    de = max(de, abs(e["damping_kJ"]) / peer.energy["input"], abs(e["constraint_work_kJ"]) / peer.energy["input"])
    print(f"{name}: largest differences: impacts: t {d_imp['t']:.1e} s, impulse {d_imp['impulse']:.1e} kN s, approach "
          f"{d_imp['approach']:.1e} m/s, separation {d_imp['separation']:.1e} m/s; holds: start "
          f"{d_hold['start']:.1e} s, "
          f"release {d_hold['release']:.1e} s, impulse share {d_hold['share']:.1e} kN s (the twin corners' releases "
          f"{spread:.1e} s apart); u {du:.1e} m over {len(t_out)} rows, |v|, |phi| {dvphi:.1e}; energy terms "
          f"{de:.1e} of the input ({e['input_kJ']:.3f} kJ, impact loss {e['impact_loss_kJ']:.3f} kJ, constraint work "
          f"{e['constraint_work_kJ']:.1e} kJ), relative residual {e['relative_residual']:.1e}")
    measured = dict(t=d_imp["t"], impulse=d_imp["impulse"], approach=d_imp["approach"],
                    separation=d_imp["separation"], start=d_hold["start"], release=d_hold["release"],
                    share=d_hold["share"], u=du, vphi=dvphi, energy=de, residual=abs(e["relative_residual"]),
                    spread=spread)
    for key, value in measured.items():
        if value > tol[key]:
            failures.append(f"{name}: {key} differs by {value:.2e} (limit {tol[key]:.0e})")


def check_modes(program, out, accel, failures):
    """The peer's storey stiffness 9 * 12 E I / H^3 gives the program's x-mode periods."""
    folder = out / "modes"
    folder.mkdir(parents=True, exist_ok=True)
    (folder / "record.txt").write_text("\n".join(f"{a!r}" for a in accel) + "\n")
    (folder / "scene.toml").write_text(scene_text(folder / "record.txt", 0.0))
    run = subprocess.run([program, "modes", str(folder / "scene.toml"), "--json", str(folder / "modes.json")],
                         capture_output=True, text=True)
    if run.returncode != 0:
        failures.append(f"modes: exit {run.returncode}: {run.stderr.strip()[-300:]}")
        return
    modes = json.loads((folder / "modes.json").read_text())["buildings"]
    worst = 0.0
    for b, m, k in zip(modes, MASS, STIFFNESS):
        x = [mode["period_s"] for mode in b["modes"] if mode["dominant"] == "x"]
        worst = max(worst, abs(x[0] / (2 * math.pi * math.sqrt(m / k)) - 1.0) if len(x) == 1 else math.inf)
        if abs(b["rayleigh"]["a0_per_s"]) + abs(b["rayleigh"]["a1_s"]) != 0.0:
            failures.append(f"modes: {b['name']} has damping {b['rayleigh']}")
    print(f"x-mode periods {', '.join(f'{2 * math.pi * math.sqrt(m / k):.6f}' for m, k in zip(MASS, STIFFNESS))} s; "
          f"the program's within {worst:.1e}")
    if worst > 1e-9:
        failures.append(f"modes: the program's x periods differ from 2 pi sqrt(m / k) by {worst:.1e}")


def check_peer(times, accel, restitution, failures):
    """Checks 1 and 2: the peer's energy balance; Radau finds what DOP853 finds; the scene makes
    what it is for. Returns the peer (DOP853)."""
    peer = Peer(restitution).run(times, accel)
    e = peer.energy
    rel = abs(e["residual"]) / e["input"]
    sides = [sum(i["side"] == s for i in peer.impacts) for s in (0, 1)]
    joined = [i for i in peer.impacts if i["joined"]]
    print(f"peer, k = {restitution}: {sides[0]} impacts B1:B2, {sides[1]} B2:B3, {len(peer.holds)} holds, "
          f"{len(joined)} joined (B1 striking B2 while B2 is held against B3) at "
          + ", ".join(f"{i['t']:.4f}" for i in joined)
          + f" s; approach speeds {min(i['approach'] for i in peer.impacts):.2e} to "
          f"{max(i['approach'] for i in peer.impacts):.2f} m/s; energy input {e['input']:.3f} kJ, impact loss "
          f"{e['impact_loss']:.3f}, residual {rel:.1e} of the input; closest approach without contact "
          f"{peer.near_miss:.1e} m, smallest open gap {peer.min_open_gap:.1e} m, smallest hold force "
          f"{peer.min_hold_force:.1e} kN; decisions: speed {peer.margin['hold_velocity']:.2f} from "
          f"hold_velocity_mps, apex {peer.margin['hold_height']:.2f} from hold_height_m, force "
          f"{peer.margin['pressing']:.1e} from zero (of the accelerations); dips found "
          f"inside a step {peer.dips}, flights lower than {ARMED_GAP_M} m {len(peer.low_apexes)}")
    # What one impact problem per floor pair would give the joined impacts: the struck pair alone.
    pair_alone = [(1 + restitution) * i["approach"] / (1 / MASS[i["side"]] + 1 / MASS[i["side"] + 1]) for i in joined]
    alone = min([abs(i["impulse"] / p - 1.0) for i, p in zip(joined, pair_alone)] or [0.0])
    print(f"peer, k = {restitution}: the joined impacts' impulses differ from the struck pair's alone by at least "
          f"{alone:.1%}")
    if rel > 1e-11:
        failures.append(f"peer, k = {restitution}: the energy balance does not close ({rel:.1e})")
    if alone < 0.01:
        failures.append(f"peer, k = {restitution}: the joined impacts do not tell one impact problem from a pair's")
    if (min(sides) < 5 or len(joined) < 3 or peer.low_apexes or peer.min_open_gap < -1e-12 or peer.near_miss < 1e-5
            or peer.margin["hold_velocity"] < 0.05 or peer.margin["hold_height"] < 0.05
            or peer.margin["pressing"] < 1e-3 or peer.min_hold_force <= 0.0):
        failures.append(f"peer, k = {restitution}: the scene no longer makes what it was chosen for")
    other = Peer(restitution, method="Radau", rtol=1e-11, atol=1e-13).run(times, accel)
    d_imp, bad = compare_events(peer.impacts, other.impacts, ["t", "impulse", "approach", "holds", "joined"])
    d_hold, bad2 = compare_events(peer.holds, other.holds, ["start", "release", "impulse", "reason"])
    print(f"peer, k = {restitution}, Radau at rtol 1e-11 against DOP853 at 1e-13: impacts {d_imp['t']:.1e} s, "
          f"{d_imp['impulse']:.1e} kN s, {d_imp['approach']:.1e} m/s; holds {d_hold['start']:.1e} s, "
          f"{d_hold['release']:.1e} s, {d_hold['impulse']:.1e} kN s")
    lim = PEER_LIMITS[restitution]
    if bad or bad2 or max(d_imp["t"], d_hold["start"], d_hold["release"]) > lim["t"] or max(
            d_imp["impulse"], d_hold["impulse"]) > lim["impulse"] or d_imp["approach"] > lim["approach"]:
        failures.append(f"peer, k = {restitution}: Radau and DOP853 disagree: {bad + bad2}")
    return peer


def check_free(times, accel, failures):
    """Check 1: without contact the peer is the exact motion."""
    t_out = np.arange(round(DURATION_S / 0.01) + 1) * 0.01
    free = Peer(contact=False).run(times, accel)
    d = float(np.max(np.abs(free.at(t_out) - exact_free(times, accel, t_out))))
    print(f"peer without contact against the exact motion: largest |u| difference {d:.1e} m; energy residual "
          f"{free.energy['residual']:.1e} kJ of {free.energy['input']:.1f}")
    if d > 1e-12 or abs(free.energy["residual"]) > 1e-11 * free.energy["input"]:
        failures.append("peer: the contact-free motion is not the exact one")


def main():
    started = time.time()
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    out.mkdir(parents=True, exist_ok=True)
    times, accel = record()
    failures = []
    check_modes(program, out, accel, failures)
    check_free(times, accel, failures)
    for restitution in RESTITUTIONS:
        peer = check_peer(times, accel, restitution, failures)
        for label in RUNS:
            check_program(program, out, label, peer, accel, restitution, failures)
    program_run.finish(failures, started)


if __name__ == "__main__":
    main()
