// The event-driven loop's units on their own: the contact state machine (ContactStates), the
// root-vector layout (WitnessLayout), the scan for contacts inside a step (scan_missed_contacts)
// against gap paths given in closed form, and the masked-flight step bound (EventStepBound).
#include <boost/test/unit_test.hpp>

#include <cmath>
#include <functional>

#include "../support/two_slabs.hpp"
#include "pounding/solvers/contact_states.hpp"
#include "pounding/solvers/event_step_bound.hpp"
#include "pounding/solvers/missed_contacts.hpp"

namespace tt = boost::test_tools;
using namespace pounding;
using solvers::ContactMode;

namespace {

constexpr double kAllowance_m = 1e-9;

contact::GapState gap_state(double gap_m, double rate_mps, double segment_param = 0.5) {
  contact::GapState s;
  s.contact_point.setZero();
  s.normal = {1.0, 0.0};
  s.striking_row.setZero();
  s.struck_row.setZero();
  s.gap_m = gap_m;
  s.gap_rate_mps = rate_mps;
  s.segment_param = segment_param;
  return s;
}

/// A gap path given as functions of time, the same for every candidate.
class ClosedFormPath final : public solvers::StepGaps {
 public:
  ClosedFormPath(std::function<double(double)> gap, std::function<double(double)> rate)
      : gap_(std::move(gap)), rate_(std::move(rate)) {}
  contact::GapState at(std::size_t, double t) override { return gap_state(gap_(t), rate_(t)); }
  double rate_round_off_mps(std::size_t) override { return 1e-15; }
  double depth_inside_m(std::size_t) override { return 1.0; }  // the closed forms' pairs are face to face
  contact::GapState at(double t) { return at(0, t); }

 private:
  std::function<double(double)> gap_, rate_;
};

/// g(t) = g_min + ½ a (t − t_min)²: a flight with its lowest point g_min at t_min.
ClosedFormPath parabola(double g_min, double t_min, double a) {
  return ClosedFormPath([=](double t) { return g_min + 0.5 * a * (t - t_min) * (t - t_min); },
                        [=](double t) { return a * (t - t_min); });
}

}  // namespace

BOOST_AUTO_TEST_CASE(ContactStatesFollowTheirNamedTransitions) {
  solvers::ContactStates states(3, kAllowance_m);
  BOOST_TEST(states.free_motion());
  BOOST_TEST(states.gap_witness(0, 0.25) == 0.25);  // armed: the gap itself

  states.mask(0, 1e-10, -2e-10);  // handled while 0.2 nm deep: floor 1 nm below that
  BOOST_TEST(states.is(0, ContactMode::masked));
  BOOST_TEST(states.mask_floor_m(0) == -2e-10 - kAllowance_m, tt::tolerance(1e-15));
  BOOST_TEST(states.gap_witness(0, 0.0) == 2e-10 + kAllowance_m, tt::tolerance(1e-12));
  states.mask(1, 1e-10, 0.3);  // open when masked: the floor is the allowance below zero
  BOOST_TEST(states.mask_floor_m(1) == -kAllowance_m);
  states.mask_beside_edge(2, 1e-10);
  BOOST_TEST(!states.has_floor(2));
  BOOST_TEST(states.gap_witness(2, -5.0) == 1.0);  // no root while it passes beside the edge

  // After a step: 0 reopened beyond its level, 1 did not; 2 came onto its edge 3 nm deep.
  states.rearm({gap_state(2e-10, 0.1), gap_state(5e-11, 0.1), gap_state(-3e-9, -0.1)},
               [](std::size_t) { return true; });
  BOOST_TEST(states.is(0, ContactMode::armed));
  BOOST_TEST(states.is(1, ContactMode::masked));
  BOOST_TEST(states.mask_floor_m(2) == -3e-9 - kAllowance_m, tt::tolerance(1e-15));

  BOOST_TEST(states.hold(0));
  BOOST_TEST(!states.hold(0));  // already held
  BOOST_TEST(states.hold(1));
  BOOST_TEST((states.held() == std::vector<std::size_t>{0, 1}));
  BOOST_TEST(!states.free_motion());
  BOOST_TEST(states.gap_witness(0, -1.0) == 1.0);  // a held gap is no root; its force is
  BOOST_TEST(states.release_hold(0, 1e-8, 0.0));
  BOOST_TEST(!states.release_hold(0, 1e-8, 0.0));  // not held any more
  BOOST_TEST((states.held() == std::vector<std::size_t>{1}));
  BOOST_TEST(states.is(0, ContactMode::masked));

  states.start_acting(2);
  BOOST_TEST((states.acting() == std::vector<std::size_t>{2}));
  states.stop_acting(2);
  BOOST_TEST(states.is(2, ContactMode::released));
  BOOST_TEST(states.acting().empty());
  states.start_acting(2);      // pushing again before the gap opened
  states.mask(2, 1e-10, 0.0);  // the contact is over
  BOOST_TEST(states.acting().empty());
  BOOST_TEST(states.is(2, ContactMode::masked));
}

BOOST_AUTO_TEST_CASE(WitnessLayoutNamesEachBlock) {
  const solvers::WitnessLayout layout(4);
  BOOST_TEST(layout.size() == 12);
  BOOST_TEST(layout.at(solvers::Witness::gap, 3) == 3);
  BOOST_TEST(layout.at(solvers::Witness::force, 1) == 5);
  BOOST_TEST(layout.at(solvers::Witness::edge, 2) == 10);
  const auto crossed = layout.crossed({0, 1, 0, 0, /*force*/ 0, 0, 0, -1, /*edge*/ 1, 0, 0, 0});
  BOOST_TEST((crossed.gap == std::vector<std::size_t>{1}));
  BOOST_TEST((crossed.force == std::vector<std::size_t>{3}));
  BOOST_TEST((crossed.edge == std::vector<std::size_t>{0}));
}

BOOST_AUTO_TEST_CASE(ADipBelowZeroInsideAStepIsAContactAtItsFirstCrossing) {
  // Both ends 0.25 m open, the lowest point 1 µm deep at 0.5 s: the crossing is at
  // t = 0.5 − √(2·1e-6/a).
  const double a = 2.0, depth = 1e-6;
  ClosedFormPath path = parabola(-depth, 0.5, a);
  solvers::ContactStates states(1, kAllowance_m);
  std::vector<solvers::Graze> grazes;
  const auto missed = solvers::scan_missed_contacts(states, path, 0.0, 1.0, {path.at(0.0)}, {path.at(1.0)}, {}, grazes);
  BOOST_TEST_REQUIRE(missed.has_value());
  BOOST_TEST(missed->t_s == 0.5 - std::sqrt(2.0 * depth / a), tt::tolerance(1e-12));
  BOOST_TEST(path.at(missed->t_s).gap_m <= 0.0);  // the root comes back on the closed side
  BOOST_TEST(grazes.empty());
}

BOOST_AUTO_TEST_CASE(AMinimumWithinTheTouchBandIsAGrazeAndOneAboveItIsNothing) {
  solvers::ContactStates states(1, kAllowance_m);
  std::vector<solvers::Graze> grazes;
  ClosedFormPath grazing = parabola(5e-9, 0.3, 2.0);  // 5 nm above contact: inside the 10 nm band
  BOOST_TEST(!solvers::scan_missed_contacts(states, grazing, 0.0, 1.0, {grazing.at(0.0)}, {grazing.at(1.0)},
                                            {.contact_tolerance_m = 1e-8}, grazes));
  BOOST_TEST_REQUIRE(grazes.size() == 1u);
  BOOST_TEST(grazes[0].t_s == 0.3, tt::tolerance(1e-9));
  BOOST_TEST(grazes[0].gap.gap_m == 5e-9, tt::tolerance(1e-6));
  ClosedFormPath clear = parabola(2e-8, 0.3, 2.0);
  grazes.clear();
  BOOST_TEST(!solvers::scan_missed_contacts(states, clear, 0.0, 1.0, {clear.at(0.0)}, {clear.at(1.0)},
                                            {.contact_tolerance_m = 1e-8}, grazes));
  BOOST_TEST(grazes.empty());
}

BOOST_AUTO_TEST_CASE(AMaskedPairThatFliesAndSinksAgainRecloseAtTheLastCrossing) {
  // Struck at t = 0 (masked at g = 0), it flies off at 0.1 m/s against g̈ = −0.3 m/s²:
  // g = 0.1 t − 0.15 t², back at zero at t = 2/3 s and 0.05 m deep at the step end t = 1 s.
  ClosedFormPath path([](double t) { return 0.1 * t - 0.15 * t * t; }, [](double t) { return 0.1 - 0.3 * t; });
  solvers::ContactStates states(1, kAllowance_m);
  states.mask(0, 1e-10, 0.0);
  std::vector<solvers::Graze> grazes;
  const auto missed = solvers::scan_missed_contacts(states, path, 0.0, 1.0, {path.at(0.0)}, {path.at(1.0)}, {}, grazes);
  BOOST_TEST_REQUIRE(missed.has_value());
  BOOST_TEST(missed->t_s == 2.0 / 3.0, tt::tolerance(1e-12));
  // A flight lower than the 32 samples resolve: g = 1e-12 − (t − 0.51)²·(…) with only its top
  // above zero, between two samples; the apex is polished and the crossing after it found.
  const double apex_t = 0.5105, apex_g = 1e-12, a = 1.0;
  ClosedFormPath low = parabola(apex_g, apex_t, -a);
  const auto low_missed =
      solvers::scan_missed_contacts(states, low, 0.5, 0.52, {low.at(0.5)}, {low.at(0.52)}, {}, grazes);
  BOOST_TEST_REQUIRE(low_missed.has_value());
  BOOST_TEST(low_missed->t_s == apex_t + std::sqrt(2.0 * apex_g / a), tt::tolerance(1e-9));
}

BOOST_AUTO_TEST_CASE(AnArmedOrRisingPairSetsNoFlightBoundAndAFallingMaskedOneAQuarterOfItsFlight) {
  using namespace testing;
  const auto system = two_slabs({}, diamond(0.05), {}, 0.05, 1.0);
  solvers::EventOptions options;
  options.max_step_s = 10.0;  // fixed, far above the flight bound
  solvers::EventStepBound bound(system, options);
  const Eigen::VectorXd y = Eigen::VectorXd::Zero(system.state_size());
  const double gap = 1e-3, rate = 0.1, accel = -2.0;
  solvers::ContactStates states(1, kAllowance_m);
  const solvers::CornerCover cover(system.candidates(), contact::link_corners(system.candidates(), {4, 4}), 1e-8);
  auto falling = [&](std::size_t) { return accel; };
  BOOST_TEST(bound.max_step_s(0.0, y, {gap_state(gap, rate)}, states, cover, falling) == 10.0);  // armed
  states.mask(0, 1e-10, 0.0);
  BOOST_TEST(bound.max_step_s(0.0, y, {gap_state(gap, rate)}, states, cover, [](std::size_t) { return 2.0; }) == 10.0);
  // Height above the floor h = g + 1 nm; back at the floor when h + ġτ + ½g̈τ² = 0.
  const double h = gap + kAllowance_m;
  const double flight = (rate + std::sqrt(rate * rate - 2.0 * h * accel)) / -accel;
  BOOST_TEST(bound.max_step_s(0.0, y, {gap_state(gap, rate)}, states, cover, falling) == flight / 4.0,
             tt::tolerance(1e-12));
}
