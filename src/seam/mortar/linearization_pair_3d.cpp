// Linearized 3D mortar pair integration by mixed-mode differentiation (ALGORITHMS.md §2, §5;
// Popp et al. 2010 for the quantities that must carry derivatives). The values follow
// integrate_pair (integration_3d.cpp) decision for decision; the derivatives are organized in
// three levels so that nothing per integration point carries a full gradient:
//
//  1. Per slave piece, the auxiliary plane (origin c, frame e = (t1, t2, n_aux)) in dual
//     numbers over the piece's vertex coordinates (<= 12 variables). Every point quantity is
//     a function of the "plane parameters" P of the pair: in-plane node coordinates U_k and
//     heights H_k = e . (x_k - c) of slave and master nodes, the slave nodal normals in the
//     plane frame n~_k = e . n_k, plus the dual coefficients A_e (plane independent).
//  2. Per clip polygon, its vertices, the fan centroid, the cell vertices and cell areas in
//     dual numbers over the in-plane vertex coordinates of the two clipped pieces (<= 16).
//  3. Per integration point, hand-coded partial derivatives with respect to the point's own
//     location u in the plane, its weight and P. A point projected onto a facet along n_aux
//     satisfies u = sum_k N_k(xi) U_k in the plane, so by the implicit function theorem
//       dxi = J^{-1} (du - sum_k N_k dU_k),  J = sum_k U_k (grad N_k)^T,
//     and x_m - x_s = (h_m - h_s) n_aux, so the gap g = n . (x_m - x_s) with n = n~ / |n~|,
//     n~ = sum_k N_k n~_k, is g = (h_m - h_s) n~_z / |n~|.
// Each output o (M_jl, g~_j, standard D_jk) accumulates adjoints: d o / dP summed over the
// points, d o / d(cell vertex, cell area) per cell. These are chained once per cell into the
// clip variables, once per clip into P, once per piece through the plane into the pair
// variables, and once per pair through dA_e = (dD_e - A_e dM_e) M_e^{-1}.
#include <memory>

#include "seam/mortar/linearization_pair_3d.hpp"

namespace seam::mortar::ad {

namespace {

using namespace pair3d;

template <int NS, int NM>
void integrate_clip(PairState& st, const mortar::detail::PlanarFacet& sp,
                    const mortar::detail::PlanarFacet& mp,
                    const mortar::detail::PieceInverse& slave_inverse,
                    const mortar::detail::PieceInverse& master_inverse, const SlavePiece& piece,
                    const MasterPiece& master_piece, const TriangleListT<ClipDual>& cells,
                    const Eigen::Matrix<double, 3, max_nodes>& normals_in_plane,
                    const CellRule& rule, const geometry::NewtonOptions& newton) {
  constexpr bool linear = NS > 0;
  const int ns = linear ? NS : st.slave->facet.n_nodes;
  const int nm = linear ? NM : st.master->n_nodes;
  const fem::CellType slave_type = st.slave->facet.type, master_type = st.master->type;
  Adjoints& adj = *st.adj;
  const int no = adj.n_outputs, width = adj.width;
  const int m_offset = 2 * ns, hs_offset = 2 * ns + 2 * nm, hm_offset = hs_offset + ns,
            n_offset = hm_offset + nm;
  const int g_first = ns * nm, d_first = ns * nm + ns;
  PairContribution& c = *st.values;
  std::fill_n(adj.clip.begin(), no * 16, 0.0);

  NodalVector N = NodalVector::Zero(), Nm = NodalVector::Zero(), Nt = NodalVector::Zero();
  std::array<NodalVector, 2> dNt;
  std::array<double, 2 * max_nodes> dN{}, dNm{};
  std::array<double, max_nodes> Phi{};
  std::array<std::array<double, 2>, max_nodes> dPhi{};
  for (const TriangleT<ClipDual>& cell : cells) {
    const double area = cell.area().value;
    const Vector2d ca = values(cell.a), cb = values(cell.b), cc = values(cell.c);
    std::fill_n(adj.cell.begin(), no * cell_parameters, 0.0);
    for (int q = 0; q < rule.n_points; ++q) {
      const auto& rp = rule.points[static_cast<std::size_t>(q)];
      const double b0 = rp[0], b1 = rp[1], b2 = rp[2], omega = rp[3];
      const double w = omega * area;
      const Vector2d u = b0 * ca + b1 * cb + b2 * cc;
      Vector2d xs, xm;
      const bool located = slave_inverse.parent_coordinates(u, xs) &&
                           (linear || mortar::detail::newton_in_plane(sp, u, xs, newton)) &&
                           master_inverse.parent_coordinates(u, xm) &&
                           (linear || mortar::detail::newton_in_plane(mp, u, xm, newton));
      if (!located) {
        ++c.n_projection_failures;
        continue;
      }
      mortar::detail::shape_functions<true>(slave_type, xs, N, dN);
      mortar::detail::shape_functions<true>(master_type, xm, Nm, dNm);
      // Planar Jacobians of both facets and their inverses (implicit function theorem).
      Eigen::Matrix2d Js = Eigen::Matrix2d::Zero(), Jm = Eigen::Matrix2d::Zero();
      for (int k = 0; k < ns; ++k)
        for (int b = 0; b < 2; ++b)
          Js.col(b) += dN[static_cast<std::size_t>(2 * k + b)] * sp.u.col(k);
      for (int l = 0; l < nm; ++l)
        for (int b = 0; b < 2; ++b)
          Jm.col(b) += dNm[static_cast<std::size_t>(2 * l + b)] * mp.u.col(l);
      const Eigen::Matrix2d Ks = Js.inverse(), Km = Jm.inverse();

      // Slave displacement and multiplier functions with their xi-derivatives.
      for (int k = 0; k < ns; ++k) {
        Nt(k) = N(k);
        dNt[0](k) = dN[static_cast<std::size_t>(2 * k)];
        dNt[1](k) = dN[static_cast<std::size_t>(2 * k + 1)];
      }
      if (st.modification != 0.0) {
        modify_basis(slave_type, st.modification, Nt.data());
        modify_basis(slave_type, st.modification, dNt[0].data());
        modify_basis(slave_type, st.modification, dNt[1].data());
      }
      for (int j = 0; j < ns; ++j) {
        if (st.dual) {
          double phi = 0.0, d0 = 0.0, d1 = 0.0;
          for (int k = 0; k < ns; ++k) {
            const double A = st.coefficients->A(j, k);
            phi += A * Nt(k);
            d0 += A * dNt[0](k);
            d1 += A * dNt[1](k);
          }
          Phi[static_cast<std::size_t>(j)] = phi;
          dPhi[static_cast<std::size_t>(j)] = {d0, d1};
        } else {
          Phi[static_cast<std::size_t>(j)] = Nt(j);
          dPhi[static_cast<std::size_t>(j)] = {dNt[0](j), dNt[1](j)};
        }
      }

      // Gap g = (h_m - h_s) n~_z / |n~| and its partial derivatives.
      double hs = 0.0, hm = 0.0;
      Vector2d dhs = Vector2d::Zero(), dhm = Vector2d::Zero();
      Vector3d nt = Vector3d::Zero();
      std::array<Vector3d, 2> dnt{Vector3d::Zero(), Vector3d::Zero()};
      for (int k = 0; k < ns; ++k) {
        const double h = sp.height(k);
        hs += h * N(k);
        nt += N(k) * normals_in_plane.col(k);
        for (int b = 0; b < 2; ++b) {
          const double d = dN[static_cast<std::size_t>(2 * k + b)];
          dhs(b) += h * d;
          dnt[static_cast<std::size_t>(b)] += d * normals_in_plane.col(k);
        }
      }
      for (int l = 0; l < nm; ++l) {
        hm += mp.height(l) * Nm(l);
        for (int b = 0; b < 2; ++b)
          dhm(b) += mp.height(l) * dNm[static_cast<std::size_t>(2 * l + b)];
      }
      const double length = nt.norm();
      const double cosine = nt.z() / length;
      const Vector3d dcos = (Vector3d::UnitZ() - cosine / length * nt) / length; // d cos / d n~
      const double dh = hm - hs;
      const double g = dh * cosine;
      const Vector2d dg_s(-dhs(0) * cosine + dh * dcos.dot(dnt[0]),
                          -dhs(1) * cosine + dh * dcos.dot(dnt[1]));
      const Vector2d dg_m = dhm * cosine;

      // One output: value w f, d/dxi_s = w s, d/dxi_m = w m; chained to U_s, U_m and the cell.
      const auto chain = [&](int o, double f, const Vector2d& s, const Vector2d& m) {
        const Vector2d r = w * (Ks.transpose() * s);
        const Vector2d t = w * (Km.transpose() * m);
        double* P = adj.parameters.data() + static_cast<std::size_t>(o) * width;
        for (int k = 0; k < ns; ++k) {
          P[2 * k] -= N(k) * r(0);
          P[2 * k + 1] -= N(k) * r(1);
        }
        for (int l = 0; l < nm; ++l) {
          P[m_offset + 2 * l] -= Nm(l) * t(0);
          P[m_offset + 2 * l + 1] -= Nm(l) * t(1);
        }
        double* C = adj.cell.data() + static_cast<std::size_t>(o) * cell_parameters;
        const Vector2d du = r + t;
        C[0] += b0 * du(0), C[1] += b0 * du(1);
        C[2] += b1 * du(0), C[3] += b1 * du(1);
        C[4] += b2 * du(0), C[5] += b2 * du(1);
        C[6] += omega * f;
      };
      for (int j = 0; j < ns; ++j) {
        const double phi = Phi[static_cast<std::size_t>(j)];
        const Vector2d dphi(dPhi[static_cast<std::size_t>(j)][0],
                            dPhi[static_cast<std::size_t>(j)][1]);
        for (int l = 0; l < nm; ++l) {
          const int o = j * nm + l;
          const double nml = Nm(l);
          c.M(j, l) += w * phi * nml;
          chain(o, phi * nml, dphi * nml,
                phi * Vector2d(dNm[static_cast<std::size_t>(2 * l)],
                               dNm[static_cast<std::size_t>(2 * l + 1)]));
          if (st.dual) {
            double* A = adj.coefficients.data() + static_cast<std::size_t>(o) * max_nodes;
            for (int k = 0; k < ns; ++k) A[k] += w * Nt(k) * nml;
          }
        }
        const int o = g_first + j;
        c.weighted_gap(j) += w * phi * g;
        chain(o, phi * g, dphi * g + phi * dg_s, phi * dg_m);
        double* P = adj.parameters.data() + static_cast<std::size_t>(o) * width;
        const double wphi = w * phi;
        for (int k = 0; k < ns; ++k) {
          P[hs_offset + k] -= wphi * N(k) * cosine;
          const Vector3d dn = (wphi * dh * N(k)) * dcos;
          for (int a = 0; a < 3; ++a) P[n_offset + 3 * k + a] += dn(a);
        }
        for (int l = 0; l < nm; ++l) P[hm_offset + l] += wphi * Nm(l) * cosine;
        if (st.dual) {
          double* A = adj.coefficients.data() + static_cast<std::size_t>(o) * max_nodes;
          for (int k = 0; k < ns; ++k) A[k] += w * Nt(k) * g;
        } else {
          for (int k = 0; k < ns; ++k) {
            c.D(j, k) += w * phi * Nt(k);
            chain(d_first + j * ns + k, phi * Nt(k),
                  dphi * Nt(k) + phi * Vector2d(dNt[0](k), dNt[1](k)), Vector2d::Zero());
          }
        }
      }
    }
    // Cell adjoints -> clip variables through the cell vertices and the cell area.
    const std::array<const Vector<ClipDual, 2>*, 3> vertex{&cell.a, &cell.b, &cell.c};
    const ClipDual cell_area = cell.area();
    for (int o = 0; o < no; ++o) {
      const double* C = adj.cell.data() + static_cast<std::size_t>(o) * cell_parameters;
      double* X = adj.clip.data() + static_cast<std::size_t>(o) * 16;
      for (int v = 0; v < 3; ++v)
        for (int a = 0; a < 2; ++a) {
          const double ca_ = C[2 * v + a];
          if (ca_ == 0.0) continue;
          const auto& gr = (*vertex[static_cast<std::size_t>(v)])(a).gradient;
          for (int i = 0; i < 16; ++i) X[i] += ca_ * gr[static_cast<std::size_t>(i)];
        }
      if (C[6] != 0.0)
        for (int i = 0; i < 16; ++i) X[i] += C[6] * cell_area.gradient[static_cast<std::size_t>(i)];
    }
  }
  // Clip variables -> in-plane node coordinates U_s, U_m.
  for (int o = 0; o < no; ++o) {
    const double* X = adj.clip.data() + static_cast<std::size_t>(o) * 16;
    double* P = adj.parameters.data() + static_cast<std::size_t>(o) * width;
    for (int v = 0; v < piece.sub.n_vertices; ++v) {
      const int k = piece.sub.nodes[static_cast<std::size_t>(v)];
      P[2 * k] += X[2 * v];
      P[2 * k + 1] += X[2 * v + 1];
    }
    for (int v = 0; v < master_piece.sub.n_vertices; ++v) {
      const int l = master_piece.sub.nodes[static_cast<std::size_t>(v)];
      P[m_offset + 2 * l] += X[clip_master_offset + 2 * v];
      P[m_offset + 2 * l + 1] += X[clip_master_offset + 2 * v + 1];
    }
  }
}

// d o / dP of one slave piece -> pair variables: U, H and n~ are e . (x - c) and e . n_k with
// e and c functions of the piece vertices (the plane), so each node gets e^T beta directly
// and the plane collects the adjoints of e and c, chained through their dual gradients.
void flush_piece(const SlaveFacet<3>& slave, const Facet<3>& master, const SlavePiece& piece,
                 Adjoints& adj, PairLinearization& out) {
  const int ns = slave.facet.n_nodes, nm = master.n_nodes, nv = out.n_variables;
  const int m_offset = 2 * ns, hs_offset = 2 * ns + 2 * nm, hm_offset = hs_offset + ns,
            n_offset = hm_offset + nm;
  const std::array<Vector3d, 3> e{values(piece.e[0]), values(piece.e[1]), values(piece.e[2])};
  const Vector3d origin = values(piece.origin);
  for (int o = 0; o < adj.n_outputs; ++o) {
    const double* P = adj.parameters.data() + static_cast<std::size_t>(o) * adj.width;
    double* grad = output_row(out, o);
    std::array<Vector3d, 3> ge{Vector3d::Zero(), Vector3d::Zero(), Vector3d::Zero()};
    Vector3d gc = Vector3d::Zero();
    const auto node = [&](const Vector3d& beta, const Vector3d& r, int first, bool moves_with_c) {
      const Vector3d own = beta(0) * e[0] + beta(1) * e[1] + beta(2) * e[2];
      for (int i = 0; i < 3; ++i) grad[first + i] += own(i);
      for (int a = 0; a < 3; ++a) ge[static_cast<std::size_t>(a)] += beta(a) * r;
      if (moves_with_c) gc -= own;
    };
    for (int k = 0; k < ns; ++k)
      node(Vector3d(P[2 * k], P[2 * k + 1], P[hs_offset + k]), slave.facet.x.col(k) - origin, 3 * k,
           true);
    for (int l = 0; l < nm; ++l)
      node(Vector3d(P[m_offset + 2 * l], P[m_offset + 2 * l + 1], P[hm_offset + l]),
           master.x.col(l) - origin, 3 * (ns + l), true);
    for (int k = 0; k < ns; ++k)
      node(Vector3d(P[n_offset + 3 * k], P[n_offset + 3 * k + 1], P[n_offset + 3 * k + 2]),
           slave.normals.col(k), 3 * (ns + nm + k), false);
    for (int v = 0; v < piece.sub.n_vertices; ++v) {
      const int k = piece.sub.nodes[static_cast<std::size_t>(v)];
      for (int i = 0; i < 3; ++i) {
        const auto g = static_cast<std::size_t>(3 * v + i);
        double sum = 0.0;
        for (int b = 0; b < 3; ++b) {
          sum += gc(b) * piece.origin(b).gradient[g];
          for (int a = 0; a < 3; ++a)
            sum += ge[static_cast<std::size_t>(a)](b) *
                   piece.e[static_cast<std::size_t>(a)](b).gradient[g];
        }
        grad[3 * k + i] += sum;
      }
    }
    (void)nv;
  }
}

template <int NS, int NM>
void pair_kernel(const SlaveFacet<3>& slave, const Facet<3>& master, const PairOptions& options,
                 const CoefficientLinearization* coefficients, PairLinearization& out) {
  const Facet<3>& s = slave.facet;
  const int ns = s.n_nodes, nm = master.n_nodes;
  const bool dual = slave.basis.multiplier == Multiplier::dual;
  SEAM_ASSERT(!dual || (coefficients && coefficients->n == ns));
  prepare_output(out, 3, ns, nm);
  PairContribution& c = out.values;

  const double factor = options.max_center_distance_factor;
  const double reach_squared =
      factor * factor *
      std::max(longest_corner_edge_squared(s), longest_corner_edge_squared(master));
  if ((center_position(s) - center_position(master)).squaredNorm() > reach_squared) return;

  // About 140 kB at full (quadratic) size: allocated once per thread on first use rather than
  // as static thread-local storage, which would come out of every thread's stack.
  static thread_local std::unique_ptr<Adjoints> scratch;
  if (!scratch) scratch = std::make_unique<Adjoints>();
  Adjoints& adj = *scratch;
  adj.n_outputs = ns * nm + ns + (dual ? 0 : ns * ns);
  adj.width = 6 * ns + 3 * nm;
  std::fill_n(adj.coefficients.begin(), adj.n_outputs * max_nodes, 0.0);

  const bool slave_linear = fem::order(s.type) == 1;
  const bool master_linear = fem::order(master.type) == 1;
  const int degree = options.cell_quadrature_degree > 0 ? options.cell_quadrature_degree
                     : slave_linear && master_linear    ? 5
                                                        : 8;
  const CellRule rule(degree);
  PairState state{
      &slave, &master, coefficients, dual, basis_modification(s.type, slave.basis.multiplier),
      &out,   &c,      &adj};
  const auto master_subfacets = linear_subfacets(master.type);
  std::array<MasterPiece, 5> master_pieces;
  bool master_pieces_made = false;
  Eigen::Matrix<double, 3, max_nodes> normals_in_plane =
      Eigen::Matrix<double, 3, max_nodes>::Zero();
  for (const SubFacet& slave_sub : linear_subfacets(s.type)) {
    const SlavePiece piece = make_slave_piece(s, slave_sub);
    if (piece.degenerate) continue;
    const mortar::detail::PlanarFacet sp(s, piece.plane);
    const mortar::detail::PlanarFacet mp(master, piece.plane);
    PolygonT<ClipDual> slave_polygon;
    std::array<Vector2d, 4> slave_u;
    slave_u.fill(Vector2d::Zero());
    for (int v = 0; v < slave_sub.n_vertices; ++v) {
      slave_u[static_cast<std::size_t>(v)] = sp.u.col(slave_sub.nodes[static_cast<std::size_t>(v)]);
      slave_polygon.push_back(Vector<ClipDual, 2>(
          ClipDual::variable(slave_u[static_cast<std::size_t>(v)](0), 2 * v),
          ClipDual::variable(slave_u[static_cast<std::size_t>(v)](1), 2 * v + 1)));
    }
    const Box slave_box =
        box_of([&](int v) { return slave_u[static_cast<std::size_t>(v)]; }, slave_sub.n_vertices);
    if (slave_box.misses(box_of([&](int l) { return Vector2d(mp.u.col(l)); }, nm))) continue;
    if (!master_pieces_made) {
      for (std::size_t i = 0; i < master_subfacets.size(); ++i)
        master_pieces[i] = make_master_piece(master, master_subfacets[i]);
      master_pieces_made = true;
    }
    for (int k = 0; k < ns; ++k)
      for (int a = 0; a < 3; ++a)
        normals_in_plane(a, k) =
            values(piece.e[static_cast<std::size_t>(a)]).dot(slave.normals.col(k));
    std::fill_n(adj.parameters.begin(), adj.n_outputs * adj.width, 0.0);
    mortar::detail::PieceInverse slave_inverse;
    bool slave_inverse_set = false, slave_valid = false, integrated = false;
    for (std::size_t i = 0; i < master_subfacets.size(); ++i) {
      const MasterPiece& mpiece = master_pieces[i];
      if (!(mpiece.normal.dot(piece.plane.normal) < -1e-12)) continue;
      std::array<Vector2d, 4> master_u;
      master_u.fill(Vector2d::Zero());
      PolygonT<ClipDual> master_polygon;
      for (int v = 0; v < mpiece.sub.n_vertices; ++v) {
        master_u[static_cast<std::size_t>(v)] =
            mp.u.col(mpiece.sub.nodes[static_cast<std::size_t>(v)]);
        master_polygon.push_back(
            Vector<ClipDual, 2>(ClipDual::variable(master_u[static_cast<std::size_t>(v)](0),
                                                   clip_master_offset + 2 * v),
                                ClipDual::variable(master_u[static_cast<std::size_t>(v)](1),
                                                   clip_master_offset + 2 * v + 1)));
      }
      if (slave_box.misses(box_of([&](int v) { return master_u[static_cast<std::size_t>(v)]; },
                                  mpiece.sub.n_vertices)))
        continue;
      const PolygonT<ClipDual> clip =
          clip_polygons_t<ClipDual>(slave_polygon, master_polygon, options.clip);
      if (clip.empty()) continue;
      const TriangleListT<ClipDual> cells = triangulate_fan_t<ClipDual>(clip);
      c.n_cells += cells.size();
      c.area += std::abs(signed_area_t<ClipDual>(clip).value);
      if (!slave_inverse_set) {
        slave_valid = slave_inverse.set(slave_sub.n_vertices, slave_u, piece.xi, slave_linear);
        slave_inverse_set = true;
      }
      mortar::detail::PieceInverse master_inverse;
      const bool master_valid =
          master_inverse.set(mpiece.sub.n_vertices, master_u, mpiece.xi, master_linear);
      if (!slave_valid || !master_valid) {
        c.n_projection_failures += cells.size() * rule.n_points;
        continue;
      }
      integrate_clip<NS, NM>(state, sp, mp, slave_inverse, master_inverse, piece, mpiece, cells,
                             normals_in_plane, rule, options.newton);
      integrated = true;
    }
    if (integrated) flush_piece(slave, master, piece, adj, out);
  }

  if (dual) {
    // dA_e chained once per pair, then D_jj = sum_l M_jl (the row-sum accumulation).
    const int n_slave_variables = 3 * ns;
    for (int o = 0; o < adj.n_outputs; ++o) {
      const int j = o < ns * nm ? o / nm : o - ns * nm;
      const double* A = adj.coefficients.data() + static_cast<std::size_t>(o) * max_nodes;
      double* grad = output_row(out, o);
      for (int k = 0; k < ns; ++k) {
        if (A[k] == 0.0) continue;
        const double* dA = coefficients->gradient.data() +
                           static_cast<std::size_t>((j * ns + k) * n_slave_variables);
        for (int v = 0; v < n_slave_variables; ++v) grad[v] += A[k] * dA[v];
      }
    }
    const auto nv = static_cast<std::size_t>(out.n_variables);
    for (int j = 0; j < ns; ++j) {
      double* d = out.D_gradient.data() + static_cast<std::size_t>(j * ns + j) * nv;
      for (int l = 0; l < nm; ++l) {
        c.D(j, j) += c.M(j, l);
        const double* m = out.M_gradient.data() + static_cast<std::size_t>(j * nm + l) * nv;
        for (std::size_t v = 0; v < nv; ++v) d[v] += m[v];
      }
    }
  }
}

} // namespace

void linearize_pair_3d(const SlaveFacet<3>& slave, const Facet<3>& master,
                       const PairOptions& options, const CoefficientLinearization* coefficients,
                       PairLinearization& out) {
  using fem::CellType;
  const CellType st = slave.facet.type, mt = master.type;
  const bool s3 = st == CellType::tri3, s4 = st == CellType::quad4;
  const bool m3 = mt == CellType::tri3, m4 = mt == CellType::quad4;
  if (s3 && m3) return pair_kernel<3, 3>(slave, master, options, coefficients, out);
  if (s3 && m4) return pair_kernel<3, 4>(slave, master, options, coefficients, out);
  if (s4 && m3) return pair_kernel<4, 3>(slave, master, options, coefficients, out);
  if (s4 && m4) return pair_kernel<4, 4>(slave, master, options, coefficients, out);
  pair_kernel<0, 0>(slave, master, options, coefficients, out);
}

} // namespace seam::mortar::ad
