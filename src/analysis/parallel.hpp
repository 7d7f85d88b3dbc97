#pragma once
// Independent runs on threads (internal to the analysis layer).

#include <cstddef>
#include <functional>

namespace pounding::analysis::detail {

/// Calls job(k) once for every k in [0, count), on up to `threads` threads (0: every core), and
/// returns when all are done. Jobs must share no mutable state (each run builds its own system
/// and SUNDIALS context). @throws the exception of the lowest k whose job threw, once all ended.
void parallel_for(std::size_t count, unsigned threads, const std::function<void(std::size_t)>& job);

}  // namespace pounding::analysis::detail
