// Facet evaluation, linear sub-facets and projections onto every facet type.
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "mortar_test_support.hpp"
#include "seam/common/error.hpp"
#include "seam/geometry/projection.hpp"
#include "seam/mortar/facet.hpp"
#include "seam/mortar/normals.hpp"

using namespace seam::mortar;
using seam::local_index;
using seam::fem::CellType;

namespace {

// Curved, non-affine facet: reference nodes mapped onto a doubly curved surface.
Facet<3> curved_facet(CellType type) {
  Facet<3> f;
  f.type = type;
  f.n_nodes = seam::fem::n_nodes(type);
  const double* ref = seam::fem::reference_nodes(type).data();
  for (int i = 0; i < f.n_nodes; ++i) {
    const double s = ref[2 * i], t = ref[2 * i + 1];
    f.x.col(i) = Eigen::Vector3d(1.0 + s + 0.1 * t * t, 2.0 + t + 0.05 * s,
                                 0.3 * s * s - 0.2 * t * t + 0.1 * s * t);
  }
  return f;
}

} // namespace

TEST(Facet, EvaluateInterpolatesNodes) {
  for (const CellType type :
       {CellType::tri3, CellType::tri6, CellType::quad4, CellType::quad8, CellType::quad9}) {
    const Facet<3> f = curved_facet(type);
    const double* ref = seam::fem::reference_nodes(type).data();
    for (int i = 0; i < f.n_nodes; ++i) {
      const auto p = evaluate(f, ref + 2 * i);
      EXPECT_TRUE(p.x.isApprox(f.x.col(i), 1e-14)) << seam::fem::name(type) << " " << i;
      EXPECT_NEAR(p.N.sum(), 1.0, 1e-14);
    }
  }
}

TEST(Facet, ProjectionRecoversParameters) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0.05, 0.45);
  for (const CellType type :
       {CellType::tri3, CellType::tri6, CellType::quad4, CellType::quad8, CellType::quad9}) {
    const Facet<3> f = curved_facet(type);
    const bool tri = type == CellType::tri3 || type == CellType::tri6;
    for (int trial = 0; trial < 10; ++trial) {
      const Eigen::Vector2d xi =
          tri ? Eigen::Vector2d(u(rng), u(rng)) : Eigen::Vector2d(4 * u(rng) - 1, 4 * u(rng) - 1);
      const Eigen::Vector3d d = Eigen::Vector3d(0.1 * u(rng), -0.2, 1.0).normalized();
      const double alpha = 2 * u(rng) - 0.5;
      const Eigen::Vector3d p = evaluate(f, xi.data()).x + alpha * d;
      const auto r = project_onto_facet(f, p, d);
      ASSERT_TRUE(r.converged) << seam::fem::name(type);
      EXPECT_NEAR(r.xi.x(), xi.x(), 1e-12);
      EXPECT_NEAR(r.xi.y(), xi.y(), 1e-12);
      EXPECT_NEAR(r.alpha, alpha, 1e-12);
    }
  }
  // 2D: onto a curved line3 along a fixed direction.
  Facet<2> line;
  line.type = CellType::line3;
  line.n_nodes = 3;
  line.x.col(0) = Eigen::Vector2d(0, 0);
  line.x.col(1) = Eigen::Vector2d(2, 0.4);
  line.x.col(2) = Eigen::Vector2d(1.1, 0.5);
  for (const double xi : {-0.9, -0.2, 0.5, 1.0}) {
    const Eigen::Vector2d d(0.3, -1.0);
    const auto r = project_onto_facet(line, evaluate(line, &xi).x + 0.7 * d, d);
    ASSERT_TRUE(r.converged);
    EXPECT_NEAR(r.xi, xi, 1e-12);
  }
}

TEST(Facet, SubFacetsTileTheFacet) {
  // On a flat facet the pieces' areas sum to the facet area and each keeps the orientation.
  for (const CellType type :
       {CellType::tri3, CellType::tri6, CellType::quad4, CellType::quad8, CellType::quad9}) {
    Facet<3> f;
    f.type = type;
    f.n_nodes = seam::fem::n_nodes(type);
    const double* ref = seam::fem::reference_nodes(type).data();
    for (int i = 0; i < f.n_nodes; ++i)
      f.x.col(i) = Eigen::Vector3d(2 * ref[2 * i] + 0.5 * ref[2 * i + 1], 3 * ref[2 * i + 1], 0.0);
    const double facet_area = (type == CellType::tri3 || type == CellType::tri6 ? 0.5 : 4.0) * 6.0;
    double sum = 0.0;
    for (const SubFacet& sub : linear_subfacets(type)) {
      double twice = 0.0;
      for (int v = 0; v < sub.n_vertices; ++v) {
        const Eigen::Vector3d a = f.x.col(sub.nodes[static_cast<std::size_t>(v)]);
        const Eigen::Vector3d b =
            f.x.col(sub.nodes[static_cast<std::size_t>((v + 1) % sub.n_vertices)]);
        twice += a.x() * b.y() - a.y() * b.x();
      }
      EXPECT_GT(twice, 0.0) << seam::fem::name(type);
      sum += 0.5 * twice;
    }
    EXPECT_NEAR(sum, facet_area, 1e-13) << seam::fem::name(type);
  }
  EXPECT_THROW(linear_subfacets(CellType::line2), seam::InputError);
}

TEST(Facet, ValidateRejectsBadInput) {
  test::Surface s = test::grid(
      2, 2, CellType::quad4, [](double u, double v) { return Eigen::Vector3d(u, v, 0); }, false);
  EXPECT_NO_THROW(validate(s.view(), "slave"));
  test::Surface bad = s;
  bad.nodes[3] = 1000;
  EXPECT_THROW(validate(bad.view(), "slave"), seam::InputError);
  bad = s;
  bad.types[0] = CellType::line2;
  EXPECT_THROW(validate(bad.view(), "slave"), seam::InputError);
  bad = s;
  bad.dim = 2;
  EXPECT_THROW(validate(bad.view(), "slave"), seam::InputError);
}

TEST(NodalNormals, CircleIsRadial) {
  // Uniform line2 and line3 meshes of a full circle, run counter-clockwise so the disc lies
  // on the left (seam::fem orientation): outward normals, whose average is radial by symmetry.
  for (const CellType type : {CellType::line2, CellType::line3}) {
    const auto circle = [](double s) {
      const double t = 2 * std::numbers::pi * s;
      return Eigen::Vector2d(2 * std::cos(t), 2 * std::sin(t));
    };
    test::Surface s = test::line_mesh(12, type, circle, false);
    // Close the circle: the last node duplicates the first; reuse node 0 instead.
    const local_index last = s.n_nodes() - 1;
    for (auto& n : s.nodes)
      if (n == last) n = 0;
    const auto normals = averaged_nodal_normals(s.view());
    for (local_index i = 0; i < last; ++i) {
      const Eigen::Vector2d x(s.coordinates[2 * i], s.coordinates[2 * i + 1]);
      EXPECT_NEAR(normals[2 * i], x.normalized().x(), 1e-14);
      EXPECT_NEAR(normals[2 * i + 1], x.normalized().y(), 1e-14);
    }
  }
}

TEST(NodalNormals, CylinderAndBoxCorner) {
  // Quad grid on a cylinder of radius 1.5 about the z axis (u: angle, v: axis), facets
  // oriented outward: interior nodes get the radial normal.
  const test::Surface cyl = test::grid(
      6, 3, CellType::quad9,
      [](double u, double v) {
        return Eigen::Vector3d(1.5 * std::cos(u), 1.5 * std::sin(u), 2 * v);
      },
      false);
  const auto normals = averaged_nodal_normals(cyl.view());
  for (local_index i = 0; i < cyl.n_nodes(); ++i) {
    const Eigen::Vector3d x(cyl.coordinates[3 * i], cyl.coordinates[3 * i + 1], 0.0);
    const Eigen::Vector3d n(normals[3 * i], normals[3 * i + 1], normals[3 * i + 2]);
    EXPECT_NEAR(n.norm(), 1.0, 1e-14);
    const double u = std::atan2(x.y(), x.x());
    if (u > 1e-9 && u < 1 - 1e-9) {
      EXPECT_TRUE(n.isApprox(x.normalized(), 1e-12)) << i;
    }
  }
  // Three faces of the unit cube meeting at (1,1,1), one tri3 each: (1,1,1)/sqrt(3).
  test::Surface corner;
  corner.coordinates = {1, 1, 1, 0, 1, 1, 1, 0, 1, 1, 1, 0};
  corner.add_facet(CellType::tri3,
                   {0, 1, 2}); // top, z = 1, normal +z: (0,1,1)-(1,1,1) x (1,0,1)-(1,1,1)
  corner.add_facet(CellType::tri3, {0, 2, 3}); // x = 1, normal +x
  corner.add_facet(CellType::tri3, {0, 3, 1}); // y = 1, normal +y
  const auto nc = averaged_nodal_normals(corner.view());
  for (int a = 0; a < 3; ++a)
    EXPECT_NEAR(nc[static_cast<std::size_t>(a)], 1 / std::sqrt(3.0), 1e-15);
}

TEST(NodalNormals, FoldedNodeIsFound) {
  // Three nodes on the x axis, node 1 beyond node 2: facet (0, 1) runs in +x, facet (1, 2) in
  // -x, so their unit normals at node 1 are (0, -1) and (0, 1) and cancel there. Node 2's
  // single facet gives it a normal; node 0 likewise.
  test::Surface folded;
  folded.dim = 2;
  folded.coordinates = {0, 0, 2, 0, 1, 0};
  folded.add_facet(CellType::line2, {0, 1});
  folded.add_facet(CellType::line2, {1, 2});
  EXPECT_EQ(folded_node(folded.view()), 1);
  EXPECT_THROW(averaged_nodal_normals(folded.view()), seam::InputError);
  const std::vector<local_index> adjacent{0, 1};
  const std::vector<local_index> node{1};
  EXPECT_THROW(averaged_nodal_normals(folded.view(), adjacent, node), seam::InputError);
  // Node 1 back between its neighbours: no fold.
  folded.coordinates[2] = 0.5;
  EXPECT_EQ(folded_node(folded.view()), -1);
  const auto normals = averaged_nodal_normals(folded.view());
  EXPECT_NEAR(normals[3], -1.0, 1e-15);
}
