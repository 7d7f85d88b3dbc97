#pragma once
// The human-readable report of a run, for any front end (the command line prints it), after
// Ceres' Summary::BriefReport / FullReport. Times in s, lengths in m (overlaps) or cm (peaks),
// energies in kJ; vertices by their 1-based number in the slab outline, as in every output file.

#include <string>

#include "pounding/analysis/run_scene.hpp"

namespace pounding::io {

/// One line, no newline: scene, method, status, impact count, first impact time, run time.
/// e.g. "paper: cvode-bdf, completed, 37 impacts, first at t = 2.345678 s, run time 0.412 s".
std::string brief_report(const analysis::RunReport& report);

/// Several lines, each ending in a newline: the run and its settings, impacts per level and the
/// first one, touches, sustained contacts, peaks at the top level, per floor the peak absolute
/// accelerations and storey drift ratios, the largest overlap, the
/// energy balance and the solver's statistics.
std::string full_report(const analysis::RunReport& report);

/// The settings the run's method used, e.g. "rtol 1e-08, atol 1e-10 m (phi ...), newton reduced"
/// or, for hht, "dt_s 0.05, alpha -0.05, ...": analysis::describe_used_settings() of the registry.
std::string method_settings_text(const analysis::RunReport& report);

}  // namespace pounding::io
