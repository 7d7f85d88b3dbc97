#pragma once
// Independent runs on threads (internal to the analysis layer).
//
// What makes a run safe to run beside others (checked for `gap --curve` and `--records`): each
// builds its own CoupledSystem from its own copy of the scene and its own SUNDIALS context
// (SUNDIALS 6.4 serial, logging and profiling off, so no shared logger); the library's
// function-local statics are const tables and regexes, initialised once (C++11 guarantees it)
// and only read; Eigen runs single-threaded (no OpenMP) and keeps no global state; fmt formats
// into its own buffers; toml++ is used only while the scene is read, before any thread starts.
// The one process-wide mutable value is the interrupt request (solvers/run_budget.hpp), an
// atomic meant to stop every run at once.

#include <cstddef>
#include <functional>

namespace pounding::analysis::detail {

/// Calls job(k) once for every k in [0, count), on up to `threads` threads (0: every core), and
/// returns when all are done. Jobs must share no mutable state (each run builds its own system
/// and SUNDIALS context). @throws the exception of the lowest k whose job threw, once all ended.
void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& job);

}  // namespace pounding::analysis::detail
