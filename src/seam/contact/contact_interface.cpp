#include "seam/contact/contact_interface.hpp"

#include "seam/common/error.hpp"
#include "seam/contact/self_contact.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/mortar/normals.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <numeric>

namespace seam::contact {

namespace {

/// The sum and number of the edge lengths of facets `facets` of `side` (all of them when
/// empty and `all`).
std::pair<double, double> edge_sum(const meshtying::InterfaceSide& side,
                                   std::span<const local_index> facets, bool all) {
  const int dim = side.dim;
  double sum = 0.0;
  long count = 0;
  const local_index n = all ? side.n_facets() : static_cast<local_index>(facets.size());
  for (local_index i = 0; i < n; ++i) {
    const local_index f = all ? i : facets[static_cast<std::size_t>(i)];
    const auto* nodes = &side.nodes[static_cast<std::size_t>(side.offsets[f])];
    const int n = fem::n_vertices(side.types[static_cast<std::size_t>(f)]);
    const int edges = dim == 2 ? 1 : n;
    for (int e = 0; e < edges; ++e) {
      const auto a = static_cast<std::size_t>(nodes[e]) * dim;
      const auto b = static_cast<std::size_t>(nodes[(e + 1) % n]) * dim;
      double d2 = 0.0;
      for (int c = 0; c < dim; ++c) {
        const double d = side.coordinates[a + c] - side.coordinates[b + c];
        d2 += d * d;
      }
      sum += std::sqrt(d2);
      ++count;
    }
  }
  return {sum, static_cast<double>(count)};
}

double mean_edge_length(const meshtying::InterfaceSide& side) {
  const auto [sum, count] = edge_sum(side, {}, true);
  return count > 0 ? sum / count : 0.0;
}

} // namespace

std::pair<double, double>
ContactInterface::slave_edge_sum(std::span<const local_index> facets) const {
  return edge_sum(slave_, facets, false);
}

ContactInterface::ContactInterface(const io::Interface& config, const mesh::Mesh& mesh,
                                   bool slave_part)
    : mesh_(&mesh), name_(config.name),
      rigid_(config.rigid_plane.has_value() || config.rigid_obstacle.has_value()),
      frictional_(config.friction.model != io::FrictionModel::frictionless),
      self_(!config.surface.empty()) {
  SEAM_ASSERT(config.type == io::InterfaceType::contact);
  const int dim = mesh.dim;
  slave_ = self_ ? extract_surface(mesh, config.surface, slave_part)
                 : meshtying::extract_side(mesh, meshtying::side_region(mesh, config.slave));
  if (slave_.n_facets() == 0 && !slave_part)
    io::fail_at(config.slave.mark, "the slave region '" + config.slave.name + "' has no facets");
  mesh_size_ = mean_edge_length(slave_);
  options_.multiplier = config.multiplier == io::Multiplier::dual ? mortar::Multiplier::dual
                                                                  : mortar::Multiplier::standard;
  if (config.rigid_obstacle) {
    const auto& round = *config.rigid_obstacle;
    obstacle_.shape = round.cylinder ? Obstacle::Shape::cylinder : Obstacle::Shape::sphere;
    obstacle_.point = round.point;
    obstacle_.direction = round.axis;
    obstacle_.radius = round.radius;
    plane_motion_ = round.motion;
    master_.dim = dim;
  } else if (rigid_) {
    const auto& plane = *config.rigid_plane;
    master_.dim = dim;
    std::array<double, 3> lo{1e300, 1e300, 1e300}, hi{-1e300, -1e300, -1e300};
    for (std::size_t i = 0; i < slave_.mesh_nodes.size(); ++i)
      for (int c = 0; c < dim; ++c) {
        lo[c] = std::min(lo[c], slave_.coordinates[i * dim + c]);
        hi[c] = std::max(hi[c], slave_.coordinates[i * dim + c]);
      }
    if (slave_.mesh_nodes.empty()) lo = hi = plane.point; // a part without slave facets
    plane_motion_ = plane.motion;
    // The plane only translates: its normal, towards the body, is the contact normal of
    // every slave node (the slave normal points out of the body, at the plane).
    obstacle_.shape = Obstacle::Shape::plane;
    obstacle_.point = plane.point;
    obstacle_.direction = plane.normal;
    span_plane(lo, hi);
  } else if (self_) {
    // Both sides are the whole surface; the pairs say which facet is slave (self_contact.hpp).
    master_ = slave_;
    master_mesh_nodes_ = master_.mesh_nodes;
  } else {
    // Sides that share nodes are refused by problem::ContactConstraint, over the ranks' parts.
    master_ = meshtying::extract_side(mesh, meshtying::side_region(mesh, *config.master));
    master_mesh_nodes_ = master_.mesh_nodes;
  }
  if (!mortar::all_affine(slave_.facet_set()) || !mortar::all_affine(master_.facet_set()))
    options_.pair.cell_quadrature_degree = 8;
  slave_adjacency_ = mortar::node_facets(slave_.facet_set());
  transformation_ =
      mortar::assemble_mortar_operators(slave_.facet_set(), master_.facet_set(), {}, options_).T;
  transformation_inverse_ = mortar::inverse_transformation(transformation_);
  // Candidates up to about one slave element away, so that approaching parts are integrated
  // (and get their weighted gaps) before they touch.
  search_options_.inflation_factor = 0.75;
  current_ = obstacle_;
  if (obstacle_.round()) {
    // No master facets: the candidates come from the analytic distance (update).
    search_options_.inflation = search_options_.inflation_factor * mesh_size_;
  } else if (self_) {
    search_options_.inflation =
        search_options_.inflation_factor * search::min_edge_length(slave_.surface());
    self_tree_ = std::make_unique<search::Tree>(
        self_contact_tree(slave_.surface(), search_options_.inflation));
  } else {
    search_ = std::make_unique<search::InterfaceSearch>(slave_.surface(), master_.surface(),
                                                        search_options_);
    search_options_.inflation = search_->inflation();
  }
  normals_.assign(slave_.coordinates.size(), 0.0);
  pair_offsets_.assign(static_cast<std::size_t>(slave_.n_facets()) + 1, 0);
  owned_.resize(static_cast<std::size_t>(slave_.n_facets()));
  std::iota(owned_.begin(), owned_.end(), local_index{0});
  owned_offsets_ = slave_.offsets;
  owned_nodes_ = slave_.nodes;
}

void ContactInterface::span_plane(const std::array<double, 3>& lo,
                                  const std::array<double, 3>& hi) {
  SEAM_ASSERT(rigid_ && obstacle_.shape == Obstacle::Shape::plane);
  // One master facet that covers every place the slave surface can reach: centred at the
  // projection of the box lo..hi (the slave surface's) onto the plane, ten times its extent.
  const int dim = this->dim();
  const auto& n = obstacle_.direction;
  std::array<double, 3> centre{};
  double diagonal = 0.0, height = 0.0;
  for (int c = 0; c < dim; ++c) {
    centre[c] = 0.5 * (lo[c] + hi[c]);
    diagonal += (hi[c] - lo[c]) * (hi[c] - lo[c]);
    height += (centre[c] - obstacle_.point[c]) * n[c];
  }
  for (int c = 0; c < dim; ++c) centre[c] -= height * n[c];
  const double h = 10.0 * std::sqrt(diagonal) + std::abs(height);
  plane_corners_.clear();
  if (dim == 2) {
    // line2 from c - h t to c + h t with t = (-n_y, n_x): its normal (t_y, -t_x) is n.
    const double t[2] = {-n[1], n[0]};
    plane_corners_ = {centre[0] - h * t[0], centre[1] - h * t[1], centre[0] + h * t[0],
                      centre[1] + h * t[1]};
    master_.types = {fem::CellType::line2};
    master_.offsets = {0, 2};
    master_.nodes = {0, 1};
  } else {
    // quad4 with edges along a and b, a x b = n.
    std::array<double, 3> a{};
    const int axis = std::abs(n[0]) < 0.9 ? 0 : 1;
    std::array<double, 3> e{};
    e[axis] = 1.0;
    a = {e[1] * n[2] - e[2] * n[1], e[2] * n[0] - e[0] * n[2], e[0] * n[1] - e[1] * n[0]};
    const double la = std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
    for (auto& v : a) v /= la;
    const std::array<double, 3> b{n[1] * a[2] - n[2] * a[1], n[2] * a[0] - n[0] * a[2],
                                  n[0] * a[1] - n[1] * a[0]};
    const double s[4][2] = {{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
    for (const auto& st : s)
      for (int c = 0; c < 3; ++c)
        plane_corners_.push_back(centre[c] + h * (st[0] * a[c] + st[1] * b[c]));
    master_.types = {fem::CellType::quad4};
    master_.offsets = {0, 4};
    master_.nodes = {0, 1, 2, 3};
  }
  master_.coordinates = plane_corners_;
  for (std::size_t i = 0; i < plane_corners_.size(); ++i)
    master_.coordinates[i] += obstacle_displacement_[i % static_cast<std::size_t>(dim)];
  search_.reset();
  if (!owned_.empty() && !external_)
    search_ = std::make_unique<search::InterfaceSearch>(
        search::FacetSurface{dim, slave_.coordinates, owned_offsets_, owned_nodes_},
        master_.surface(), search_options_);
}

void ContactInterface::hold_slave_facets(const mesh::Region& region) {
  hold_slave_facets(meshtying::extract_side(*mesh_, region));
}

void ContactInterface::hold_slave_facets(meshtying::InterfaceSide side) {
  forget_prechecked_pairs(); // side-local facet ids of the side dropped
  // The normals of the nodes held before and after are kept (read until the next place()).
  const auto d = static_cast<std::size_t>(dim());
  std::vector<std::pair<std::int32_t, std::size_t>> before(slave_.mesh_nodes.size());
  for (std::size_t i = 0; i < before.size(); ++i) before[i] = {slave_.mesh_nodes[i], i};
  std::sort(before.begin(), before.end());
  std::vector<double> normals(side.mesh_nodes.size() * d, 0.0);
  for (std::size_t j = 0; j < side.mesh_nodes.size(); ++j) {
    const auto it = std::lower_bound(before.begin(), before.end(),
                                     std::pair<std::int32_t, std::size_t>{side.mesh_nodes[j], 0});
    if (it == before.end() || it->first != side.mesh_nodes[j]) continue;
    std::copy_n(normals_.begin() + static_cast<std::ptrdiff_t>(it->second * d), d,
                normals.begin() + static_cast<std::ptrdiff_t>(j * d));
  }
  slave_reference_ = side.coordinates;
  slave_ = std::move(side);
  if (self_) {
    // The surface held in part is both sides; the slave patch follows the next pairs.
    master_ = slave_;
    master_mesh_nodes_ = slave_.mesh_nodes;
    patch_ = {};
  }
  slave_adjacency_ = mortar::node_facets(slave_.facet_set());
  transformation_ =
      mortar::assemble_mortar_operators(slave_.facet_set(), master_.facet_set(), {}, options_).T;
  transformation_inverse_ = mortar::inverse_transformation(transformation_);
  normals_ = std::move(normals);
  all_normals_ = true;
  normal_nodes_.clear();
  pairs_.clear();
  pair_offsets_.assign(static_cast<std::size_t>(slave_.n_facets()) + 1, 0);
  owned_.clear();
  owned_offsets_.assign(1, 0);
  owned_nodes_.clear();
  search_.reset();
}

void ContactInterface::place_slave(meshtying::InterfaceSide& side,
                                   std::span<const double> u) const {
  if (slave_reference_.empty()) {
    side.update_coordinates(*mesh_, u);
    return;
  }
  const auto d = static_cast<std::size_t>(dim());
  side.coordinates = slave_reference_;
  if (u.empty()) return;
  for (std::size_t j = 0; j < side.mesh_nodes.size(); ++j)
    for (std::size_t c = 0; c < d; ++c)
      side.coordinates[j * d + c] += u[static_cast<std::size_t>(side.mesh_nodes[j]) * d + c];
}

void ContactInterface::set_owned_facets(std::vector<local_index> facets) {
  std::sort(facets.begin(), facets.end());
  facets.erase(std::unique(facets.begin(), facets.end()), facets.end());
  SEAM_CHECK(facets.empty() || (facets.front() >= 0 && facets.back() < slave_.n_facets()),
             InputError, "interface '", name_, "': owned slave facet out of range");
  owned_ = std::move(facets);
  owned_offsets_.assign(1, 0);
  owned_nodes_.clear();
  for (const auto f : owned_) {
    const auto nodes = slave_.facet_set().facet_nodes(f);
    owned_nodes_.insert(owned_nodes_.end(), nodes.begin(), nodes.end());
    owned_offsets_.push_back(static_cast<local_index>(owned_nodes_.size()));
  }
  search_.reset();
  if (!owned_.empty() && !self_ && !obstacle_.round() && !external_)
    search_ = std::make_unique<search::InterfaceSearch>(
        search::FacetSurface{dim(), slave_.coordinates, owned_offsets_, owned_nodes_},
        master_.surface(), search_options_);
  pairs_.clear();
  pair_offsets_.assign(static_cast<std::size_t>(slave_.n_facets()) + 1, 0);
}

std::array<double, 3> ContactInterface::slave_centroid(local_index f) const {
  std::array<double, 3> c{};
  const auto nodes = slave_.facet_set().facet_nodes(f);
  for (const auto j : nodes)
    for (int a = 0; a < dim(); ++a)
      c[static_cast<std::size_t>(a)] += slave_.coordinates[static_cast<std::size_t>(j) * dim() + a];
  for (auto& v : c) v /= static_cast<double>(nodes.size());
  return c;
}

void apply_inverse_transformation(std::span<const mortar::Triplet> T_inverse, int dim,
                                  std::span<const double> x, std::span<double> y) {
  const auto n = x.size() / static_cast<std::size_t>(dim);
  std::vector<char> has_row(n, 0);
  for (const auto& e : T_inverse) has_row[static_cast<std::size_t>(e.row)] = 1;
  for (std::size_t j = 0; j < n; ++j)
    for (int c = 0; c < dim; ++c) y[j * dim + c] = has_row[j] ? 0.0 : x[j * dim + c];
  for (const auto& e : T_inverse)
    for (int c = 0; c < dim; ++c)
      y[static_cast<std::size_t>(e.row) * dim + c] +=
          e.value * x[static_cast<std::size_t>(e.col) * dim + c];
}

InverseTransformationRows::InverseTransformationRows(std::span<const mortar::Triplet> T_inverse,
                                                     std::size_t n_nodes)
    : begin_(n_nodes + 1, 0), col_(T_inverse.size()), value_(T_inverse.size()) {
  for (const auto& e : T_inverse) ++begin_[static_cast<std::size_t>(e.row) + 1];
  for (std::size_t k = 0; k < n_nodes; ++k) begin_[k + 1] += begin_[k];
  std::vector<std::size_t> next(begin_.begin(), begin_.end() - 1);
  for (const auto& e : T_inverse) {
    const auto i = next[static_cast<std::size_t>(e.row)]++;
    col_[i] = static_cast<std::size_t>(e.col);
    value_[i] = e.value;
  }
}

std::vector<double> ContactInterface::modified_increment(std::span<const double> step_start) const {
  if (step_start.empty()) return {};
  const int dim = this->dim();
  std::vector<double> dx(slave_.coordinates.size()), out(dx.size());
  for (std::size_t k = 0; k < slave_.mesh_nodes.size(); ++k)
    for (int a = 0; a < dim; ++a) {
      const auto i = static_cast<std::size_t>(slave_.mesh_nodes[k]) * dim + a;
      dx[k * dim + a] = slave_.coordinates[k * dim + a] - reference_x()[i] - step_start[i];
    }
  apply_inverse_transformation(transformation_inverse_, dim, dx, out);
  return out;
}

std::vector<double> ContactInterface::transformed_slave_positions() const {
  std::vector<double> y(slave_.coordinates.size());
  apply_inverse_transformation(transformation_inverse_, dim(), slave_.coordinates, y);
  return y;
}

ContactInterface::~ContactInterface() = default;
ContactInterface::ContactInterface(ContactInterface&&) noexcept = default;
ContactInterface& ContactInterface::operator=(ContactInterface&&) noexcept = default;

std::span<const std::int32_t> ContactInterface::master_nodes() const {
  return master_mesh_nodes_;
}

std::int64_t ContactInterface::mesh_dof_of_master(local_index p) const {
  if (rigid_) return -1;
  return static_cast<std::int64_t>(integration_node(p)) * dim();
}

void ContactInterface::set_master_facets(std::span<const std::int64_t> facet_ids,
                                         std::span<const local_index> offsets,
                                         std::span<const local_index> connectivity,
                                         std::span<const std::int64_t> node_ids,
                                         std::span<const double> coords,
                                         std::span<const std::int32_t> mesh_nodes) {
  SEAM_ASSERT(external_ && !rigid_);
  SEAM_ASSERT(offsets.size() == facet_ids.size() + 1);
  SEAM_ASSERT(std::is_sorted(facet_ids.begin(), facet_ids.end()));
  const int dim = this->dim();
  ghosted_ = true;
  ghost_ids_.assign(facet_ids.begin(), facet_ids.end());
  auto& g = ghost_master_;
  g.dim = dim;
  g.offsets.assign(offsets.begin(), offsets.end());
  g.nodes.assign(connectivity.begin(), connectivity.end());
  g.coordinates.assign(coords.begin(), coords.end());
  if (mesh_nodes.empty()) {
    g.mesh_nodes.resize(node_ids.size());
    for (std::size_t i = 0; i < node_ids.size(); ++i)
      g.mesh_nodes[i] = master_mesh_nodes_[static_cast<std::size_t>(node_ids[i])];
    ghost_side_nodes_.assign(node_ids.begin(), node_ids.end());
  } else {
    g.mesh_nodes.assign(mesh_nodes.begin(), mesh_nodes.end());
    ghost_side_nodes_.clear();
  }
  // The facet type from its node count (dim - 1 dimensional facets of one order each).
  g.types.resize(facet_ids.size());
  for (std::size_t f = 0; f < facet_ids.size(); ++f) {
    const auto n = offsets[f + 1] - offsets[f];
    using fem::CellType;
    CellType t = CellType::point1;
    if (dim == 2)
      t = n == 2 ? CellType::line2 : n == 3 ? CellType::line3 : t;
    else
      t = n == 3   ? CellType::tri3
          : n == 4 ? CellType::quad4
          : n == 6 ? CellType::tri6
          : n == 8 ? CellType::quad8
          : n == 9 ? CellType::quad9
                   : t;
    SEAM_CHECK(t != CellType::point1, InputError, "interface '", name_,
               "': a ghosted master facet has ", n, " nodes");
    g.types[f] = t;
  }
}

void ContactInterface::refresh_master_coordinates() {
  if (!ghosted_) return;
  SEAM_ASSERT(ghost_side_nodes_.size() == ghost_master_.mesh_nodes.size());
  const int dim = this->dim();
  // The side the search cut the ghosts from: the surface of self contact, else the master side.
  const auto& source = self_ ? slave_.coordinates : master_.coordinates;
  auto& x = ghost_master_.coordinates;
  for (std::size_t i = 0; i < ghost_side_nodes_.size(); ++i)
    for (int c = 0; c < dim; ++c)
      x[i * dim + c] = source[static_cast<std::size_t>(ghost_side_nodes_[i]) * dim + c];
}

void ContactInterface::set_master_coordinates(std::span<const double> coords) {
  SEAM_ASSERT(ghosted_ && coords.size() == ghost_master_.coordinates.size());
  ghost_master_.coordinates.assign(coords.begin(), coords.end());
}

local_index ContactInterface::integration_facet(local_index f) const {
  if (!ghosted_) return f;
  const auto it = std::lower_bound(ghost_ids_.begin(), ghost_ids_.end(), std::int64_t{f});
  SEAM_CHECK(it != ghost_ids_.end() && *it == f, InputError, "interface '", name_,
             "': master facet ", f, " of a candidate pair was not ghosted to this rank");
  return static_cast<local_index>(it - ghost_ids_.begin());
}

void ContactInterface::place(std::span<const double> u, double t) {
  const int dim = this->dim();
  place_slave(slave_, u);
  if (rigid_) {
    for (int c = 0; c < dim; ++c) {
      obstacle_displacement_[c] = plane_motion_.empty() ? 0.0 : plane_motion_[c](t);
      current_.point[c] = obstacle_.point[c] + obstacle_displacement_[c];
    }
    for (std::size_t i = 0; i < plane_corners_.size(); ++i)
      master_.coordinates[i] =
          plane_corners_[i] + obstacle_displacement_[i % static_cast<std::size_t>(dim)];
    normals_ = averaged_normals(slave_, all_normals_);
    return;
  }
  // Self contact: the surface is both sides (held in part, it may have nodes beyond the mesh);
  // the normals of the current slave patch are known after the search.
  if (self_) {
    master_.coordinates = slave_.coordinates;
    return;
  }
  master_.update_coordinates(*mesh_, u);
  normals_ = averaged_normals(slave_, all_normals_);
}

void ContactInterface::set_normal_nodes(std::vector<local_index> nodes) {
  SEAM_ASSERT(std::is_sorted(nodes.begin(), nodes.end()));
  all_normals_ = false;
  normal_nodes_ = std::move(nodes);
}

void ContactInterface::set_normals_from_owners(std::span<const double> normals) {
  SEAM_ASSERT(normals.size() == normals_.size());
  if (all_normals_) return;
  const auto dim = static_cast<std::size_t>(this->dim());
  for (std::size_t j = 0; j < normals.size() / dim; ++j) {
    if (std::binary_search(normal_nodes_.begin(), normal_nodes_.end(), static_cast<local_index>(j)))
      continue;
    for (std::size_t c = 0; c < dim; ++c) normals_[j * dim + c] = normals[j * dim + c];
  }
}

std::vector<local_index> ContactInterface::normal_ring(std::span<const local_index> nodes) const {
  std::vector<local_index> ring(nodes.begin(), nodes.end());
  const auto set = slave_.facet_set();
  for (const auto j : nodes)
    for (const auto f : slave_adjacency_.of(j))
      for (const auto k : set.facet_nodes(f)) ring.push_back(k);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  return ring;
}

std::vector<double> ContactInterface::averaged_normals(const meshtying::InterfaceSide& side,
                                                       bool all,
                                                       std::span<const local_index> nodes) const {
  const int dim = this->dim();
  if (rigid_) {
    // The obstacle's normal at the node's closest point, reversed (out of the slave body).
    std::vector<double> n(side.coordinates.size(), 0.0);
    const auto n_nodes = side.mesh_nodes.size();
    for (std::size_t j = 0; j < n_nodes; ++j)
      if (all || std::binary_search(nodes.begin(), nodes.end(), static_cast<local_index>(j)))
        current_.contact_normal(dim, &side.coordinates[j * dim], &n[j * dim], nullptr);
    return n;
  }
  const mortar::FacetSet set = self_ ? patch_.facet_set(side) : side.facet_set();
  if (set.n_facets() == 0) return std::vector<double>(side.coordinates.size(), 0.0);
  if (all) return mortar::averaged_nodal_normals(set);
  // Only the facets around the nodes asked for (of the slave set: the patch on self contact).
  std::vector<local_index> adjacent;
  const auto& adjacency = slave_adjacency();
  for (const auto j : nodes)
    for (const auto f : adjacency.of(j)) adjacent.push_back(f);
  std::sort(adjacent.begin(), adjacent.end());
  adjacent.erase(std::unique(adjacent.begin(), adjacent.end()), adjacent.end());
  return mortar::averaged_nodal_normals(set, adjacent, nodes);
}

std::vector<double> ContactInterface::normals_at(std::span<const double> u,
                                                 std::span<const local_index> nodes) const {
  meshtying::InterfaceSide side = slave_;
  place_slave(side, u);
  return averaged_normals(side, false, nodes);
}

std::int32_t ContactInterface::folded_slave_node(std::span<const double> u) const {
  if (rigid_ || slave_.n_facets() == 0) return -1;
  meshtying::InterfaceSide side = slave_;
  place_slave(side, u);
  const local_index j = mortar::folded_node(side.facet_set());
  return j < 0 ? -1 : side.mesh_nodes[static_cast<std::size_t>(j)];
}

void ContactInterface::use_external_search() {
  SEAM_CHECK(!rigid_, InputError, "interface '", name_,
             "': an external search is for two-body and self-contact interfaces only");
  external_ = true;
  search_.reset();
  self_tree_.reset();
  pairs_.clear();
  index_pairs();
}

void ContactInterface::set_candidates(std::span<const mortar::CandidatePair> pairs) {
  SEAM_ASSERT(external_);
  pairs_.clear();
  if (self_)
    take_self_pairs(pairs);
  else
    keep_facing(pairs);
  index_pairs();
}

void ContactInterface::take_self_pairs(std::span<const mortar::CandidatePair> all) {
  // Each part keeps the pairs of its own slave facets; the slave patch and its normals are
  // those of all pairs.
  // (A pair whose master facet is not among the ghosts, master < 0, only shapes the patch:
  // the pairs of a surface held in part handed in after a redistribution, before the next
  // search.)
  for (const auto& p : all)
    if (p.master >= 0 && std::binary_search(owned_.begin(), owned_.end(), p.slave))
      pairs_.push_back(p);
  build_slave_patch(slave_, all, patch_);
  normals_ = averaged_normals(slave_, all_normals_);
}

void ContactInterface::keep_facing(std::span<const mortar::CandidatePair> pairs) {
  // Only facets that face each other can come into contact.
  const auto& masters = integration_master();
  std::vector<std::array<double, 3>> nm(static_cast<std::size_t>(masters.n_facets()));
  std::vector<char> has_normal(static_cast<std::size_t>(masters.n_facets()), 0);
  for (const auto& p : pairs) {
    SEAM_ASSERT(std::binary_search(owned_.begin(), owned_.end(), p.slave));
    // Against a rigid plane the gap is the distance to the plane for any facet orientation,
    // so every facet near it takes part (no jump in D when a facet turns past 90 degrees).
    if (rigid_) {
      pairs_.push_back(p);
      continue;
    }
    const auto a = facet_normal(slave_, p.slave);
    const auto m = static_cast<std::size_t>(integration_facet(p.master));
    if (!has_normal[m]) {
      nm[m] = facet_normal(masters, static_cast<local_index>(m));
      has_normal[m] = 1;
    }
    const auto& b = nm[m];
    if (a[0] * b[0] + a[1] * b[1] + a[2] * b[2] < 0.0) pairs_.push_back(p);
  }
}

void ContactInterface::update(std::span<const double> u, double t) {
  place(u, t);
  if (external_) return;
  pairs_.clear();
  if (obstacle_.round()) {
    collect_round_candidates();
  } else if (self_) {
    // The whole surface is searched on every part, so that all parts assign the same roles.
    std::vector<mortar::CandidatePair> all;
    self_contact_pairs(*self_tree_, slave_, all);
    take_self_pairs(all);
  } else if (search_) {
    search_->update(slave_.coordinates, master_.coordinates);
    std::vector<mortar::CandidatePair> found;
    for (const auto& p : search_->find_pairs()) // owned -> slave facet
      found.push_back({owned_[static_cast<std::size_t>(p.slave)], p.master});
    keep_facing(found);
  }
  index_pairs();
}

void ContactInterface::index_pairs() {
  std::sort(pairs_.begin(), pairs_.end(), [](const auto& x, const auto& y) {
    return x.slave != y.slave ? x.slave < y.slave : x.master < y.master;
  });
  pair_offsets_.assign(static_cast<std::size_t>(slave_.n_facets()) + 1, 0);
  for (const auto& p : pairs_) ++pair_offsets_[static_cast<std::size_t>(p.slave) + 1];
  for (std::size_t f = 0; f < static_cast<std::size_t>(slave_.n_facets()); ++f)
    pair_offsets_[f + 1] += pair_offsets_[f];
  index_prechecked();
}

void ContactInterface::keep_prechecked_pairs() {
  if (rigid_ || dim() != 2) return;
  const mortar::FacetSet slaves = slave_set();
  const mortar::FacetSet masters = integration_master().facet_set();
  // The chord from end node 0 to end node 1 (line2 and line3): the pre-check's centre normals
  // are the chords turned by 90 degrees, so their dot product is that of the unit chords.
  const auto chord = [](const mortar::FacetSet& set, local_index f) {
    const auto nodes = set.facet_nodes(f);
    const auto a = static_cast<std::size_t>(nodes[0]) * 2,
               b = static_cast<std::size_t>(nodes[1]) * 2;
    return Eigen::Vector2d(set.coordinates[b] - set.coordinates[a],
                           set.coordinates[b + 1] - set.coordinates[a + 1])
        .normalized();
  };
  const std::size_t kept = prechecked_.size();
  for (const auto f : owned_)
    for (const auto& p : pairs_of(f)) {
      const std::pair key(p.slave, p.master);
      if (std::binary_search(prechecked_.begin(), prechecked_.begin() + kept, key)) continue;
      if (chord(slaves, slave_index(p.slave)).dot(chord(masters, integration_facet(p.master))) <
          options_.pair.max_normal_alignment_2d)
        prechecked_.push_back(key);
    }
  if (prechecked_.size() == kept) return;
  std::sort(prechecked_.begin(), prechecked_.end());
  prechecked_.erase(std::unique(prechecked_.begin(), prechecked_.end()), prechecked_.end());
  index_prechecked();
}

void ContactInterface::forget_prechecked_pairs() {
  prechecked_.clear();
  options_.prechecked.clear();
}

void ContactInterface::index_prechecked() {
  options_.prechecked.clear();
  if (prechecked_.empty()) return;
  for (const auto f : owned_)
    for (const auto& p : pairs_of(f))
      if (std::binary_search(prechecked_.begin(), prechecked_.end(), std::pair(p.slave, p.master)))
        options_.prechecked.emplace_back(slave_index(p.slave), integration_facet(p.master));
  std::sort(options_.prechecked.begin(), options_.prechecked.end());
}

void ContactInterface::evaluate(NodalValues& out) const {
  const auto n_slave = static_cast<std::size_t>(n_slave_nodes());
  out.D.assign(n_slave, 0.0);
  out.gap.assign(n_slave, 0.0);
  out.M.clear();
  out.D_coupling.clear();
  out.area = 0.0;
  out.n_pairs = 0;
  out.n_cells = 0;
  out.facet_cells.assign(static_cast<std::size_t>(slave_.n_facets()), 0);
  if (rigid_) {
    evaluate_rigid(out);
    return;
  }
  std::vector<mortar::CandidatePair> mine;
  for (const auto f : owned_)
    for (auto i = pair_offsets_[static_cast<std::size_t>(f)];
         i < pair_offsets_[static_cast<std::size_t>(f) + 1]; ++i)
      mine.push_back({slave_index(pairs_[static_cast<std::size_t>(i)].slave),
                      integration_facet(pairs_[static_cast<std::size_t>(i)].master)});
  if (mine.empty()) return;
  const auto ops = mortar::assemble_mortar_operators(slave_set(), integration_master().facet_set(),
                                                     mine, options_);
  for (const auto& e : ops.D) {
    if (e.row == e.col)
      out.D[static_cast<std::size_t>(e.row)] += e.value;
    else if (standard() && e.value != 0.0)
      out.D_coupling.push_back(e);
  }
  for (std::size_t j = 0; j < n_slave; ++j) out.gap[j] = ops.weighted_gap[j];
  if (!rigid_)
    for (const auto& e : ops.M) out.M.push_back({e.row, integration_node(e.col), e.value});
  out.area = ops.integrated_area;
  for (local_index f = 0; f < slave_.n_facets(); ++f)
    if (const auto k = slave_index(f); k >= 0)
      out.facet_cells[static_cast<std::size_t>(f)] =
          ops.slave_facet_cells[static_cast<std::size_t>(k)];
  out.n_pairs = ops.n_pairs_integrated;
  out.n_cells = ops.n_integration_cells;
}

void ContactInterface::add_force(const NodalValues& values, std::span<const double> lambda,
                                 std::span<double> force) const {
  const int dim = this->dim();
  // The multiplier vector of slave node j: lambda_n,j n_j, or the Cartesian one.
  const auto add = [&](std::size_t row, double scale, std::size_t j) {
    if (scale == 0.0) return;
    for (int c = 0; c < dim; ++c)
      force[row + c] +=
          frictional_ ? scale * lambda[j * dim + c] : scale * lambda[j] * normals_[j * dim + c];
  };
  for (std::size_t j = 0; j < slave_.mesh_nodes.size(); ++j)
    add(static_cast<std::size_t>(slave_.mesh_nodes[j]) * dim, values.D[j], j);
  for (const auto& e : values.D_coupling)
    add(static_cast<std::size_t>(slave_.mesh_nodes[static_cast<std::size_t>(e.col)]) * dim, e.value,
        static_cast<std::size_t>(e.row));
  for (const auto& e : values.M)
    add(static_cast<std::size_t>(e.master_node) * dim, -e.value, static_cast<std::size_t>(e.slave));
}

std::array<double, 3> ContactInterface::plane_displacement() const {
  return obstacle_displacement_;
}

void ContactInterface::collect_round_candidates() {
  const int dim = this->dim();
  const double inflation = search_options_.inflation;
  for (const auto f : owned_) {
    // The facet lies in the ball about its centroid through its farthest node: it can reach
    // the surface only if the centroid is within that radius (plus the inflation) of it.
    const auto centre = slave_centroid(f);
    double reach = 0.0;
    for (const auto j : slave_.facet_set().facet_nodes(f)) {
      double d2 = 0.0;
      for (int c = 0; c < dim; ++c) {
        const double d = slave_.coordinates[static_cast<std::size_t>(j) * dim + c] - centre[c];
        d2 += d * d;
      }
      reach = std::max(reach, std::sqrt(d2));
    }
    const auto at = [&](int c) { return centre[static_cast<std::size_t>(c)]; };
    const double g = dim == 2 ? current_.distance<double, 2>(at) : current_.distance<double, 3>(at);
    if (g < reach + inflation) pairs_.push_back({f, 0});
  }
}

void ContactInterface::normal_jacobian(local_index j, std::vector<DofTriplet>& out) const {
  const int dim = this->dim();
  if (rigid_) {
    // The obstacle's normal moves with the node's closest point on a round surface.
    double n[3], jac[9];
    current_.contact_normal(dim, &slave_.coordinates[static_cast<std::size_t>(j) * dim], n, jac);
    const auto dof0 =
        static_cast<std::int64_t>(slave_.mesh_nodes[static_cast<std::size_t>(j)]) * dim;
    for (int a = 0; a < dim; ++a)
      for (int b = 0; b < dim; ++b)
        if (jac[a * dim + b] != 0.0) out.push_back({a, dof0 + b, jac[a * dim + b]});
    return;
  }
  mortar::NodalNormalLinearization lin;
  mortar::linearize_nodal_normal(slave_set(), j, slave_adjacency().of(j), lin);
  const auto n = lin.nodes.size();
  for (int a = 0; a < dim; ++a)
    for (std::size_t i = 0; i < n; ++i)
      for (int b = 0; b < dim; ++b) {
        const double v = lin.jacobian[static_cast<std::size_t>(a * dim) * n + dim * i + b];
        if (v != 0.0)
          out.push_back({a,
                         static_cast<std::int64_t>(
                             slave_.mesh_nodes[static_cast<std::size_t>(lin.nodes[i])]) *
                                 dim +
                             b,
                         v});
      }
}

void ContactInterface::rigid_facet(local_index f, bool derivatives, RigidObstacleFacet& out) const {
  if (dim() == 2) {
    rigid_obstacle_facet<2>(mortar::gather_facet<2>(slave_.facet_set(), f), current_,
                            options_.multiplier, derivatives, out);
  } else {
    rigid_obstacle_facet<3>(mortar::gather_facet<3>(slave_.facet_set(), f), current_,
                            options_.multiplier, derivatives, out);
  }
}

void ContactInterface::evaluate_rigid(NodalValues& out) const {
  RigidObstacleFacet rf;
  for (const auto f : owned_) {
    if (pair_offsets_[static_cast<std::size_t>(f)] ==
        pair_offsets_[static_cast<std::size_t>(f) + 1])
      continue;
    rigid_facet(f, false, rf);
    const auto nodes = slave_.facet_set().facet_nodes(f);
    for (int j = 0; j < rf.n; ++j) {
      const auto sj = nodes[static_cast<std::size_t>(j)];
      out.D[static_cast<std::size_t>(sj)] += rf.D[static_cast<std::size_t>(j * rf.n + j)];
      out.gap[static_cast<std::size_t>(sj)] += rf.gap[static_cast<std::size_t>(j)];
      if (!standard()) continue;
      for (int k = 0; k < rf.n; ++k) {
        const double v = rf.D[static_cast<std::size_t>(j * rf.n + k)];
        if (k != j && v != 0.0)
          out.D_coupling.push_back({sj, nodes[static_cast<std::size_t>(k)], v});
      }
    }
    out.area += rf.area;
    ++out.n_pairs;
    ++out.n_cells;
    out.facet_cells[static_cast<std::size_t>(f)] = 1;
  }
}

bool ContactInterface::carries_multiplier(std::span<const double> lambda, local_index j) const {
  if (!frictional_) return lambda[static_cast<std::size_t>(j)] != 0.0;
  for (int c = 0; c < dim(); ++c)
    if (lambda[static_cast<std::size_t>(j) * dim() + c] != 0.0) return true;
  return false;
}

double ContactInterface::multiplier(std::span<const double> lambda, std::size_t j, int c) const {
  const auto d = static_cast<std::size_t>(dim());
  return frictional_ ? lambda[j * d + c] : lambda[j] * normals_[j * d + c];
}

void ContactInterface::linearize_rigid(std::span<const double> lambda,
                                       std::span<const char> want_gap, Linearization& out,
                                       std::span<const double> step_start) const {
  const int dim = this->dim();
  RigidObstacleFacet rf;
  std::vector<std::int64_t> column;
  const auto increment = modified_increment(step_start);
  const InverseTransformationRows rows(step_start.empty() ? std::span<const mortar::Triplet>{}
                                                          : transformation_inverse_,
                                       slave_.mesh_nodes.size());
  for (const auto f : owned_) {
    if (pair_offsets_[static_cast<std::size_t>(f)] ==
        pair_offsets_[static_cast<std::size_t>(f) + 1])
      continue;
    const auto nodes = slave_.facet_set().facet_nodes(f);
    bool needed = false;
    for (const auto j : nodes) needed = needed || carries_multiplier(lambda, j) || want_gap[j];
    if (!needed) continue;
    rigid_facet(f, true, rf);
    const int n = rf.n, nv = rf.n_variables;
    column.resize(static_cast<std::size_t>(nv));
    for (int i = 0; i < n; ++i)
      for (int b = 0; b < dim; ++b)
        column[static_cast<std::size_t>(dim * i + b)] =
            static_cast<std::int64_t>(
                slave_.mesh_nodes[static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)])]) *
                dim +
            b;
    const auto push_row = [&](std::vector<DofTriplet>& to, std::int64_t row, const double* g,
                              double scale) {
      for (int v = 0; v < nv; ++v)
        if (g[v] != 0.0) to.push_back({row, column[static_cast<std::size_t>(v)], scale * g[v]});
    };
    for (int j = 0; j < n; ++j) {
      const auto sj = static_cast<std::size_t>(nodes[static_cast<std::size_t>(j)]);
      if (want_gap[sj]) {
        push_row(out.gap_gradient, static_cast<std::int64_t>(sj),
                 rf.dgap.data() + static_cast<std::size_t>(j * nv), 1.0);
        // The nodal weight sum_k D_jk with standard multipliers (D_jj with dual ones).
        if (frictional_)
          for (int k = standard() ? 0 : j; k < (standard() ? n : j + 1); ++k) {
            const double* dD = rf.dD.data() + static_cast<std::size_t>((j * n + k) * nv);
            push_row(out.D_gradient, static_cast<std::int64_t>(sj), dD, 1.0);
            if (step_start.empty()) continue;
            // Energy-momentum friction: d(sum_k D_jk dx~_k) at fixed dx.
            const auto sk = static_cast<std::size_t>(nodes[static_cast<std::size_t>(k)]);
            for (int a = 0; a < dim; ++a)
              push_row(out.operator_gradient, static_cast<std::int64_t>(sj * dim) + a, dD,
                       increment[sk * dim + static_cast<std::size_t>(a)]);
          }
      }
      if (!carries_multiplier(lambda, static_cast<local_index>(sj))) continue;
      // Frictionless against a round obstacle the multiplier vector lambda_n,j n_j turns with
      // the normal at node j: D_jk lambda_n,j dn_j/dx_j (a plane's normal is constant).
      double dn[9] = {};
      const bool turning = !frictional_ && obstacle_.round();
      if (turning) {
        double nj[3];
        current_.contact_normal(dim, &slave_.coordinates[sj * dim], nj, dn);
      }
      const auto dof_j = static_cast<std::int64_t>(slave_.mesh_nodes[sj]) * dim;
      // Slave node k: D_jk lambda_j (dual: k = j only); energy-momentum friction: on the
      // nodes m by (T^-1)_km.
      for (int k = standard() ? 0 : j; k < (standard() ? n : j + 1); ++k) {
        const auto sk = static_cast<std::size_t>(nodes[static_cast<std::size_t>(k)]);
        const double* dD = rf.dD.data() + static_cast<std::size_t>((j * n + k) * nv);
        rows.visit(sk, [&](std::size_t m, double t) {
          const auto row0 = static_cast<std::int64_t>(slave_.mesh_nodes[m]) * dim;
          for (int a = 0; a < dim; ++a)
            push_row(out.force_tangent, row0 + a, dD, t * multiplier(lambda, sj, a));
        });
        const auto row0 = static_cast<std::int64_t>(slave_.mesh_nodes[sk]) * dim;
        if (!turning) continue;
        const double scale = rf.D[static_cast<std::size_t>(j * n + k)] * lambda[sj];
        for (int a = 0; a < dim; ++a)
          for (int b = 0; b < dim; ++b)
            if (scale * dn[a * dim + b] != 0.0)
              out.force_tangent.push_back({row0 + a, dof_j + b, scale * dn[a * dim + b]});
      }
    }
  }
}

void ContactInterface::linearize(std::span<const double> lambda, std::span<const char> want_gap,
                                 Linearization& out, std::span<const double> step_start) const {
  const int dim = this->dim();
  out.force_tangent.clear();
  out.gap_gradient.clear();
  out.D_gradient.clear();
  out.operator_gradient.clear();
  if (rigid_) {
    linearize_rigid(lambda, want_gap, out, step_start);
    return;
  }
  mortar::SlaveFacetLinearization lin;
  // D_jj multiplies the positions of the modified basis in the slip increment (with
  // `step_start`: their increments in the step).
  const std::vector<double> x_slave =
      frictional_ && step_start.empty() ? transformed_slave_positions() : std::vector<double>{};
  const auto increment = modified_increment(step_start);
  const InverseTransformationRows rows(step_start.empty() ? std::span<const mortar::Triplet>{}
                                                          : transformation_inverse_,
                                       slave_.mesh_nodes.size());
  std::vector<local_index> masters;
  std::vector<std::int64_t> column; // mesh dof of every variable, -1 for rigid ones
  for (const auto f : owned_) {
    const auto begin = pair_offsets_[static_cast<std::size_t>(f)];
    const auto end = pair_offsets_[static_cast<std::size_t>(f) + 1];
    if (begin == end) continue;
    const auto nodes = slave_.facet_set().facet_nodes(f);
    bool needed = false;
    for (const auto j : nodes) needed = needed || carries_multiplier(lambda, j) || want_gap[j];
    if (!needed) continue;
    masters.clear();
    for (auto i = begin; i < end; ++i)
      masters.push_back(integration_facet(pairs_[static_cast<std::size_t>(i)].master));
    mortar::linearize_slave_facet(slave_set(), integration_master().facet_set(), slave_adjacency(),
                                  slave_index(f), masters, options_, lin);
    if (lin.n_pairs_integrated == 0) continue;
    const int nv = lin.n_variables();
    column.assign(static_cast<std::size_t>(nv), -1);
    const auto n_sv = lin.slave_nodes.size();
    for (std::size_t i = 0; i < n_sv; ++i)
      for (int b = 0; b < dim; ++b)
        column[i * dim + b] = static_cast<std::int64_t>(
                                  slave_.mesh_nodes[static_cast<std::size_t>(lin.slave_nodes[i])]) *
                                  dim +
                              b;
    for (int p = 0; p < lin.n_master_nodes(); ++p) {
      const auto d = mesh_dof_of_master(lin.master_nodes[static_cast<std::size_t>(p)]);
      for (int b = 0; b < dim; ++b)
        column[(n_sv + static_cast<std::size_t>(p)) * dim + b] = d < 0 ? -1 : d + b;
    }
    const int ns = lin.n_slave;
    // to += sa a + sb b over the variables that are mesh dofs (b optional).
    const auto add_row = [&](std::vector<DofTriplet>& to, std::int64_t row,
                             std::span<const double> a, double sa, const double* b, double sb) {
      for (int v = 0; v < nv; ++v) {
        const double value = sa * a[static_cast<std::size_t>(v)] + (b ? sb * b[v] : 0.0);
        if (value != 0.0 && column[static_cast<std::size_t>(v)] >= 0)
          to.push_back({row, column[static_cast<std::size_t>(v)], value});
      }
    };
    for (int j = 0; j < ns; ++j) {
      const auto sj = static_cast<std::size_t>(lin.slave_nodes[static_cast<std::size_t>(j)]);
      if (want_gap[sj]) {
        add_row(out.gap_gradient, static_cast<std::int64_t>(sj), lin.dgap(j), 1.0, nullptr, 0.0);
        if (frictional_) {
          // Standard multipliers: the nodal weight sum_k D_jk and sum_k D_jk x_k take the
          // place of D_jj and D_jj x~_j (dual: k = j only).
          const int k_begin = standard() ? 0 : j, k_end = standard() ? ns : j + 1;
          for (int k = k_begin; k < k_end; ++k)
            add_row(out.D_gradient, static_cast<std::int64_t>(sj), lin.dD(j, k), 1.0, nullptr, 0.0);
          // d(sum_p M_jp x_p - sum_k D_jk x~_k) at fixed x, component by component.
          for (int a = 0; a < dim; ++a) {
            const auto row = static_cast<std::int64_t>(sj * dim) + a;
            for (int k = k_begin; k < k_end; ++k) {
              const auto sk =
                  static_cast<std::size_t>(lin.slave_nodes[static_cast<std::size_t>(k)]);
              // With step_start: +dx~_k (the operators applied to the step's increment).
              const double w = step_start.empty()
                                   ? -x_slave[sk * dim + static_cast<std::size_t>(a)]
                                   : increment[sk * dim + static_cast<std::size_t>(a)];
              add_row(out.operator_gradient, row, lin.dD(j, k), w, nullptr, 0.0);
            }
            for (int p = 0; p < lin.n_master_nodes(); ++p) {
              const auto mp =
                  static_cast<std::size_t>(lin.master_nodes[static_cast<std::size_t>(p)]);
              const double xp =
                  integration_master().coordinates[mp * dim + static_cast<std::size_t>(a)];
              double w = xp;
              if (!step_start.empty()) {
                const auto d = mesh_dof_of_master(lin.master_nodes[static_cast<std::size_t>(p)]);
                w = d < 0 ? 0.0
                          : -(xp - reference_x()[static_cast<std::size_t>(d + a)] -
                              step_start[static_cast<std::size_t>(d + a)]);
              }
              add_row(out.operator_gradient, row, lin.dM(j, p), w, nullptr, 0.0);
            }
          }
        }
      }
      if (!carries_multiplier(lambda, static_cast<local_index>(sj))) continue;
      // Frictionless: the multiplier vector lambda_n,j n_j moves with the normal, whose
      // derivative enters; a frictional (Cartesian) multiplier is fixed.
      const double lambda_n = frictional_ ? 0.0 : lambda[sj];
      // Slave node k: D_jk lambda_j; derivative dD_jk lambda_j (+ D_jk lambda_n,j dn_j).
      for (int k = 0; k < ns; ++k) {
        const double Djk = lin.D[static_cast<std::size_t>(j * ns + k)];
        const auto sk = static_cast<std::size_t>(lin.slave_nodes[static_cast<std::size_t>(k)]);
        // Energy-momentum friction: on the nodes m by (T^-1)_km.
        rows.visit(sk, [&](std::size_t m, double t) {
          const auto row0 = static_cast<std::int64_t>(slave_.mesh_nodes[m]) * dim;
          for (int a = 0; a < dim; ++a)
            add_row(out.force_tangent, row0 + a, lin.dD(j, k), t * multiplier(lambda, sj, a),
                    lin.normal_jacobian.data() + static_cast<std::size_t>(j * dim + a) * nv,
                    t * lambda_n * Djk);
        });
      }
      // Master node p: -M_jp lambda_j.
      for (int p = 0; p < lin.n_master_nodes(); ++p) {
        const auto row0 = mesh_dof_of_master(lin.master_nodes[static_cast<std::size_t>(p)]);
        if (row0 < 0) continue;
        const double Mjp = lin.M[static_cast<std::size_t>(j * lin.n_master_nodes() + p)];
        for (int a = 0; a < dim; ++a)
          add_row(out.force_tangent, row0 + a, lin.dM(j, p), -multiplier(lambda, sj, a),
                  lin.normal_jacobian.data() + static_cast<std::size_t>(j * dim + a) * nv,
                  -lambda_n * Mjp);
      }
    }
  }
}

} // namespace seam::contact
