// The contact linearization against central differences of the contact evaluation itself:
// d(contact force)/d(displacement) at fixed normal multipliers and d g~_j/d(displacement), on
// two non-matching meshes in 2D (line2) and 3D (quad4, tri3), with dual and with standard
// multipliers (D not diagonal), pressed into each other with a random perturbation, so that
// master edges cross the slave integration cells, some slave nodes penetrate and others are
// open; and on rigid obstacles (a plane, a sphere or circle, a cylinder with a tilted axis; the
// round ones with the derivative of their normal at the node). Every derivative the contact
// Newton uses goes through here: normals, projections, clip polygons, cell Jacobians, dual
// coefficients, D, M and g~.
#include "seam/contact/contact_interface.hpp"
#include "seam/mesh/gmsh_reader.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>

namespace seam::contact {
namespace {

std::filesystem::path write_geo(const std::string& name, const std::string& text) {
  const auto path = std::filesystem::temp_directory_path() / name;
  std::ofstream(path) << text;
  return path;
}

mesh::Mesh two_blocks(int dim, bool tets) {
  std::string geo;
  if (dim == 2) {
    geo = R"(
Point(1) = {0, -0.5, 0}; Point(2) = {1, -0.5, 0}; Point(3) = {1, 0, 0}; Point(4) = {0, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 8; Transfinite Curve{2, 4} = 3; Transfinite Surface{1}; Recombine Surface{1};
Point(5) = {0.13, 0, 0}; Point(6) = {0.91, 0, 0}; Point(7) = {0.91, 0.4, 0}; Point(8) = {0.13, 0.4, 0};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Transfinite Curve{5, 7} = 6; Transfinite Curve{6, 8} = 3; Transfinite Surface{2}; Recombine Surface{2};
Physical Surface("lower") = {1}; Physical Surface("upper") = {2};
Physical Curve("master") = {3}; Physical Curve("slave") = {5};
)";
  } else {
    geo = "SetFactory(\"OpenCASCADE\");\n"
          "Box(1) = {0, 0, -0.5, 1, 1, 0.5};\n"
          "Box(2) = {0.11, 0.07, 0, 0.8, 0.85, 0.4};\n";
    if (tets) {
      geo += "Mesh.MeshSizeMax = 0.3;\n";
    } else {
      geo += "Transfinite Curve{1:12} = 5; Transfinite Surface{1:6}; Recombine Surface{1:6};\n"
             "Transfinite Volume{1};\n"
             "Transfinite Curve{13:24} = 4; Transfinite Surface{7:12}; Recombine "
             "Surface{7:12};\nTransfinite Volume{2};\n";
    }
    geo += "Physical Volume(\"lower\") = {1}; Physical Volume(\"upper\") = {2};\n"
           "Physical Surface(\"master\") = {6}; Physical Surface(\"slave\") = {11};\n";
  }
  mesh::ReadOptions options;
  options.dim = dim;
  return mesh::read_mesh(write_geo(dim == 2 ? "contact_fd_2d.geo"
                                            : (tets ? "contact_fd_tet.geo" : "contact_fd_hex.geo"),
                                   geo),
                         options);
}

/// The rigid obstacle of a rigid case: a plane, or below the slave block's bottom a sphere
/// (circle) or a cylinder of radius 2, so the slave bottom meets a curved surface.
enum class Shape { plane, sphere, cylinder };

io::Interface contact_config(bool rigid, int dim, bool standard, bool friction = false,
                             Shape shape = Shape::plane) {
  io::Interface c;
  if (friction) {
    c.friction.model = io::FrictionModel::coulomb;
    c.friction.coefficient = 0.3;
  }
  c.multiplier = standard ? io::Multiplier::standard : io::Multiplier::dual;
  c.name.assign("contact");
  c.type = io::InterfaceType::contact;
  c.slave.name.assign("slave");
  if (rigid && shape != Shape::plane) {
    io::RigidObstacle o;
    o.cylinder = shape == Shape::cylinder;
    o.radius = 2.0;
    o.point = {0.5, 0.5, 0.0};
    o.point[dim - 1] = -2.0;
    const double l = std::hypot(1.0, 0.3);
    o.axis = {1.0 / l, 0.3 / l, 0.0};
    o.motion.assign(static_cast<std::size_t>(dim), io::Expression(0.0));
    c.rigid_obstacle = o;
  } else if (rigid) {
    io::RigidPlane p;
    p.point = {0.0, 0.0, 0.0};
    p.normal = {0.0, 0.0, 0.0};
    p.normal[dim - 1] = 1.0;
    c.rigid_plane = p;
  } else {
    c.master = io::RegionRef{"master", {}};
  }
  return c;
}

using Dense = std::map<std::pair<std::int64_t, std::int64_t>, double>;

void check(int dim, bool tets, bool rigid, bool standard = false, Shape shape = Shape::plane) {
  const auto mesh = two_blocks(dim, tets);
  ContactInterface itf(contact_config(rigid, dim, standard, false, shape), mesh);
  // Press the upper block into the lower one, perturb every interface node.
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> perturb(-0.015, 0.015);
  std::vector<double> u(mesh.x.size(), 0.0);
  std::vector<std::int64_t> dofs;
  // Every third slave node is lifted off, the others pushed in.
  const auto add_side = [&](std::span<const std::int32_t> nodes, double push) {
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (int c = 0; c < dim; ++c) {
        const auto n = nodes[i];
        const double lift = i % 3 == 0 ? -2.0 * push : push;
        u[static_cast<std::size_t>(n) * dim + c] = perturb(rng) + (c == dim - 1 ? lift : 0.0);
        dofs.push_back(static_cast<std::int64_t>(n) * dim + c);
      }
  };
  add_side(itf.slave().mesh_nodes, -0.01);
  add_side(itf.master_nodes(), 0.0);
  itf.update(u, 0.0);
  NodalValues values;
  itf.evaluate(values);
  const auto n_slave = static_cast<std::size_t>(itf.n_slave_nodes());
  std::vector<double> lambda(n_slave);
  std::uniform_real_distribution<double> pressure(0.5, 2.0);
  int open = 0, closed = 0;
  for (std::size_t j = 0; j < n_slave; ++j) {
    lambda[j] = j % 5 == 3 ? 0.0 : pressure(rng); // some nodes without a multiplier
    if (values.D[j] > 0.0) (values.gap[j] > 0.0 ? open : closed)++;
  }
  EXPECT_GT(closed, 0);
  if (!rigid) {
    EXPECT_GT(open, 0);
  }
  const std::vector<char> want(n_slave, 1);
  Linearization lin;
  itf.linearize(lambda, want, lin);
  Dense K, G;
  for (const auto& e : lin.force_tangent) K[{e.row, e.col}] += e.value;
  for (const auto& e : lin.gap_gradient) G[{e.row, e.col}] += e.value;

  const auto state = [&](std::vector<double>& force, std::vector<double>& gap) {
    itf.update(u, 0.0);
    NodalValues v;
    itf.evaluate(v);
    force.assign(u.size(), 0.0);
    itf.add_force(v, lambda, force);
    gap = v.gap;
  };
  const double h = 1e-6;
  double k_max = 0.0, g_max = 0.0, k_err = 0.0, g_err = 0.0;
  std::vector<double> fp, fm, gp, gm;
  for (const auto d : dofs) {
    const auto i = static_cast<std::size_t>(d);
    const double u0 = u[i];
    u[i] = u0 + h;
    state(fp, gp);
    u[i] = u0 - h;
    state(fm, gm);
    u[i] = u0;
    for (std::size_t r = 0; r < fp.size(); ++r) {
      const double fd = (fp[r] - fm[r]) / (2 * h);
      const auto it = K.find({static_cast<std::int64_t>(r), d});
      const double an = it == K.end() ? 0.0 : it->second;
      k_max = std::max(k_max, std::abs(fd));
      k_err = std::max(k_err, std::abs(fd - an));
    }
    for (std::size_t j = 0; j < n_slave; ++j) {
      const double fd = (gp[j] - gm[j]) / (2 * h);
      const auto it = G.find({static_cast<std::int64_t>(j), d});
      const double an = it == G.end() ? 0.0 : it->second;
      g_max = std::max(g_max, std::abs(fd));
      g_err = std::max(g_err, std::abs(fd - an));
    }
  }
  std::printf("  dim %d %s %s %s: %zu dofs, |dF/du| max %.3e err %.3e, |dg/du| max %.3e err "
              "%.3e\n",
              dim, tets ? "tri3" : (dim == 2 ? "line2" : "quad4"),
              rigid ? (shape == Shape::plane
                           ? "rigid plane"
                           : (shape == Shape::sphere ? "rigid sphere" : "rigid cylinder"))
                    : "two bodies",
              standard ? "standard" : "dual", dofs.size(), k_max, k_err, g_max, g_err);
  if (standard) {
    EXPECT_FALSE(values.D_coupling.empty()); // D is not diagonal
  }
  EXPECT_GT(k_max, 0.1);
  EXPECT_GT(g_max, 1e-3);
  EXPECT_LT(k_err, 1e-6 * k_max);
  EXPECT_LT(g_err, 1e-6 * g_max);
}

// Friction: Cartesian multipliers. The force tangent at fixed multipliers, dD_jj, the
// derivative of the operators in the slip increment, sum_l M_jl x_l - D_jj x_j at fixed x, and
// the normals' Jacobian, against central differences. Standard multipliers: the nodal weight
// sum_k D_jk and sum_l M_jl x_l - sum_k D_jk x_k instead.
void check_friction(int dim, bool tets, bool rigid, bool standard = false,
                    Shape shape = Shape::plane) {
  const auto mesh = two_blocks(dim, tets);
  ContactInterface itf(contact_config(rigid, dim, standard, true, shape), mesh);
  ASSERT_TRUE(itf.frictional());
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> perturb(-0.015, 0.015), unit(-1.0, 1.0);
  std::vector<double> u(mesh.x.size(), 0.0);
  std::vector<std::int64_t> dofs;
  const auto add_side = [&](std::span<const std::int32_t> nodes, double push) {
    for (const auto n : nodes)
      for (int c = 0; c < dim; ++c) {
        u[static_cast<std::size_t>(n) * dim + c] = perturb(rng) + (c == dim - 1 ? push : 0.0);
        dofs.push_back(static_cast<std::int64_t>(n) * dim + c);
      }
  };
  add_side(itf.slave().mesh_nodes, -0.01);
  add_side(itf.master_nodes(), 0.0);
  const auto n_slave = static_cast<std::size_t>(itf.n_slave_nodes());
  std::vector<double> lambda(n_slave * dim);
  for (auto& l : lambda) l = unit(rng);
  itf.update(u, 0.0);
  const std::vector<double> x0(itf.slave_positions().begin(), itf.slave_positions().end());
  const std::vector<double> xm0(itf.master_positions().begin(), itf.master_positions().end());
  const std::vector<char> want(n_slave, 1);
  Linearization lin;
  itf.linearize(lambda, want, lin);
  Dense K, DD, W, N;
  for (const auto& e : lin.force_tangent) K[{e.row, e.col}] += e.value;
  for (const auto& e : lin.D_gradient) DD[{e.row, e.col}] += e.value;
  for (const auto& e : lin.operator_gradient) W[{e.row, e.col}] += e.value;
  std::vector<DofTriplet> dn;
  for (std::size_t j = 0; j < n_slave; ++j) {
    dn.clear();
    itf.normal_jacobian(static_cast<local_index>(j), dn);
    for (const auto& e : dn) N[{static_cast<std::int64_t>(j) * dim + e.row, e.col}] += e.value;
  }
  // force, D, the operators' part of the slip at the base positions, normals.
  const auto state = [&](std::vector<double>& f, std::vector<double>& d, std::vector<double>& w,
                         std::vector<double>& n) {
    itf.update(u, 0.0);
    NodalValues v;
    itf.evaluate(v);
    f.assign(u.size(), 0.0);
    itf.add_force(v, lambda, f);
    d = v.D;
    w.assign(n_slave * dim, 0.0);
    for (std::size_t j = 0; j < n_slave; ++j)
      for (int c = 0; c < dim; ++c) w[j * dim + c] -= v.D[j] * x0[j * dim + c];
    for (const auto& e : v.D_coupling) {
      const auto j = static_cast<std::size_t>(e.row), k = static_cast<std::size_t>(e.col);
      d[j] += e.value;
      for (int c = 0; c < dim; ++c) w[j * dim + c] -= e.value * x0[k * dim + c];
    }
    // M columns are mesh nodes: the master positions at the base state.
    const auto& masters = itf.master_nodes();
    for (const auto& e : v.M) {
      const auto p = static_cast<std::size_t>(
          std::lower_bound(masters.begin(), masters.end(), e.master_node) - masters.begin());
      for (int c = 0; c < dim; ++c)
        w[static_cast<std::size_t>(e.slave) * dim + c] += e.value * xm0[p * dim + c];
    }
    n = itf.normals();
  };
  const double h = 1e-6;
  double err[4] = {0, 0, 0, 0}, big[4] = {0, 0, 0, 0};
  std::vector<double> a[4], b[4];
  const Dense* an[4] = {&K, &DD, &W, &N};
  for (const auto d : dofs) {
    const auto i = static_cast<std::size_t>(d);
    const double u0 = u[i];
    u[i] = u0 + h;
    state(a[0], a[1], a[2], a[3]);
    u[i] = u0 - h;
    state(b[0], b[1], b[2], b[3]);
    u[i] = u0;
    for (int k = 0; k < 4; ++k)
      for (std::size_t r = 0; r < a[k].size(); ++r) {
        const double fd = (a[k][r] - b[k][r]) / (2 * h);
        const auto it = an[k]->find({static_cast<std::int64_t>(r), d});
        const double value = it == an[k]->end() ? 0.0 : it->second;
        big[k] = std::max(big[k], std::abs(fd));
        err[k] = std::max(err[k], std::abs(fd - value));
      }
  }
  if (standard) {
    ASSERT_FALSE(lin.D_gradient.empty());
  }
  std::printf("  friction%s dim %d %s %s: |dF| %.2e err %.2e, |dD| %.2e err %.2e, |dW| %.2e err "
              "%.2e, |dn| %.2e err %.2e\n",
              standard ? " standard" : "", dim, tets ? "tri3" : (dim == 2 ? "line2" : "quad4"),
              rigid ? (shape == Shape::plane
                           ? "rigid plane"
                           : (shape == Shape::sphere ? "rigid sphere" : "rigid cylinder"))
                    : "two bodies",
              big[0], err[0], big[1], err[1], big[2], err[2], big[3], err[3]);
  EXPECT_GT(big[0], 0.05);
  EXPECT_GT(big[1], 1e-3);
  // A rigid plane has no M: its slip increment is built from the nodal positions alone.
  for (int k = 0; k < 4; ++k)
    if (!rigid || k != 2) {
      EXPECT_LE(err[k], 1e-6 * std::max(big[k], 1e-3));
    }
  if (!rigid) {
    EXPECT_GT(big[2], 1e-3);
  }
  if (!rigid || shape != Shape::plane) {
    EXPECT_GT(big[3], 1e-2); // the normal turns with the node
  }
}

TEST(ContactLinearization, Friction2D) {
  check_friction(2, false, false);
}
TEST(ContactLinearization, FrictionQuad4) {
  check_friction(3, false, false);
}
TEST(ContactLinearization, FrictionTri3) {
  check_friction(3, true, false);
}
TEST(ContactLinearization, FrictionRigidPlane2D) {
  check_friction(2, false, true);
}
TEST(ContactLinearization, FrictionRigidPlane3D) {
  check_friction(3, false, true);
}
TEST(ContactLinearization, FrictionStandard2D) {
  check_friction(2, false, false, true);
}
TEST(ContactLinearization, FrictionStandardQuad4) {
  check_friction(3, false, false, true);
}
TEST(ContactLinearization, FrictionStandardRigidPlane3D) {
  check_friction(3, false, true, true);
}

TEST(ContactLinearization, TwoBodies2D) {
  check(2, false, false);
}
TEST(ContactLinearization, TwoBodiesQuad4) {
  check(3, false, false);
}
TEST(ContactLinearization, TwoBodiesTri3) {
  check(3, true, false);
}
TEST(ContactLinearization, TwoBodies2DStandard) {
  check(2, false, false, true);
}
TEST(ContactLinearization, TwoBodiesQuad4Standard) {
  check(3, false, false, true);
}
TEST(ContactLinearization, TwoBodiesTri3Standard) {
  check(3, true, false, true);
}
TEST(ContactLinearization, RigidPlane2D) {
  check(2, false, true);
}
TEST(ContactLinearization, RigidPlane3D) {
  check(3, false, true);
}
TEST(ContactLinearization, RigidPlane3DStandard) {
  check(3, false, true, true);
}
TEST(ContactLinearization, RigidPlaneTri3) {
  check(3, true, true);
}
TEST(ContactLinearization, RigidCircle2D) {
  check(2, false, true, false, Shape::sphere);
}
TEST(ContactLinearization, RigidCircle2DStandard) {
  check(2, false, true, true, Shape::sphere);
}
TEST(ContactLinearization, RigidSphereQuad4) {
  check(3, false, true, false, Shape::sphere);
}
TEST(ContactLinearization, RigidSphereTri3) {
  check(3, true, true, false, Shape::sphere);
}
TEST(ContactLinearization, RigidCylinderQuad4) {
  check(3, false, true, false, Shape::cylinder);
}
TEST(ContactLinearization, RigidCylinderTri3) {
  check(3, true, true, false, Shape::cylinder);
}
TEST(ContactLinearization, FrictionRigidCircle2D) {
  check_friction(2, false, true, false, Shape::sphere);
}
TEST(ContactLinearization, FrictionRigidSphere3D) {
  check_friction(3, false, true, false, Shape::sphere);
}
TEST(ContactLinearization, FrictionRigidCylinder3DStandard) {
  check_friction(3, false, true, true, Shape::cylinder);
}

/// The slave facets split into parts (as the ranks hold them): each part searches and
/// integrates its own facets only, and the parts' sums equal the whole interface's D, g~, M,
/// pairs, integration cells and force tangent.
void check_parts(int dim, bool tets, bool rigid, Shape shape = Shape::plane) {
  const auto mesh = two_blocks(dim, tets);
  ContactInterface whole(contact_config(rigid, dim, false, false, shape), mesh);
  std::vector<double> u(mesh.x.size(), 0.0);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> perturb(-0.01, 0.01);
  for (const auto n : whole.slave().mesh_nodes)
    for (int c = 0; c < dim; ++c)
      u[static_cast<std::size_t>(n) * dim + c] = perturb(rng) + (c == dim - 1 ? -0.01 : 0.0);
  whole.update(u, 0.0);
  NodalValues all;
  whole.evaluate(all);
  const auto n_slave = static_cast<std::size_t>(whole.n_slave_nodes());
  const std::vector<double> lambda(n_slave, 1.0);
  const std::vector<char> want(n_slave, 1);
  Linearization lin;
  whole.linearize(lambda, want, lin);
  Dense K, M;
  for (const auto& e : lin.force_tangent) K[{e.row, e.col}] += e.value;
  for (const auto& e : all.M) M[{e.slave, e.master_node}] += e.value;
  ASSERT_GT(all.n_pairs, 0);

  const local_index n_facets = whole.slave().n_facets();
  constexpr int n_parts = 3;
  std::vector<double> D(n_slave, 0.0), gap(n_slave, 0.0);
  Dense K_parts, M_parts;
  local_index pairs = 0, cells = 0, candidates = 0;
  for (int part = 0; part < n_parts; ++part) {
    ContactInterface itf(contact_config(rigid, dim, false, false, shape), mesh);
    std::vector<local_index> mine; // contiguous blocks: parts with and without contact
    for (local_index f = part * n_facets / n_parts; f < (part + 1) * n_facets / n_parts; ++f)
      mine.push_back(f);
    itf.set_owned_facets(mine);
    itf.update(u, 0.0);
    for (local_index f = 0; f < n_facets; ++f)
      if (!std::binary_search(mine.begin(), mine.end(), f)) {
        EXPECT_EQ(itf.n_pairs_of(f), 0);
      }
    NodalValues v;
    itf.evaluate(v);
    for (std::size_t j = 0; j < n_slave; ++j) {
      D[j] += v.D[j];
      gap[j] += v.gap[j];
    }
    for (const auto& e : v.M) M_parts[{e.slave, e.master_node}] += e.value;
    pairs += v.n_pairs;
    cells += v.n_cells;
    candidates += itf.n_candidates();
    itf.linearize(lambda, want, lin);
    for (const auto& e : lin.force_tangent) K_parts[{e.row, e.col}] += e.value;
  }
  EXPECT_EQ(pairs, all.n_pairs);
  EXPECT_EQ(cells, all.n_cells);
  EXPECT_EQ(candidates, whole.n_candidates());
  for (std::size_t j = 0; j < n_slave; ++j) {
    EXPECT_NEAR(D[j], all.D[j], 1e-14);
    EXPECT_NEAR(gap[j], all.gap[j], 1e-14);
  }
  const auto same = [](const Dense& a, const Dense& b) {
    double worst = 0.0;
    for (const auto& [k, v] : a) {
      const auto it = b.find(k);
      worst = std::max(worst, std::abs(v - (it == b.end() ? 0.0 : it->second)));
    }
    for (const auto& [k, v] : b)
      if (!a.count(k)) worst = std::max(worst, std::abs(v));
    return worst;
  };
  EXPECT_LT(same(M, M_parts), 1e-14);
  EXPECT_LT(same(K, K_parts), 1e-12);
}

TEST(ContactParts, TwoBodies2D) {
  check_parts(2, false, false);
}
TEST(ContactParts, TwoBodiesQuad4) {
  check_parts(3, false, false);
}
TEST(ContactParts, TwoBodiesTri3) {
  check_parts(3, true, false);
}
TEST(ContactParts, RigidPlane3D) {
  check_parts(3, false, true);
}
TEST(ContactParts, RigidSphere3D) {
  check_parts(3, false, true, Shape::sphere);
}

// The search split from the placement (ContactInterface::place / set_candidates): an
// interface given the pairs of its own search from outside evaluates to the same D, g~ and M
// bit for bit, and given every slave-master pair (the facing test applied inside) to the same
// values up to round-off, since the extra pairs do not overlap.
void check_external_search(int dim, bool tets) {
  const auto mesh = two_blocks(dim, tets);
  ContactInterface own(contact_config(false, dim, false), mesh);
  ContactInterface outside(contact_config(false, dim, false), mesh);
  outside.use_external_search();
  EXPECT_TRUE(outside.external_search());
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> perturb(-0.01, 0.01);
  std::vector<double> u(mesh.x.size(), 0.0);
  for (auto& v : u) v = perturb(rng);
  own.update(u, 0.0);
  outside.place(u, 0.0);
  EXPECT_EQ(outside.normals(), own.normals());
  std::vector<mortar::CandidatePair> pairs, every;
  for (local_index f = 0; f < own.slave().n_facets(); ++f) {
    for (const auto& p : own.pairs_of(f)) pairs.push_back(p);
    for (local_index m = 0; m < outside.n_master_facets(); ++m) every.push_back({f, m});
  }
  ASSERT_GT(pairs.size(), 0u);
  NodalValues a, b;
  own.evaluate(a);
  outside.set_candidates(pairs);
  EXPECT_EQ(outside.n_candidates(), own.n_candidates());
  outside.evaluate(b);
  EXPECT_EQ(b.D, a.D);
  EXPECT_EQ(b.gap, a.gap);
  ASSERT_EQ(b.M.size(), a.M.size());
  outside.set_candidates(every);
  EXPECT_GT(outside.n_candidates(), own.n_candidates());
  outside.evaluate(b);
  double scale = 0.0;
  for (const double d : a.D) scale = std::max(scale, d);
  for (std::size_t j = 0; j < a.D.size(); ++j) {
    EXPECT_NEAR(b.D[j], a.D[j], 1e-13 * scale);
    EXPECT_NEAR(b.gap[j], a.gap[j], 1e-13 * scale);
  }
  std::map<std::pair<local_index, std::int32_t>, double> ma, mb;
  for (const auto& e : a.M) ma[{e.slave, e.master_node}] += e.value;
  for (const auto& e : b.M) mb[{e.slave, e.master_node}] += e.value;
  for (const auto& [key, value] : ma) EXPECT_NEAR(mb[key], value, 1e-13 * scale);
  for (const auto& [key, value] : mb) EXPECT_NEAR(ma[key], value, 1e-13 * scale);
}

TEST(ContactExternalSearch, SameValues2D) {
  check_external_search(2, false);
}
TEST(ContactExternalSearch, SameValuesQuad4) {
  check_external_search(3, false);
}
TEST(ContactExternalSearch, SameValuesTri3) {
  check_external_search(3, true);
}

} // namespace
} // namespace seam::contact
