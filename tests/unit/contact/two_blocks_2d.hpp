#pragma once
// The 2D pair of blocks of the weighted-gap tests (test_gap_block_ends.cpp,
// test_prechecked_pairs.cpp): a lower block whose top (master) has facets 0.2 long at x = 0,
// 0.2, ..., 1 and an upper block whose bottom (slave) has facets 0.195 long at x = 0.13, 0.325,
// 0.52, 0.715, 0.91, touching at y = 0; a dual-multiplier contact interface between them; and
// g~ summed over the gap blocks.
#include "seam/contact/contact_interface.hpp"
#include "seam/mesh/gmsh_reader.hpp"

#include <filesystem>
#include <fstream>
#include <span>
#include <string>
#include <vector>

namespace seam::contact::two_blocks_2d {

inline constexpr const char* geo = R"(
Point(1) = {0, -0.5, 0}; Point(2) = {1, -0.5, 0}; Point(3) = {1, 0, 0}; Point(4) = {0, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 6; Transfinite Curve{2, 4} = 3; Transfinite Surface{1}; Recombine Surface{1};
Point(5) = {0.13, 0, 0}; Point(6) = {0.91, 0, 0}; Point(7) = {0.91, 0.4, 0}; Point(8) = {0.13, 0.4, 0};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Transfinite Curve{5, 7} = 5; Transfinite Curve{6, 8} = 3; Transfinite Surface{2}; Recombine Surface{2};
Physical Surface("lower") = {1}; Physical Surface("upper") = {2};
Physical Curve("master") = {3}; Physical Curve("slave") = {5};
)";

/// The mesh, meshed from a file `name`.geo in the temporary directory.
inline mesh::Mesh mesh(const std::string& name) {
  const auto path = std::filesystem::temp_directory_path() / (name + ".geo");
  std::ofstream(path) << geo;
  mesh::ReadOptions options;
  options.dim = 2;
  return mesh::read_mesh(path, options);
}

/// Slave "slave" (the upper block's bottom) against master "master", dual multipliers.
inline io::Interface contact() {
  io::Interface c;
  c.multiplier = io::Multiplier::dual;
  c.name.assign("contact");
  c.type = io::InterfaceType::contact;
  c.slave.name.assign("slave");
  c.master = io::RegionRef{"master", {}};
  return c;
}

/// g~ per slave node, summed over the gap blocks at the mesh displacement `u` (the interface
/// updated there).
inline std::vector<double> gaps(ContactInterface& itf, std::span<const double> u) {
  itf.update(u, 0.0);
  std::vector<GapBlock> blocks;
  itf.gap_blocks(u, GapOrder::value, blocks);
  std::vector<double> g(static_cast<std::size_t>(itf.n_slave_nodes()), 0.0);
  for (const auto& b : blocks)
    for (std::size_t r = 0; r < b.slave.size(); ++r)
      g[static_cast<std::size_t>(b.slave[r])] += b.gap[r];
  return g;
}

} // namespace seam::contact::two_blocks_2d
