// seam-bench mortar-share: the share of a tied 3D run's time spent in mortar work (search,
// integration, mesh initialization, building and applying the condensation) against the bulk
// assembly, for two hex8 blocks tied across a non-matching interface of about 1e5 slave faces.
#include "registry.hpp"

#include "seam/la/petsc.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/mortar/interface.hpp"
#include "seam/mortar/normals.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/tying_constraint.hpp"
#include "seam/search/interface_search.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

namespace {

using seam::fem::CellType;
namespace mortar = seam::mortar;
namespace search = seam::search;

double wall_now() {
  timespec t{};
  clock_gettime(CLOCK_MONOTONIC, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

/// Adds an n x n x layers block of hex8 cells on [0,1]^2 x [z0, z0 + thickness] to `mesh`;
/// returns the cells of its top (top = true) or bottom face as a facet region.
seam::mesh::Region add_block(seam::mesh::Mesh& mesh, int n, int layers, double z0, double thickness,
                             bool top, const std::string& name) {
  const auto first = static_cast<std::int32_t>(mesh.x.size() / 3);
  const auto id = [&](int i, int j, int k) { return first + (k * (n + 1) + j) * (n + 1) + i; };
  for (int k = 0; k <= layers; ++k)
    for (int j = 0; j <= n; ++j)
      for (int i = 0; i <= n; ++i)
        mesh.x.insert(mesh.x.end(), {double(i) / n, double(j) / n, z0 + thickness * k / layers});
  // The local facet of a hex8 on which the reference coordinate z is +1 (top) or -1.
  int face = -1;
  const auto ref = seam::fem::reference_nodes(CellType::hex8);
  for (int f = 0; f < seam::fem::n_facets(CellType::hex8) && face < 0; ++f) {
    bool on = true;
    for (const int a : seam::fem::facet_nodes(CellType::hex8, f))
      on = on && ref[static_cast<std::size_t>(a) * 3 + 2] == (top ? 1.0 : -1.0);
    if (on) face = f;
  }
  seam::mesh::Region region;
  region.name = name;
  region.dim = 2;
  for (int k = 0; k < layers; ++k)
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const std::array<std::int32_t, 8> nodes{
            id(i, j, k),     id(i + 1, j, k),     id(i + 1, j + 1, k),     id(i, j + 1, k),
            id(i, j, k + 1), id(i + 1, j, k + 1), id(i + 1, j + 1, k + 1), id(i, j + 1, k + 1)};
        if (k == (top ? layers - 1 : 0)) {
          region.facet_cell.push_back(mesh.n_cells());
          region.facet_local.push_back(static_cast<std::int8_t>(face));
        }
        mesh.add_cell(CellType::hex8, nodes);
      }
  const int k = top ? layers : 0;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) region.nodes.push_back(id(i, j, k));
  return region;
}

int run_mortar_share(int argc, char** argv) {
  long slave_faces = 100'000;
  int layers = 2;
  std::vector<std::string> petsc_args;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) throw std::invalid_argument("missing value after " + a);
      return argv[++i];
    };
    if (a == "--slave-faces")
      slave_faces = std::lround(std::atof(value()));
    else if (a == "--layers")
      layers = std::atoi(value());
    else if (a == "--help" || a == "-h") {
      std::printf(
          "usage: seam-bench mortar-share [--slave-faces N] [--layers L]\n"
          "  Two hex8 blocks on [0,1]^2, n x n x L cells (n = sqrt(N), default N = 1e5, L = 2)\n"
          "  under 0.83 n x 0.83 n x L cells, tied by dual mortar (condensed) across z = 1:\n"
          "  seconds (wall, one rank) of the mortar phases of a run against one bulk assembly\n"
          "  (Neo-Hooke residual + tangent into PETSc).\n");
      return 0;
    } else
      throw std::invalid_argument("unknown option " + a);
  }
  if (slave_faces < 4 || layers < 1) throw std::invalid_argument("need N >= 4 and L >= 1");
  seam::la::Session session(argc, argv, petsc_args);
  const seam::Comm comm(PETSC_COMM_WORLD);
  const int n_slave = static_cast<int>(std::lround(std::sqrt(double(slave_faces))));
  const int n_master = std::max(1, static_cast<int>(std::lround(0.83 * n_slave)));

  seam::mesh::Mesh mesh;
  mesh.dim = 3;
  auto slave_region = add_block(mesh, n_slave, layers, 0.0, 1.0, true, "slave");
  auto master_region = add_block(mesh, n_master, layers, 1.0, 1.0, false, "master");
  mesh.check();
  const seam::problem::Discretization disc(mesh, comm);
  seam::problem::Model model;
  model.materials.resize(1);
  model.materials[0].model = seam::solid::MaterialModel::neo_hooke;
  model.materials[0].young = 1.0;
  model.materials[0].poisson = 0.3;
  model.material_names = {"block"};
  model.cell_material.assign(static_cast<std::size_t>(mesh.n_cells()), 0);

  std::vector<std::pair<std::string, double>> phases;
  const auto timed = [&](const std::string& phase, auto&& f) {
    const double t0 = wall_now();
    f();
    phases.emplace_back(phase, wall_now() - t0);
  };
  std::vector<seam::meshtying::TiedInterface> tied(1);
  auto& t = tied[0];
  t.name = "tie";
  t.slave = seam::meshtying::extract_side(mesh, slave_region);
  t.master = seam::meshtying::extract_side(mesh, master_region);
  std::vector<mortar::CandidatePair> candidates;
  timed("search", [&] {
    search::InterfaceSearch finder(t.slave.surface(), t.master.surface());
    for (const auto& p : finder.find_pairs()) candidates.push_back({p.slave, p.master});
  });
  timed("integration (D, M)", [&] {
    t.operators = mortar::assemble_mortar_operators(t.slave.facet_set(), t.master.facet_set(),
                                                    candidates, {});
  });
  timed("mesh initialization", [&] {
    t.slave.coordinates = mortar::initialize_slave_coordinates(t.operators, t.slave.coordinates,
                                                               t.master.coordinates);
  });
  std::unique_ptr<seam::problem::TyingConstraint> tying;
  timed("condensation setup (P)",
        [&] { tying = std::make_unique<seam::problem::TyingConstraint>(tied, disc, model); });
  seam::la::Vector u = disc.make_vector(), r = disc.make_vector(), rt = disc.make_vector();
  seam::la::Matrix K = disc.make_matrix(), Kt;
  // Newton iterations: the first condensation also runs the symbolic product (once per run);
  // later ones reuse its pattern. Best of the later passes.
  double bulk = 1e300, condense = 1e300;
  for (int rep = 0; rep < 3; ++rep) {
    const double t0 = wall_now();
    seam::problem::assemble(model, disc, u, 0.0, r, &K);
    const double t1 = wall_now();
    tying->condense_matrix(K, Kt);
    tying->condense_vector(r, rt);
    const double t2 = wall_now();
    bulk = std::min(bulk, t1 - t0);
    if (rep == 0)
      phases.emplace_back("first condensation", t2 - t1);
    else
      condense = std::min(condense, t2 - t1);
  }
  double setup = 0.0;
  for (const auto& [name, seconds] : phases) setup += seconds;
  if (comm.is_root()) {
    std::printf("seam-bench mortar-share: hex8 %dx%dx%d (slave) + %dx%dx%d (master), %d cells, "
                "%lld dofs,\n  %d slave / %d master faces, %zu candidate pairs, %d integrated, "
                "%d cells; wall seconds, %d rank(s)\n",
                n_slave, n_slave, layers, n_master, n_master, layers, mesh.n_cells(),
                static_cast<long long>(disc.n_global_dofs()), t.slave.n_facets(),
                t.master.n_facets(), candidates.size(), t.operators.n_pairs_integrated,
                t.operators.n_integration_cells, comm.size());
    std::printf("  once per run (D and M live in the reference configuration; the first "
                "condensation\n  includes the symbolic product T^T K T):\n");
    for (const auto& [name, seconds] : phases)
      std::printf("    %-26s %8.3f s\n", name.c_str(), seconds);
    std::printf("    %-26s %8.3f s  = %.2f bulk assemblies\n", "mortar setup total", setup,
                setup / bulk);
    std::printf("  per Newton iteration:\n    %-26s %8.3f s\n    %-26s %8.3f s  = %.2f x bulk\n",
                "bulk assembly (r + K)", bulk, "condensation (numeric)", condense, condense / bulk);
    for (const int iterations : {2, 5})
      std::printf("  run with %d Newton iterations: mortar share %.1f %% of mortar + bulk "
                  "assembly\n",
                  iterations,
                  100.0 * (setup + (iterations - 1) * condense) /
                      (setup + (iterations - 1) * condense + iterations * bulk));
  }
  return 0;
}

const seam::bench::Register registered_share{
    "mortar-share", "share of mortar work vs bulk assembly in a tied 3D run", &run_mortar_share};

} // namespace
