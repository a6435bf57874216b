#include "seam/problem/solver_checkpoint.hpp"

#include <string>

namespace seam::problem {

namespace {

/// The saddle-point multipliers of tied interface k that this rank owns, with the prefix of
/// their part records: keyed by slave node and component, written and read by their owners.
struct OwnedMultipliers {
  std::string prefix;
  std::vector<std::int64_t> keys;
  std::vector<double> values;
};
OwnedMultipliers owned_multipliers(const SaddlePoint& saddle, std::size_t k) {
  OwnedMultipliers m;
  m.prefix = "saddle_point." + std::to_string(k) + ".";
  saddle.owned_multipliers(k, m.keys, m.values);
  return m;
}

} // namespace

void write_checkpoint(const Checkpoints& checkpoints, const DriverState& state,
                      const StepControl& control, const ContactConstraint& contact,
                      const SaddlePoint& saddle, const std::vector<meshtying::TiedInterface>& tied,
                      const Output& out,
                      const std::vector<std::pair<const char*, const la::Vector*>>& vectors) {
  if (!checkpoints.due(state.step)) return;
  const auto c = control.state();
  RecordWriter w = checkpoints.begin(state.step, c.t);
  w.put_real("control.dt", c.dt);
  w.put_integer("control.cuts", c.cuts);
  w.put_real("external_work", state.external_work);
  w.put_real("guess.t_older", state.t_older);
  w.put_real("guess.t_oldest", state.t_oldest);
  w.put_integer("guess.known", state.n_known);
  w.put_integer("energy_bound.transient", state.impact_transient ? 1 : 0);
  if (!state.ordering.empty()) w.put("linear_solver.ordering", std::span(state.ordering));
  for (const auto& [name, v] : vectors) checkpoints.put_vector(w, name, *v);
  if (contact.active()) contact.write_checkpoint(w);
  if (saddle.active())
    for (std::size_t k = 0; k < tied.size(); ++k) {
      const auto m = owned_multipliers(saddle, k);
      w.put_part(m.prefix + "keys", m.keys);
      w.put_part(m.prefix + "values", m.values);
    }
  out.write_checkpoint(w);
  checkpoints.commit(w, state.step);
}

DriverState read_checkpoint(const Checkpoints& checkpoints, StepControl& control,
                            ContactConstraint& contact, SaddlePoint& saddle,
                            const std::vector<meshtying::TiedInterface>& tied, const Output& out,
                            const std::vector<std::pair<const char*, la::Vector*>>& vectors) {
  const auto& r = checkpoints.restart();
  DriverState state;
  state.step = checkpoints.restart_step();
  state.external_work = r.real("external_work");
  state.t_older = r.real("guess.t_older");
  state.t_oldest = r.real("guess.t_oldest");
  state.n_known = static_cast<int>(r.integer("guess.known"));
  state.impact_transient = r.integer("energy_bound.transient") != 0;
  // Checkpoints of earlier versions have none: the choice starts anew.
  if (r.has("linear_solver.ordering")) state.ordering = r.reals("linear_solver.ordering", 6);
  control.set_state({checkpoints.restart_time(), r.real("control.dt"),
                     static_cast<int>(r.integer("control.cuts"))});
  for (const auto& [name, v] : vectors) checkpoints.get_vector(name, *v);
  if (contact.active())
    for (const auto& line : contact.read_checkpoint(checkpoints)) out.note(line);
  if (saddle.active() && r.has("saddle_point.0"))
    r.fail("was written by an earlier seam, which stored the multipliers in state.bin; rerun "
           "to write a checkpoint of this version");
  if (saddle.active())
    for (std::size_t k = 0; k < tied.size(); ++k) {
      // The multipliers this rank owns now, from the parts that hold them.
      const auto m = owned_multipliers(saddle, k);
      saddle.set_owned_multipliers(
          k, checkpoints.get_keyed(m.prefix + "keys", m.prefix + "values", 1,
                                   r.integer("mesh_nodes") * r.integer("dimension"), m.keys));
    }
  return state;
}

} // namespace seam::problem
