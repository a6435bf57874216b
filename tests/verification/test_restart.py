"""Checkpoints and restart (CONTRACT.md "Checkpoints").

A run writes checkpoint_NNNNN/ every `output.checkpoint_every` converged steps; a copy of its
output directory, whose rows after the checkpoint are overwritten with garbage (a run that died
later), is continued with `--restart copy/checkpoint_NNNNN`. The continued tables must equal
those of the uninterrupted run: bit for bit on one rank, and to 1e-12 relative (of each
column's scale) on another number of ranks (1 -> 3 and 3 -> 1) or on 3 ranks with MUMPS's
parallel factorization (which is not reproducible from run to run). On 3 ranks with the
reproducible direct solve (REPRODUCIBLE, docs/parallel.md "Reproducible runs") two
uninterrupted runs and a 3 -> 3 restart are bit for bit the same (test_same_ranks_np3), also
after redistributions of a contact interface, whose cut the checkpoint keeps
(test_same_ranks_rebalanced_np3).
- static frictional contact of two elastic blocks (the mortar operators of the last converged
  step M^n, D^n enter the slip increment), and frictionless with standard multipliers,
- dynamic frictional contact on a rigid plane with generalized-alpha (velocity, acceleration),
- frictionless dynamic contact with generalized-alpha (a block dropped on a plane,
  checkpoint in the contact, where each step projects the velocity onto the persistent contacts),
- self and multi-body contact (`surface:`) with friction,
- 3D: a hex block dragged over a rigid plane with Coulomb friction,
- static friction continued from a checkpoint written while the step was cut (the halved step
  size and the cut count in effect), and a rigid circle moved along a block (its position is
  a function of the restart time),
- free flight of two tied bodies with the energy-momentum method (condensed and saddle-point
  mesh tying),
- pulsating Poiseuille flow with generalized-alpha for the fluid (velocity, pressure, their
  rates, the forces of the last step), two fluid subdomains tied by mortar (the flow through
  them started from rest), and a flow over a bulging wall on a moving mesh (ALE),
- fluid-structure interaction (the Turek-Hron FSI3 start-up with generalized-alpha: structure
  displacement, velocity and acceleration, fluid velocity, pressure and rates, mesh
  displacement and its rate, the interface forces, the energy budget's works; and the steady
  FSI1 flag with continuation in t). Across rank counts the FSI tables are compared to 5e-11:
  the uninterrupted 1-rank and 3-rank runs of the FSI3 case differ by 1.5e-11 in the tip's u_y
  (of the largest |u|; 5e-17 m on a flag tip that has moved 7e-8 m), two 3-rank runs by
  1.1e-11 (the parallel direct solver's reductions), which no restart can undercut; the other
  columns agree to a few 1e-12.
Damaged or mismatched checkpoints (missing, truncated, corrupted file, another input, another
mesh, another dimension, no such directory, a missing or damaged part file, a checkpoint of
another kind of run: solid, fluid, fluid-structure) end with exit code 1 and a message. Nothing is
gathered on one rank: each rank writes its own entries of the nodal vectors, of the contact
interface state per slave node and of the saddle-point multipliers (test_parts_not_gathered).
"""
import json
import math
import os
import shutil
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry as G  # noqa: E402
import harness as H  # noqa: E402
import test_friction as F  # noqa: E402
import test_ale as TA  # noqa: E402
import test_contact as T  # noqa: E402
import test_fluid as TF  # noqa: E402
import test_hertz_impact as HI  # noqa: E402

_dirs = []
TABLES = ["steps.csv", "reactions.csv", "interfaces.csv", "probes.csv", "forces.csv",
          "errors.csv"]
# Columns that are not results: the wall clock, and the residual at convergence, which is
# round-off when the summation order changes (compared bit for bit on the same ranks).
SKIP = {"wall_seconds"}
# Columns of one unit share a scale: a component or an energy that stays near zero (the
# external work of a free flight, the strain energy of a rigid slide) is compared with the
# size of its kind, not with its own round-off.
GROUPS = [("kinetic_energy", "internal_energy", "external_work", "total_energy"),
          ("momentum_x", "momentum_y", "momentum_z"),
          ("angular_momentum_x", "angular_momentum_y", "angular_momentum_z"),
          ("fx", "fy", "fz"), ("ux", "uy", "uz"), ("vx", "vy", "vz"),
          ("normal_force", "tangential_force"),
          ("interface_force_fluid_x", "interface_force_fluid_y", "interface_force_fluid_z",
           "interface_force_structure_x", "interface_force_structure_y",
           "interface_force_structure_z"),
          ("fluid_kinetic_energy", "viscous_dissipation", "boundary_work", "interface_work_fluid",
           "interface_work_structure")]


def column_scale(rows, col, floors=None):
    """The largest value of the column's group, at least floors[col] (columns zero up to
    round-off, such as the momenta of free bodies, against a scale of the case)."""
    group = next((g for g in GROUPS if col in g), (col,))
    return max(max(abs(r[c]) for r in rows for c in group if c in r),
               (floors or {}).get(col, 1e-300))

# The two blocks of test_friction.py: base 2 x 0.5 (h = 0.15), slider 1 x 0.25 (h = 0.1) on it.
TWO_BLOCKS_GEO = F.TWO_BLOCKS_GEO % {"hb": 0.15, "hs": 0.1}


def two_blocks_yaml(every, contact="friction: {model: coulomb, coefficient: 0.3}"):
    """Press the slider onto the base (t in [0, 1]), then drag it along (t in [1, 3])."""
    return "\n".join([
        "dimension: 2", "mesh: {geo: case.geo}",
        "materials: {m: {model: neo_hooke, young: 100.0, poisson: 0.0}}",
        "bodies: [{region: base, material: m}, {region: slider, material: m}]",
        "boundary_conditions:",
        "  - {region: base_bottom, type: dirichlet, components: [x, y], value: [0, 0]}",
        "  - {region: slider_top, type: dirichlet, components: [x, y], "
        "value: ['0.1*max(t-1,0)', '-0.01*min(t,1)']}",
        "interfaces:",
        "  - {name: slide, type: contact, slave: slider_bottom, master: base_top, %s}" % contact,
        "time: {integrator: static, end: 3.0, steps: 8}",
        "solver: {newton: {tolerance: 1.0e-12, max_iterations: 30}}",
        "output: {checkpoint_every: %d, probes: [[1.0, 0.125]]}" % every]) + "\n"


def sliding_block_yaml(every):
    """A block under gravity on a rigid plane, pushed along by a growing body force: it sticks,
    then slides (test_friction.py), with generalized-alpha."""
    return "\n".join([
        "dimension: 2", "mesh: {geo: case.geo}",
        "materials: {m: {model: neo_hooke, young: 10000.0, poisson: 0.3, density: 1.0}}",
        "bodies: [{region: body, material: m}]",
        "boundary_conditions:",
        "  - {region: body, type: body_force, value: ['6*t', '-10*min(t/0.2,1)']}",
        "interfaces:",
        "  - {name: floor, type: contact, slave: bottom, friction: {model: coulomb, "
        "coefficient: 0.3}, rigid_plane: {point: [0, 0], normal: [0, 1]}}",
        "time: {integrator: generalized_alpha, rho_inf: 0.5, end: 1.0, steps: 20}",
        "solver: {newton: {tolerance: 1.0e-10, max_iterations: 30}}",
        "output: {every: 5, checkpoint_every: %d, probes: [[0.5, 0.125]]}" % every]) + "\n"


def flight_yaml(strategy, every):
    """Two tied Neo-Hookean bodies in free flight, rotating and stretching (test_dynamics.py)."""
    v = "['-3*(y-1) + 1 + 0.5*(x-0.5)', '3*(x-0.5) + 0.5']"
    return "\n".join([
        "dimension: 2", "mesh: {geo: case.geo}",
        "materials: {m: {model: neo_hooke, young: 100, poisson: 0.3, density: 1}}",
        "bodies: [{region: lower, material: m}, {region: upper, material: m}]",
        "initial_conditions:",
        "  - {region: lower, velocity: %s}" % v,
        "  - {region: upper, velocity: %s}" % v,
        "interfaces:",
        "  - {name: tie, type: mesh_tying, slave: upper_bottom, master: lower_top, "
        "strategy: %s}" % strategy,
        "time: {integrator: energy_momentum, end: 0.3, steps: 30}",
        "solver: {newton: {tolerance: 1.0e-12}}",
        "output: {every: 10, checkpoint_every: %d}" % every]) + "\n"


def pulsating_flow_yaml(every):
    """Pulsating plane Poiseuille flow with generalized-alpha (test_fluid.py): the restart
    needs the velocity, the pressure, their rates and the last step's forces."""
    return (TF.pulsating_yaml(10).replace("body.geo", "case.geo")
            + "  checkpoint_every: %d\n  probes: [[1.0, 0.3]]\n" % every)


TUREK_HRON = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "examples",
                          "turek_hron")


def fsi_geo(refine=0.5):
    """The Turek-Hron channel and flag of examples/turek_hron (refine 0.5: test_fsi.py's
    coarse mesh)."""
    with open(os.path.join(TUREK_HRON, "fsi.geo")) as f:
        text = f.read()
    assert "refine = 1;" in text
    return text.replace("refine = 1;", "refine = %g;" % refine)


def fsi_yaml(example, every, time):
    with open(os.path.join(TUREK_HRON, example)) as f:
        text = f.read()
    for a, b in (("geo: fsi.geo", "geo: case.geo"), (time[0], time[1]),
                 ("output:\n", "output:\n  checkpoint_every: %d\n" % every)):
        assert a in text, a
        text = text.replace(a, b)
    return text


def fsi3_yaml(every):
    """The FSI3 start-up (generalized-alpha on structure, fluid and fluid mesh) to t = 0.06."""
    return fsi_yaml("fsi3.yaml", every, ("end: 0.5, dt: 0.01", "end: 0.06, dt: 0.01"))


def fsi1_yaml(every):
    """The steady FSI1 flag in 4 load steps (each continues from the last converged state)."""
    return fsi_yaml("fsi1.yaml", every, ("end: 1, steps: 2", "end: 1, steps: 4"))


def make_case(geo, yaml):
    work = tempfile.mkdtemp(prefix="seam_restart_")
    _dirs.append(work)
    H.write_case(work, "case.geo", geo)
    return work, H.write_case(work, "case.yaml", yaml)


_full_runs = {}


def full_run(yaml, np, petsc=()):
    """The uninterrupted run of `yaml` on np ranks (once per test session); `petsc`: PETSc
    options (after `--`)."""
    key = (open(yaml).read(), open(os.path.join(os.path.dirname(yaml), "case.geo")).read(), np,
           tuple(petsc))
    if key not in _full_runs:
        out = tempfile.mkdtemp(prefix="seam_restart_out_")
        _dirs.append(out)
        H.run(["run", yaml, "-o", out, "--quiet"] + (["--"] + list(petsc) if petsc else []), np=np)
        _full_runs[key] = out
    return _full_runs[key]


def spoil_rows_after(path, step):
    """Overwrites the numbers of every row after `step` (as if the run had gone on
    differently and died): a restart must drop them."""
    with open(path) as f:
        lines = f.read().splitlines()
    out = [lines[0]]
    for line in lines[1:]:
        cells = line.split(",")
        if int(cells[0]) > step:
            cells = [cells[0]] + ["12345" if c.replace(".", "").replace("-", "").replace("e", "")
                                  .isdigit() else c for c in cells[1:]]
        out.append(",".join(cells))
    with open(path, "w") as f:
        f.write("\n".join(out) + "\n")


def restarted_run(yaml, full_out, step, np, petsc=(), said=()):
    """A copy of the uninterrupted run's output with its later rows spoiled, continued from
    checkpoint `step` on np ranks; its terminal output must contain every line of `said`."""
    copy = tempfile.mkdtemp(prefix="seam_restart_copy_")
    _dirs.append(copy)
    shutil.rmtree(copy)
    shutil.copytree(full_out, copy)
    for name in TABLES + ["newton.csv"]:
        if os.path.exists(os.path.join(copy, name)):
            spoil_rows_after(os.path.join(copy, name), step)
    checkpoint = os.path.join(copy, "checkpoint_%05d" % step)
    if not os.path.isdir(checkpoint):
        raise AssertionError("no checkpoint_%05d in %s" % (step, full_out))
    code, stdout, _ = H.run(["run", yaml, "--restart", checkpoint]
                            + (["--"] + list(petsc) if petsc else []), np=np)
    for line in ("restarting from",) + tuple(said):
        if line not in stdout:
            raise AssertionError("the restart does not say '%s':\n%s" % (line, stdout[-2000:]))
    return copy


def compare(full, restarted, rtol, what, extra=(), floors=None):
    """Every table (and the tables `extra`) row by row; rtol 0: bit for bit. Returns the
    largest relative difference."""
    worst = 0.0
    for name in TABLES + (["newton.csv"] if rtol == 0.0 else []) + list(extra):
        a_path, b_path = os.path.join(full, name), os.path.join(restarted, name)
        if not os.path.exists(a_path):
            continue
        a, b = H.read_csv(a_path), H.read_csv(b_path)
        if len(a) != len(b):
            raise AssertionError("%s %s: %d rows uninterrupted, %d restarted"
                                 % (what, name, len(a), len(b)))
        if not a:
            continue
        for col in a[0]:
            if col in SKIP:
                continue
            va, vb = [r[col] for r in a], [r[col] for r in b]
            if not isinstance(va[0], float):
                if va != vb:
                    raise AssertionError("%s %s column %s differs" % (what, name, col))
                continue
            if col == "residual" and rtol > 0.0:
                continue
            scale = column_scale(a, col, floors)
            for i, (x, y) in enumerate(zip(va, vb)):
                d = abs(x - y) / scale
                worst = max(worst, d)
                if (rtol == 0.0 and x != y) or d > rtol:
                    raise AssertionError("%s %s row %d column %s: %r uninterrupted, %r restarted "
                                         "(relative %.3e)" % (what, name, i + 1, col, x, y, d))
    pvd_a = open(os.path.join(full, "results.pvd")).read().count("<DataSet")
    pvd_b = open(os.path.join(restarted, "results.pvd")).read().count("<DataSet")
    if pvd_a != pvd_b:
        raise AssertionError("%s results.pvd: %d entries uninterrupted, %d restarted"
                             % (what, pvd_a, pvd_b))
    return worst


def check_case(geo, yaml_of, step, what, cross_np=True, rtol=1e-12, floors=None):
    _, yaml = make_case(geo, yaml_of(step))
    one = full_run(yaml, 1)
    rows = H.read_csv(os.path.join(one, "steps.csv"))
    if "contact" in open(yaml).read() and not any(r["active_nodes"] > 0 for r in rows[step:]):
        raise AssertionError("%s: no active contact node after the checkpoint" % what)
    same = compare(one, restarted_run(yaml, one, step, 1), 0.0, what + " 1 -> 1")
    print("   %s: 1 -> 1 bit for bit (max %.1e)" % (what, same))
    if not cross_np:
        return yaml
    d13 = compare(one, restarted_run(yaml, one, step, 3), rtol, what + " 1 -> 3", floors=floors)
    print("   %s: largest relative difference 1 -> 3 %.2e" % (what, d13))
    if cross_np == "1 -> 3":
        return yaml
    # On 3 ranks two uninterrupted runs differ at round-off already (MUMPS's parallel
    # factorization, test_same_ranks_np3), so 3 -> 3 is compared to 1e-12 as well.
    three = full_run(yaml, 3)
    d31 = compare(three, restarted_run(yaml, three, step, 1), rtol, what + " 3 -> 1",
                  floors=floors)
    print("   %s: largest relative difference 3 -> 1 %.2e" % (what, d31))
    if H.FULL:
        d33 = compare(three, restarted_run(yaml, three, step, 3), rtol, what + " 3 -> 3")
        print("   %s: largest relative difference 3 -> 3 %.2e" % (what, d33))
    return yaml


def test_static_friction_two_bodies():
    """Two blocks with Coulomb friction, the independent distribution of the interface (the
    default): at np 3 the slave side is held in part; a restart holds the slave nodes of the
    part of M^n it reads (docs/parallel.md, "Converting the contact sides", step 3)."""
    check_case(TWO_BLOCKS_GEO, two_blocks_yaml, 3, "static friction, two bodies")


# PETSc options of a reproducible direct solve on several ranks (docs/parallel.md
# "Reproducible runs"): every rank factors the whole matrix with sequential MUMPS. MUMPS's own
# parallel factorization assembles the contribution blocks of its fronts in the order their
# messages arrive, so that two 3-rank runs of the same input differ at round-off.
REPRODUCIBLE = ["-pc_type", "redundant", "-redundant_pc_type", "lu",
                "-redundant_pc_factor_mat_solver_type", "mumps",
                "-redundant_mat_mumps_icntl_14", "100"]


def test_same_ranks_np3():
    """Static friction of two blocks on 3 ranks, continued on 3 ranks from step 3, with the
    reproducible direct solve (REPRODUCIBLE): two uninterrupted 3-rank runs are bit for bit the
    same (every table, newton.csv's residuals included), and so is the restarted run. Fails if
    any sum in seam or PETSc depends on the order in which messages arrive (PETSc's VecAssembly
    did: la::Vector::assemble sums in rank order)."""
    what = "static friction, two bodies, 3 -> 3"
    step = 3
    _, yaml = make_case(TWO_BLOCKS_GEO, two_blocks_yaml(step))
    first = full_run(yaml, 3, REPRODUCIBLE)
    for attempt in range(2):
        again = tempfile.mkdtemp(prefix="seam_restart_out_")
        _dirs.append(again)
        H.run(["run", yaml, "-o", again, "--quiet", "--"] + REPRODUCIBLE, np=3)
        compare(first, again, 0.0, "two uninterrupted 3-rank runs (%d)" % (attempt + 1))
    print("   three uninterrupted 3-rank runs: bit for bit")
    restarted = restarted_run(yaml, first, step, 3, REPRODUCIBLE)
    compare(first, restarted, 0.0, what)
    print("   %s: bit for bit" % what)


def test_static_standard_multipliers():
    """Standard multipliers (the multipliers are unknowns of the saddle point), frictionless and
    with Coulomb friction, two bodies, and a block sliding on a rigid plane with Coulomb friction
    (generalized-alpha): the sides held in part at np 3, the multiplier rows numbered by the
    slave nodes' owners (docs/parallel.md, "Converting the contact sides", step 6); the state
    is checkpointed by node id (with friction D^n_jk by its two nodes), so 1 -> 1 is bit for bit
    and 1 -> 3, 3 -> 1 equal the uninterrupted runs to 1e-12."""
    check_case(TWO_BLOCKS_GEO, lambda e: two_blocks_yaml(e, "multiplier: standard"), 3,
               "static contact, standard multipliers")
    check_case(TWO_BLOCKS_GEO, lambda e: two_blocks_yaml(
        e, "multiplier: standard, friction: {model: coulomb, coefficient: 0.3}"), 3,
        "static friction, standard multipliers")
    block = G.rectangle("quad_structured", 0.0625, lx=1.0, ly=0.25)
    check_case(block, lambda e: sliding_block_yaml(e).replace(
        "type: contact,", "type: contact, multiplier: standard,"), 8,
        "generalized-alpha friction on a rigid plane, standard multipliers")


def test_static_slave_side_in_part():
    """Two blocks, frictionless and with Coulomb friction, with the bulk distribution of the
    interface: at np 3 each rank holds the slave facets of its own and ghost cells only and the
    state of the slave nodes it holds (docs/parallel.md, "Converting the contact sides", step
    3); the checkpoint keys the state by node id, so a restart on another number of ranks
    continues the run."""
    bulk = "parallel: {interface_distribution: bulk}\n"
    check_case(TWO_BLOCKS_GEO, lambda e: two_blocks_yaml(e, "multiplier: dual") + bulk, 3,
               "static frictionless, slave side in part")
    check_case(TWO_BLOCKS_GEO, lambda e: two_blocks_yaml(e) + bulk, 3,
               "static friction, slave side in part")


def test_static_slave_side_in_part_independent():
    """Two blocks without friction, with the independent distribution of the interface (the
    default): at np 3 each rank holds the rings of the slave nodes it owns and of the nodes of
    the slave facets it evaluates, taken anew at each distribution, and the state of the slave
    nodes it holds (docs/parallel.md, "Converting the contact sides", step 3). A restart
    on another number of ranks distributes anew from the checkpointed state (keyed by node
    id): 1 -> 1 bit for bit, 1 -> 3 and 3 -> 1 to 1e-12; 3 -> 3 (with the reproducible direct
    solve) keeps the checkpoint's cut, compared to 1e-12 here because `work: time` (the
    default) redistributes at steps that depend on timing (bit for bit with `work:
    integration_cells`: test_same_ranks_rebalanced_np3)."""
    what = "static frictionless, independent, slave side in part"
    step = 3
    yaml = check_case(TWO_BLOCKS_GEO, lambda e: two_blocks_yaml(e, "multiplier: dual"), step, what)
    first = full_run(yaml, 3, REPRODUCIBLE)
    restarted = restarted_run(yaml, first, step, 3, REPRODUCIBLE)
    d33 = compare(first, restarted, 1e-12, what + " 3 -> 3")
    print("   %s: largest relative difference 3 -> 3 %.2e" % (what, d33))


def test_same_ranks_rebalanced_np3():
    """Two blocks without friction on 3 ranks, the interface redistributed deterministically
    (`work: integration_cells`, `rebalance_tolerance: 1`) after steps before and after the
    checkpoint, with the reproducible direct solve: the 3 -> 3 restart from step 3 equals the
    uninterrupted run bit for bit (every table, newton.csv and parallel.csv included). The
    checkpoint keeps the cut of the slave elements (each rank's facets in its part file, the
    cut trees in state.bin), so the restarted run evaluates them where the uninterrupted one
    did and moves its planes from the same trees; cut anew from the pairs of the restart step,
    the sums ran in another order (docs/parallel.md, "Converting the contact sides"). On
    another number of ranks the cut is made anew (the run says so), to round-off."""
    what = "static frictionless, redistributed, 3 -> 3"
    step = 3
    balance = "parallel: {work: integration_cells, rebalance_tolerance: 1.0}\n"
    _, yaml = make_case(TWO_BLOCKS_GEO, two_blocks_yaml(step, "multiplier: dual") + balance)
    first = full_run(yaml, 3, REPRODUCIBLE)
    rows = H.read_csv(os.path.join(first, "parallel.csv"))
    moves = [r["step"] for r in rows if r["redistributed"]]
    if not any(m <= step for m in moves) or not any(m > step for m in moves):
        raise AssertionError("%s: redistributed after steps %s, wanted before and after step %d"
                             % (what, moves, step))
    restarted = restarted_run(yaml, first, step, 3, REPRODUCIBLE,
                              said=["the slave elements keep the checkpoint's cut on 3 ranks"])
    compare(first, restarted, 0.0, what, extra=["parallel.csv"])
    print("   %s: bit for bit (redistributed after steps %s)" % (what, [int(m) for m in moves]))
    # A part whose cut names a facet outside the slave side (checksum intact): exit 1.
    bad = os.path.join(restarted, "bad_cut")
    shutil.copytree(os.path.join(first, "checkpoint_%05d" % step), bad)
    replace_record(os.path.join(bad, "part_00001.bin"), "contact.0.cut.facets", [1])
    expect_input_error(["run", yaml, "--restart", bad, "-o", os.path.join(restarted, "o")],
                       ["part_00001.bin", "contact.0.cut.facets", "outside the slave side"],
                       "a cut naming a facet outside the side, np 3", np=3)
    one = full_run(yaml, 1)
    d13 = compare(one, restarted_run(yaml, one, step, 3, REPRODUCIBLE,
                                     said=["the slave elements are cut anew on 3"]),
                  1e-12, what + " 1 -> 3")
    print("   %s: 1 -> 3 cut anew, largest relative difference %.2e" % (what, d13))


def test_dynamic_friction_generalized_alpha():
    # 3 -> 1 is the static case's in CI (the state read from 3 part files is routed the same way).
    check_case(G.rectangle("quad_structured", 0.125, lx=1.0, ly=0.25), sliding_block_yaml, 8,
               "generalized-alpha friction", cross_np=True if H.FULL else "1 -> 3")


def test_rigid_slave_side_in_part():
    """A block under gravity on a rigid plane, pushed along by a growing body force (it sticks,
    then slides; Coulomb friction, generalized-alpha: sliding_block_yaml, h = 1/16), with the
    bulk and with the independent distribution of the interface: at np 3 each rank holds part
    of the slave side and the state of the slave nodes it holds (docs/parallel.md, "Converting
    the contact sides", step 3); the checkpoint is keyed by node id, so a restart on another
    number of ranks continues the run: 1 -> 1 bit for bit, 1 -> 3 and 3 -> 1 to 1e-12."""
    block = G.rectangle("quad_structured", 0.0625, lx=1.0, ly=0.25)
    bulk = "parallel: {interface_distribution: bulk}\n"
    check_case(block, lambda e: sliding_block_yaml(e) + bulk, 8,
               "generalized-alpha friction on a rigid plane, bulk, slave side in part")
    check_case(block, sliding_block_yaml, 8,
               "generalized-alpha friction on a rigid plane, independent, slave side in part")


def drop_yaml(every):
    """test_contact.py's Neo-Hooke block dropped on a rigid plane (frictionless, dual
    multipliers), generalized-alpha, to t = 0.1: the checkpoint after step 27 lies in the
    contact, where every step projects the velocity onto the persistent contacts
    (docs/contact_dynamics.md §6; no state of its own)."""
    return (T.DROP_YAML.replace("INTEGRATOR", "generalized_alpha")
            .replace("MULTIPLIER", "dual").replace("end: 0.3, steps: 150", "end: 0.1, steps: 50")
            .replace("output: {every: 50}", "output: {every: 5, checkpoint_every: %d}" % every))


def test_dynamic_contact_generalized_alpha():
    check_case(G.rectangle("quad", 0.1, lx=1.0, ly=0.5), drop_yaml, 27,
               "generalized-alpha frictionless drop", cross_np="1 -> 3")


def test_impact_release_transient():
    """generalized-alpha's energy bound at impacts (docs/contact_dynamics.md §6) lasts from the
    first active node through the ringing after the release, taking a step's gain from the
    patch of the last contact force: a checkpoint one step after the release (no node active
    at this step or the one before) must carry both, or the restarted steps keep the gains the
    uninterrupted run removes. test_hertz_impact's sphere (CI mesh, 20 steps over the contact
    time), checkpoints every step, restarted 1 -> 1 bit for bit."""
    v = math.sqrt(16.0 * HI.E / (1.0 - HI.NU ** 2) * 0.0025 ** 2.5
                  / (15.0 * HI.RHO * 4.0 / 3.0 * math.pi))
    t_c = HI.hertz(HI.RHO * 4.0 / 3.0 * math.pi, v)[2]
    steps = 32
    dt = 1.25 * t_c / 25
    geo = (HI.GEO.replace("H0", repr(0.006)).replace("HMAX", repr(0.25))
           .replace("K;", repr(0.15) + ";"))
    yaml = ((HI.YAML % (HI.E, HI.NU, HI.RHO, -v, steps * dt, steps))
            .replace("INTEGRATOR", "generalized_alpha")
            .replace("output: {every: 100000}", "output: {every: 100000, checkpoint_every: 1}"))
    _, path = make_case(geo, yaml)
    one = full_run(path, 1)
    active = [r["active_nodes"] for r in H.read_csv(os.path.join(one, "steps.csv"))]
    touched = [i for i, a in enumerate(active) if a > 0]
    release = next((i for i in range(touched[0], len(active)) if active[i] == 0), None) \
        if touched else None
    if release is None or release + 2 >= len(active):
        raise AssertionError("no release with steps after it: active nodes %s" % active)
    step = release + 2  # steps.csv row i is step i + 1: the second step without contact
    # The bound's and the persistency projection's phases are timed in summary.json.
    with open(os.path.join(one, "summary.json")) as f:
        timings = json.load(f)["timings"]
    for phase in ("contact_energy_bound", "contact_persistency", "assembly", "condensation"):
        if not timings.get(phase, 0.0) > 0.0:
            raise AssertionError("summary.json timings: %s missing or zero: %s" % (phase, timings))
    same = compare(one, restarted_run(path, one, step, 1), 0.0, "impact release 1 -> 1")
    print("   release at step %d, restarted from step %d: 1 -> 1 bit for bit (max %.1e)"
          % (release + 1, step, same))


def test_partition_reproducible():
    """The generalized-alpha drop on 3 ranks with the reproducible direct solve (REPRODUCIBLE):
    three uninterrupted runs and the 3 -> 3 restart from step 27 are bit for bit the same, and
    every rank owns the same cells and nodes in each (summary.json ranks_detail). The mesh of
    its .geo is read in chunks and partitioned in parallel by PT-Scotch, whose partition used
    to change from run to run here (90/95/91 and 91/90/95 cells in two runs) while PT-Scotch
    ran several threads per rank (docs/parallel.md "Reproducible runs")."""
    what = "generalized-alpha drop, 3 ranks"
    step = 27
    _, yaml = make_case(G.rectangle("quad", 0.1, lx=1.0, ly=0.5), drop_yaml(step))

    def owned(out):
        return [(r["cells"], r["owned_nodes"])
                for r in H.read_json(os.path.join(out, "summary.json"))["ranks_detail"]]

    first = full_run(yaml, 3, REPRODUCIBLE)
    for attempt in range(2):
        again = tempfile.mkdtemp(prefix="seam_restart_out_")
        _dirs.append(again)
        H.run(["run", yaml, "-o", again, "--quiet", "--"] + REPRODUCIBLE, np=3)
        if owned(again) != owned(first):
            raise AssertionError("%s: cells and owned nodes per rank %s in the first run, %s in "
                                 "run %d" % (what, owned(first), owned(again), attempt + 2))
        compare(first, again, 0.0, "%s, uninterrupted run %d" % (what, attempt + 2))
    print("   three uninterrupted 3-rank runs: bit for bit, (cells, owned nodes) per rank %s"
          % owned(first))
    compare(first, restarted_run(yaml, first, step, 3, REPRODUCIBLE), 0.0, what + " 3 -> 3")
    print("   %s 3 -> 3 restart: bit for bit" % what)


def test_energy_momentum_tied_condensed():
    check_case(G.tied_rectangles(0.3, 0.2), lambda e: flight_yaml("condensed", e), 10,
               "energy-momentum, condensed tying", cross_np="1 -> 3")


def test_energy_momentum_tied_saddle_point():
    """Standard multipliers, the interface distributed (docs/parallel.md, "Saddle-point tying
    distributed"): the multipliers checkpointed by the slave nodes' owners, keyed by node id,
    continue 1 -> 3 and 3 -> 1."""
    check_case(G.tied_rectangles(0.3, 0.2), lambda e: flight_yaml("saddle_point", e), 10,
               "energy-momentum, saddle-point tying")


def test_energy_momentum_contact():
    """test_friction_dynamics.py's two free rings with energy-momentum contact and Coulomb
    friction, as one surface (dual multipliers) and as two bodies (standard multipliers): at
    np 3 the sides are held in part (docs/parallel.md, "Converting the contact sides", step 6);
    the checkpoint after step 20 (in contact) continues the run: 1 -> 1 bit for bit, 1 -> 3 and
    3 -> 1 to 1e-12."""
    import test_friction_dynamics as F
    import test_rings as R
    geo = R.ring_geo(R.CENTRES, 8, 2)
    for interface in ("surface", "two_bodies"):
        def yaml_of(every, interface=interface):
            text = F.rings_yaml(interface, 40, 2)
            old = "output: {every: 1000}"
            if old not in text:
                raise AssertionError("rings_yaml: '%s' not found" % old)
            return text.replace(old, "output: {every: 1000, checkpoint_every: %d}" % every)
        # The momenta of the free rings are zero up to round-off: against one ring's, 0.5.
        check_case(geo, yaml_of, 20, "energy-momentum friction, rings, " + interface,
                   floors={"momentum_%s" % c: 0.5 for c in "xyz"})


def test_friction_3d_rigid_plane():
    """3D: test_friction.py's hex block pressed on a rigid plane and dragged diagonally with
    Coulomb friction (quad4 slave faces, the 3D slip history), restarted after step 3, in the
    drag."""
    geo, yaml = F.drag_3d(np=0)
    check_case(geo, lambda e: yaml + "output: {checkpoint_every: %d}\n" % e, 3,
               "3D friction on a rigid plane", cross_np="1 -> 3")


def test_fluid_generalized_alpha():
    check_case(G.rectangle("quad_structured", 0.25, 2), pulsating_flow_yaml, 4,
               "fluid, generalized-alpha", cross_np="1 -> 3")


def tied_flow_yaml(every):
    """test_fluid_tying.py's two fluid squares tied non-matching (dual mortar on the velocity),
    the flow through them started from rest with generalized-alpha."""
    import test_fluid_tying as FT
    text = FT.TIED_POISEUILLE
    for a, b in (('  exact_velocity: [0, "4*x*(1-x)"]\n', ""), ('  exact_pressure: "0.8*(2-y)"\n', ""),
                 ('"4*x*(1-x)"]', '"4*x*(1-x)*(1-cos(3*t))"]'), ("geo: body.geo", "geo: case.geo"),
                 ("time: {integrator: static, end: 1, steps: 1}",
                  "time: {integrator: generalized_alpha, rho_inf: 0.5, end: 1, steps: 8}")):
        assert a in text, a
        text = text.replace(a, b)
    return text + "  checkpoint_every: %d\n" % every


def test_fluid_tied():
    check_case(G.tied_rectangles(0.25, 0.2, order=2, kind="quad"), tied_flow_yaml, 4,
               "fluid, tied subdomains", cross_np="1 -> 3")


def test_fluid_moving_mesh():
    """ALE: a wall bulging in and out (test_ale.py); the mesh displacement and its rate are
    part of the state."""
    yaml = (TA.BULGE.replace("body.geo", "case.geo").replace("every: 6", "every: 2")
            + "  checkpoint_every: 3\n")
    check_case(G.rectangle("tri", 0.2, 2), lambda e: yaml, 3, "fluid, moving mesh",
               cross_np="1 -> 3")


def test_fsi_generalized_alpha():
    """FSI3 start-up, 6 steps, restarted after step 3: bit for bit on 1 rank; 1 -> 3 and
    3 -> 1 to 5e-11, the level at which uninterrupted runs on 1 and 3 ranks agree (printed;
    see the docstring above)."""
    yaml = check_case(fsi_geo(), fsi3_yaml, 3, "fluid-structure, generalized-alpha", rtol=5e-11)
    d = compare(full_run(yaml, 1), full_run(yaml, 3), 1.0, "uninterrupted 1 and 3 ranks")
    print("   fluid-structure: uninterrupted runs on 1 and 3 ranks differ by %.2e" % d)


def test_fsi_static():
    """The steady FSI1 flag in 4 load steps, restarted after step 2 (its residual scale and
    the continued state; no time integration history)."""
    check_case(fsi_geo(), fsi1_yaml, 2, "fluid-structure, static", cross_np=False)


def test_fsi_bad_checkpoints():
    """A checkpoint of another kind of run (an FSI checkpoint given to a solid and to a fluid
    run, a solid and a fluid checkpoint given to an FSI run), of another FSI mesh or input, or
    damaged: exit 1 with a message naming what differs."""
    work, yaml = make_case(fsi_geo(), fsi3_yaml(3))
    fsi = os.path.join(full_run(yaml, 1), "checkpoint_00003")
    _, solid_yaml = make_case(TWO_BLOCKS_GEO, two_blocks_yaml(3))
    solid = os.path.join(full_run(solid_yaml, 1), "checkpoint_00003")
    _, fluid_yaml = make_case(G.rectangle("quad_structured", 0.25, 2), pulsating_flow_yaml(4))
    fluid = os.path.join(full_run(fluid_yaml, 1), "checkpoint_00004")
    scratch = os.path.join(work, "o")
    for input_, checkpoint, words, what in (
            (solid_yaml, fsi, ["fluid-structure run", "describes a solid run"], "FSI -> solid"),
            (fluid_yaml, fsi, ["fluid-structure run", "describes a fluid run"], "FSI -> fluid"),
            (yaml, solid, ["solid run", "describes a fluid-structure run"], "solid -> FSI"),
            (yaml, fluid, ["fluid run", "describes a fluid-structure run"], "fluid -> FSI")):
        expect_input_error(["run", input_, "--restart", checkpoint, "-o", scratch], words, what)
    # The FSI case on a finer mesh, and with another rho_inf.
    _, finer = make_case(fsi_geo(0.6), fsi3_yaml(3))
    expect_input_error(["run", finer, "--restart", fsi, "-o", scratch], ["mesh of"],
                       "FSI, another mesh")
    other = H.write_case(work, "other.yaml", fsi3_yaml(3).replace("rho_inf: 0.5", "rho_inf: 0.6"))
    expect_input_error(["run", other, "--restart", fsi, "-o", scratch], ["another input"],
                       "FSI, another input")
    # A damaged state.bin (one byte flipped), on 3 ranks: every rank stops.
    damaged = os.path.join(work, "damaged")
    shutil.copytree(fsi, damaged)
    path = os.path.join(damaged, "state.bin")
    data = open(path, "rb").read()
    middle = len(data) // 2
    open(path, "wb").write(data[:middle] + bytes([data[middle] ^ 0x40]) + data[middle + 1:])
    expect_input_error(["run", yaml, "--restart", damaged, "-o", scratch], ["damaged"],
                       "FSI, damaged state.bin, np 3", np=3)


def test_self_contact_surface():
    """The two blocks as one `surface:` interface (self and multi-body contact: the slave and
    master facets are assigned at every search) with Coulomb friction."""
    check_case(TWO_BLOCKS_GEO, lambda e: two_blocks_yaml(e).replace(
        "slave: slider_bottom, master: base_top", "surface: [slider_bottom, base_top]"), 3,
        "self contact surface, friction", cross_np="1 -> 3")


def cut_steps_yaml(every):
    """The two blocks in two steps of 2 with 6 Newton iterations at most: the first step is
    cut once and the drag steps twice, so the checkpoint after step 2 (t = 1.5) holds a
    halved step size (0.5, two cuts in effect) that must be continued (dt 1 next), not the
    nominal 2; a restart that forgot it would try t = 3.5 and cut again (other newton.csv
    rows)."""
    return (two_blocks_yaml(every).replace("end: 3.0, steps: 8", "end: 4.0, steps: 2")
            .replace("max_iterations: 30", "max_iterations: 6"))


def test_after_step_cuts():
    _, yaml = make_case(TWO_BLOCKS_GEO, cut_steps_yaml(1))
    one = full_run(yaml, 1)
    text = open(os.path.join(one, "newton.csv")).read()
    times = [r["time"] for r in H.read_csv(os.path.join(one, "steps.csv"))]
    # The uninterrupted run must cut where the docstring says, or the test checks nothing.
    if times[:3] != [1.0, 1.5, 2.5]:
        raise AssertionError("expected steps at t = 1, 1.5, 2.5 (cut steps), got %s" % times)
    print("   uninterrupted run: steps at t = %s, %d Newton rows"
          % (", ".join("%g" % t for t in times), text.count("\n") - 1))
    check_case(TWO_BLOCKS_GEO, cut_steps_yaml, 2, "after step cuts", cross_np="1 -> 3")


def test_other_steps():
    """An input that differs only in its `steps:` continues with the new step size (the
    static friction case, 8 steps to t = 3, restarted after step 4 at t = 1.5 with `steps: 4`):
    the restart says so and takes two steps of 0.75 (ending at 2.25 and 3), not the
    checkpoint's 0.375; the contact stays active. An input that changes `end` as well is
    refused. (Dynamic runs with another dt: test_fsi.py test_fsi3_restart_other_dt.)"""
    work, yaml = make_case(TWO_BLOCKS_GEO, two_blocks_yaml(4))
    one = full_run(yaml, 1)
    coarse = H.write_case(work, "coarse.yaml", two_blocks_yaml(4).replace("steps: 8", "steps: 4"))
    out = os.path.join(work, "coarse_out")
    _, stdout, _ = H.run(["run", coarse, "--restart", os.path.join(one, "checkpoint_00004"),
                          "-o", out])
    line = next((ln for ln in stdout.splitlines() if "restarting with dt" in ln), "")
    if "dt = 0.75" not in line or "had dt = 0.375" not in line:
        raise AssertionError("the restart does not name the new step:\n" + stdout[-2000:])
    rows = H.read_csv(os.path.join(out, "steps.csv"))
    print("   %s; steps end at t = %s" % (line.strip(), [r["time"] for r in rows]))
    if [r["time"] for r in rows] != [2.25, 3.0] or not all(r["active_nodes"] > 0 for r in rows):
        raise AssertionError("expected steps ending at 2.25 and 3 in contact: %s" % rows)
    other = H.write_case(work, "other.yaml", two_blocks_yaml(4).replace(
        "end: 3.0, steps: 8", "end: 4.0, steps: 4"))
    expect_input_error(["run", other, "--restart", os.path.join(one, "checkpoint_00004"), "-o",
                        os.path.join(work, "o")], ["another input"], "steps and end changed")


def moving_sphere_yaml(every):
    """A rigid circle pressed into a block and moved along it (its motion is a function of
    t: the restart must place it where the uninterrupted run had it), Coulomb friction."""
    return "\n".join([
        "dimension: 2", "mesh: {geo: case.geo}",
        "materials: {m: {model: neo_hooke, young: 100.0, poisson: 0.3}}",
        "bodies: [{region: body, material: m}]",
        "boundary_conditions:",
        "  - {region: bottom, type: dirichlet, components: [x, y], value: [0, 0]}",
        "interfaces:",
        "  - {name: ball, type: contact, slave: top, friction: {model: coulomb, "
        "coefficient: 0.2}, rigid_sphere: {center: [0.3, 0.55], radius: 0.3, "
        "motion: ['0.4*max(t-1,0)', '-0.06*min(t,1)']}}",
        "time: {integrator: static, end: 2.0, steps: 8}",
        "solver: {newton: {tolerance: 1.0e-12, max_iterations: 30}}",
        "output: {checkpoint_every: %d, probes: [[0.5, 0.125]]}" % every]) + "\n"


def test_moving_obstacle():
    check_case(G.rectangle("quad_structured", 0.05, lx=1.0, ly=0.25), moving_sphere_yaml, 5,
               "moving rigid circle", cross_np="1 -> 3")


def expect_input_error(args, words, what, np=1):
    code, stdout, stderr = H.run(args, np=np, check=False, timeout=300)
    text = stdout + stderr
    if code != 1 or not all(w in text for w in words) or "PETSC ERROR" in text:
        raise AssertionError("%s: exit %d (expected 1 with %s):\n%s" % (what, code, words,
                                                                         text[-2000:]))
    line = next((ln for ln in text.splitlines() if ln.startswith("seam:")), "")
    print("   %s: %s" % (what, line[:150]))


def test_bad_checkpoints():
    work, yaml = make_case(TWO_BLOCKS_GEO, two_blocks_yaml(3))
    out = full_run(yaml, 1)  # the static friction case's run
    good = os.path.join(out, "checkpoint_00003")
    state = os.path.join(good, "state.bin")
    with open(state, "rb") as f:
        data = f.read()

    def variant(name, content):
        d = os.path.join(out, name)
        os.makedirs(d)
        if content is not None:
            with open(os.path.join(d, "state.bin"), "wb") as f:
                f.write(content)
        return d

    expect_input_error(["run", yaml, "--restart", variant("missing", None)],
                       ["state.bin", "missing"], "missing file")
    expect_input_error(["run", yaml, "--restart", variant("truncated", data[:len(data) // 2])],
                       ["truncated"], "truncated file")
    middle = len(data) // 2
    flipped = data[:middle] + bytes([data[middle] ^ 0x40]) + data[middle + 1:]
    expect_input_error(["run", yaml, "--restart", variant("flipped", flipped)],
                       ["damaged"], "corrupted byte")
    expect_input_error(["run", yaml, "--restart", os.path.join(out, "checkpoint_99999")],
                       ["no such checkpoint"], "no such directory")
    # Another input: the same case with another friction coefficient.
    other = H.write_case(work, "other.yaml", open(yaml).read().replace("0.3}", "0.4}"))
    expect_input_error(["run", other, "--restart", good], ["another input"], "another input")
    # Another mesh: the same input next to a finer .geo.
    work2, yaml2 = make_case(F.TWO_BLOCKS_GEO % {"hb": 0.15, "hs": 0.05}, two_blocks_yaml(3))
    expect_input_error(["run", yaml2, "--restart", good], ["mesh"], "another mesh")
    # The same numbers of nodes and cells, one corner moved.
    moved = TWO_BLOCKS_GEO.replace("Point(7) = {1.5, 0.25,", "Point(7) = {1.5, 0.26,")
    work4, yaml4 = make_case(moved, two_blocks_yaml(3))
    expect_input_error(["run", yaml4, "--restart", good], ["another mesh"], "moved mesh node")
    # Another dimension: a 3D input restarted from the 2D checkpoint.
    work3, yaml3 = make_case(G.box("hex", 0.5), "\n".join([
        "dimension: 3", "mesh: {geo: case.geo}",
        "materials: {m: {model: neo_hooke, young: 100.0, poisson: 0.3}}",
        "bodies: [{region: body, material: m}]",
        "time: {integrator: static, end: 1.0, steps: 2}"]) + "\n")
    expect_input_error(["run", yaml3, "--restart", good], ["dimension"], "another dimension")
    expect_input_error(["run", yaml3, "--restart", good, "-o", os.path.join(work3, "o")],
                       ["dimension 2"], "another dimension, -o")
    # A table of the output directory that cannot be continued (another header): every rank
    # stops with the message, none waits for rank 0.
    other = os.path.join(work, "other_out")
    os.makedirs(other)
    with open(os.path.join(other, "steps.csv"), "w") as f:
        f.write("a,b,c\n1,2,3\n")
    expect_input_error(["run", yaml, "--restart", good, "-o", other], ["steps.csv", "header"],
                       "foreign steps.csv on 3 ranks", np=3)
    # The part files of a 3-rank checkpoint: one missing (restart on 3 ranks: the rank that
    # reads it names it, every rank stops), one damaged (on 1 rank, which reads all three).
    three = os.path.join(full_run(yaml, 3), "checkpoint_00003")
    for name, change, np, words in (("part_00002.bin", None, 3, ["part_00002.bin", "missing"]),
                                    ("part_00001.bin", "flip", 1, ["part_00001.bin", "damaged"])):
        copy = os.path.join(work, "parts_" + name)
        shutil.copytree(three, copy)
        path = os.path.join(copy, name)
        if change is None:
            os.remove(path)
        else:
            data = open(path, "rb").read()
            middle = len(data) // 2
            open(path, "wb").write(data[:middle] + bytes([data[middle] ^ 0x40])
                                   + data[middle + 1:])
        expect_input_error(["run", yaml, "--restart", copy, "-o", os.path.join(copy, "o")],
                           words, "%s %s, np %d" % (name, "missing" if change is None
                                                    else "damaged", np), np=np)


def test_parts_not_gathered():
    """Nothing is gathered on one rank in a checkpoint. The nodal vectors are written by the
    ranks that own them: at np 3 each part file holds about a third of the entries (none holds
    them all), and the three together hold each entry once. The contact interface state per
    slave node (multipliers, active set, stick/slip status, D^n, x^n) is written by the slave
    nodes' owners: part r holds the slave nodes that rank r owns (as many as the rows of
    interface_slide.csv it computed, ranks_detail contact_output_rows), the parts together hold
    each slave node once, and state.bin holds no per-node record of the interface (only its
    size, a hash of its node ids and the rigid plane's position: at most 3 values per record).
    The M^n triplets are in the parts of the ranks that integrated them, the slave facets each
    rank evaluates (the cut of the independent distribution) in its part. Saddle-point mesh tying
    (the energy-momentum flight): the parts hold each multiplier once, state.bin none. Read
    through the records' byte counts (the format of checkpoint.hpp)."""
    _, yaml = make_case(TWO_BLOCKS_GEO, two_blocks_yaml(3))
    one_out, three_out = full_run(yaml, 1), full_run(yaml, 3)
    one = os.path.join(one_out, "checkpoint_00003")
    three = os.path.join(three_out, "checkpoint_00003")
    parts = [records(os.path.join(three, "part_%05d.bin" % r)) for r in range(3)]
    total = len(ints(records(os.path.join(one, "part_00000.bin"))["index"]))
    counts = [len(ints(p["index"])) for p in parts]
    entries = sorted(i for p in parts for i in ints(p["index"]))
    print("   entries per part at np 3: %s of %d" % (counts, total))
    if entries != list(range(total)):
        raise AssertionError("the parts do not hold each of the %d entries once" % total)
    if max(counts) > 0.7 * total:
        raise AssertionError("a part holds %d of %d entries" % (max(counts), total))
    # The contact interface state.
    slave = sorted(ints(records(os.path.join(one, "part_00000.bin"))["contact.0.nodes"]))
    nodes = [ints(p["contact.0.nodes"]) for p in parts]
    owned = [r["contact_slave_nodes_owned"] for r in
             H.read_json(os.path.join(three_out, "summary.json"))["ranks_detail"]]
    rows = len(H.read_csv(os.path.join(three_out, "interface_slide.csv")))
    print("   slave nodes per part at np 3: %s of %d (owned per rank %s); M^n triplets "
          "per part %s" % ([len(n) for n in nodes], len(slave), owned,
                           [len(p["contact.0.M_old.value"]) // 8 for p in parts]))
    if len(slave) != rows or sorted(i for n in nodes for i in n) != slave:
        raise AssertionError("the parts do not hold each of the %d slave nodes once" % rows)
    if [len(n) for n in nodes] != owned:
        raise AssertionError("the parts hold %s slave nodes, the ranks own %s"
                             % ([len(n) for n in nodes], owned))
    if not any(len(p["contact.0.M_old.value"]) for p in parts):
        raise AssertionError("no part holds M^n")
    # The cut of the slave elements (the independent distribution): part r lists the slave
    # facets rank r evaluates, each facet of the side in one part; state.bin the ranks of the
    # cut.
    cut = [ints(p["contact.0.cut.facets"]) for p in parts]
    facets = H.read_json(os.path.join(three_out, "summary.json"))["interfaces"][0]["slave_elements"]
    print("   slave facets evaluated per part at np 3: %s of %d" % ([len(c) for c in cut], facets))
    flat = sorted(i for c in cut for i in c)
    if len(flat) != facets or len(set(flat)) != facets or not all(cut):
        raise AssertionError("the parts do not list each of the %d slave facets once: %s"
                             % (facets, cut))
    if ints(records(os.path.join(three, "state.bin"))["contact.0.cut.ranks"]) != [3]:
        raise AssertionError("state.bin does not give the 3 ranks of the cut")
    # Saddle-point mesh tying: the multipliers by their owners, each (slave node, component)
    # in one part, none in state.bin.
    _, flight = make_case(G.tied_rectangles(0.3, 0.2), flight_yaml("saddle_point", 10))
    tied_one = os.path.join(full_run(flight, 1), "checkpoint_00010")
    tied_three = os.path.join(full_run(flight, 3), "checkpoint_00010")
    keys = sorted(ints(records(os.path.join(tied_one, "part_00000.bin"))["saddle_point.0.keys"]))
    per_part = [ints(records(os.path.join(tied_three, "part_%05d.bin" % r))["saddle_point.0.keys"])
                for r in range(3)]
    print("   saddle-point multipliers per part at np 3: %s of %d"
          % ([len(k) for k in per_part], len(keys)))
    if not keys or sorted(k for p in per_part for k in p) != keys:
        raise AssertionError("the parts do not hold each of the %d multipliers once" % len(keys))
    for path in (os.path.join(one, "state.bin"), os.path.join(three, "state.bin"),
                 os.path.join(tied_one, "state.bin"), os.path.join(tied_three, "state.bin")):
        state = records(path)
        big = [n for n, v in state.items() if n.startswith(("contact.", "saddle_point."))
               and len(v) > 3 * 8]
        if big:
            raise AssertionError("%s holds interface records %s" % (path, big))


def records(path):
    """The records of a checkpoint file as name -> bytes (magic line, then records: uint32 name
    length, name, type byte, uint64 byte count, bytes; a 16-byte trailer)."""
    import struct
    data = open(path, "rb").read()
    pos = data.index(b"\n") + 1
    out = {}
    while pos < len(data) - 16:
        (n,) = struct.unpack_from("<I", data, pos)
        name = data[pos + 4:pos + 4 + n].decode()
        (size,) = struct.unpack_from("<Q", data, pos + 5 + n)
        start = pos + 13 + n
        out[name] = data[start:start + size]
        pos = start + size
    return out


def replace_record(path, name, values):
    """Rewrites record `name` (int64) of a checkpoint file with `values`, its byte count and
    checksum made anew (FNV-1a over the records), as seam would have written it."""
    import struct
    data = open(path, "rb").read()
    head = data.index(b"\n") + 1
    pos, out = head, b""
    while pos < len(data) - 16:
        (n,) = struct.unpack_from("<I", data, pos)
        (size,) = struct.unpack_from("<Q", data, pos + 5 + n)
        start = pos + 13 + n
        body = data[start:start + size]
        if data[pos + 4:pos + 4 + n].decode() == name:
            body = struct.pack("<%dq" % len(values), *values)
        out += data[pos:pos + 5 + n] + struct.pack("<Q", len(body)) + body
        pos = start + size
    h = 0xcbf29ce484222325
    for b in out:
        h = ((h ^ b) * 0x100000001b3) & 0xFFFFFFFFFFFFFFFF
    with open(path, "wb") as f:
        f.write(data[:head] + out + struct.pack("<QQ", len(out), h))


def ints(data):
    """The int64 values of a record."""
    import struct
    return list(struct.unpack("<%dq" % (len(data) // 8), data))


if __name__ == "__main__":
    try:
        H.main([test_static_friction_two_bodies, test_static_slave_side_in_part,
                test_static_slave_side_in_part_independent, test_same_ranks_np3,
                test_same_ranks_rebalanced_np3, test_partition_reproducible,
                test_static_standard_multipliers,
                test_dynamic_friction_generalized_alpha, test_dynamic_contact_generalized_alpha,
                test_energy_momentum_tied_condensed, test_energy_momentum_tied_saddle_point,
                test_energy_momentum_contact,
                test_friction_3d_rigid_plane,
                test_fluid_generalized_alpha, test_fluid_tied, test_fluid_moving_mesh, test_fsi_generalized_alpha,
                test_fsi_static, test_fsi_bad_checkpoints, test_self_contact_surface,
                test_after_step_cuts, test_other_steps, test_moving_obstacle, test_bad_checkpoints, test_parts_not_gathered])
    finally:
        H.cleanup(*_dirs)
