#include "seam/search/interface_search.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <cstdint>
#include <numeric>
#include <utility>
#include <variant>

namespace seam::search {

namespace {

TreeOptions tree_options(const FacetSurface& slave, const FacetSurface& master,
                         const SearchOptions& options) {
  check_surface(slave);
  check_surface(master);
  SEAM_CHECK(slave.dim == master.dim, InputError, "search: slave surface is ", slave.dim,
             "D, master surface ", master.dim, "D");
  SEAM_CHECK(options.inflation_factor >= 0.0, InputError,
             "search: inflation_factor must be >= 0, got ", options.inflation_factor);
  TreeOptions t;
  t.volume = options.volume;
  t.rebuild_factor = options.rebuild_factor;
  if (options.inflation >= 0.0) {
    t.inflation = options.inflation;
    return t;
  }
  double l_min = 0.0;
  const double ls = min_edge_length(slave), lm = min_edge_length(master);
  if (ls > 0.0 && lm > 0.0)
    l_min = std::min(ls, lm);
  else
    l_min = std::max(ls, lm);
  t.inflation = options.inflation_factor * l_min;
  return t;
}

} // namespace

InterfaceSearch::InterfaceSearch(const FacetSurface& slave, const FacetSurface& master,
                                 const SearchOptions& options)
    : InterfaceSearch(slave, master, tree_options(slave, master, options)) {}

InterfaceSearch::InterfaceSearch(const FacetSurface& slave, const FacetSurface& master,
                                 const TreeOptions& options)
    : slave_(slave, options), master_(master, options) {}

void InterfaceSearch::update(std::span<const double> slave_coords,
                             std::span<const double> master_coords,
                             std::span<const double> slave_old_coords,
                             std::span<const double> master_old_coords) {
  slave_.update(slave_coords, slave_old_coords);
  master_.update(master_coords, master_old_coords);
}

const std::vector<CandidatePair>& InterfaceSearch::find_pairs() {
  search::find_pairs(slave_, master_, pairs_);
  return pairs_;
}

std::vector<BodyPair> find_body_pairs(std::span<const Tree> bodies, bool include_self,
                                      const SelfContactOptions& options) {
  std::vector<BodyPair> out;
  std::vector<CandidatePair> pairs;
  const int n = static_cast<int>(bodies.size());
  for (int a = 0; a < n; ++a) {
    if (include_self) {
      find_self_pairs(bodies[a], pairs, options);
      for (const auto& p : pairs) out.push_back({a, p.slave, a, p.master});
    }
    // The traversal starts with a root-root test, so far-apart bodies cost one test each.
    for (int b = a + 1; b < n; ++b) {
      find_pairs(bodies[a], bodies[b], pairs);
      for (const auto& p : pairs) out.push_back({a, p.slave, b, p.master});
    }
  }
  return out;
}

std::vector<CandidatePair> assign_roles(const Tree& tree, std::span<const CandidatePair> pairs) {
  SEAM_CHECK(tree.options().normal_cones, InputError,
             "search: assign_roles needs a tree built with normal_cones = true");
  const local_index n = tree.n_facets();
  // Facet normal (axis of the leaf cone) of every facet.
  std::vector<std::array<double, 3>> axis(n);
  std::visit(
      [&](const auto& b) {
        for (local_index s = 0; s < n; ++s) axis[b.facet_of_slot[s]] = b.facet_cones[s].axis;
      },
      tree.bvh());
  return assign_roles(axis, pairs);
}

std::vector<CandidatePair> assign_roles(std::span<const std::array<double, 3>> axis,
                                        std::span<const CandidatePair> pairs) {
  std::vector<Role> roles(axis.size(), Role::none);
  return assign_roles(axis, pairs, roles);
}

std::vector<CandidatePair> assign_roles(std::span<const std::array<double, 3>> axis,
                                        std::span<const CandidatePair> pairs,
                                        std::span<Role> roles) {
  const auto n = static_cast<local_index>(axis.size());
  SEAM_CHECK(roles.size() == axis.size(), InternalError, "search: ", roles.size(), " roles for ", n,
             " facets");
  std::vector<std::pair<double, std::size_t>> order(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto& p = pairs[k];
    SEAM_CHECK(p.slave >= 0 && p.slave < n && p.master >= 0 && p.master < n, InputError,
               "search: pair (", p.slave, ", ", p.master, ") outside ", n, " facets");
    const auto& a = axis[p.slave];
    const auto& b = axis[p.master];
    order[k] = {a[0] * b[0] + a[1] * b[1] + a[2] * b[2], k}; // most opposed first
  }
  std::sort(order.begin(), order.end());

  // Union-find with parity: parity[f] is f's role relative to its parent (0 same, 1 other).
  // Node n stands for the role slave: the facets with a role hang from it with their role as
  // parity, so that every group joined to one of them is coloured around the roles kept.
  std::vector<local_index> parent(static_cast<std::size_t>(n) + 1);
  std::iota(parent.begin(), parent.end(), 0);
  std::vector<std::uint8_t> parity(static_cast<std::size_t>(n) + 1, 0);
  for (local_index f = 0; f < n; ++f)
    if (roles[f] != Role::none) {
      parent[f] = n;
      parity[f] = static_cast<std::uint8_t>(roles[f]);
    }
  auto find = [&](local_index f) {
    std::uint8_t par = 0;
    local_index r = f;
    while (parent[r] != r) {
      par ^= parity[r];
      r = parent[r];
    }
    // Path compression, keeping each node's parity relative to the root.
    std::uint8_t p_f = par;
    while (parent[f] != r) {
      const local_index next = parent[f];
      const std::uint8_t p_next = p_f ^ parity[f];
      parent[f] = r;
      parity[f] = p_f;
      f = next;
      p_f = p_next;
    }
    return std::pair{r, par};
  };
  for (const auto& [weight, k] : order) {
    const auto [ra, pa] = find(pairs[k].slave);
    const auto [rb, pb] = find(pairs[k].master);
    if (ra == rb) continue; // consistent already, or an odd cycle: left as it is
    parent[rb] = ra;
    parity[rb] = static_cast<std::uint8_t>(pa ^ pb ^ 1); // opposite roles across the pair
  }
  // The group of the roles kept is coloured by them (node n slave); each other connected group
  // of pairs so that its lowest facet number is slave: the roles then depend only on which
  // facets meet, not on the order of the pairs, and a slave patch stays slave while its contact
  // zone persists.
  std::vector<std::uint8_t> flip(static_cast<std::size_t>(n) + 1, 2); // per root (2: unset)
  {
    const auto [r, par] = find(n);
    flip[r] = par;
  }
  std::vector<char> paired(n, 0);
  for (const auto& p : pairs) paired[p.slave] = paired[p.master] = 1;
  for (local_index f = 0; f < n; ++f)
    if (paired[f]) {
      const auto [r, par] = find(f);
      if (flip[r] == 2) flip[r] = par;
    }
  const auto role = [&](local_index f) {
    const auto [r, par] = find(f);
    return static_cast<std::uint8_t>(par ^ flip[r]);
  };
  std::vector<CandidatePair> out;
  out.reserve(pairs.size());
  for (const auto& p : pairs) {
    const local_index lo = std::min(p.slave, p.master), hi = std::max(p.slave, p.master);
    const std::uint8_t role_lo = role(lo), role_hi = role(hi);
    if (role_lo == role_hi || role_lo == 0)
      out.push_back({lo, hi});
    else
      out.push_back({hi, lo});
  }
  for (local_index f = 0; f < n; ++f)
    if (paired[f] && roles[f] == Role::none) roles[f] = static_cast<Role>(role(f));
  return out;
}

} // namespace seam::search
