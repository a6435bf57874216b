#pragma once
// A structural check of ASCII .msh 4.1 files before Gmsh reads them. Gmsh 4.8's reader trusts
// the counts and tags of the file: a negative node tag in an element, a $Nodes header whose
// count disagrees with its blocks or a malformed physical name make it crash (segfault, heap
// corruption) instead of reporting an error. Checked here: the section headers against the
// blocks, every tag positive and within the header's range, the number of nodes of every
// element of a known type, the DIM TAG "NAME" lines of $PhysicalNames.
#include <filesystem>
#include <string>

namespace seam::mesh::detail {

/// Throws InputError "mesh 'FILE': line N: $SECTION: ..." for a structural error; returns
/// without a word for other formats (.msh 2.2, 4.0, binary) and for what Gmsh reports itself.
void check_msh_structure(const std::filesystem::path& path, const std::string& file);

} // namespace seam::mesh::detail
