// The IMK peak-oriented law (dynamics/imk_law.hpp) on prescribed drift histories, against its
// published equations (Ibarra, Medina & Krawinkler 2005; the rules of OpenSees' IMKPeakOriented)
// evaluated by hand here: a spring of K_e = 1000 kN/m, F_y = 10 kN (U_y = 0.01 m), U_p = 0.03 m,
// F_max/F_y = 1.2 (the cap at 0.04 m, 12 kN, K_p = 2/0.03 kN/m), U_pc = 0.1 m (K_pc = −120 kN/m),
// F_res/F_y = 0.25 (from 0.040 + 9.5/120 m), U_u = 0.3 m. Driving a drift history means what an
// event-driven run does: the drift moves monotonically between turns, and the law is advanced at
// each end of its present branch and at each turn. The pinching case (IMKPinching) adds κ_F = 0.4,
// κ_D = 0.5. Tolerance 1e-12 relative (the hand formulas
// and the law's differ by round-off only).

#include <boost/test/unit_test.hpp>

#include <cmath>
#include <vector>

#include "pounding/dynamics/imk_law.hpp"

namespace tt = boost::test_tools;
using pounding::dynamics::ImkParameters;
using pounding::dynamics::ImkPeakOriented;
using pounding::dynamics::ImkSide;

namespace {

constexpr double kKe = 1000.0, kFy = 10.0, kUy = 0.01, kUp = 0.03, kCap = 1.2, kUpc = 0.1, kRes = 0.25, kUu = 0.3;
constexpr double kKp = (kCap - 1.0) * kFy / kUp, kKpc = -kCap * kFy / kUpc;

ImkParameters parameters(double lamda_m = 0.0, double residual_ratio = kRes) {
  const ImkSide side{.yield_force_kN = kFy,
                     .plastic_drift_m = kUp,
                     .post_cap_drift_m = kUpc,
                     .ultimate_drift_m = kUu,
                     .cap_ratio = kCap,
                     .residual_ratio = residual_ratio,
                     .deterioration_rate = 1.0};
  return {.stiffness_kN_per_m = kKe,
          .positive = side,
          .negative = side,
          .lamda_m = {lamda_m, lamda_m, lamda_m, lamda_m},
          .exponent = {1.0, 1.0, 1.0, 1.0}};
}

/// Moves the drift monotonically from `d` to `target`, advancing the law at the turn and at each
/// end of a branch on the way (as the run's events do).
void drive(ImkPeakOriented& law, double& d, double target) {
  const int direction = target > d ? 1 : -1;
  law.advance(d, direction);  // a turn: a loading branch reverses
  for (int guard = 0; guard < 32 && !law.failed(); ++guard) {
    const double end = direction > 0 ? law.line().upper_m : law.line().lower_m;
    if (direction * end > direction * target) break;
    d = end;
    if (!law.advance(d, direction)) break;
  }
  d = target;
}

/// ∫F dd along straight pieces between corner points (d, F): the trapezoids.
double polygon_work(const std::vector<std::pair<double, double>>& corners) {
  double work = 0.0;
  for (std::size_t i = 1; i < corners.size(); ++i)
    work += 0.5 * (corners[i - 1].second + corners[i].second) * (corners[i].first - corners[i - 1].first);
  return work;
}

}  // namespace

BOOST_AUTO_TEST_CASE(monotonic_backbone_matches_the_published_corners) {
  ImkPeakOriented law(parameters());
  double d = 0.0;
  drive(law, d, 0.005);
  BOOST_TEST(law.force_kN(d) == kKe * 0.005, tt::tolerance(1e-12));
  BOOST_TEST(law.branch() == 0);
  drive(law, d, 0.025);  // post-yield: F_y + K_p (d − U_y)
  BOOST_TEST(law.branch() == 5);
  BOOST_TEST(law.force_kN(d) == kFy + kKp * (0.025 - kUy), tt::tolerance(1e-12));
  BOOST_TEST(law.force_kN(kUy + kUp) == kCap * kFy, tt::tolerance(1e-12));
  drive(law, d, 0.08);  // post-capping: F_max + K_pc (d − U_cap)
  BOOST_TEST(law.branch() == 6);
  BOOST_TEST(law.force_kN(d) == kCap * kFy + kKpc * (0.08 - kUy - kUp), tt::tolerance(1e-12));
  const double residual_from_m = kUy + kUp + (kCap - kRes) * kFy / -kKpc;
  BOOST_TEST(law.line().upper_m == residual_from_m, tt::tolerance(1e-12));
  drive(law, d, 0.2);  // residual
  BOOST_TEST(law.branch() == 7);
  BOOST_TEST(law.force_kN(d) == kRes * kFy, tt::tolerance(1e-12));
  BOOST_TEST(law.line().upper_m == kUu);
  drive(law, d, 0.35);  // the ultimate drift: fails, all its work dissipated
  BOOST_TEST(law.failed());
  BOOST_TEST(law.force_kN(0.35) == 0.0);
  const double work =
      polygon_work({{0.0, 0.0}, {kUy, kFy}, {kUy + kUp, kCap * kFy}, {residual_from_m, kRes * kFy}, {kUu, kRes * kFy}});
  BOOST_TEST(law.dissipated_kJ(0.35) == work, tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(a_cycle_without_deterioration_is_peak_oriented) {
  ImkPeakOriented law(parameters());
  double d = 0.0;
  drive(law, d, 0.025);
  const double f1 = kFy + kKp * (0.025 - kUy);  // 11 kN
  drive(law, d, 0.02);                          // unloading at K_e
  BOOST_TEST(law.branch() == 1);
  BOOST_TEST(law.force_kN(d) == f1 - kKe * 0.005, tt::tolerance(1e-12));
  const double u0 = 0.025 - f1 / kKe;
  drive(law, d, -0.005);  // reloading towards the negative global peak, (−U_y, −F_y)
  BOOST_TEST(law.branch() == 14);
  const double k_reload = -kFy / (-kUy - u0);
  BOOST_TEST(law.force_kN(d) == k_reload * (-0.005 - u0), tt::tolerance(1e-12));
  drive(law, d, -0.02);  // on the negative backbone
  BOOST_TEST(law.branch() == 15);
  const double f2 = -kFy - kKp * 0.01;
  BOOST_TEST(law.force_kN(d) == f2, tt::tolerance(1e-12));
  drive(law, d, 0.0);  // unloads at K_e, then reloads towards the positive global peak (0.025, 11)
  const double u1 = -0.02 - f2 / kKe;
  BOOST_TEST(law.branch() == 4);
  BOOST_TEST(law.force_kN(0.0) == f1 / (0.025 - u1) * (0.0 - u1), tt::tolerance(1e-12));
  // At the zero-force drift u1 nothing is stored: the work of the loop is dissipated.
  const double loop =
      polygon_work({{0.0, 0.0}, {kUy, kFy}, {0.025, f1}, {u0, 0.0}, {-kUy, -kFy}, {-0.02, f2}, {u1, 0.0}});
  BOOST_TEST(law.dissipated_kJ(u1) == loop, tt::tolerance(1e-12));
  // Reloading past the old peak goes on along the backbone.
  drive(law, d, 0.03);
  BOOST_TEST(law.branch() == 5);
  BOOST_TEST(law.force_kN(d) == kFy + kKp * (0.03 - kUy), tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(deterioration_follows_the_energy_rules) {
  const double lamda_m = 1.0, reference_kJ = lamda_m * kFy;  // E_t = Λ F_y, every mode, c = 1, D = 1
  ImkPeakOriented law(parameters(lamda_m));
  double d = 0.0;
  drive(law, d, 0.025);
  const double f1 = kFy + kKp * 0.015;
  const double work1 = 0.5 * kFy * kUy + 0.5 * (kFy + f1) * 0.015;
  // Reversal: β_K = (E_i − ½F²/K_u) / (E_t − (E − ½F²/K_u)), with E_i = E (the first excursion).
  drive(law, d, 0.024);
  const double stored = 0.5 * f1 * f1 / kKe;
  const double beta_k = (work1 - stored) / (reference_kJ - (work1 - stored));
  const double k_unload = kKe * (1.0 - beta_k);
  BOOST_TEST(law.line().slope_kN_per_m == k_unload, tt::tolerance(1e-12));
  BOOST_TEST(law.force_kN(d) == f1 - k_unload * 0.001, tt::tolerance(1e-12));
  // New excursion at zero force: β = E_i / (E_t − E), E_i = E = the work so far.
  const double u0 = 0.025 - f1 / k_unload;
  drive(law, d, u0 - 0.001);
  const double work2 = work1 - 0.5 * f1 * f1 / k_unload;
  const double beta = work2 / (reference_kJ - work2);
  // The negative backbone after β_S, β_C, β_A (signed, as OpenSees' neg* members).
  const double fy = -kFy * (1.0 - beta), kp = kKp * (1.0 - beta), uy = fy / kKe;
  const double cap_intercept = (-kCap * kFy - kKpc * -(kUy + kUp)) * (1.0 - beta);
  const double fy_intercept = fy - kp * uy;
  const double u_cap = (cap_intercept - fy_intercept) / (kp - kKpc), f_cap = fy_intercept + kp * u_cap;
  const double u_global = -kUy * (1.0 + beta), f_global = fy + kp * (u_global - uy);  // beyond the new U_y
  BOOST_TEST(law.branch() == 14);
  BOOST_TEST(law.line().lower_m == u_global, tt::tolerance(1e-12));
  BOOST_TEST(law.force_kN(d) == f_global / (u_global - u0) * (d - u0), tt::tolerance(1e-12));
  drive(law, d, -0.03);  // on the deteriorated post-yield branch
  BOOST_TEST(law.branch() == 15);
  BOOST_TEST(law.force_kN(d) == f_cap + kp * (d - u_cap), tt::tolerance(1e-12));
  BOOST_TEST(law.line().lower_m == u_cap, tt::tolerance(1e-12));
  // The stored energy is ½F²/K_u with the deteriorated K_u: dissipated = work − that.
  const double work3 = work2 + 0.5 * law.force_kN(u_global) * (u_global - u0) +
                       0.5 * (law.force_kN(u_global) + law.force_kN(-0.03)) * (-0.03 - u_global);
  BOOST_TEST(law.dissipated_kJ(-0.03) == work3 - 0.5 * std::pow(law.force_kN(-0.03), 2) / k_unload,
             tt::tolerance(1e-12));
}

BOOST_AUTO_TEST_CASE(the_spring_fails_where_its_energy_is_spent_or_its_strength_ends) {
  // β_S = E_i / (E_t − E) > 1 at the first new excursion: E_t = 0.02 · 10 = 0.2 kJ, E ≈ 0.147 kJ.
  ImkPeakOriented exhausted(parameters(0.02));
  double d = 0.0;
  drive(exhausted, d, 0.025);
  BOOST_TEST(!exhausted.failed());
  drive(exhausted, d, -0.005);
  BOOST_TEST(exhausted.failed());
  BOOST_TEST(exhausted.force_kN(d) == 0.0);
  // E_t below the work already done (this program's rule): fails too.
  ImkPeakOriented spent(parameters(0.01));
  d = 0.0;
  drive(spent, d, 0.025);
  drive(spent, d, -0.005);
  BOOST_TEST(spent.failed());
  // A stiffness deterioration that would let unloading return more than the spring received,
  // ½F²/K_u > E (this program's rule): β_K = 0.147/(10 Λ_K − 0.147) at the first reversal, so
  // Λ_K = 0.033 gives β_K = 0.80, K_u = 200 kN/m, ½ 11²/200 = 0.30 kJ > E = 0.2075 kJ: fails; Λ_K =
  // 0.05 gives β_K = 0.42, 0.10 kJ: goes on unloading.
  for (const auto& [lamda_k, fails] : {std::pair{0.033, true}, std::pair{0.05, false}}) {
    ImkParameters only_k = parameters();
    only_k.lamda_m = {0.0, 0.0, 0.0, lamda_k};
    ImkPeakOriented law(only_k);
    d = 0.0;
    drive(law, d, 0.025);
    drive(law, d, 0.024);
    BOOST_TEST(law.failed() == fails);
    BOOST_TEST(law.dissipated_kJ(d) >= 0.0);
  }
  // No residual strength: fails at the end of the post-capping branch, at U_cap + F_max/|K_pc|.
  ImkPeakOriented brittle(parameters(0.0, 0.0));
  d = 0.0;
  drive(brittle, d, kUy + kUp + kUpc - 1e-9);
  BOOST_TEST(!brittle.failed());
  drive(brittle, d, kUy + kUp + kUpc + 1e-9);
  BOOST_TEST(brittle.failed());
}

BOOST_AUTO_TEST_CASE(pinching_reloads_through_the_pinching_point) {
  // IMKPinching: U_pinch = (1 − κ_D) (U_global − F_global/K_u), F_pinch = κ_F F_global (U_pinch − u0)/(U_global − u0).
  constexpr double kappa_f = 0.4, kappa_d = 0.5;
  ImkParameters p = parameters();
  p.pinching = pounding::dynamics::ImkPinching{.kappa_f = kappa_f, .kappa_d = kappa_d};
  ImkPeakOriented law(p);
  double d = 0.0;
  drive(law, d, 0.025);
  const double f1 = kFy + kKp * 0.015, u0 = 0.025 - f1 / kKe;
  // Towards the negative side, whose global peak (−U_y, −F_y) has no plastic drift: U_pinch = 0.
  drive(law, d, 0.005);
  const double f_pinch0 = kappa_f * -kFy * (0.0 - u0) / (-kUy - u0);
  BOOST_TEST(law.branch() == 12);
  BOOST_TEST(law.force_kN(d) == f_pinch0 / (0.0 - u0) * (d - u0), tt::tolerance(1e-12));
  drive(law, d, -0.005);  // past the pinching point: to the global peak
  BOOST_TEST(law.branch() == 14);
  BOOST_TEST(law.force_kN(d) == f_pinch0 + (-kFy - f_pinch0) / (-kUy) * -0.005, tt::tolerance(1e-12));
  drive(law, d, -0.02);
  const double f2 = -kFy - kKp * 0.01, u1 = -0.02 - f2 / kKe;
  drive(law, d, 0.0);  // towards the positive pinching point
  const double u_pinch = (1.0 - kappa_d) * (0.025 - f1 / kKe);
  const double f_pinch = kappa_f * f1 * (u_pinch - u1) / (0.025 - u1);
  BOOST_TEST(law.branch() == 2);
  BOOST_TEST(law.line().upper_m == u_pinch, tt::tolerance(1e-12));
  BOOST_TEST(law.force_kN(0.0) == f_pinch / (u_pinch - u1) * (0.0 - u1), tt::tolerance(1e-12));
  drive(law, d, 0.015);  // then to the global peak (0.025, 11)
  BOOST_TEST(law.branch() == 4);
  BOOST_TEST(law.force_kN(d) == f_pinch + (f1 - f_pinch) / (0.025 - u_pinch) * (0.015 - u_pinch), tt::tolerance(1e-12));
  // The loop's work up to the positive zero-force drift u1 is all dissipated there.
  const double loop = polygon_work(
      {{0.0, 0.0}, {kUy, kFy}, {0.025, f1}, {u0, 0.0}, {0.0, f_pinch0}, {-kUy, -kFy}, {-0.02, f2}, {u1, 0.0}});
  ImkPeakOriented again(p);
  double e = 0.0;
  for (double target : {0.025, u0 + 1e-3, -0.02, u1}) drive(again, e, target);
  BOOST_TEST(again.dissipated_kJ(u1) == loop, tt::tolerance(1e-12));
}
