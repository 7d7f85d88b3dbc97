#pragma once
// The peaks of a run (FloorPeaks per floor of each building): displacements and the contact
// vertices' x-displacements, storey drifts at the CM and the corners, absolute accelerations; the
// groups an OutputSelection asks for. Each is updated at every instant the recorder measures, and
// inside each stretch located at the turning points of its value, found from the rates at the
// stretch's ends and polished on the stretch's interpolant, so a peak does not depend on where
// the steps end.

#include <array>
#include <functional>
#include <vector>

#include "pounding/solvers/run_kinematics.hpp"
#include "pounding/solvers/run_result.hpp"

namespace pounding::solvers {

class PeakTracker {
 public:
  /// Writes the components `indices` of the state at t into y (others may be left stale): a
  /// cheaper state for the peaks, which read two to four components each.
  using ComponentsAt = std::function<void(double t, const std::vector<int>& indices, dynamics::VectorXd& y)>;
  using StateAt = std::function<dynamics::VectorXd(double)>;

  /// @pre `kinematics` outlives the tracker.
  PeakTracker(const RunKinematics& kinematics, const OutputSelection& outputs);

  /// The peaks at the instant `at` (measured with the accelerations and drifts the selection asks for).
  void update(const Instant& at);
  /// The turning points inside the stretch (t_a, t_b) from `start` to `end` (both measured as for
  /// update; their acceleration rates are filled in here), on the stretch's states `at`, or
  /// `components_at` for displacements and drifts when given.
  void locate(double t_a, double t_b, Instant& start, Instant& end, const StateAt& at,
              const ComponentsAt& components_at);
  /// The peaks, per building.
  std::vector<BuildingPeaks> take() { return std::move(peaks_); }

 private:
  /// The components of the state that a floor's peaks read, for ComponentsAt.
  struct FloorComponents {
    std::array<std::vector<int>, 3> coordinate;  // (u, u̇), (v, v̇), (φ, φ̇)
    std::vector<int> vertex;                     // u, φ and their rates
    std::vector<int> drift;                      // the floor's and the floor below's (u, v, φ) and rates
  };

  void locate_displacements(double t_a, double t_b, const Instant& start, const Instant& end, const StateAt& at,
                            const ComponentsAt& components_at);
  void locate_drifts(double t_a, double t_b, const Instant& start, const Instant& end, const StateAt& at,
                     const ComponentsAt& components_at);
  void locate_accelerations(double t_a, double t_b, Instant& start, Instant& end, const StateAt& at);
  /// The state at t with (at least) the components `indices` right, from `components_at` when
  /// given, else `at`; in partial_, valid until the next call.
  const dynamics::VectorXd& read_components(double t, const std::vector<int>& indices, const StateAt& at,
                                            const ComponentsAt& components_at);
  /// Updates `peak` at the turning point of `value` inside (t_a, t_b), if its rate changes sign
  /// there and it can beat the peak.
  template <class State, class Value, class Rate>
  void locate_peak(Peak& peak, double t_a, double t_b, const dynamics::VectorXd& y_a, const dynamics::VectorXd& y_b,
                   const State& state_at, const Value& value, const Rate& rate);

  const RunKinematics& kinematics_;
  const dynamics::CoupledSystem& system_;
  OutputSelection outputs_;
  std::vector<std::vector<FloorComponents>> components_;  // per building and floor, as peaks_
  std::vector<BuildingPeaks> peaks_;
  dynamics::VectorXd partial_, accel_lo_, accel_hi_;  // states and accelerations inside a stretch
};

}  // namespace pounding::solvers
