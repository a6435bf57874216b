#include "seam/meshtying/tied_interface.hpp"

#include "seam/common/error.hpp"
#include "seam/meshtying/tied_interface_detail.hpp"
#include "seam/search/interface_search.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>
#include <sstream>

namespace seam::meshtying {

namespace detail {

// Slave nodes (side-local) whose displacement (a fluid's velocity) is known: every component
// prescribed by some Dirichlet (velocity) condition. On facets with a modified quadratic basis (d =
// T d~) an edge node's d~_e = (d_e - a (d_v0 + d_v1)) / (1 - 2a) is known only if its two vertices
// are prescribed as well; otherwise it keeps its multiplier.
std::vector<char> bound_slave_nodes(const io::Config& config, const mesh::Mesh& mesh,
                                    const InterfaceSide& slave, mortar::Multiplier multiplier) {
  std::vector<unsigned char> prescribed(static_cast<std::size_t>(mesh.n_nodes()), 0);
  for (const auto& bc : config.boundary_conditions) {
    // A fluid's velocity conditions bind its tied slave nodes as a solid's displacements do.
    if (bc.type != io::BoundaryType::dirichlet && bc.type != io::BoundaryType::velocity) continue;
    unsigned char components = 0;
    for (int c : bc.components) components |= static_cast<unsigned char>(1U << c);
    // The region a Dirichlet condition names is the first of that name (as for the model).
    for (const auto& r : mesh.regions) {
      if (r.name != bc.region.name) continue;
      for (auto n : r.nodes) prescribed[static_cast<std::size_t>(n)] |= components;
      break;
    }
  }
  const unsigned all = (1U << mesh.dim) - 1U;
  std::vector<char> bound(slave.mesh_nodes.size(), 0);
  bool any = false;
  for (std::size_t i = 0; i < bound.size(); ++i) {
    bound[i] = prescribed[static_cast<std::size_t>(slave.mesh_nodes[i])] == all ? 1 : 0;
    any = any || bound[i] != 0;
  }
  if (!any) return {};
  for (local_index f = 0; f < slave.n_facets(); ++f) {
    const auto type = slave.types[static_cast<std::size_t>(f)];
    if (mortar::basis_modification(type, multiplier) == 0.0) continue;
    const auto* nodes = slave.nodes.data() + slave.offsets[static_cast<std::size_t>(f)];
    for (const auto& e : mortar::edge_nodes(type))
      if (!bound[nodes[e.v0]] || !bound[nodes[e.v1]]) bound[nodes[e.node]] = 0;
  }
  return bound;
}

mortar::MortarOptions mortar_options(const io::Interface& itf, const InterfaceSide& slave,
                                     const InterfaceSide& master) {
  mortar::MortarOptions options;
  options.multiplier = itf.multiplier == io::Multiplier::dual ? mortar::Multiplier::dual
                                                              : mortar::Multiplier::standard;
  if (!mortar::all_affine(slave.facet_set()) || !mortar::all_affine(master.facet_set()))
    options.pair.cell_quadrature_degree = 8;
  return options;
}

TiedInterface setup_whole(const io::Config& config, const io::Interface& itf, mesh::Mesh& mesh,
                          PhaseTimers& timers, io::InterfaceType type,
                          std::span<const std::int64_t> node_gid) {
  TiedInterface t;
  t.name = itf.name;
  t.multiplier = itf.multiplier;
  t.strategy = itf.strategy;
  t.slave = extract_side(mesh, side_region(mesh, itf.slave));
  t.master = extract_side(mesh, side_region(mesh, *itf.master));
  t.n_slave_facets = t.slave.n_facets();
  t.n_master_facets = t.master.n_facets();

  // Both sides whole on every rank: each rank finds the same nodes.
  const auto shared = shared_nodes(
      MPI_COMM_SELF, mesh, t.slave.mesh_nodes, t.master.mesh_nodes,
      [](std::int32_t) { return true; },
      [&](std::int32_t n) {
        return node_gid.empty() ? std::int64_t{n} : node_gid[static_cast<std::size_t>(n)];
      });
  if (shared.count > 0) fail_shared_nodes(itf, shared, mesh.dim);

  std::vector<mortar::CandidatePair> candidates;
  {
    ScopedTimer timer(timers, "search");
    search::InterfaceSearch finder(t.slave.surface(), t.master.surface());
    for (const auto& p : finder.find_pairs()) candidates.push_back({p.slave, p.master});
  }
  {
    ScopedTimer timer(timers, "mortar");
    const auto options = mortar_options(itf, t.slave, t.master);
    // Slave nodes with a fully prescribed displacement are treated like master nodes
    // (boundary modification of the multiplier basis, mortar/dual_basis.hpp).
    const auto bound = type == io::InterfaceType::fsi
                           ? std::vector<char>{}
                           : bound_slave_nodes(config, mesh, t.slave, options.multiplier);
    t.operators = mortar::assemble_mortar_operators(t.slave.facet_set(), t.master.facet_set(),
                                                    candidates, options, bound);
    if (t.operators.n_pairs_integrated == 0) fail_no_overlap(itf);
    // Mesh initialization: D X_S = M X_M exactly, so that the tying constraint on the
    // displacements is also one on the positions (patch test on curved interfaces,
    // conservation of angular momentum).
    const auto moved = mortar::initialize_slave_coordinates(t.operators, t.slave.coordinates,
                                                            t.master.coordinates);
    const int dim = mesh.dim;
    for (std::size_t i = 0; i < t.slave.mesh_nodes.size(); ++i) {
      double d2 = 0.0;
      for (int c = 0; c < dim; ++c) {
        const double delta = moved[i * dim + c] - t.slave.coordinates[i * dim + c];
        d2 += delta * delta;
        mesh.x[static_cast<std::size_t>(t.slave.mesh_nodes[i]) * dim + c] = moved[i * dim + c];
      }
      t.max_relocation = std::max(t.max_relocation, std::sqrt(d2));
    }
    t.slave.coordinates = moved;
  }
  t.local_slave_facets = t.n_slave_facets;
  t.local_master_ghosts = t.n_master_facets;
  t.local_pairs = t.operators.n_candidates;
  t.local_integration_cells = t.operators.n_integration_cells;
  return t;
}

void fail_shared_nodes(const io::Interface& itf, const SharedNodes& shared, int dim) {
  io::fail_at(itf.mark, "the slave side '" + itf.slave.name + "' and the master side '" +
                            itf.master->name + "' " + shared.describe(dim) +
                            "; mesh tying couples two separate meshes");
}

void fail_no_overlap(const io::Interface& itf) {
  io::fail_at(itf.mark, "the sides '" + itf.slave.name + "' and '" + itf.master->name +
                            "' do not overlap: no slave facet faces a master facet");
}

} // namespace detail

std::string SharedNodes::describe(int dim) const {
  std::ostringstream s;
  s.precision(6);
  s << "share " << count << (count == 1 ? " node" : " nodes") << " (the first: node " << first
    << " at (";
  for (int c = 0; c < dim; ++c) s << (c ? ", " : "") << x[static_cast<std::size_t>(c)];
  s << "))";
  return s.str();
}

SharedNodes shared_nodes(MPI_Comm comm, const mesh::Mesh& mesh, std::span<const std::int32_t> slave,
                         std::span<const std::int32_t> master,
                         const std::function<bool(std::int32_t)>& owned,
                         const std::function<std::int64_t(std::int32_t)>& id) {
  std::vector<std::int32_t> shared;
  std::set_intersection(slave.begin(), slave.end(), master.begin(), master.end(),
                        std::back_inserter(shared));
  SharedNodes out;
  std::int64_t first = std::numeric_limits<std::int64_t>::max();
  std::int32_t first_node = -1;
  for (const auto n : shared) {
    if (!owned(n)) continue;
    ++out.count;
    if (id(n) < first) {
      first = id(n);
      first_node = n;
    }
  }
  MPI_Allreduce(MPI_IN_PLACE, &out.count, 1, MPI_INT64_T, MPI_SUM, comm);
  MPI_Allreduce(MPI_IN_PLACE, &first, 1, MPI_INT64_T, MPI_MIN, comm);
  if (out.count == 0) return out;
  out.first = first;
  // The coordinates from the node's owner (the only rank that counted it).
  if (first_node >= 0 && id(first_node) == first)
    for (int c = 0; c < mesh.dim; ++c)
      out.x[static_cast<std::size_t>(c)] =
          mesh.x[static_cast<std::size_t>(first_node) * mesh.dim + c];
  MPI_Allreduce(MPI_IN_PLACE, out.x.data(), 3, MPI_DOUBLE, MPI_SUM, comm);
  return out;
}

const mesh::Region& side_region(const mesh::Mesh& mesh, const io::RegionRef& ref) {
  const auto* r = mesh.find_region(ref.name, mesh.dim - 1);
  if (!r)
    io::fail_at(ref.mark, "no boundary region '" + ref.name + "' of dimension " +
                              std::to_string(mesh.dim - 1) + " in the mesh");
  return *r;
}

std::vector<mortar::Triplet> projection(const mortar::MortarOperators& ops, local_index n_rows) {
  const auto n = static_cast<std::size_t>(n_rows);
  std::vector<double> diag(n, 0.0);
  for (const auto& e : ops.D) {
    if (e.row != e.col) SEAM_THROW(InternalError, "fsi: D of a dual basis is not diagonal");
    diag[static_cast<std::size_t>(e.row)] = e.value;
  }
  std::vector<std::map<local_index, double>> tilde(n), P;
  for (const auto& e : ops.M) {
    const double d = diag[static_cast<std::size_t>(e.row)];
    if (d != 0.0) tilde[static_cast<std::size_t>(e.row)][e.col] += e.value / d;
  }
  if (ops.T.empty()) {
    P = std::move(tilde);
  } else {
    P.resize(n);
    for (const auto& e : ops.T)
      for (const auto& [m, v] : tilde[static_cast<std::size_t>(e.col)])
        P[static_cast<std::size_t>(e.row)][m] += e.value * v;
  }
  std::vector<mortar::Triplet> out;
  for (std::size_t j = 0; j < n; ++j)
    for (const auto& [m, v] : P[j]) out.push_back({static_cast<local_index>(j), m, v});
  return out;
}

std::vector<TiedInterface> setup_mesh_tying(const io::Config& config, mesh::Mesh& mesh,
                                            PhaseTimers& timers, io::InterfaceType type,
                                            std::span<const std::int64_t> node_gid) {
  std::vector<TiedInterface> out;
  for (const auto& itf : config.interfaces)
    if (itf.type == type)
      out.push_back(detail::setup_whole(config, itf, mesh, timers, type, node_gid));
  return out;
}

} // namespace seam::meshtying
