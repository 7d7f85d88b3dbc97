#pragma once
// Small helpers shared by the tests: temporary files and simple buildings.

#include <filesystem>
#include <fstream>
#include <random>
#include <string>

#include "pounding/model/building.hpp"

namespace pounding::testing {

/// A folder under the system temp dir, removed with everything in it when the object dies.
class TempDir {
 public:
  TempDir() {
    std::random_device seed;
    path_ = std::filesystem::temp_directory_path() / ("pounding-test-" + std::to_string(seed()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() { std::filesystem::remove_all(path_); }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  /// Writes `content` byte for byte (no newline added) and returns the file's path.
  std::filesystem::path write(const std::string& name, const std::string& content) const {
    const auto file = path_ / name;
    std::ofstream(file, std::ios::binary) << content;
    return file;
  }
  const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// A square slab of side `side_m` centred on the origin with one column at each corner and the
/// CM at `cm`; uniform storeys. Frame factor 1.
inline model::BuildingDefinition square_building(int storeys, double side_m, double mass_t, double polar_moment_tm2,
                                                 model::Point2 cm = model::Point2::Zero()) {
  model::BuildingDefinition b;
  b.name = "test";
  b.storeys = storeys;
  b.storey_height_m.assign(storeys, 3.0);
  const double h = side_m / 2;
  b.slab = model::Polygon({{-h, -h}, {h, -h}, {h, h}, {-h, h}});
  b.centre_of_mass = cm;
  b.mass_t.assign(storeys, mass_t);
  b.polar_moment_tm2.assign(storeys, polar_moment_tm2);
  for (const model::Point2& corner : b.slab.vertices()) b.columns.push_back({corner, 0.4, 0.4});
  b.E_kPa = 3.0e7;
  b.frame_factor = 1.0;
  return b;
}

}  // namespace pounding::testing
