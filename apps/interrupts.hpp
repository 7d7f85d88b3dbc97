#pragma once
// Signals a command turns into an orderly stop.

#include <csignal>

#include "pounding/solvers/run_budget.hpp"

namespace pounding::cli {

/// While it lives, SIGINT and SIGTERM ask every run to stop (each then ends with status
/// interrupted and the command writes what it has); a second signal has the default effect, so a
/// stuck program still dies.
class InterruptRequests {
 public:
  InterruptRequests() {
    struct sigaction action {};
    action.sa_handler = [](int) { solvers::request_interrupt(); };
    action.sa_flags = SA_RESETHAND;
    sigemptyset(&action.sa_mask);
    sigaction(SIGINT, &action, &old_int_);
    sigaction(SIGTERM, &action, &old_term_);
  }
  ~InterruptRequests() {
    sigaction(SIGINT, &old_int_, nullptr);
    sigaction(SIGTERM, &old_term_, nullptr);
  }
  InterruptRequests(const InterruptRequests&) = delete;
  InterruptRequests& operator=(const InterruptRequests&) = delete;

 private:
  struct sigaction old_int_ {};
  struct sigaction old_term_ {};
};

}  // namespace pounding::cli
