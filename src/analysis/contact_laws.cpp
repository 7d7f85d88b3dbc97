#include "pounding/analysis/contact_laws.hpp"

#include <algorithm>
#include <fmt/format.h>
#include <fmt/ranges.h>

#include "pounding/input_error.hpp"

namespace pounding::analysis {
namespace {

// Compliant laws need an integrator that stops at roots of the force and carries a state
// dependent Jacobian: the SUNDIALS paths. hht's contact step and the exact path's linear
// propagator assume impulses and held contacts.
const std::vector<std::string_view> kEventDrivenIntegrators{"cvode-bdf", "cvode-adams", "arkode-erk", "arkode-dirk"};

double impulse_rebound(double restitution) { return restitution; }
double kelvin_rebound(double restitution) {
  return contact::kelvin_release(contact::kelvin_damping_ratio(restitution)).rebound;
}

const std::vector<ContactLawInfo> kLaws = {
    {.name = "impulse",
     .description = "rigid impact with Newton's restitution, sustained contacts held: the paper's law",
     .law = contact::ContactLaw::impulse,
     .keys = {},
     .default_stiffness_kN_per_m = 0.0,
     .stiffness_source = "",
     .methods = {},
     .rebound = impulse_rebound},
    {.name = "kelvin",
     .description = "Kelvin-Voigt element F = k delta + c delta_dot while overlapping, c from restitution "
                    "(Anagnostopoulos 1988)",
     .law = contact::ContactLaw::kelvin,
     .keys = {"stiffness_kN_per_m"},
     // Jankowski (2005, Earthquake Engng Struct. Dyn. 34:595-611) fitted the linear viscoelastic
     // model to concrete-on-concrete impact tests: k = 93.5 kN/mm (quoted, not yet checked against the paper).
     .default_stiffness_kN_per_m = 93.5e3,
     .stiffness_source = "Jankowski 2005, linear viscoelastic fit to concrete impact tests (93.5 kN/mm)",
     .methods = kEventDrivenIntegrators,
     .rebound = kelvin_rebound},
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
  return fmt::format("Contact law: {} (default {}); kelvin runs on {}", contact_law_names(), kLaws.front().name,
                     fmt::join(kEventDrivenIntegrators, ", "));
}

}  // namespace pounding::analysis
