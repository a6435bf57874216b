// The gap against a rigid plane on a curved slave surface. The plane's normal is the contact
// normal of every slave node, so the gap field over a slave facet is the distance of its points
// to the plane; with linear facets that field is the interpolant of the nodal distances, and the
// biorthogonality of the dual basis (on each facet) makes the nodal gap g~_j / D_jj the exact
// distance of node j, for every node that meets the plane's candidate zone whatever the tilt of
// its facets. Averaged slave normals would measure the distance along a tilted normal instead,
// (z_plane - z_j) / cos(theta), which grows without bound where the surface turns away.
#include "seam/contact/contact_interface.hpp"
#include "seam/mesh/gmsh_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace seam::contact {
namespace {

mesh::Mesh cylinder(int dim) {
  // A circular cylinder of radius 0.5 along x (3D, tetrahedra) or a disc (2D, triangles).
  std::string geo = "SetFactory(\"OpenCASCADE\");\nMesh.MeshSizeMax = 0.12;\n";
  if (dim == 2)
    geo += "Disk(1) = {0, 0, 0, 0.5};\nPhysical Surface(\"body\") = {1};\n"
           "Physical Curve(\"outer\") = {1};\n";
  else
    geo += "Cylinder(1) = {0, 0, 0, 1, 0, 0, 0.5};\nPhysical Volume(\"body\") = {1};\n"
           "Physical Surface(\"outer\") = {1};\n";
  const auto path = std::filesystem::temp_directory_path() /
                    (dim == 2 ? "rigid_gap_disc.geo" : "rigid_gap_cylinder.geo");
  std::ofstream(path) << geo;
  mesh::ReadOptions options;
  options.dim = dim;
  return mesh::read_mesh(path, options);
}

void check(int dim) {
  const auto mesh = cylinder(dim);
  io::Interface c;
  c.name.assign("wall");
  c.type = io::InterfaceType::contact;
  c.slave.name.assign("outer");
  // A plane cutting the top of the section (the upper 0.08 penetrates), normal towards the
  // body, slightly tilted so that no facet is parallel to it.
  io::RigidPlane plane;
  const double tilt = 0.1;
  plane.point = {0.0, 0.0, 0.0};
  plane.point[dim - 1] = 0.42;
  plane.normal = {0.0, 0.0, 0.0};
  plane.normal[0] = std::sin(tilt);
  plane.normal[dim - 1] = -std::cos(tilt);
  c.rigid_plane = plane;
  ContactInterface itf(c, mesh);
  // A smooth displacement flattens the section a little (u_vertical = -0.05 (y / 0.5)^2 in the
  // section plane), moved with the plane by a translation that changes nothing.
  std::vector<double> u(mesh.x.size(), 0.0);
  const auto n_nodes = static_cast<std::size_t>(mesh.n_nodes());
  for (std::size_t i = 0; i < n_nodes; ++i) {
    const double lateral = mesh.x[i * dim + (dim == 2 ? 0 : 1)];
    u[i * dim + dim - 1] = -0.05 * lateral * lateral / 0.25;
  }
  itf.update(u, 0.0);
  NodalValues values;
  itf.evaluate(values);
  const auto& nodes = itf.slave().mesh_nodes;
  int checked = 0, steep = 0;
  double err = 0.0;
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    if (values.D[j] <= 0.0) continue;
    // Distance of the current node from the plane, positive on the body's side.
    double distance = 0.0;
    for (int a = 0; a < dim; ++a) {
      const auto k = static_cast<std::size_t>(nodes[j]) * dim + static_cast<std::size_t>(a);
      distance += (mesh.x[k] + u[k] - plane.point[a]) * plane.normal[a];
    }
    err = std::max(err, std::abs(values.gap[j] / values.D[j] - distance));
    ++checked;
    // Nodes more than 30 degrees round the section from its top.
    const double lateral = mesh.x[static_cast<std::size_t>(nodes[j]) * dim + (dim == 2 ? 0 : 1)];
    if (std::abs(lateral) > 0.25) ++steep;
  }
  std::printf("  dim %d: %d slave nodes with a gap (%d on facets steeper than 30 degrees), "
              "max |g~/D - distance| = %.3e\n",
              dim, checked, steep, err);
  EXPECT_GT(checked, 10);
  EXPECT_GT(steep, 2);
  EXPECT_LT(err, 1e-12);
}

TEST(RigidPlaneGap, NodalGapIsTheDistanceOnACurvedSurface2D) {
  check(2);
}
TEST(RigidPlaneGap, NodalGapIsTheDistanceOnACurvedSurface3D) {
  check(3);
}

} // namespace
} // namespace seam::contact
