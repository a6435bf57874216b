// The chunked .msh reader with parallel partitioning (mesh/distribute_file.hpp), checked against
// the Gmsh-API reader: every rank reads the same file whole with read_mesh (small meshes) and
// the brute-force check of distribution_check.hpp compares cells, nodes, coordinates (bit for
// bit), regions, ghost layers and numbering. Files are written by the gmsh executable in MSH 4.1,
// ASCII and binary: tets and hexes in 3D (two blocks tied at z = 1), triangles and quads in 2D,
// first and second order. Bad files exit through an InputError naming the file on every rank.
#include "distribution_check.hpp"
#include "seam/common/error.hpp"
#include "seam/mesh/distribute_file.hpp"
#include "seam/mesh/gmsh_reader.hpp"
#include "seam/mesh/msh_chunk.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

namespace seam::parallel::test {
namespace {

namespace fs = std::filesystem;

// A directory every rank sees (rank 0 names it).
fs::path shared_dir() {
  std::string name;
  if (rank() == 0) {
    name = (fs::temp_directory_path() / ("seam_distribute_file_" + std::to_string(::getpid())))
               .string();
    fs::create_directories(name);
  }
  std::uint64_t n = name.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, 0, world());
  name.resize(n);
  MPI_Bcast(name.data(), static_cast<int>(n), MPI_CHAR, 0, world());
  return name;
}

// Rank 0 meshes `geo` with the gmsh executable into `name` (MSH 4.1); every rank waits.
fs::path mesh_file(const std::string& geo, const std::string& name, int dim, bool binary,
                   int order) {
  const auto dir = shared_dir();
  const auto msh = dir / name;
  if (rank() == 0) {
    std::ofstream(dir / "in.geo") << geo;
    const std::string cmd = "gmsh -" + std::to_string(dim) + " -order " + std::to_string(order) +
                            " -format msh41" + (binary ? " -bin" : "") + " " +
                            (dir / "in.geo").string() + " -o " + msh.string() + " > /dev/null";
    EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  }
  MPI_Barrier(world());
  return msh;
}

const std::string blocks_geo = R"(SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 1, 1};
Box(2) = {0, 0, 1, 1, 1, 1};
Transfinite Curve{1:12} = 5;
Transfinite Surface{1:6};
Recombine Surface{1:6};
Transfinite Volume{1};
MeshSize{PointsOf{Volume{2};}} = 0.3;
Physical Volume("lower") = {1};
Physical Volume("upper") = {2};
Physical Surface("bottom") = {5};
Physical Surface("top") = {12};
Physical Surface("lower_top") = {6};
Physical Surface("upper_bottom") = {11};
Physical Curve("edge") = {1};
Physical Point("corner") = {1};
)";

std::string square_geo(bool quads) {
  return std::string(R"(Point(1) = {0, 0, 0, 0.2}; Point(2) = {2, 0, 0, 0.2};
Point(3) = {2, 1, 0, 0.2}; Point(4) = {0, 1, 0, 0.2};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Surface("plate") = {1};
Physical Curve("bottom") = {1};
Physical Curve("top") = {3};
Physical Point("origin") = {1};
)") + (quads ? "Recombine Surface{1};\n" : "");
}

void compare(const fs::path& file, const std::vector<std::string>& interfaces) {
  const mesh::Mesh g = mesh::read_mesh(file);
  const DistributedMesh d = mesh::distribute_file(file, world(), interfaces);
  EXPECT_EQ(d.n_global_cells, g.n_cells());
  check_part(g, d, interfaces);
  if (size() > 1) {
    EXPECT_LT(d.n_cells(), g.n_cells()) << "rank " << rank() << " holds every cell";
  }
}

TEST(DistributeFile, TiedHexAndTetBlocksAsciiAndBinary) {
  for (int order : {1, 2}) {
    for (bool binary : {false, true}) {
      SCOPED_TRACE("order " + std::to_string(order) + (binary ? " binary" : " ascii"));
      const auto file = mesh_file(blocks_geo, "blocks.msh", 3, binary, order);
      compare(file, {"lower_top", "upper_bottom"});
    }
  }
}

TEST(DistributeFile, TrianglesAndQuadsAsciiAndBinary) {
  for (bool quads : {false, true}) {
    for (int order : {1, 2}) {
      for (bool binary : {false, true}) {
        SCOPED_TRACE(std::string(quads ? "quads" : "triangles") + " order " +
                     std::to_string(order) + (binary ? " binary" : " ascii"));
        const auto file = mesh_file(square_geo(quads), "plate.msh", 2, binary, order);
        compare(file, {"top"});
      }
    }
  }
}

// The parallel partition is a function of the file and the number of ranks: reading the same
// file again in the same processes gives every rank the same cells with the same roles (PT-Scotch
// with one thread per rank and its random generator reset; docs/parallel.md "Reproducible runs").
// Across processes test_restart.py's test_partition_reproducible checks it.
TEST(DistributeFile, SamePartitionEveryTime) {
  const auto file = mesh_file(blocks_geo, "again.msh", 3, true, 2);
  const std::vector<std::string> sides = {"lower_top"};
  const DistributedMesh first = mesh::distribute_file(file, world(), sides);
  for (int again = 0; again < 3; ++again) {
    const DistributedMesh d = mesh::distribute_file(file, world(), sides);
    EXPECT_EQ(d.cell_gid, first.cell_gid) << "read " << again + 2 << ", rank " << rank();
    EXPECT_EQ(d.cell_owner, first.cell_owner) << "read " << again + 2 << ", rank " << rank();
    EXPECT_EQ(d.node_index, first.node_index) << "read " << again + 2 << ", rank " << rank();
  }
}

// Truncated files and other versions: MSH 2.2 is left to Gmsh (MshUnsupported); a truncated
// 4.1 file is an InputError naming the file on every rank.
TEST(DistributeFile, BadFilesNameTheFileOnEveryRank) {
  for (bool binary : {false, true}) {
    const auto file = mesh_file(blocks_geo, "cut.msh", 3, binary, 1);
    if (rank() == 0) fs::resize_file(file, fs::file_size(file) * 2 / 3);
    MPI_Barrier(world());
    try {
      mesh::distribute_file(file, world());
      ADD_FAILURE() << "a truncated file was read";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
    }
  }
  const auto dir = shared_dir();
  const auto old = dir / "old.msh";
  if (rank() == 0) {
    std::ofstream(dir / "in.geo") << square_geo(false);
    EXPECT_EQ(std::system(("gmsh -2 -format msh22 " + (dir / "in.geo").string() + " -o " +
                           old.string() + " > /dev/null")
                              .c_str()),
              0);
  }
  MPI_Barrier(world());
  EXPECT_THROW(mesh::distribute_file(old, world()), mesh::MshUnsupported);
  const auto wrong = dir / "wrong.msh";
  if (rank() == 0) std::ofstream(wrong) << "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 2\n";
  MPI_Barrier(world());
  try {
    mesh::distribute_file(wrong, world());
    ADD_FAILURE() << "a broken file was read";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(wrong.string()), std::string::npos) << e.what();
  }
  MPI_Barrier(world());
  if (rank() == 0) fs::remove_all(dir);
}

} // namespace
} // namespace seam::parallel::test
