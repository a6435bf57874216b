#include "seam/app/run.hpp"

#include "seam/common/collective.hpp"
#include "seam/common/error.hpp"
#include "seam/common/mpi.hpp"
#include "seam/flow/fluid_model.hpp"
#include "seam/flow/fluid_solver.hpp"
#include "seam/fsi/fsi_solver.hpp"
#include "seam/io/config.hpp"
#include "seam/la/petsc.hpp"
#include "seam/mesh/distribute.hpp"
#include "seam/mesh/distribute_file.hpp"
#include "seam/mesh/gmsh_reader.hpp"
#include "seam/mesh/msh_chunk.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/parallel/memory_trace.hpp"
#include "seam/problem/checkpoint.hpp"
#include "seam/problem/contact_constraint.hpp"
#include "seam/problem/contact_search.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/dynamic_solver.hpp"
#include "seam/problem/model.hpp"
#include "seam/problem/newton.hpp"
#include "seam/problem/output.hpp"
#include "seam/problem/saddle_point.hpp"
#include "seam/problem/static_solver.hpp"

#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <map>
#include <optional>
#include <system_error>

namespace seam::app {

using flow::has_fluid;
using flow::run_fluid;
using fsi::has_fsi;
using fsi::run_fsi;
using problem::Checkpoints;
using problem::ContactConstraint;
using problem::Discretization;
using problem::identify;
using problem::master_held_in_part;
using problem::MeshIdentity;
using problem::Output;
using problem::restart_output_directory;
using problem::SaddlePoint;
using problem::slave_held_in_part;
using problem::TyingConstraint;

const char* version() {
  return "0.1.0";
}

namespace {

/// The mark that names the input file and key of the mesh in messages.
io::Mark mesh_mark(const io::Config& config) {
  io::Mark mark = config.mesh.mark;
  mark.key_path = config.mesh.geo.empty() ? "mesh.file" : "mesh.geo";
  return mark;
}

/// Rank 0 reads (or meshes) the mesh; the other ranks get an empty one. `meshed`: a .msh file
/// written from the geometry file already, read instead of meshing again.
mesh::Mesh read_on_root(const io::Config& config, const Comm& comm,
                        const std::filesystem::path& meshed = {}) {
  mesh::Mesh m;
  on_root_collectively(comm, [&] {
    mesh::ReadOptions opts;
    opts.dim = config.dimension;
    // The reader names the mesh file; the prefix names the input file and key that chose it.
    try {
      if (!meshed.empty()) {
        m = mesh::read_mesh(meshed, opts);
      } else if (!config.mesh.geo.empty()) {
        opts.size = config.mesh.size;
        opts.order = config.mesh.order;
        opts.serendipity = config.mesh.serendipity;
        m = mesh::read_mesh(config.mesh.geo, opts);
      } else {
        m = mesh::read_mesh(config.mesh.file, opts);
      }
    } catch (const InputError& e) {
      io::fail_at(mesh_mark(config), e.what());
    }
  });
  return m;
}

/// The chunked reader (mesh/distribute_file.hpp) on a .msh file, or nothing if it leaves the
/// file to Gmsh (said once on rank 0). SEAM_MESH_READER=rank0 forces the rank-0 path (used by
/// bench/memory_per_rank.py to compare both).
std::optional<mesh::DistributedMesh> read_chunked(const io::Config& config, const Comm& comm,
                                                  const std::filesystem::path& file,
                                                  std::span<const std::string> sides, bool quiet) {
  const char* reader = std::getenv("SEAM_MESH_READER");
  if (reader != nullptr && std::string_view(reader) == "rank0") return std::nullopt;
  try {
    return mesh::distribute_file(file, comm.get(), sides, config.dimension);
  } catch (const mesh::MshUnsupported& e) {
    if (comm.is_root() && !quiet)
      std::printf("seam: mesh '%s' is read on rank 0 through Gmsh (%s)\n", file.string().c_str(),
                  e.what());
  } catch (const InputError& e) {
    // A mesh made from a geometry file is named by that file, as read_mesh names it.
    std::string message = e.what();
    const std::string made = file.string();
    if (!config.mesh.geo.empty())
      for (auto at = message.find(made); at != std::string::npos; at = message.find(made))
        message.replace(at, made.size(), config.mesh.geo.string());
    io::fail_at(mesh_mark(config), message);
  }
  return std::nullopt;
}

/// This rank's part of the mesh: its cells, one ghost layer and the cells of the interface
/// sides (mesh/distribute.hpp). A .msh file is read in chunks by every rank and partitioned in
/// parallel, so that no rank ever holds the whole mesh; a geometry file is meshed by Gmsh on
/// rank 0 into `scratch` (binary MSH 4.1, removed after reading; the Gmsh model is freed
/// first) and then read the same way. Files the chunked reader leaves to Gmsh are read whole
/// on rank 0, which sends each rank its part and frees the whole mesh.
/// `identity` gets the whole mesh's (checkpoint.hpp). An empty `scratch` (`seam check`, which
/// has no output directory): a geometry file is meshed in memory on rank 0, which sends the parts.
mesh::DistributedMesh load_distributed_mesh(const io::Config& config, const Comm& comm,
                                            MeshIdentity& identity,
                                            const std::filesystem::path& scratch, bool quiet) {
  // Sides held whole on every rank: those of contact. The sides of mesh tying (condensed and
  // saddle point) and of the fsi couplings are set up distributed
  // (meshtying::distributed_tying): each rank needs only its own cells' facets and the master
  // facets ghosted to it; so are the master side of
  // two-body contact held in part (master_held_in_part) and the slave side held in part
  // (slave_held_in_part, a self-contact surface too; with the independent distribution the
  // facets a rank needs beyond its own and ghost cells reach it as facets,
  // ContactConstraint::hold_slave_part).
  std::vector<std::string> sides;
  for (const auto& itf : config.interfaces) {
    if (meshtying::distributed_tying(itf)) continue;
    const bool slave_part = slave_held_in_part(itf, config);
    if (!slave_part) sides.push_back(itf.slave.name);
    if (itf.master && !master_held_in_part(itf, config)) sides.push_back(itf.master->name);
    if (!slave_part)
      for (const auto& group : itf.surface) sides.push_back(group.name);
  }
  std::filesystem::path file = config.mesh.file;
  const bool generated = !config.mesh.geo.empty();
  const bool in_memory = generated && scratch.empty();
  if (generated && !in_memory) {
    file = scratch / "mesh_generated.msh";
    on_root_collectively(comm, [&] {
      mesh::ReadOptions opts;
      opts.dim = config.dimension;
      opts.size = config.mesh.size;
      opts.order = config.mesh.order;
      opts.serendipity = config.mesh.serendipity;
      try {
        mesh::mesh_to_msh(config.mesh.geo, opts, file);
      } catch (const InputError& e) {
        io::fail_at(mesh_mark(config), e.what());
      }
    });
  }
  auto part = in_memory ? std::nullopt : read_chunked(config, comm, file, sides, quiet);
  if (part) {
    identity = identify(*part, comm);
  } else {
    auto whole =
        read_on_root(config, comm, generated && !in_memory ? file : std::filesystem::path());
    if (comm.is_root()) identity = identify(whole);
    comm.broadcast_value(identity);
    part = mesh::distribute_mesh(whole, comm.get(), sides);
  }
  if (generated && !in_memory && comm.is_root()) {
    std::error_code ec;
    std::filesystem::remove(file, ec);
  }
  return std::move(*part);
}

std::filesystem::path output_directory(const RunOptions& options) {
  if (!options.output_dir.empty()) return options.output_dir;
  // A restart continues the files of the run that wrote the checkpoint.
  if (!options.restart.empty()) return restart_output_directory(options.restart);
  return std::filesystem::path(std::filesystem::path(options.input).stem().string() + "_out");
}

// Only rank 0 writes files; creating the directory here, with the error shared by all ranks,
// keeps an unusable directory from stopping rank 0 while the others wait in a collective.
void make_output_directory(const std::filesystem::path& dir, const Comm& comm) {
  on_root_collectively(comm, [&] {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec)
      SEAM_THROW(InputError, "output directory '", dir.string(), "' cannot be created (",
                 ec.message(), "); choose another one with -o DIR");
  });
}

} // namespace

int run(const RunOptions& options, int argc, char** argv) {
  Comm comm;
  la::Session petsc(argc, argv, options.petsc_args);
  const auto config = io::load_config(options.input);
  if (has_fsi(config)) {
    // Distributed as the fluid runs, the fsi sides held in part as mesh tying's.
    make_output_directory(output_directory(options), comm);
    MeshIdentity identity;
    auto part =
        load_distributed_mesh(config, comm, identity, output_directory(options), options.quiet);
    run_fsi(config, part, identity, comm, output_directory(options), options.quiet, false,
            {options.input, options.restart});
    return 0;
  }
  if (has_fluid(config)) {
    // Distributed as the solids: each rank holds its cells, their nodes and one ghost layer.
    make_output_directory(output_directory(options), comm);
    MeshIdentity identity;
    auto part =
        load_distributed_mesh(config, comm, identity, output_directory(options), options.quiet);
    run_fluid(config, part, identity, comm, output_directory(options), options.quiet,
              {options.input, options.restart});
    return 0;
  }
  MeshIdentity identity;
  // The output directory holds the mesh Gmsh makes of a geometry file (read by every rank).
  make_output_directory(output_directory(options), comm);
  // Memory by phase (parallel/memory_trace.hpp): summary.json and SEAM_MEMORY_TRACE=1.
  parallel::mark_memory(comm.get(), "start");
  auto part =
      load_distributed_mesh(config, comm, identity, output_directory(options), options.quiet);
  parallel::mark_memory(comm.get(), "mesh");
  const Discretization disc(part, comm);
  const auto model = build_model(config, disc);
  parallel::mark_memory(comm.get(), "discretization");
  PhaseTimers setup_timers;
  const auto tied = meshtying::setup_mesh_tying(config, part, comm.get(), setup_timers);
  parallel::mark_memory(comm.get(), "interface_integration");
  const TyingConstraint tying(tied, disc, model);
  SaddlePoint saddle(tied, disc, model);
  ContactConstraint contact(config, disc, model);
  parallel::mark_memory(comm.get(), "interface_operators");
  if (tying.active() && saddle.active())
    SEAM_THROW(InputError, options.input,
               ": interfaces: condensed and saddle_point mesh tying cannot be mixed in one run");
  if (contact.active() && (tying.active() || saddle.active()))
    SEAM_THROW(InputError, options.input,
               ": interfaces: contact and mesh tying in one run are not available in this "
               "version of seam");
  const Checkpoints checkpoints(config, "solid", identity, comm, nodal_order(disc), options.input,
                                output_directory(options), options.restart);
  make_output_directory(output_directory(options), comm);
  Output out(config, disc, model, tied, output_directory(options), options.quiet,
             checkpoints.restarting() ? &checkpoints : nullptr);
  for (const auto& [phase, seconds] : setup_timers.all()) out.timers().add(phase, seconds);
  if (comm.is_root() && !options.quiet)
    std::printf("seam %s: %s\n  %d nodes, %d cells, %lld dofs, %d rank(s); output in %s\n",
                version(), config.title.empty() ? options.input.c_str() : config.title.c_str(),
                static_cast<int>(disc.n_global_nodes()), static_cast<int>(disc.n_global_cells()),
                static_cast<long long>(disc.n_global_dofs()), comm.size(),
                out.directory().string().c_str());
  // Collective: `auto` may count the boundary nodes over all ranks.
  const auto linear_solver =
      describe_linear_solver(config, disc, saddle.active() || contact.saddle_point());
  if (comm.is_root() && !options.quiet) std::printf("  linear solver: %s\n", linear_solver.c_str());
  if (comm.is_root() && !options.quiet)
    for (const auto& line : contact.held_whole()) std::printf("  %s\n", line.c_str());
  parallel::mark_memory(comm.get(), "output_setup");
  if (checkpoints.restarting() && comm.is_root() && !options.quiet)
    std::printf("  restarting from %s: step %d, t = %.17g\n", options.restart.c_str(),
                checkpoints.restart_step(), checkpoints.restart_time());
  if (config.time.is_dynamic())
    run_dynamic(config, model, disc, tied, tying, saddle, contact, out, checkpoints);
  else
    run_static(config, model, disc, tied, tying, saddle, contact, out, checkpoints);
  return 0;
}

int check(const std::string& input, const std::vector<std::string>& petsc_args) {
  Comm comm;
  int argc = 0;
  char** argv = nullptr;
  la::Session petsc(argc, argv, petsc_args); // the parallel partition of the chunked reader
  const auto config = io::load_config(input);
  // The mesh as a run distributes it (each rank its cells, one ghost layer and the cells of
  // the interface sides held whole), and the set-up a run does on it.
  MeshIdentity identity;
  auto part = load_distributed_mesh(config, comm, identity, {}, true);
  // The cells each rank holds (own, ghost layer, interface sides), printed by rank 0.
  const auto held_per_rank = [&] {
    std::vector<long long> held(static_cast<std::size_t>(comm.size()));
    const long long n_held = part.n_cells();
    MPI_Gather(&n_held, 1, MPI_LONG_LONG, held.data(), 1, MPI_LONG_LONG, 0, comm.get());
    return held;
  };
  const auto print_held = [&](const std::vector<long long>& held) {
    if (held.size() < 2) return;
    std::printf("  cells held per rank (own, ghost layer, interface sides):");
    for (std::size_t r = 0; r < held.size(); ++r)
      std::printf("%s %lld", r == 0 ? "" : " /", held[r]);
    std::printf(" of %lld\n", static_cast<long long>(part.n_global_cells));
  };
  if (has_fsi(config)) {
    const auto info = run_fsi(config, part, identity, comm, {}, true, true);
    const auto held = held_per_rank();
    if (comm.is_root()) {
      std::printf("%s: ok\n  fluid-structure interaction, dimension %d, %lld nodes, %lld cells, "
                  "%lld unknowns\n",
                  input.c_str(), part.mesh.dim, static_cast<long long>(part.n_global_nodes),
                  static_cast<long long>(part.n_global_cells), info.n_dofs);
      print_held(held);
    }
    return 0;
  }
  if (has_fluid(config)) {
    const auto info = run_fluid(config, part, identity, comm, {}, true, {}, true);
    if (comm.is_root())
      std::printf("%s: ok\n  fluid, dimension %d, %lld nodes, %lld cells, %lld dofs\n",
                  input.c_str(), part.mesh.dim, static_cast<long long>(part.n_global_nodes),
                  static_cast<long long>(part.n_global_cells), info.n_dofs);
    return 0;
  }
  const Discretization disc(part, comm);
  const auto model = build_model(config, disc);
  PhaseTimers timers;
  const auto tied = meshtying::setup_mesh_tying(config, part, comm.get(), timers);
  const ContactConstraint contact(config, disc, model);
  // Cells by type over the owned cells (the types in the order of fem::CellType), and the
  // integration cells of each tied interface over the ranks that integrated them.
  std::vector<long long> by_type(256, 0);
  for (std::int32_t c = 0; c < part.n_cells(); ++c)
    if (part.cell_role[static_cast<std::size_t>(c)] == mesh::CellRole::owned)
      ++by_type[static_cast<std::size_t>(part.mesh.cell_type[static_cast<std::size_t>(c)])];
  MPI_Allreduce(MPI_IN_PLACE, by_type.data(), static_cast<int>(by_type.size()), MPI_LONG_LONG,
                MPI_SUM, comm.get());
  std::vector<long long> integration_cells;
  for (const auto& t : tied) integration_cells.push_back(t.local_integration_cells);
  if (!integration_cells.empty())
    MPI_Allreduce(MPI_IN_PLACE, integration_cells.data(),
                  static_cast<int>(integration_cells.size()), MPI_LONG_LONG, MPI_SUM, comm.get());
  const auto contact_lines = contact.describe();
  const auto held = held_per_rank();
  if (!comm.is_root()) return 0;
  std::map<std::string, long long> named;
  for (std::size_t t = 0; t < by_type.size(); ++t)
    if (by_type[t] > 0) named[std::string(fem::name(static_cast<fem::CellType>(t)))] = by_type[t];
  std::printf("%s: ok\n", input.c_str());
  if (!config.title.empty()) std::printf("  title: %s\n", config.title.c_str());
  std::printf("  dimension %d, %lld nodes, %lld cells (", part.mesh.dim,
              static_cast<long long>(part.n_global_nodes),
              static_cast<long long>(part.n_global_cells));
  bool first = true;
  for (const auto& [name, n] : named) {
    std::printf("%s%lld %s", first ? "" : ", ", n, name.c_str());
    first = false;
  }
  std::printf("), %lld dofs\n", static_cast<long long>(disc.n_global_dofs()));
  std::printf("  regions:");
  for (const auto& r : part.mesh.regions) std::printf(" %s (dim %d)", r.name.c_str(), r.dim);
  std::printf("\n  %zu bodies, %zu boundary conditions, %zu interfaces, %d steps to t = %g\n",
              config.bodies.size(), config.boundary_conditions.size(), config.interfaces.size(),
              config.time.n_steps, config.time.end);
  for (std::size_t k = 0; k < tied.size(); ++k) {
    const auto& t = tied[k];
    // Distributed interfaces: each rank integrated its own slave facets; the others whole on
    // every rank.
    const long long cells = t.distributed ? integration_cells[k] : t.local_integration_cells;
    std::printf("  interface %s: %lld slave and %lld master facets, %lld integration cells, "
                "slave nodes moved by at most %.3g\n",
                t.name.c_str(), static_cast<long long>(t.n_slave_facets),
                static_cast<long long>(t.n_master_facets), cells, t.max_relocation);
  }
  for (const auto& line : contact_lines) std::printf("  %s\n", line.c_str());
  print_held(held);
  return 0;
}

} // namespace seam::app
