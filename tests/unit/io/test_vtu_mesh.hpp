#pragma once
// A small mixed mesh for the VTU tests: a hexahedron and a tetrahedron on its x = max face, with
// coordinates and field values chosen to catch any loss of bits (thirds, tenths, -0.0, a
// subnormal, huge and tiny magnitudes).
#include "seam/io/vtu.hpp"

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace seam::test {

inline constexpr std::uint8_t vtk_tetra = 10;      // VTK_TETRA
inline constexpr std::uint8_t vtk_hexahedron = 12; // VTK_HEXAHEDRON
inline constexpr std::uint8_t vtk_triangle = 5;    // VTK_TRIANGLE
inline constexpr std::uint8_t vtk_quad = 9;        // VTK_QUAD

struct MixedMesh {
  std::vector<double> points;
  std::vector<std::int32_t> connectivity{0, 1, 2, 3, 4, 5, 6, 7, /* tet */ 1, 8, 2, 5};
  std::vector<std::int32_t> offsets{8, 12};
  std::vector<std::uint8_t> types{vtk_hexahedron, vtk_tetra};
  std::vector<double> displacement; // 3 per point
  std::vector<std::int32_t> status; // 1 per point
  std::vector<double> von_mises;    // 1 per cell
  std::vector<double> stress;       // 6 per cell
  std::vector<std::int32_t> rank{0, 3};
  double time = 0.1 + 0.2; // not 0.3: its last bit must survive
  std::int64_t cycle = 7;

  MixedMesh() {
    const double cube[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                               {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    for (const auto& p : cube)
      for (const double x : p) points.push_back(x + x / 3.0);
    points.insert(points.end(), {2.0 + 0.1, -0.0, std::numeric_limits<double>::denorm_min()});
    for (std::size_t i = 0; i < 9; ++i) {
      for (int c = 0; c < 3; ++c)
        displacement.push_back(std::sin(1.0 + double(i) + 0.37 * c) * 1e-3);
      status.push_back(std::int32_t(i % 3) - 1);
    }
    displacement[4] = -0.0;
    displacement[7] = 1.0e300;
    displacement[11] = -std::numeric_limits<double>::min();
    von_mises = {1.0 / 7.0, 2.5e8};
    for (int k = 0; k < 12; ++k) stress.push_back(std::exp(0.5 * k) - 100.0);
  }

  io::VtuPiece piece() const {
    io::VtuPiece p;
    p.point_dim = 3;
    p.points = points;
    p.connectivity = connectivity;
    p.offsets = offsets;
    p.types = types;
    p.point_data.emplace_back("displacement", 3, std::span<const double>(displacement));
    p.point_data.emplace_back("status", 1, std::span<const std::int32_t>(status));
    p.cell_data.emplace_back("von_mises", 1, std::span<const double>(von_mises));
    p.cell_data.emplace_back("stress", 6, std::span<const double>(stress));
    p.cell_data.emplace_back("rank", 1, std::span<const std::int32_t>(rank));
    p.time = time;
    p.cycle = cycle;
    return p;
  }
};

} // namespace seam::test
