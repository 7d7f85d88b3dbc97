#!/usr/bin/python3
"""IMK peak-oriented and pinching columns against an independent computation (scipy with events, no
code shared).

    tests/solvers/test_imk_scipy.py POUNDING [OUT]

A one-storey building (3.5 m, 800 t, slab 10 x 8 m, centre of mass at (6, 4), 1 m off the plan
centre along x) on two column lines of different size at the same yield drift ratio (0.4 %, d_y =
14 mm): 0.60 m square columns at y = 0 (x = 0 and 10 m), 0.35 m ones at y = 8 m, so the x springs'
yield forces differ 8.6-fold, the stiffness centre sits near y = 0 and the slab twists under x
shaking (u, v and phi coupled). Every column spring (x and y, 8 in all) follows the
`imk-peak-oriented` law (the `imk-pinching` one in the fourth case); the record is three cycles of a
1.7 m/s2 sine of period 0.45 s along x, then free vibration to 4 s (several reversals and new
excursions per spring, up to 16). A second, elastic building stands 10 m away (no contact). Four
cases, all with Lamda_S, Lamda_C, Lamda_A, Lamda_K on (0.4, 0.5, 0.8, 0.6 m), c_C = 1.1, c_A = 1.2,
D_neg = 0.9 and unequal sides:
  deteriorating:  Up 0.03 / 0.035 m, Upc 0.12 / 0.10 m: every spring yields, none reaches its cap;
                  the yield force falls to 84 % and K_unload to 80 % of the initial;
  post-capping:   Up 0.012 / 0.01 m, Upc 0.012 / 0.0225 m, FresFy 0.25 / 0.35: the small columns'
                  x springs pass their capping points and reach the residual branch on both sides;
  ultimate-drift: deteriorating with Uu 0.035 / 0.045 m: the small columns' x springs fail moving
                  out past 0.035 m (at 0.936 s) and carry no force afterwards;
  pinching:       deteriorating with law = "imk-pinching", kappaF 0.4, kappaD 0.5: all 98 new
                  excursions reload towards a pinching point (their u0 lies before it); of these
                  and the two re-entries below, 52 reach it and go on, 10 to a local peak (2 -> 3,
                  12 -> 13), 42 to the global one; the yield force falls to 88 % and K_unload to
                  85 % of the initial. The large columns' x
                  springs (columns[1] and [2]) also take the branch 1 -> 12 at 2.471 s, in the free
                  vibration: on branch 12 from u0 = +0.089 mm towards the pinching point (-0.973 mm,
                  -33.5 kN) they turn at -0.341 mm (-13.6 kN), unload 0.03 mm and reload past that
                  local peak, back onto the line to the pinching point.
The program runs each with cvode-bdf at rtol 1e-10, atol 1e-12. The peer implements OpenSees'
IMKPeakOriented and IMKPinching (setTrialStrain, revertToStart) itself in the limit of
infinitesimal steps, with the program's stated differences (Lamda = 0: mode off; E_t - E <= 0
where a beta is formed: beta = 1, failure; a failed spring carries nothing; exact transitions, u0
the exact zero-force drift): a state machine per spring over OpenSees' branches 0, 1, 3-7, 13-17
(and 2/12, towards the pinching point, for IMKPinching), each a line F = a + b d, so
    M q'' + C q' + sum_j t_j (a_j + b_j t_j.q) = -M r a_g
is linear between events; it integrates it with scipy's DOP853 (rtol 1e-11, atol 1e-13) over
each record interval, restarting at every event: each spring's drift reaching its branch's bound
(yield, pinching point, local and global peak, cap, residual, the zero force of an unloading
branch, the ultimate drift) and, on a loading branch, its drift rate turning (a reversal), plus any
spring found at its bound at that instant (columns on one line have equal drifts along a
direction). IMKPinching's
rules, from IMKPinching.cpp: at a new excursion U_pinch = (1 - kappaD)(U_global - F_global/K_unload),
F_pinch = kappaF F_global (U_pinch - u0)/(U_global - u0), one point for both sides (the latest
excursion's); if u0 lies before U_pinch, branch 2/12 at F_pinch/(U_pinch - u0), else as
IMKPeakOriented; at U_pinch on to the local peak if it lies ahead, below the global peak, and
(F_local - F_pinch)/(U_local - U_pinch) exceeds the slope to the global peak, else to the global
peak; back at a local peak on the unloading line, to the pinching point if U_local < U_pinch <
U_global, F_local < F_pinch < F_global (signs mirrored on the negative side) and the line to it is
less steep than the one to the global peak, else to the global peak. E_acml is
accumulated exactly (trapezoid on each line), the hysteretic energy is E_acml - F^2/(2 K_unload)
(E_acml once failed), with its own K (12 E I / H^3), Rayleigh fit (modes 1 and 3, 5 %) and
F_y = k d_y. The scenes never reach the reloading guard (a global peak reached more steeply than
K_e or behind u0, from u0 or from a pinching point): the peer raises ReloadGuard there, which fails
the test, and it reports that no reload towards a local peak is steeper than K_e. Checked per case:
  1. u, v, phi at every history row: within 1e-8 m and 2e-9 rad;
  2. per spring (yielding.csv): the stiffness (1e-12 relative), whether and when it first yields
     (1e-7 s), its peak drift (yielded springs: their peaks are reversal instants) and final drift
     within 1e-8 m, final_slip_m = d - F/k within 1e-8 m (the final force), hysteretic_kJ within
     1e-6 relative (of the larger of its own and 1e-3 of the total), yield_count = the entries
     onto the backbone (post-yield, post-capping or residual) from off it, and degrading_failure_t_s present exactly where the
     peer's spring fails, within 1e-7 s;
  3. summary.json: the hysteretic total (1e-6 relative), yield_events = the peer's number of
     transitions (one per spring and event instant), the number of failed springs, and the
     energy audit's relative residual below 1e-6;
  4. the scene does what it is for (from the peer's logs): visible deterioration (yield force and
     K_unload below 90 %) in all but the third, no failure but in the third, post-capping and
     residual branches only in the second; branches 2/12 only in the fourth, where they must be
     visited, go on from a pinching point to a local peak at least once and be re-entered from an
     unloading turned back before the pinching point (1 -> 2|12) at least once.
Measured at these settings: 9.8e-10 m and 2.1e-10 rad in the history, 1.0e-9 m in peak drift,
2.2e-10 m in final drift and slip, 3.8e-7 in hysteretic energy, 1.8e-8 s in first yield, 2.9e-9 s
in failure time, audit residuals 5.6e-8 in the first three cases; in the pinching one 1.8e-9 m and
2.1e-10 rad, 1.2e-9 m in peak drift, 1.3e-9 m in final drift, 1.2e-9 m in slip, 3.1e-7 in
hysteretic energy, 7.7e-9 s in first yield, audit residual 3.4e-8. The history difference falls to
2.2e-11 m (pinching: 3.9e-11 m) and the energy's to 1e-8 (1e-9) with the program at rtol 1e-12
(the program's integration error, not a disagreement). Each parameter matters far beyond the
tolerance: the peer with any one Lamda at 0, or c_C, c_A or D_neg at 1, or FresFy_neg at 0.3,
differs from the program's post-capping run by 6.7e-5 m or more (Lamda_C and the residual only
matter where a cap is passed); from the pinching run, with kappaF 0.41 by 1.9e-4 m, kappaD 0.51 by
9.8e-5 m, always on to the global peak from a pinching point by 1.3e-4 m, without the branch
1 -> 2|12 (back to the global peak instead) by 4.8e-4 m, as the peak-oriented law by 8.9e-3 m.
Before, a self-check of the peer's law alone, driven along prescribed drifts, against numbers
computed by hand (1e-12 relative): the backbone both ways (F_y at F_y/K_e, F_cap at U_y + U_p,
the post-capping slope, F_res past U_res) and its work; one cycle with every mode on: beta_K =
E_i/(E_t - E_pj) and K_unload at the reversal, beta_S = (E_i/(E_t - E_acml))^c_S at the new
excursion, the negative side's F_y, K_p, capping drift (beta_C), global peak (beta_A), the reload
slope, the force, work and hysteretic energy reloading and past the global peak; a partial unloading
retracing its line back onto the backbone; the first reload towards (-U_y, -F_y); failure at the
ultimate drift (no force after, hysteretic = E_acml) and at a new excursion whose energy is spent
(E_t <= E) or whose beta_S exceeds 1; and one pinched cycle (kappaF 0.4, kappaD 0.5, Lamda_K on so
that K_unload < K_e): the pinching point of a side that never yielded (behind zero, U_y - F_y/K_u
< 0), those after yield on each side, the forces towards them and on from them to the global
peak, a partial unloading on branch 12 that reloads past its local peak onto the line to the
pinching point (1 -> 12), a reversal on branch 2, and a reload from a pinching point on to a
local peak ahead (12 -> 13 -> 14), with the work and hysteretic energy along the path and the
branch sequence.
"""
import csv
import sys
import tempfile
import time
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp
from scipy.linalg import eigh

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "support"))
import program_run  # noqa: E402

# ---------------------------------------------------------------------------------------------
# The law: OpenSees' IMKPeakOriented (SRC/material/uniaxial/IMKPeakOriented.cpp, setTrialStrain
# and revertToStart) in the limit of infinitesimal steps, and with kappa = (kappaF, kappaD) its
# IMKPinching (IMKPinching.cpp: the same but for the reload targets). Each branch is a straight
# line F(U); leaving it is either U reaching a bound (thresholds()) or, on a backbone branch
# (2..7, 12..17), the drift rate turning (a reversal). Branch numbers are OpenSees':
#   0 elastic, 1 unloading, 2/12 towards the pinching point (IMKPinching only), 3/13 towards the
#   local peak, 4/14 towards the global peak, 5/15 post-yield (towards the capping point),
#   6/16 post-capping, 7/17 residual.
# ---------------------------------------------------------------------------------------------

FAR = 1.0e9  # "no bound"


class ReloadGuard(Exception):
    """The reload target's slope is outside (0, Ke]: the scene would exercise the program's guard,
    which this peer does not implement."""


class Side:
    """One side of the backbone (OpenSees' pos* or neg* variables; the negative side's are negative)."""

    def __init__(self, sign, Ke, Fy, Up, Upc, FmaxFy, FresFy):
        self.s = sign
        Uy0 = Fy / Ke
        Fcap0 = FmaxFy * Fy
        self.Uy, self.Fy = sign * Uy0, sign * Fy
        self.Ucap, self.Fcap = sign * (Uy0 + Up), sign * Fcap0
        self.Ulocal, self.Flocal = self.Uy, self.Fy
        self.Uglobal, self.Fglobal = self.Uy, self.Fy
        self.Fres = sign * Fy * FresFy
        self.Kp = (Fcap0 - Fy) / Up
        self.Kpc = -Fcap0 / Upc
        self.Ures = (self.Fres - self.Fcap) / self.Kpc + self.Ucap


class ImkSpring:
    """One spring's state. U is the drift the law was last moved to, E the work integral E_acml,
    Ed the E_acml of the last new excursion (engDspt)."""

    def __init__(self, Ke, Fy, pos, neg, lamda, c, D_pos, D_neg, kappa=None):
        self.Ke = Ke
        # IMKPinching: (kappaF, kappaD), and its one pinching point (Upinch, Fpinch), shared by both
        # sides, set at every new excursion
        self.kappa = kappa
        self.Upinch = self.Fpinch = 0.0
        self.pinch_resumed = 0  # branch 1 -> 2/12: an unloading turned back at a local peak before the pinching point
        self.Uu = {+1: pos.get("Uu"), -1: neg.get("Uu")}
        self.pos = Side(+1, Ke, Fy, pos["Up"], pos["Upc"], pos["FmaxFy"], pos["FresFy"])
        self.neg = Side(-1, Ke, Fy, neg["Up"], neg["Upc"], neg["FmaxFy"], neg["FresFy"])
        self.ref = {m: lamda[m] * Fy for m in "SCAK"}  # engRef = LAMBDA * posFy_0
        self.c, self.D = c, {+1: D_pos, -1: D_neg}
        self.Kreload = self.Kunload = Ke
        self.E = self.Ed = 0.0
        self.branch, self.failed = 0, False
        self.U, self.Urev, self.Frev = 0.0, 0.0, 0.0
        self.peak = 0.0
        self.first_yield = None  # (drift, branch) of the first yield, set by cross()
        self.log = []  # (what, U, details) of every transition
        self.times = []  # (t, event kind) of every transition (the structural peer)
        self.first_yield_t = self.failed_t = None
        self.betas = []  # (kind, value) of every beta computed
        self.klocal_above_ke = 0
        self.negative_energy_base = 0

    def side(self, s):
        return self.pos if s > 0 else self.neg

    def branch_side(self):
        if self.failed:
            return 0
        return +1 if 2 <= self.branch <= 7 else (-1 if self.branch >= 12 else 0)

    def line(self):
        """(a, b): F = a + b U on the current branch."""
        if self.failed:
            return 0.0, 0.0
        b = self.branch
        if b == 0:
            return 0.0, self.Ke
        if b == 1:
            return self.Frev - self.Kunload * self.Urev, self.Kunload
        sd = self.side(self.branch_side())
        k = b % 10
        if k == 2:
            return self.Fpinch - self.Kreload * self.Upinch, self.Kreload
        if k == 3:
            return sd.Flocal - self.Kreload * sd.Ulocal, self.Kreload
        if k == 4:
            return sd.Fglobal - self.Kreload * sd.Uglobal, self.Kreload
        if k == 5:
            return sd.Fcap - sd.Kp * sd.Ucap, sd.Kp
        if k == 6:
            return sd.Fcap - sd.Kpc * sd.Ucap, sd.Kpc
        return sd.Fres, 0.0

    def force(self, U=None):
        a, b = self.line()
        return a + b * (self.U if U is None else U)

    def thresholds(self):
        """(lo, hi): the drifts at which the current branch ends moving down / up."""
        if self.failed:
            return -FAR, FAR
        b = self.branch
        if b == 0:
            return self.neg.Uy, self.pos.Uy
        if b == 1:
            u0 = self.Urev - self.Frev / self.Kunload
            local = self.side(1 if self.Frev > 0 else -1).Ulocal
            return (u0, local) if self.Frev > 0 else (local, u0)
        s = self.branch_side()
        sd = self.side(s)
        bound = {2: self.Upinch, 3: sd.Ulocal, 4: sd.Uglobal, 5: sd.Ucap, 6: sd.Ures, 7: s * FAR}[b % 10]
        return (-FAR, bound) if s > 0 else (bound, FAR)

    def bounds(self):
        """thresholds() with the ultimate drifts: moving out past +Uu_pos or -Uu_neg the spring fails."""
        lo, hi = self.thresholds()
        if self.failed:
            return lo, hi
        if self.Uu[+1] is not None:
            hi = min(hi, self.Uu[+1])
        if self.Uu[-1] is not None:
            lo = max(lo, -self.Uu[-1])
        return lo, hi

    def advance(self, U):
        """Moves along the current branch to U: E_acml gains the exact work (F is linear in U)."""
        F0, F1 = self.force(self.U), self.force(U)
        self.E += 0.5 * (F0 + F1) * (U - self.U)
        self.U = U
        self.peak = max(self.peak, abs(U))

    def beta(self, kind, Ei, Eref_minus):
        """OpenSees' beta = (Ei / (E_t - E))^c, with the stated differences: Lamda = 0 is off (0),
        a denominator <= 0 is beta = 1 and a failure; beta > 1 fails; clipped to [0, 1]."""
        if self.ref[kind] == 0.0:
            return 0.0, False
        denominator = self.ref[kind] - Eref_minus
        if denominator <= 0.0:
            self.betas.append((kind, 1.0))
            return 1.0, True
        base = Ei / denominator
        if base < 0.0:
            self.negative_energy_base += 1
            value = 0.0
        else:
            value = base ** self.c[kind]
        self.betas.append((kind, value))
        return min(max(value, 0.0), 1.0), value > 1.0

    def fail(self, why):
        self.log.append(("fail", self.U, why))
        self.failed = True

    def enter(self, branch):
        """Goes onto `branch` at the current U and cascades along the backbone while U is at or past
        the next bound (OpenSees' chained checks 2 -> 3|4 -> 4 -> 5 -> 6 -> 7 in one step)."""
        self.branch = branch
        self.log.append(("branch", self.U, branch))
        while not self.failed and self.branch_side() != 0:
            s, sd = self.branch_side(), self.side(self.branch_side())
            k = self.branch % 10
            if k == 7:
                if s * sd.Fres <= 0.0:  # FailRp / FailRn
                    self.fail("residual strength reached at zero")
                break
            lo, hi = self.thresholds()
            bound = hi if s > 0 else lo
            if s * (self.U - bound) < 0.0:
                break
            if k == 2:
                self.branch = self.from_pinch(s)
            else:
                if k == 3:
                    self.Kreload = (sd.Fglobal - sd.Flocal) / (sd.Uglobal - sd.Ulocal)
                self.branch += 1
            self.log.append(("branch", self.U, self.branch))

    def from_pinch(self, s):
        """IMKPinching at the pinching point (Branch 2 -> 3 | 4, 12 -> 13 | 14): on to the local peak
        if it lies ahead, below the global peak, and is reached more steeply than the global peak
        is from the pinching point; else to the global peak. Sets Kreload, returns the branch."""
        sd = self.side(s)
        Kglobal = (sd.Fglobal - self.Fpinch) / (sd.Uglobal - self.Upinch)
        if (s * self.Upinch < s * sd.Ulocal and s * self.Fpinch < s * sd.Flocal and s * sd.Flocal < s * sd.Fglobal
                and (sd.Flocal - self.Fpinch) / (sd.Ulocal - self.Upinch) > Kglobal):
            self.Kreload = (sd.Flocal - self.Fpinch) / (sd.Ulocal - self.Upinch)
            if self.Kreload > self.Ke:
                self.klocal_above_ke += 1
            return 3 if s > 0 else 13
        if not 0.0 < Kglobal <= self.Ke:
            raise ReloadGuard(f"from the pinching point ({self.Upinch}, {self.Fpinch}): Kglobal {Kglobal} "
                              f"(Ke {self.Ke})")
        self.Kreload = Kglobal
        return 4 if s > 0 else 14

    def pinch_ahead(self, s):
        """IMKPinching's Branch 1 -> 2 (12): back at the local peak on the unloading line, the pinching
        point lies between the local and the global peak (drift and force) and the line to it is
        less steep than the one to the global peak."""
        sd = self.side(s)
        if not (s * sd.Ulocal < s * self.Upinch < s * sd.Uglobal and s * sd.Flocal < s * self.Fpinch < s * sd.Fglobal):
            return False
        Kpinch = (self.Fpinch - sd.Flocal) / (self.Upinch - sd.Ulocal)
        return Kpinch < (sd.Fglobal - sd.Flocal) / (sd.Uglobal - sd.Ulocal)

    def cross(self, U, direction):
        """U reached the current branch's bound moving in `direction` (+1 up, -1 down)."""
        self.advance(U)
        if self.Uu[direction] is not None and direction * U >= self.Uu[direction]:  # FailDp / FailDn
            self.fail("ultimate drift")
            return
        b = self.branch
        if b == 0:
            if self.first_yield is None:
                self.first_yield = U
            self.enter(5 if direction > 0 else 15)
        elif b == 1:
            s = 1 if self.Frev > 0 else -1
            if direction == s:  # back at the local peak on the unloading line: towards the global peak
                sd = self.side(s)
                if self.kappa is not None and self.pinch_ahead(s):  # IMKPinching: to the pinching point ahead
                    self.Kreload = (self.Fpinch - sd.Flocal) / (self.Upinch - sd.Ulocal)
                    self.pinch_resumed += 1
                    self.enter(2 if s > 0 else 12)
                    return
                if sd.Uglobal != sd.Ulocal:
                    self.Kreload = (sd.Fglobal - sd.Flocal) / (sd.Uglobal - sd.Ulocal)
                self.enter(4 if s > 0 else 14)
            else:
                self.new_excursion(direction)
        else:
            assert direction == self.branch_side(), (b, direction)
            if b % 10 == 2:
                self.enter(self.from_pinch(direction))
                return
            if b % 10 == 3:
                sd = self.side(direction)
                self.Kreload = (sd.Fglobal - sd.Flocal) / (sd.Uglobal - sd.Ulocal)
            self.enter(b + 1)

    def new_excursion(self, direction):
        """The unloading branch's force reached 0 at u0 = U: the backbone of the side now loaded
        deteriorates (S, C, A) and the reload target is chosen."""
        E = self.E
        Ei = max(0.0, E - self.Ed)
        bS, fS = self.beta("S", Ei, E)
        bC, fC = self.beta("C", Ei, E)
        bA, fA = self.beta("A", Ei, E)
        self.Ed = E
        s, sd, D = direction, self.side(direction), self.D[direction]
        FcapProj = sd.Fcap - sd.Kpc * sd.Ucap
        sd.Fy *= 1.0 - bS * D
        sd.Kp *= 1.0 - bS * D
        FcapProj *= 1.0 - bC * D
        sd.Uglobal *= 1.0 + bA * D
        sd.Uy = sd.Fy / self.Ke
        FyProj = sd.Fy - sd.Kp * sd.Uy
        sd.Ucap = 0.0 if sd.Kp <= sd.Kpc else (FcapProj - FyProj) / (sd.Kp - sd.Kpc)
        sd.Fcap = FyProj + sd.Kp * sd.Ucap
        if s * sd.Uglobal < s * sd.Uy:
            sd.Fglobal = self.Ke * sd.Uglobal
        elif s * sd.Uglobal < s * sd.Ucap:
            sd.Fglobal = sd.Fy + sd.Kp * (sd.Uglobal - sd.Uy)
        else:
            sd.Fglobal = sd.Fcap + sd.Kpc * (sd.Uglobal - sd.Ucap)
        if s * sd.Fglobal < s * sd.Fres:
            sd.Fglobal = sd.Fres
        sd.Ures = (sd.Fres - sd.Fcap + sd.Kpc * sd.Ucap) / sd.Kpc
        u0 = self.Urev - self.Frev / self.Kunload
        self.log.append(("excursion", self.U, dict(u0=u0, side=s, betaS=bS, betaC=bC, betaA=bA)))
        if fS or fC or fA:
            self.fail("beta S, C or A")
            return
        if self.pos.Fglobal == 0.0 or self.neg.Fglobal == 0.0:
            self.fail("global peak force 0")
            return
        Kglobal = sd.Fglobal / (sd.Uglobal - u0)
        Klocal = sd.Flocal / (sd.Ulocal - u0)
        if not 0.0 < Kglobal <= self.Ke:
            raise ReloadGuard(f"Kglobal {Kglobal} (Ke {self.Ke}) at u0 {u0}")
        if self.kappa is not None:  # IMKPinching: the pinching point, on the line from u0 to the global peak
            kappaF, kappaD = self.kappa
            self.Upinch = (1.0 - kappaD) * (sd.Uglobal - sd.Fglobal / self.Kunload)
            self.Fpinch = kappaF * sd.Fglobal * (self.Upinch - u0) / (sd.Uglobal - u0)
            self.log[-1][2].update(Upinch=self.Upinch, Fpinch=self.Fpinch)
            if s * u0 < s * self.Upinch:
                self.Kreload = self.Fpinch / (self.Upinch - u0)
                self.enter(2 if s > 0 else 12)
                return
        if s * u0 < s * sd.Ulocal and s * sd.Flocal < s * sd.Fglobal and Klocal > Kglobal:
            self.Kreload = Klocal
            if Klocal > self.Ke:
                self.klocal_above_ke += 1
            self.enter(3 if s > 0 else 13)
        else:
            self.Kreload = Kglobal
            self.enter(4 if s > 0 else 14)

    def reverse(self, U):
        """The drift rate turned on a backbone branch at U: the peaks are updated, the unloading
        stiffness deteriorates (K) and the spring unloads."""
        self.advance(U)
        F = self.force(U)
        sd = self.side(1 if F > 0 else -1)
        sd.Ulocal, sd.Flocal = U, F
        if sd.s * U > sd.s * sd.Uglobal:
            sd.Uglobal, sd.Fglobal = U, F
        EpjK = self.E - 0.5 * F * F / self.Kunload
        EiK = self.E - self.Ed - 0.5 * F * F / self.Kunload
        bK, fK = self.beta("K", EiK, EpjK)
        self.Kunload *= 1.0 - bK
        self.branch, self.Urev, self.Frev = 1, U, F
        self.log.append(("reversal", U, dict(F=F, betaK=bK, Kunload=self.Kunload)))
        if fK:
            self.fail("beta K")

    def drive(self, target):
        """Moves the drift monotonically from U to target, every branch change exact (the self-check)."""
        if self.failed:
            self.U = target
            return
        if target == self.U:
            return
        direction = 1 if target > self.U else -1
        if self.branch_side() == -direction:
            self.reverse(self.U)
        while not self.failed:
            lo, hi = self.bounds()
            bound = hi if direction > 0 else lo
            if direction * (target - bound) <= 0.0:
                break
            self.cross(bound, direction)
        if not self.failed:
            self.advance(target)
        else:
            self.U = target

    def hysteretic(self):
        """E_acml - F^2 / (2 K_unload); E_acml once failed."""
        if self.failed:
            return self.E
        F = self.force()
        return self.E - 0.5 * F * F / self.Kunload


def self_check(failures):
    """The law alone, driven along prescribed drifts, against numbers computed here by hand."""
    Ke, Fy = 20000.0, 200.0  # Uy = 0.01 m
    side = dict(Up=0.03, Upc=0.10, FmaxFy=1.25, FresFy=0.25)
    off = {m: 0.0 for m in "SCAK"}
    ones = {m: 1.0 for m in "SCAK"}
    Uy, Ucap, Fcap, Fres = 0.01, 0.04, 250.0, 50.0
    Kp, Kpc = (Fcap - Fy) / 0.03, -Fcap / 0.10
    Ures = Ucap + (Fres - Fcap) / Kpc
    worst = 0.0

    def close(value, expected, what):
        nonlocal worst
        error = abs(value - expected) / max(abs(expected), 1e-300)
        worst = max(worst, error)
        if error > 1e-12:
            failures.append(f"self-check: {what} is {value!r}, by hand {expected!r}")

    # 1. the monotonic backbone, both ways, deterioration off
    for s in (1, -1):
        law = ImkSpring(Ke, Fy, side, side, off, ones, 1.0, 1.0)
        for U, F, branch in ((0.5 * Uy, 0.5 * Fy, 0), (Uy, Fy, 0), (0.02, Fy + Kp * 0.01, 5), (Ucap, Fcap, 5),
                             (0.06, Fcap + Kpc * 0.02, 6), (Ures + 0.05, Fres, 7)):
            law.drive(s * U)
            close(law.force(), s * F, f"backbone force at {s * U} m")
            if law.branch != (branch if s > 0 or branch == 0 else branch + 10):
                failures.append(f"self-check: branch {law.branch} at {s * U} m, expected {branch}")
        close(law.E, 0.5 * Fy * Uy + (Fy + Fcap) / 2 * 0.03 + (Fcap + Fres) / 2 * (Ures - Ucap) + Fres * 0.05,
              "work along the backbone")
    # 2. one cycle with deterioration on (c_S = 1.3, c_K = 1, Lamda_S = 2 m, Lamda_K = 3 m, Lamda_C =
    #    2.5 m, Lamda_A = 4 m, D_neg = 0.8): push to 0.025 m, back to -0.015 m
    lamda, c = dict(S=2.0, C=2.5, A=4.0, K=3.0), dict(S=1.3, C=1.1, A=0.9, K=1.0)
    law = ImkSpring(Ke, Fy, side, side, lamda, c, 1.0, 0.8)
    U1 = 0.025
    law.drive(U1)
    F1 = Fy + Kp * (U1 - Uy)
    E1 = 0.5 * Fy * Uy + 0.5 * (Fy + F1) * (U1 - Uy)
    close(law.E, E1, "work to the first peak")
    law.drive(U1 - 1e-3)  # the reversal at U1
    EpK = E1 - 0.5 * F1 * F1 / Ke
    betaK = EpK / (3.0 * Fy - EpK)
    Kun = Ke * (1 - betaK)
    close(law.Kunload, Kun, "K_unload after beta_K = E_i/(E_t - E_pj)")
    u0 = U1 - F1 / Kun
    E0 = E1 - 0.5 * F1 * F1 / Kun  # the work at zero force: the hysteretic energy
    law.drive(-0.004)
    bS, bC, bA = ((E0 / (lamda[m] * Fy - E0)) ** c[m] for m in "SCA")
    close(law.betas[1][1], bS, "beta_S = (E_i/(E_t - E_acml))^c_S at the new excursion")
    neg_Fy = -Fy * (1 - 0.8 * bS)
    neg_Kp = Kp * (1 - 0.8 * bS)
    close(law.neg.Fy, neg_Fy, "negative yield force after beta_S")
    close(law.neg.Kp, neg_Kp, "negative post-yield stiffness after beta_S")
    proj = (-Fcap - Kpc * -Ucap) * (1 - 0.8 * bC)  # the post-capping line's intercept at U = 0
    neg_Uy = neg_Fy / Ke
    neg_Ucap = (proj - (neg_Fy - neg_Kp * neg_Uy)) / (neg_Kp - Kpc)
    close(law.neg.Ucap, neg_Ucap, "negative capping drift after beta_S, beta_C")
    neg_Ug = -Uy * (1 + 0.8 * bA)
    close(law.neg.Uglobal, neg_Ug, "negative global peak drift after beta_A")
    neg_Fg = neg_Fy + neg_Kp * (neg_Ug - neg_Uy)
    close(law.neg.Fglobal, neg_Fg, "negative global peak force")
    Kreload = neg_Fg / (neg_Ug - u0)
    close(law.Kreload, Kreload, "reload slope towards the global peak")
    close(law.force(), Kreload * (-0.004 - u0), "force reloading at -0.004 m")
    E2 = E0 + 0.5 * Kreload * (-0.004 - u0) ** 2
    close(law.E, E2, "work at -0.004 m")
    close(law.hysteretic(), E2 - 0.5 * law.force() ** 2 / Kun, "hysteretic energy at -0.004 m")
    law.drive(-0.015)  # past the global peak: on the deteriorated post-yield branch
    F3 = neg_Fy + neg_Kp * (-0.015 - neg_Uy)
    close(law.force(), F3, "deteriorated post-yield force at -0.015 m")
    E3 = E2 + 0.5 * (Kreload * (-0.004 - u0) + neg_Fg) * (neg_Ug + 0.004) + 0.5 * (neg_Fg + F3) * (-0.015 - neg_Ug)
    close(law.E, E3, "work at -0.015 m")
    # 3. back on the unloading line to the local peak, then towards the global peak and past it
    law2 = ImkSpring(Ke, Fy, side, side, off, ones, 1.0, 1.0)
    for U in (0.02, 0.012, 0.02):  # unload elastically from 0.02 then reload to it: back on the backbone
        law2.drive(U)
    close(law2.force(), Fy + Kp * 0.01, "force back at the local peak after a partial unloading")
    law2.drive(0.03)
    close(law2.force(), Fy + Kp * 0.02, "post-yield force past the peak")
    law2.drive(-0.02)  # new excursion at u0 = 0.03 - F/Ke; first negative excursion: towards -Uy
    u0 = 0.03 - (Fy + Kp * 0.02) / Ke
    close(law2.Kreload, Fy / (Uy + u0), "first negative reload slope, u0 to (-Uy, -Fy)")
    close(law2.force(), -Fy - Kp * 0.01, "negative post-yield force at -0.02 m")
    # 4. failures: the ultimate drift moving out, and the energy spent at a new excursion (E_t <= E:
    #    Lamda_S = 0.01 m, E_t = 2 kJ) or beta_S > 1 (Lamda_S = 0.02 m, E_t = 4 kJ)
    law = ImkSpring(Ke, Fy, dict(side, Uu=0.03), side, off, ones, 1.0, 1.0)
    law.drive(0.029)
    law.drive(0.031)
    close(law.E, 0.5 * Fy * Uy + 0.5 * (Fy + Fy + Kp * 0.02) * 0.02, "work to the ultimate drift")
    if not law.failed or law.force() != 0.0 or law.hysteretic() != law.E:
        failures.append("self-check: the spring does not fail at its ultimate drift, or keeps a force")
    F1 = Fy + Kp * 0.015
    E0 = 0.5 * Fy * Uy + 0.5 * (Fy + F1) * 0.015 - 0.5 * F1 * F1 / Ke  # 2.92 kJ at zero force
    for lamda_s in (0.01, 0.02):
        law = ImkSpring(Ke, Fy, side, side, dict(off, S=lamda_s), ones, 1.0, 1.0)
        law.drive(0.025)
        law.drive(0.0)
        close(law.E, E0, f"work at zero force (Lamda_S = {lamda_s} m)")
        if not law.failed or law.force() != 0.0 or law.log[-1][1] != 0.025 - F1 / Ke:
            failures.append(f"self-check: Lamda_S = {lamda_s} m does not fail at the new excursion at u0")
    # 5. IMKPinching (kappaF = 0.4, kappaD = 0.5) with only Lamda_K on (3 m, c_K = 1, so that K_u < K_e
    #    enters the pinching drift): -0.02, then out to 0.025 (through a pinching point behind zero),
    #    back to -0.002 (before the pinching point), a partial unloading to -0.001 and on to -0.012
    #    (branch 1 -> 12, back on the pinched line), a short excursion to 0.005 (reversing on branch 2)
    #    and out to -0.016 (from the pinching point towards the local peak at -0.012, then the global)
    kF, kD, EtK = 0.4, 0.5, 3.0 * Fy
    law = ImkSpring(Ke, Fy, side, side, dict(off, K=3.0), ones, 1.0, 1.0, kappa=(kF, kD))

    def beta_K(E, Ed, F, Ku):  # (E_i - F^2/2K_u) / (E_t,K - (E - F^2/2K_u)), c_K = 1
        return (E - Ed - 0.5 * F * F / Ku) / (EtK - (E - 0.5 * F * F / Ku))

    def pinch(Ug, Fg, Ku, u0):  # the pinching point and the slope from u0 to it
        Up = (1 - kD) * (Ug - Fg / Ku)
        Fp = kF * Fg * (Up - u0) / (Ug - u0)
        return Up, Fp, Fp / (Up - u0)

    Fa = -Fy - Kp * 0.01  # a. yield on the negative side
    law.drive(-0.02)
    close(law.force(), Fa, "pinching: force at -0.02 m")
    Ea = 0.5 * Fy * Uy + 0.5 * (Fy - Fa) * 0.01
    Ku1 = Ke * (1 - beta_K(Ea, 0.0, Fa, Ke))  # b. the reversal; the positive side never yielded
    u0 = -0.02 - Fa / Ku1
    Ed = Ea - 0.5 * Fa * Fa / Ku1
    Up, Fp, Kpin = pinch(Uy, Fy, Ku1, u0)  # Up < 0: U_y - F_y/K_u with K_u < K_e
    law.drive(-0.004)
    close(law.Kunload, Ku1, "pinching: K_unload after the first reversal")
    close(law.Upinch, Up, "pinching: U_pinch behind zero for a side that never yielded")
    close(law.Fpinch, Fp, "pinching: F_pinch = kappa_F F_global (U_pinch - u0)/(U_global - u0)")
    close(law.force(), Kpin * (-0.004 - u0), "pinching: force at -0.004 m towards the pinching point")
    if law.branch != 2 or not u0 < -0.004 < Up:
        failures.append(f"self-check: pinching: branch {law.branch} at -0.004 m, expected 2 (u0 {u0}, U_pinch {Up})")
    law.drive(0.025)  # past the pinching point towards the global peak (U_y, F_y), then post-yield
    Fb = Fy + Kp * 0.015
    close(law.force(), Fb, "pinching: post-yield force at 0.025 m")
    Eb = Ed + 0.5 * Fp * (Up - u0) + 0.5 * (Fp + Fy) * (Uy - Up) + 0.5 * (Fy + Fb) * (0.025 - Uy)
    close(law.E, Eb, "pinching: work at 0.025 m")
    Ku2 = Ku1 * (1 - beta_K(Eb, Ed, Fb, Ku1))  # c. reversal, new excursion towards (-0.02, Fa)
    u0 = 0.025 - Fb / Ku2
    Ed = Eb - 0.5 * Fb * Fb / Ku2
    Upc, Fpc, Kpc_ = pinch(-0.02, Fa, Ku2, u0)
    law.drive(-0.002)
    Fc = Kpc_ * (-0.002 - u0)
    close(law.Upinch, Upc, "pinching: negative U_pinch = (1 - kappa_D)(U_global - F_global/K_u)")
    close(law.Fpinch, Fpc, "pinching: negative F_pinch")
    close(law.force(), Fc, "pinching: force at -0.002 m towards the pinching point")
    if law.branch != 12 or not Upc < -0.002 < u0:
        failures.append(f"self-check: pinching: branch {law.branch} at -0.002 m, expected 12")
    Ec = Ed + 0.5 * Fc * (-0.002 - u0)
    Ku3 = Ku2 * (1 - beta_K(Ec, Ed, Fc, Ku2))  # d. reversal on branch 12, a partial unloading
    law.drive(-0.001)
    Fd = Fc + Ku3 * 0.001
    close(law.force(), Fd, "pinching: force unloading to -0.001 m")
    if law.branch != 1 or not Fd < 0.0:
        failures.append(f"self-check: pinching: branch {law.branch} at -0.001 m, expected 1 with F < 0")
    law.drive(-0.004)  # e. back past the local peak at -0.002: branch 1 -> 12, on the line to the pinching point
    Kres = (Fpc - Fc) / (Upc + 0.002)
    close(law.Kreload, Kres, "pinching: reload slope from the local peak to the pinching point")
    close(law.force(), Fpc + Kres * (-0.004 - Upc), "pinching: force at -0.004 m after the partial unloading")
    if law.branch != 12 or law.pinch_resumed != 1:
        failures.append(f"self-check: pinching: branch {law.branch} at -0.004 m after the partial unloading "
                        f"({law.pinch_resumed} resumed), expected 12 (once)")
    law.drive(-0.012)  # f. past the pinching point: the local peak (-0.002) lies behind it, towards the global
    K14 = (Fa - Fpc) / (-0.02 - Upc)
    Ff = Fpc + K14 * (-0.012 - Upc)
    close(law.Kreload, K14, "pinching: slope from the pinching point to the global peak")
    close(law.force(), Ff, "pinching: force at -0.012 m")
    Ef = Ec + 0.5 * (Fc + Fpc) * (Upc + 0.002) + 0.5 * (Fpc + Ff) * (-0.012 - Upc)
    close(law.E, Ef, "pinching: work at -0.012 m (the partial unloading returns what it took)")
    Ku4 = Ku3 * (1 - beta_K(Ef, Ed, Ff, Ku3))  # g. reversal at -0.012 (the local peak), out to 0.005
    u0 = -0.012 - Ff / Ku4
    Ed = Ef - 0.5 * Ff * Ff / Ku4
    Upg, Fpg, Kpg = pinch(0.025, Fb, Ku4, u0)
    law.drive(0.005)
    Fg = Kpg * (0.005 - u0)
    close(law.Upinch, Upg, "pinching: U_pinch of the positive side after its yield")
    close(law.Fpinch, Fpg, "pinching: F_pinch of the positive side")
    close(law.force(), Fg, "pinching: force at 0.005 m")
    if law.branch != 2 or not u0 < 0.005 < Upg:
        failures.append(f"self-check: pinching: branch {law.branch} at 0.005 m, expected 2")
    Eg = Ed + 0.5 * Fg * (0.005 - u0)
    Ku5 = Ku4 * (1 - beta_K(Eg, Ed, Fg, Ku4))  # h. reversal on branch 2, out to -0.016
    u0 = 0.005 - Fg / Ku5
    Ed = Eg - 0.5 * Fg * Fg / Ku5
    Uph, Fph, _ = pinch(-0.02, Fa, Ku5, u0)
    Klocal, Kglobal = (Ff - Fph) / (-0.012 - Uph), (Fa - Fph) / (-0.02 - Uph)
    law.drive(-0.016)
    K14 = (Fa - Ff) / (-0.02 + 0.012)
    Fh = Fa + K14 * (-0.016 + 0.02)
    close(law.Upinch, Uph, "pinching: U_pinch of the last excursion")
    close(law.Fpinch, Fph, "pinching: F_pinch of the last excursion")
    close(law.force(), Fh, "pinching: force at -0.016 m, past the local peak")
    Eh = Ed + 0.5 * Fph * (Uph - u0) + 0.5 * (Fph + Ff) * (-0.012 - Uph) + 0.5 * (Ff + Fh) * (-0.004)
    close(law.E, Eh, "pinching: work at -0.016 m")
    close(law.hysteretic(), Eh - 0.5 * Fh * Fh / Ku5, "pinching: hysteretic energy at -0.016 m")
    branches = [x[2] for x in law.log if x[0] == "branch"]
    if not Klocal > Kglobal or branches != [15, 2, 4, 5, 12, 12, 14, 2, 12, 13, 14]:
        failures.append(f"self-check: pinching: branches {branches} (Klocal {Klocal}, Kglobal {Kglobal}), expected "
                        f"[15, 2, 4, 5, 12, 12, 14, 2, 12, 13, 14]")
    print(f"self-check: pinching points ({Up:.6g} m, {Fp:.6g} kN), ({Upc:.6g}, {Fpc:.6g}), ({Upg:.6g}, {Fpg:.6g}), "
          f"({Uph:.6g}, {Fph:.6g}); K_u down to {Ku5 / Ke:.4f} K_e")
    print(f"self-check: {len(failures)} failures, largest relative error {worst:.1e} against the hand numbers")


# ---------------------------------------------------------------------------------------------
# The building
# ---------------------------------------------------------------------------------------------

E_KPA, MASS_T, HEIGHT_M = 3.0e7, 800.0, 3.5
SLAB = (0.0, 0.0, 10.0, 8.0)
CM = np.array([6.0, 4.0])
COLUMNS = [((0.0, 0.0), 0.60), ((10.0, 0.0), 0.60), ((0.0, 8.0), 0.35), ((10.0, 8.0), 0.35)]
YIELD_RATIO, ZETA = 0.004, 0.05
PULSE_MPS2, PULSE_PERIOD_S, PULSE_CYCLES, DT_S, DURATION_S = 1.7, 0.45, 3, 0.005, 4.0
LAW_KEYS = ("Up_pos", "Upc_pos", "Uu_pos", "FmaxFy_pos", "FresFy_pos", "Up_neg", "Upc_neg", "Uu_neg", "FmaxFy_neg",
            "FresFy_neg",
            "Lamda_S", "Lamda_C", "Lamda_A", "Lamda_K", "c_S", "c_C", "c_A", "c_K", "D_pos", "D_neg",
            "kappaF", "kappaD")
DETERIORATING = dict(Up_pos=0.03, Upc_pos=0.12, FmaxFy_pos=1.15, FresFy_pos=0.3,
                     Up_neg=0.035, Upc_neg=0.10, FmaxFy_neg=1.2, FresFy_neg=0.3,
                     Lamda_S=0.4, Lamda_C=0.5, Lamda_A=0.8, Lamda_K=0.6,
                     c_S=1.0, c_C=1.1, c_A=1.2, c_K=1.0, D_pos=1.0, D_neg=0.9)
CASES = {
    # every spring stays before its capping point (the small x columns reach 0.041 m of 0.044 m)
    "deteriorating": DETERIORATING,
    # shorter plastic and post-capping ranges: the small columns' x springs pass their capping point
    # and go on to their residual strength, on both sides
    "post-capping": dict(DETERIORATING, Up_pos=0.012, Up_neg=0.01, Upc_pos=0.012, Upc_neg=0.0225,
                         FresFy_pos=0.25, FresFy_neg=0.35),
    # an ultimate drift: the small columns' x springs fail moving out past 0.035 m and carry nothing after
    "ultimate-drift": dict(DETERIORATING, Uu_pos=0.035, Uu_neg=0.045),
    # IMKPinching: every new excursion reloads first towards a pinching point at 40 % of the force,
    # half-way back from the global peak's plastic drift
    "pinching": dict(DETERIORATING, law="imk-pinching", kappaF=0.4, kappaD=0.5),
}


def scene_text(params):
    law = "\n".join(f"{k} = {params[k]!r}" for k in LAW_KEYS if k in params)

    def text(record):
        columns = ", ".join(f"[{x}, {y}, {b}, {b}]" for (x, y), b in COLUMNS)
        x0, y0, x1, y1 = SLAB
        return f"""name = "imk-peer"
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
[building.hysteresis]
law = "{params.get('law', 'imk-peak-oriented')}"
yield_drift_ratio = {YIELD_RATIO}
{law}

[[building]]
name = "E"
storeys = 1
storey_height_m = {HEIGHT_M}
slab = [[20.0, 0.0], [30.0, 0.0], [30.0, 8.0], [20.0, 8.0]]
centre_of_mass = [25.0, 4.0]
mass_t = {MASS_T}
polar_moment_tm2 = "uniform"
E_kPa = {E_KPA}
frame_factor = 1.0
columns = [[20.0, 0.0, 0.5, 0.5], [30.0, 0.0, 0.5, 0.5], [20.0, 8.0, 0.5, 0.5], [30.0, 8.0, 0.5, 0.5]]

[excitation]
file = "{record}"
format = "single"
units = "m/s2"
dt_s = {DT_S}
direction_deg = 0.0

[contact]
gap_m = 10.0
restitution = 0.5

[output.floor_history]
Y = [1]

[solver]
method = "cvode-bdf"
rtol = 1e-10
atol = 1e-12
"""
    return text


def record():
    """PULSE_CYCLES cycles of a sine of period PULSE_PERIOD_S, then zeros to DURATION_S."""
    t = np.arange(0.0, DURATION_S + DT_S / 2, DT_S)
    end = PULSE_CYCLES * PULSE_PERIOD_S
    return t, np.where(t < end, PULSE_MPS2 * np.sin(2 * np.pi * np.minimum(t, end) / PULSE_PERIOD_S), 0.0)


class Peer:
    """The IMK building alone: q = (u, v, phi) of its slab about the CM, one ImkSpring a column and
    direction (x then y, column by column)."""

    def __init__(self, params):
        x0, y0, x1, y1 = SLAB
        a, b = x1 - x0, y1 - y0
        # "uniform": J = m (a^2 + b^2)/12 about the slab's centroid (docs/scene-format.md)
        self.m = np.array([MASS_T, MASS_T, MASS_T * (a * a + b * b) / 12.0])
        p = dict(params)
        pos = dict(Up=p["Up_pos"], Upc=p["Upc_pos"], FmaxFy=p["FmaxFy_pos"], FresFy=p.get("FresFy_pos", 0.0),
                   Uu=p.get("Uu_pos"))
        neg = dict(Up=p.get("Up_neg", pos["Up"]), Upc=p.get("Upc_neg", pos["Upc"]),
                   FmaxFy=p.get("FmaxFy_neg", pos["FmaxFy"]), FresFy=p.get("FresFy_neg", pos["FresFy"]),
                   Uu=p.get("Uu_neg", pos["Uu"]))
        lamda = {m: p.get(f"Lamda_{m}", 0.0) for m in "SCAK"}
        c = {m: p.get(f"c_{m}", 1.0) for m in "SCAK"}
        kappa = (p["kappaF"], p["kappaD"]) if p.get("law") == "imk-pinching" else None
        rows, self.k, self.springs, self.names = [], [], [], []
        for index, ((x, y), size) in enumerate(COLUMNS):
            k = 12.0 * E_KPA * size ** 4 / 12.0 / HEIGHT_M ** 3  # fixed-fixed, square: same along x and y
            arm = np.array([x, y]) - CM
            for direction, row in (("x", [1.0, 0.0, -arm[1]]), ("y", [0.0, 1.0, arm[0]])):
                rows.append(row)
                self.k.append(k)
                self.names.append((f"columns[{index + 1}]", direction))
                self.springs.append(ImkSpring(k, k * YIELD_RATIO * HEIGHT_M, pos, neg, lamda, c,
                                              p.get("D_pos", 1.0), p.get("D_neg", 1.0), kappa))
        self.t, self.k = np.array(rows), np.array(self.k)
        K = (self.t.T * self.k) @ self.t
        w2, _ = eigh(K, np.diag(self.m))
        w = np.sqrt(np.sort(w2))
        self.omega = w
        a0, a1 = 2 * ZETA * w[0] * w[2] / (w[0] + w[2]), 2 * ZETA / (w[0] + w[2])
        self.C = a0 * np.diag(self.m) + a1 * K
        self.r = np.array([1.0, 0.0, 0.0])
        self.events_taken = 0
        self.update_lines()

    def update_lines(self):
        lines = np.array([s.line() for s in self.springs])
        self.a, self.b = lines[:, 0], lines[:, 1]

    def rhs(self, t, y, ag):
        q, qd = y[:3], y[3:]
        force = self.a + self.b * (self.t @ q)
        return np.concatenate([qd, (-self.t.T @ force - self.C @ qd) / self.m - self.r * ag(t)])

    def events(self):
        fs = []
        for j, spring in enumerate(self.springs):
            lo, hi = spring.bounds()
            row = self.t[j]

            def upper(t, y, _ag, row=row, hi=hi):
                return row @ y[:3] - hi

            def lower(t, y, _ag, row=row, lo=lo):
                return row @ y[:3] - lo

            upper.terminal, upper.direction = True, 1
            lower.terminal, lower.direction = True, -1
            s = spring.branch_side()

            def turn(t, y, _ag, row=row, s=s):
                return row @ y[3:] if s != 0 else 1.0

            turn.terminal, turn.direction = True, -s if s != 0 else 0
            fs += [upper, lower, turn]
        return fs

    def move_all(self, y):
        for j, spring in enumerate(self.springs):
            if not spring.failed:
                spring.advance(self.t[j] @ y[:3])

    def run(self, times, accel, out_times):
        ag = lambda t: np.interp(t, times, accel)
        y = np.zeros(6)
        rows, k_out = [], 0
        for a, b in zip(times[:-1], times[1:]):
            t0 = a
            while True:
                sol = solve_ivp(self.rhs, (t0, b), y, method="DOP853", rtol=1e-11, atol=1e-13, events=self.events(),
                                args=(ag,), dense_output=True)
                while k_out < len(out_times) and out_times[k_out] <= sol.t[-1] + 1e-12:
                    rows.append(sol.sol(out_times[k_out])[:3])
                    k_out += 1
                y = sol.y[:, -1]
                self.move_all(y)
                if sol.status != 1:
                    break
                t0 = sol.t[-1]
                fired = [divmod(e, 3) for e, hits in enumerate(sol.t_events) if len(hits) and hits[-1] >= t0 - 1e-15]
                # solve_ivp keeps only the first of simultaneous terminal events (columns on one line along
                # a direction have the same drift): any other spring at its bound, or whose drift rate is
                # at zero, moving on past it, switches too
                acc = self.rhs(t0, y, ag)[3:]
                for j, spring in enumerate(self.springs):
                    d, dd, ddd = self.t[j] @ y[:3], self.t[j] @ y[3:], self.t[j] @ acc
                    lo, hi = spring.bounds()
                    s = spring.branch_side()
                    if abs(d - hi) <= 1e-13 and (dd > 0 or (dd == 0 and ddd > 0)):
                        fired.append((j, 0))
                    elif abs(d - lo) <= 1e-13 and (dd < 0 or (dd == 0 and ddd < 0)):
                        fired.append((j, 1))
                    elif s != 0 and abs(dd) <= 1e-13 and s * ddd < 0:
                        fired.append((j, 2))
                for j, kind in sorted(set(fired)):
                    spring = self.springs[j]
                    if spring.failed:
                        continue
                    if kind == 2:
                        spring.reverse(self.t[j] @ y[:3])
                    else:
                        lo, hi = spring.bounds()
                        spring.cross(hi if kind == 0 else lo, 1 if kind == 0 else -1)
                    spring.times.append((t0, kind))
                    if spring.first_yield is not None and spring.first_yield_t is None:
                        spring.first_yield_t = t0
                    if spring.failed and spring.failed_t is None:
                        spring.failed_t = t0
                    self.events_taken += 1
                self.update_lines()
        self.final = y
        return np.array(rows)


HISTORY = ["B1_f1_u_m", "B1_f1_v_m", "B1_f1_phi_rad"]
LIMITS = dict(u=1e-8, phi=2e-9, peak=1e-8, final=1e-8, slip=1e-8, energy=1e-6, first_yield=1e-7, failure=1e-7,
              residual=1e-6)


def check_case(program, out, label, params, failures):
    """One scene: the program's run against the peer's. Returns the peer."""
    times, accel = record()
    folder = out / label
    run, message = program_run.run_scene(program, folder, scene_text(params), accel, columns=HISTORY)
    if run is None:
        failures.append(f"{label}: {message}")
        return None
    peer = Peer(params)
    peer_q = peer.run(times, accel, run.t)
    du = np.max(np.abs(run.q[:, :2] - peer_q[:, :2]))
    dphi = np.max(np.abs(run.q[:, 2] - peer_q[:, 2]))
    print(f"{label}: largest |u, v| difference {du:.2e} m, |phi| {dphi:.2e} rad over {len(run.t)} rows; peak |u| "
          f"{np.abs(peer_q[:, 0]).max():.4f} m, |v| {np.abs(peer_q[:, 1]).max():.4f} m, |phi| "
          f"{np.abs(peer_q[:, 2]).max():.5f} rad; the peer took {peer.events_taken} law events")
    if du > LIMITS["u"] or dphi > LIMITS["phi"]:
        failures.append(f"{label}: history differs ({du:.2e} m, {dphi:.2e} rad)")
    with open(folder / "run/yielding.csv") as f:
        springs = [r for r in csv.DictReader(f) if r["building"] == "1"]
    if [(r["column"].strip('"'), r["direction"]) for r in springs] != peer.names:
        failures.append(f"{label}: yielding.csv's springs {[(r['column'], r['direction']) for r in springs]} are "
                        f"not the peer's {peer.names}")
        return peer
    total = sum(sp.hysteretic() for sp in peer.springs)
    worst = dict(peak=0.0, final=0.0, slip=0.0, energy=0.0, first_yield=0.0, failure=0.0)
    for row, spring, (name, direction) in zip(springs, peer.springs, peer.names):
        where = f"{label} {name} {direction}"
        d_end = float(peer.t[peer.names.index((name, direction))] @ peer.final[:3])
        if float(row["stiffness_kN_per_m"]) != 0 and abs(float(row["stiffness_kN_per_m"]) / spring.Ke - 1) > 1e-12:
            failures.append(f"{where}: stiffness {row['stiffness_kN_per_m']} kN/m, the peer's {spring.Ke}")
        yielded = spring.first_yield is not None
        if yielded != bool(row["first_yield_t_s"]):
            failures.append(f"{where}: first_yield_t_s '{row['first_yield_t_s']}', the peer "
                            f"{'yields at %.9f s' % spring.first_yield_t if yielded else 'never yields'}")
            continue
        if yielded:
            worst["first_yield"] = max(worst["first_yield"], abs(float(row["first_yield_t_s"]) - spring.first_yield_t))
            # a yielded spring's peak is at a reversal, an event both locate; below yield the program
            # samples its step ends, so an elastic spring's peak is not compared
            worst["peak"] = max(worst["peak"], abs(float(row["peak_drift_m"]) - spring.peak))
        worst["final"] = max(worst["final"], abs(float(row["final_drift_m"]) - d_end))
        # yield_count: the entries onto the backbone (post-yield, post-capping or residual, 5-7 and
        # 15-17) from off it: each yielding phase, wherever on the backbone it begins
        entries, previous = 0, 0
        for what, _, branch in spring.log:
            if what != "branch":
                continue
            entries += branch % 10 in (5, 6, 7) and previous % 10 not in (5, 6, 7)
            previous = branch
        if int(row["yield_count"]) != entries:
            failures.append(f"{where}: yield_count {row['yield_count']}, the peer enters a post-yield branch "
                            f"{entries} times")
        if bool(row.get("degrading_failure_t_s")) != spring.failed:
            failures.append(f"{where}: degrading_failure_t_s '{row.get('degrading_failure_t_s')}', the peer's spring "
                            f"{'fails at %.9f s' % spring.failed_t if spring.failed else 'does not fail'}")
        elif spring.failed:
            worst["failure"] = max(worst["failure"], abs(float(row["degrading_failure_t_s"]) - spring.failed_t))
        slip = d_end - spring.force(d_end) / spring.Ke
        worst["slip"] = max(worst["slip"], abs(float(row["final_slip_m"]) - slip))
        energy = spring.hysteretic()
        worst["energy"] = max(worst["energy"], abs(float(row["hysteretic_kJ"]) - energy) / max(energy, 1e-3 * total))
    energy = run.summary["energy"]
    print(f"  {sum(sp.first_yield is not None for sp in peer.springs)} of {len(springs)} springs yielded; "
          f"differences: peak drift {worst['peak']:.1e} m, final drift {worst['final']:.1e} m, final slip "
          f"{worst['slip']:.1e} m, hysteretic energy {worst['energy']:.1e} relative; first yield "
          f"{worst['first_yield']:.1e} s, failure {worst['failure']:.1e} s; hysteretic "
          f"{energy['hysteretic_kJ']:.6f} kJ, peer {total:.6f} kJ; audit residual {energy['relative_residual']:.2e}")
    for name in ("peak", "final", "slip", "energy", "first_yield", "failure"):
        if worst[name] > LIMITS[name]:
            failures.append(f"{label}: {name} differs by {worst[name]:.2e} (limit {LIMITS[name]:g})")
    if abs(energy["hysteretic_kJ"] - total) > LIMITS["energy"] * total:
        failures.append(f"{label}: hysteretic energy {energy['hysteretic_kJ']} kJ, the peer's {total} kJ")
    yielding = run.summary["yielding"]
    print(f"  law events: program {yielding['yield_events']}, peer {peer.events_taken}; degrading failures "
          f"{yielding['buildings'][0]['storeys'][0]['degrading']['failures']}")
    if yielding["yield_events"] != peer.events_taken:
        failures.append(f"{label}: {yielding['yield_events']} law events, the peer {peer.events_taken}")
    failed, reported = sum(sp.failed for sp in peer.springs), yielding["buildings"][0]["storeys"][0]["degrading"]
    if reported["failures"] != failed:
        failures.append(f"{label}: the program reports {reported['failures']} failed springs, the peer {failed}")
    if abs(energy["relative_residual"]) > LIMITS["residual"]:
        failures.append(f"{label}: the energy audit's relative residual is {energy['relative_residual']:.2e}")
    return peer


def describe(label, peer, failures):
    """What the scene exercises (from the peer's own logs): the deterioration must be visible, no spring
    may fail, the post-capping case must reach a post-capping branch while the others must not, and the
    pinching case must visit branches 2 and 12, go on from a pinching point to a local peak and turn
    back at a local peak before a pinching point (branch 1 -> 2|12)."""
    strength = min(min(sp.pos.Fy / (sp.Ke * YIELD_RATIO * HEIGHT_M), -sp.neg.Fy / (sp.Ke * YIELD_RATIO * HEIGHT_M))
                   for sp in peer.springs)
    unloading = min(sp.Kunload / sp.Ke for sp in peer.springs)
    capped = [n for n, sp in zip(peer.names, peer.springs) if any(x[0] == "branch" and x[2] % 10 == 6 for x in sp.log)]
    residual = sorted({x[2] for sp in peer.springs for x in sp.log if x[0] == "branch" and x[2] % 10 == 7})
    excursions = max(sum(x[0] == "excursion" for x in sp.log) for sp in peer.springs)
    kinds = sorted({x[2] for sp in peer.springs for x in sp.log if x[0] == "branch"})
    print(f"  peer: branches visited {kinds}; up to {excursions} new excursions a spring; yield force down to "
          f"{100 * strength:.1f} %, unloading stiffness to {100 * unloading:.1f} % of the initial; "
          f"post-capping: {capped or 'none'}; reloads towards a local peak steeper than K_e: "
          f"{sum(sp.klocal_above_ke for sp in peer.springs)}, beta_K bases below 0 (beta_K = 0): "
          f"{sum(sp.negative_energy_base for sp in peer.springs)}")
    failed = [n for n, sp in zip(peer.names, peer.springs) if sp.failed]
    if failed != ([("columns[3]", "x"), ("columns[4]", "x")] if label == "ultimate-drift" else []):
        failures.append(f"{label}: the peer's failed springs are {failed}")
    if label != "ultimate-drift" and (strength > 0.9 or unloading > 0.9):
        failures.append(f"{label}: the deterioration is not visible (yield force {strength}, K_unload {unloading})")
    if failed:
        print(f"  peer: {failed} fail at {[sp.failed_t for sp in peer.springs if sp.failed]} s "
              f"({[x[2] for sp in peer.springs for x in sp.log if x[0] == 'fail']})")
    if bool(capped) != (label == "post-capping") or residual != ([7, 17] if label == "post-capping" else []):
        failures.append(f"{label}: post-capping springs {capped}, residual branches {residual}")
    # the pinching case: new excursions reloading towards a pinching point (branches 2 and 12), on from it
    # to a local or the global peak, and an unloading turned back at a local peak before the pinching point
    # (branch 1 -> 2|12)
    pinched = sum(1 for sp in peer.springs for x in sp.log if x[0] == "branch" and x[2] in (2, 12))
    onward = {}
    for sp in peer.springs:
        previous = 0
        for what, _, branch in sp.log:
            if what == "branch":
                if previous % 10 == 2:
                    onward[branch % 10] = onward.get(branch % 10, 0) + 1
                previous = branch
    resumed = [(n, sp.pinch_resumed) for n, sp in zip(peer.names, peer.springs) if sp.pinch_resumed]
    if label == "pinching":
        print(f"  peer: {pinched} entries onto a branch towards a pinching point, on from it to a local peak "
              f"{onward.get(3, 0)} times and to the global {onward.get(4, 0)}; back at a local peak before the "
              f"pinching point (1 -> 2|12): "
              f"{resumed or 'none'}")
        if not {2, 12} <= set(kinds) or not onward.get(3) or not resumed:
            failures.append(f"{label}: branches {kinds}, on from the pinching point {onward}, 1 -> 2|12 {resumed}: "
                            f"the scene does not exercise the pinching rules")
    elif pinched:
        failures.append(f"{label}: {pinched} reloads towards a pinching point in a peak-oriented scene")


def main():
    started = time.time()
    failures = []
    self_check(failures)
    if len(sys.argv) < 2:
        sys.exit("usage: test_imk_scipy.py POUNDING [OUT]")
    program = sys.argv[1]
    out = Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp())
    out.mkdir(parents=True, exist_ok=True)
    for label, params in CASES.items():
        try:
            peer = check_case(program, out, label, params, failures)
        except ReloadGuard as guard:
            failures.append(f"{label}: the scene reaches the reloading guard, which the peer does not model: {guard}")
            continue
        if peer is not None:
            describe(label, peer, failures)
    program_run.finish(failures, started)


if __name__ == "__main__":
    main()
