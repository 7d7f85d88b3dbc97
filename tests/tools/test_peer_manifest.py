#!/usr/bin/python3
"""tools/peer_manifest.py (the check behind the *_peer_current tests): a peer regenerated on
another CPU differs from the committed manifest in its last digits and must still be current;
a change of a tenth of a check's tolerance, a value more or less, or a renamed case must not."""
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "tools"))
from peer_manifest import manifest_is_current  # noqa: E402

COMMITTED = """name = "peer"
[defaults.checks]
rebound = {{ rel = 1e-6 }}
[[case]]
name = "a"
[case.checks]
impact_times = {{ abs_s = 1e-9 }}
impulses = {{ rel = 1e-6 }}
[case.expected]
impact_times_s = [{t0}, 5.75]
impulses_kNs = [{j0}, 0.3]
rebound = {e}
"""


def current(**values):
    fields = {"t0": 5.7, "j0": 274.0, "e": 0.5}
    with tempfile.TemporaryDirectory() as scratch:
        old, new = Path(scratch) / "old.toml", Path(scratch) / "new.toml"
        old.write_text(COMMITTED.format(**fields))
        new.write_text(COMMITTED.format(**{**fields, **values}))
        return manifest_is_current(old, new)


def main():
    checks = [
        ("identical", current(), True),
        ("round-off of another CPU (1e-12 s, 2e-8 relative)", current(t0=5.7 + 1e-12, j0=274.0 * (1 + 2e-8)), True),
        ("an impact time moved by 0.2 of its tolerance", current(t0=5.7 + 2e-10), False),
        ("an impulse moved by 0.2 of its tolerance", current(j0=274.0 * (1 + 2e-7)), False),
        ("a default check's value moved (rebound)", current(e=0.5 * (1 + 2e-7)), False),
        ("one impact more", current(j0="274.0, 1.0"), False),
    ]
    failures = [name for name, got, want in checks if got != want]
    for name, got, want in checks:
        print(f"{'ok  ' if got == want else 'FAIL'} {name}: current = {got}")
    sys.exit(1 if failures else 0)


if __name__ == "__main__":
    main()
