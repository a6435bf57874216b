#pragma once
// Shared helpers for the mesh tests: a scratch directory, .geo sources for the unit square and
// cube, and exact geometric transformations applied to a mesh.
#include "seam/mesh/mesh.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace seam::mesh::test {

/// A fresh directory per test, removed afterwards.
class ScratchDir {
public:
  /// Named after the running test, or after `name` outside a test (suite set-up).
  explicit ScratchDir(const std::string& name = "") {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string label =
        info != nullptr ? std::string(info->test_suite_name()) + "_" + info->name() : name;
    std::replace(label.begin(), label.end(), '/', '_'); // parameterised test names

    path_ = std::filesystem::temp_directory_path() /
            ("seam_mesh_" + std::to_string(::getpid()) + "_" + label);
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;

  std::filesystem::path write(const std::string& name, const std::string& text) const {
    const auto file = path_ / name;
    std::ofstream(file) << text;
    return file;
  }
  std::filesystem::path operator/(const std::string& name) const { return path_ / name; }

private:
  std::filesystem::path path_;
};

/// Unit square [0,1]^2 (built-in kernel) with regions "square", "bottom" (y = 0), "right"
/// (x = 1), "top" (y = 1), "left" (x = 0), "origin" (a point). structured_n > 0 makes it a
/// transfinite n x n grid; quads recombines the triangles.
inline std::string unit_square_geo(int structured_n, bool quads) {
  std::string geo = "Point(1) = {0, 0, 0};\nPoint(2) = {1, 0, 0};\n"
                    "Point(3) = {1, 1, 0};\nPoint(4) = {0, 1, 0};\n"
                    "Line(1) = {1, 2};\nLine(2) = {2, 3};\nLine(3) = {3, 4};\nLine(4) = {4, 1};\n"
                    "Curve Loop(1) = {1, 2, 3, 4};\nPlane Surface(1) = {1};\n";
  if (structured_n > 0)
    geo += "Transfinite Curve{1, 2, 3, 4} = " + std::to_string(structured_n + 1) +
           ";\nTransfinite Surface{1};\n";
  if (quads) geo += "Recombine Surface{1};\n";
  geo += "Physical Surface(\"square\") = {1};\nPhysical Curve(\"bottom\") = {1};\n"
         "Physical Curve(\"right\") = {2};\nPhysical Curve(\"top\") = {3};\n"
         "Physical Curve(\"left\") = {4};\nPhysical Point(\"origin\") = {1};\n";
  return geo;
}

/// Unit cube [0,1]^3 (OpenCASCADE) with regions "cube" and "x0", "x1", "y0", "y1", "z0", "z1"
/// (the faces x = 0, x = 1, ...). structured_n > 0 makes a transfinite n^3 grid of hexes.
inline std::string unit_cube_geo(int structured_n) {
  std::string geo = "SetFactory(\"OpenCASCADE\");\nBox(1) = {0, 0, 0, 1, 1, 1};\n";
  if (structured_n > 0)
    geo += "Transfinite Curve{:} = " + std::to_string(structured_n + 1) +
           ";\nTransfinite Surface{:};\nRecombine Surface{:};\nTransfinite Volume{1};\n";
  geo += "Physical Volume(\"cube\") = {1};\n";
  const char* names[3][2] = {{"x0", "x1"}, {"y0", "y1"}, {"z0", "z1"}};
  for (int a = 0; a < 3; ++a)
    for (int side = 0; side < 2; ++side) {
      double lo[3] = {-0.1, -0.1, -0.1}, hi[3] = {1.1, 1.1, 1.1};
      lo[a] = side - 0.1;
      hi[a] = side + 0.1;
      geo += std::string("Physical Surface(\"") + names[a][side] + "\") = Surface In BoundingBox{" +
             std::to_string(lo[0]) + ", " + std::to_string(lo[1]) + ", " + std::to_string(lo[2]) +
             ", " + std::to_string(hi[0]) + ", " + std::to_string(hi[1]) + ", " +
             std::to_string(hi[2]) + "};\n";
    }
  return geo;
}

/// Apply a map to every node (the map gets and returns 3 coordinates; z = 0 in 2D).
template <class Map> void transform(Mesh& mesh, Map&& map) {
  for (std::int32_t n = 0; n < mesh.n_nodes(); ++n) {
    std::array<double, 3> p{};
    for (int a = 0; a < mesh.dim; ++a) p[a] = mesh.x[static_cast<std::size_t>(n * mesh.dim + a)];
    const auto q = map(p);
    for (int a = 0; a < mesh.dim; ++a) mesh.x[static_cast<std::size_t>(n * mesh.dim + a)] = q[a];
  }
}

} // namespace seam::mesh::test
