// Shape functions: partition of unity, Kronecker property, gradients against central
// differences, and exact reproduction of the cell's polynomial space (complete P_k on
// simplices, tensor Q_k on Lagrange lines/quads/hexes, serendipity S_2 on quad8/hex20). The
// Kronecker property plus reproduction of n_nodes independent polynomials identifies the basis
// uniquely.
#include "fem_test_support.hpp"
#include "seam/fem/cell.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <random>
#include <vector>

namespace seam::fem {
namespace {

using test::all_cell_types;
using Exponents = std::array<int, 3>;

bool is_serendipity(CellType t) {
  return t == CellType::quad8 || t == CellType::hex20;
}

// Monomial basis of the space the cell's shape functions must span.
std::vector<Exponents> polynomial_space(CellType t) {
  const int dim = dimension(t);
  const int k = order(t);
  std::vector<Exponents> space;
  const int top = std::max(k, 0);
  for (int c = 0; c <= (dim >= 3 ? top : 0); ++c)
    for (int b = 0; b <= (dim >= 2 ? top : 0); ++b)
      for (int a = 0; a <= (dim >= 1 ? top : 0); ++a) {
        bool keep = false;
        if (test::is_simplex(t)) {
          keep = a + b + c <= k; // complete P_k
        } else if (is_serendipity(t)) {
          // superlinear degree <= 2 (Arnold & Awanou 2011): at most one exponent equals 2
          keep = (a == 2) + (b == 2) + (c == 2) <= 1;
        } else {
          keep = true; // tensor Q_k
        }
        if (keep) space.push_back({a, b, c});
      }
  return space;
}

double monomial(const Exponents& e, const double* x, int dim) {
  double v = 1.0;
  for (int a = 0; a < dim; ++a) v *= std::pow(x[a], e[static_cast<std::size_t>(a)]);
  return v;
}

double monomial_derivative(const Exponents& e, const double* x, int dim, int d) {
  double v = 1.0;
  for (int a = 0; a < dim; ++a) {
    const int p = e[static_cast<std::size_t>(a)];
    if (a == d) {
      v *= p == 0 ? 0.0 : p * std::pow(x[a], p - 1);
    } else {
      v *= std::pow(x[a], p);
    }
  }
  return v;
}

std::vector<std::array<double, 3>> sample_points(CellType t, int n) {
  std::mt19937 rng(1234 + static_cast<int>(t));
  std::vector<std::array<double, 3>> pts;
  for (int i = 0; i < n; ++i) pts.push_back(test::random_point(t, rng));
  return pts;
}

TEST(ShapeFunctions, PartitionOfUnityAndGradientsSumToZero) {
  for (CellType t : all_cell_types) {
    SCOPED_TRACE(name(t));
    const int dim = dimension(t);
    for (const auto& xi : sample_points(t, 25)) {
      std::array<double, max_cell_nodes> N{};
      std::array<double, max_cell_nodes * 3> dN{};
      shape_values(t, xi.data(), N.data());
      shape_gradients(t, xi.data(), dN.data());
      double sum = 0.0;
      std::array<double, 3> grad_sum{0.0, 0.0, 0.0};
      for (int i = 0; i < n_nodes(t); ++i) {
        sum += N[static_cast<std::size_t>(i)];
        for (int a = 0; a < dim; ++a)
          grad_sum[static_cast<std::size_t>(a)] += dN[static_cast<std::size_t>(i * dim + a)];
      }
      EXPECT_NEAR(sum, 1.0, 1e-14);
      for (int a = 0; a < dim; ++a) EXPECT_NEAR(grad_sum[static_cast<std::size_t>(a)], 0.0, 1e-13);
    }
  }
}

TEST(ShapeFunctions, KroneckerDeltaAtNodes) {
  for (CellType t : all_cell_types) {
    SCOPED_TRACE(name(t));
    const int dim = dimension(t);
    const auto X = reference_nodes(t);
    for (int j = 0; j < n_nodes(t); ++j) {
      std::array<double, max_cell_nodes> N{};
      shape_values(t, X.data() + j * dim, N.data());
      for (int i = 0; i < n_nodes(t); ++i)
        EXPECT_NEAR(N[static_cast<std::size_t>(i)], i == j ? 1.0 : 0.0, 1e-15)
            << "N_" << i << " at node " << j;
    }
  }
}

TEST(ShapeFunctions, GradientsMatchCentralDifferences) {
  const double h = 1e-5;
  for (CellType t : all_cell_types) {
    SCOPED_TRACE(name(t));
    const int dim = dimension(t);
    const int n = n_nodes(t);
    for (const auto& xi : sample_points(t, 10)) {
      std::array<double, max_cell_nodes * 3> dN{};
      shape_gradients(t, xi.data(), dN.data());
      for (int a = 0; a < dim; ++a) {
        auto xp = xi;
        auto xm = xi;
        xp[static_cast<std::size_t>(a)] += h;
        xm[static_cast<std::size_t>(a)] -= h;
        std::array<double, max_cell_nodes> Np{}, Nm{};
        shape_values(t, xp.data(), Np.data());
        shape_values(t, xm.data(), Nm.data());
        for (int i = 0; i < n; ++i) {
          const auto ui = static_cast<std::size_t>(i);
          // Shape functions are at most cubic per direction: the O(h^2) error is ~1e-10.
          EXPECT_NEAR(dN[ui * static_cast<std::size_t>(dim) + static_cast<std::size_t>(a)],
                      (Np[ui] - Nm[ui]) / (2 * h), 1e-9)
              << "dN_" << i << "/dxi_" << a;
        }
      }
    }
  }
}

TEST(ShapeFunctions, SpaceHasOneMonomialPerNode) {
  for (CellType t : all_cell_types)
    EXPECT_EQ(polynomial_space(t).size(), static_cast<std::size_t>(n_nodes(t))) << name(t);
}

TEST(ShapeFunctions, ReproducePolynomialsOfTheirSpaceWithGradients) {
  for (CellType t : all_cell_types) {
    SCOPED_TRACE(name(t));
    const int dim = dimension(t);
    const auto X = reference_nodes(t);
    for (const Exponents& e : polynomial_space(t)) {
      for (const auto& xi : sample_points(t, 10)) {
        std::array<double, max_cell_nodes> N{};
        std::array<double, max_cell_nodes * 3> dN{};
        shape_values(t, xi.data(), N.data());
        shape_gradients(t, xi.data(), dN.data());
        double value = 0.0;
        std::array<double, 3> grad{0.0, 0.0, 0.0};
        for (int i = 0; i < n_nodes(t); ++i) {
          const double p_i = monomial(e, X.data() + i * dim, dim);
          value += N[static_cast<std::size_t>(i)] * p_i;
          for (int a = 0; a < dim; ++a)
            grad[static_cast<std::size_t>(a)] += dN[static_cast<std::size_t>(i * dim + a)] * p_i;
        }
        EXPECT_NEAR(value, monomial(e, xi.data(), dim), 1e-14)
            << "monomial " << e[0] << " " << e[1] << " " << e[2];
        for (int a = 0; a < dim; ++a)
          EXPECT_NEAR(grad[static_cast<std::size_t>(a)], monomial_derivative(e, xi.data(), dim, a),
                      1e-13)
              << "monomial " << e[0] << " " << e[1] << " " << e[2] << " d/dxi_" << a;
      }
    }
  }
}

// The serendipity cells must not be the full tensor space: x^2 y^2 is not reproduced.
TEST(ShapeFunctions, SerendipityMissesBiquadratic) {
  for (CellType t : {CellType::quad8, CellType::hex20}) {
    const int dim = dimension(t);
    const auto X = reference_nodes(t);
    const std::array<double, 3> xi{0.3, -0.4, 0.2};
    std::array<double, max_cell_nodes> N{};
    shape_values(t, xi.data(), N.data());
    double value = 0.0;
    for (int i = 0; i < n_nodes(t); ++i)
      value += N[static_cast<std::size_t>(i)] * monomial({2, 2, 0}, X.data() + i * dim, dim);
    EXPECT_GT(std::abs(value - monomial({2, 2, 0}, xi.data(), dim)), 1e-3) << name(t);
  }
}

} // namespace
} // namespace seam::fem
