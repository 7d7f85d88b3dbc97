#include "pounding/analysis/contact_laws.hpp"

#include <algorithm>
#include <cmath>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/contact/kelvin.hpp"
#include "pounding/input_error.hpp"

namespace pounding::analysis {
namespace {

// Compliant laws need an integrator that stops at roots of the force and carries a state
// dependent Jacobian: the SUNDIALS paths. hht's contact step and the exact path's linear
// propagator assume impulses and held contacts.
constexpr double kKipInKilonewtons = 4.4482216152605;
constexpr double kInchInMetres = 0.0254;
// Muthukumar & DesRoches' (2006) k_h = 25 000 kip/in^1.5 for concrete bridge decks (kN/m^1.5): the
// default of both hertzdamp laws.
const double kBridgeDeckHertzStiffness = 25e3 * kKipInKilonewtons / (kInchInMetres * std::sqrt(kInchInMetres));

const std::vector<std::string_view> kEventDrivenIntegrators{"cvode-bdf", "cvode-adams", "arkode-erk", "arkode-dirk"};

double impulse_rebound(double restitution) { return restitution; }
double kelvin_rebound(double restitution) {
  return contact::kelvin_release(contact::kelvin_damping_ratio(restitution)).rebound;
}

const std::vector<ContactLawInfo> kLaws = {
    {.name = "impulse",
     .description = "rigid impact with Newton's restitution, sustained contacts held: the paper's law",
     .law = contact::ContactLaw::impulse,
     .stiffness_key = "",
     .stiffness_unit = "",
     .default_stiffness = 0.0,
     .stiffness_source = "",
     .damping_key = "",
     .methods = {},
     .rebound = impulse_rebound},
    {.name = "kelvin",
     .description = "Kelvin-Voigt element F = k delta + c delta_dot while overlapping, c from restitution "
                    "(Anagnostopoulos 1988)",
     .law = contact::ContactLaw::kelvin,
     .stiffness_key = "stiffness_kN_per_m",
     .stiffness_unit = "kN/m",
     // Jankowski (2005, Earthquake Engng Struct. Dyn. 34:595-611) fitted the linear viscoelastic
     // model to concrete-on-concrete impact tests: k = 93.5 kN/mm (quoted, not yet checked against the paper).
     .default_stiffness = 93.5e3,
     .stiffness_source = "Jankowski 2005, linear viscoelastic fit to concrete impact tests (93.5 kN/mm)",
     .damping_key = "damping_ratio",
     .methods = kEventDrivenIntegrators,
     .rebound = kelvin_rebound},
    {.name = "hertzdamp",
     .description = "Hertz contact with nonlinear damping F = k_h delta^1.5 (1 + 3(1-e^2)/4 delta_dot/v0) "
                    "(Muthukumar & DesRoches 2006)",
     .law = contact::ContactLaw::hertzdamp,
     .stiffness_key = "stiffness_kN_per_m1_5",
     .stiffness_unit = "kN/m^1.5",
     // Muthukumar & DesRoches (2006, Earthquake Engng Struct. Dyn. 35:811-828) and Muthukumar
     // (2003) give k_h = 25 000 kip/in^1.5 for concrete bridge decks (as the OpenSees
     // ImpactMaterial documentation quotes them; not yet checked against the papers).
     .default_stiffness = kBridgeDeckHertzStiffness,
     .stiffness_source = "Muthukumar & DesRoches 2006, 25 000 kip/in^1.5 for concrete bridge decks (2.75e7 kN/m^1.5)",
     .damping_key = "normalised_damping",
     .methods = kEventDrivenIntegrators},
    {.name = "hertzdamp-ye",
     .description = "Hertz contact with nonlinear damping F = k_h delta^1.5 (1 + 8(1-e)/(5e) delta_dot/v0) "
                    "(Ye, Li & Zhu 2009): hertzdamp's form, its rebound within 0.05 of e at any e",
     .law = contact::ContactLaw::hertzdamp_ye,
     .stiffness_key = "stiffness_kN_per_m1_5",
     .stiffness_unit = "kN/m^1.5",
     .default_stiffness = kBridgeDeckHertzStiffness,
     .stiffness_source = "as hertzdamp: Muthukumar & DesRoches 2006, 25 000 kip/in^1.5 (2.75e7 kN/m^1.5)",
     .damping_key = "normalised_damping",
     .methods = kEventDrivenIntegrators},
    {.name = "jankowski",
     .description = "nonlinear viscoelastic F = beta delta^1.5 + c delta_dot approaching, beta delta^1.5 "
                    "separating, c from restitution (Jankowski 2005)",
     .law = contact::ContactLaw::jankowski,
     .stiffness_key = "stiffness_kN_per_m1_5",
     .stiffness_unit = "kN/m^1.5",
     // Jankowski (2005) fitted the nonlinear model to the same concrete impact tests as the
     // linear one: beta = 2.75e9 N/m^1.5 (quoted, not yet checked against the paper). At 1 mm
     // of overlap both fits push with about 90 kN.
     .default_stiffness = 2.75e6,
     .stiffness_source = "Jankowski 2005, nonlinear viscoelastic fit to concrete impact tests (2.75e9 N/m^1.5)",
     .damping_key = "damping_ratio",
     .methods = kEventDrivenIntegrators},
};

}  // namespace

std::span<const ContactLawInfo> contact_laws() { return kLaws; }

std::string contact_law_names() {
  std::vector<std::string_view> names;
  for (const ContactLawInfo& info : kLaws) names.push_back(info.name);
  if (names.size() < 2) return fmt::format("{}", fmt::join(names, ""));
  return fmt::format("{} or {}", fmt::join(names.begin(), names.end() - 1, ", "), names.back());
}

const ContactLawInfo& contact_law_info(std::string_view name, const std::string& key) {
  for (const ContactLawInfo& info : kLaws) {
    if (info.name == name) return info;
  }
  throw InputError(key, "\"" + std::string(name) + "\"", "expected " + contact_law_names());
}

double contact_damping(const ContactLawInfo& law, double restitution) {
  switch (law.law) {
    case contact::ContactLaw::impulse: return 0.0;
    case contact::ContactLaw::kelvin: return contact::kelvin_damping_ratio(restitution);
    case contact::ContactLaw::hertzdamp: return contact::hertzdamp_normalised_damping(restitution);
    case contact::ContactLaw::hertzdamp_ye: return contact::hertzdamp_ye_normalised_damping(restitution);
    case contact::ContactLaw::jankowski: return contact::jankowski_damping_ratio(restitution);
  }
  return 0.0;
}

bool supports(const ContactLawInfo& law, const MethodInfo& method) {
  return law.methods.empty() || std::find(law.methods.begin(), law.methods.end(), method.name) != law.methods.end();
}

void require_supported(const ContactLawInfo& law, const MethodInfo& method) {
  if (supports(law, method)) return;
  throw InputError("contact.law", "\"" + std::string(law.name) + "\"",
                   fmt::format("does not run on method {}: the {} law runs on {} only", method.name, law.name,
                               fmt::join(law.methods, ", ")));
}

std::string contact_laws_help() {
  return fmt::format("Contact law: {} (default {}); the compliant laws run on {}", contact_law_names(),
                     kLaws.front().name, fmt::join(kEventDrivenIntegrators, ", "));
}

std::string contact_stiffness_help() {
  std::vector<std::string> laws;
  for (const ContactLawInfo& info : kLaws) {
    if (info.stiffness_key.empty()) continue;
    laws.push_back(fmt::format("{}: {} {} (default {:g})", info.name, info.stiffness_key, info.stiffness_unit,
                               info.default_stiffness));
  }
  return fmt::format("Contact stiffness, in the law's unit; sets the law's key ({})", fmt::join(laws, "; "));
}

}  // namespace pounding::analysis
