#pragma once
// A one-line progress display of a long run on the terminal: simulated time, the share of the
// record done, the impacts so far and the wall time, redrawn at most four times a second and
// cleared before the report is printed. Shown only when stderr is a terminal (never in a pipe,
// a log or CI) and not asked away (--no-progress).

#include <unistd.h>

#include <chrono>
#include <cstdio>

#include <fmt/format.h>

namespace pounding::cli {

class ProgressLine {
 public:
  /// True when stderr is a terminal: the only place a redrawn line belongs.
  static bool wanted(bool no_progress) { return !no_progress && isatty(fileno(stderr)) == 1; }

  ~ProgressLine() { clear(); }

  /// The run has reached t_s of a record ending at end_s (s), with `impacts` impacts so far.
  void update(double t_s, double end_s, std::size_t impacts) {
    const auto now = std::chrono::steady_clock::now();
    if (shown_ && now - last_ < std::chrono::milliseconds(250)) return;
    last_ = now;
    shown_ = true;
    const double share = end_s > 0.0 ? 100.0 * t_s / end_s : 100.0;
    fmt::print(stderr, "\r\033[K  t = {:.2f} of {:.2f} s ({:.0f} %), {} impact{}, {:.1f} s", t_s, end_s, share, impacts,
               impacts == 1 ? "" : "s", std::chrono::duration<double>(now - start_).count());
    std::fflush(stderr);
  }
  /// Removes the line (once something was drawn).
  void clear() {
    if (!shown_) return;
    fmt::print(stderr, "\r\033[K");
    std::fflush(stderr);
    shown_ = false;
  }

 private:
  std::chrono::steady_clock::time_point start_ = std::chrono::steady_clock::now(), last_;
  bool shown_ = false;
};

}  // namespace pounding::cli
