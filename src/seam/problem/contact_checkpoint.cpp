// The contact and friction state in checkpoints (checkpoint.hpp): what a converged step
// leaves for the next one. Multipliers, the active set and the stick/slip status are kept per
// slave node of each side (replicated on every rank); the operators of the last converged step
// for the objective slip increment, D^n (replicated), the slave positions x^n and the rigid
// plane's displacement, and M^n, which each rank holds in part (its slave elements), as
// (slave node, master node, value) triplets gathered from all ranks: any number of ranks can
// reload them, each taking a share, since only the sum over the ranks enters (the slip
// increment is summed, the tangent rows are added into the matrix).
#include "seam/common/collective.hpp"
#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/problem/checkpoint.hpp"
#include "seam/problem/contact_constraint.hpp"

#include <algorithm>
#include <unordered_map>

namespace seam::problem {

namespace {

template <class T> std::vector<std::int64_t> to_integers(const std::vector<T>& v) {
  return std::vector<std::int64_t>(v.begin(), v.end());
}

} // namespace

void ContactConstraint::write_checkpoint(RecordWriter& out) const {
  // Slave nodes by their ids in the mesh as read (the same on any number of ranks).
  const auto node_ids = [&](const auto& nodes) {
    std::vector<std::int64_t> ids;
    for (const auto node : nodes) ids.push_back(disc_.node_gid(node));
    return ids;
  };
  const auto& comm = disc_.comm();
  for (std::size_t k = 0; k < sides_.size(); ++k) {
    const auto& s = sides_[k];
    const std::string p = "contact." + std::to_string(k) + ".";
    out.put(p + "slave_nodes", node_ids(s.itf.slave().mesh_nodes));
    out.put(p + "lambda", s.lambda_saved);
    out.put(p + "active", to_integers(s.active));
    if (!s.friction) continue;
    out.put(p + "status", to_integers(s.status));
    out.put(p + "D_old", s.D_diag_old);
    // Each rank reads the positions of the nodes it evaluates only: the owners' x^n.
    std::vector<double> x_old = s.x_old;
    parallel::publish_from_owners(comm.get(), s.node_keys, s.node_owners, x_old, disc_.dim());
    out.put(p + "x_old", x_old);
    out.put(p + "plane_old", std::span<const double>(s.plane_old));
    out.put_real(p + "dissipation", s.dissipation);
    out.put_integer(p + "has_old", s.has_old ? 1 : 0);
    std::vector<std::int64_t> slave, master;
    std::vector<double> value;
    for (const auto& e : s.M_old) {
      slave.push_back(e.slave);
      master.push_back(disc_.node_gid(e.master_node));
      value.push_back(e.value);
    }
    out.put(p + "M_old.slave", gather_to_root(comm, slave));
    out.put(p + "M_old.master", gather_to_root(comm, master));
    out.put(p + "M_old.value", gather_to_root(comm, value));
    // Standard multipliers: this rank's entries D_jk (j != k) of the last converged step.
    std::vector<std::int64_t> row, col;
    std::vector<double> coupling;
    for (const auto& e : s.D_coupling_old) {
      row.push_back(e.row);
      col.push_back(e.col);
      coupling.push_back(e.value);
    }
    out.put(p + "D_coupling_old.row", gather_to_root(comm, row));
    out.put(p + "D_coupling_old.col", gather_to_root(comm, col));
    out.put(p + "D_coupling_old.value", gather_to_root(comm, coupling));
  }
}

void ContactConstraint::read_checkpoint(const RecordReader& in) {
  // Slave nodes by their ids in the mesh as read (the same on any number of ranks).
  const auto node_ids = [&](const auto& nodes) {
    std::vector<std::int64_t> ids;
    for (const auto node : nodes) ids.push_back(disc_.node_gid(node));
    return ids;
  };
  const auto& comm = disc_.comm();
  const int dim = disc_.dim();
  for (std::size_t k = 0; k < sides_.size(); ++k) {
    auto& s = sides_[k];
    const std::string p = "contact." + std::to_string(k) + ".";
    const auto& nodes = s.itf.slave().mesh_nodes;
    const auto n = nodes.size();
    if (in.integers(p + "slave_nodes") != node_ids(nodes))
      in.fail("contact interface " + std::to_string(k + 1) +
              " has other slave nodes than the input's");
    const std::size_t per_node = s.friction ? static_cast<std::size_t>(dim) : 1;
    s.lambda = in.reals(p + "lambda", n * per_node);
    s.lambda_saved = s.lambda;
    for (std::size_t j = 0; const auto a : in.integers(p + "active", n)) s.active[j++] = a != 0;
    s.active_previous = s.active;
    s.active_accepted = s.active;
    if (s.friction != in.has(p + "status"))
      in.fail("contact interface " + std::to_string(k + 1) + " was written " +
              (s.friction ? "without" : "with") + " friction");
    if (!s.friction) continue;
    for (std::size_t j = 0; const auto a : in.integers(p + "status", n))
      s.status[j++] = static_cast<char>(a);
    s.status_previous = s.status;
    s.status_accepted = s.status;
    s.D_diag_old = in.reals(p + "D_old", n);
    s.x_old = in.reals(p + "x_old", n * dim);
    const auto plane = in.reals(p + "plane_old", 3);
    std::copy(plane.begin(), plane.end(), s.plane_old.begin());
    s.dissipation = in.real(p + "dissipation");
    s.has_old = in.integer(p + "has_old") != 0;
    const auto slave = in.integers(p + "M_old.slave");
    const auto master = in.integers(p + "M_old.master", slave.size());
    const auto value = in.reals(p + "M_old.value", slave.size());
    // Each rank takes a contiguous share of the triplets.
    const auto total = slave.size();
    const auto np = static_cast<std::size_t>(comm.size());
    const auto r = static_cast<std::size_t>(comm.rank());
    // Checked on every rank before any rank takes its share: all fail together.
    // Master nodes by their ids in the mesh as read: every rank holds the interface cells.
    std::unordered_map<std::int64_t, std::int32_t> local_of;
    for (std::int32_t node = 0; node < disc_.mesh().n_nodes(); ++node)
      local_of.emplace(disc_.node_gid(node), node);
    for (std::size_t i = 0; i < total; ++i)
      if (slave[i] < 0 || static_cast<std::size_t>(slave[i]) >= n || !local_of.count(master[i]))
        in.fail("record '" + p + "M_old' names a node outside the interface or the mesh");
    s.M_old.clear();
    for (std::size_t i = total * r / np; i < total * (r + 1) / np; ++i)
      s.M_old.push_back({static_cast<local_index>(slave[i]), local_of.at(master[i]), value[i]});
    const auto row = in.integers(p + "D_coupling_old.row");
    const auto col = in.integers(p + "D_coupling_old.col", row.size());
    const auto coupling = in.reals(p + "D_coupling_old.value", row.size());
    for (std::size_t i = 0; i < row.size(); ++i)
      if (row[i] < 0 || static_cast<std::size_t>(row[i]) >= n || col[i] < 0 ||
          static_cast<std::size_t>(col[i]) >= n)
        in.fail("record '" + p + "D_coupling_old' names a node outside the interface");
    s.D_coupling_old.clear();
    for (std::size_t i = row.size() * r / np; i < row.size() * (r + 1) / np; ++i)
      s.D_coupling_old.push_back(
          {static_cast<std::int32_t>(row[i]), static_cast<std::int32_t>(col[i]), coupling[i]});
  }
}

} // namespace seam::problem
