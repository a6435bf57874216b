#pragma once
// Reading meshes through the Gmsh API: .msh 2.2 / 4.x files, or geometry files (.geo, and the
// CAD formats Gmsh opens) meshed at start. Physical groups become regions.
#include "seam/mesh/mesh.hpp"

#include <filesystem>
#include <optional>

namespace seam::mesh {

struct ReadOptions {
  /// Geometry files only: largest element size (Gmsh option Mesh.MeshSizeMax); unset = as the
  /// geometry file says.
  std::optional<double> size;
  /// Geometry files only: element order 1 or 2 (Mesh.ElementOrder); 0 = as the file says.
  int order = 0;
  /// Geometry files only: second-order quads/hexes without interior nodes (quad8, hex20)
  /// instead of quad9/hex27 (Mesh.SecondOrderIncomplete = 1).
  bool serendipity = false;
  /// Expected mesh dimension, 2 or 3; 0 accepts either. A mismatch is an InputError.
  int dim = 0;
};

/// Read a mesh. The cells are the elements of the highest dimension in the file (mixed types
/// allowed); nodes are those used by cells, numbered 0..n-1 in increasing Gmsh node tag; cells
/// are in increasing Gmsh element tag. Physical groups of the mesh dimension give region cells,
/// those of dimension - 1 give region facets (matched to cell facets by corner nodes), all
/// give region nodes.
///
/// Throws InputError naming the file for: a missing or unreadable file, an extension that is
/// neither .msh nor a geometry file, a file Gmsh cannot parse or mesh (with Gmsh's message),
/// no elements of dimension 2 or 3, a dimension other than options.dim, an element type
/// seam does not support, a 2D mesh with z != 0, a boundary element that is not a facet of
/// any cell (naming the region), a region node that belongs to no cell, two physical groups
/// with the same name and dimension, a negative tag in an ASCII $Elements section (naming the
/// line), a node coordinate that is not finite, a cell with det(dX/dxi) <= 0 at a point of
/// the element kernels' quadrature rule (naming its Gmsh element tag).
///
/// Gmsh is a process-wide singleton: read_mesh serialises calls with a mutex and runs each
/// read in its own Gmsh session (initialize ... finalize, no configuration files, nothing
/// printed, no exit on error), so options set by one geometry file never affect the next
/// read. Do not call it while the calling code itself holds Gmsh initialized.
Mesh read_mesh(const std::filesystem::path& file, const ReadOptions& options = {});

/// Meshes a geometry file as read_mesh does and writes the mesh to `msh` (binary MSH 4.1, the
/// elements of every entity), for the chunked reader (distribute_file.hpp); the Gmsh model is freed
/// on return. Throws InputError as read_mesh, or naming `msh` if it cannot be written.
void mesh_to_msh(const std::filesystem::path& geometry, const ReadOptions& options,
                 const std::filesystem::path& msh);

} // namespace seam::mesh
