#include "seam/mesh/distribute_file.hpp"

#include "seam/common/error.hpp"
#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/msh_chunk.hpp"
#include "seam/mesh/parallel_partition.hpp"
#include "seam/mesh/partition.hpp"
#include "seam/mesh/transfer.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>
#include <set>
#include <tuple>

namespace seam::mesh {
namespace {

using parallel::alltoallv;

/// Records to the ranks `dest` names; what every rank sent here, grouped by source
/// (`from` gets the source offsets).
template <class T, class F>
std::vector<T> route(MPI_Comm comm, int size, const std::vector<T>& records, F&& dest,
                     std::vector<std::int64_t>& from) {
  std::vector<std::int64_t> offsets(static_cast<std::size_t>(size) + 1, 0);
  for (const auto& r : records) ++offsets[dest(r) + 1];
  for (int p = 0; p < size; ++p) offsets[p + 1] += offsets[p];
  std::vector<T> send(records.size());
  auto at = offsets;
  for (const auto& r : records) send[at[dest(r)]++] = r;
  return alltoallv<T>(comm, send, offsets, from);
}
template <class T, class F>
std::vector<T> route(MPI_Comm comm, int size, const std::vector<T>& records, F&& dest) {
  std::vector<std::int64_t> from;
  return route(comm, size, records, dest, from);
}

/// An error found on some ranks, thrown on every rank: the message of the lowest such rank.
/// `unsupported` errors become MshUnsupported (the caller falls back to Gmsh).
void agree(MPI_Comm comm, std::string error, bool unsupported = false) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int mine = error.empty() ? size : rank;
  int first = size;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm);
  if (first == size) return;
  int kind = unsupported ? 1 : 0;
  MPI_Bcast(&kind, 1, MPI_INT, first, comm);
  std::uint64_t n = error.size();
  MPI_Bcast(&n, 1, MPI_UINT64_T, first, comm);
  error.resize(n);
  MPI_Bcast(error.data(), static_cast<int>(n), MPI_CHAR, first, comm);
  if (kind) throw MshUnsupported(error);
  throw InputError(error);
}

template <class F> void collectively(MPI_Comm comm, F&& f) {
  std::string error;
  bool unsupported = false;
  try {
    f();
  } catch (const MshUnsupported& e) {
    error = e.what();
    unsupported = true;
  } catch (const InputError& e) {
    error = e.what();
  }
  agree(comm, error, unsupported);
}

struct FacetRecord {
  std::array<std::uint64_t, 4> key; // sorted corner tags, 0-padded
  std::int64_t cell;                // cell gid, or -1 for a boundary element
  std::uint64_t element;            // boundary element tag (messages)
  std::int32_t region;              // boundary element: region index
  std::int8_t local;                // cell: local facet
};
struct Edge {
  std::int64_t cell, other;
};
struct RegionFacet {
  std::int64_t cell;
  std::int32_t region;
  std::int8_t local;
};
struct NodeUse {
  std::uint64_t tag;
  std::int64_t cell;
  std::int32_t part, entity;
};
struct RegionNode {
  std::uint64_t tag;
  std::uint64_t element;
  std::int32_t region;
};
struct Hold {
  std::int64_t cell;
  std::int32_t part;
  std::int32_t role;
};
struct NodeInfo {
  std::int64_t gid, index;
  std::int32_t owner, n_regions;
  std::array<double, 3> x;
};

std::uint64_t mix(const std::array<std::uint64_t, 4>& k) {
  std::uint64_t h = 0x9e3779b97f4a7c15ULL;
  for (auto v : k) {
    h ^= v + 0x9e3779b97f4a7c15ULL + (h << 6) + (h >> 2);
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
  }
  return h ^ (h >> 31);
}

// Insertion sort of the first n (<= 4) corner tags; the rest stay 0.
void sort_key(std::array<std::uint64_t, 4>& key, int n) {
  for (int i = 1; i < n; ++i)
    for (int j = i; j > 0 && key[j - 1] > key[j]; --j) std::swap(key[j - 1], key[j]);
}

class Builder {
public:
  Builder(MPI_Comm comm, std::span<const std::string> interfaces) : comm_(comm) {
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &size_);
    interfaces_.assign(interfaces.begin(), interfaces.end());
  }

  DistributedMesh run(const std::filesystem::path& file, int want_dim) {
    int threads = MPI_THREAD_SINGLE;
    MPI_Query_thread(&threads);
    // PT-Scotch 7 partitions with threads that call MPI; without MPI_THREAD_MULTIPLE it fails
    // at random (seen at np 4: "dgraphHaloSync: communication error").
    if (size_ > 1 && threads < MPI_THREAD_MULTIPLE)
      throw MshUnsupported("MPI was not initialized with MPI_THREAD_MULTIPLE");
    collectively(comm_, [&] { c_ = read_msh_chunk(file, rank_, size_); });
    check_chunk(want_dim);
    make_regions();
    number_nodes();
    read_coordinates();
    match_facets();
    partition();
    collect_node_uses();
    send_cells();
    return assemble();
  }

private:
  // The whole-file checks: one dimension, increasing cell tags (cell gid = file position).
  void check_chunk(int want_dim) {
    dim_ = c_.dim;
    n_cells_ = c_.n_cells;
    file_ = c_.file;
    std::string error;
    if (want_dim != 0 && want_dim != c_.dim)
      error = "mesh '" + c_.file + "': the mesh has dimension " + std::to_string(c_.dim) +
              " but dimension " + std::to_string(want_dim) + " was asked for";
    if (c_.n_cells < size_)
      error = "cannot partition a mesh of " + std::to_string(c_.n_cells) + " cells into " +
              std::to_string(size_) + " parts (more parts than cells)";
    agree(comm_, error);
    const auto& t = c_.cells.tag;
    std::array<std::uint64_t, 2> mine{t.empty() ? 0 : t.front(), t.empty() ? 0 : t.back()};
    std::vector<std::int64_t> off;
    const auto ends =
        parallel::allgatherv<std::array<std::uint64_t, 2>>(comm_, std::span(&mine, 1), off);
    bool increasing = std::adjacent_find(t.begin(), t.end(), std::greater_equal<>()) == t.end();
    std::uint64_t last = 0;
    for (const auto& e : ends) {
      if (e[0] == 0) continue;
      increasing = increasing && e[0] > last;
      last = e[1];
    }
    int ok = increasing ? 1 : 0, all = 0;
    MPI_Allreduce(&ok, &all, 1, MPI_INT, MPI_MIN, comm_);
    if (!all) throw MshUnsupported("element tags that do not increase through the file");
    first_.resize(static_cast<std::size_t>(size_) + 1);
    for (int r = 0; r <= size_; ++r) first_[r] = c_.n_cells * r / size_;
  }

  int chunk_of(std::int64_t cell) const {
    return static_cast<int>(std::upper_bound(first_.begin(), first_.end(), cell) - first_.begin()) -
           1;
  }
  int node_dir(std::uint64_t tag) const {
    const auto n = static_cast<std::uint64_t>(size_);
    const auto block = (c_.max_node_tag - c_.min_node_tag + n) / n; // tags per directory rank
    return static_cast<int>((tag - c_.min_node_tag) / block);
  }

  // Regions as read_mesh makes them: the physical groups in (dim, tag) order.
  void make_regions() {
    std::set<std::pair<int, int>> groups;
    for (const auto& [entity, phys] : c_.physicals)
      if (entity.first <= c_.dim)
        for (int p : phys) groups.insert({entity.first, p});
    std::set<std::pair<int, std::string>> seen;
    std::string error;
    for (const auto& [dim, tag] : groups) {
      Region r;
      r.dim = dim;
      r.tag = tag;
      const auto it = c_.names.find({dim, tag});
      r.name = it != c_.names.end() ? it->second : std::to_string(dim) + ":" + std::to_string(tag);
      if (!seen.insert({dim, r.name}).second && error.empty())
        error = "mesh '" + c_.file + "': two physical groups of dimension " + std::to_string(dim) +
                " are named '" + r.name + "'";
      regions_.push_back(std::move(r));
    }
    agree(comm_, error);
    for (const auto& [entity, phys] : c_.physicals)
      for (int p : phys) {
        const auto it = std::find_if(regions_.begin(), regions_.end(), [&](const Region& r) {
          return r.dim == entity.first && r.tag == p;
        });
        if (it != regions_.end())
          entity_regions_[entity].push_back(static_cast<int>(it - regions_.begin()));
      }
  }
  const std::vector<int>& regions_of(int dim, int entity) const {
    static const std::vector<int> none;
    const auto it = entity_regions_.find({dim, entity});
    return it == entity_regions_.end() ? none : it->second;
  }

  // Node gids: the rank of a tag among the tags cells use (read_mesh's numbering), counted in
  // the tag ranges of the node directory.
  void number_nodes() {
    std::vector<std::uint64_t> used(c_.cells.nodes);
    std::sort(used.begin(), used.end());
    used.erase(std::unique(used.begin(), used.end()), used.end());
    tags_ = route(comm_, size_, used, [&](std::uint64_t t) { return node_dir(t); });
    std::sort(tags_.begin(), tags_.end());
    tags_.erase(std::unique(tags_.begin(), tags_.end()), tags_.end());
    std::int64_t n = static_cast<std::int64_t>(tags_.size());
    MPI_Exscan(&n, &gid_base_, 1, MPI_INT64_T, MPI_SUM, comm_);
    if (rank_ == 0) gid_base_ = 0;
    MPI_Allreduce(&n, &n_nodes_, 1, MPI_INT64_T, MPI_SUM, comm_);
  }
  std::int64_t dir_index(std::uint64_t tag) const {
    const auto it = std::lower_bound(tags_.begin(), tags_.end(), tag);
    return it != tags_.end() && *it == tag ? it - tags_.begin() : -1;
  }

  void read_coordinates() {
    collectively(comm_, [&] { x_ = read_msh_nodes(c_, tags_); });
    std::string error;
    std::array<double, 2> z{0, 0}; // max |z|, max |coordinate|
    for (std::size_t i = 0; i < x_.size(); ++i) {
      if (!std::isfinite(x_[i]) && error.empty())
        error = "mesh '" + c_.file + "': node " + std::to_string(tags_[i / 3]) +
                " has a coordinate that is not a finite number";
      z[1] = std::max(z[1], std::abs(x_[i]));
      if (i % 3 == 2) z[0] = std::max(z[0], std::abs(x_[i]));
    }
    agree(comm_, error);
    std::array<double, 2> all{};
    MPI_Allreduce(z.data(), all.data(), 2, MPI_DOUBLE, MPI_MAX, comm_);
    // A 2D analysis is in the x-y plane (as read_mesh).
    if (c_.dim == 2 && all[0] > 1e-12 * std::max(all[1], 1.0))
      agree(comm_, "mesh '" + c_.file +
                       "': a 2D mesh must lie in the plane z = 0, but a node has |z| = " +
                       std::to_string(all[0]));
  }

  // Facets meet at the rank their corner tags hash to: cell pairs give the dual graph, boundary
  // elements find their cell (the lowest gid, as read_mesh's FacetIndex).
  void match_facets() {
    std::vector<FacetRecord> out;
    const auto& cells = c_.cells;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      const auto type = cells.type[c];
      const auto* nodes = cells.nodes.data() + cells.offsets[c];
      for (int f = 0; f < fem::n_facets(type); ++f) {
        FacetRecord r{{0, 0, 0, 0},
                      first_[rank_] + static_cast<std::int64_t>(c),
                      0,
                      -1,
                      static_cast<std::int8_t>(f)};
        const auto local = fem::facet_nodes(type, f);
        const int n = fem::n_vertices(fem::facet_type(type, f));
        for (int a = 0; a < n; ++a) r.key[a] = nodes[local[a]];
        sort_key(r.key, n);
        out.push_back(r);
      }
    }
    const auto& low = c_.lower;
    for (std::size_t e = 0; e < low.size(); ++e) {
      if (fem::dimension(low.type[e]) != c_.dim - 1) continue;
      FacetRecord r{{0, 0, 0, 0}, -1, low.tag[e], -1, -1};
      const int n = fem::n_vertices(low.type[e]);
      for (int a = 0; a < n; ++a) r.key[a] = low.nodes[low.offsets[e] + a];
      sort_key(r.key, n);
      for (int region : regions_of(c_.dim - 1, low.entity[e])) {
        r.region = region;
        out.push_back(r);
      }
    }
    auto here = route(comm_, size_, out, [&](const FacetRecord& r) {
      return static_cast<int>(mix(r.key) % static_cast<std::uint64_t>(size_));
    });
    out = {};
    std::sort(here.begin(), here.end(), [](const FacetRecord& a, const FacetRecord& b) {
      return std::tie(a.key, a.cell, a.region) < std::tie(b.key, b.cell, b.region);
    });
    std::vector<Edge> edges;
    std::vector<RegionFacet> facets;
    std::string error;
    for (std::size_t i = 0; i < here.size();) {
      std::size_t j = i;
      while (j < here.size() && here[j].key == here[i].key) ++j;
      // Boundary elements sort first (cell -1), then the cells by gid.
      std::size_t k = i;
      while (k < j && here[k].cell < 0) ++k;
      for (std::size_t a = k; a < j; ++a)
        for (std::size_t b = k; b < j; ++b)
          if (a != b) edges.push_back({here[a].cell, here[b].cell});
      for (std::size_t a = i; a < k; ++a) {
        if (k == j) {
          if (error.empty())
            error = "mesh '" + c_.file + "': element " + std::to_string(here[a].element) +
                    " of boundary region '" + regions_[here[a].region].name +
                    "' is not a facet of any cell of dimension " + std::to_string(c_.dim);
          continue;
        }
        facets.push_back({here[k].cell, here[a].region, here[k].local});
      }
      i = j;
    }
    agree(comm_, error);
    here = {};
    edges = route(comm_, size_, edges, [&](const Edge& e) { return chunk_of(e.cell); });
    std::sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) {
      return std::tie(a.cell, a.other) < std::tie(b.cell, b.other);
    });
    edges.erase(std::unique(edges.begin(), edges.end(),
                            [](const Edge& a, const Edge& b) {
                              return a.cell == b.cell && a.other == b.other;
                            }),
                edges.end());
    adjacency_offsets_.assign(c_.cells.size() + 1, 0);
    for (const auto& e : edges) ++adjacency_offsets_[e.cell - first_[rank_] + 1];
    for (std::size_t c = 0; c < c_.cells.size(); ++c)
      adjacency_offsets_[c + 1] += adjacency_offsets_[c];
    adjacency_.resize(edges.size());
    for (std::size_t k = 0; k < edges.size(); ++k) adjacency_[k] = edges[k].other;

    facets_ = route(comm_, size_, facets, [&](const RegionFacet& f) { return chunk_of(f.cell); });
    std::sort(facets_.begin(), facets_.end(), [](const RegionFacet& a, const RegionFacet& b) {
      return std::tie(a.cell, a.region, a.local) < std::tie(b.cell, b.region, b.local);
    });
  }

  // The partitioning weight of each chunk cell (partition.hpp, cell_weight): the node
  // directory counts the cells around each node and returns every cell its nodes' shares.
  std::vector<int> cell_weights() {
    if (size_ == 1) return {};
    struct Share {
      std::int64_t cell;
      double share;
    };
    std::vector<NodeUse> uses;
    const auto& cells = c_.cells;
    for (std::size_t c = 0; c < cells.size(); ++c)
      for (auto k = cells.offsets[c]; k < cells.offsets[c + 1]; ++k)
        uses.push_back({cells.nodes[k], first_[rank_] + static_cast<std::int64_t>(c), 0, 0});
    uses = route(comm_, size_, uses, [&](const NodeUse& u) { return node_dir(u.tag); });
    std::sort(uses.begin(), uses.end(),
              [](const NodeUse& a, const NodeUse& b) { return a.tag < b.tag; });
    std::vector<Share> shares;
    shares.reserve(uses.size());
    for (std::size_t i = 0; i < uses.size();) {
      std::size_t j = i;
      while (j < uses.size() && uses[j].tag == uses[i].tag) ++j;
      for (std::size_t a = i; a < j; ++a)
        shares.push_back({uses[a].cell, 1.0 / static_cast<double>(j - i)});
      i = j;
    }
    uses = {};
    shares = route(comm_, size_, shares, [&](const Share& s) { return chunk_of(s.cell); });
    std::vector<double> sum(cells.size(), 0.0);
    for (const auto& s : shares) sum[static_cast<std::size_t>(s.cell - first_[rank_])] += s.share;
    double total = 0.0;
    for (std::size_t c = 0; c < cells.size(); ++c) {
      sum[c] = cell_weight(static_cast<int>(cells.offsets[c + 1] - cells.offsets[c]), sum[c]);
      total += sum[c];
    }
    MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_DOUBLE, MPI_SUM, comm_);
    std::vector<int> weights(cells.size());
    for (std::size_t c = 0; c < cells.size(); ++c) weights[c] = integer_weight(sum[c], total);
    return weights;
  }

  void partition() {
    part_ = partition_dual_graph(comm_, first_[rank_], c_.n_cells, adjacency_offsets_, adjacency_,
                                 cell_weights());
    adjacency_ = {};
    adjacency_offsets_ = {};
  }

  // The node directory learns every node's cells and their parts: the node's owner (the
  // smallest part), its global number, its regions, and which ranks hold which cells.
  void collect_node_uses() {
    std::vector<NodeUse> uses;
    const auto& cells = c_.cells;
    for (std::size_t c = 0; c < cells.size(); ++c)
      for (auto k = cells.offsets[c]; k < cells.offsets[c + 1]; ++k)
        uses.push_back({cells.nodes[k], first_[rank_] + static_cast<std::int64_t>(c), part_[c],
                        cells.entity[c]});
    uses = route(comm_, size_, uses, [&](const NodeUse& u) { return node_dir(u.tag); });
    std::sort(uses.begin(), uses.end(), [](const NodeUse& a, const NodeUse& b) {
      return std::tie(a.tag, a.part, a.cell) < std::tie(b.tag, b.part, b.cell);
    });
    // Region nodes: cells of the mesh dimension, and the lower-dimensional elements' nodes.
    std::vector<std::pair<std::int64_t, std::int32_t>> node_region; // (dir index, region)
    for (const auto& u : uses)
      for (int region : regions_of(c_.dim, u.entity))
        node_region.emplace_back(dir_index(u.tag), region);
    std::vector<RegionNode> lower;
    const auto& low = c_.lower;
    for (std::size_t e = 0; e < low.size(); ++e)
      for (int region : regions_of(fem::dimension(low.type[e]), low.entity[e]))
        for (auto k = low.offsets[e]; k < low.offsets[e + 1]; ++k)
          lower.push_back({low.nodes[k], low.tag[e], region});
    lower = route(comm_, size_, lower, [&](const RegionNode& r) { return node_dir(r.tag); });
    std::string error;
    for (const auto& r : lower) {
      const auto i = dir_index(r.tag);
      if (i < 0 && error.empty())
        error = "mesh '" + c_.file + "': region '" + regions_[r.region].name + "' has node " +
                std::to_string(r.tag) + ", which belongs to no cell of dimension " +
                std::to_string(c_.dim);
      if (i >= 0) node_region.emplace_back(i, r.region);
    }
    agree(comm_, error);
    std::sort(node_region.begin(), node_region.end());
    node_region.erase(std::unique(node_region.begin(), node_region.end()), node_region.end());
    region_offsets_.assign(tags_.size() + 1, 0);
    for (const auto& [i, region] : node_region) ++region_offsets_[i + 1];
    for (std::size_t i = 0; i < tags_.size(); ++i) region_offsets_[i + 1] += region_offsets_[i];
    node_regions_.resize(node_region.size());
    for (std::size_t k = 0; k < node_region.size(); ++k) node_regions_[k] = node_region[k].second;

    // Owners and numbers: per part, in increasing gid (read_mesh's number_nodes).
    owner_.assign(tags_.size(), -1);
    std::vector<Hold> holds;
    for (std::size_t i = 0; i < uses.size();) {
      std::size_t j = i;
      while (j < uses.size() && uses[j].tag == uses[i].tag) ++j;
      owner_[dir_index(uses[i].tag)] = uses[i].part;
      // Every part with a cell here holds all cells here: the ghost layer.
      for (std::size_t a = i; a < j; ++a)
        if (a == i || uses[a].part != uses[a - 1].part)
          for (std::size_t b = i; b < j; ++b)
            holds.push_back(
                {uses[b].cell, uses[a].part,
                 static_cast<std::int32_t>(uses[b].part == uses[a].part ? CellRole::owned
                                                                        : CellRole::ghost)});
      i = j;
    }
    uses = {};
    std::vector<std::int64_t> count(static_cast<std::size_t>(size_), 0), before(count.size(), 0);
    for (auto o : owner_) ++count[o];
    MPI_Exscan(count.data(), before.data(), size_, MPI_INT64_T, MPI_SUM, comm_);
    if (rank_ == 0) std::fill(before.begin(), before.end(), 0);
    std::vector<std::int64_t> total(count.size(), 0);
    MPI_Allreduce(count.data(), total.data(), size_, MPI_INT64_T, MPI_SUM, comm_);
    offsets_.assign(static_cast<std::size_t>(size_) + 1, 0);
    for (int p = 0; p < size_; ++p) offsets_[p + 1] = offsets_[p] + total[p];
    index_.resize(tags_.size());
    for (std::size_t i = 0; i < tags_.size(); ++i)
      index_[i] = offsets_[owner_[i]] + before[owner_[i]]++;

    // Interface cells go to every rank.
    std::vector<char> interface_region(regions_.size(), 0);
    for (std::size_t k = 0; k < regions_.size(); ++k)
      interface_region[k] =
          std::find(interfaces_.begin(), interfaces_.end(), regions_[k].name) != interfaces_.end();
    holds = route(comm_, size_, holds, [&](const Hold& h) { return chunk_of(h.cell); });
    for (const auto& f : facets_)
      if (interface_region[f.region])
        for (int p = 0; p < size_; ++p)
          holds.push_back({f.cell, p, static_cast<std::int32_t>(CellRole::interface)});
    std::sort(holds.begin(), holds.end(), [](const Hold& a, const Hold& b) {
      return std::tie(a.cell, a.part, a.role) < std::tie(b.cell, b.part, b.role);
    });
    holds_.clear();
    for (std::size_t k = 0; k < holds.size(); ++k)
      if (k == 0 || holds[k].cell != holds[k - 1].cell || holds[k].part != holds[k - 1].part)
        holds_.push_back(holds[k]); // the strongest role first
  }

  // Each held cell as words: gid, tag, type, entity, owner, role, nodes, facets (region, local).
  void send_cells() {
    std::vector<std::int64_t> offsets(static_cast<std::size_t>(size_) + 1, 0);
    std::vector<std::vector<std::int64_t>> out(static_cast<std::size_t>(size_));
    const auto& cells = c_.cells;
    for (const auto& h : holds_) {
      const auto c = static_cast<std::size_t>(h.cell - first_[rank_]);
      auto& w = out[h.part];
      w.insert(w.end(), {h.cell, static_cast<std::int64_t>(cells.tag[c]),
                         static_cast<std::int64_t>(cells.type[c]), std::int64_t{cells.entity[c]},
                         std::int64_t{part_[c]}, std::int64_t{h.role},
                         cells.offsets[c + 1] - cells.offsets[c]});
      for (auto k = cells.offsets[c]; k < cells.offsets[c + 1]; ++k)
        w.push_back(static_cast<std::int64_t>(cells.nodes[k]));
      const auto lo =
          std::lower_bound(facets_.begin(), facets_.end(), h.cell,
                           [](const RegionFacet& f, std::int64_t cell) { return f.cell < cell; });
      auto hi = lo;
      while (hi != facets_.end() && hi->cell == h.cell) ++hi;
      w.push_back(hi - lo);
      for (auto f = lo; f != hi; ++f)
        w.insert(w.end(), {std::int64_t{f->region}, std::int64_t{f->local}});
    }
    holds_ = {};
    std::vector<std::int64_t> send;
    for (int p = 0; p < size_; ++p) {
      send.insert(send.end(), out[p].begin(), out[p].end());
      offsets[p + 1] = static_cast<std::int64_t>(send.size());
      out[p] = {};
    }
    std::vector<std::int64_t> from;
    words_ = alltoallv<std::int64_t>(comm_, send, offsets, from);
    c_.cells = MshElements{}; // the chunk's cells have gone where they are held
    c_.lower = MshElements{};
  }

  DistributedMesh assemble() {
    // Held cells by gid (monotone local numbering).
    std::vector<std::size_t> at;
    for (std::size_t k = 0; k < words_.size();) {
      at.push_back(k);
      k += 7 + static_cast<std::size_t>(words_[k + 6]);
      k += 1 + 2 * static_cast<std::size_t>(words_[k]);
    }
    std::sort(at.begin(), at.end(), [&](auto a, auto b) { return words_[a] < words_[b]; });
    std::vector<std::uint64_t> tags;
    for (auto k : at)
      for (std::int64_t a = 0; a < words_[k + 6]; ++a)
        tags.push_back(static_cast<std::uint64_t>(words_[k + 7 + a]));
    std::sort(tags.begin(), tags.end());
    tags.erase(std::unique(tags.begin(), tags.end()), tags.end());

    // Node data from the directory, answered in the order asked.
    std::vector<std::int64_t> from;
    const auto asked = route(
        comm_, size_, tags, [&](std::uint64_t t) { return node_dir(t); }, from);
    std::vector<NodeInfo> info(asked.size());
    std::vector<std::int32_t> region_ids;
    std::vector<std::int64_t> region_send(static_cast<std::size_t>(size_) + 1, 0);
    for (int p = 0; p < size_; ++p) {
      for (auto k = from[p]; k < from[p + 1]; ++k) {
        const auto i = dir_index(asked[k]);
        SEAM_ASSERT(i >= 0);
        auto& n = info[k];
        n.gid = gid_base_ + i;
        n.index = index_[i];
        n.owner = owner_[i];
        n.n_regions = static_cast<std::int32_t>(region_offsets_[i + 1] - region_offsets_[i]);
        for (int a = 0; a < 3; ++a) n.x[a] = x_[3 * i + a];
        region_ids.insert(region_ids.end(), node_regions_.begin() + region_offsets_[i],
                          node_regions_.begin() + region_offsets_[i + 1]);
      }
      region_send[p + 1] = static_cast<std::int64_t>(region_ids.size());
    }
    std::vector<std::int64_t> back;
    info = alltoallv<NodeInfo>(comm_, info, from, back);
    region_ids = alltoallv<std::int32_t>(comm_, region_ids, region_send, back);
    // Answers come grouped by directory rank, which is the order of the sorted tags.

    DistributedMesh d;
    auto& m = d.mesh;
    m.dim = dim_;
    m.regions.resize(regions_.size());
    for (std::size_t r = 0; r < regions_.size(); ++r) {
      m.regions[r].name = regions_[r].name;
      m.regions[r].dim = regions_[r].dim;
      m.regions[r].tag = regions_[r].tag;
    }
    std::size_t next_region = 0;
    for (std::size_t n = 0; n < tags.size(); ++n) {
      const auto& i = info[n];
      for (int a = 0; a < dim_; ++a) m.x.push_back(i.x[a]);
      d.node_gid.push_back(i.gid);
      d.node_owner.push_back(i.owner);
      d.node_index.push_back(i.index);
      for (std::int32_t k = 0; k < i.n_regions; ++k)
        m.regions[region_ids[next_region++]].nodes.push_back(static_cast<std::int32_t>(n));
    }
    std::vector<std::int32_t> nodes;
    std::vector<std::uint64_t> cell_tags;
    for (std::size_t c = 0; c < at.size(); ++c) {
      const auto* w = words_.data() + at[c];
      d.cell_gid.push_back(w[0]);
      cell_tags.push_back(static_cast<std::uint64_t>(w[1]));
      d.cell_owner.push_back(static_cast<int>(w[4]));
      d.cell_role.push_back(static_cast<CellRole>(w[5]));
      nodes.clear();
      for (std::int64_t a = 0; a < w[6]; ++a)
        nodes.push_back(static_cast<std::int32_t>(
            std::lower_bound(tags.begin(), tags.end(), static_cast<std::uint64_t>(w[7 + a])) -
            tags.begin()));
      m.add_cell(static_cast<fem::CellType>(w[2]), nodes);
      const auto lc = static_cast<std::int32_t>(c);
      for (int region : regions_of(dim_, static_cast<int>(w[3])))
        m.regions[region].cells.push_back(lc);
      const auto* f = w + 7 + w[6];
      for (std::int64_t k = 0; k < f[0]; ++k) {
        auto& r = m.regions[f[1 + 2 * k]];
        r.facet_cell.push_back(lc);
        r.facet_local.push_back(static_cast<std::int8_t>(f[2 + 2 * k]));
      }
    }
    words_ = {};
    for (auto& r : m.regions) r.sort_facets();
    d.node_offsets = offsets_;
    d.n_global_nodes = n_nodes_;
    d.n_global_cells = n_cells_;
    check_owned_geometry(d, cell_tags);
    return d;
  }

  // read_mesh's check on inverted or degenerate cells, on the cells this rank owns.
  void check_owned_geometry(const DistributedMesh& d, const std::vector<std::uint64_t>& tags) {
    std::string error;
    std::array<double, 9> J{};
    for (std::int32_t c = 0; c < d.n_cells() && error.empty(); ++c) {
      if (d.cell_role[c] != CellRole::owned) continue;
      const auto type = d.mesh.cell_type[c];
      const auto rule = fem::quadrature(type, fem::default_quadrature_degree(type));
      for (int q = 0; q < rule.n_points && error.empty(); ++q) {
        const double det = jacobian(d.mesh, c, &rule.points[q * rule.dim], J);
        if (!(det > 0.0))
          error =
              ::seam::detail::concat("mesh '", file_, "': element ", tags[c], " (", fem::name(type),
                                     ") is inverted or degenerate: det(dX/dxi) = ", det,
                                     " <= 0 inside it (misordered, coincident or misplaced nodes)");
      }
    }
    agree(comm_, error);
  }

  MPI_Comm comm_;
  int rank_ = 0, size_ = 1;
  std::vector<std::string> interfaces_;
  MshChunk c_;
  std::string file_;
  int dim_ = 0;
  std::int64_t n_cells_ = 0, n_nodes_ = 0, gid_base_ = 0;
  std::vector<std::int64_t> first_; // size + 1: chunk of rank r = cells [first_[r], first_[r+1])
  std::vector<Region> regions_;     // names, dims, tags only
  std::map<std::pair<int, int>, std::vector<int>> entity_regions_;
  // Node directory (this rank's tag range): tags, coordinates, owners, numbers, regions.
  std::vector<std::uint64_t> tags_;
  std::vector<double> x_;
  std::vector<int> owner_;
  std::vector<std::int64_t> index_, region_offsets_, offsets_;
  std::vector<std::int32_t> node_regions_;
  // Chunk cells: dual graph, part, region facets; then the cells to send.
  std::vector<std::int64_t> adjacency_offsets_, adjacency_;
  std::vector<int> part_;
  std::vector<RegionFacet> facets_;
  std::vector<Hold> holds_;
  std::vector<std::int64_t> words_;
};

} // namespace

DistributedMesh distribute_file(const std::filesystem::path& file, MPI_Comm comm,
                                std::span<const std::string> interface_regions, int dim) {
  return Builder(comm, interface_regions).run(file, dim);
}

} // namespace seam::mesh
