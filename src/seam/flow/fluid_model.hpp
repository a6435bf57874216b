#pragma once
// The configured fluid problem on this rank (fixed mesh, steady): the fluid of every cell,
// velocity conditions on the dofs this rank owns, pressure and traction loads on its facets,
// body forces on its cells, and the force groups of forces.csv. Built once from the input; the
// input's combinations that the fluid field does not support yet fail here with a located
// message.
#include "seam/flow/fluid_layout.hpp"
#include "seam/fluid/navier_stokes.hpp"
#include "seam/io/config.hpp"
#include "seam/problem/model.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace seam::flow {

/// One prescribed dof owned by this rank: a velocity component or a pinned pressure.
struct FluidDirichletDof {
  PetscInt dof;      ///< global
  std::int32_t node; ///< its coordinates feed the expression
  int expression;    ///< index into FluidModel::values
};

/// A force group of forces.csv: the nodes of its regions that this rank owns.
struct ForceRegion {
  std::string name;
  std::vector<std::int32_t> owned_nodes;
};

struct FluidModel {
  int dim = 2;
  std::vector<fluid::Fluid> fluids;
  std::vector<int> cell_fluid; ///< per mesh cell, index into fluids
  std::vector<io::Expression> values;
  std::vector<FluidDirichletDof> dirichlet; ///< sorted by dof, unique (a later condition wins)
  std::vector<problem::SurfaceLoad> surface_loads; ///< pressure (-p n) and traction
  std::vector<problem::BodyLoad> body_loads;
  std::vector<ForceRegion> forces;
  /// The flow is enclosed (the velocity is prescribed on the whole boundary): its pressure is
  /// fixed at one vertex, and errors and output remove the mean instead.
  bool pressure_pinned = false;
  /// Per mesh node: 1 on a side of a tied interface (mesh tying of fluid subdomains).
  std::vector<char> tied_nodes;
};

/// True if some body of the input is made of a fluid material.
bool has_fluid(const io::Config& config);

/// Checks the input against the mesh and what the fluid field supports (InputError, located)
/// and builds this rank's fluid model.
FluidModel build_fluid_model(const io::Config& config, const FluidLayout& layout);

} // namespace seam::flow
