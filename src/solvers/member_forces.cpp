#include "pounding/solvers/member_forces.hpp"

#include <fmt/format.h>

#include "pounding/model/building.hpp"

namespace pounding::solvers {

std::string_view member_force_name(MemberForce::Kind kind) {
  switch (kind) {
    case MemberForce::Kind::shear_x: return "Vx_kN";
    case MemberForce::Kind::shear_y: return "Vy_kN";
    case MemberForce::Kind::torque: return "T_kNm";
    case MemberForce::Kind::moment_x: return "Mx_kNm";
    case MemberForce::Kind::moment_y: return "My_kNm";
  }
  return "";
}

namespace {

Eigen::RowVector3d as_row(const std::array<double, 3>& t) { return {t[0], t[1], t[2]}; }

}  // namespace

MemberForces::MemberForces(const dynamics::CoupledSystem& system) : springs_(system.springs()) {
  using Kind = MemberForce::Kind;
  for (int b = 0; b < system.building_count(); ++b) {
    const model::Building& building = system.building(b);
    const model::BuildingDefinition& d = building.definition;
    for (int storey = 1; storey <= d.storeys; ++storey) {
      Storey s{.upper = system.floor_index(b, storey),
               .lower = storey > 1 ? system.floor_index(b, storey - 1) : -1,
               .remainder = Eigen::Matrix3d::Zero(),
               .members = {},
               .out = static_cast<int>(quantities_.size())};
      for (Kind kind : {Kind::shear_x, Kind::shear_y, Kind::torque})
        quantities_.push_back(
            {.building = b, .storey = storey, .column = -1, .column_key = {}, .kind = kind, .peak = {}});
      const double height_m = d.storey_height_m[static_cast<std::size_t>(storey - 1)];
      if (!d.uses_columns()) {
        // A storey matrix: its two storey springs along their rows, the rest of K elastic.
        const model::StoreySprings split = model::storey_springs(d, storey);
        s.remainder = d.storey_stiffness[static_cast<std::size_t>(storey - 1)];
        for (int direction = 0; direction < 2; ++direction) {
          Member m{.stiffness_kN_per_m = split.stiffness_kN_per_m[direction],
                   .row = as_row(split.rows[direction]),
                   .spring = springs_.index_of(b, storey, 0, direction),
                   .out = -1,  // a storey spring has no column forces of its own
                   .half_height_m = 0.0};
          s.remainder -= m.stiffness_kN_per_m * m.row.transpose() * m.row;
          s.members.push_back(m);
        }
        storeys_.push_back(std::move(s));
        continue;
      }
      for (std::size_t c = 0; c < d.columns.size(); ++c) {
        const int out = static_cast<int>(quantities_.size());
        for (Kind kind : {Kind::shear_x, Kind::shear_y, Kind::moment_x, Kind::moment_y}) {
          quantities_.push_back({.building = b,
                                 .storey = storey,
                                 .column = static_cast<int>(c),
                                 .column_key = model::column_key(d, c),
                                 .kind = kind,
                                 .peak = {}});
        }
        const Eigen::Vector2d k = model::column_stiffness(d.columns[c], d.E_kPa, height_m, building.frame_factor);
        for (int direction = 0; direction < 2; ++direction) {
          s.members.push_back({.stiffness_kN_per_m = k[direction],
                               .row = as_row(model::column_drift_row(d, c, direction)),
                               .spring = springs_.index_of(b, storey, c, direction),
                               .out = out + direction,
                               .half_height_m = 0.5 * height_m});
        }
      }
      storeys_.push_back(std::move(s));
    }
  }
}

std::vector<std::string> MemberForces::column_names() const {
  std::vector<std::string> names;
  for (const MemberForce& q : quantities_) {
    const std::string column = q.column >= 0 ? fmt::format("col{}_", q.column + 1) : std::string();
    names.push_back(fmt::format("B{}_s{}_{}{}", q.building + 1, q.storey, column, member_force_name(q.kind)));
  }
  return names;
}

void MemberForces::measure(const dynamics::VectorXd& y, const dynamics::SpringStates* springs,
                           Eigen::Ref<Eigen::VectorXd> out) const {
  for (const Storey& s : storeys_) {
    Eigen::Vector3d drift = y.segment<3>(s.upper);
    if (s.lower >= 0) drift -= y.segment<3>(s.lower);
    Eigen::Vector3d force = s.remainder * drift;
    for (const Member& m : s.members) {
      const double f_kN = springs != nullptr && m.spring ? springs_.force_kN(y, *springs, *m.spring)
                                                         : m.stiffness_kN_per_m * m.row.dot(drift);
      force += f_kN * m.row.transpose();
      if (m.out < 0) continue;
      out[m.out] = f_kN;
      out[m.out + 2] = f_kN * m.half_height_m;  // the moment sits two after its shear
    }
    out.segment<3>(s.out) = force;
  }
}

}  // namespace pounding::solvers
