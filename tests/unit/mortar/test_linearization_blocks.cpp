// The pieces of the linearized mortar kernel one by one, each against central differences of
// the original double-valued seam function: dual-number arithmetic, averaged nodal normals,
// dual coefficients A_e, the three kinds of projection (including the 2D segment ends), the
// auxiliary plane, clip polygon vertices, the fan centroid and the cell areas (Jacobians).
#include <cstdio>
#include <functional>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "mortar_test_support.hpp"
#include "seam/geometry/plane.hpp"
#include "seam/geometry/polygon.hpp"
#include "seam/mortar/linearization.hpp"
#include "seam/mortar/linearization_clip.hpp"
#include "seam/mortar/normals.hpp"

using namespace seam::mortar;
using seam::Dual;
using seam::local_index;
using seam::fem::CellType;

namespace {

using Function = std::function<Eigen::VectorXd(const Eigen::VectorXd&)>;

// max |AD - FD| / max(|row of AD|, 1e-3 * max |AD|, 1e-2 * max |f|) over rows. The last floor
// (derivatives per unit length, inputs are O(1)) covers Jacobians that vanish exactly, such as
// the dual coefficients of an affine facet, where FD returns round-off noise.
double max_relative_error(const Function& f, const Eigen::VectorXd& q, const Eigen::MatrixXd& ad,
                          double h = 1e-7) {
  Eigen::MatrixXd fd(ad.rows(), ad.cols());
  for (int v = 0; v < q.size(); ++v) {
    Eigen::VectorXd qp = q, qm = q;
    qp(v) += h;
    qm(v) -= h;
    fd.col(v) = (f(qp) - f(qm)) / (2 * h);
  }
  const double global =
      std::max({ad.cwiseAbs().maxCoeff(), 10.0 * f(q).cwiseAbs().maxCoeff(), 1e-300});
  double worst = 0.0;
  for (int i = 0; i < ad.rows(); ++i) {
    const double scale = std::max(ad.row(i).cwiseAbs().maxCoeff(), 1e-3 * global);
    worst = std::max(worst, (ad.row(i) - fd.row(i)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

template <int N> Eigen::RowVectorXd gradient(const Dual<N>& x, int n) {
  Eigen::RowVectorXd g = Eigen::RowVectorXd::Zero(n);
  for (int v = 0; v < std::min(n, N); ++v) g(v) = x.gradient[static_cast<std::size_t>(v)];
  return g;
}

// Variables q -> dual numbers 0..n-1.
template <int N> std::vector<Dual<N>> seeds(const Eigen::VectorXd& q) {
  std::vector<Dual<N>> x;
  for (int v = 0; v < q.size(); ++v) x.push_back(Dual<N>::variable(q(v), v));
  return x;
}

Eigen::VectorXd random_vector(std::mt19937& rng, int n, double amplitude) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  Eigen::VectorXd v(n);
  for (int i = 0; i < n; ++i) v(i) = u(rng);
  return v;
}

// A facet of the given type: reference nodes mapped to a warped surface, perturbed.
Facet<3> random_surface_facet(CellType type, std::mt19937& rng) {
  Facet<3> f;
  f.type = type;
  f.n_nodes = seam::fem::n_nodes(type);
  const double* X = seam::fem::reference_nodes(type).data();
  for (int i = 0; i < f.n_nodes; ++i) {
    const double a = X[2 * i], b = X[2 * i + 1];
    f.x.col(i) =
        Eigen::Vector3d(a, 0.8 * b + 0.2 * a, 0.2 * a * a - 0.1 * b) + random_vector(rng, 3, 0.05);
  }
  return f;
}

Facet<2> random_line_facet(CellType type, std::mt19937& rng) {
  Facet<2> f;
  f.type = type;
  f.n_nodes = seam::fem::n_nodes(type);
  f.x.col(0) = Eigen::Vector2d(1, 0) + random_vector(rng, 2, 0.05);
  f.x.col(1) = Eigen::Vector2d(0, 0.1) + random_vector(rng, 2, 0.05);
  if (type == CellType::line3)
    f.x.col(2) = Eigen::Vector2d(0.5, 0.12) + random_vector(rng, 2, 0.03);
  return f;
}

template <int Dim> Eigen::VectorXd coordinates(const Facet<Dim>& f) {
  Eigen::VectorXd q(Dim * f.n_nodes);
  for (int i = 0; i < f.n_nodes; ++i) q.segment<Dim>(Dim * i) = f.x.col(i);
  return q;
}

template <int Dim> Facet<Dim> with_coordinates(Facet<Dim> f, const Eigen::VectorXd& q) {
  for (int i = 0; i < f.n_nodes; ++i) f.x.col(i) = q.segment<Dim>(Dim * i);
  return f;
}

} // namespace

TEST(LinearizationBlocks, DualArithmeticMatchesAnalyticDerivatives) {
  using D = Dual<2>;
  const D x = D::variable(1.3, 0), y = D::variable(-0.7, 1);
  const D f = sqrt(x * x + y * y) + x / y - 2.0 / x + abs(y) * 3.0 - (1.0 - x) * y;
  const double xv = 1.3, yv = -0.7, r = std::hypot(xv, yv);
  EXPECT_NEAR(f.value, r + xv / yv - 2.0 / xv - 3.0 * yv - (1.0 - xv) * yv, 1e-15);
  EXPECT_NEAR(f.gradient[0], xv / r + 1.0 / yv + 2.0 / (xv * xv) + yv, 1e-14);
  EXPECT_NEAR(f.gradient[1], yv / r - xv / (yv * yv) - 3.0 - (1.0 - xv), 1e-14);
  // Eigen matrices of dual numbers: d|a x b|^2 / da_0 with b constant.
  Eigen::Matrix<D, 3, 1> a(D::variable(1.0, 0), D(2.0), D(-1.0));
  const Eigen::Matrix<D, 3, 1> b(D(0.5), D(1.5), D(2.0));
  const D c = a.cross(b).squaredNorm();
  const Eigen::Vector3d av(1.0, 2.0, -1.0), bv(0.5, 1.5, 2.0);
  EXPECT_NEAR(c.value, av.cross(bv).squaredNorm(), 1e-14);
  // d/da0 |a x b|^2 = 2 (a x b) . (e0 x b)
  EXPECT_NEAR(c.gradient[0], 2.0 * av.cross(bv).dot(Eigen::Vector3d::UnitX().cross(bv)), 1e-14);
  EXPECT_TRUE(x < 2.0 && 2.0 > x && x != y && -1.0 < y.value + 1.0);
}

TEST(LinearizationBlocks, AveragedNodalNormals) {
  std::mt19937 rng(3);
  // Warped, perturbed 3D grids (quad4, tri3, quad9) and a curved 2D line3 mesh.
  std::vector<test::Surface> surfaces;
  for (const CellType type : {CellType::quad4, CellType::tri3, CellType::quad9}) {
    surfaces.push_back(test::grid(
        3, 3, type,
        [](double u, double v) { return Eigen::Vector3d(u, v, 0.3 * u * u - 0.2 * u * v); },
        false));
  }
  surfaces.push_back(test::line_mesh(
      4, CellType::line3, [](double s) { return Eigen::Vector2d(std::cos(s), 0.8 * std::sin(s)); },
      false));
  double worst = 0.0;
  for (test::Surface& surface : surfaces) {
    for (double& x : surface.coordinates) x += random_vector(rng, 1, 0.02)(0);
    const FacetSet set = surface.view();
    const NodeFacets adjacency = node_facets(set);
    const int dim = set.dim;
    for (local_index node = 0; node < set.n_nodes(); ++node) {
      if (adjacency.of(node).empty()) continue;
      NodalNormalLinearization lin;
      linearize_nodal_normal(set, node, adjacency.of(node), lin);
      const int n = static_cast<int>(lin.nodes.size());
      Eigen::MatrixXd ad(dim, dim * n);
      for (int a = 0; a < dim; ++a)
        for (int v = 0; v < dim * n; ++v)
          ad(a, v) = lin.jacobian[static_cast<std::size_t>(a * dim * n + v)];
      Eigen::VectorXd q(dim * n);
      for (int i = 0; i < n; ++i)
        for (int b = 0; b < dim; ++b)
          q(dim * i + b) = surface.coordinates[static_cast<std::size_t>(lin.nodes[i] * dim + b)];
      const auto f = [&](const Eigen::VectorXd& x) {
        test::Surface s = surface;
        for (int i = 0; i < n; ++i)
          for (int b = 0; b < dim; ++b)
            s.coordinates[static_cast<std::size_t>(lin.nodes[i] * dim + b)] = x(dim * i + b);
        const std::vector<double> normals = averaged_nodal_normals(s.view());
        Eigen::VectorXd r(dim);
        for (int a = 0; a < dim; ++a) r(a) = normals[static_cast<std::size_t>(node * dim + a)];
        return r;
      };
      Eigen::VectorXd value(dim);
      for (int a = 0; a < dim; ++a) value(a) = lin.normal[static_cast<std::size_t>(a)];
      EXPECT_LT((value - f(q)).norm(), 1e-14);
      const double e = max_relative_error(f, q, ad);
      EXPECT_LT(e, 1e-6) << "node " << node;
      worst = std::max(worst, e);
    }
  }
  std::printf("[ nodal normals ] worst relative derivative error %.2e\n", worst);
}

TEST(LinearizationBlocks, DualCoefficients) {
  // A_e = D_e M_e^{-1} amplifies round-off by the condition number of M_e, so the differences
  // use a step of 1e-6 here to stay clear of their own noise.
  constexpr double h = 1e-6;
  std::mt19937 rng(5);
  double worst = 0.0;
  for (const CellType type :
       {CellType::tri3, CellType::quad4, CellType::tri6, CellType::quad8, CellType::quad9}) {
    const double a = basis_modification(type, Multiplier::dual);
    const Facet<3> facet = random_surface_facet(type, rng);
    using S = Dual<27>;
    const auto A = ad::dual_coefficients_t(ad::seed<S, 3>(facet, 0), a);
    const int n = facet.n_nodes;
    Eigen::MatrixXd jac(n * n, 3 * n);
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) jac.row(j * n + k) = gradient(A(j, k), 3 * n);
    const auto f = [&](const Eigen::VectorXd& q) {
      const SmallMatrix Av = dual_coefficients(with_coordinates(facet, q), a);
      return Eigen::VectorXd(
          Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(Av.transpose()).data(), n * n));
    };
    const double e = max_relative_error(f, coordinates(facet), jac, h);
    EXPECT_LT(e, 1e-6) << seam::fem::name(type);
    worst = std::max(worst, e);
  }
  for (const CellType type : {CellType::line2, CellType::line3}) {
    const Facet<2> facet = random_line_facet(type, rng);
    using S = Dual<6>;
    const auto A = ad::dual_coefficients_t(ad::seed<S, 2>(facet, 0), 0.0);
    const int n = facet.n_nodes;
    Eigen::MatrixXd jac(n * n, 2 * n);
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) jac.row(j * n + k) = gradient(A(j, k), 2 * n);
    const auto f = [&](const Eigen::VectorXd& q) {
      const SmallMatrix Av = dual_coefficients(with_coordinates(facet, q), 0.0);
      return Eigen::VectorXd(
          Eigen::Map<const Eigen::VectorXd>(Eigen::MatrixXd(Av.transpose()).data(), n * n));
    };
    const double e = max_relative_error(f, coordinates(facet), jac, h);
    EXPECT_LT(e, 1e-6) << seam::fem::name(type);
    worst = std::max(worst, e);
  }
  std::printf("[ dual coefficients ] worst relative derivative error %.2e\n", worst);
}

TEST(LinearizationBlocks, SurfaceBackProjection) {
  // x(xi) + alpha d = p: derivatives of (xi, eta, alpha) w.r.t. facet nodes, p and d.
  std::mt19937 rng(9);
  double worst = 0.0;
  for (const CellType type : {CellType::tri3, CellType::quad4, CellType::quad9, CellType::tri6}) {
    const Facet<3> facet = random_surface_facet(type, rng);
    const int n = 3 * facet.n_nodes;
    Eigen::VectorXd q(n + 6);
    q.head(n) = coordinates(facet);
    q.segment<3>(n) = Eigen::Vector3d(0.2, 0.1, 0.4) + random_vector(rng, 3, 0.1);      // p
    q.segment<3>(n + 3) = Eigen::Vector3d(0.1, -0.2, 1.0) + random_vector(rng, 3, 0.1); // d
    using S = Dual<33>;
    const auto x = seeds<33>(q);
    ad::FacetT<S, 3> fs = ad::seed<S, 3>(facet, 0);
    const ad::Vector<S, 3> p(x[n], x[n + 1], x[n + 2]), d(x[n + 3], x[n + 4], x[n + 5]);
    const auto r = ad::project_onto_surface_t<S>(fs, p, d, Eigen::Vector2d(0.2, 0.2), {});
    ASSERT_TRUE(r.converged);
    Eigen::MatrixXd jac(3, n + 6);
    jac << gradient(r.xi(0), n + 6), gradient(r.xi(1), n + 6), gradient(r.alpha, n + 6);
    const auto f = [&](const Eigen::VectorXd& y) {
      const auto s = project_onto_facet(with_coordinates(facet, y.head(n)), y.segment<3>(n),
                                        y.segment<3>(n + 3), Eigen::Vector2d(0.2, 0.2));
      return Eigen::Vector3d(s.xi(0), s.xi(1), s.alpha).eval();
    };
    const Eigen::Vector3d value(r.xi(0).value, r.xi(1).value, r.alpha.value);
    EXPECT_LT((value - f(q)).norm(), 1e-14);
    const double e =
        max_relative_error([&](const Eigen::VectorXd& y) { return Eigen::VectorXd(f(y)); }, q, jac);
    EXPECT_LT(e, 1e-6) << seam::fem::name(type);
    worst = std::max(worst, e);
  }
  std::printf("[ back-projection ] worst relative derivative error %.2e\n", worst);
}

TEST(LinearizationBlocks, LineProjectionsAndSegmentEnds) {
  // Gauss point image along a fixed direction, and a master end node projected onto the slave
  // along the interpolated nodal normals (the 2D segment ends, ALGORITHMS.md §1).
  std::mt19937 rng(17);
  double worst = 0.0;
  for (const CellType type : {CellType::line2, CellType::line3}) {
    const Facet<2> facet = random_line_facet(type, rng);
    const int n = 2 * facet.n_nodes;
    // Fixed direction.
    {
      Eigen::VectorXd q(n + 4);
      q.head(n) = coordinates(facet);
      q.segment<2>(n) = Eigen::Vector2d(0.3, 0.5) + random_vector(rng, 2, 0.1);
      q.segment<2>(n + 2) = Eigen::Vector2d(0.2, 1.0) + random_vector(rng, 2, 0.1);
      using S = Dual<10>;
      const auto x = seeds<10>(q);
      const auto r =
          ad::project_onto_line_t<S>(ad::seed<S, 2>(facet, 0), ad::Vector<S, 2>(x[n], x[n + 1]),
                                     ad::Vector<S, 2>(x[n + 2], x[n + 3]), 0.0, {});
      ASSERT_TRUE(r.converged);
      const Eigen::MatrixXd jac = gradient(r.xi, n + 4);
      const auto f = [&](const Eigen::VectorXd& y) {
        Eigen::VectorXd v(1);
        v(0) = project_onto_facet(with_coordinates(facet, y.head(n)), y.segment<2>(n),
                                  y.segment<2>(n + 2), 0.0)
                   .xi;
        return v;
      };
      EXPECT_LT(std::abs(r.xi.value - f(q)(0)), 1e-14);
      const double e = max_relative_error(f, q, jac);
      EXPECT_LT(e, 1e-6);
      worst = std::max(worst, e);
    }
    // Along the nodal normal field.
    {
      const int nn = 2 * facet.n_nodes;
      Eigen::VectorXd q(n + nn + 2);
      q.head(n) = coordinates(facet);
      for (int k = 0; k < facet.n_nodes; ++k)
        q.segment<2>(n + 2 * k) =
            (Eigen::Vector2d(0.1, 1.0) + random_vector(rng, 2, 0.2)).normalized();
      q.segment<2>(n + nn) = Eigen::Vector2d(0.35, 0.4) + random_vector(rng, 2, 0.05);
      using S = Dual<20>;
      const auto x = seeds<20>(q);
      Eigen::Matrix<S, 2, max_facet_nodes> normals = Eigen::Matrix<S, 2, max_facet_nodes>::Zero();
      for (int k = 0; k < facet.n_nodes; ++k) normals.col(k) << x[n + 2 * k], x[n + 2 * k + 1];
      const auto r = ad::project_along_normals_t<S>(
          ad::seed<S, 2>(facet, 0), normals, ad::Vector<S, 2>(x[n + nn], x[n + nn + 1]), 0.0, {});
      ASSERT_TRUE(r.converged);
      const Eigen::MatrixXd jac = gradient(r.xi, n + nn + 2);
      const auto f = [&](const Eigen::VectorXd& y) {
        const Facet<2> g = with_coordinates(facet, y.head(n));
        Eigen::Matrix<double, 2, max_facet_nodes> nv =
            Eigen::Matrix<double, 2, max_facet_nodes>::Zero();
        for (int k = 0; k < facet.n_nodes; ++k) nv.col(k) = y.segment<2>(n + 2 * k);
        const auto curve = [&g](double xi) {
          const auto p = evaluate(g, &xi);
          return seam::geometry::CurvePoint{p.x, p.dx.col(0)};
        };
        const auto field = [&g, &nv](double xi) {
          const auto p = evaluate(g, &xi);
          return seam::geometry::CurvePoint{nv * p.N, nv * p.dN.col(0)};
        };
        Eigen::VectorXd v(1);
        v(0) =
            seam::geometry::project_onto_curve_along_field(curve, field, y.segment<2>(n + nn), 0.0)
                .xi;
        return v;
      };
      EXPECT_LT(std::abs(r.xi.value - f(q)(0)), 1e-14);
      const double e = max_relative_error(f, q, jac);
      EXPECT_LT(e, 1e-6);
      worst = std::max(worst, e);
    }
  }
  std::printf("[ line projections ] worst relative derivative error %.2e\n", worst);
}

TEST(LinearizationBlocks, PlaneClipCentroidAndCells) {
  // Auxiliary plane of a random normal; two random convex quads / triangles in general
  // position clipped; the clip vertices, the fan centroid and each cell area differentiated
  // with respect to the input vertices.
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  double worst = 0.0;
  int n_tested = 0;
  for (int trial = 0; trial < 40; ++trial) {
    const int ns = trial % 2 == 0 ? 4 : 3, nm = trial % 3 == 0 ? 3 : 4;
    Eigen::VectorXd q(2 * (ns + nm));
    const double phase = u(rng);
    for (int i = 0; i < ns; ++i) {
      const double t = 2 * std::numbers::pi * i / ns + 0.2 * u(rng);
      q.segment<2>(2 * i) = Eigen::Vector2d(std::cos(t), std::sin(t)) * (1 + 0.1 * u(rng));
    }
    const Eigen::Vector2d shift(0.6 * u(rng), 0.6 * u(rng));
    for (int i = 0; i < nm; ++i) {
      const double t = 2 * std::numbers::pi * i / nm + phase + 0.2 * u(rng);
      q.segment<2>(2 * (ns + i)) =
          shift + Eigen::Vector2d(std::cos(t), std::sin(t)) * (0.9 + 0.1 * u(rng));
    }
    const auto polygons = [&](const Eigen::VectorXd& y) {
      std::array<seam::geometry::Polygon, 2> p;
      for (int i = 0; i < ns; ++i) p[0].push_back(y.segment<2>(2 * i));
      for (int i = 0; i < nm; ++i) p[1].push_back(y.segment<2>(2 * (ns + i)));
      return p;
    };
    const auto reference = polygons(q);
    const auto clip = seam::geometry::clip_polygons(reference[0], reference[1]);
    if (clip.size() < 4) continue; // want intersections and a fan of several cells
    // Outputs: clip vertices, centroid, cell areas.
    const auto f = [&](const Eigen::VectorXd& y) {
      const auto p = polygons(y);
      const auto c = seam::geometry::clip_polygons(p[0], p[1]);
      Eigen::VectorXd r(2 * clip.size() + 2 + clip.size());
      if (c.size() != clip.size()) return Eigen::VectorXd(r.setConstant(1e300));
      for (int i = 0; i < c.size(); ++i) r.segment<2>(2 * i) = c[i];
      r.segment<2>(2 * c.size()) = seam::geometry::centroid(c);
      const auto cells = seam::geometry::triangulate_fan(c);
      for (int i = 0; i < cells.size(); ++i) r(2 * c.size() + 2 + i) = cells[i].area();
      return r;
    };
    using S = Dual<16>;
    const auto x = seeds<16>(q);
    ad::PolygonT<S> sp, mp;
    for (int i = 0; i < ns; ++i) sp.push_back(ad::Vector<S, 2>(x[2 * i], x[2 * i + 1]));
    for (int i = 0; i < nm; ++i)
      mp.push_back(ad::Vector<S, 2>(x[2 * (ns + i)], x[2 * (ns + i) + 1]));
    const auto c = ad::clip_polygons_t<S>(sp, mp, {});
    ASSERT_EQ(c.size(), clip.size());
    const int nv = static_cast<int>(q.size());
    Eigen::MatrixXd jac(2 * c.size() + 2 + c.size(), nv);
    for (int i = 0; i < c.size(); ++i) {
      jac.row(2 * i) = gradient(c[i](0), nv);
      jac.row(2 * i + 1) = gradient(c[i](1), nv);
    }
    const auto center = ad::centroid_t<S>(c);
    jac.row(2 * c.size()) = gradient(center(0), nv);
    jac.row(2 * c.size() + 1) = gradient(center(1), nv);
    const auto cells = ad::triangulate_fan_t<S>(c);
    for (int i = 0; i < cells.size(); ++i)
      jac.row(2 * c.size() + 2 + i) = gradient(cells[i].area(), nv);
    const double e = max_relative_error(f, q, jac);
    EXPECT_LT(e, 1e-6) << "trial " << trial;
    worst = std::max(worst, e);
    ++n_tested;
  }
  EXPECT_GE(n_tested, 10);

  // The plane: local coordinates of a point as a function of origin, normal and the point.
  for (int trial = 0; trial < 6; ++trial) {
    Eigen::VectorXd q = random_vector(rng, 9, 1.0);
    q(3 + trial % 3) += 2.0; // exercise each choice of first axis
    using S = Dual<9>;
    const auto x = seeds<9>(q);
    const auto plane =
        ad::make_plane_t<S>(ad::Vector<S, 3>(x[0], x[1], x[2]), ad::Vector<S, 3>(x[3], x[4], x[5]));
    const auto local = plane.to_local(ad::Vector<S, 3>(x[6], x[7], x[8]));
    Eigen::MatrixXd jac(2, 9);
    jac << gradient(local(0), 9), gradient(local(1), 9);
    const auto f = [](const Eigen::VectorXd& y) {
      const auto p = seam::geometry::make_plane(y.segment<3>(0), y.segment<3>(3));
      return Eigen::VectorXd(p.to_local(y.segment<3>(6)));
    };
    const double e = max_relative_error(f, q, jac);
    EXPECT_LT(e, 1e-6);
    worst = std::max(worst, e);
  }
  std::printf("[ plane, clip, centroid, cells ] %d clips, worst relative derivative error %.2e\n",
              n_tested, worst);
}
