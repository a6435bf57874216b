"""The contact interface distributed over the ranks on its own (CONTRACT.md "Parallel runs";
the seed paper's Sect. 3.1): the slave elements of a contact interface are partitioned
independently of the bulk by weighted recursive coordinate bisection (the facets near contact
separately from the rest), and redistributed after a step whose per-rank work max/min exceeds
parallel.rebalance_tolerance (eq. 21).

Each test can fail:
- results at np = 4 equal np = 1 (reactions 1e-10 relative, the same active sets), with the
  independent and with the bulk distribution;
- every slave element is evaluated on exactly one rank: the pairs and integration cells of
  the ranks (summary.json ranks_detail) add up to the np = 1 counts, and so do the slave
  elements; no rank holds the whole mesh (cells + ghost_cells below the mesh's cells);
- Hertz sphere on a block at np = 4, held at a fixed load so that a redistribution is judged
  on the configuration it was made for: integration cells per rank max/mean <= 1.1 with the
  independent distribution; with `interface_distribution: bulk` the contact zone lies on two
  of the four ranks (max/mean >= 2, min 0): the imbalance of the seed's Fig. 5;
- 2D ironing at np = 4 (the die slides over the slave slab, the contact zone moves across its
  elements): redistributions happen while sliding, and the step after each one is back under
  the tolerance; with SEAM_FULL=1 also equal to np = 1;
- one master surface shared by two slave interfaces (two blocks tied side by side onto one
  block, non-matching) at np = 3: the patch test (uniform uniaxial stress) stays exact;
- `seam check` at np 3 prints what np 1 prints on the refined tied blocks (from a .geo and from
  a .msh) and a line of cells held per rank, none holding the whole mesh;
- with the default measure (CPU time of the interface evaluation) parallel.csv reports
  positive per-rank times and a consistent imbalance column;
- what each rank holds, at np = 3 on the tied blocks (a refined copy of the example): against
  the ghost layer found by brute force from the ranks' output pieces (each piece holds the
  cells its rank owns; a ghost is a cell of another piece sharing a node position with one of
  them), no rank holds more than (its cells + ghosts) * 1.1 cells besides the cells of the
  interface sides, no more of those than touch the interface, and no more nodes than its held
  cells have (ranks_detail nodes, owned_nodes, ghost_nodes, interface_cells); the owned
  cells and nodes add up to the mesh's, no rank owns half of the nodes or holds 0.7 of them;
- the tied interface distributed (two 3 x 1 x 1 blocks tied at z = 1, np = 3): every slave
  facet is integrated on exactly one rank, the ranks hold no cells for the interface sides, the
  interface elements they hold (slave facets integrated, master facets ghosted) add up to at
  most 1.25 x the interface's and no rank holds 0.75 of it; results equal np = 1 to 1e-10;
- the slave facets of tied interfaces cut by RCB on their own (`interface_distribution:
  independent`, the default): on the tied blocks example at np 3 and np 4 and on a cylinder
  tied into a block (tet10, tri6 slave facets with the modified dual basis, bound slave nodes)
  at np 3, the slave facets integrated per rank have max/mean <= 1.1 and add up to np 1's
  (with main's binary before the cut: 0 / 118 / 0 and 97 / 0 / 3), outputs equal np 1 to
  1e-10; with `bulk` the facets of each rank's cells, outputs equal np 1;
- the two-body contact search distributed (Hertz sphere on a block in 3D, 2D ironing with
  friction; np = 1, 2, 3): every rank receives strictly fewer master facets than the master
  surface has (at np = 3 at most 0.65 / 0.5 of it), each rank every master facet its pairs
  reach, the ranks together at least the master facets the np = 1 pairs reach; the ranks'
  pairs add up to np = 1's, reactions.csv and interfaces.csv equal np = 1 to 1e-10; the same
  runs check what a rank reads: its mortar integration as many master facets as were ghosted
  to it, its displacement scatter at np > 1 strictly fewer nodes than the interface has
  (ranks_detail contact_interface_nodes_gathered), every output (active sets included) equal
  to np = 1 to 1e-10;
- the self-contact search distributed (a pile of 7 rings from examples/rings, 2D, until the
  rings touch; the two blocks of test_self_contact.py as one `surface:` interface, 3D
  tetrahedra): at np = 3 every rank receives strictly fewer surface facets than the surface
  has, and the results (steps.csv energies and momenta, interfaces.csv, reactions.csv,
  interface_*.csv, probes.csv) equal np = 1 to 1e-10;
- the master side of two-body contact held in part (Hertz sphere on a block, np 3): every rank
  holds strictly fewer master facets than the side has, the ranks together at most 1.4 x of
  it, and every output equals np 1 to 1e-10; the same equality on 2D ironing without
  friction at np 3;
- the slave side of two-body contact held in part, with the bulk and with the independent
  distribution, with and without friction (Hertz and 2D ironing at np 3, and after the
  rebalancings of the Hertz case and of the sliding ironing at np 4): no rank holds the whole
  slave side, and every output equals np 1 to 1e-10;
- the slave side of contact against a rigid obstacle held in part, bulk and independent (Hertz
  sphere on a rigid plane, a block dragged on a rigid plane with Coulomb friction, a ring
  thrown onto a rigid circle with Coulomb friction and generalized-alpha, rebalanced while it
  rolls; np 3): no rank holds the whole slave side, the ranks together at most 1.3 to 1.6 x
  of it, and every output equals np 1 to 1e-10;
- the cells a rank holds with contact sides held in part and the independent distribution
  (Hertz sphere on a block and on a rigid plane, np 3): no rank holds more than (its owned +
  ghost cells) x 1.1, the slave facets beyond them reaching it as facets, and every output
  equals np 1 to 1e-10;
- the ghosting reused (Verlet skin): on the two blocks and on the Hertz sphere (bodies that
  move little) at np = 3 the ghosts are exchanged at fewer searches than there are searches,
  and the results equal those of a run that exchanges at every search (SEAM_GHOST_SKIN=0,
  which then reports as many exchanges as searches) to 1e-12.
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402
import vtu_reader  # noqa: E402

_dirs = []


def run_example(name, yaml, np, replace=()):
    """Runs a copy of an example with text replacements; returns the output directory."""
    work, path = H.copy_example(name, yaml, replace)
    _dirs.append(work)
    out = H.solve(path, np=np)
    _dirs.append(out)
    return out


def rows_of(out, name):
    return H.read_csv(os.path.join(out, name))


def compare_reactions(a, b, rtol, what):
    ra, rb = rows_of(a, "reactions.csv"), rows_of(b, "reactions.csv")
    if len(ra) != len(rb):
        raise AssertionError("%s: %d reaction rows against %d" % (what, len(ra), len(rb)))
    scale = max(abs(r[k]) for r in ra for k in ("fx", "fy", "fz")) or 1.0
    worst = max(abs(x[k] - y[k]) / scale for x, y in zip(ra, rb) for k in ("fx", "fy", "fz"))
    print("   %s: reactions differ by %.2e (relative to %.3g)" % (what, worst, scale))
    if worst > rtol:
        raise AssertionError("%s: reactions differ by %.3e" % (what, worst))
    sa = [r["active_nodes"] for r in rows_of(a, "steps.csv")]
    sb = [r["active_nodes"] for r in rows_of(b, "steps.csv")]
    if sa != sb:
        raise AssertionError("%s: active nodes per step differ: %s vs %s" % (what, sa, sb))


def ranks_detail(out):
    return H.read_json(os.path.join(out, "summary.json"))["ranks_detail"]


def check_counts_add_up(one, many, what):
    """Every slave element on exactly one rank: the ranks' counts add up to the serial ones."""
    d1, dn = ranks_detail(one), ranks_detail(many)
    for key in ("slave_elements", "pairs", "integration_cells", "cells"):
        total = sum(r[key] for r in dn)
        if total != d1[0][key]:
            raise AssertionError("%s: %s summed over %d ranks = %d, one rank: %d"
                                 % (what, key, len(dn), total, d1[0][key]))
    # The mesh is distributed: each rank holds its cells, a ghost layer and the interface
    # sides' cells, never the whole mesh (np = 1 holds it all, with no ghosts).
    if d1[0]["ghost_cells"] != 0:
        raise AssertionError("%s: one rank holds ghost cells: %s" % (what, d1[0]))
    for r in dn:
        held = r["cells"] + r["ghost_cells"]
        if not r["cells"] <= held < d1[0]["cells"] or r["peak_rss_mb"] <= 0.0:
            raise AssertionError("%s: ranks_detail of rank %d: %s" % (what, r["rank"], r))


HOLD = (("-0.03*t", "-0.03*min(t,0.6)"), ("steps: 5", "steps: 6"))


def hertz(np, distribution, tolerance=1.0):
    """The sphere on a block, pressed to 0.6 of the example's stroke by step 4 and held there
    for steps 5 and 6; the balance counts integration cells (deterministic)."""
    return run_example("hertz_3d", "sphere_block.yaml", np, HOLD + (
        ("solver:", "parallel: {interface_distribution: %s, work: integration_cells, "
                    "rebalance_tolerance: %g}\nsolver:" % (distribution, tolerance)),))


def test_hertz_independent_against_bulk_np4():
    one = hertz(1, "independent")
    independent = hertz(4, "independent")
    bulk = hertz(4, "bulk")
    compare_reactions(one, independent, 1e-10, "np 4 independent vs np 1")
    compare_reactions(one, bulk, 1e-10, "np 4 bulk vs np 1")
    check_counts_add_up(one, independent, "independent")
    check_counts_add_up(one, bulk, "bulk")
    # Redistributed with the slave side held in part: no rank holds it whole.
    n_s = H.read_json(os.path.join(independent, "summary.json"))["interfaces"][0]["slave_elements"]
    held = [(r["contact_slave_facets_held"], r["slave_elements"]) for r in ranks_detail(independent)]
    print("   independent np 4: slave facets held / evaluated per rank %s of %d"
          % (" ".join("%d/%d" % h for h in held), n_s))
    if any(h >= n_s for h, _ in held):
        raise AssertionError("independent np 4: slave facets held / evaluated %s of %d" % (held, n_s))
    rows_i, rows_b = rows_of(independent, "parallel.csv"), rows_of(bulk, "parallel.csv")
    for r in rows_i:
        print("   independent step %d: integration cells per rank min %g mean %g max %g, "
              "max/mean %.3f, redistributed %d" % (r["step"], r["min_work"], r["mean_work"],
                                                   r["max_work"], r["max_work"] / r["mean_work"],
                                                   r["redistributed"]))
    last_b = rows_b[-1]
    print("   bulk step %d: min %g mean %g max %g, max/mean %.3f, redistributed %s"
          % (last_b["step"], last_b["min_work"], last_b["mean_work"], last_b["max_work"],
             last_b["max_work"] / last_b["mean_work"], sorted({r["redistributed"] for r in rows_b})))
    # Steps 5 and 6 see the configuration their partition was made for (held load).
    for r in rows_i[-2:]:
        if r["max_work"] / r["mean_work"] > 1.1:
            raise AssertionError("independent: max/mean %.3f > 1.1 at step %d"
                                 % (r["max_work"] / r["mean_work"], r["step"]))
    if rows_i[0]["redistributed"] != 1:
        raise AssertionError("independent: no redistribution after step 1 at tolerance 1")
    if any(r["redistributed"] for r in rows_b):
        raise AssertionError("bulk: the interface was redistributed")
    if last_b["min_work"] != 0 or last_b["max_work"] / last_b["mean_work"] < 2.0:
        raise AssertionError("bulk: expected the contact zone on at most two of four ranks")
    H.cleanup(*_dirs)


def test_hertz_held_never_redistributes():
    """At the default tolerance 1.2, a redistribution is made while the contact zone grows;
    once the load is held, the partition it left stays under the tolerance: no more moves."""
    out = hertz(3, "independent", tolerance=1.2)
    rows = rows_of(out, "parallel.csv")
    print("   np 3: imbalance per step %s, redistributed %s"
          % (["%.3f" % r["imbalance"] for r in rows], [r["redistributed"] for r in rows]))
    for r in rows:
        if (r["imbalance"] > 1.2) != (r["redistributed"] == 1):
            raise AssertionError("step %d: imbalance %.3f and redistributed %d disagree"
                                 % (r["step"], r["imbalance"], r["redistributed"]))
    if any(r["redistributed"] for r in rows if r["step"] >= 5):
        raise AssertionError("redistributed under a held load")
    H.cleanup(*_dirs)


IRONING = (("time: {integrator: static, end: 2, steps: 140}",
            "time: {integrator: static, end: 1.3, steps: 52}\n"
            "parallel: {work: integration_cells}"), ("every: 10", "every: 1000"))

IRONING_SHORT = (("time: {integrator: static, end: 2, steps: 140}",
                  "time: {integrator: static, end: 1.1, steps: 22}"), ("every: 10", "every: 1000"))


def test_ironing_rebalances_np4():
    """The die presses into the slab for t <= 1 and slides from then on: the contact zone moves
    across the slave elements, and the balance follows it."""
    four = run_example("ironing", "ironing_2d.yaml", 4, IRONING)
    if H.FULL:  # np = 4 against np = 1 is also checked on the Hertz case above
        one = run_example("ironing", "ironing_2d.yaml", 1, IRONING)
        compare_reactions(one, four, 1e-8, "ironing np 4 vs np 1")
        check_counts_add_up(one, four, "ironing")
    rows = rows_of(four, "parallel.csv")
    sliding = [r for r in rows if r["time"] > 1.05]
    moves = [r["step"] for r in sliding if r["redistributed"]]
    print("   sliding steps %d..%d: redistributed after steps %s; imbalance %s"
          % (sliding[0]["step"], sliding[-1]["step"], moves,
             " ".join("%.2f" % r["imbalance"] for r in sliding)))
    if not moves:
        raise AssertionError("no redistribution while the die slides")
    # The slave side (with Coulomb friction, independent distribution) held in part after the
    # redistributions: no rank holds it whole.
    n_s = H.read_json(os.path.join(four, "summary.json"))["interfaces"][0]["slave_elements"]
    held = [r["contact_slave_facets_held"] for r in ranks_detail(four)]
    print("   np 4: slave facets held per rank %s of %d" % ("/".join(map(str, held)), n_s))
    if max(held) >= n_s:
        raise AssertionError("np 4: slave facets held per rank %s of %d" % (held, n_s))
    by_step = {r["step"]: r for r in rows}
    for s in moves:
        after = by_step.get(s + 1)
        if after and after["imbalance"] > 1.2:
            raise AssertionError("step %d after the redistribution: imbalance %.3f > 1.2"
                                 % (s + 1, after["imbalance"]))
    H.cleanup(*_dirs)


def test_time_measure_np2():
    """The default measure: each rank's CPU time of the interface evaluation in the step."""
    out = run_example("hertz_3d", "sphere_block.yaml", 2)
    rows = rows_of(out, "parallel.csv")
    for r in rows:
        if not (0.0 < r["min_work"] <= r["mean_work"] <= r["max_work"]):
            raise AssertionError("step %d: per-rank times %s" % (r["step"], r))
        H.assert_close(r["imbalance"], r["max_work"] / r["min_work"], rtol=1e-12,
                       what="imbalance = max/min")
        if r["ranks"] != 2:
            raise AssertionError("ranks column %s" % r["ranks"])
    print("   np 2: interface CPU seconds per step (max) %s"
          % " ".join("%.3f" % r["max_work"] for r in rows))
    H.cleanup(*_dirs)


SHARED_GEO = """Geometry.AutoCoherence = 0;
Point(1) = {0, 0, 0, 0.23}; Point(2) = {2, 0, 0, 0.23}; Point(3) = {2, 1, 0, 0.23};
Point(4) = {0, 1, 0, 0.23};
Point(5) = {0, 1, 0, 0.17}; Point(6) = {1, 1, 0, 0.17}; Point(7) = {1, 2, 0, 0.17};
Point(8) = {0, 2, 0, 0.17};
Point(9) = {1, 1, 0, 0.29}; Point(10) = {2, 1, 0, 0.29}; Point(11) = {2, 2, 0, 0.29};
Point(12) = {1, 2, 0, 0.29};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Line(9) = {9, 10}; Line(10) = {10, 11}; Line(11) = {11, 12}; Line(12) = {12, 9};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Curve Loop(3) = {9, 10, 11, 12}; Plane Surface(3) = {3};
Recombine Surface{2};
Physical Surface("lower") = {1}; Physical Surface("upper_left") = {2};
Physical Surface("upper_right") = {3};
Physical Curve("bottom") = {1}; Physical Curve("top") = {7, 11}; Physical Curve("left") = {4, 8};
Physical Curve("lower_top") = {3}; Physical Curve("left_bottom") = {5};
Physical Curve("right_bottom") = {9};
"""

E, NU, T = 200.0, 0.3, 1.5
SHARED_PROBES = [[0.37, 0.61], [1.6, 0.3], [0.5, 1.5], [0.2, 1.9], [1.7, 1.8], [1.3, 1.1]]


def shared_yaml(multiplier):
    return """dimension: 2
mesh: {geo: shared.geo}
materials:
  steel: {model: linear_elastic, young: %g, poisson: %g}
bodies:
  - {region: lower, material: steel}
  - {region: upper_left, material: steel}
  - {region: upper_right, material: steel}
boundary_conditions:
  - {region: bottom, type: dirichlet, components: [y], value: [0]}
  - {region: left, type: dirichlet, components: [x], value: [0]}
  - {region: top, type: traction, value: [0, %g]}
interfaces:
  - {name: tie_left, type: mesh_tying, slave: left_bottom, master: lower_top, multiplier: %s}
  - {name: tie_right, type: mesh_tying, slave: right_bottom, master: lower_top, multiplier: %s}
time: {integrator: static, end: 1, steps: 1}
output: {probes: %s}
""" % (E, NU, T, multiplier, multiplier, SHARED_PROBES)


def test_shared_master_patch_np3():
    """Two blocks side by side (their own nodes at x = 1, not connected) tied onto one lower
    block through one master surface; pulled by a uniform traction T on their tops. Plane
    strain: u_x = -nu (1 + nu) T / E x, u_y = (1 - nu^2) T / E y in all three bodies."""
    exx, eyy = -NU * (1 + NU) * T / E, (1 - NU ** 2) * T / E
    for multiplier in ("dual", "standard"):
        for np in (1, 3):
            work = tempfile.mkdtemp(prefix="seam_shared_")
            _dirs.append(work)
            H.write_case(work, "shared.geo", SHARED_GEO)
            path = H.write_case(work, "shared.yaml", shared_yaml(multiplier))
            out = H.solve(path, np=np)
            _dirs.append(out)
            worst = 0.0
            for p in H.last_step_rows(rows_of(out, "probes.csv")):
                exact = (exx * p["x"], eyy * p["y"])
                worst = max(worst, abs(p["ux"] - exact[0]) / abs(eyy * 2),
                            abs(p["uy"] - exact[1]) / abs(eyy * 2))
            reaction = sum(r["fy"] for r in H.last_step_rows(rows_of(out, "reactions.csv"))
                           if r["region"] == "bottom")
            print("   %s multipliers, np %d: probes off the exact field by %.2e (relative), "
                  "bottom reaction %.12g (exact %g)" % (multiplier, np, worst, reaction, -2 * T))
            if worst > 1e-10:
                raise AssertionError("patch test not exact: %.3e" % worst)
            H.assert_close(reaction, -2 * T, rtol=1e-10, what="bottom reaction")
    H.cleanup(*_dirs)


def refined_blocks():
    """The tied blocks example refined (11 x 11 x 11 hexahedra, tetrahedra of size 0.1), one
    step: (work directory, input path)."""
    work, path = H.copy_example("tied_blocks", "blocks.yaml", (("steps: 5}", "steps: 1}"),))
    _dirs.append(work)
    geo = os.path.join(work, "blocks.geo")
    with open(geo) as f:
        text = f.read()
    for a, b in (("Curve{1:12} = 6;", "Curve{1:12} = 12;"), ("= 0.15;", "= 0.1;")):
        if a not in text:
            raise AssertionError("blocks.geo: '%s' not found" % a)
        text = text.replace(a, b)
    with open(geo, "w") as f:
        f.write(text)
    return work, path


def test_check_distributed_np3():
    """`seam check` sets up the mesh as a run does, distributed: on the refined tied blocks,
    from the .geo (meshed on rank 0, which sends the parts) and from a binary MSH 4.1 file
    (read in chunks), np 3 reports what np 1 reports (counts, cell types, regions, the tied
    interface's facets and integration cells; the mesh initialization's relocation, a
    round-off figure, is left out) and a line of cells held per rank, each below the mesh's."""
    import re
    import subprocess
    work, path = refined_blocks()
    msh = os.path.join(work, "blocks.msh")
    subprocess.run(["gmsh", "-3", "-bin", "-format", "msh41", os.path.join(work, "blocks.geo"),
                    "-o", msh], check=True, stdout=subprocess.DEVNULL)
    with open(path) as f:
        text = f.read()
    if "geo: blocks.geo" not in text:
        raise AssertionError("blocks.yaml: 'geo: blocks.geo' not found")
    from_file = H.write_case(work, "from_file.yaml", text.replace("geo: blocks.geo",
                                                                  "file: blocks.msh"))
    held_line = re.compile(r"cells held per rank \(own, ghost layer, interface sides\): "
                           r"([0-9 /]+) of (\d+)")

    def report(yaml, np):
        _, out, _ = H.run(["check", yaml], np=np)
        lines = [re.sub(r"moved by at most \S+", "moved by at most X", line)
                 for line in out.splitlines() if line.startswith(" ") or line.endswith(": ok")]
        held = [line for line in lines if held_line.search(line)]
        return [line for line in lines if line not in held], held

    for yaml, what in ((path, ".geo"), (from_file, ".msh")):
        one, held_one = report(yaml, 1)
        three, held = report(yaml, 3)
        if held_one:
            raise AssertionError("%s: np 1 reports cells held per rank: %s" % (what, held_one))
        if one != three:
            raise AssertionError("%s: seam check np 1 and np 3 differ:\n%s\n---\n%s"
                                 % (what, "\n".join(one), "\n".join(three)))
        if len(held) != 1:
            raise AssertionError("%s: np 3 does not report the cells held per rank:\n%s"
                                 % (what, "\n".join(three)))
        m = held_line.search(held[0])
        per_rank, total = [int(v) for v in m.group(1).split("/")], int(m.group(2))
        if len(per_rank) != 3 or max(per_rank) >= total:
            raise AssertionError("%s: cells held per rank %s of %d: a rank holds the whole mesh"
                                 % (what, per_rank, total))
        print("   seam check %s: np 3 reports what np 1 does; cells held per rank %s of %d"
              % (what, " / ".join(str(v) for v in per_rank), total))


def test_held_cells_np3():
    # Refined: the interface sides' cells, which every rank holds, are then a small part of
    # each rank's cells.
    work, path = refined_blocks()
    out = H.solve(path, np=3)
    _dirs.append(out)
    summary = H.read_json(os.path.join(out, "summary.json"))
    detail = summary["ranks_detail"]
    pieces = vtu_reader.read_pieces(os.path.join(out, "results_00000.pvtu"))
    if len(pieces) != 3 or len(detail) != 3:
        raise AssertionError("%d pieces, %d ranks_detail entries" % (len(pieces), len(detail)))

    def key(p):
        return tuple(round(v, 9) for v in p)

    # Cells as sets of node positions (two bodies touching at z = 1 may share a position:
    # that only makes the brute-force ghost layer larger, never smaller).
    cells = [[frozenset(key(piece["points"][i]) for i in c) for c in piece["cells"]]
             for piece in pieces]
    # Cells with a facet on the tied plane z = 1 (3 or more nodes there): the interface cells.
    on_plane = sum(1 for part in cells for c in part
                   if sum(1 for p in c if abs(p[2] - 1.0) < 1e-9) >= 3)
    total_cells = sum(len(part) for part in cells)
    if total_cells != summary["cells"]:
        raise AssertionError("pieces hold %d cells, the mesh %d" % (total_cells, summary["cells"]))
    if sum(r["owned_nodes"] for r in detail) != summary["nodes"]:
        raise AssertionError("owned nodes add up to %d, the mesh has %d"
                             % (sum(r["owned_nodes"] for r in detail), summary["nodes"]))
    layers = []
    for r, part in enumerate(cells):
        mine = set().union(*part)
        ghosts = [c for q, other in enumerate(cells) if q != r for c in other if c & mine]
        layers.append((ghosts, set(mine).union(*ghosts)))
        d = detail[r]
        print("   rank %d: owns %d cells, holds %d (ghost layer by brute force %d, interface "
              "cells %d of %d touching z = 1); nodes held %d, owned %d + ghost %d, of the "
              "layer %d; mesh %d cells, %d nodes" % (
                  r, d["cells"], d["cells"] + d["ghost_cells"], len(ghosts),
                  d["interface_cells"], on_plane, d["nodes"], d["owned_nodes"], d["ghost_nodes"],
                  len(layers[-1][1]), summary["cells"], summary["nodes"]))
    for r, part in enumerate(cells):
        d = detail[r]
        ghosts, layer_nodes = layers[r]
        held = d["cells"] + d["ghost_cells"]
        if d["cells"] != len(part):
            raise AssertionError("rank %d assembles %d cells, its piece has %d"
                                 % (r, d["cells"], len(part)))
        if held - d["interface_cells"] > 1.1 * (len(part) + len(ghosts)):
            raise AssertionError("rank %d holds %d cells besides the interface cells, more "
                                 "than 1.1 x (%d own + %d ghosts)"
                                 % (r, held - d["interface_cells"], len(part), len(ghosts)))
        if d["interface_cells"] > on_plane:
            raise AssertionError("rank %d holds %d interface cells, only %d touch the interface"
                                 % (r, d["interface_cells"], on_plane))
        if d["owned_nodes"] + d["ghost_nodes"] > d["nodes"]:
            raise AssertionError("rank %d: owned + ghost nodes exceed the nodes it holds" % r)
        # The nodes held are those of the held cells: the layer's plus the interface cells'.
        if d["nodes"] > 1.1 * len(layer_nodes) + 8 * d["interface_cells"]:
            raise AssertionError("rank %d holds %d nodes, its cells and ghosts have %d"
                                 % (r, d["nodes"], len(layer_nodes)))
        # Cells are weighted by their nodes in the partition (a hexahedron weighs about ten
        # tetrahedra), so the owned nodes are balanced, not the cells.
        if d["owned_nodes"] > 0.5 * summary["nodes"] or d["nodes"] > 0.7 * summary["nodes"]:
            raise AssertionError("rank %d owns %d and holds %d of the %d nodes"
                                 % (r, d["owned_nodes"], d["nodes"], summary["nodes"]))
    H.cleanup(*_dirs)


SADDLE_POINT = (("multiplier: dual", "multiplier: standard"),
                ("strategy: condensed", "strategy: saddle_point"))


def wide_tied_case(replace=()):
    """The tied blocks example stretched to two 3 x 1 x 1 blocks (one step): the bulk
    partition cuts the bar along its length, so every rank owns a part of the interface.
    `replace`: further (old, new) edits of the input (SADDLE_POINT: standard multipliers)."""
    work, path = H.copy_example("tied_blocks", "blocks.yaml",
                                (("steps: 5}", "steps: 1}"),) + tuple(replace))
    _dirs.append(work)
    geo = os.path.join(work, "blocks.geo")
    with open(geo) as f:
        text = f.read()
    for a, b in (("Box(1) = {0, 0, 0, 1, 1, 1};", "Box(1) = {0, 0, 0, 3, 1, 1};"),
                 ("Box(2) = {0, 0, 1, 1, 1, 1};", "Box(2) = {0, 0, 1, 3, 1, 1};")):
        if a not in text:
            raise AssertionError("blocks.geo: '%s' not found" % a)
        text = text.replace(a, b)
    with open(geo, "w") as f:
        f.write(text)
    return path


def test_tied_interface_part_np3():
    """Mesh tying distributed (docs/parallel.md, "Mesh tying distributed"). Bounds: each
    slave facet is integrated by one rank (its part of the RCB cut), so the slave counts add
    up to the interface's exactly; a master facet is ghosted to every rank whose slave part its box
    overlaps: one rank, two or three near the cuts between the parts, so the master copies
    exceed the master facets only by the facets along the cuts (1.25 x the whole interface
    bounds both together). Replicated, every rank held all interface cells."""
    check_tied_part(wide_tied_case())


def test_saddle_point_tying_part_np3():
    """The same with standard multipliers as unknowns of the saddle-point system (docs/
    parallel.md, "Saddle-point tying distributed"): the mesh initialization D X_S = M X_M (D
    not diagonal) solved distributed, the multipliers numbered by the slave nodes' owners.
    Held whole before, every rank integrated the whole interface (np 3: each rank's slave
    facets the whole side's, failing the sum)."""
    check_tied_part(wide_tied_case(SADDLE_POINT))


def curved_saddle_yaml(slave, master):
    """A disk tied into a plate's hole by standard multipliers (test_mesh_tying.py's curved
    patch test, stretched by a traction): the non-matching circles make the mesh
    initialization move the slave nodes."""
    return "\n".join([
        "dimension: 2", "plane: strain", "mesh: {geo: case.geo}",
        "materials: {m: {model: linear_elastic, young: 100, poisson: 0.3}}",
        "bodies: [{region: plate, material: m}, {region: disk, material: m}]",
        "boundary_conditions:",
        "  - {region: left, type: dirichlet, components: [x], value: [0]}",
        "  - {region: bottom, type: dirichlet, components: [y], value: [0]}",
        "  - {region: right, type: traction, value: [2, 0]}",
        "interfaces:",
        "  - {name: tie, type: mesh_tying, slave: %s, master: %s, multiplier: standard, "
        "strategy: saddle_point}" % (slave, master),
        "time: {integrator: static, end: 1, steps: 1}",
        "output: {probes: [[0.1, 0.2], [0.45, 0.1], [-0.8, 0.7], [0.0, 0.5]]}"]) + "\n"


def test_saddle_point_mesh_initialization_np3():
    """The mesh initialization D X_S = M X_M with standard multipliers (D not diagonal) solved
    distributed on the slave nodes' owners (docs/parallel.md, "Saddle-point tying
    distributed"), linear and quadratic curved interfaces: the relocated slave nodes
    (interface_tie.csv's x, y), the largest move and the results at np 3 equal np 1; the
    slave nodes move (1.8e-3 and 1.3e-6 of the radius 0.5), and each slave facet is integrated
    once, the facets per rank max/mean <= 1.1 (the independent distribution)."""
    import geometry
    for order, slave, master in ((1, "rim", "hole"), (2, "hole", "rim")):
        geo = geometry.plate_with_inclusion(0.1, 0.06, order)
        outs = {np: run_case(geo, curved_saddle_yaml(slave, master), np) for np in (1, 3)}
        what = "curved, order %d" % order
        moved = [H.read_json(os.path.join(outs[np], "summary.json"))["interfaces"][0]
                 ["max_slave_relocation"] for np in (1, 3)]
        detail = ranks_detail(outs[3])
        n_s = H.read_json(os.path.join(outs[3], "summary.json"))["interfaces"][0]["slave_elements"]
        print("   %s: slave nodes moved by at most %.6e (np 1), %.6e (np 3); slave facets per "
              "rank %s of %d" % (what, moved[0], moved[1], [d["slave_elements"] for d in detail],
                                 n_s))
        if not moved[0] > 1e-9:
            raise AssertionError("%s: the slave nodes did not move (%.3e)" % (what, moved[0]))
        if abs(moved[0] - moved[1]) > 1e-12 * moved[0]:
            raise AssertionError("%s: largest move %.17g at np 1, %.17g at np 3" % (what, *moved))
        if sum(d["slave_elements"] for d in detail) != n_s or max(
                d["slave_elements"] for d in detail) == n_s:
            raise AssertionError("%s: slave facets per rank %s of %d"
                                 % (what, [d["slave_elements"] for d in detail], n_s))
        # Cut by RCB (the facets arrive with those around their nodes, whose averaged normals
        # the 2D projection reads): balanced to max/mean 1.1.
        tied_share(outs[1], outs[3], what, 1.1)
        compare_tied(outs[1], outs[3], what)
    H.cleanup(*_dirs)


def compare_tied(one, three, what):
    """probes, reactions, interfaces.csv and interface_tie.csv: np 3 against np 1, relative to
    the largest value of each group of columns (a vector's components together: a component
    that vanishes is compared with the vector's size, not with its own round-off)."""
    for name, groups in (("probes.csv", (("ux", "uy", "uz"),)),
                         ("reactions.csv", (("fx", "fy", "fz"),)),
                         ("interfaces.csv", (("normal_force", "tangential_force"),)),
                         ("interface_tie.csv", (("x", "y", "z"), ("ux", "uy", "uz"),
                                                ("normal_traction", "tangential_traction")))):
        a, b = rows_of(one, name), rows_of(three, name)
        if len(a) != len(b):
            raise AssertionError("%s: %s: %d rows at np 1, %d at np 3" % (what, name, len(a), len(b)))
        worst = 0.0
        for keys in groups:
            scale = max(abs(r[k]) for r in a for k in keys) or 1.0
            worst = max([worst] + [abs(x[k] - y[k]) / scale for x, y in zip(a, b) for k in keys])
        if name == "interface_tie.csv" and any(x["node"] != y["node"] or x["status"] != y["status"]
                                               for x, y in zip(a, b)):
            raise AssertionError("%s: interface_tie.csv: nodes or status differ" % what)
        print("   %s: %s: np 3 against np 1, largest difference %.2e (relative)" % (what, name, worst))
        # The sums run in another order at np 3 and PT-Scotch's cut varies from run to run:
        # 2.8e-13, 8.95e-13 and 1.6e-12 measured in three runs; 1e-10 is far below any tying error.
        if worst > 1e-10:
            raise AssertionError("%s: %s differs by %.3e" % (what, name, worst))


def check_tied_part(path):
    outs = {}
    for np in (1, 3):
        out = H.solve(path, np=np)
        _dirs.append(out)
        outs[np] = out
    summary = H.read_json(os.path.join(outs[3], "summary.json"))
    serial = H.read_json(os.path.join(outs[1], "summary.json"))
    itf = summary["interfaces"][0]
    n_s, n_m = itf["slave_elements"], itf["master_elements"]
    total = n_s + n_m
    detail = summary["ranks_detail"]
    held = [d["slave_elements"] + d["master_ghosts"] + d["interface_cells"] for d in detail]
    for r, d in enumerate(detail):
        print("   rank %d: slave facets %d, master ghosts %d, interface cells %d, pairs %d, "
              "integration cells %d (interface: %d slave, %d master facets)"
              % (r, d["slave_elements"], d["master_ghosts"], d["interface_cells"], d["pairs"],
                 d["integration_cells"], n_s, n_m))
    if sum(d["slave_elements"] for d in detail) != n_s:
        raise AssertionError("slave facets integrated: %d over the ranks, the interface has %d"
                             % (sum(d["slave_elements"] for d in detail), n_s))
    for key in ("pairs", "integration_cells"):
        got = sum(d[key] for d in detail)
        want = serial["ranks_detail"][0][key]
        if got != want:
            raise AssertionError("%s: %d over the ranks, %d at np 1" % (key, got, want))
    if any(d["interface_cells"] != 0 for d in detail):
        raise AssertionError("ranks hold cells for the interface sides: %s"
                             % [d["interface_cells"] for d in detail])
    if sum(held) > 1.25 * total:
        raise AssertionError("interface elements held: %d over the ranks, more than 1.25 x %d"
                             % (sum(held), total))
    if max(held) >= 0.75 * total:
        raise AssertionError("a rank holds %d of the %d interface elements" % (max(held), total))
    compare_tied(outs[1], outs[3], "np 3")
    H.cleanup(*_dirs)


def tied_share(serial, out, what, balance):
    """Slave facets integrated per rank (ranks_detail slave_elements): they, the pairs and the
    integration cells add up to np 1's; with `balance`, max/mean of the facets is at most it.
    Returns max/mean."""
    n_s = H.read_json(os.path.join(out, "summary.json"))["interfaces"][0]["slave_elements"]
    detail, one = ranks_detail(out), ranks_detail(serial)[0]
    share = [d["slave_elements"] for d in detail]
    ratio = max(share) * len(share) / float(sum(share))
    print("   %s: slave facets integrated per rank %s of %d, max/mean %.3f"
          % (what, share, n_s, ratio))
    if sum(share) != n_s or n_s != one["slave_elements"]:
        raise AssertionError("%s: slave facets %s add up to %d, the interface has %d (np 1: %d)"
                             % (what, share, sum(share), n_s, one["slave_elements"]))
    for key in ("pairs", "integration_cells"):
        if sum(d[key] for d in detail) != one[key]:
            raise AssertionError("%s: %s %d over the ranks, %d at np 1"
                                 % (what, key, sum(d[key] for d in detail), one[key]))
    if balance is not None and ratio > balance:
        raise AssertionError("%s: slave facets per rank %s: max/mean %.3f above %.2f"
                             % (what, share, ratio, balance))
    return ratio


def test_tied_independent_np3():
    """The slave facets of a tied interface cut by RCB over all ranks (`interface_distribution:
    independent`, the default; docs/parallel.md "Mesh tying distributed"): on the tied blocks
    example (118 slave facets on the plane z = 1, which the bulk partition gives to one or two
    of the ranks' cells), at np 3 and np 4 the slave facets integrated per rank have max/mean
    <= 1.1, they, the pairs and the integration cells add up to np 1's, and every output equals
    np 1 to 1e-10; with `interface_distribution: bulk` the facets of each rank's cells (the
    imbalance printed), the same sums and equality."""
    work, path = H.copy_example("tied_blocks", "blocks.yaml", (("steps: 5}", "steps: 1}"),))
    _dirs.append(work)
    bulk = H.write_case(work, "bulk.yaml", open(path).read().replace(
        "time:", "parallel: {interface_distribution: bulk}\ntime:", 1))
    outs = {}
    for key, yaml, np in ((1, path, 1), (3, path, 3), (4, path, 4), ("bulk", bulk, 3)):
        outs[key] = H.solve(yaml, np=np)
        _dirs.append(outs[key])
    for np in (3, 4):
        tied_share(outs[1], outs[np], "independent, np %d" % np, 1.1)
        compare_tied(outs[1], outs[np], "independent, np %d" % np)
    tied_share(outs[1], outs["bulk"], "bulk, np 3", None)
    compare_tied(outs[1], outs["bulk"], "bulk, np 3")
    H.cleanup(*_dirs)


def test_tied_curved_quadratic_independent_np3():
    """A cylinder tied into a block's hole (non-matching curved interface, tetrahedra of order
    2: tri6 slave facets with dual multipliers, whose displacement basis is modified, d = T d~,
    and whose nodal normals average the facets around each node), the base clamped (the slave
    nodes at z = 0 bound) and the block pulled sideways and up: with the independent
    distribution at np 3 the slave facets integrated per rank have max/mean <= 1.1, add up
    to np 1's, and every output (the relocated slave nodes included) equals np 1 to 1e-10."""
    import geometry
    geo = geometry.block_with_cylinder(0.5, 0.3, 2)
    yaml = "\n".join([
        "dimension: 3", "mesh: {geo: case.geo}",
        "materials: {m: {model: linear_elastic, young: 100, poisson: 0.3}}",
        "bodies: [{region: block, material: m}, {region: cylinder, material: m}]",
        "boundary_conditions:",
        "  - {region: base, type: dirichlet, components: [x, y, z], value: [0, 0, 0]}",
        "  - {region: right, type: traction, value: [2, 0, 1]}",
        "interfaces:",
        "  - {name: tie, type: mesh_tying, slave: mantle, master: hole, multiplier: dual, "
        "strategy: condensed}",
        "time: {integrator: static, end: 1, steps: 1}",
        "output: {probes: [[0.1, 0.2, 0.5], [0.45, 0.1, 0.9], [-0.8, 0.7, 0.5], [0.0, 0.5, 1.0]]}"]) + "\n"
    outs = {np: run_case(geo, yaml, np) for np in (1, 3)}
    moved = H.read_json(os.path.join(outs[1], "summary.json"))["interfaces"][0]["max_slave_relocation"]
    print("   slave nodes moved by at most %.3e at np 1" % moved)
    if not moved > 1e-9:
        raise AssertionError("the slave nodes did not move (%.3e)" % moved)
    tied_share(outs[1], outs[3], "curved quadratic, np 3", 1.1)
    compare_tied(outs[1], outs[3], "curved quadratic, np 3")
    H.cleanup(*_dirs)


def contact_part_case(np, friction):
    """The sphere on a block (examples/hertz_3d/sphere_block.yaml) in three load steps, the
    slave facets integrated by the ranks owning their cells (`interface_distribution: bulk`);
    with `friction`, Coulomb friction mu = 0.3 (stick in the centre, slip at the rim)."""
    replace = [("steps: 5", "steps: 3"),
               ("solver:", "parallel: {interface_distribution: bulk}\nsolver:")]
    if friction:
        replace.append(("    multiplier: dual",
                        "    multiplier: dual\n    friction: {model: coulomb, coefficient: 0.3}"))
    return run_example("hertz_3d", "sphere_block.yaml", np, tuple(replace))


def check_contact_part(friction):
    """Contact distributed by the bulk partition (docs/parallel.md, "Contact distributed"):
    each rank integrates the slave facets of its own cells; the partial D_jj, g~_j (and slip
    increments) go to the owners of the slave nodes, which decide the nodes' status and
    publish the sums and decisions. Bounds: the slave facets, pairs and integration cells of
    the ranks add up to the interface's (each facet on one rank); the nodes the ranks decide
    add up to the nodes with nonzero sums at np 1 (each decided by its owner only); the nodal
    records sent to the owners number at most 1.5 x those nodes (a node gets one record per
    rank holding a facet around it: one, or two or three along the cuts); np 3 equals np 1."""
    what = "friction" if friction else "frictionless"
    one, three = contact_part_case(1, friction), contact_part_case(3, friction)
    d1, d3 = ranks_detail(one), ranks_detail(three)
    itf = H.read_json(os.path.join(one, "summary.json"))["interfaces"][0]
    n_s = itf["slave_elements"]
    for r in d3:
        print("   %s rank %d: slave facets %d of %d, pairs %d, integration cells %d, nodes decided "
              "%d, nodal records sent %d" % (what, r["rank"], r["slave_elements"], n_s, r["pairs"],
                                             r["integration_cells"], r["contact_nodes"],
                                             r["contact_nodal_records"]))
    check_counts_add_up(one, three, what)
    check_slave_in_part(three, what, False)  # the bulk distribution: the slave side in part
    decided = sum(r["contact_nodes"] for r in d3)
    records = sum(r["contact_nodal_records"] for r in d3)
    print("   %s: nodes decided %d over the ranks, %d at np 1; records %d" %
          (what, decided, d1[0]["contact_nodes"], records))
    if d1[0]["contact_nodes"] == 0 or decided != d1[0]["contact_nodes"]:
        raise AssertionError("%s: nodes decided %d over the ranks, %d at np 1"
                             % (what, decided, d1[0]["contact_nodes"]))
    if max(r["contact_nodes"] for r in d3) >= decided:
        raise AssertionError("%s: one rank decides every node" % what)
    if max(r["slave_elements"] for r in d3) >= n_s:
        raise AssertionError("%s: one rank integrates every slave facet" % what)
    if not decided <= records <= 1.5 * decided:
        raise AssertionError("%s: %d nodal records for %d nodes" % (what, records, decided))
    compare_reactions(one, three, 1e-10, what + " np 3 vs np 1")
    keys = ["x", "y", "z", "gap", "normal_traction"] + (["tangential_traction"] if friction else [])
    a, b = rows_of(one, "interface_contact.csv"), rows_of(three, "interface_contact.csv")
    if len(a) != len(b) or any(x["node"] != y["node"] or x["status"] != y["status"]
                               for x, y in zip(a, b)):
        raise AssertionError("%s: interface_contact.csv nodes or status differ" % what)
    worst = 0.0
    for k in keys:
        scale = max(abs(r[k]) for r in a) or 1.0
        worst = max([worst] + [abs(x[k] - y[k]) / scale for x, y in zip(a, b)])
    print("   %s: interface_contact.csv np 3 against np 1, largest difference %.2e (relative)"
          % (what, worst))
    if worst > 1e-10:
        raise AssertionError("%s: interface_contact.csv differs by %.3e" % (what, worst))
    H.cleanup(*_dirs)


def test_contact_interface_part_np3():
    check_contact_part(friction=False)


def test_contact_friction_part_np3():
    check_contact_part(friction=True)


def compare_rows(a, b, name, keys, rtol, what, scale_of=None):
    """The rows of `name` at np = k against np = 1: largest difference relative to the
    largest value of each column (of column scale_of[k] for column k)."""
    scale_of = scale_of or {}
    ra, rb = rows_of(a, name), rows_of(b, name)
    if len(ra) != len(rb):
        raise AssertionError("%s: %s has %d rows against %d" % (what, name, len(ra), len(rb)))
    worst = 0.0
    for k in keys:
        # A force column relative to the largest force (the tangential force of frictionless
        # contact is round-off).
        scale = max(abs(r[scale_of.get(k, k)]) for r in ra) or 1.0
        worst = max([worst] + [abs(x[k] - y[k]) / scale for x, y in zip(ra, rb)])
    print("   %s: %s differs by %.2e (relative)" % (what, name, worst))
    if worst > rtol:
        raise AssertionError("%s: %s differs by %.3e" % (what, name, worst))


def check_master_ghosted(name, yaml, replace, below):
    """The two-body contact search distributed (docs/parallel.md, "Contact: master facets
    ghosted"): at np = 1, 2, 3 each rank searches its slave elements against the master facets
    ghosted to it by bounding boxes. Bounds: every rank receives strictly fewer master facets
    than the master surface has, at np = 3 at most `below` of it; each rank received every
    master facet its own pairs reach (master_ghosts), and the ranks together every master facet
    the np = 1 pairs reach; the ranks' pairs add up to the np = 1 pairs, and reactions.csv and
    interfaces.csv equal np = 1 to 1e-10."""
    outs = {np: run_example(name, yaml, np, replace) for np in (1, 2, 3)}
    one = ranks_detail(outs[1])[0]
    for np in (1, 2, 3):
        detail = ranks_detail(outs[np])
        n_m = detail[0]["contact_master_facets"]
        received = [r["contact_master_received"] for r in detail]
        print("   %s np %d: master facets received per rank %s of %d; pairs %s, master facets "
              "they reach %s" % (name, np, "/".join(map(str, received)), n_m,
                                 [r["pairs"] for r in detail], [r["master_ghosts"] for r in detail]))
        if n_m <= 0 or any(r["contact_master_facets"] != n_m for r in detail):
            raise AssertionError("np %d: master surface sizes %s"
                                 % (np, [r["contact_master_facets"] for r in detail]))
        if max(received) >= n_m:
            raise AssertionError("np %d: a rank received %d of the %d master facets"
                                 % (np, max(received), n_m))
        if np == 3 and max(received) > below * n_m:
            raise AssertionError("np 3: a rank received %d of the %d master facets (> %g)"
                                 % (max(received), n_m, below))
        for r in detail:
            if r["contact_master_received"] < r["master_ghosts"]:
                raise AssertionError("np %d rank %d: pairs reach %d master facets, %d received"
                                     % (np, r["rank"], r["master_ghosts"],
                                        r["contact_master_received"]))
        if sum(received) < one["master_ghosts"]:
            raise AssertionError("np %d: %d master facets received over the ranks, the np 1 "
                                 "pairs reach %d" % (np, sum(received), one["master_ghosts"]))
        pairs = sum(r["pairs"] for r in detail)
        if pairs != one["pairs"]:
            raise AssertionError("np %d: %d pairs over the ranks, %d at np 1"
                                 % (np, pairs, one["pairs"]))
        check_nodes_read(detail, np, name, outs[np])
        if np == 1:
            continue
        what = "%s np %d vs np 1" % (name, np)
        compare_reactions(outs[1], outs[np], 1e-10, what)
        # Every output of the run, the nodes' statuses (active sets) and gaps included.
        compare_outputs(outs[1], outs[np], 1e-10, what)
        compare_rows(outs[1], outs[np], "interfaces.csv",
                     ("normal_force", "tangential_force", "contact_area",
                      "frictional_dissipation"), 1e-10, what,
                     {"tangential_force": "normal_force"})
        c1 = H.read_json(os.path.join(outs[1], "summary.json"))["interfaces"][0]
        cn = H.read_json(os.path.join(outs[np], "summary.json"))["interfaces"][0]
        if cn["candidate_pairs"] != c1["candidate_pairs"]:
            raise AssertionError("%s: %d candidate pairs, %d at np 1"
                                 % (what, cn["candidate_pairs"], c1["candidate_pairs"]))
    H.cleanup(*_dirs)


def check_nodes_read(detail, np, name, out):
    """What each rank reads of the interface (docs/parallel.md, "What is still replicated"):
    the mortar integration reads the master facets ghosted to it (as many as it received), and
    at np > 1 the displacement scatter brings strictly fewer nodes than the interface has
    (the averaged normals are computed for the slave nodes of its elements and those it owns;
    printed, not bounded: the bulk partition may give one rank every slave node). The rows of
    interface_<name>.csv are computed by the slave nodes' owners (ranks_detail
    contact_output_rows): they add up to the rows of the file, each computed once, and at
    np > 1 no rank computes every row (the output reads no more than the evaluation)."""
    rows = [r["contact_output_rows"] for r in detail]
    files = [f for f in os.listdir(out) if f.startswith("interface_") and f.endswith(".csv")]
    n_rows = sum(len(rows_of(out, f)) for f in files)
    print("   %s np %d: output rows computed per rank %s of %d"
          % (name, np, "/".join(map(str, rows)), n_rows))
    if n_rows <= 0 or sum(rows) != n_rows:
        raise AssertionError("np %d: the ranks computed %s of the %d rows" % (np, rows, n_rows))
    if np > 1 and max(rows) >= n_rows:
        raise AssertionError("np %d: a rank computed all %d output rows" % (np, n_rows))
    n = detail[0]["contact_interface_nodes"]
    gathered = [r["contact_interface_nodes_gathered"] for r in detail]
    normals = [r["contact_normals_computed"] for r in detail]
    read = [r["contact_master_facets_read"] for r in detail]
    print("   %s np %d: interface nodes gathered per rank %s of %d; normals computed %s; master "
          "facets read %s" % (name, np, "/".join(map(str, gathered)), n,
                              "/".join(map(str, normals)), "/".join(map(str, read))))
    if n <= 0 or min(gathered) <= 0:
        raise AssertionError("np %d: interface nodes %d, gathered %s" % (np, n, gathered))
    if read != [r["contact_master_received"] for r in detail]:
        raise AssertionError("np %d: master facets read %s, received %s"
                             % (np, read, [r["contact_master_received"] for r in detail]))
    if np > 1 and max(gathered) >= n:
        raise AssertionError("np %d: a rank gathered %d of the %d interface nodes"
                             % (np, max(gathered), n))


def check_part_read(detail, what):
    """Every rank's displacement scatter brings strictly fewer nodes than the interface has
    (energy-momentum contact reads the start of the step through the same scatter, not every
    interface node: docs/parallel.md, "Contact: what a rank reads")."""
    n = detail[0]["contact_interface_nodes"]
    gathered = [r["contact_interface_nodes_gathered"] for r in detail]
    print("   %s: interface nodes gathered per rank %s of %d"
          % (what, "/".join(map(str, gathered)), n))
    if n <= 0 or min(gathered) <= 0 or max(gathered) >= n:
        raise AssertionError("%s: ranks gathered %s of the %d interface nodes"
                             % (what, gathered, n))


def test_hertz_master_ghosted():
    """Hertz sphere on a block (3D, two bodies), two load steps."""
    # 0.8: the boxes are widened by the ghosting's skin (docs/parallel.md, "Reused ghosting"),
    # and the slave parts follow the rebalancing by measured times, so the counts vary from run
    # to run: 209 / 212 / 234 and 206 / 216 / 290 of 402 measured with the skin, 180 / 176 /
    # 189 without. Every rank receiving the whole surface gives 402 and fails.
    check_master_ghosted("hertz_3d", "sphere_block.yaml", (("steps: 5", "steps: 2"),), 0.8)


def test_hertz_master_side_in_part_np3():
    """The master side of two-body contact held in part (docs/parallel.md, "Converting the
    contact sides", step 2): the distributed mesh no longer gives every rank the whole master
    side; a rank holds the master facets of its own and ghost cells and reads the others as
    ghosts, whose nodes outside its part carry their global dofs. Bounds at np 3 on the Hertz
    sphere on a block (two load steps): every rank holds strictly fewer master facets than the
    master side has and the ranks together at most 1.4 x of it (the facets of ghost cells
    are held twice; ranks_detail contact_side_facets_held less contact_slave_facets_held), and
    the slave side is held in part with the independent distribution too (check_slave_in_part);
    every output equals np 1 to 1e-10. Held whole on every rank before: 402 of 402 master
    facets."""
    replace = (("steps: 5", "steps: 2"),)
    one = run_example("hertz_3d", "sphere_block.yaml", 1, replace)
    three = run_example("hertz_3d", "sphere_block.yaml", 3, replace)
    itf = H.read_json(os.path.join(three, "summary.json"))["interfaces"][0]
    n_m = itf["master_elements"]
    held = [r["contact_side_facets_held"] - r["contact_slave_facets_held"]
            for r in ranks_detail(three)]
    print("   hertz np 3: master facets held per rank %s of %d (%s)"
          % ("/".join(map(str, held)), n_m, "/".join("%.2f" % (h / n_m) for h in held)))
    if n_m <= 0 or max(held) >= n_m or min(held) < 0:
        raise AssertionError("master facets held per rank %s of %d" % (held, n_m))
    if sum(held) > 1.4 * n_m:
        raise AssertionError("the ranks hold %d master facets of %d together" % (sum(held), n_m))
    compare_outputs(one, three, 1e-10, "hertz master side in part np 3 vs np 1")
    # The independent distribution (the default) holds the slave side in part too.
    check_slave_in_part(three, "hertz independent", False, 2.2)
    # 2D ironing without friction (the die, the master, slides over the slab): the parts'
    # shortest master edges differ from the side's, and the search inflation taken from a
    # part's own edges gave extra pairs at np 2 and 3 (nonzero D at inactive nodes).
    replace = tuple(IRONING_SHORT) + (("    friction: {model: coulomb, coefficient: 0.3}\n", ""),)
    one = run_example("ironing", "ironing_2d.yaml", 1, replace)
    three = run_example("ironing", "ironing_2d.yaml", 3, replace)
    itf = H.read_json(os.path.join(three, "summary.json"))["interfaces"][0]
    held = [r["contact_side_facets_held"] - r["contact_slave_facets_held"]
            for r in ranks_detail(three)]
    # Printed, not bounded: the die's cells may all lie on one rank, which then holds the side.
    print("   ironing np 3: master facets held per rank %s of %d"
          % ("/".join(map(str, held)), itf["master_elements"]))
    compare_outputs(one, three, 1e-10, "ironing without friction np 3 vs np 1")
    H.cleanup(*_dirs)


BULK = ("solver:", "parallel: {interface_distribution: bulk}\nsolver:")


def check_slave_in_part(three, what, whole, bound=1.5):
    """ranks_detail at np 3 of a run whose slave side is held in part (`whole`: it is not, the
    slave side held whole on every rank as before): no rank holds the whole slave side, each
    holds at least the slave elements it evaluates, the ranks together at most `bound` x the
    side (bulk distribution, 1.5: the facets of its own cells, which it evaluates, and of its
    ghost cells, the rings of the averaged normals; independent distribution, 2.2: the rings of
    the nodes it owns and the facets it evaluates with their nodes' rings, elsewhere on the
    side), and the ranks evaluate every slave facet once. Returns the slave facets held per rank."""
    n_s = H.read_json(os.path.join(three, "summary.json"))["interfaces"][0]["slave_elements"]
    detail = ranks_detail(three)
    held = [r["contact_slave_facets_held"] for r in detail]
    own = [r["slave_elements"] for r in detail]
    print("   %s np 3: slave facets held per rank %s of %d, evaluated %s"
          % (what, "/".join(map(str, held)), n_s, "/".join(map(str, own))))
    if sum(own) != n_s:
        raise AssertionError("%s: the ranks evaluate %d slave facets of %d" % (what, sum(own), n_s))
    if whole:
        if held != [n_s] * len(held):
            raise AssertionError("%s: slave side not whole on every rank: %s" % (what, held))
        return held
    # With the independent distribution `slave_elements` are those of the last step, which a
    # redistribution after it may have moved elsewhere.
    if max(held) >= n_s or (bound <= 1.5 and any(h < o for h, o in zip(held, own))):
        raise AssertionError("%s: slave facets held per rank %s of %d (evaluated %s)"
                             % (what, held, n_s, own))
    if sum(held) > bound * n_s:
        raise AssertionError("%s: the ranks hold %d slave facets of %d together"
                             % (what, sum(held), n_s))
    return held


def test_slave_side_in_part_np3():
    """The slave side of two-body contact held in part with the bulk distribution of the
    interface (docs/parallel.md, "Converting the contact sides", step 3): the
    distributed mesh no longer gives every rank the slave side; a rank holds the slave facets of
    its own cells (which it evaluates) and of its ghost cells (their nodes' rings), the nodal
    arrays per held slave node, and the counts, norms and the cycling guard's comparisons are
    agreed over the owners. At np 3 (check_slave_in_part): the Hertz sphere on a block (two load
    steps) and the 2D ironing without and with Coulomb friction; every output equals np 1 to
    1e-10 (test_contact_friction_part_np3 checks the Hertz sphere with friction). Held on every
    rank before: 358 of 358 (Hertz), 60 of 60 (ironing)."""
    replace = (("steps: 5", "steps: 2"), BULK)
    one = run_example("hertz_3d", "sphere_block.yaml", 1, replace)
    three = run_example("hertz_3d", "sphere_block.yaml", 3, replace)
    check_slave_in_part(three, "hertz", False)
    compare_outputs(one, three, 1e-10, "hertz slave side in part np 3 vs np 1")
    frictionless = (("    friction: {model: coulomb, coefficient: 0.3}\n", ""),)
    for friction in (False, True):
        replace = tuple(IRONING_SHORT) + (BULK,) + (() if friction else frictionless)
        what = "ironing with friction" if friction else "ironing"
        one = run_example("ironing", "ironing_2d.yaml", 1, replace)
        three = run_example("ironing", "ironing_2d.yaml", 3, replace)
        check_slave_in_part(three, what, False)
        compare_outputs(one, three, 1e-10, what + " np 3 vs np 1")
    H.cleanup(*_dirs)


def test_slave_side_in_part_independent_np3():
    """The slave side of two-body contact held in part with the independent distribution of
    the interface (the default; docs/parallel.md, "Converting the contact sides", step 3): a
    rank holds the rings of the slave nodes it owns and of the nodes of the slave facets it
    evaluates (with friction also of the slave nodes of its parts of M^n and M), taken anew
    at each distribution; the nodal arrays follow by node id. At np 3 (check_slave_in_part,
    bound 2.2 x the side, 2.5 with friction): the Hertz sphere on a block (two load steps,
    redistributed after each) and the 2D ironing without and with Coulomb friction; every
    output equals np 1 to 1e-10. Held on every rank before: 358 of 358 (Hertz), 60 of 60
    (ironing)."""
    replace = (("steps: 5", "steps: 2"),)
    one = run_example("hertz_3d", "sphere_block.yaml", 1, replace)
    three = run_example("hertz_3d", "sphere_block.yaml", 3, replace)
    check_slave_in_part(three, "hertz independent", False, 2.2)
    compare_outputs(one, three, 1e-10, "hertz independent slave side in part np 3 vs np 1")
    frictionless = (("    friction: {model: coulomb, coefficient: 0.3}\n", ""),)
    for friction in (False, True):
        replace = tuple(IRONING_SHORT) + (() if friction else frictionless)
        what = "ironing independent" + (" with friction" if friction else "")
        one = run_example("ironing", "ironing_2d.yaml", 1, replace)
        three = run_example("ironing", "ironing_2d.yaml", 3, replace)
        check_slave_in_part(three, what, False, 2.5 if friction else 2.2)
        compare_outputs(one, three, 1e-10, what + " np 3 vs np 1")
    H.cleanup(*_dirs)


def run_case(geo, yaml, np):
    """Runs case.yaml with case.geo in a new folder; returns the output directory."""
    work = tempfile.mkdtemp(prefix="seam_dist_")
    _dirs.append(work)
    H.write_case(work, "case.geo", geo)
    out = H.solve(H.write_case(work, "case.yaml", yaml), np=np)
    _dirs.append(out)
    return out


def drag_on_plane_yaml(bulk):
    """A 1 x 0.25 block (h = 1/16: 16 slave facets) pressed onto a rigid plane and dragged
    along it with Coulomb friction (mu 0.3), static, 8 steps: test_friction.py's drag."""
    return "\n".join([
        "dimension: 2", "mesh: {geo: case.geo}",
        "materials: {m: {model: neo_hooke, young: 100.0, poisson: 0.0}}",
        "bodies: [{region: body, material: m}]",
        "boundary_conditions:",
        "  - {region: top, type: dirichlet, components: [x, y], "
        "value: ['0.05*max(t-1,0)', '-0.01*min(t,1)']}",
        "interfaces:",
        "  - {name: floor, type: contact, slave: bottom, friction: {model: coulomb, "
        "coefficient: 0.3}, rigid_plane: {point: [0, 0], normal: [0, 1]}}",
        "time: {integrator: static, end: 3.0, steps: 8}",
        "solver: {newton: {tolerance: 1.0e-12, max_iterations: 30}}"]
        + (["parallel: {interface_distribution: bulk}"] if bulk else [])) + "\n"


def ring_on_circle_yaml(bulk):
    """test_rings.py's ring (8 cells per quarter circle, 64 slave facets on its two circles)
    thrown obliquely and spinning onto a rigid circle (radius 6) with Coulomb friction (mu
    0.3), generalized-alpha, 30 steps to t = 0.3."""
    return "\n".join([
        "dimension: 2", "mesh: {geo: case.geo}",
        "materials: {rubber: {model: neo_hooke, young: 1000, poisson: 0.3, density: 1}}",
        "bodies: [{region: r0, material: rubber}]",
        "initial_conditions:",
        "  - {region: r0, velocity: [\"0.4 - 0.5*(y - 1.05)\", \"-1 + 0.5*x\"]}",
        "interfaces:",
        "  - {name: floor, type: contact, slave: r0_boundary, multiplier: dual, friction: "
        "{model: coulomb, coefficient: 0.3}, rigid_sphere: {center: [0, -6], radius: 6}}",
        "time: {integrator: generalized_alpha, rho_inf: 0.5, end: 0.3, steps: 30}",
        "solver: {newton: {tolerance: 1.0e-11, max_iterations: 30}}",
        "output: {every: 1000}",
        # Independent: redistributed after every step whose integration cells are not even.
        "parallel: {interface_distribution: bulk}" if bulk else
        "parallel: {work: integration_cells, rebalance_tolerance: 1.0}"]) + "\n"


def check_rigid_in_part(what, run, bounds, rebalanced=0):
    """A contact interface against a rigid obstacle at np 1 and at np 3 with the bulk and the
    independent distribution (`run(np, bulk)`: the output directory): at np 3 the slave side
    is held in part (check_slave_in_part with bounds[bulk]; the active sets and every output
    equal np 1 to 1e-10); the independent run redistributed after at least `rebalanced` steps
    (parallel.csv). Returns the slave facets held per rank, bulk then independent."""
    one = run(1, False)
    held = []
    for bulk in (True, False):
        name = what + (" bulk" if bulk else " independent")
        three = run(3, bulk)
        held.append(check_slave_in_part(three, name, False, bounds[bulk]))
        if not bulk:
            steps = [r["step"] for r in rows_of(three, "parallel.csv") if r["redistributed"]]
            print("   %s: redistributed after %d steps" % (name, len(steps)))
            if len(steps) < rebalanced:
                raise AssertionError("%s: redistributed after steps %s" % (name, steps))
        compare_outputs(one, three, 1e-10, name + " np 3 vs np 1")
        if max(r["active_nodes"] for r in rows_of(one, "steps.csv")) == 0:
            raise AssertionError("%s: no contact" % what)
    return held


def test_rigid_slave_side_in_part_np3():
    """The slave side of contact against a rigid obstacle held in part (docs/parallel.md,
    "Converting the contact sides", step 3): with the bulk distribution a rank holds the slave
    facets of its own and ghost cells, with the independent one the rings of the slave nodes
    it owns and of the nodes of the facets it evaluates; the nodal arrays per held slave node.
    At np 3, bulk and independent (check_rigid_in_part): the Hertz sphere on a rigid plane
    (examples/hertz_3d/hertz_3d.yaml, two load steps, frictionless), a 2D block pressed onto a
    rigid plane and dragged with Coulomb friction, and a 2D ring thrown onto a rigid circle
    with Coulomb friction, generalized-alpha (independent: rebalanced after every uneven
    step, at least 5 times, the state following the parts). Held on every rank before: 473 of 473 (Hertz),
    16 of 16 (block), 64 of 64 (ring)."""
    steps = (("steps: 5", "steps: 2"),)
    check_rigid_in_part(
        "hertz on a rigid plane",
        lambda np, bulk: run_example("hertz_3d", "hertz_3d.yaml", np,
                                     steps + ((BULK,) if bulk else ())),
        {True: 1.5, False: 1.3})
    import geometry  # noqa: E402
    block = geometry.rectangle("quad_structured", 0.0625, lx=1.0, ly=0.25)
    check_rigid_in_part("block dragged on a rigid plane",
                        lambda np, bulk: run_case(block, drag_on_plane_yaml(bulk), np),
                        {True: 1.5, False: 1.6})
    import test_rings  # noqa: E402
    ring = test_rings.ring_geo(((0.0, 1.05),), 8, 2)
    check_rigid_in_part("ring on a rigid circle, generalized-alpha",
                        lambda np, bulk: run_case(ring, ring_on_circle_yaml(bulk), np),
                        {True: 1.5, False: 1.6}, rebalanced=5)
    H.cleanup(*_dirs)


def check_held_cells(three, what):
    """Issue 12's held-cells bound for the contact sides at np 3: no rank holds more cells than
    (its owned cells + its ghost cells) * 1.1 (ranks_detail: `ghost_cells` counts every held
    cell it does not assemble, the cells held only for an interface side, `interface_cells`,
    among them). Returns (owned, ghosts, interface cells) per rank."""
    detail = ranks_detail(three)
    shares = [(r["cells"], r["ghost_cells"] - r["interface_cells"], r["interface_cells"])
              for r in detail]
    print("   %s np 3: cells owned / ghost / held for the interface per rank %s"
          % (what, ", ".join("%d / %d / %d" % s for s in shares)))
    for r, (own, ghosts, extra) in enumerate(shares):
        if own + ghosts + extra > 1.1 * (own + ghosts):
            raise AssertionError("%s: rank %d holds %d cells, more than 1.1 x (%d owned + %d "
                                 "ghost cells)" % (what, r, own + ghosts + extra, own, ghosts))
    return shares


def test_contact_held_cells_np3():
    """The slave side of contact held in part with the independent distribution (the default)
    no longer brings its cells to every rank's mesh (docs/parallel.md, "Converting the contact
    sides", step 3 (a)): the facets a rank needs beyond its own and ghost cells reach it as
    facets (ids, nodes' global dofs and coordinates). At np 3 on the Hertz sphere on a block
    (two bodies, two load steps) and on the Hertz sphere on a rigid plane (two load steps) no
    rank holds more than (owned + ghost cells) * 1.1 cells (check_held_cells), the slave side
    is held in part, and every output equals np 1 to 1e-10. Before, every rank held every
    cell with a slave facet (e.g. 358 more cells on the rank of the block)."""
    check_hertz_held_cells((), "")
    H.cleanup(*_dirs)


def check_held_part(one, three, what, bound):
    """At np 3 no rank holds more than (owned + ghost cells) * 1.1 cells (check_held_cells),
    the slave side is held in part (check_slave_in_part, the ranks together at most `bound` x
    the side) and every output equals np 1 to 1e-10."""
    check_held_cells(three, what)
    check_slave_in_part(three, what, False, bound)
    compare_outputs(one, three, 1e-10, what + " held cells np 3 vs np 1")


def check_hertz_held_cells(replace, label):
    """check_held_part on the Hertz sphere on a block and on a rigid plane (two load steps,
    the input with the replacements `replace`)."""
    steps = (("steps: 5", "steps: 2"),) + tuple(replace)
    for yaml, what, bound in (("sphere_block.yaml", "hertz on a block", 2.2),
                              ("hertz_3d.yaml", "hertz on a rigid plane", 1.3)):
        check_held_part(run_example("hertz_3d", yaml, 1, steps),
                        run_example("hertz_3d", yaml, 3, steps), what + label, bound)


STANDARD = ("multiplier: dual", "multiplier: standard")


def test_standard_multipliers_held_in_part_np3():
    """Contact with standard multipliers (a saddle point: the multipliers are unknowns) with
    its sides held in part (docs/parallel.md, "Converting the contact sides", step 6): the
    multiplier rows numbered by the slave nodes' owners and reached by node id, each rank's
    mesh only its own and ghost cells. At np 1 and 3: the Hertz sphere on a block (two bodies,
    two load steps), the Hertz sphere on a rigid plane (two load steps), test_friction.py's
    block pressed onto a rigid plane and dragged with Coulomb friction (8 steps) and the 2D
    ironing with Coulomb friction (IRONING_SHORT): at np 3 no rank holds more than (owned +
    ghost cells) * 1.1 cells (check_held_cells), the slave side is held in part
    (check_slave_in_part) and every output equals np 1 to 1e-10. Before, the sides of such a
    run were held whole on every rank."""
    check_hertz_held_cells((STANDARD,), ", standard")
    import geometry  # noqa: E402
    block = geometry.rectangle("quad_structured", 0.0625, lx=1.0, ly=0.25)
    yaml = drag_on_plane_yaml(False).replace("type: contact,",
                                             "type: contact, multiplier: standard,")
    check_held_part(run_case(block, yaml, 1), run_case(block, yaml, 3),
                    "block dragged on a rigid plane, standard", 1.6)
    friction = (("friction: {model: coulomb",
                 "multiplier: standard\n    friction: {model: coulomb"),)
    check_held_part(run_example("ironing", "ironing_2d.yaml", 1, IRONING_SHORT + friction),
                    run_example("ironing", "ironing_2d.yaml", 3, IRONING_SHORT + friction),
                    "ironing with friction, standard", 2.5)
    H.cleanup(*_dirs)


def test_ironing_master_ghosted():
    """2D ironing with Coulomb friction: pressed in and slid a little, coarse steps."""
    check_master_ghosted("ironing", "ironing_2d.yaml", IRONING_SHORT, 0.5)


# Columns compared against the largest value of their group (a tangential force or a gap of
# closed contact is round-off next to the normal force or the displacements).
SCALE_GROUPS = (("ux", "uy", "uz", "gap"), ("normal_traction", "tangential_traction"),
                ("interface_force_fluid_x", "interface_force_fluid_y", "interface_force_fluid_z",
                 "interface_force_structure_x", "interface_force_structure_y",
                 "interface_force_structure_z"),
                ("fx", "fy", "fz"), ("normal_force", "tangential_force"),
                ("momentum_x", "momentum_y", "momentum_z"),
                ("angular_momentum_x", "angular_momentum_y", "angular_momentum_z"),
                ("kinetic_energy", "internal_energy", "external_work", "total_energy"))
NOT_COMPARED = ("residual", "newton_iterations", "wall_seconds")


def compare_outputs(a, b, rtol, what, floor=0.0):
    """steps.csv (energies, momenta, active nodes), interfaces.csv, reactions.csv, probes.csv
    and interface_*.csv of two runs: every numeric column to rtol relative to the largest value
    of its group (SCALE_GROUPS) or of itself, at least `floor` (for columns that are zero up to
    round-off, such as the momenta of free bodies), every other column equal."""
    names = sorted(n for n in os.listdir(a) if n in ("steps.csv", "interfaces.csv",
                                                     "reactions.csv", "probes.csv")
                   or (n.startswith("interface_") and n.endswith(".csv")))
    worst_all = 0.0
    for name in names:
        ra, rb = rows_of(a, name), rows_of(b, name)
        if len(ra) != len(rb):
            raise AssertionError("%s: %s has %d rows against %d" % (what, name, len(ra), len(rb)))
        if not ra:
            continue
        worst = 0.0
        for k, v in ra[0].items():
            if k in NOT_COMPARED:
                continue
            if not isinstance(v, float):
                if any(x[k] != y[k] for x, y in zip(ra, rb)):
                    raise AssertionError("%s: %s column %s differs" % (what, name, k))
                continue
            group = [g for g in SCALE_GROUPS if k in g]
            group = [c for c in group[0] if c in ra[0]] if group else [k]
            scale = max([floor] + [abs(r[c]) for r in ra for c in group]) or 1.0
            worst = max([worst] + [abs(x[k] - y[k]) / scale for x, y in zip(ra, rb)])
        worst_all = max(worst_all, worst)
        if worst > rtol:
            raise AssertionError("%s: %s differs by %.3e (relative)" % (what, name, worst))
    print("   %s: %s equal, largest difference %.2e (relative)" % (what, ", ".join(names),
                                                                 worst_all))
    if "steps.csv" not in names or len(names) < 3:
        raise AssertionError("%s: too few outputs compared: %s" % (what, names))


def check_surface_received(out, what):
    """At np > 1 every rank receives strictly fewer surface facets than the surface has."""
    detail = ranks_detail(out)
    n = detail[0]["contact_surface_facets"]
    received = [r["contact_surface_received"] for r in detail]
    print("   %s: surface facets received per rank %s of %d; ghost exchanges %s at %s searches"
          % (what, "/".join(map(str, received)), n, detail[0]["contact_ghost_exchanges"],
             detail[0]["contact_searches"]))
    if n <= 0 or any(r["contact_surface_facets"] != n for r in detail):
        raise AssertionError("%s: surface sizes %s" % (what, [r["contact_surface_facets"]
                                                              for r in detail]))
    if min(received) <= 0 or max(received) >= n:
        raise AssertionError("%s: a rank received %d (another %d) of the %d surface facets"
                             % (what, max(received), min(received), n))
    return detail


def check_self_decisions(one, three, what, groups_at_least=2):
    """The roles of the self-contact pairs decided by connected group of pairs, each group on
    one rank (docs/parallel.md, "Self contact searched distributed"): at the last search the
    pairs the ranks received to decide (`contact_self_pairs_received`) add up at np 3 to the
    pairs np 1 found, every rank got pairs back only of those, and when there are
    `groups_at_least` groups or more, no rank received all pairs and more than one rank
    decided: no rank gathers the pairs of all ranks."""
    d1, d3 = ranks_detail(one), ranks_detail(three)
    found = d1[0]["contact_self_pairs_received"]
    received = [r["contact_self_pairs_received"] for r in d3]
    returned = [r["contact_self_pairs_returned"] for r in d3]
    groups = [r["contact_self_groups_decided"] for r in d3]
    print("   %s np 3: pairs received to decide per rank %s (groups %s) of %d; pairs back %s"
          % (what, "/".join(map(str, received)), "/".join(map(str, groups)), found,
             "/".join(map(str, returned))))
    if found <= 0 or d1[0]["contact_self_pairs_returned"] != found:
        raise AssertionError("%s np 1: %d pairs decided, %d back"
                             % (what, found, d1[0]["contact_self_pairs_returned"]))
    if sum(received) != found or max(returned) > found or min(returned) < 0:
        raise AssertionError("%s: pairs received to decide %s, back %s, np 1 found %d"
                             % (what, received, returned, found))
    if sum(groups) != d1[0]["contact_self_groups_decided"]:
        raise AssertionError("%s: groups %s at np 3, %d at np 1"
                             % (what, groups, d1[0]["contact_self_groups_decided"]))
    if sum(groups) >= groups_at_least:
        if max(received) >= found:
            raise AssertionError("%s: one rank received all %d pairs (%s) of %d groups"
                                 % (what, found, received, sum(groups)))
        if sum(g > 0 for g in groups) < 2:
            raise AssertionError("%s: one rank decided all %d groups" % (what, sum(groups)))
    return sum(groups)


def two_pairs_case(np, end=0.2, steps=20):
    """Two copies of test_rings.py's two free rings, the second 4 higher: two separate groups
    of contact pairs on one surface (energy-momentum, 8 cells per quarter circle, 20 steps to
    t = 0.2, both pairs touching from t ~ 0.1)."""
    import test_rings as R
    centres = list(R.CENTRES) + [(x, y + 4.0) for x, y in R.CENTRES]
    va, vb = R.VELOCITIES[2]
    shift = lambda v: v.replace("y", "(y - 4)")  # noqa: E731
    yaml = R.FREE_YAML.replace("DIM", "2").replace("INTEGRATOR", "energy_momentum")
    yaml = yaml.replace("STEPS", str(steps)).replace("end: 0.4", "end: %r" % end)
    yaml = yaml.replace("SETFACTORY\n", "")
    yaml = yaml.replace("  - {region: r1, material: rubber}\n",
                        "  - {region: r1, material: rubber}\n"
                        "  - {region: r2, material: rubber}\n"
                        "  - {region: r3, material: rubber}\n")
    yaml = yaml.replace("  - {region: r1, velocity: [VB]}\n",
                        "  - {region: r1, velocity: [VB]}\n"
                        "  - {region: r2, velocity: [%s]}\n"
                        "  - {region: r3, velocity: [%s]}\n" % (shift(va), shift(vb)))
    yaml = yaml.replace("VA", va).replace("VB", vb)
    yaml = yaml.replace("surface: [r0_boundary, r1_boundary]",
                        "surface: [r0_boundary, r1_boundary, r2_boundary, r3_boundary]")
    work, out = R.T.run_case(R.ring_geo(centres, 8, 2), yaml, np=np)
    _dirs.extend([work, out])
    return out


def test_self_roles_decided_by_group_np3():
    """Two separate pairs of rings on one surface: at np 3 the two groups of contact pairs
    are decided on different ranks (each group's pairs on one rank, none receives all pairs),
    and every output equals np 1 to 1e-10."""
    one, three = two_pairs_case(1), two_pairs_case(3)
    if max(r["active_nodes"] for r in rows_of(one, "steps.csv")) == 0:
        raise AssertionError("two pairs of rings: no contact")
    if check_self_decisions(one, three, "two pairs of rings") != 2:
        raise AssertionError("two pairs of rings: not two groups at the last search")
    compare_outputs(one, three, 1e-10, "two pairs of rings np 3 vs np 1", 0.5)
    H.cleanup(*_dirs)


def pile_case(np):
    """7 rings of examples/rings (rows of 4 and 3) to t = 0.3: the second row lands on the
    first at t = 0.25, so the last 20 steps have ring-ring contact."""
    import test_rings  # noqa: E402 - the rings example as test_rings runs it
    _, _, work, out, _ = test_rings.rings_case(np, rings=7, k=4, end=0.3)
    _dirs.extend((work, out))
    return out


def test_rings_self_search_np3():
    """The self-contact search distributed (docs/parallel.md, "Self contact searched
    distributed"): each rank searches the surface facets it evaluates against those ghosted
    to it, every pair once, roles from the gathered pairs."""
    one, three = pile_case(1), pile_case(3)
    touching = [r for r in rows_of(one, "interfaces.csv")
                if r["interface"] == "rings" and r["active_nodes"] > 0]
    print("   ring-ring contact in %d of the steps" % len(touching))
    if len(touching) < 5:
        raise AssertionError("the rings touch in %d steps only" % len(touching))
    if ranks_detail(one)[0]["contact_surface_received"] != ranks_detail(one)[0][
            "contact_surface_facets"]:
        raise AssertionError("np 1 searched a part of the surface: %s" % ranks_detail(one)[0])
    check_surface_received(three, "rings np 3")
    check_self_decisions(one, three, "rings")
    check_part_read(ranks_detail(three), "rings np 3 (energy-momentum)")
    compare_outputs(one, three, 1e-10, "rings np 3 vs np 1")
    H.cleanup(*_dirs)


def test_roles_restart_across_np():
    """The kept self-contact roles and pairs of a checkpoint are written by the ranks that keep
    them and routed at a restart by facet id to the ranks that keep them then, at any np: the
    7-ring pile (contact from step 100) checkpointed at step 110 at np 1 and restarted at np 3,
    and checkpointed at np 3 and restarted at np 1, repeats the uninterrupted np 1 run's steps
    111 to 120 (energy and momenta to 1e-10, Newton iterations exactly)."""
    import test_rings
    rows, _, work, one, _ = test_rings.rings_case(1, rings=7, k=4, end=0.3,
                                                  checkpoint_every=110)
    _, _, work3, three, _ = test_rings.rings_case(3, rings=7, k=4, end=0.3,
                                                  checkpoint_every=110)
    _dirs.extend((work, one, work3, three))
    columns = ("total_energy", "momentum_x", "momentum_y")
    for what, source, np in (("np 1 -> np 3", one, 3), ("np 3 -> np 1", three, 1)):
        again = H.solve(os.path.join(work, "rings.yaml"), np=np,
                        extra=["--restart", os.path.join(source, "checkpoint_00110")])
        _dirs.append(again)
        steps = rows_of(again, "steps.csv")
        scale = max(abs(r[c]) for r in rows for c in columns)
        worst = max(abs(a[c] - b[c]) for a, b in zip(rows[110:], steps) for c in columns)
        iterations = [(a["newton_iterations"], b["newton_iterations"])
                      for a, b in zip(rows[110:], steps)]
        print("   restart %s at step 110: %d steps, largest difference %.2e of %.2e"
              % (what, len(steps), worst, scale))
        if (len(steps) != len(rows) - 110 or worst > 1e-10 * scale
                or any(a != b for a, b in iterations)):
            raise AssertionError("restart %s differs from the uninterrupted run: %.3e, "
                                 "iterations %s" % (what, worst, iterations))
    H.cleanup(*_dirs)


def friction_rings_case(np, interface="surface"):
    """test_friction_dynamics.py's two free rings with energy-momentum contact and Coulomb
    friction (`surface:`, dual multipliers, or with interface "two_bodies" slave and master
    rings with standard multipliers; 8 cells per quarter circle, 40 steps)."""
    import test_friction_dynamics as F
    import test_rings
    yaml = F.rings_yaml(interface, 40, 2)
    work, out = test_rings.T.run_case(test_rings.ring_geo(test_rings.CENTRES, 8, 2), yaml,
                                      np=np)
    _dirs.extend([work, out])
    return out


def test_energy_momentum_friction_part_np3():
    """Energy-momentum contact with friction reads the nodes of its rank's part (its slave
    elements, owned slave nodes and the slave rows of its M^n, D^n with their rings, its
    ghosts), not every interface node, and np 3 equals np 1."""
    one, three = friction_rings_case(1), friction_rings_case(3)
    slipping = [r for r in rows_of(one, "interfaces.csv") if r["slip_nodes"] > 0]
    if len(slipping) < 3:
        raise AssertionError("the rings slip in %d steps only" % len(slipping))
    check_part_read(ranks_detail(three), "friction rings np 3 (energy-momentum)")
    # The momenta and the external work are zero up to round-off (3e-13, free bodies): against
    # the momentum of one ring (0.5, as test_rings.py scales it).
    compare_outputs(one, three, 1e-10, "friction rings np 3 vs np 1", floor=0.5)
    H.cleanup(*_dirs)


def two_rings_em_case(np):
    """test_rings.py's two free rings (8 cells per quarter circle) thrown at each other with
    energy-momentum contact, frictionless, as two bodies (slave: the first ring, master: the
    second; dual multipliers, a saddle point: the discrete gradient), 40 steps."""
    import test_rings
    va, vb = test_rings.VELOCITIES[2]
    surface = "{name: impact, type: contact, surface: [r0_boundary, r1_boundary]}"
    if surface not in test_rings.FREE_YAML:
        raise AssertionError("FREE_YAML: '%s' not found" % surface)
    yaml = (test_rings.FREE_YAML.replace("DIM", "2").replace("VA", va).replace("VB", vb)
            .replace("INTEGRATOR", "energy_momentum").replace("STEPS", "40")
            .replace("SETFACTORY\n", "")
            .replace(surface, "{name: impact, type: contact, slave: r0_boundary, "
                              "master: r1_boundary}"))
    return run_case(test_rings.ring_geo(test_rings.CENTRES, 8, 2), yaml, np)


def check_em_entries(out, what):
    """The entries of the discrete gradients go to the owners of their slave nodes only
    (docs/parallel.md, "Contact: sums and decisions on the owners"): every rank receives fewer
    than all the ranks sent, which a gather on every rank would bring each of them."""
    detail = ranks_detail(out)
    sent = [r["contact_em_entries_sent"] for r in detail]
    received = [r["contact_em_entries_received"] for r in detail]
    print("   %s: discrete-gradient entries sent %s, received %s"
          % (what, " / ".join(map(str, sent)), " / ".join(map(str, received))))
    if sum(received) != sum(sent) or sum(sent) == 0:
        raise AssertionError("%s: entries sent %s, received %s" % (what, sent, received))
    if max(received) >= sum(sent):
        raise AssertionError("%s: a rank received %d of the %d entries sent: gathered"
                             % (what, max(received), sum(sent)))


def test_energy_momentum_held_in_part_np3():
    """Energy-momentum contact with its sides held in part (docs/parallel.md, "Converting the
    contact sides", step 6): the gap blocks read the reference coordinates of mesh and outside
    nodes, the owner of a slave node maps the dofs of its discrete gradient by node id (outside
    nodes from the directories), the multiplier rows are the owners'. At np 1 and 3: the
    7-ring pile (self contact of the rings' surface, rigid floor and walls, 120 steps), two
    free rings as two bodies (40 steps), and test_friction_dynamics.py's two rings with Coulomb
    friction as one surface (dual multipliers) and as two bodies (standard multipliers), both
    redistributed after several steps: at np 3 no rank holds more than
    (owned + ghost cells) * 1.1 cells, no rank holds the contact sides whole (side facets
    held below np 1's) and every output equals np 1 to 1e-10 (the free rings' momenta against
    one ring's, 0.5); each rank receives fewer discrete-gradient entries than the ranks sent
    (check_em_entries). Before, every rank held every cell with a contact facet."""
    for what, case, floor in (
            ("7-ring pile, energy-momentum", pile_case, 0.0),
            ("two rings as two bodies, energy-momentum", two_rings_em_case, 0.5),
            ("two rings with friction, surface, energy-momentum", friction_rings_case, 0.5),
            ("two rings with friction, two bodies, standard multipliers, energy-momentum",
             lambda np: friction_rings_case(np, "two_bodies"), 0.5)):
        one, three = case(1), case(3)
        if max(r["active_nodes"] for r in rows_of(one, "steps.csv")) == 0:
            raise AssertionError("%s: no contact" % what)
        check_held_cells(three, what)
        whole = ranks_detail(one)[0]["contact_side_facets_held"]
        held = [r["contact_side_facets_held"] for r in ranks_detail(three)]
        print("   %s np 3: side facets held per rank %s of %d"
              % (what, " / ".join(map(str, held)), whole))
        if max(held) >= whole:
            raise AssertionError("%s: side facets held per rank %s of %d: not in part"
                                 % (what, held, whole))
        check_em_entries(three, what + " np 3")
        if "surface" in what or "pile" in what:
            check_self_decisions(one, three, what)
        compare_outputs(one, three, 1e-10, what + " np 3 vs np 1", floor)
    H.cleanup(*_dirs)


def two_blocks_case(np, bulk=False):
    """The two blocks of test_self_contact.py (3D tetrahedra, tilted top) as one surface,
    stretched to 3 x 1 x 1 so that the partition cuts the contact faces (stacked unit cubes
    are cut across z: one rank then evaluates both faces whole); `bulk`: with
    `interface_distribution: bulk`."""
    import geometry
    import test_self_contact as S
    geo = geometry.tied_boxes(0.35, 0.25, kind="tet")
    for z in ("0", "1"):
        box = "{0, 0, %s, 1, 1, 1};" % z
        if box not in geo:
            raise AssertionError("tied_boxes: '%s' not found" % box)
        geo = geo.replace(box, "{0, 0, %s, 3, 1, 1};" % z)
    yaml = S.blocks_yaml(
        3, "{name: contact, type: contact, surface: [lower_top, upper_bottom]}", True)
    if bulk:
        if BULK[0] not in yaml:
            raise AssertionError("blocks_yaml: '%s' not found" % BULK[0])
        yaml = yaml.replace(*BULK)
    work, out = S.T.run_case(geo, yaml, np=np)
    _dirs.extend([work, out])
    return out


def test_two_blocks_self_search_np3():
    one, three = two_blocks_case(1), two_blocks_case(3)
    import contact_analysis
    active = sum(contact_analysis.is_active(r) for r in rows_of(one, "interface_contact.csv"))
    print("   %d active nodes" % active)
    if active == 0:
        raise AssertionError("no active contact node")
    check_surface_received(three, "two blocks np 3")
    check_self_decisions(one, three, "two blocks")
    compare_outputs(one, three, 1e-10, "two blocks np 3 vs np 1")
    H.cleanup(*_dirs)


def check_surface_in_part(one, three, what, floor=0.0):
    """The surface of self contact held in part at np 3 (docs/parallel.md, "Converting the
    contact sides", step 4): no rank holds more cells than (owned + ghost cells) * 1.1
    (check_held_cells), no rank holds the contact sides whole (`contact_side_facets_held`,
    a surface counted once, below np 1's, where the sides are whole; the surface's size
    `contact_surface_facets` that of np 1), and every output equals np 1 to 1e-10."""
    check_held_cells(three, what)
    detail = ranks_detail(three)
    n = ranks_detail(one)[0]["contact_surface_facets"]
    whole = ranks_detail(one)[0]["contact_side_facets_held"]
    held = [r["contact_side_facets_held"] for r in detail]
    print("   %s np 3: side facets held per rank %s of %d (the surface: %d)"
          % (what, " / ".join(map(str, held)), whole, n))
    if n <= 0 or any(r["contact_surface_facets"] != n for r in detail):
        raise AssertionError("%s: surface sizes %s against %d at np 1"
                             % (what, [r["contact_surface_facets"] for r in detail], n))
    if max(held) >= whole or min(held) <= 0:
        raise AssertionError("%s: side facets held per rank %s of %d: the surface is not "
                             "held in part" % (what, held, whole))
    compare_outputs(one, three, 1e-10, what + " np 3 vs np 1", floor)


def test_self_contact_held_cells_np3():
    """Self contact (`surface:`) with dual multipliers, outside energy-momentum contact: the
    surface held in part, each rank's mesh only its own and ghost cells, the surface facets
    it pairs beyond them read as ghosts through the directories of two-body contact, the roles
    from the facing pairs gathered by facet id. The two blocks of test_self_contact.py as one
    surface (static, 3 load steps) and test_self_contact.py's ring squeezed between two rigid
    planes until its hole closes onto itself (2D, static, 30 steps) at np 1 and np 3
    (check_surface_in_part; the blocks also with `interface_distribution: bulk`). Before, every
    rank held every cell with a surface facet and the whole surface."""
    one, three = two_blocks_case(1), two_blocks_case(3)
    check_surface_in_part(one, three, "two blocks (self contact)")
    check_surface_in_part(one, two_blocks_case(3, bulk=True),
                          "two blocks (self contact, bulk distribution)")
    import test_self_contact as S

    def ring(np):
        work, out = S.T.run_case(S.RING_GEO.replace("NC", "24").replace("NR", "6"),
                                 S.RING_YAML.replace("STEPS", "30"), np=np)
        _dirs.extend([work, out])
        return out

    one, three = ring(1), ring(3)
    if S.last_interface_rows(one)["inner"]["active_nodes"] <= 0:
        raise AssertionError("ring: the hole did not close")
    # The pinned points' reactions are zero up to the Newton tolerance (1e-8 of the plane
    # force, 35): compared against a floor of 1 (force and displacement units alike).
    check_surface_in_part(one, three, "ring closing onto itself", floor=1.0)
    H.cleanup(*_dirs)


def with_env(name, value, run):
    old = os.environ.get(name)
    os.environ[name] = value
    try:
        return run()
    finally:
        if old is None:
            del os.environ[name]
        else:
            os.environ[name] = old


def test_ghosting_reused_np3():
    """The ghosting reused between searches (docs/parallel.md, "Reused ghosting"): the blocks
    (self contact) and the Hertz sphere (two bodies) move little within a step, so most
    searches reuse the ghosts; they equal runs that exchange at every search."""
    cases = (("two blocks", lambda: two_blocks_case(3)),
             ("hertz", lambda: run_example("hertz_3d", "sphere_block.yaml", 3,
                                           (("steps: 5", "steps: 2"),))))
    for what, case in cases:
        reused = case()
        every = with_env("SEAM_GHOST_SKIN", "0", case)
        for out, kind in ((reused, "reused"), (every, "every search")):
            counts = {(r["contact_ghost_exchanges"], r["contact_searches"])
                      for r in ranks_detail(out)}
            print("   %s, %s: ghost exchanges / searches per rank %s" % (what, kind, counts))
            if len(counts) != 1:
                raise AssertionError("%s: ranks disagree on the exchanges: %s" % (what, counts))
            exchanges, searches = counts.pop()
            if searches < 2 or exchanges < 1:
                raise AssertionError("%s: %d searches, %d exchanges" % (what, searches, exchanges))
            if kind == "reused" and not exchanges < searches:
                raise AssertionError("%s: ghosts exchanged at %d of %d searches"
                                     % (what, exchanges, searches))
            if kind != "reused" and exchanges != searches:
                raise AssertionError("%s, SEAM_GHOST_SKIN=0: %d exchanges at %d searches"
                                     % (what, exchanges, searches))
        compare_outputs(every, reused, 1e-12, what + " reused vs every search")
    H.cleanup(*_dirs)


if __name__ == "__main__":
    H.main([test_hertz_master_side_in_part_np3, test_slave_side_in_part_np3,
            test_slave_side_in_part_independent_np3, test_rings_self_search_np3, test_two_blocks_self_search_np3,
            test_self_roles_decided_by_group_np3, test_roles_restart_across_np,
            test_ghosting_reused_np3, test_hertz_master_ghosted, test_ironing_master_ghosted, test_held_cells_np3,
            test_check_distributed_np3, test_tied_interface_part_np3, test_saddle_point_tying_part_np3,
            test_tied_independent_np3, test_tied_curved_quadratic_independent_np3,
            test_saddle_point_mesh_initialization_np3,
            test_contact_interface_part_np3, test_contact_friction_part_np3,
            test_hertz_independent_against_bulk_np4,
            test_hertz_held_never_redistributes, test_ironing_rebalances_np4, test_shared_master_patch_np3, test_time_measure_np2,
            test_contact_held_cells_np3, test_self_contact_held_cells_np3,
            test_standard_multipliers_held_in_part_np3, test_energy_momentum_held_in_part_np3])

