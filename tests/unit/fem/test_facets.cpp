// Facets of the reference cells: each lies on one face of the reference domain, every face
// appears once, the facet's own parametrisation reproduces the cell's trace and gives the
// outward normal.
#include "fem_test_support.hpp"
#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <set>
#include <vector>

namespace seam::fem {
namespace {

using test::all_cell_types;

// Faces of a reference domain as (axis, value) for tensor cells, and (axis, 0) or
// (-1, "sum = 1") for simplices. Returns every face all given points lie on.
std::vector<std::pair<int, double>> faces_containing(CellType t,
                                                     const std::vector<std::array<double, 3>>& x) {
  const int dim = dimension(t);
  std::vector<std::pair<int, double>> candidates;
  for (int a = 0; a < dim; ++a) {
    if (test::is_simplex(t)) {
      candidates.emplace_back(a, 0.0);
    } else {
      candidates.emplace_back(a, -1.0);
      candidates.emplace_back(a, 1.0);
    }
  }
  if (test::is_simplex(t)) candidates.emplace_back(-1, 1.0);
  std::vector<std::pair<int, double>> hits;
  for (const auto& [axis, value] : candidates) {
    bool all = true;
    for (const auto& p : x) {
      double v = 0.0;
      if (axis >= 0) {
        v = p[static_cast<std::size_t>(axis)];
      } else {
        for (int a = 0; a < dim; ++a) v += p[static_cast<std::size_t>(a)];
      }
      all = all && std::abs(v - value) < 1e-14;
    }
    if (all) hits.emplace_back(axis, value);
  }
  return hits;
}

std::array<double, 3> ref_node(CellType t, int i) {
  std::array<double, 3> x{0.0, 0.0, 0.0};
  const int dim = dimension(t);
  for (int a = 0; a < dim; ++a)
    x[static_cast<std::size_t>(a)] = reference_nodes(t)[static_cast<std::size_t>(i * dim + a)];
  return x;
}

// Reference point of the cell at facet-local coordinates eta, through the facet's shape
// functions.
std::array<double, 3> facet_map(CellType t, int f, const double* eta) {
  const CellType ft = facet_type(t, f);
  const auto nodes = facet_nodes(t, f);
  std::array<double, max_facet_nodes> N{};
  shape_values(ft, eta, N.data());
  std::array<double, 3> x{0.0, 0.0, 0.0};
  for (std::size_t k = 0; k < nodes.size(); ++k) {
    const auto X = ref_node(t, nodes[k]);
    for (std::size_t a = 0; a < 3; ++a) x[a] += N[k] * X[a];
  }
  return x;
}

CellType linear_version(CellType t) {
  switch (t) {
  case CellType::line3:
    return CellType::line2;
  case CellType::tri6:
    return CellType::tri3;
  case CellType::quad8:
  case CellType::quad9:
    return CellType::quad4;
  default:
    return t;
  }
}

int expected_n_facets(CellType t) {
  switch (dimension(t)) {
  case 0:
    return 0;
  case 1:
    return 2;
  case 2:
    return test::is_simplex(t) ? 3 : 4;
  default:
    return test::is_simplex(t) ? 4 : 6;
  }
}

TEST(Facets, TypesAndCounts) {
  for (CellType t : all_cell_types) {
    SCOPED_TRACE(name(t));
    ASSERT_EQ(n_facets(t), expected_n_facets(t));
    for (int f = 0; f < n_facets(t); ++f) {
      const CellType ft = facet_type(t, f);
      EXPECT_EQ(dimension(ft), dimension(t) - 1);
      // A facet carries the cell's order (point facets excepted).
      if (dimension(ft) > 0) {
        EXPECT_EQ(order(ft), order(t));
      }
      EXPECT_EQ(facet_nodes(t, f).size(), static_cast<std::size_t>(n_nodes(ft)));
    }
    EXPECT_THROW(facet_nodes(t, n_facets(t)), InputError);
    EXPECT_THROW(facet_type(t, -1), InputError);
  }
}

TEST(Facets, EachLiesOnOneFaceWhichItCoversAndFacesAppearOnce) {
  for (CellType t : all_cell_types) {
    SCOPED_TRACE(name(t));
    std::set<std::pair<int, double>> seen;
    for (int f = 0; f < n_facets(t); ++f) {
      const auto nodes = facet_nodes(t, f);
      std::vector<std::array<double, 3>> x;
      std::set<int> distinct(nodes.begin(), nodes.end());
      EXPECT_EQ(distinct.size(), nodes.size());
      for (int i : nodes) {
        ASSERT_GE(i, 0);
        ASSERT_LT(i, n_nodes(t));
        x.push_back(ref_node(t, i));
      }
      const auto faces = faces_containing(t, x);
      ASSERT_EQ(faces.size(), 1u) << "facet " << f;
      EXPECT_TRUE(seen.insert(faces[0]).second) << "facet " << f << " repeats a face";
      // Every cell node on that face belongs to the facet.
      int on_face = 0;
      for (int i = 0; i < n_nodes(t); ++i) {
        const auto faces_of_i = faces_containing(t, {ref_node(t, i)});
        if (std::find(faces_of_i.begin(), faces_of_i.end(), faces[0]) != faces_of_i.end())
          ++on_face;
      }
      EXPECT_EQ(on_face, static_cast<int>(nodes.size())) << "facet " << f;
      // Facet corners are cell corners.
      const int facet_corners = dimension(t) == 1 ? 1 : n_vertices(facet_type(t, f));
      for (int k = 0; k < facet_corners; ++k)
        EXPECT_LT(nodes[static_cast<std::size_t>(k)], n_vertices(t)) << "facet " << f;
    }
    EXPECT_EQ(static_cast<int>(seen.size()), n_facets(t));
  }
}

// Higher-order facet nodes sit where the facet's own node order puts them: each equals the
// image of its facet-reference position under the facet's linear (corner) map.
TEST(Facets, HigherOrderNodesFollowTheFacetNodeOrder) {
  for (CellType t : all_cell_types) {
    if (dimension(t) < 2) continue;
    SCOPED_TRACE(name(t));
    for (int f = 0; f < n_facets(t); ++f) {
      const CellType ft = facet_type(t, f);
      const CellType lin = linear_version(ft);
      const auto nodes = facet_nodes(t, f);
      const int fdim = dimension(ft);
      for (int j = 0; j < n_nodes(ft); ++j) {
        std::array<double, 4> N{};
        shape_values(lin, reference_nodes(ft).data() + j * fdim, N.data());
        std::array<double, 3> x{0.0, 0.0, 0.0};
        for (int c = 0; c < n_nodes(lin); ++c) {
          const auto X = ref_node(t, nodes[static_cast<std::size_t>(c)]);
          for (std::size_t a = 0; a < 3; ++a) x[a] += N[static_cast<std::size_t>(c)] * X[a];
        }
        const auto Y = ref_node(t, nodes[static_cast<std::size_t>(j)]);
        for (std::size_t a = 0; a < 3; ++a)
          EXPECT_NEAR(x[a], Y[a], 1e-15) << "facet " << f << " node " << j;
      }
    }
  }
}

// The restriction of the cell's shape functions to a facet equals the facet's shape functions
// (cell node fn[k] <-> facet node k), and every other cell shape function vanishes there.
TEST(Facets, CellTraceEqualsFacetInterpolation) {
  std::mt19937 rng(7);
  for (CellType t : all_cell_types) {
    if (dimension(t) < 1) continue;
    SCOPED_TRACE(name(t));
    for (int f = 0; f < n_facets(t); ++f) {
      const CellType ft = facet_type(t, f);
      const auto nodes = facet_nodes(t, f);
      for (int s = 0; s < 5; ++s) {
        const auto eta = test::random_point(ft, rng);
        const auto x = facet_map(t, f, eta.data());
        std::array<double, max_cell_nodes> N{};
        std::array<double, max_facet_nodes> Nf{};
        shape_values(t, x.data(), N.data());
        shape_values(ft, eta.data(), Nf.data());
        std::vector<double> expected(static_cast<std::size_t>(n_nodes(t)), 0.0);
        for (std::size_t k = 0; k < nodes.size(); ++k)
          expected[static_cast<std::size_t>(nodes[k])] = Nf[k];
        for (int i = 0; i < n_nodes(t); ++i)
          EXPECT_NEAR(N[static_cast<std::size_t>(i)], expected[static_cast<std::size_t>(i)], 1e-14)
              << "facet " << f << " node " << i;
      }
    }
  }
}

// Normal from the facet's own parametrisation: 3D dx/deta1 x dx/deta2, 2D (t_y, -t_x); it must
// point away from the cell centroid (all reference faces are flat, so the sign at the facet
// centre decides). Line cells: facet 0 is xi = -1, facet 1 is xi = +1.
TEST(Facets, ParametrisationGivesOutwardNormal) {
  std::mt19937 rng(11);
  for (CellType t : all_cell_types) {
    const int dim = dimension(t);
    if (dim < 1) continue;
    SCOPED_TRACE(name(t));
    const auto centroid = test::reference_centroid(t);
    for (int f = 0; f < n_facets(t); ++f) {
      const auto nodes = facet_nodes(t, f);
      if (dim == 1) {
        EXPECT_EQ(reference_nodes(t)[static_cast<std::size_t>(nodes[0])], f == 0 ? -1.0 : 1.0);
        continue;
      }
      const CellType ft = facet_type(t, f);
      for (int s = 0; s < 4; ++s) {
        const auto eta = s == 0 ? test::reference_centroid(ft) : test::random_point(ft, rng);
        std::array<double, max_facet_nodes * 2> dN{};
        shape_gradients(ft, eta.data(), dN.data());
        std::array<double, 3> g1{0.0, 0.0, 0.0}, g2{0.0, 0.0, 0.0};
        for (std::size_t k = 0; k < nodes.size(); ++k) {
          const auto X = ref_node(t, nodes[k]);
          for (std::size_t a = 0; a < 3; ++a) {
            g1[a] += dN[k * static_cast<std::size_t>(dim - 1)] * X[a];
            if (dim == 3) g2[a] += dN[k * 2 + 1] * X[a];
          }
        }
        std::array<double, 3> n{};
        if (dim == 2) {
          n = {g1[1], -g1[0], 0.0};
        } else {
          n = {g1[1] * g2[2] - g1[2] * g2[1], g1[2] * g2[0] - g1[0] * g2[2],
               g1[0] * g2[1] - g1[1] * g2[0]};
        }
        const auto x = facet_map(t, f, eta.data());
        double dot = 0.0, nn = 0.0, dd = 0.0;
        for (std::size_t a = 0; a < 3; ++a) {
          dot += n[a] * (x[a] - centroid[a]);
          nn += n[a] * n[a];
          dd += (x[a] - centroid[a]) * (x[a] - centroid[a]);
        }
        EXPECT_GT(nn, 1e-3) << "facet " << f << ": degenerate parametrisation";
        EXPECT_GT(dot, 0.1 * std::sqrt(nn * dd)) << "facet " << f << " normal points inwards";
      }
    }
  }
}

} // namespace
} // namespace seam::fem
