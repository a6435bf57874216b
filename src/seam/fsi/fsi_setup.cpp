// The set-up of FsiSystem (fsi_system.hpp): bodies, checks of the input, P = D^-1 M of
// every interface, the condensed numbering and the maps T_c and R, the pseudo-elastic
// mesh moduli.
#include "seam/fsi/fsi_system.hpp"

#include "seam/ale/mesh_motion.hpp"
#include "seam/common/error.hpp"
#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/distribute.hpp"
#include "seam/mesh/facets.hpp"
#include "seam/mesh/partition.hpp"
#include "seam/problem/checkpoint.hpp"
#include "seam/problem/model.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <span>
#include <unordered_map>

namespace seam::fsi {

using problem::CanonicalOrder;
using problem::find_region;
using problem::to_solid;

la::Vector FsiSystem::nodal_vector(int width) const {
  std::vector<PetscInt> ghosts;
  for (auto n : ghost_nodes_)
    for (int k = 0; k < width; ++k)
      ghosts.push_back(static_cast<PetscInt>(node_slot_[n] * width + k));
  return la::Vector(comm_.get(), static_cast<PetscInt>(n_owned_nodes_ * width), ghosts);
}

std::size_t FsiSystem::nodal_local(std::int32_t n, std::size_t k, PetscInt first,
                                   std::size_t width) const {
  if (owns_node(n))
    return static_cast<std::size_t>(node_slot_[n] * static_cast<std::int64_t>(width) - first) + k;
  const auto g =
      std::lower_bound(ghost_nodes_.begin(), ghost_nodes_.end(), n) - ghost_nodes_.begin();
  return (static_cast<std::size_t>(n_owned_nodes_) + static_cast<std::size_t>(g)) * width + k;
}

la::Vector FsiSystem::make_raw_vector() const {
  return nodal_vector(static_cast<int>(raw_slots()));
}

CanonicalOrder FsiSystem::raw_order() const {
  CanonicalOrder order;
  const auto slots = raw_slots();
  order.size = (part_ ? part_->n_global_nodes : static_cast<std::int64_t>(n_nodes_)) *
               static_cast<std::int64_t>(slots);
  const auto first = make_raw_vector().owned_begin();
  for (std::size_t a = 0; a < n_raw(); ++a) {
    const auto n = raw_node(a);
    order.add(raw_id(a), static_cast<std::int32_t>(nodal_local(n, raw_slot(a), first, slots)),
              owns_node(n));
  }
  return order;
}

void FsiSystem::raw_to_vector(std::span<const double> raw, la::Vector& v) const {
  const auto slots = raw_slots();
  const auto first = v.owned_begin();
  la::Vector::LocalView view(v, true);
  auto values = view.values();
  for (std::size_t a = 0; a < n_raw(); ++a)
    values[nodal_local(raw_node(a), raw_slot(a), first, slots)] = raw[a];
}

void FsiSystem::vector_to_raw(const la::Vector& v, std::vector<double>& raw) const {
  const auto slots = raw_slots();
  const auto first = v.owned_begin();
  raw.assign(n_raw(), 0.0);
  la::Vector::LocalView view(v, false);
  const auto values = view.values();
  for (std::size_t a = 0; a < n_raw(); ++a)
    raw[a] = values[nodal_local(raw_node(a), raw_slot(a), first, slots)];
}

void FsiSystem::unknowns_from_raw(std::span<const double> raw, std::vector<double>& x) const {
  for (std::size_t a = 0; a < n_raw(); ++a)
    if (own_[a] >= 0) {
      const auto p = held_position(own_[a]);
      if (p >= 0) x[static_cast<std::size_t>(p)] = raw[a];
    }
}

std::vector<double> FsiSystem::share(std::span<const double> contributions, int width) const {
  // A node-laid-out vector with the other nodes held here as ghosts: the contributions are
  // summed on the owners (in rank order), then sent back to every rank holding the node.
  const auto n_nodes = static_cast<std::int32_t>(n_nodes_);
  const auto w = static_cast<PetscInt>(width);
  std::vector<PetscInt> rows;
  const auto& ghost_nodes = ghost_nodes_;
  auto v = nodal_vector(width);
  for (std::int32_t n = 0; n < n_nodes; ++n)
    for (PetscInt k = 0; k < w; ++k) rows.push_back(static_cast<PetscInt>(node_slot_[n]) * w + k);
  v.add_values(rows, contributions);
  v.assemble();
  v.update_ghosts();
  std::vector<double> out(contributions.size(), 0.0);
  la::Vector::LocalView view(v, false);
  const auto values = view.values();
  const auto first = v.owned_begin();
  for (std::int32_t n = 0; n < n_nodes; ++n)
    if (owns_node(n))
      for (PetscInt k = 0; k < w; ++k)
        out[static_cast<std::size_t>(n * w + k)] =
            values[static_cast<std::size_t>(node_slot_[n] * w + k - first)];
  const auto n_owned = static_cast<std::size_t>(n_owned_nodes_ * w);
  for (std::size_t g = 0; g < ghost_nodes.size(); ++g)
    for (PetscInt k = 0; k < w; ++k)
      out[static_cast<std::size_t>(ghost_nodes[g] * w + k)] = values[n_owned + g * w + k];
  return out;
}

FsiSystem::FsiSystem(const io::Config& config, const mesh::Mesh& mesh,
                     const std::vector<meshtying::TiedInterface>& interfaces, Comm comm,
                     const mesh::DistributedMesh* part)
    : config_(&config), mesh_(&mesh), part_(part), comm_(comm), dim_(mesh.dim) {
  const int dim = dim_;
  // Distributed: the structure nodes the couplings reach that this rank does not hold follow
  // the mesh's nodes, in the order first met.
  std::unordered_map<std::int64_t, std::int32_t> node_of; // global number -> node
  std::vector<std::int64_t> extra_index;                  // their global numbers
  if (part) {
    for (std::int32_t n = 0; n < mesh.n_nodes(); ++n) node_of.emplace(part->node_index[n], n);
    for (const auto& t : interfaces)
      for (const auto& e : t.projection) {
        const auto g = t.master_index[static_cast<std::size_t>(e.col)];
        const auto next = static_cast<std::int32_t>(mesh.n_nodes() + extra_index.size());
        if (!node_of.emplace(g, next).second) continue;
        extra_index.push_back(g);
        for (int i = 0; i < dim; ++i)
          extra_x_.push_back(t.master.coordinates[static_cast<std::size_t>(e.col) * dim + i]);
      }
  }
  n_nodes_ = static_cast<std::size_t>(mesh.n_nodes()) + extra_index.size();
  base_f_ = n_nodes_ * dim;
  base_m_ = base_f_ + n_nodes_ * (dim + 1);
  plane_ = dim == 3                                ? solid::PlaneMode::none
           : config.plane == io::PlaneMode::stress ? solid::PlaneMode::plane_stress
                                                   : solid::PlaneMode::plane_strain;

  // The partition: a distributed mesh's; on the replicated mesh as a fluid run's there
  // (FluidLayout): METIS parts of the cells, each node owned by the lowest part among its cells.
  const int size = comm.size(), rank = comm.rank();
  std::vector<int> cell_part;
  mesh::NodeNumbering numbering;
  if (part) {
    cell_part = part->cell_owner;
    node_owner_ = part->node_owner;
    node_slot_ = part->node_index;
    n_owned_nodes_ = part->node_offsets[rank + 1] - part->node_offsets[rank];
    for (auto g : extra_index) {
      node_slot_.push_back(g);
      node_owner_.push_back(static_cast<int>(
          std::upper_bound(part->node_offsets.begin(), part->node_offsets.end(), g) -
          part->node_offsets.begin() - 1));
    }
  } else {
    if (comm.is_root()) cell_part = mesh::partition_cells(mesh, size);
    comm.broadcast(cell_part);
    numbering = mesh::number_nodes(mesh, cell_part, size);
    node_owner_ = numbering.owner;
    node_slot_ = numbering.new_index;
    n_owned_nodes_ = numbering.offsets[rank + 1] - numbering.offsets[rank];
  }
  std::vector<char> held_node(n_nodes_, 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    if (cell_part[c] == rank) {
      local_cells_.push_back(c);
      for (auto n : mesh.cell(c)) held_node[n] = 1;
    }
  for (std::size_t n = 0; n < n_nodes_; ++n) {
    if (held_node[n]) held_nodes_.push_back(static_cast<std::int32_t>(n));
    if (!owns_node(static_cast<std::int32_t>(n)))
      ghost_nodes_.push_back(static_cast<std::int32_t>(n));
  }
  // The ids of the nodes after the mesh's, from their owners.
  if (part) {
    node_gid_ = part->node_gid;
    std::vector<double> ids(n_nodes_, 0.0);
    for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
      if (owns_node(n)) ids[static_cast<std::size_t>(n)] = static_cast<double>(node_gid_[n] + 1);
    ids = share(ids, 1);
    for (std::size_t n = node_gid_.size(); n < n_nodes_; ++n)
      node_gid_.push_back(static_cast<std::int64_t>(ids[n]) - 1);
  }
  const auto gid = [&](std::int32_t n) { return node_gid(n); };
  // "node G at (x, y[, z])" of the node with id `id` (found by its owner; collective).
  const auto node_text = [&](double id) {
    std::array<double, 3> at{};
    for (std::size_t n = 0; n < n_nodes_; ++n)
      if (owns_node(static_cast<std::int32_t>(n)) &&
          static_cast<double>(gid(static_cast<std::int32_t>(n))) == id)
        for (int i = 0; i < dim; ++i) at[i] = node_x(n)[i];
    comm.sum_in_place(at);
    std::string text = "(";
    for (int i = 0; i < dim; ++i) text += (i ? ", " : "") + std::to_string(at[i]);
    return "node " + std::to_string(static_cast<std::int64_t>(id)) + " at " + text + ")";
  };
  // The lowest id of the owned nodes among `nodes` with bad(n), over all ranks (inf: none).
  const auto first_bad = [&](const std::vector<std::int32_t>& nodes, const auto& bad) {
    double first = std::numeric_limits<double>::infinity();
    for (auto n : nodes)
      if (owns_node(n) && bad(n)) first = std::min(first, static_cast<double>(gid(n)));
    return comm.min(first);
  };

  // Bodies: a fluid or a solid material per cell.
  std::map<std::string, int> fluid_index, solid_index;
  for (const auto& [name, m] : config.materials) {
    if (m.is_fluid()) {
      fluid_index[name] = static_cast<int>(fluids_.size());
      fluids_.push_back({m.density, m.viscosity});
    } else {
      solid_index[name] = static_cast<int>(solids_.size());
      solids_.push_back({to_solid(m.model), m.young, m.poisson, m.density});
    }
  }
  cell_fluid_.assign(mesh.n_cells(), -1);
  cell_solid_.assign(mesh.n_cells(), -1);
  std::vector<int> cell_body(mesh.n_cells(), -1);
  for (std::size_t b = 0; b < config.bodies.size(); ++b) {
    const auto& body = config.bodies[b];
    const bool is_fluid = config.materials.at(body.material).is_fluid();
    if (!is_fluid && body.mesh_motion)
      io::fail_at(body.mark, "body '" + body.region.name +
                                 "' is a solid: mesh_motion applies only to fluid bodies");
    if (is_fluid && body.mesh_motion &&
        body.mesh_motion->model != io::MeshMotionModel::pseudo_elastic)
      io::fail_at(body.mesh_motion->mark,
                  "in a run with an 'fsi' interface the fluid mesh follows the structure: "
                  "mesh_motion must be 'pseudo_elastic'");
    int bad_type = -1; // a cell type no fluid uses, on any rank (collective)
    for (auto c : find_region(mesh, body.region, {dim}, "a body").cells) {
      const auto type = mesh.cell_type[c];
      if (is_fluid && !fluid::is_taylor_hood(type) && !fluid::is_stabilized(type))
        bad_type = std::max(bad_type, static_cast<int>(type));
      if (is_fluid && !fluid::is_taylor_hood(type)) taylor_hood_ = false;
      cell_fluid_[c] = is_fluid ? fluid_index.at(body.material) : -1;
      cell_solid_[c] = is_fluid ? -1 : solid_index.at(body.material);
      cell_body[c] = static_cast<int>(b);
    }
    bad_type = comm.max(bad_type);
    if (bad_type >= 0)
      io::fail_at(body.mark, "fluid body '" + body.region.name + "' has " +
                                 std::string(fem::name(static_cast<fem::CellType>(bad_type))) +
                                 " cells; seam's fluids use tri6, quad9, tet10, hex27 "
                                 "(Taylor-Hood) or tri3, quad4, tet4, hex8 (stabilized)");
  }
  taylor_hood_ = !comm.any(!taylor_hood_);
  std::int64_t uncovered = 0;
  for (auto c : local_cells_) uncovered += cell_body[c] < 0 ? 1 : 0;
  uncovered = comm.sum(uncovered);
  if (uncovered > 0)
    io::fail_at(config.bodies.front().mark,
                std::to_string(uncovered) + " of " +
                    std::to_string(comm.sum(static_cast<std::int64_t>(local_cells_.size()))) +
                    " cells belong to no body (every cell needs a material)");

  solid_node_.assign(n_nodes_, 0);
  fluid_node_.assign(n_nodes_, 0);
  pressure_node_.assign(n_nodes_, 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const auto nodes = mesh.cell(c);
    const int nv = fem::n_vertices(mesh.cell_type[c]);
    for (std::size_t a = 0; a < nodes.size(); ++a) {
      if (cell_fluid_[c] >= 0) {
        fluid_node_[nodes[a]] = 1;
        if (static_cast<int>(a) < nv) pressure_node_[nodes[a]] = 1;
      } else {
        solid_node_[nodes[a]] = 1;
      }
    }
  }
  for (std::size_t n = static_cast<std::size_t>(mesh.n_nodes()); n < n_nodes_; ++n)
    solid_node_[n] = 1;
  // A node of a fluid and a solid cell: its owner holds every cell around it (collective).
  std::vector<std::int32_t> all_nodes(n_nodes_);
  for (std::size_t n = 0; n < n_nodes_; ++n) all_nodes[n] = static_cast<std::int32_t>(n);
  const double shared =
      first_bad(all_nodes, [&](std::int32_t n) { return solid_node_[n] && fluid_node_[n]; });
  if (std::isfinite(shared))
    io::fail_at(config.bodies.front().mark,
                node_text(shared) +
                    " belongs to a fluid and a solid cell; the fluid and the structure are "
                    "separate meshes (own nodes) joined by an 'fsi' interface");

  // The fsi interfaces: sides of the right kind, P = D^-1 M.
  std::size_t k = 0;
  for (const auto& itf : config.interfaces) {
    if (itf.type != io::InterfaceType::fsi)
      io::fail_at(itf.mark, "interface '" + itf.name + "' of type '" +
                                std::string(io::to_string(itf.type)) +
                                "' in a run with an 'fsi' interface: a fluid-structure run "
                                "holds 'fsi' interfaces only in this version of seam");
    const auto& t = interfaces.at(k++);
    // Each side's nodes checked by their owners (who hold every facet around them).
    const auto check_side = [&](const io::RegionRef& side, const std::vector<char>& ok,
                                const char* key, const char* what) {
      const double bad = first_bad(meshtying::side_region(mesh, side).nodes,
                                   [&](std::int32_t n) { return !ok[n]; });
      if (std::isfinite(bad))
        io::fail_at(itf.mark, "interface '" + itf.name + "': its '" + key + "' group '" +
                                  side.name + "' has " + node_text(bad) + " that is not on a " +
                                  what +
                                  " body; 'fluid' names a boundary group of the fluid, "
                                  "'structure' one of the structure");
    };
    check_side(itf.slave, fluid_node_, "fluid", "fluid");
    check_side(*itf.master, solid_node_, "structure", "solid");
    const auto& ops = t.operators;
    FsiCoupling cp;
    cp.name = t.name;
    cp.fluid_nodes = t.slave.mesh_nodes;
    const std::size_t ns = cp.fluid_nodes.size();
    std::vector<double> diag(ns, 0.0);
    for (const auto& e : ops.D) diag[e.row] = e.value;
    double d_max = 0.0;
    for (std::size_t j = 0; j < ns; ++j)
      if (owns_node(cp.fluid_nodes[j])) {
        d_max = std::max(d_max, std::abs(diag[j]));
        cp.d_total += diag[j];
      }
    d_max = comm.max(d_max);
    cp.d_total = comm.sum(cp.d_total);
    std::vector<char> faces(n_nodes_, 1);
    for (std::size_t j = 0; j < ns; ++j) faces[cp.fluid_nodes[j]] = diag[j] > 1e-12 * d_max;
    const double lone = first_bad(cp.fluid_nodes, [&](std::int32_t n) { return !faces[n]; });
    if (std::isfinite(lone))
      io::fail_at(itf.mark, "interface '" + itf.name + "': fluid " + node_text(lone) +
                                " faces no structure facet (the fluid group must lie on the "
                                "structure group)");
    // P = D^-1 M (with a modified quadratic basis T D^-1 M, tying_constraint.cpp): from the
    // nodes' owners on a distributed mesh; each row's structure nodes in the order of their ids.
    const auto P = part ? t.projection : meshtying::projection(ops, static_cast<local_index>(ns));
    std::vector<std::vector<std::pair<std::int32_t, double>>> rows(ns);
    for (const auto& e : P)
      rows[static_cast<std::size_t>(e.row)].emplace_back(
          part ? node_of.at(t.master_index[static_cast<std::size_t>(e.col)])
               : t.master.mesh_nodes[static_cast<std::size_t>(e.col)],
          e.value);
    for (auto& row : rows) {
      std::sort(row.begin(), row.end(),
                [&](const auto& p, const auto& q) { return gid(p.first) < gid(q.first); });
      for (const auto& [m, v] : row) {
        cp.structure_nodes.push_back(m);
        cp.weights.push_back(v);
      }
      cp.offsets.push_back(static_cast<std::int64_t>(cp.structure_nodes.size()));
    }
    cp.d_diagonal = diag;
    couplings_.push_back(std::move(cp));
  }
  // Per mesh node: (coupling, side-local index) of a fluid interface node; the first wins.
  std::vector<std::pair<int, std::int32_t>> on_interface(n_nodes_, {-1, -1});
  for (std::size_t c = 0; c < couplings_.size(); ++c)
    for (std::size_t j = 0; j < couplings_[c].fluid_nodes.size(); ++j) {
      auto& slot = on_interface[couplings_[c].fluid_nodes[j]];
      if (slot.first < 0) slot = {static_cast<int>(c), static_cast<std::int32_t>(j)};
    }

  // Conditions: the structure's displacement, the fluid's velocity.
  prescribed_.assign(n_raw(), -1);
  for (const auto& bc : config.boundary_conditions) {
    const auto& region = find_region(mesh, bc.region, {0, 1, 2, 3}, "a boundary condition");
    // Over the owned nodes of the region, summed over ranks.
    std::int64_t n_fluid = 0, n_region = 0;
    for (auto n : region.nodes)
      if (owns_node(n)) {
        ++n_region;
        n_fluid += fluid_node_[n] != 0 ? 1 : 0;
      }
    n_fluid = comm.sum(n_fluid);
    n_region = comm.sum(n_region);
    switch (bc.type) {
    case io::BoundaryType::dirichlet:
      if (n_fluid > 0)
        io::fail_at(bc.mark, "type 'dirichlet' prescribes a solid's displacement, but region '" +
                                 bc.region.name +
                                 "' belongs to a fluid body; prescribe the fluid's velocity "
                                 "with type 'velocity'");
      break;
    case io::BoundaryType::velocity:
      if (n_fluid < n_region)
        io::fail_at(bc.mark, "type 'velocity' prescribes a fluid's velocity, but region '" +
                                 bc.region.name +
                                 "' belongs to a solid body (a solid's motion is prescribed "
                                 "with type 'dirichlet')");
      break;
    default:
      io::fail_at(bc.mark, "type '" + std::string(io::to_string(bc.type)) +
                               "' is not available yet in a run with an 'fsi' interface (only "
                               "'dirichlet' on the structure and 'velocity' on the fluid)");
    }
    for (std::size_t q = 0; q < bc.components.size(); ++q) {
      const int expr = static_cast<int>(values_.size());
      values_.push_back(bc.value[q]);
      for (auto n : region.nodes) {
        if (bc.type == io::BoundaryType::dirichlet) {
          prescribed_[d_dof(n, bc.components[q])] = expr;
        } else if (on_interface[n].first < 0) {
          // On the interface the coupling wins (CONTRACT.md): the structure's motion.
          prescribed_[f_dof(n, bc.components[q])] = expr;
        }
      }
    }
  }

  // The prescribed components of the nodes after the mesh's, from their owners.
  if (part) {
    std::vector<double> expr(n_nodes_ * static_cast<std::size_t>(dim), 0.0);
    for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
      if (owns_node(n))
        for (int i = 0; i < dim; ++i)
          expr[static_cast<std::size_t>(n) * dim + i] = prescribed_[d_dof(n, i)] + 1;
    expr = share(expr, dim);
    for (auto n = static_cast<std::int32_t>(mesh.n_nodes());
         n < static_cast<std::int32_t>(n_nodes_); ++n)
      for (int i = 0; i < dim; ++i)
        prescribed_[d_dof(n, i)] =
            static_cast<int>(expr[static_cast<std::size_t>(n) * dim + i]) - 1;
  }

  // Fluid boundary nodes off the interfaces hold their mesh position: in every component, but
  // on the facets of a slip wall (a `velocity` condition on some of the components) only in the
  // prescribed ones, so that the mesh slides along the wall as the flow does.
  std::map<std::pair<std::int32_t, int>, unsigned> slip; // facet (cell, local) -> components
  for (const auto& bc : config.boundary_conditions) {
    if (bc.type != io::BoundaryType::velocity || static_cast<int>(bc.components.size()) == dim)
      continue;
    const auto& region = find_region(mesh, bc.region, {0, 1, 2, 3}, "a boundary condition");
    unsigned mask = 0;
    for (auto i : bc.components) mask |= 1u << i;
    for (std::int32_t f = 0; f < region.n_facets(); ++f)
      slip[{region.facet_cell[f], region.facet_local[f]}] |= mask;
  }
  const unsigned all = (1u << dim) - 1;
  std::vector<unsigned> held(n_nodes_, 0); // per node: the components its mesh holds
  // On a distributed mesh the facets of the owned cells only (the ghost layer holds every
  // neighbour of an owned cell, so they are exterior in the mesh; the ghost layer's edge is
  // not), the components of each node then gathered from all ranks.
  const auto exterior = mesh::exterior_facets(mesh);
  for (std::int32_t f = 0; f < exterior.size(); ++f) {
    const auto c = exterior.cell[f];
    if (cell_fluid_[c] < 0 || (part && cell_part[c] != rank)) continue;
    const auto it = slip.find({c, exterior.local[f]});
    const unsigned mask = it == slip.end() ? all : it->second;
    const auto nodes = mesh.cell(c);
    for (int a : fem::facet_nodes(mesh.cell_type[c], exterior.local[f])) held[nodes[a]] |= mask;
  }
  if (part) {
    std::vector<double> bits(n_nodes_ * static_cast<std::size_t>(dim), 0.0);
    for (std::size_t n = 0; n < n_nodes_; ++n)
      for (int i = 0; i < dim; ++i) bits[n * dim + i] = held[n] >> i & 1u;
    bits = share(bits, dim);
    for (std::size_t n = 0; n < n_nodes_; ++n)
      for (int i = 0; i < dim; ++i)
        if (bits[n * dim + i] > 0.0) held[n] |= 1u << i;
  }

  // Condensed numbering and the maps T_c (columns) and R (rows), raw dof by raw dof: the
  // unknowns in the order of the ranks (each rank's nodes in numbering order: structure, then
  // fluid, then mesh).
  const auto structure_unknown = [&](std::size_t n, int i) {
    return solid_node_[n] && prescribed_[d_dof(static_cast<std::int32_t>(n), i)] < 0;
  };
  const auto fluid_unknown = [&](std::size_t n, int c) {
    if (!fluid_node_[n]) return false;
    if (c == dim) return pressure_node_[n] != 0;
    return on_interface[n].first < 0 && prescribed_[f_dof(static_cast<std::int32_t>(n), c)] < 0;
  };
  const auto mesh_unknown = [&](std::size_t n, int i) {
    return fluid_node_[n] && on_interface[n].first < 0 && !(held[n] >> i & 1u);
  };
  std::vector<PetscInt> own(n_raw(), -1);
  if (part) {
    // Each rank numbers the unknowns of its nodes (in global node order) after those of the
    // lower ranks (one MPI_Exscan); the numbers of the other nodes held come from their
    // owners (one exchange).
    std::vector<std::int32_t> owned;
    for (std::int32_t n = 0; n < static_cast<std::int32_t>(n_nodes_); ++n)
      if (owns_node(n)) owned.push_back(n);
    std::sort(owned.begin(), owned.end(),
              [&](std::int32_t p, std::int32_t q) { return node_slot_[p] < node_slot_[q]; });
    long long count = 0, before = 0;
    for (auto n : owned) {
      for (int i = 0; i < dim; ++i) count += structure_unknown(n, i) + mesh_unknown(n, i);
      for (int c = 0; c <= dim; ++c) count += fluid_unknown(n, c);
    }
    MPI_Exscan(&count, &before, 1, MPI_LONG_LONG, MPI_SUM, comm.get());
    if (rank == 0) before = 0;
    first_owned_ = static_cast<PetscInt>(before);
    n_owned_ = static_cast<PetscInt>(count);
    n_unknowns_ = static_cast<PetscInt>(comm.sum(static_cast<std::int64_t>(count)));
    PetscInt next = first_owned_;
    for (auto n : owned)
      for (int i = 0; i < dim; ++i)
        if (structure_unknown(n, i)) {
          structure_raw_.push_back(d_dof(n, i));
          own[d_dof(n, i)] = next++;
        }
    end_structure_ = next;
    for (auto n : owned)
      for (int c = 0; c <= dim; ++c)
        if (fluid_unknown(n, c)) own[f_dof(n, c)] = next++;
    end_fluid_ = next;
    for (auto n : owned)
      for (int i = 0; i < dim; ++i)
        if (mesh_unknown(n, i)) own[m_dof(n, i)] = next++;
    const auto slots = raw_slots();
    std::vector<double> numbers(n_nodes_ * slots, 0.0);
    for (std::size_t a = 0; a < n_raw(); ++a)
      if (own[a] >= 0) numbers[raw_node(a) * slots + raw_slot(a)] = static_cast<double>(own[a] + 1);
    numbers = share(numbers, static_cast<int>(slots));
    for (std::size_t a = 0; a < n_raw(); ++a)
      own[a] = static_cast<PetscInt>(numbers[raw_node(a) * slots + raw_slot(a)]) - 1;
  } else {
    PetscInt next = 0;
    for (int r = 0; r < size; ++r) {
      const auto nodes =
          std::span(numbering.old_index)
              .subspan(static_cast<std::size_t>(numbering.offsets[r]),
                       static_cast<std::size_t>(numbering.offsets[r + 1] - numbering.offsets[r]));
      if (r == rank) first_owned_ = next;
      for (auto n : nodes)
        for (int i = 0; i < dim; ++i)
          if (structure_unknown(n, i)) {
            if (r == rank) structure_raw_.push_back(d_dof(n, i));
            own[d_dof(n, i)] = next++;
          }
      if (r == rank) end_structure_ = next;
      for (auto n : nodes)
        for (int c = 0; c <= dim; ++c)
          if (fluid_unknown(n, c)) own[f_dof(n, c)] = next++;
      if (r == rank) end_fluid_ = next;
      for (auto n : nodes)
        for (int i = 0; i < dim; ++i)
          if (mesh_unknown(n, i)) own[m_dof(n, i)] = next++;
      if (r == rank) n_owned_ = next - first_owned_;
    }
    n_unknowns_ = next;
  }

  own_ = own;
  // The structure dofs P maps an interface node to, component i.
  const auto for_master = [&](std::int32_t n, const auto& f) {
    const auto& cp = couplings_[on_interface[n].first];
    const auto j = on_interface[n].second;
    for (auto q = cp.offsets[j]; q < cp.offsets[j + 1]; ++q)
      f(cp.structure_nodes[q], cp.weights[q]);
  };
  velocity_row_.assign(n_raw(), 0);
  for (std::size_t a = 0; a < n_raw(); ++a) {
    if (own[a] >= 0) {
      columns_.add(own[a], 1.0);
      rows_.add(own[a], 1.0);
    } else if (a >= base_f_ && a < base_m_) {
      const auto n = static_cast<std::int32_t>((a - base_f_) / (dim + 1));
      const int i = static_cast<int>((a - base_f_) % (dim + 1));
      // The interface velocity's momentum row moves to the structure by P^T; its value is
      // u_G = P v(d) (column_scale: dv/dd; steady: the structure rests, u_G = 0).
      if (i < dim && fluid_node_[n] && on_interface[n].first >= 0) {
        velocity_row_[a] = 1;
        for_master(n, [&](std::int32_t s, double w) {
          if (own[d_dof(s, i)] >= 0) {
            rows_.add(own[d_dof(s, i)], w);
            columns_.add(own[d_dof(s, i)], w);
          }
        });
      }
    } else if (a >= base_m_) {
      const auto n = static_cast<std::int32_t>((a - base_m_) / dim);
      const int i = static_cast<int>((a - base_m_) % dim);
      if (fluid_node_[n] && on_interface[n].first >= 0)
        for_master(n, [&](std::int32_t s, double w) {
          if (own[d_dof(s, i)] >= 0) columns_.add(own[d_dof(s, i)], w);
        });
    }
    columns_.append_row();
    rows_.append_row();
  }

  // The pseudo-elastic mesh: E = (V_min / V_e)^chi over the fluid cells (Stein et al.; on a
  // distributed mesh V_min over the owned cells of all ranks).
  std::vector<std::int32_t> fluid_cells;
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    if (cell_fluid_[c] >= 0) fluid_cells.push_back(c);
  double smallest = 0.0;
  if (part) {
    smallest = std::numeric_limits<double>::infinity();
    for (auto c : local_cells_)
      if (cell_fluid_[c] >= 0) smallest = std::min(smallest, mesh::cell_volume(mesh, c));
    smallest = comm.min(smallest);
  }
  const auto ratio = ale::jacobian_stiffening(mesh, fluid_cells, 1.0, smallest);
  mesh_young_.assign(mesh.n_cells(), 0.0);
  for (std::size_t q = 0; q < fluid_cells.size(); ++q) {
    const auto& body = config.bodies[cell_body[fluid_cells[q]]];
    double power = 1.0;
    if (body.mesh_motion)
      power = body.mesh_motion->stiffening == io::Stiffening::jacobian
                  ? body.mesh_motion->stiffening_power
                  : 0.0;
    mesh_young_[fluid_cells[q]] = std::pow(ratio[q], power);
  }

  // The unknowns the cells of this rank need.
  const auto scan_raw = [&](std::size_t a) {
    for (auto q = columns_.offsets[a]; q < columns_.offsets[a + 1]; ++q)
      held_.push_back(columns_.index[q]);
  };
  for (auto n : held_nodes_) {
    const auto& scan = scan_raw;
    for (int i = 0; i < dim; ++i) {
      scan(d_dof(n, i));
      scan(m_dof(n, i));
    }
    for (int c = 0; c <= dim; ++c) scan(f_dof(n, c));
  }
  // And those of the couplings' nodes this rank holds: the structure nodes P reaches (also
  // beyond the mesh's nodes) have their displacement, velocity and acceleration here (the
  // fluid's interface velocity and mesh displacement follow them).
  for (const auto& cp : couplings_) {
    for (auto n : cp.fluid_nodes)
      for (int i = 0; i < dim; ++i) {
        scan_raw(f_dof(n, i));
        scan_raw(m_dof(n, i));
      }
    for (auto n : cp.structure_nodes)
      for (int i = 0; i < dim; ++i) scan_raw(d_dof(n, i));
  }
  std::sort(held_.begin(), held_.end());
  held_.erase(std::unique(held_.begin(), held_.end()), held_.end());
  // The owned unknowns, a contiguous block of held_ (the owned nodes are nodes of owned cells).
  if (n_owned_ > 0 &&
      (held_position(first_owned_) < 0 ||
       held_position(first_owned_ + n_owned_ - 1) != held_position(first_owned_) + n_owned_ - 1))
    SEAM_THROW(InternalError, "fsi: the owned unknowns are not all held");
  held_column_.resize(columns_.index.size());
  for (std::size_t q = 0; q < columns_.index.size(); ++q)
    held_column_[q] = held_position(columns_.index[q]);
}

} // namespace seam::fsi
