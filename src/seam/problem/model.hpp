#pragma once
// The configured problem on this rank: materials per cell, loads on the facets and cells
// this rank assembles, Dirichlet conditions on the dofs it owns. Built once from the input
// and the mesh; every region name is checked here against the mesh, with a located message.
#include "seam/io/config.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/solid/material.hpp"

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace seam::problem {

struct FacetRef {
  std::int32_t cell;
  std::int8_t local;
};

/// A pressure or traction load on the facets of one boundary region this rank assembles.
struct SurfaceLoad {
  io::BoundaryType type; ///< pressure or traction
  std::vector<FacetRef> facets;
  std::vector<int> components;       ///< traction: which components the values give
  std::vector<io::Expression> value; ///< pressure: one; traction: one per component
};

/// A body force on the cells of one body region this rank assembles.
struct BodyLoad {
  std::vector<std::int32_t> cells;
  std::vector<int> components;
  std::vector<io::Expression> value;
};

/// One prescribed dof owned by this rank.
struct DirichletDof {
  PetscInt dof;      ///< global index
  std::int32_t node; ///< mesh node (its reference coordinates feed the expression)
  int expression;    ///< index into Model::dirichlet_values
};

/// A Dirichlet region, for reactions.csv: the nodes of the region this rank owns.
struct ReactionRegion {
  std::string name;
  std::vector<std::int32_t> owned_nodes;
};

struct Model {
  int dim = 3;
  solid::PlaneMode plane = solid::PlaneMode::none;
  std::vector<solid::Material> materials;
  std::vector<std::string> material_names;
  std::vector<int> cell_material; ///< per mesh cell, index into materials
  std::vector<SurfaceLoad> surface_loads;
  std::vector<BodyLoad> body_loads;
  std::vector<io::Expression> dirichlet_values;
  std::vector<io::Mark> dirichlet_marks; ///< per value: where the input gave it
  std::vector<DirichletDof> dirichlet;   ///< sorted by dof, unique (a later condition wins)
  std::vector<ReactionRegion> reaction_regions;
};

/// The load of a pressure or traction condition on the facets of its region (checked, located)
/// that this rank assembles.
SurfaceLoad surface_load(const mesh::Mesh& mesh, const io::BoundaryCondition& bc,
                         const std::function<bool(std::int32_t)>& is_local_cell);
/// The load of a body_force condition on the cells of its region that this rank assembles.
BodyLoad body_load(const mesh::Mesh& mesh, const io::BoundaryCondition& bc,
                   const std::function<bool(std::int32_t)>& is_local_cell);

/// The solid model of a solid material of the input (linear_elastic for a fluid, which has none).
solid::MaterialModel to_solid(io::MaterialModel m);

/// Checks the input's region references against the mesh (InputError, located in the YAML)
/// and builds this rank's model.
Model build_model(const io::Config& config, const Discretization& disc);

/// Throws a located InputError unless the mesh has a region `ref` of one of the dimensions
/// in `dims`; lists the regions there are.
const mesh::Region& find_region(const mesh::Mesh& mesh, const io::RegionRef& ref,
                                std::initializer_list<int> dims, std::string_view what);

} // namespace seam::problem
