"""Whether a committed `pounding verify` manifest written by a scipy peer is still what the peer
computes: the check behind the CTest entries *_peer_current.

A peer (bench/peers/scipy_paper.py, validation/contact-laws/restitution_peer.py) writes its
results as a manifest's expected values. Regenerated on another machine they differ in their
last digits: numpy, scipy and the BLAS choose their kernels by CPU at run time, and an ODE
integration with events amplifies the difference (measured on the paper peer with its matrices
perturbed by 1e-16 to 1e-15 relative: impact times move by up to 1.2e-12 s, impulses by up to
1.8e-8 relative, the smallest ones at the end of a bounce sequence). So the fresh values are
compared with the committed ones within a fraction (CURRENCY_FRACTION) of the tolerance the
manifest's own checks give each quantity: a change of the peer large enough to matter to the
check fails, round-off of another CPU never does.

    from peer_manifest import manifest_is_current
    ok = manifest_is_current(committed_path, fresh_path)   # prints what differs
"""
import tomllib
from pathlib import Path

CURRENCY_FRACTION = 0.1

# [case.expected] key -> (its [case.checks] entry, the tolerance fields: absolute, relative).
QUANTITIES = {
    "impact_times_s": ("impact_times", "abs_s", None),
    "impulses_kNs": ("impulses", "abs_kNs", "rel"),
    "approach_velocity_mps": ("approach_velocity", "abs_mps", "rel"),
    "rebound": ("rebound", "abs", "rel"),
}


def _allowed(checks, key, reference):
    """The difference allowed for one expected value of `key` whose committed value is `reference`."""
    check, absolute, relative = QUANTITIES[key]
    spec = checks.get(check)
    if spec is None:
        raise ValueError(f"{key}: the manifest gives no tolerance for it ([case.checks] {check})")
    bounds = [spec[absolute]] if absolute in spec else []
    bounds += [spec[relative] * abs(reference)] if relative in spec else []
    if not bounds:
        raise ValueError(f"{key}: [case.checks] {check} gives no absolute or relative tolerance")
    return CURRENCY_FRACTION * max(bounds)


def _as_list(value):
    return value if isinstance(value, list) else [value]


def case_differences(committed_case, fresh_case, defaults):
    """What differs between two cases of the same name beyond the allowed fraction (a list of text)."""
    checks = {**defaults, **committed_case.get("checks", {})}
    old, new = committed_case["expected"], fresh_case["expected"]
    problems = []
    if set(old) != set(new):
        problems.append(f"expected keys {sorted(old)} against {sorted(new)}")
        return problems
    for key in sorted(old):
        if key not in QUANTITIES:
            # Text and whole numbers (a status, a count) compare exactly; a computed number needs
            # its tolerance in QUANTITIES, or another CPU's last digits would fail it.
            if any(isinstance(v, float) for v in _as_list(old[key]) + _as_list(new[key])):
                raise ValueError(f"{key}: a computed number with no tolerance here (add it to QUANTITIES)")
            if old[key] != new[key]:
                problems.append(f"{key} = {old[key]!r}, the peer now gives {new[key]!r}")
            continue
        a, b = _as_list(old[key]), _as_list(new[key])
        if len(a) != len(b):
            problems.append(f"{key}: {len(a)} values, the peer now gives {len(b)}")
            continue
        for index, (x, y) in enumerate(zip(a, b)):
            allowed = _allowed(checks, key, x)
            if not abs(x - y) <= allowed:
                problems.append(f"{key}[{index}] = {x!r}, the peer now gives {y!r} "
                                f"(differs by {abs(x - y):.3g}, allowed {allowed:.3g})")
    return problems


def manifest_is_current(committed, fresh):
    """True when every case of `fresh` matches the case of `committed` of the same name within
    CURRENCY_FRACTION of its checks' tolerances; otherwise prints each difference and returns False."""
    documents = [tomllib.loads(Path(f).read_text()) for f in (committed, fresh)]
    old_cases, new_cases = ({case["name"]: case for case in d.get("case", [])} for d in documents)
    defaults = documents[0].get("defaults", {}).get("checks", {})
    problems = []
    if list(old_cases) != list(new_cases):
        problems.append(f"cases {list(old_cases)} against the peer's {list(new_cases)}")
    for name in old_cases.keys() & new_cases.keys():
        problems += [f"case {name}: {p}" for p in case_differences(old_cases[name], new_cases[name], defaults)]
    for problem in problems:
        print(f"{committed}: {problem}")
    if problems:
        print(f"{committed} is not what the peer computes now (allowed: {CURRENCY_FRACTION:g} of each check's "
              "tolerance): run the peer with --manifest again")
    return not problems
