#!/usr/bin/python3
"""The restitution one compliant contact achieves, computed independently of pounding (scipy,
sharing no code with the program): for each compliant law and target e,

1. the lone contact in the rigid limit: the normal motion of two masses, δ̈ = −W F(δ, δ̇) with
   δ(0) = 0, δ̇(0) = v₀, integrated until the law releases the contact. The ratio of separation to
   approach speed depends on e alone (kelvin by linearity, the Hertz laws by self-similarity), so
   it is the law's restitution table. It is also given for the published damping relations of
   the Hertz form F = k_h δ^1.5 (1 + χ δ̇/δ̇₀), to show what each achieves: Hunt & Crossley
   (1975) χ = 3(1 − e)/2, Lankarani & Nikravesh (1990) χ = 3(1 − e²)/4 (the program's hertzdamp,
   after Muthukumar & DesRoches 2006) and Ye, Li & Zhu (2009) χ = 8(1 − e)/(5e) (the program's
   hertzdamp-ye);
2. the first contact of the scene lone-impact.toml (two undamped one-storey oscillators after a
   ground pulse, meeting head-on in line with both centres of mass) at 100 times each law's
   default stiffness: its onset, impulse and ratio of separation to approach speed, which
   restitution.verify.toml checks the program against. The storeys act during the contact, so
   the scene's ratio differs from the rigid limit's by what this script prints as the mapping
   error.

    validation/contact-laws/restitution_peer.py            (print both tables)
    validation/contact-laws/restitution_peer.py --manifest OUT [--manifest-current COMMITTED]

The laws as docs/model.md §6a states them (released where the force turns tensile, kelvin, hertzdamp
and hertzdamp-ye; jankowski's dashpot acts only while approaching and the contact lasts until the gap
opens). Units: t, m, s, kN.
"""
import argparse
import math
import sys
import tomllib
from pathlib import Path

import numpy as np
from scipy.integrate import solve_ivp

HERE = Path(__file__).resolve().parent
sys.path.insert(0, str(HERE.parents[1] / "tools"))
from peer_manifest import manifest_is_current  # noqa: E402  (the check behind restitution_peer_current)
SCENE = HERE / "lone-impact.toml"
RTOL, ATOL = 1e-12, 1e-15
RESTITUTIONS = [0.1, 0.3, 0.5, 0.7, 0.9, 1.0]
# Each law's default stiffness (kN/m for kelvin, kN/m^1.5 for the Hertz laws; docs/scene-format.md)
# and the multiple the scene uses, at which the contact lasts a few milliseconds.
DEFAULT_STIFFNESS = {"kelvin": 93500.0, "hertzdamp": 2.74711e7, "hertzdamp-ye": 2.74711e7, "jankowski": 2.75e6}
STIFFNESS_FACTOR = 100.0
LAWS = ("kelvin", "hertzdamp", "hertzdamp-ye", "jankowski")
HERTZ_RELATIONS = {  # χ(e) of F = k_h δ^1.5 (1 + χ δ̇/δ̇₀)
    "Hunt & Crossley 1975": lambda e: 1.5 * (1.0 - e),
    "Lankarani & Nikravesh 1990 (hertzdamp)": lambda e: 0.75 * (1.0 - e * e),
    "Ye, Li & Zhu 2009 (hertzdamp-ye)": lambda e: 1.6 * (1.0 - e) / e,
}


class Law:
    """One contact of a law from onset, its constants fixed there: force(δ, δ̇) (kN, > 0 pushes
    apart), and whether the contact is over (released or the gap open)."""

    def __init__(self, name, stiffness, e, approach_mps, inverse_mass_per_t, chi=None):
        self.name, self.k, self.v0 = name, stiffness, approach_mps
        if name == "kelvin":  # Anagnostopoulos 1988; e = 0 is critical damping
            xi = 1.0 if e == 0.0 else -math.log(e) / math.sqrt(math.pi ** 2 + math.log(e) ** 2)
            self.c = 2.0 * xi * math.sqrt(stiffness / inverse_mass_per_t)
        elif name == "hertz":
            self.chi = chi
        elif name == "jankowski":  # Jankowski 2005/2006
            xi = 9.0 * math.sqrt(5.0) * (1.0 - e * e) / (2.0 * e * (e * (9.0 * math.pi - 16.0) + 16.0))
            self.c_per_root4 = 2.0 * xi * math.sqrt(stiffness / inverse_mass_per_t)

    def force(self, d, dd):
        dp = max(d, 0.0)
        if self.name == "kelvin":
            return self.k * d + self.c * dd
        if self.name == "hertz":
            return self.k * dp ** 1.5 * (1.0 + self.chi * dd / self.v0)
        return self.k * dp ** 1.5 + (self.c_per_root4 * dp ** 0.25 * dd if dd > 0.0 else 0.0)

    def release_events(self):
        """Functions of (δ, δ̇) whose falling zero ends the contact's push."""
        events = [lambda d, dd: d]  # the gap opens
        if self.name == "kelvin":
            events.append(lambda d, dd: self.k * d + self.c * dd)
        elif self.name == "hertz":
            events.append(lambda d, dd: 1.0 + self.chi * dd / self.v0)
        return events


def law_for(name, stiffness, e, v0, w):
    if name == "hertzdamp":
        return Law("hertz", stiffness, e, v0, w, chi=HERTZ_RELATIONS["Lankarani & Nikravesh 1990 (hertzdamp)"](e))
    if name == "hertzdamp-ye":
        return Law("hertz", stiffness, e, v0, w, chi=HERTZ_RELATIONS["Ye, Li & Zhu 2009 (hertzdamp-ye)"](e))
    return Law(name, stiffness, e, v0, w)


def through_contact(law, rhs, y0, t0, t_max, overlap_of):
    """Integrates rhs(t, y, force) from onset (t0, y0) until the law releases: returns (t, y,
    impulse kN·s). overlap_of(y) = (δ, δ̇). Jankowski's dashpot switches off at δ̇ = 0, a root of
    its own so no step straddles it."""
    impulse = 0.0
    phases = [None, "restitution"] if law.name == "jankowski" else [None]
    t, y = t0, np.asarray(y0, float)
    for phase in phases:
        def f(t, z):
            force = law.force(*overlap_of(z[:-1]))
            if phase == "restitution":
                force = law.k * max(overlap_of(z[:-1])[0], 0.0) ** 1.5
            return np.append(rhs(t, z[:-1], force), force)

        events = []
        for g in law.release_events():
            ev = (lambda g: lambda t, z: g(*overlap_of(z[:-1])))(g)
            ev.terminal, ev.direction = True, -1
            events.append(ev)
        if phase is None and law.name == "jankowski":
            ev = lambda t, z: overlap_of(z[:-1])[1]
            ev.terminal, ev.direction = True, -1
            events.append(ev)
        # δ = 0 at onset is a zero of the gap event too; its direction (falling) keeps it from firing.
        sol = solve_ivp(f, (t, t_max), np.append(y, impulse), method="DOP853", rtol=RTOL, atol=ATOL,
                        events=events, first_step=1e-9 * (t_max - t))
        if sol.status != 1:
            raise RuntimeError(f"{law.name}: the contact did not end by t = {t_max}")
        t, z = sol.t[-1], sol.y[:, -1]
        y, impulse = z[:-1], z[-1]
        which = next(i for i, te in enumerate(sol.t_events) if len(te))
        if not (law.name == "jankowski" and phase is None and which == len(events) - 1):
            break  # released (or the gap opened): the contact's push is over
    return t, y, impulse


def rigid_limit(name, e, chi=None):
    """The separation over approach speed of a lone contact: unit inverse mass, stiffness and
    approach speed (the ratio is scale-free)."""
    law = Law("hertz", 1.0, e, 1.0, 1.0, chi=chi) if chi is not None else law_for(name, 1.0, e, 1.0, 1.0)
    rhs = lambda t, y, force: np.array([y[1], -force])
    _, y, _ = through_contact(law, rhs, [0.0, 1.0], 0.0, 100.0, lambda y: (y[0], y[1]))
    return -y[1]


class Scene:
    """lone-impact.toml read as data: two oscillators u_A, u_B (relative to the ground) along x,
    the gap g = g₀ − u_A + u_B, a piecewise-linear ground acceleration."""

    def __init__(self, path=SCENE):
        scene = tomllib.loads(path.read_text())
        a, b = scene["building"]
        self.m = np.array([a["mass_t"], b["mass_t"]])
        self.k = np.array([a["storey_stiffness"][0][0], b["storey_stiffness"][0][0]])
        self.gap0 = scene["contact"]["gap_m"]
        rows = [line.split() for line in (path.parent / scene["excitation"]["file"]).read_text().splitlines()
                if line.strip() and not line.lstrip().startswith("#")]
        self.t_rec = np.array([float(r[0]) for r in rows])
        self.a_rec = np.array([float(r[1]) for r in rows])
        self.w = 1.0 / self.m[0] + 1.0 / self.m[1]

    def ground(self, t):
        return float(np.interp(t, self.t_rec, self.a_rec))

    def rhs(self, t, y, force=0.0):
        """y = (u_A, u_B, v_A, v_B); the contact force pushes A to −x and B to +x."""
        accel = -self.k * y[:2] / self.m - self.ground(t)
        accel += np.array([-force / self.m[0], force / self.m[1]])
        return np.concatenate([y[2:], accel])

    def overlap(self, y):
        return -(self.gap0 - y[0] + y[1]), y[2] - y[3]

    def first_onset(self):
        """Integrates the free motion knot by knot (the record is linear between them) until the
        gap first closes."""
        y, t = np.zeros(4), 0.0
        closes = lambda t, y: self.gap0 - y[0] + y[1]
        closes.terminal, closes.direction = True, -1
        knots = [k for k in self.t_rec if k > 0.0] + [self.t_rec[-1]]
        for end in knots:
            sol = solve_ivp(self.rhs, (t, end), y, method="DOP853", rtol=RTOL, atol=ATOL, events=closes)
            t, y = sol.t[-1], sol.y[:, -1]
            if sol.status == 1:
                return t, y
        raise RuntimeError("the slabs never meet")

    def first_contact(self, law_name, e, stiffness):
        t0, y0 = self.first_onset()
        v0 = self.overlap(y0)[1]
        law = law_for(law_name, stiffness, e, v0, self.w)
        t1, y1, impulse = through_contact(law, self.rhs, y0, t0, self.t_rec[-1], self.overlap)
        return {"onset_s": t0, "approach_mps": v0, "impulse_kNs": impulse, "duration_s": t1 - t0,
                "rebound": -self.overlap(y1)[1] / v0}


def laws_and_restitutions():
    for law in LAWS:
        for e in RESTITUTIONS:
            yield law, e


def print_tables(scene):
    print("Rigid limit: separation / approach speed of a lone contact (depends on e alone)")
    print("| e | " + " | ".join(f"{e:g}" for e in RESTITUTIONS) + " |")
    print("|---|" + "---|" * len(RESTITUTIONS))
    for law in LAWS:
        print(f"| {law} | " + " | ".join(f"{rigid_limit(law, e):.4f}" for e in RESTITUTIONS) + " |")
    for label, chi in HERTZ_RELATIONS.items():
        print(f"| Hertz, {label} | " + " | ".join(f"{rigid_limit(None, e, chi(e)):.4f}" for e in RESTITUTIONS) + " |")
    print(f"\n{SCENE.name} at {STIFFNESS_FACTOR:g} × each default stiffness: the first contact")
    print("| law | e | onset (s) | approach (m/s) | duration (ms) | impulse (kN·s) | rebound | vs rigid limit |")
    print("|---|---|---|---|---|---|---|---|")
    for law, e in laws_and_restitutions():
        c = scene.first_contact(law, e, STIFFNESS_FACTOR * DEFAULT_STIFFNESS[law])
        limit = rigid_limit(law, e)
        print(f"| {law} | {e:g} | {c['onset_s']:.9f} | {c['approach_mps']:.6f} | {1e3 * c['duration_s']:.3f} | "
              f"{c['impulse_kNs']:.6f} | {c['rebound']:.6f} | {c['rebound'] / limit - 1:+.2e} |")


def write_manifest(path, scene):
    lines = ["# Written by validation/contact-laws/restitution_peer.py --manifest (scipy DOP853, sharing no",
             "# code with pounding): the first contact of lone-impact.toml for each compliant law and",
             f"# restitution, at {STIFFNESS_FACTOR:g} times each law's default stiffness, on cvode-bdf at rtol 1e-10.",
             "# rebound is the contact's separation over approach speed, the restitution the law achieves",
             "# (its rigid-limit table is in docs/model.md §6a; the storeys move it by the mapping error",
             "# the peer prints). CTest verify_restitution runs it, restitution_peer_current checks that",
             "# the peer still writes these numbers.",
             'name = "contact-laws-restitution"', "",
             "[defaults.checks]", 'status = "completed"', "energy_residual = { max_relative = 1e-6 }",
             "rebound = { rel = 1e-6 }", "", ]
    for law, e in laws_and_restitutions():
        c = scene.first_contact(law, e, STIFFNESS_FACTOR * DEFAULT_STIFFNESS[law])
        window = c["onset_s"] + c["duration_s"]
        lines += ["[[case]]", f'name = "{law}-e{e:g}"', f'scene = "{SCENE.name}"', 'method = "cvode-bdf"',
                  "settings = { rtol = 1e-10, atol = 1e-12 }", f'contact_law = "{law}"', f"restitution = {e!r}",
                  f"contact_stiffness = {STIFFNESS_FACTOR * DEFAULT_STIFFNESS[law]!r}",
                  "[case.checks]", f"impact_times = {{ abs_s = 1e-09, before_s = {window!r} }}",
                  f"impulses = {{ rel = 1e-06, before_s = {window!r} }}",
                  "[case.expected]", f"impact_times_s = [{c['onset_s']!r}]", f"impulses_kNs = [{c['impulse_kNs']!r}]",
                  f"rebound = {c['rebound']!r}", ""]
    Path(path).write_text("\n".join(lines))
    print(f"Wrote {path}")


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--manifest", metavar="OUT", help="write the pounding verify manifest")
    parser.add_argument("--manifest-current", metavar="COMMITTED",
                        help="with --manifest: exit 1 unless COMMITTED holds the same expected values "
                             "(within a tenth of its checks' tolerances: tools/peer_manifest.py)")
    args = parser.parse_args()
    scene = Scene()
    if args.manifest:
        write_manifest(args.manifest, scene)
        sys.exit(0 if not args.manifest_current or manifest_is_current(args.manifest_current, args.manifest) else 1)
    print_tables(scene)


if __name__ == "__main__":
    main()
