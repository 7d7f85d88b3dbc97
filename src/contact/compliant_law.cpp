#include "pounding/contact/compliant_law.hpp"

#include <algorithm>
#include <cassert>
#include <cmath>
#include <numbers>

#include "pounding/contact/kelvin.hpp"

namespace pounding::contact {

std::string_view to_string(ContactLaw law) {
  switch (law) {
    case ContactLaw::impulse: return "impulse";
    case ContactLaw::kelvin: return "kelvin";
    case ContactLaw::hertzdamp: return "hertzdamp";
    case ContactLaw::hertzdamp_ye: return "hertzdamp-ye";
    case ContactLaw::jankowski: return "jankowski";
  }
  return "?";
}

double hertzdamp_normalised_damping(double restitution) { return 0.75 * (1.0 - restitution * restitution); }

double hertzdamp_ye_normalised_damping(double restitution) { return 1.6 * (1.0 - restitution) / restitution; }

bool refuses_plastic(ContactLaw law) { return law == ContactLaw::jankowski || law == ContactLaw::hertzdamp_ye; }

double jankowski_damping_ratio(double restitution) {
  const double e = restitution;
  return 9.0 * std::sqrt(5.0) * (1.0 - e * e) / (2.0 * e * (e * (9.0 * std::numbers::pi - 16.0) + 16.0));
}

CompliantContact::CompliantContact(ContactLaw law, double stiffness, double restitution, double approach_speed_mps,
                                   double normal_inverse_mass_per_t, double series_flexibility_m_per_kN)
    : law_(law), stiffness_(stiffness), series_flexibility_(series_flexibility_m_per_kN) {
  assert(law != ContactLaw::impulse && stiffness > 0.0 && approach_speed_mps > 0.0 && normal_inverse_mass_per_t > 0.0 &&
         series_flexibility_m_per_kN >= 0.0);
  switch (law) {
    case ContactLaw::impulse:
    case ContactLaw::kelvin:
      // Two springs in series; the damping ratio then holds for the pair.
      if (series_flexibility_ > 0.0) stiffness_ = 1.0 / (1.0 / stiffness + series_flexibility_);
      damping_ = kelvin_damping(stiffness_, restitution, normal_inverse_mass_per_t);
      break;
    case ContactLaw::hertzdamp:
      damping_ = hertzdamp_normalised_damping(restitution) * stiffness / approach_speed_mps;
      break;
    case ContactLaw::hertzdamp_ye:
      assert(restitution > 0.0);
      damping_ = hertzdamp_ye_normalised_damping(restitution) * stiffness / approach_speed_mps;
      break;
    case ContactLaw::jankowski:
      assert(restitution > 0.0);
      damping_ = 2.0 * jankowski_damping_ratio(restitution) * std::sqrt(stiffness / normal_inverse_mass_per_t);
      break;
  }
}

bool CompliantContact::acts() const { return law_ == ContactLaw::jankowski || !switched_; }

double CompliantContact::force_kN(double overlap_m, double rate_mps) const {
  if (!acts()) return 0.0;
  if (law_ == ContactLaw::kelvin) return stiffness_ * overlap_m + damping_ * rate_mps;
  const double overlap = own_overlap(std::max(overlap_m, 0.0));
  const double hertz = std::pow(overlap, 1.5);
  if (hertzdamp_form()) return hertz * (stiffness_ + damping_ * rate_mps);
  const bool approaching = !switched_;
  return stiffness_ * hertz + (approaching ? damping_ * std::pow(overlap, 0.25) * rate_mps : 0.0);
}

ForceSlopes CompliantContact::slopes(double overlap_m, double rate_mps) const {
  if (!acts()) return {};
  if (law_ == ContactLaw::kelvin) return {stiffness_, damping_};
  const double overlap = own_overlap(std::max(overlap_m, 0.0));
  const double root = std::sqrt(overlap);
  ForceSlopes slopes = hertz_slopes(overlap, root, rate_mps);
  if (series_flexibility_ > 0.0) slopes.per_overlap_kN_per_m *= own_overlap_slope(overlap);
  return slopes;
}

ForceSlopes CompliantContact::hertz_slopes(double overlap, double root, double rate_mps) const {
  if (hertzdamp_form()) {
    return {1.5 * root * (stiffness_ + damping_ * rate_mps), damping_ * overlap * root};
  }
  ForceSlopes slopes{1.5 * stiffness_ * root, 0.0};
  if (!switched_ && overlap > 0.0) {
    // c δ̇ with c ∝ δ^(1/4): its slope in δ, (c/4δ)δ̇, is unbounded at onset; a
    // Newton matrix only needs to be close, so it is taken at
    // kJankowskiSlopeFloor_m below that overlap.
    const double floored = std::max(overlap, kJankowskiSlopeFloor_m);
    slopes.per_overlap_kN_per_m += 0.25 * damping_ * std::pow(floored, -0.75) * rate_mps;
    slopes.per_rate_kNs_per_m = damping_ * std::pow(overlap, 0.25);
  }
  return slopes;
}

double CompliantContact::own_overlap(double overlap_m) const {
  if (series_flexibility_ == 0.0 || law_ == ContactLaw::kelvin || overlap_m <= 0.0) return overlap_m;
  // δ = s² + c s³ with s = √δ_c, c = f k: convex and increasing in s, so Newton from above (each
  // term alone reaching δ bounds s) descends monotonically onto the root.
  const double c = series_flexibility_ * stiffness_;
  double s = std::min(std::sqrt(overlap_m), std::cbrt(overlap_m / c));
  for (int i = 0; i < 100; ++i) {
    const double step = (s * s * (1.0 + c * s) - overlap_m) / (s * (2.0 + 3.0 * c * s));
    if (!(step > 1e-16 * s)) break;
    s -= step;
  }
  return s * s;
}

double CompliantContact::own_overlap_slope(double own_overlap_m) const {
  return 1.0 / (1.0 + 1.5 * series_flexibility_ * stiffness_ * std::sqrt(own_overlap_m));
}

double CompliantContact::first_switch(double overlap_m, double rate_mps) const {
  switch (law_) {
    case ContactLaw::impulse:
    case ContactLaw::kelvin: return stiffness_ * overlap_m + damping_ * rate_mps;
    case ContactLaw::hertzdamp:
    case ContactLaw::hertzdamp_ye: return stiffness_ + damping_ * rate_mps;
    case ContactLaw::jankowski: return rate_mps;
  }
  return 0.0;
}

double CompliantContact::switch_value(double overlap_m, double rate_mps) const {
  const double value = first_switch(overlap_m, rate_mps);
  return switched_ ? -value : value;
}

double CompliantContact::switch_rate(double, double rate_mps, double accel_mps2) const {
  double rate = 0.0;
  switch (law_) {
    case ContactLaw::impulse:
    case ContactLaw::kelvin: rate = stiffness_ * rate_mps + damping_ * accel_mps2; break;
    case ContactLaw::hertzdamp:
    case ContactLaw::hertzdamp_ye: rate = damping_ * accel_mps2; break;
    case ContactLaw::jankowski: rate = accel_mps2; break;
  }
  return switched_ ? -rate : rate;
}

}  // namespace pounding::contact
