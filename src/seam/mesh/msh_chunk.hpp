#pragma once
// A chunked reader of Gmsh MSH 4.1 files (ASCII and binary), for the distributed mesh
// (distribute_file.hpp): rank r of P keeps the elements [N r / P, N (r+1) / P) of the file's
// top-dimension elements (in file order) and the same share of the elements of the lower
// dimensional physical groups; nodes are read later, only those a rank asks for. No rank holds
// all elements or all nodes. $MeshFormat, $PhysicalNames and $Entities (small: O(entities))
// are read by every rank.
//
// What this reader does not handle (MSH 2.x and 4.0, partitioned or periodic files, element
// types seam does not map, element tags that do not increase through the file, a data size
// other than 8) is reported as MshUnsupported, and the caller reads the file through Gmsh on
// rank 0 instead. Structural errors (truncated sections, counts that disagree, tags out of
// range) are InputErrors naming the file and the section.
#include "seam/fem/cell.hpp"

#include <cstdint>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

namespace seam::mesh {

/// A file the chunked reader leaves to Gmsh; what() says why.
class MshUnsupported : public std::runtime_error {
public:
  using std::runtime_error::runtime_error;
};

/// Elements of one kind (cells, or boundary/lower-dimensional elements) as flat arrays.
struct MshElements {
  std::vector<std::uint64_t> tag;
  std::vector<fem::CellType> type;
  std::vector<int> entity; ///< entity tag (of dimension fem::dimension(type))
  std::vector<std::int64_t> offsets{0};
  std::vector<std::uint64_t> nodes; ///< node tags, Gmsh (= fem) order
  std::size_t size() const { return tag.size(); }
};

struct MshChunk {
  std::string file;
  bool binary = false;
  int dim = 0;                 ///< dimension of the cells (highest element dimension)
  std::int64_t n_cells = 0;    ///< top-dimension elements in the file
  std::int64_t first_cell = 0; ///< index (file order) of this rank's first cell
  MshElements cells;           ///< this rank's share of the top-dimension elements
  MshElements lower;           ///< this rank's share of the lower-dimensional physical elements
  /// (dim, physical tag) -> name, from $PhysicalNames.
  std::map<std::pair<int, int>, std::string> names;
  /// (dim, entity tag) -> physical tags, from $Entities.
  std::map<std::pair<int, int>, std::vector<int>> physicals;
  std::uint64_t min_node_tag = 0, max_node_tag = 0; ///< from the $Nodes header
  std::uint64_t node_blocks = 0;                    ///< entity blocks of $Nodes
  std::int64_t nodes_at = -1;                       ///< file offset of the $Nodes data
};

/// Reads rank `rank`'s share (of `n_ranks`). Throws MshUnsupported or InputError.
MshChunk read_msh_chunk(const std::filesystem::path& path, int rank, int n_ranks);

/// Coordinates (3 per node) of the nodes with the given sorted, unique tags, streamed from the
/// $Nodes section. Throws InputError naming a tag that the file does not define.
std::vector<double> read_msh_nodes(const MshChunk& chunk, const std::vector<std::uint64_t>& tags);

} // namespace seam::mesh
