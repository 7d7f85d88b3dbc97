#include "pounding/solvers/history_schema.hpp"

#include <cmath>

namespace pounding::solvers {
namespace {

using Per = HistoryQuantity::Per;

/// Displacement (m) of the contact vertex k, exact rotation about the CM.
model::Point2 vertex_displacement(const SlabSample& s, std::size_t k) {
  return point_displacement(s.contact_vertices[k] - s.centre, s.q[0], s.q[1], std::cos(s.q[2]), std::sin(s.q[2]));
}

double vertex_dx(const SlabSample& s, std::size_t k) { return vertex_displacement(s, k).x(); }
double vertex_dy(const SlabSample& s, std::size_t k) { return vertex_displacement(s, k).y(); }

}  // namespace

std::string HistoryQuantity::column(int n) const {
  std::string text(name);
  if (const std::size_t at = text.find("{n}"); at != std::string::npos && n > 0) text.replace(at, 3, std::to_string(n));
  return unit.empty() ? text : text + "_" + std::string(unit);
}

const std::vector<HistoryQuantity>& history_quantities() {
  static const std::vector<HistoryQuantity> quantities = {
      {"u", "m", Per::slab, "x-displacement of the slab's centre of mass, relative to the ground",
       [](const SlabSample& s, std::size_t) { return s.q[0]; }},
      {"v", "m", Per::slab, "y-displacement of the centre of mass, relative to the ground",
       [](const SlabSample& s, std::size_t) { return s.q[1]; }},
      {"phi", "rad", Per::slab, "rotation of the slab about the centre of mass, counter-clockwise positive",
       [](const SlabSample& s, std::size_t) { return s.q[2]; }},
      {"vtx{n}_dx", "m", Per::contact_vertex,
       "x-displacement of contact vertex n (its number in the slab outline), exact rotation", vertex_dx},
      {"ax_abs", "mps2", Per::slab, "absolute x-acceleration of the centre of mass (ground's included)",
       [](const SlabSample& s, std::size_t) { return s.accel[0]; }},
      {"ay_abs", "mps2", Per::slab, "absolute y-acceleration of the centre of mass",
       [](const SlabSample& s, std::size_t) { return s.accel[1]; }},
      {"phi_ddot", "radps2", Per::slab, "angular acceleration of the slab",
       [](const SlabSample& s, std::size_t) { return s.accel[2]; }},
      {"drift_x", "", Per::slab, "x-drift ratio of the storey below at the centre of mass (its height's fraction)",
       [](const SlabSample& s, std::size_t) { return s.drift[0]; }},
      {"drift_y", "", Per::slab, "y-drift ratio of the storey below at the centre of mass",
       [](const SlabSample& s, std::size_t) { return s.drift[1]; }},
      {"c{n}_drift_x", "", Per::corner, "x-drift ratio of the storey below at slab corner n (outline order)",
       [](const SlabSample& s, std::size_t k) { return s.drift[2 * k + 2]; }},
      {"c{n}_drift_y", "", Per::corner, "y-drift ratio of the storey below at slab corner n",
       [](const SlabSample& s, std::size_t k) { return s.drift[2 * k + 3]; }},
      {"vtx{n}_dy", "m", Per::contact_vertex, "y-displacement of contact vertex n, exact rotation", vertex_dy},
  };
  return quantities;
}

}  // namespace pounding::solvers
