#!/usr/bin/env bash
# The test suite, but for its slowest tests (listed below), under AddressSanitizer + UndefinedBehaviorSanitizer
# (build-asan/): any memory error, leak or undefined behaviour fails the test that meets it.
set -euo pipefail
cd "$(dirname "$0")/.."
./scripts/build-sanitized.sh
export ASAN_OPTIONS=detect_leaks=1:abort_on_error=1:strict_string_checks=1
export UBSAN_OPTIONS=print_stacktrace=1:halt_on_error=1
# Left out here, run by the Release pass only: test_beyond_paper (20 s in Release, 4.5 min here),
# extreme_quick (every path on nine extreme cases: 35-60 s in Release, 8.5 min here) and
# test_needed_gap (15 s in Release: full runs bisecting the gap; test_gap_cli runs the same
# code here end to end). The first two passed here when this was written; test_needed_gap has not
# been run under the sanitizers. The peer_scipy tests (a Python peer solution checked against the
# exact and CVODE paths, 7 s each in Release) run no C++ code the other tests do not. All of these
# exercise the same code as the tests that do run, only longer, and together would take CI past
# 30 minutes on 2 cores. Also left out since CI reached 26 minutes (all three passed here, commit
# 83b9b6f): test_step_bound (210 s here: long stiff runs of the bound the other solver tests use),
# test_record_set (214 s: the same record runs with 1 and 2 threads; test_gap_cli runs the record
# set end to end here) and test_hht (91 s: the HHT path, unchanged for several releases). And,
# since issue 12's merges took CI to 25 minutes (both passed here, commit 34933d7): test_cli
# (316 s here: the command line's options and refusals, one process each; fuzz_scene and the
# scene-reader tests cover its parsing under the sanitizers) and test_stream_cli (100 s:
# streamed output files; test_run_stream runs the same sink here). And yielding_scipy (408 s here
# under load, passed at 6846839: long command-line runs of the yielding paper scene; test_yielding
# runs the yielding columns' code, closed forms and collapse, under the sanitizers). And
# two_components_scipy (706 s here, passed at 434d02f: the Kobe pair at rtol 1e-10 on three
# methods, gap --all-angles, spectral scaling; two_components_quick runs its small scenes here)
# and all_angles (about 400 contact-free runs of the command line). And bouc_wen_scipy (over 3.5 min
# here before it was left out, 50 s in Release: the paper's buildings with 950 Bouc-Wen columns on
# two methods and a gap search; test_yielding runs the Bouc-Wen code, its closed forms and its
# Jacobian, under the sanitizers). And slab_column_random (25 random scenes through the command
# line; test_column_contact and slab_column_scipy run the slab-to-column code under the sanitizers).
# And rows_cli (the command line, report and the Python module; test_rows and row_scipy run the
# rows' code under the sanitizers). And zero_gap_and_grazing (964 s here at 3742d93, 31 s in
# Release: the twins at zero gap on every event-driven method, whose held problem now goes through
# the block enumeration, which allocates a matrix per active set; test_impact runs that code,
# test_event_driven the holds, under the sanitizers). And street_scipy (45 s in Release: twelve
# cases of slabs in line at rtol 1e-12 on two methods; test_corners runs a kelvin contact and a
# hold handed round corners on its scenes, and the rest of the corner rules, under the sanitizers).
ctest --test-dir build-asan --output-on-failure -j "$(nproc)" \
  -E '^(test_beyond_paper|extreme_quick|test_needed_gap|peer_scipy_exact|peer_scipy_bdf|test_step_bound|test_record_set|test_hht|test_cli|test_stream_cli|yielding_scipy|all_angles|two_components_scipy|bouc_wen_scipy|slab_column_random|rows_cli|zero_gap_and_grazing|street_scipy)$'
