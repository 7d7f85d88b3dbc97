#include "pounding/solvers/missed_contacts.hpp"

#include <algorithm>
#include <array>
#include <cmath>

#include "pounding/solvers/root_finding.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

namespace {

/// A vertex that came onto its edge already behind it (masked beside the edge, or dormant): a
/// contact at the step end if it lies inside the other slab with this edge the nearest (its depth
/// is −g). Behind the line beside the slab's corner it is outside; nearer another edge, it came
/// in across that one, whose own candidate answers for it.
std::optional<double> arrival(StepGaps& path, std::size_t i, double t_end, const contact::GapState& end) {
  path.at(i, t_end);
  return inside_across_edge(end.gap_m, path.depth_inside_m(i)) ? std::optional(t_end) : std::nullopt;
}

/// An armed pair's minimum inside the step (ġ < 0 at the start, ġ > 0 at the end, both ends
/// open): the crossing into contact if the minimum is below zero; a graze if within the band.
std::optional<double> dip(StepGaps& path, std::size_t i, double t_start, double t_end, const contact::GapState& s0,
                          const contact::GapState& s1, double contact_tolerance_m, std::vector<Graze>& grazes) {
  if (!(s0.gap_m > 0.0 && s1.gap_m > 0.0 && s0.gap_rate_mps < 0.0 && s1.gap_rate_mps > 0.0)) return std::nullopt;
  const double t_min = find_root([&](double time) { return path.at(i, time).gap_rate_mps; }, t_start, t_end,
                                 s0.gap_rate_mps, s1.gap_rate_mps);
  const contact::GapState lowest = path.at(i, t_min);
  if (!lowest.on_segment()) return std::nullopt;
  // A minimum below zero is where the path would have gone without the impact at t_cross: it is
  // not an overlap of the computed motion (the event notes the gap at the crossing).
  if (lowest.gap_m < 0.0) {
    return find_root([&](double time) { return path.at(i, time).gap_m; }, t_start, t_min, s0.gap_m, lowest.gap_m);
  }
  if (lowest.gap_m <= contact_tolerance_m) grazes.push_back({t_min, i, lowest});
  return std::nullopt;
}

/// A masked pair sinking at the step end (g < 0, ġ < 0) closed again after it was handled. If
/// the gap rose to g ≥ 0 inside the step, the re-closure is the last crossing of zero, at any
/// height (a flight from rest at ġ⁺ ≈ 0 rises only by nanometres, and its rate may change sign
/// twice in the step: rounding leaves ġ⁺ at −1e−17 while g̈ lifts the pair). The step is scanned
/// on the interpolant, the highest sample polished to the maximum. If the gap never rose, the
/// pair has been in contact (within the allowance) since before the step; once past its floor,
/// the contact is taken at the step end, where its own root stopped the integrator.
std::optional<double> reclosure(const ContactStates& states, StepGaps& path, std::size_t i, double t_start,
                                double t_end, const contact::GapState& start, const contact::GapState& end,
                                double overlap_allowance_m) {
  if (!end.on_segment()) return std::nullopt;
  // Masked after crossing the edge's extension, the vertex has come onto the edge inside the
  // other slab: a contact now, wherever it is heading. (Behind the edge's line beside the slab's
  // corner, it is not inside.)
  if (!states.has_floor(i) && end.gap_m < -overlap_allowance_m) return arrival(path, i, t_end, end);
  if (!(end.gap_m < 0.0 && end.gap_rate_mps < 0.0)) return std::nullopt;
  auto state_at = [&](double time) { return path.at(i, time); };
  constexpr int kSamples = 32;
  std::array<double, kSamples + 1> times{}, gaps{}, rates{};
  for (int k = 0; k <= kSamples; ++k) {
    times[k] = k == kSamples ? t_end : t_start + (t_end - t_start) * k / kSamples;
    const contact::GapState s = k == 0 ? start : k == kSamples ? end : state_at(times[k]);
    gaps[k] = s.gap_m;
    rates[k] = s.gap_rate_mps;
  }
  int last_open = -1;
  for (int k = 0; k < kSamples; ++k) {
    if (gaps[k] >= 0.0) last_open = k;
  }
  double t_open = last_open >= 0 ? times[last_open] : 0.0, g_open = last_open >= 0 ? gaps[last_open] : 0.0;
  int after = last_open + 1;
  if (last_open < 0) {
    // No sample open: the top of a flight lower than the samples resolve may still be above zero.
    const int top = static_cast<int>(std::max_element(gaps.begin(), gaps.end()) - gaps.begin());
    for (int k : {top - 1, top}) {
      if (k < 0 || k >= kSamples || !(rates[k] > 0.0 && rates[k + 1] < 0.0)) continue;
      const double t_top = find_root([&](double time) { return state_at(time).gap_rate_mps; }, times[k], times[k + 1],
                                     rates[k], rates[k + 1]);
      const double g_top = state_at(t_top).gap_m;
      if (g_top >= 0.0) t_open = t_top, g_open = g_top, after = k + 1;
    }
  }
  // The root stops the integrator with g at the floor to within its own tolerance.
  const double floor_m = states.mask_floor_m(i);
  const bool at_floor = end.gap_m <= floor_m + 1e-9 * std::abs(floor_m);
  if (after > 0) {
    const double t_hit =
        find_root([&](double time) { return state_at(time).gap_m; }, t_open, times[after], g_open, gaps[after]);
    const contact::GapState hit = state_at(t_hit);
    // Rising and falling by rounding alone (two identical buildings at zero gap) is no flight;
    // a pair that really sinks reaches its floor.
    if (!at_floor && -hit.gap_rate_mps <= path.rate_round_off_mps(i)) return std::nullopt;
    return hit.on_segment() ? t_hit : t_end;  // closed beside the edge, then slid onto it
  }
  return at_floor ? std::optional<double>(t_end) : std::nullopt;
}

/// A dormant corner candidate (no root over the step) that ends it closed on its edge: the last
/// crossing of zero inside the step, if the vertex was on the edge there; if it came onto the edge
/// already behind it, a contact at the step end when it lies inside the other slab.
std::optional<double> dormant_closing(StepGaps& path, std::size_t i, double t_start, double t_end,
                                      const contact::GapState& start, const contact::GapState& end,
                                      double overlap_allowance_m) {
  if (!(end.on_segment() && end.gap_m < 0.0)) return std::nullopt;
  constexpr int kSamples = 32;
  double t_open = t_start, g_open = start.gap_m, t_shut = t_end, g_shut = end.gap_m;
  if (g_open < 0.0) {  // the last sample still open, if any
    t_open = -1.0;
    for (int k = kSamples - 1; k > 0; --k) {
      const double time = t_start + (t_end - t_start) * k / kSamples;
      const double g = path.at(i, time).gap_m;
      if (g >= 0.0) {
        t_open = time, g_open = g;
        break;
      }
      t_shut = time, g_shut = g;
    }
  }
  if (t_open >= t_start) {
    const double t_hit = find_root([&](double time) { return path.at(i, time).gap_m; }, t_open, t_shut, g_open, g_shut);
    if (path.at(i, t_hit).on_segment()) return t_hit;
  }
  if (end.gap_m >= -overlap_allowance_m) return std::nullopt;
  return arrival(path, i, t_end, end);
}

}  // namespace

std::optional<MissedContact> scan_missed_contacts(const ContactStates& states, StepGaps& path, double t_start,
                                                  double t_end, const std::vector<contact::GapState>& start,
                                                  const std::vector<contact::GapState>& end,
                                                  const ScanTolerances& tolerances, std::vector<Graze>& grazes,
                                                  const CornerCover* cover) {
  std::optional<MissedContact> earliest;
  for (std::size_t i = 0; i < states.size(); ++i) {
    if (cover && cover->covered(i)) continue;
    std::optional<double> t_hit;
    if (states.is(i, ContactMode::masked)) {
      t_hit = reclosure(states, path, i, t_start, t_end, start[i], end[i], tolerances.overlap_allowance_m);
    } else if (states.is(i, ContactMode::armed)) {
      if (cover && !cover->live(i))
        t_hit = dormant_closing(path, i, t_start, t_end, start[i], end[i], tolerances.overlap_allowance_m);
      if (!t_hit) t_hit = dip(path, i, t_start, t_end, start[i], end[i], tolerances.contact_tolerance_m, grazes);
    }
    if (t_hit && (!earliest || *t_hit < earliest->t_s)) earliest = MissedContact{*t_hit, i};
  }
  return earliest;
}

}  // namespace pounding::solvers
