// The weighted gaps of 2D line2 contact as functions of the nodal positions with exact first
// and second derivatives (energy-momentum contact, docs/contact_dynamics.md §4).
//
// The kernel follows integrate_pair of segmentation_2d.cpp step by step on a scalar type S
// (double, Dual<12> or Hyper<12>): averaged unit nodal normals of the slave facet's nodes, the
// centre-normal pre-check, the end-node projections and the overlap segment (decided on
// values), five Gauss points on the segment, each projected onto the master along the
// interpolated slave normal, the dual (or standard) basis of line2 and the gap
// n . (x_m - x_s). Every formula is written exactly (no first-order expansion), so second
// derivatives come out right: the projection of a master node onto the slave, a root of a
// quadratic, is polished by three Newton steps on S from its converged value (each step
// doubles the order of the derivatives that are exact at the root); the Gauss point's image on
// a straight master is in closed form.
#include "seam/contact/contact_interface.hpp"

#include "seam/common/dual_number.hpp"
#include "seam/common/error.hpp"
#include "seam/common/hyper_dual.hpp"
#include "seam/contact/gap_vectors.hpp"
#include "seam/contact/rigid_obstacle_gaps.hpp"
#include "seam/geometry/cell_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace seam::contact {

namespace {

using namespace gap_vectors;

/// xi clamped to [-1, 1] with rounded corners: max(a, b) ~ (a + b + sqrt((a - b)^2 + d^2)) / 2.
/// A segment end is a master node's projection until it passes the slave's end, and the slave
/// end after: with a sharp clamp g~ has a kink where a master node meets a slave end node
/// (equal meshes, the bar impact), the solution sits on it, and the midpoint gradient (taken
/// at a nonzero gap) jumps between Newton iterations. The rounding moves a segment end by at
/// most smoothing / 2 and only within a few smoothing widths of the slave end.
template <class S> S clamp_unit(const S& xi) {
  using std::sqrt;
  constexpr double smoothing = 1e-4;
  const S d1 = xi + 1.0;
  const S lower = 0.5 * (xi - 1.0 + sqrt(d1 * d1 + smoothing * smoothing));
  const S e = lower - 1.0;
  return 0.5 * (lower + 1.0 - sqrt(e * e + smoothing * smoothing));
}

/// One pair in the frame of the slave facet's first node: the 6 slots of GapBlock and, per
/// slave node, the slots of the (at most two) facets whose unit normals it averages.
struct PairInput {
  std::array<Eigen::Vector2d, 6> x;
  std::array<int, 2> n_adjacent{};
  std::array<std::array<std::array<int, 2>, 2>, 2> adjacent{};
  bool dual = true;
};

template <class S>
void pair_gaps(const PairInput& in, const mortar::PairOptions& options, std::array<S, 2>& g) {
  using std::sqrt;
  g = {S(0.0), S(0.0)};
  std::array<V2<S>, 6> X;
  for (int i = 0; i < 6; ++i)
    X[static_cast<std::size_t>(i)] = {
        independent_variable<S>(in.x[static_cast<std::size_t>(i)].x(), 2 * i),
        independent_variable<S>(in.x[static_cast<std::size_t>(i)].y(), 2 * i + 1)};
  // Averaged nodal normals: s_k = sum of the unit facet normals (t_y, -t_x) / |t|, n = s / |s|.
  std::array<V2<S>, 2> nn;
  for (std::size_t k = 0; k < 2; ++k) {
    V2<S> s;
    for (int f = 0; f < in.n_adjacent[k]; ++f) {
      const auto& ab = in.adjacent[k][static_cast<std::size_t>(f)];
      const V2<S> t = X[static_cast<std::size_t>(ab[1])] - X[static_cast<std::size_t>(ab[0])];
      const S l = length(t);
      s = s + V2<S>{t.y / l, -t.x / l};
    }
    const S l = length(s);
    nn[k] = {s.x / l, s.y / l};
  }
  const V2<S>&x0 = X[0], &x1 = X[1], &m0 = X[4], &m1 = X[5];
  const Eigen::Vector2d x0v = value(x0), x1v = value(x1), m0v = value(m0), m1v = value(m1);
  const Eigen::Vector2d n0v = value(nn[0]), n1v = value(nn[1]);
  // Centre normals of the two facets (integrate_pair's pre-check).
  const Eigen::Vector2d ts = 0.5 * (x1v - x0v), tm = 0.5 * (m1v - m0v);
  const Eigen::Vector2d ns = Eigen::Vector2d(ts.y(), -ts.x()).normalized();
  const Eigen::Vector2d nm = Eigen::Vector2d(tm.y(), -tm.x()).normalized();
  if (!(ns.dot(nm) < options.max_normal_alignment_2d)) return;

  const auto slave_curve = [&](double xi) {
    return geometry::CurvePoint{0.5 * (1.0 - xi) * x0v + 0.5 * (1.0 + xi) * x1v, ts};
  };
  const auto normal_field = [&](double xi) {
    return geometry::CurvePoint{0.5 * (1.0 - xi) * n0v + 0.5 * (1.0 + xi) * n1v, 0.5 * (n1v - n0v)};
  };
  const auto master_curve = [&](double eta) {
    return geometry::CurvePoint{0.5 * (1.0 - eta) * m0v + 0.5 * (1.0 + eta) * m1v, tm};
  };
  std::array<geometry::CurveProjection, 2> master_on_slave, slave_on_master;
  for (std::size_t k = 0; k < 2; ++k) {
    master_on_slave[k] = geometry::project_onto_curve_along_field(
        slave_curve, normal_field, k == 0 ? m0v : m1v, 0.0, options.newton);
    slave_on_master[k] = geometry::project_onto_curve(master_curve, k == 0 ? x0v : x1v,
                                                      k == 0 ? n0v : n1v, 0.0, options.newton);
  }
  // Master node k on the slave along n~(xi) = N_0 n_0 + N_1 n_1: the root of
  // F(xi) = (x_s(xi) - m_k) x n~(xi), polished on S.
  const auto on_slave = [&](std::size_t k) {
    S xi = master_on_slave[k].xi;
    const V2<S>& p = k == 0 ? m0 : m1;
    const V2<S> half_t = (x1 - x0) * 0.5, half_dn = (nn[1] - nn[0]) * 0.5;
    for (int it = 0; it < 3; ++it) {
      const S a0 = 0.5 * (1.0 - xi), a1 = 0.5 * (1.0 + xi);
      const V2<S> r = x0 * a0 + x1 * a1 - p;
      const V2<S> d = nn[0] * a0 + nn[1] * a1;
      xi = xi - cross(r, d) / (cross(half_t, d) + cross(r, half_dn));
    }
    return xi;
  };
  const double tol = options.projection_range_tolerance;
  const auto inside = [tol](const geometry::CurveProjection& r) {
    return r.converged && r.xi >= -1.0 - tol && r.xi <= 1.0 + tol;
  };
  const bool in0 = inside(master_on_slave[0]), in1 = inside(master_on_slave[1]);
  S xa = -1.0, xb = 1.0;
  if (in0 && in1) {
    const S e0 = on_slave(0), e1 = on_slave(1);
    const bool first = master_on_slave[0].xi < master_on_slave[1].xi;
    xa = first ? e0 : e1;
    xb = first ? e1 : e0;
  } else if (in0 || in1) {
    const std::size_t k = in0 ? 0 : 1;
    const S xi_in = on_slave(k);
    const Eigen::Vector2d towards_other = k == 0 ? Eigen::Vector2d(m1v - m0v) : m0v - m1v;
    if (towards_other.dot(ts) > 0.0) {
      xa = xi_in;
      xb = 1.0;
    } else {
      xa = -1.0;
      xb = xi_in;
    }
  } else if (!(inside(slave_on_master[0]) && inside(slave_on_master[1]))) {
    return;
  }
  xa = clamp_unit(xa);
  xb = clamp_unit(xb);
  if (!(value_of(xb) - value_of(xa) > 1e-12)) return;

  using Rule = geometry::LineRule5;
  const S segment_jacobian = (xb - xa) * 0.5;
  const V2<S> half_t = (x1 - x0) * 0.5;
  const S surface_jacobian = length(half_t);
  const V2<S> centre = (m0 + m1) * 0.5, half_m = (m1 - m0) * 0.5;
  for (int q = 0; q < Rule::n_points; ++q) {
    const double gp = Rule::points[static_cast<std::size_t>(q)];
    const S xi = 0.5 * ((1.0 - gp) * xa + (1.0 + gp) * xb);
    const S N0 = 0.5 * (1.0 - xi), N1 = 0.5 * (1.0 + xi);
    const V2<S> xs = x0 * N0 + x1 * N1;
    const V2<S> nt = nn[0] * N0 + nn[1] * N1;
    const S nl = length(nt);
    const V2<S> n = {nt.x / nl, nt.y / nl};
    // The image on the straight master: (m_c + eta h - x_s) x n = 0.
    const S slope = cross(half_m, n);
    if (!(std::abs(value_of(slope)) > 1e-14 * tm.norm())) continue;
    const S eta = cross(xs - centre, n) / slope;
    const V2<S> xm = m0 * (0.5 * (1.0 - eta)) + m1 * (0.5 * (1.0 + eta));
    const S w = Rule::weights[static_cast<std::size_t>(q)] * surface_jacobian * segment_jacobian;
    const S wg = w * dot(n, xm - xs);
    if (in.dual) {
      // Dual basis of a line2 facet: Phi = A N with A = D_e M_e^-1 = [[2, -1], [-1, 2]].
      g[0] += wg * (2.0 * N0 - N1);
      g[1] += wg * (2.0 * N1 - N0);
    } else {
      g[0] += wg * N0;
      g[1] += wg * N1;
    }
  }
}

} // namespace

bool ContactInterface::has_gap_blocks() const {
  const auto supported = [this](fem::CellType t) {
    return dim() == 2 ? t == fem::CellType::line2
                      : t == fem::CellType::tri3 || t == fem::CellType::quad4;
  };
  // Against a rigid obstacle the whole-facet kernel takes line3 faces as well (2D; quadratic
  // 3D faces: rigid_obstacle_facet.cpp).
  for (const auto t : slave_.types)
    if (!supported(t) && !(rigid_ && t == fem::CellType::line3)) return false;
  if (rigid_) return true;
  for (const auto t : master_.types)
    if (!supported(t)) return false;
  return true;
}

void ContactInterface::gap_blocks(std::span<const double> u, GapOrder order,
                                  std::vector<GapBlock>& out,
                                  std::span<const char> hessian_rows) const {
  SEAM_ASSERT(has_gap_blocks());
  out.clear();
  // The order of a block with slave nodes `nodes`: gradients instead of Hessians where no
  // node asks for them.
  const auto order_of = [&](const auto& nodes) {
    if (order != GapOrder::hessian || hessian_rows.empty()) return order;
    for (const auto k : nodes)
      if (hessian_rows[static_cast<std::size_t>(k)]) return order;
    return GapOrder::gradient;
  };
  if (rigid_) {
    // One block per owned candidate slave facet: its nodes' weighted gaps as functions of its
    // nodal positions (the obstacle where the last update put it).
    const int dim = this->dim();
    mortar::FacetSet facets = slave_.facet_set();
    std::vector<double> x(slave_.mesh_nodes.size() * static_cast<std::size_t>(dim));
    for (std::size_t k = 0; k < slave_.mesh_nodes.size(); ++k)
      for (int a = 0; a < dim; ++a) {
        const auto i = static_cast<std::size_t>(slave_.mesh_nodes[k]) * dim + a;
        x[k * dim + a] = mesh_->x[i] + u[i];
      }
    facets.coordinates = x;
    RigidObstacleFacet rf;
    for (const auto f : owned_) {
      if (n_pairs_of(f) == 0) continue;
      const auto nodes = facets.facet_nodes(f);
      GapBlock b;
      b.dim = dim;
      for (const auto k : nodes) {
        b.slave.push_back(k);
        b.dofs.push_back(static_cast<std::int64_t>(slave_.mesh_nodes[static_cast<std::size_t>(k)]) *
                         dim);
      }
      const GapOrder block_order = order_of(nodes);
      if (block_order == GapOrder::hessian) {
        if (dim == 2)
          rigid_obstacle_gap_hessians<2>(mortar::gather_facet<2>(facets, f), current_,
                                         options_.multiplier, b.gap, b.gradient, b.hessian);
        else
          rigid_obstacle_gap_hessians<3>(mortar::gather_facet<3>(facets, f), current_,
                                         options_.multiplier, b.gap, b.gradient, b.hessian);
      } else {
        const bool derivatives = block_order == GapOrder::gradient;
        if (dim == 2)
          rigid_obstacle_facet<2>(mortar::gather_facet<2>(facets, f), current_, options_.multiplier,
                                  derivatives, rf);
        else
          rigid_obstacle_facet<3>(mortar::gather_facet<3>(facets, f), current_, options_.multiplier,
                                  derivatives, rf);
        b.gap.assign(rf.gap.begin(), rf.gap.begin() + rf.n);
        if (derivatives) b.gradient = rf.dgap;
      }
      out.push_back(std::move(b));
    }
    return;
  }
  if (dim() == 3) {
    gap_blocks_3d(u, order, out, hessian_rows);
    return;
  }
  const auto& X = mesh_->x;
  const auto position = [&](std::int32_t node) {
    const auto i = static_cast<std::size_t>(node) * 2;
    return Eigen::Vector2d(X[i] + u[i], X[i + 1] + u[i + 1]);
  };
  const mortar::FacetSet slaves = slave_set();
  const mortar::FacetSet masters = integration_master().facet_set();
  const mortar::NodeFacets& adjacency = slave_adjacency();
  for (const auto f : owned_)
    for (const auto& pair : pairs_of(f)) {
      const auto sn = slaves.facet_nodes(slave_index(pair.slave));
      const auto mn = masters.facet_nodes(integration_facet(pair.master));
      GapBlock b;
      b.dofs.assign(6, -1);
      std::array<local_index, 4> slave_slots{sn[0], sn[1], -1, -1};
      PairInput in;
      in.dual = options_.multiplier == mortar::Multiplier::dual;
      int n_slave_slots = 2;
      for (std::size_t k = 0; k < 2; ++k) {
        const auto facets = adjacency.of(sn[k]);
        SEAM_CHECK(facets.size() <= 2, InputError, "interface '", name_, "': slave node ",
                   slave_.mesh_nodes[static_cast<std::size_t>(sn[k])],
                   " lies on more than two facets");
        in.n_adjacent[k] = static_cast<int>(facets.size());
        for (std::size_t e = 0; e < facets.size(); ++e) {
          const auto nodes = slaves.facet_nodes(facets[e]);
          for (std::size_t c = 0; c < 2; ++c) {
            int slot = -1;
            for (int s = 0; s < n_slave_slots; ++s)
              if (slave_slots[static_cast<std::size_t>(s)] == nodes[c]) slot = s;
            if (slot < 0) {
              SEAM_ASSERT(n_slave_slots < 4);
              slot = n_slave_slots++;
              slave_slots[static_cast<std::size_t>(slot)] = nodes[c];
            }
            in.adjacent[k][e][c] = slot;
          }
        }
      }
      for (int s = 0; s < n_slave_slots; ++s) {
        const auto node = slave_.mesh_nodes[static_cast<std::size_t>(slave_slots[s])];
        b.dofs[static_cast<std::size_t>(s)] = static_cast<std::int64_t>(node) * 2;
        in.x[static_cast<std::size_t>(s)] = position(node);
      }
      for (std::size_t l = 0; l < 2; ++l) {
        const auto node = integration_node(mn[l]);
        b.dofs[4 + l] = static_cast<std::int64_t>(node) * 2;
        in.x[4 + l] = position(node);
      }
      // The frame of the slave facet's first node (as integrate_pair).
      const Eigen::Vector2d origin = in.x[0];
      for (auto& x : in.x) x -= origin;
      b.slave = {sn[0], sn[1]};
      b.gap.assign(2, 0.0);
      const GapOrder block_order = order_of(b.slave);
      if (block_order == GapOrder::value) {
        std::array<double, 2> g{};
        pair_gaps(in, options_.pair, g);
        b.gap = {g[0], g[1]};
      } else if (block_order == GapOrder::gradient) {
        std::array<Dual<12>, 2> g;
        pair_gaps(in, options_.pair, g);
        for (std::size_t j = 0; j < 2; ++j) {
          b.gap[j] = g[j].value;
          b.gradient.insert(b.gradient.end(), g[j].gradient.begin(), g[j].gradient.end());
        }
      } else {
        std::array<Hyper<12>, 2> g;
        pair_gaps(in, options_.pair, g);
        for (std::size_t j = 0; j < 2; ++j) {
          b.gap[j] = g[j].value;
          b.gradient.insert(b.gradient.end(), g[j].gradient.begin(), g[j].gradient.end());
          b.hessian.insert(b.hessian.end(), g[j].hessian.begin(), g[j].hessian.end());
        }
      }
      if (b.gap[0] == 0.0 && b.gap[1] == 0.0 &&
          std::all_of(b.gradient.begin(), b.gradient.end(), [](double v) { return v == 0.0; }))
        continue; // no overlap: the pair adds nothing
      out.push_back(std::move(b));
    }
}

} // namespace seam::contact
