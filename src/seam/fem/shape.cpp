// Shape functions of the reference cells and their gradients. Tensor-product Lagrange cells
// (lines, quad4/9, hex8/27) take each node's 1D factors from its reference coordinates;
// serendipity cells (quad8, hex20) use the classical Ergatoudis-Irons-Zienkiewicz functions
// (Zienkiewicz, Taylor & Zhu, The Finite Element Method: Its Basis and Fundamentals, ch. 6);
// simplices use barycentric coordinates (ibid.). Every path writes into caller buffers only.
#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"

#include <array>

namespace seam::fem {

namespace {

// 1D Lagrange factor of the node at coordinate c in {-1, 1} (order 1) or {-1, 0, 1} (order 2).
template <int order> inline double lagrange(double x, double c) {
  if constexpr (order == 1) {
    return 0.5 * (1.0 + c * x);
  } else {
    return c == 0.0 ? 1.0 - x * x : 0.5 * x * (x + c);
  }
}

template <int order> inline double lagrange_derivative(double x, double c) {
  if constexpr (order == 1) {
    return 0.5 * c;
  } else {
    return c == 0.0 ? -2.0 * x : x + 0.5 * c;
  }
}

template <int dim, int order> void tensor_values(CellType t, const double* xi, double* N) {
  const double* X = reference_nodes(t).data();
  const int n = n_nodes(t);
  for (int i = 0; i < n; ++i) {
    double v = 1.0;
    for (int a = 0; a < dim; ++a) v *= lagrange<order>(xi[a], X[i * dim + a]);
    N[i] = v;
  }
}

template <int dim, int order> void tensor_gradients(CellType t, const double* xi, double* dN) {
  const double* X = reference_nodes(t).data();
  const int n = n_nodes(t);
  for (int i = 0; i < n; ++i) {
    std::array<double, dim> v{};
    std::array<double, dim> d{};
    for (int a = 0; a < dim; ++a) {
      v[static_cast<std::size_t>(a)] = lagrange<order>(xi[a], X[i * dim + a]);
      d[static_cast<std::size_t>(a)] = lagrange_derivative<order>(xi[a], X[i * dim + a]);
    }
    for (int a = 0; a < dim; ++a) {
      double g = d[static_cast<std::size_t>(a)];
      for (int b = 0; b < dim; ++b)
        if (b != a) g *= v[static_cast<std::size_t>(b)];
      dN[i * dim + a] = g;
    }
  }
}

// Quadratic serendipity (quad8, hex20). Corner node X: N = 2^-d prod_b (1 + x_b X_b)
// (sum_b x_b X_b - (d - 1)); mid-edge node with X_a = 0: N = 2^-(d-1) (1 - x_a^2)
// prod_{b != a} (1 + x_b X_b).
template <int dim> int zero_axis(const double* X) {
  for (int a = 0; a < dim; ++a)
    if (X[a] == 0.0) return a;
  return -1;
}

template <int dim> void serendipity_values(CellType t, const double* xi, double* N) {
  const double* X = reference_nodes(t).data();
  const int n = n_nodes(t);
  const double corner_scale = 1.0 / (1 << dim);
  for (int i = 0; i < n; ++i) {
    const double* Xi = X + i * dim;
    const int a0 = zero_axis<dim>(Xi);
    if (a0 < 0) {
      double p = corner_scale;
      double s = -(dim - 1);
      for (int a = 0; a < dim; ++a) {
        p *= 1.0 + xi[a] * Xi[a];
        s += xi[a] * Xi[a];
      }
      N[i] = p * s;
    } else {
      double p = 2.0 * corner_scale * (1.0 - xi[a0] * xi[a0]);
      for (int b = 0; b < dim; ++b)
        if (b != a0) p *= 1.0 + xi[b] * Xi[b];
      N[i] = p;
    }
  }
}

template <int dim> void serendipity_gradients(CellType t, const double* xi, double* dN) {
  const double* X = reference_nodes(t).data();
  const int n = n_nodes(t);
  const double corner_scale = 1.0 / (1 << dim);
  for (int i = 0; i < n; ++i) {
    const double* Xi = X + i * dim;
    std::array<double, dim> p{}; // p_b = 1 + x_b X_b
    for (int b = 0; b < dim; ++b) p[static_cast<std::size_t>(b)] = 1.0 + xi[b] * Xi[b];
    const int a0 = zero_axis<dim>(Xi);
    if (a0 < 0) {
      double s = -(dim - 1);
      for (int b = 0; b < dim; ++b) s += xi[b] * Xi[b];
      // dN/dx_c = 2^-d X_c prod_{b != c} p_b (s + p_c)
      for (int c = 0; c < dim; ++c) {
        double g = corner_scale * Xi[c] * (s + p[static_cast<std::size_t>(c)]);
        for (int b = 0; b < dim; ++b)
          if (b != c) g *= p[static_cast<std::size_t>(b)];
        dN[i * dim + c] = g;
      }
    } else {
      const double bubble = 1.0 - xi[a0] * xi[a0];
      for (int c = 0; c < dim; ++c) {
        double g = 2.0 * corner_scale * (c == a0 ? -2.0 * xi[a0] : bubble * Xi[c]);
        for (int b = 0; b < dim; ++b)
          if (b != a0 && b != c) g *= p[static_cast<std::size_t>(b)];
        dN[i * dim + c] = g;
      }
    }
  }
}

// Simplices in barycentric coordinates L_0 = 1 - sum_a xi_a, L_k = xi_{k-1}. Quadratic
// corner nodes: L_i (2 L_i - 1); edge node between i and j: 4 L_i L_j.
constexpr std::array<std::array<int, 2>, 3> tri6_edges{{{0, 1}, {1, 2}, {2, 0}}};
constexpr std::array<std::array<int, 2>, 6> tet10_edges{
    {{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}}};

template <int dim> std::array<double, dim + 1> barycentric(const double* xi) {
  std::array<double, dim + 1> L{};
  L[0] = 1.0;
  for (int a = 0; a < dim; ++a) {
    L[static_cast<std::size_t>(a + 1)] = xi[a];
    L[0] -= xi[a];
  }
  return L;
}

// dL_k/dxi_a: -1 for k = 0, delta_{k-1,a} otherwise.
inline double barycentric_derivative(int k, int a) {
  return k == 0 ? -1.0 : (k - 1 == a ? 1.0 : 0.0);
}

template <int dim, std::size_t n_edges>
void simplex_values(const double* xi, int order, const std::array<std::array<int, 2>, n_edges>& e,
                    double* N) {
  const auto L = barycentric<dim>(xi);
  for (int i = 0; i <= dim; ++i) {
    const double l = L[static_cast<std::size_t>(i)];
    N[i] = order == 1 ? l : l * (2.0 * l - 1.0);
  }
  if (order == 1) return;
  for (std::size_t k = 0; k < n_edges; ++k)
    N[dim + 1 + static_cast<int>(k)] =
        4.0 * L[static_cast<std::size_t>(e[k][0])] * L[static_cast<std::size_t>(e[k][1])];
}

template <int dim, std::size_t n_edges>
void simplex_gradients(const double* xi, int order,
                       const std::array<std::array<int, 2>, n_edges>& e, double* dN) {
  const auto L = barycentric<dim>(xi);
  for (int i = 0; i <= dim; ++i) {
    const double f = order == 1 ? 1.0 : 4.0 * L[static_cast<std::size_t>(i)] - 1.0;
    for (int a = 0; a < dim; ++a) dN[i * dim + a] = f * barycentric_derivative(i, a);
  }
  if (order == 1) return;
  for (std::size_t k = 0; k < n_edges; ++k) {
    const int i = e[k][0];
    const int j = e[k][1];
    const double Li = L[static_cast<std::size_t>(i)];
    const double Lj = L[static_cast<std::size_t>(j)];
    const int node = dim + 1 + static_cast<int>(k);
    for (int a = 0; a < dim; ++a)
      dN[node * dim + a] =
          4.0 * (Lj * barycentric_derivative(i, a) + Li * barycentric_derivative(j, a));
  }
}

constexpr std::array<std::array<int, 2>, 0> no_edges{};

} // namespace

void shape_values(CellType t, const double* xi, double* N) {
  switch (t) {
  case CellType::point1:
    N[0] = 1.0;
    return;
  case CellType::line2:
    tensor_values<1, 1>(t, xi, N);
    return;
  case CellType::line3:
    tensor_values<1, 2>(t, xi, N);
    return;
  case CellType::tri3:
    simplex_values<2>(xi, 1, no_edges, N);
    return;
  case CellType::tri6:
    simplex_values<2>(xi, 2, tri6_edges, N);
    return;
  case CellType::quad4:
    tensor_values<2, 1>(t, xi, N);
    return;
  case CellType::quad8:
    serendipity_values<2>(t, xi, N);
    return;
  case CellType::quad9:
    tensor_values<2, 2>(t, xi, N);
    return;
  case CellType::tet4:
    simplex_values<3>(xi, 1, no_edges, N);
    return;
  case CellType::tet10:
    simplex_values<3>(xi, 2, tet10_edges, N);
    return;
  case CellType::hex8:
    tensor_values<3, 1>(t, xi, N);
    return;
  case CellType::hex20:
    serendipity_values<3>(t, xi, N);
    return;
  case CellType::hex27:
    tensor_values<3, 2>(t, xi, N);
    return;
  }
  SEAM_THROW(InputError, "invalid cell type id ", static_cast<int>(t));
}

void shape_gradients(CellType t, const double* xi, double* dN) {
  switch (t) {
  case CellType::point1:
    return;
  case CellType::line2:
    tensor_gradients<1, 1>(t, xi, dN);
    return;
  case CellType::line3:
    tensor_gradients<1, 2>(t, xi, dN);
    return;
  case CellType::tri3:
    simplex_gradients<2>(xi, 1, no_edges, dN);
    return;
  case CellType::tri6:
    simplex_gradients<2>(xi, 2, tri6_edges, dN);
    return;
  case CellType::quad4:
    tensor_gradients<2, 1>(t, xi, dN);
    return;
  case CellType::quad8:
    serendipity_gradients<2>(t, xi, dN);
    return;
  case CellType::quad9:
    tensor_gradients<2, 2>(t, xi, dN);
    return;
  case CellType::tet4:
    simplex_gradients<3>(xi, 1, no_edges, dN);
    return;
  case CellType::tet10:
    simplex_gradients<3>(xi, 2, tet10_edges, dN);
    return;
  case CellType::hex8:
    tensor_gradients<3, 1>(t, xi, dN);
    return;
  case CellType::hex20:
    serendipity_gradients<3>(t, xi, dN);
    return;
  case CellType::hex27:
    tensor_gradients<3, 2>(t, xi, dN);
    return;
  }
  SEAM_THROW(InputError, "invalid cell type id ", static_cast<int>(t));
}

} // namespace seam::fem
