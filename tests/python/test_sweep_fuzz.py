"""The sweep file reader (pounding.sweep.Sweep) under mutated sweep files: a bounded, seeded
mutation fuzz (libFuzzer cannot drive Python here). Every mutant of a valid sweep file — bytes
flipped, inserted or deleted, lines duplicated, dropped or swapped, values replaced by
hostile ones (NUL, inf, nan, huge and negative numbers, long strings, wrong types) — must either
read as a sweep or raise InputError: never another exception, never a hang. Seeds and the
mutants that once failed are kept in fuzz/regressions/sweep_file/ and replayed first.

    PYTHONPATH=build/python python3 -m pytest tests/python/test_sweep_fuzz.py  (FUZZ_MUTANTS=N for more)
"""
import os
import pathlib
import random

import pytest

import pounding
from pounding import sweep as sweeps

SOURCE = pathlib.Path(os.environ.get("POUNDING_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
PAPER = SOURCE / "examples" / "paper" / "paper.toml"
REGRESSIONS = SOURCE / "fuzz" / "regressions" / "sweep_file"
MUTANTS = int(os.environ.get("FUZZ_MUTANTS", "400"))

HOSTILE_VALUES = ["inf", "-inf", "nan", "1e308", "-1", "0", "2e19", "99999999999999999999", '""', '"\\u0000"',
                  '"' + "x" * 5000 + '"', "[]", "{}", "[[]]", "true", '["a", 1, 2.5]', "1979-05-27", '"../../.."']


def valid_sweep(folder):
    (folder / "pulse.txt").write_text("0 0\n0.1 1\n0.2 0\n0.3 -1\n0.4 0\n")
    return (f'scenes = ["{PAPER}"]\n'
            'records = [{file = "pulse.txt", format = "columns", units = "m/s2"}]\n'
            "gaps_m = [0.05, 0.2]\n"
            "restitutions = [0.5]\n"
            'methods = [{name = "cvode-bdf", rtol = 1e-8}, "arkode-erk"]\n'
            'contact_laws = ["impulse", {name = "kelvin", stiffness_kN_per_m = 93500.0}]\n'
            "needed_gap = true\n"
            "max_wall_time_s = 600\n"
            'out = "out"\n').encode()


def mutate(data, rng):
    lines = data.split(b"\n")
    kind = rng.randrange(7)
    if kind == 0 and data:  # flip a byte
        i = rng.randrange(len(data))
        return data[:i] + bytes([rng.randrange(256)]) + data[i + 1:]
    if kind == 1:  # insert bytes
        i = rng.randrange(len(data) + 1)
        return data[:i] + bytes(rng.randrange(256) for _ in range(rng.randrange(1, 8))) + data[i:]
    if kind == 2 and data:  # delete a run
        i = rng.randrange(len(data))
        return data[:i] + data[i + rng.randrange(1, 20):]
    if kind == 3:  # duplicate a line
        i = rng.randrange(len(lines))
        return b"\n".join(lines[:i] + [lines[i]] + lines[i:])
    if kind == 4:  # drop a line
        i = rng.randrange(len(lines))
        return b"\n".join(lines[:i] + lines[i + 1:])
    if kind == 5 and len(lines) > 1:  # swap two lines
        i, j = rng.sample(range(len(lines)), 2)
        lines[i], lines[j] = lines[j], lines[i]
        return b"\n".join(lines)
    # replace a value (after an '=' or inside brackets) by a hostile one
    i = rng.randrange(len(lines))
    line = lines[i].decode("utf-8", "replace")
    if "=" in line:
        key = line.split("=", 1)[0]
        lines[i] = f"{key}= {rng.choice(HOSTILE_VALUES)}".encode()
    return b"\n".join(lines)


def read(path):
    """Sweep(path): a sweep, or InputError. Anything else fails the test with the mutant kept."""
    try:
        sweeps.Sweep(path)
    except pounding.InputError:
        pass


def test_regressions_and_seed_read_or_refuse(tmp_path):
    seed = tmp_path / "seed.toml"
    seed.write_bytes(valid_sweep(tmp_path))
    sweeps.Sweep(seed)  # the seed itself is valid
    for kept in sorted(REGRESSIONS.glob("*.toml")) if REGRESSIONS.is_dir() else []:
        path = tmp_path / kept.name
        path.write_bytes(kept.read_bytes().replace(b"@PAPER@", str(PAPER).encode()))
        read(path)


@pytest.mark.parametrize("block", range(4))
def test_mutants_read_or_refuse(tmp_path, block):
    rng = random.Random(20261124 + block)
    data = valid_sweep(tmp_path)
    path = tmp_path / "mutant.toml"
    for n in range(MUTANTS // 4):
        mutant = data
        for _ in range(rng.randrange(1, 4)):
            mutant = mutate(mutant, rng)
        path.write_bytes(mutant)
        try:
            read(path)
        except Exception as error:  # keep the failing mutant for the regression replay
            REGRESSIONS.mkdir(parents=True, exist_ok=True)
            kept = REGRESSIONS / f"block{block}-{n}.toml"
            kept.write_bytes(mutant.replace(str(PAPER).encode(), b"@PAPER@"))
            raise AssertionError(f"mutant {n} of block {block} ({kept}) raised {type(error).__name__}: {error}")
