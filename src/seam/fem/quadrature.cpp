// Quadrature on the reference cells.
//  - line, quad, hex: (tensor products of) Gauss-Legendre, n = degree/2 + 1 points per direction.
//  - triangle: symmetric rules with positive weights and interior points for degree <= 5:
//    centroid (1 point, degree 1), Strang & Fix's 3-point rule (degree 2), the 6-point degree-4
//    rule (Dunavant, IJNME 21, 1985, p = 4; closed form from Cowper, IJNME 7, 1973) which is
//    also used for degree 3 because the 4-point degree-3 rule has a negative weight, and
//    Radon's 7-point degree-5 rule (closed form, Stroud, Approximate Calculation of Multiple
//    Integrals, 1971, T2:5-1).
//  - tetrahedron: centroid (degree 1), the 4-point degree-2 rule (Keast, CMAME 55, 1986), and
//    the 14-point degree-5 rule with positive weights (Walkington, "Quadrature on simplices of
//    arbitrary dimension", CMU 2000) for degree 4 and 5.
//  - otherwise on simplices: the collapsed (conical product) rule of Stroud: Gauss-Legendre in
//    the first direction and Gauss-Jacobi with weights (1-x) and (1-x)^2 in the collapsed ones
//    (Karniadakis & Sherwin, Spectral/hp Element Methods, 2nd ed., ch. 4 and app. B), exact for
//    total degree 2n - 1 with n points per direction, all weights positive, all points interior.
#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"
#include "seam/fem/gauss.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <mutex>
#include <vector>

namespace seam::fem {

namespace {

struct Rule {
  int degree = 0;
  std::vector<double> points;
  std::vector<double> weights;
};

// ---- tensor products of Gauss-Legendre ------------------------------------------------------

void tensor_gauss(int dim, int degree, Rule& r) {
  const int n = degree / 2 + 1;
  std::vector<double> x(static_cast<std::size_t>(n));
  std::vector<double> w(static_cast<std::size_t>(n));
  gauss_legendre(n, x, w);
  r.degree = 2 * n - 1;
  const int n_total = dim == 1 ? n : (dim == 2 ? n * n : n * n * n);
  r.points.reserve(static_cast<std::size_t>(n_total * dim));
  r.weights.reserve(static_cast<std::size_t>(n_total));
  // The first reference coordinate varies fastest.
  const int nk = dim == 3 ? n : 1;
  const int nj = dim >= 2 ? n : 1;
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < nj; ++j)
      for (int i = 0; i < n; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        const auto uj = static_cast<std::size_t>(j);
        const auto uk = static_cast<std::size_t>(k);
        r.points.push_back(x[ui]);
        double weight = w[ui];
        if (dim >= 2) {
          r.points.push_back(x[uj]);
          weight *= w[uj];
        }
        if (dim == 3) {
          r.points.push_back(x[uk]);
          weight *= w[uk];
        }
        r.weights.push_back(weight);
      }
}

// ---- collapsed rules on simplices -----------------------------------------------------------

// Gauss-Jacobi with weight (1-v)^alpha mapped to v in [0, 1].
void jacobi_01(int n, int alpha, std::vector<double>& v, std::vector<double>& w) {
  v.resize(static_cast<std::size_t>(n));
  w.resize(static_cast<std::size_t>(n));
  gauss_jacobi(n, alpha, 0.0, v, w);
  const double scale = std::ldexp(1.0, -(alpha + 1)); // dv = dx/2, (1-v) = (1-x)/2
  for (std::size_t q = 0; q < v.size(); ++q) {
    v[q] = 0.5 * (1.0 + v[q]);
    w[q] *= scale;
  }
}

// Triangle: xi = u (1 - v), eta = v, d(xi,eta) = (1 - v) du dv.
// Tetrahedron: xi = u (1-v)(1-w), eta = v (1-w), zeta = w, d(xi,eta,zeta) = (1-v)(1-w)^2.
void collapsed_simplex(int dim, int degree, Rule& r) {
  const int n = degree / 2 + 1;
  r.degree = 2 * n - 1;
  std::vector<double> u, wu, v, wv, s, ws;
  jacobi_01(n, 0, u, wu);
  jacobi_01(n, 1, v, wv);
  if (dim == 3) jacobi_01(n, 2, s, ws);
  const int nk = dim == 3 ? n : 1;
  for (int k = 0; k < nk; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const auto ui = static_cast<std::size_t>(i);
        const auto uj = static_cast<std::size_t>(j);
        const auto uk = static_cast<std::size_t>(k);
        const double zeta = dim == 3 ? s[uk] : 0.0;
        const double shrink = 1.0 - zeta;
        r.points.push_back(u[ui] * (1.0 - v[uj]) * shrink);
        r.points.push_back(v[uj] * shrink);
        if (dim == 3) r.points.push_back(zeta);
        r.weights.push_back(wu[ui] * wv[uj] * (dim == 3 ? ws[uk] : 1.0));
      }
}

// ---- symmetric simplex rules ----------------------------------------------------------------

// Adds the orbit of a point of barycentric coordinates (permutations of `bary`) with weight w
// each; `bary` has dim + 1 entries, the reference coordinates are entries 1..dim.
void add_orbit(int dim, std::span<const double> bary, double w, Rule& r) {
  std::array<double, 4> b{};
  for (std::size_t a = 0; a < bary.size(); ++a) b[a] = bary[a];
  // Distinct permutations of dim + 1 values, enumerated by sorting then next_permutation.
  std::sort(b.begin(), b.begin() + dim + 1);
  do {
    for (int a = 1; a <= dim; ++a) r.points.push_back(b[static_cast<std::size_t>(a)]);
    r.weights.push_back(w);
  } while (std::next_permutation(b.begin(), b.begin() + dim + 1));
}

void triangle_rule(int degree, Rule& r) {
  constexpr double area = 0.5;
  if (degree <= 1) {
    r.degree = 1;
    const double c = 1.0 / 3.0;
    add_orbit(2, std::array{c, c, c}, area, r);
  } else if (degree == 2) {
    r.degree = 2;
    add_orbit(2, std::array{1.0 / 6.0, 1.0 / 6.0, 2.0 / 3.0}, area / 3.0, r);
  } else if (degree <= 4) {
    r.degree = 4;
    const double s10 = std::sqrt(10.0);
    const double root = std::sqrt(38.0 - 44.0 * std::sqrt(0.4));
    const double a1 = (8.0 - s10 + root) / 18.0;
    const double a2 = (8.0 - s10 - root) / 18.0;
    const double wroot = std::sqrt(213125.0 - 53320.0 * s10);
    add_orbit(2, std::array{a1, a1, 1.0 - 2.0 * a1}, area * (620.0 + wroot) / 3720.0, r);
    add_orbit(2, std::array{a2, a2, 1.0 - 2.0 * a2}, area * (620.0 - wroot) / 3720.0, r);
  } else if (degree == 5) {
    r.degree = 5;
    const double s15 = std::sqrt(15.0);
    const double a1 = (6.0 - s15) / 21.0;
    const double a2 = (6.0 + s15) / 21.0;
    const double c = 1.0 / 3.0;
    add_orbit(2, std::array{c, c, c}, area * 9.0 / 40.0, r);
    add_orbit(2, std::array{a1, a1, 1.0 - 2.0 * a1}, area * (155.0 - s15) / 1200.0, r);
    add_orbit(2, std::array{a2, a2, 1.0 - 2.0 * a2}, area * (155.0 + s15) / 1200.0, r);
  } else {
    collapsed_simplex(2, degree, r);
  }
}

void tetrahedron_rule(int degree, Rule& r) {
  if (degree <= 1) {
    r.degree = 1;
    add_orbit(3, std::array{0.25, 0.25, 0.25, 0.25}, 1.0 / 6.0, r);
  } else if (degree == 2) {
    r.degree = 2;
    const double a = (5.0 - std::sqrt(5.0)) / 20.0;
    add_orbit(3, std::array{a, a, a, 1.0 - 3.0 * a}, 1.0 / 24.0, r);
  } else if (degree == 4 || degree == 5) {
    r.degree = 5;
    constexpr double a1 = 0.09273525031089122640232391373703060;
    constexpr double a2 = 0.31088591926330060979734573376345783;
    constexpr double b = 0.45449629587435035050811947372066056;
    add_orbit(3, std::array{a1, a1, a1, 1.0 - 3.0 * a1}, 0.01224884051939365826922115397552, r);
    add_orbit(3, std::array{a2, a2, a2, 1.0 - 3.0 * a2}, 0.01878132095300264180669551268113, r);
    add_orbit(3, std::array{b, b, 0.5 - b, 0.5 - b}, 0.00709100346284691107301157135338, r);
  } else {
    // degree 3 included: the cheapest positive symmetric rules are no smaller than 8 points.
    collapsed_simplex(3, degree, r);
  }
}

Rule build_rule(CellType t, int degree) {
  Rule r;
  switch (t) {
  case CellType::point1:
    r.degree = degree;
    r.weights.push_back(1.0);
    break;
  case CellType::line2:
  case CellType::line3:
    tensor_gauss(1, degree, r);
    break;
  case CellType::quad4:
  case CellType::quad8:
  case CellType::quad9:
    tensor_gauss(2, degree, r);
    break;
  case CellType::hex8:
  case CellType::hex20:
  case CellType::hex27:
    tensor_gauss(3, degree, r);
    break;
  case CellType::tri3:
  case CellType::tri6:
    triangle_rule(degree, r);
    break;
  case CellType::tet4:
  case CellType::tet10:
    tetrahedron_rule(degree, r);
    break;
  }
  return r;
}

// One slot per (cell type, requested degree). std::call_once makes the first build
// thread-safe and later look-ups a single atomic load; slots never move, so the spans handed
// out stay valid for the life of the program.
struct Slot {
  std::once_flag once;
  Rule rule;
};

constexpr int n_cell_types = 13;

Slot& slot(CellType t, int degree) {
  static const auto cache = std::make_unique<Slot[]>(
      static_cast<std::size_t>(n_cell_types * (max_quadrature_degree + 1)));
  return cache[static_cast<std::size_t>(static_cast<int>(t) * (max_quadrature_degree + 1) +
                                        degree)];
}

} // namespace

QuadratureRule quadrature(CellType t, int degree) {
  const int type_id = static_cast<int>(t);
  SEAM_CHECK(type_id >= 0 && type_id < n_cell_types, InputError, "invalid cell type id ", type_id);
  SEAM_CHECK(degree >= 0 && degree <= max_quadrature_degree, InputError, "no quadrature rule of ",
             "degree ", degree, " on a ", name(t), " cell: degrees 0 to ", max_quadrature_degree,
             " are available");
  Slot& s = slot(t, degree);
  std::call_once(s.once, [&] { s.rule = build_rule(t, degree); });
  const Rule& r = s.rule;
  QuadratureRule q;
  q.dim = dimension(t);
  q.degree = r.degree;
  q.n_points = static_cast<int>(r.weights.size());
  q.points = r.points;
  q.weights = r.weights;
  return q;
}

// Full integration for every cell: 2 * order. On tensor cells this is the (order+1)^dim Gauss
// rule, which integrates the mass matrix of an affine cell exactly and keeps the stiffness free
// of hourglass modes (2x2 for quad4, 3x3x3 for hex20/hex27). On simplices it integrates the mass
// matrix exactly and leaves margin for the non-polynomial integrands of finite deformation:
// 1 point for tri3 / tet4 would also do for linear stiffness, but degree 2 keeps mass and
// stiffness on one rule (3 points on tri3, 4 on tet4, 6 on tri6, 14 on tet10).
int default_quadrature_degree(CellType t) {
  return 2 * order(t);
}

} // namespace seam::fem
