"""Bad input (issue: bad input ends with exit code 1 and a located message).

Each case breaks one thing in a small valid problem (the rectangle [0,2] x [0,1] of
geometry.py, linear elastic, clamped on the left, pulled on the right) and runs both
`seam check` and `seam run`. Expected, per CONTRACT.md:

  * exit code exactly 1;
  * one message naming the input file with line:column and key path (schema and YAML
    errors), or the mesh file (mesh errors), and what was expected: the "did you mean",
    the list of available regions, the allowed values, "expected a number", ...;
  * no crash, uncaught exception or PETSc traceback.

The line and column are computed from the broken text itself (where the offending token
is), not taken from an earlier run. Exit code 2 (the solver gave up after its step cuts)
is checked with a Neo-Hookean bar compressed to -1.5 times its length: its elements invert
late in the load history, and the converged steps before that must be written and kept.
Representative cases also run on 3 ranks: every rank exits with the same code and the
message appears once.
"""
import functools
import os
import re
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402

BASE = """\
title: bad input base case
dimension: 2
mesh:
  geo: body.geo
materials:
  steel: {model: linear_elastic, young: 200, poisson: 0.3, density: 1}
bodies:
  - {region: body, material: steel}
boundary_conditions:
  - {region: left, type: dirichlet, components: [x, y], value: [0, 0]}
  - {region: right, type: traction, value: ["0.1*t", 0]}
time:
  integrator: static
  end: 1
  steps: 2
output:
  probes: [[1.0, 0.5]]
"""

REGIONS = "bottom (dim 1), right (dim 1), top (dim 1), left (dim 1), body (dim 2)"

# What must never reach the user, whatever the input.
FORBIDDEN = ("PETSc", "Traceback", "terminate called", "Segmentation", "core dumped",
             "internal error", "MPI_ABORT", "exited on signal", "what():")

# A single prism (Gmsh type 6) with a boundary triangle: a mesh seam cannot use.
PRISM_MSH = """\
$MeshFormat
2.2 0 8
$EndMeshFormat
$PhysicalNames
2
2 1 "bottom"
3 2 "body"
$EndPhysicalNames
$Nodes
6
1 0 0 0
2 1 0 0
3 0 1 0
4 0 0 1
5 1 0 1
6 0 1 1
$EndNodes
$Elements
2
1 2 2 1 1 1 2 3
2 6 2 2 1 1 2 3 4 5 6
$EndElements
"""

PRISM_YAML = """\
dimension: 3
mesh: {file: prism.msh}
materials:
  steel: {model: linear_elastic, young: 200, poisson: 0.3}
bodies:
  - {region: body, material: steel}
boundary_conditions:
  - {region: bottom, type: dirichlet, value: [0, 0, 0]}
time: {end: 1, steps: 1}
"""

# Announces a .msh 2.2 file, then stops in the middle of the node block.
TRUNCATED_MSH = "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$Nodes\n10\n1 0 0 0\n2 1 0 0\n"

# Neo-Hookean bar [0,2] x [0,1]: the right face moves to x = 2 - 3 t, through the left face
# at t = 2/3, so elements must invert after a few converged steps.
CRUSH_YAML = """\
dimension: 2
mesh: {geo: body.geo}
materials:
  rubber: {model: neo_hooke, young: 100, poisson: 0.3}
bodies:
  - {region: body, material: rubber}
boundary_conditions:
  - {region: left, type: dirichlet, components: [x], value: [0]}
  - {region: bottom, type: dirichlet, components: [y], value: [0]}
  - {region: right, type: dirichlet, components: [x], value: ["-3*t"]}
time: {end: 1, steps: 10, max_step_cuts: 2}
"""


def mutate(old, new, text=BASE):
    """The base case with one piece of text replaced (which must be there)."""
    if old not in text:
        raise AssertionError("test set-up: %r is not in the base case" % old)
    return text.replace(old, new, 1)


def position(text, line_has, token):
    """(line, column), 1-based, of `token` on the first line of `text` containing `line_has`."""
    for number, line in enumerate(text.splitlines(), start=1):
        if line_has in line:
            column = line.find(token)
            if column < 0:
                raise AssertionError("test set-up: %r is not on line %r" % (token, line))
            return number, column + 1
    raise AssertionError("test set-up: no line contains %r" % line_has)


def workdir(files=()):
    """A fresh case folder holding the rectangle's geometry and any extra files."""
    work = tempfile.mkdtemp(prefix="seam_bad_input_")
    H.write_case(work, "body.geo", geometry.rectangle("tri", 0.5))
    for name, text in files:
        H.write_case(work, name, text)
    return work


def check_clean(output, where):
    for word in FORBIDDEN:
        if word in output:
            raise AssertionError("%s: output contains %r:\n%s" % (where, word, output[-3000:]))


def commands(yaml_name):
    return (["check", yaml_name], ["run", yaml_name, "-o", "out", "--quiet"])


def expect_input_error(text, must, at=None, files=(), yaml_name="case.yaml", nps=(1,),
                       timeout=300, run_only=False):
    """Runs `seam check` and `seam run` on `text` (`run_only`: `seam run`, for what `seam
    check` does not set up); both must exit with 1 and a message that starts with the location
    (FILE:LINE:COL when `at` is given, else FILE; `at` False: no location) and contains every
    string of `must`, the same message on every number of ranks of `nps`. A run longer than
    `timeout` seconds (a rank left waiting in a collective) fails."""
    work = workdir(files)
    if text is not None:
        H.write_case(work, yaml_name, text)
    where = yaml_name if at is None else "" if at is False else "%s:%d:%d:" % (yaml_name, *at)
    messages = {}
    try:
        for np in nps:
            for args in commands(yaml_name)[1 if run_only else 0:]:
                label = "seam %s (np=%d)" % (args[0], np)
                try:
                    code, out, err = H.run(args, np=np, cwd=work, check=False, timeout=timeout)
                except subprocess.TimeoutExpired:
                    raise AssertionError("%s: no exit within %d s (a rank waiting for the others?)"
                                         % (label, timeout))
                both = out + err
                check_clean(both, label)
                if code != 1:
                    raise AssertionError("%s: exit code %d, expected 1\nstdout:\n%s\nstderr:\n%s"
                                         % (label, code, out[-2000:], err[-2000:]))
                prefix = "seam: input error: "
                if err.count(prefix) != 1:
                    raise AssertionError("%s: expected one %r message on stderr, got %d:\n%s"
                                         % (label, prefix, err.count(prefix), err))
                message = err[err.index(prefix) + len(prefix):]
                if not message.startswith(where):
                    raise AssertionError("%s: message does not start with %r:\n%s"
                                         % (label, where, message))
                for piece in must:
                    if piece not in message:
                        raise AssertionError("%s: message lacks %r:\n%s" % (label, piece, message))
                line = message.splitlines()[0]
                first = messages.setdefault(args[0], (np, line))
                if first[1] != line:
                    raise AssertionError("%s: message differs from np=%d:\n%s\n%s"
                                         % (label, first[0], first[1], message))
                if np > 1:
                    expect_every_rank(args, np, work, 1, timeout)
    finally:
        H.cleanup(work)


def expect_every_rank(args, np, cwd, code, timeout=300):
    """Runs seam under mpirun with each rank's exit code reported by a shell around it (the
    shell then exits 0 so that mpirun does not end the other ranks early)."""
    script = '"$0" "$@"; echo "seam-rank-exit $?" >&2; exit 0'
    cmd = [H.MPIEXEC, "--oversubscribe", "-np", str(np), "sh", "-c", script, H.SEAM] + list(args)
    try:
        p = subprocess.run(cmd, cwd=cwd, env=H.mpi_env(), capture_output=True, text=True,
                           timeout=timeout)
    except subprocess.TimeoutExpired:
        raise AssertionError("seam %s (np=%d, per rank): no exit within %d s" % (args[0], np, timeout))
    codes = [int(c) for c in re.findall(r"seam-rank-exit (\d+)", p.stderr)]
    if codes != [code] * np:
        raise AssertionError("seam %s: rank exit codes %s, expected %d on each of %d ranks\n%s"
                             % (args[0], codes, code, np, p.stderr[-3000:]))
    check_clean(p.stdout + p.stderr, "seam %s (np=%d, per rank)" % (args[0], np))


# --- the schema: keys, types, required sections ------------------------------------------

def test_unknown_top_level_key():
    text = mutate("title:", "titel:")
    expect_input_error(text, ["titel", "unknown key 'titel'", "(did you mean 'title'?)"],
                       at=position(text, "titel:", "titel"))


def test_unknown_nested_key():
    text = mutate("young:", "youngs:")
    expect_input_error(text, ["materials.steel.youngs", "(did you mean 'young'?)",
                              "'model', 'young', 'poisson', 'density'"],
                       at=position(text, "youngs:", "youngs"))


def test_wrong_type():
    text = mutate("young: 200", "young: abc")
    expect_input_error(text, ["materials.steel.young", "expected a number, got 'abc'"],
                       at=position(text, "young: abc", "abc"))


def test_missing_bodies():
    text = mutate("bodies:\n  - {region: body, material: steel}\n", "")
    expect_input_error(text, ["missing required key 'bodies'"], at=(1, 1))


def test_missing_materials():
    text = mutate("materials:\n  steel: {model: linear_elastic, young: 200, poisson: 0.3, "
                  "density: 1}\n", "")
    expect_input_error(text, ["missing required key 'materials'"], at=(1, 1))


def test_missing_mesh():
    text = mutate("mesh:\n  geo: body.geo\n", "")
    expect_input_error(text, ["missing required key 'mesh'"], at=(1, 1))


def test_duplicate_key():
    text = mutate("dimension: 2\n", "dimension: 2\ndimension: 2\n")
    expect_input_error(text, ["key 'dimension' given twice (first at line 2)"], at=(3, 1))


def test_empty_file():
    expect_input_error("", ["the input file is empty", "'dimension', 'mesh'"])


def test_list_instead_of_mapping():
    expect_input_error("- dimension: 2\n- mesh: {geo: body.geo}\n",
                       ["expected a mapping (key: value), got a list"], at=(1, 1))


def test_input_file_missing():
    expect_input_error(None, ["nope.yaml: input file not found"], yaml_name="nope.yaml")


# --- YAML syntax -----------------------------------------------------------------------

def test_yaml_unclosed_bracket():
    text = mutate("value: [0, 0]}", "value: [0, 0}")
    # yaml-cpp stops at the brace that closes a mapping inside the open list.
    expect_input_error(text, ["invalid YAML", "flow"], at=position(text, "value: [0, 0}", "}"))


def test_yaml_bad_indentation():
    text = mutate("  end: 1\n", "    end: 1\n")
    # `end` indented under `integrator: static`, a scalar: the ':' after it is the error.
    expect_input_error(text, ["invalid YAML", "map value"], at=position(text, "    end: 1", ":"))


def test_yaml_tab_indentation():
    text = mutate("  end: 1\n", "\tend: 1\n")
    expect_input_error(text, ["invalid YAML", "tab"], at=(position(text, "end: 1", "\t")[0], 1))


# --- meshes ----------------------------------------------------------------------------

def test_mesh_file_missing():
    text = mutate("geo: body.geo", "file: nothere.msh")
    expect_input_error(text, ["mesh.file", "file not found", "nothere.msh"],
                       at=position(text, "file: nothere.msh", "nothere.msh"))


def test_geo_gmsh_cannot_parse():
    text = mutate("geo: body.geo", "geo: broken.geo")
    expect_input_error(text, ["mesh.geo", "broken.geo", "line 2", "syntax error"],
                       at=position(text, "geo: broken.geo", "geo"),
                       files=[("broken.geo", "Point(1) = {0, 0, 0, 0.5};\nLine(1) = {1, 2;\n")])


def test_msh_garbage():
    text = mutate("geo: body.geo", "file: garbage.msh")
    expect_input_error(text, ["mesh.file", "garbage.msh'"],
                       at=position(text, "file: garbage.msh", "file"),
                       files=[("garbage.msh", "This is not a mesh file.\nNodes: 1 2 3\n")])


def test_msh_truncated():
    text = mutate("geo: body.geo", "file: truncated.msh")
    expect_input_error(text, ["mesh.file", "truncated.msh'"],
                       at=position(text, "file: truncated.msh", "file"),
                       files=[("truncated.msh", TRUNCATED_MSH)])


def test_msh_unsupported_element():
    text = PRISM_YAML
    expect_input_error(text, ["mesh.file", "prism.msh'", "6-node prism) is not supported",
                              "tet4, tet10, hex8"],
                       at=position(text, "mesh:", "{"), files=[("prism.msh", PRISM_MSH)])


def test_3d_mesh_with_dimension_2():
    text = mutate("geo: body.geo", "geo: box.geo")
    expect_input_error(text, ["mesh.geo", "box.geo'", "dimension 3", "dimension 2"],
                       at=position(text, "geo: box.geo", "geo"),
                       files=[("box.geo", geometry.box("tet", 1.0))])


# --- expressions -----------------------------------------------------------------------

def test_expression_syntax():
    text = mutate('"0.1*t"', '"sin(t"')
    expect_input_error(text, ["boundary_conditions[1].value[0]", 'expression "sin(t"',
                              "parenthesis", "expected an expression in t, x, y, z"],
                       at=position(text, "sin(t", '"sin'))


def test_expression_unknown_variable():
    text = mutate('"0.1*t"', '"q*t"')
    expect_input_error(text, ["boundary_conditions[1].value[0]", 'expression "q*t"', '"q"',
                              "expected an expression in t, x, y, z"],
                       at=position(text, "q*t", '"q'))


def test_dirichlet_value_not_finite():
    """'-0.01*t/(1-t)' compiles and is finite until t = 1, where the last step would prescribe
    an infinite displacement: `seam run` stops there with exit 1 and a message located at the
    condition that names the expression and t, on every rank (before, the run went on with
    infinite values: a step cut and exit 2, or in a contact run an unlocated "degenerate
    facet" error)."""
    text = mutate("components: [x, y], value: [0, 0]", 'components: [x, y], value: [0, "-0.01*t/(1-t)"]')
    work = workdir()
    H.write_case(work, "case.yaml", text)
    try:
        for np in (1, 3):
            args = ["run", "case.yaml", "-o", "out", "--quiet"]
            code, out, err = H.run(args, np=np, cwd=work, check=False, timeout=300)
            check_clean(out + err, "np %d" % np)
            prefix = "seam: input error: case.yaml:"
            message = err[err.find(prefix):].strip()
            if code != 1 or err.count("seam: input error: ") != 1 or not message.startswith(prefix) \
                    or "boundary_conditions[0]" not in message \
                    or "'-0.01*t/(1-t)' is not finite at t = 1" not in message:
                raise AssertionError("np %d: exit %d\n%s" % (np, code, err[-2000:]))
            print("   np %d: %s" % (np, message.splitlines()[0]))
            rows = H.read_csv(os.path.join(work, "out", "steps.csv"))
            if len(rows) != 1:
                raise AssertionError("np %d: %d steps written, expected the one before t = 1"
                                     % (np, len(rows)))
            if np > 1:
                expect_every_rank(args, np, work, 1)
    finally:
        H.cleanup(work)


# --- non-physical material constants ---------------------------------------------------

def material_case(old, new, key, expected):
    text = mutate(old, new)
    line, column = position(text, new, new)
    expect_input_error(text, ["materials.steel." + key, expected],
                       at=(line, column + len(key) + 2))


def test_young_zero():
    material_case("young: 200", "young: 0", "young", "must be > 0, got 0")


def test_young_negative():
    material_case("young: 200", "young: -5", "young", "must be > 0, got -5")


def test_poisson_half():
    material_case("poisson: 0.3", "poisson: 0.5", "poisson",
                  "must satisfy -1 < poisson < 0.5, got 0.5")


def test_poisson_minus_one():
    material_case("poisson: 0.3", "poisson: -1", "poisson",
                  "must satisfy -1 < poisson < 0.5, got -1")


def test_density_negative():
    material_case("density: 1", "density: -1", "density", "must be >= 0, got -1")


# --- time ------------------------------------------------------------------------------

def test_zero_steps():
    text = mutate("steps: 2", "steps: 0")
    expect_input_error(text, ["time.steps", "must be a positive integer, got 0"],
                       at=position(text, "steps: 0", "0"))


def test_negative_end():
    text = mutate("end: 1", "end: -1")
    expect_input_error(text, ["time.end", "must be > 0, got -1"], at=position(text, "end: -1", "-1"))


def test_checkpoint_every_zero():
    text = mutate("  probes: [[1.0, 0.5]]\n", "  probes: [[1.0, 0.5]]\n  checkpoint_every: 0\n")
    expect_input_error(text, ["output.checkpoint_every", "must be >= 1"],
                       at=position(text, "checkpoint_every: 0", "0"))


def test_dt_and_steps():
    text = mutate("steps: 2\n", "steps: 2\n  dt: 0.5\n")
    expect_input_error(text, ["time.dt", "either 'steps' or 'dt', not both"],
                       at=position(text, "dt: 0.5", "0.5"))


def test_unknown_integrator():
    text = mutate("integrator: static", "integrator: statik")
    expect_input_error(text, ["time.integrator", "unknown value 'statik'",
                              "(did you mean 'static'?)",
                              "expected one of 'static', 'generalized_alpha', 'energy_momentum'"],
                       at=position(text, "statik", "statik"))


# --- regions, materials, vectors -------------------------------------------------------

def test_bc_region_missing():
    text = mutate("region: left", "region: lefty")
    expect_input_error(text, ["boundary_conditions[0].region", "no region 'lefty' in the mesh",
                              "available: " + REGIONS],
                       at=position(text, "lefty", "lefty"), nps=(1, 3))


def test_bc_region_wrong_dimension():
    text = mutate('{region: right, type: traction, value: ["0.1*t", 0]}',
                  "{region: body, type: pressure, value: 1}")
    expect_input_error(text, ["boundary_conditions[1].region", "region 'body' has dimension 2",
                              "a pressure load needs a region of dimension 1"],
                       at=position(text, "type: pressure", "body"))


def test_body_region_missing():
    text = mutate("region: body,", "region: bdy,")
    expect_input_error(text, ["bodies[0].region", "no region 'bdy' in the mesh",
                              "available: " + REGIONS],
                       at=position(text, "region: bdy", "bdy"))


def test_unknown_material():
    text = mutate("material: steel}", "material: steal}")
    expect_input_error(text, ["bodies[0].material", "unknown material 'steal'",
                              "(did you mean 'steel'?)", "defined under 'materials': 'steel'"],
                       at=position(text, "steal", "steal"))


def test_probe_outside_mesh():
    text = mutate("[[1.0, 0.5]]", "[[1.0, 0.5], [5.0, 0.5]]")
    expect_input_error(text, ["output.probes[1]", "probe (5, 0.5) lies outside the mesh",
                              "[0, 2] x [0, 1]"],
                       at=position(text, "probes:", "[5.0"))


def test_vector_too_long_for_2d():
    text = mutate('value: ["0.1*t", 0]', 'value: ["0.1*t", 0, 0]')
    expect_input_error(text, ["boundary_conditions[1].value", "expected 2 components "
                              "(dimension is 2), got 3"],
                       at=position(text, '"0.1*t", 0, 0', '["0.1'))


def test_probe_with_three_coordinates_in_2d():
    text = mutate("[[1.0, 0.5]]", "[[1.0, 0.5, 0.0]]")
    expect_input_error(text, ["output.probes[0]", "expected 2 coordinates (dimension is 2), got 3"],
                       at=position(text, "probes:", "[1.0"))


def test_component_listed_twice():
    text = mutate("components: [x, y]", "components: [x, x]")
    expect_input_error(text, ["boundary_conditions[0].components[1]", "'x' is listed twice"],
                       at=position(text, "[x, x]", "x]"))


def test_component_z_in_2d():
    text = mutate("components: [x, y]", "components: [x, z]")
    expect_input_error(text, ["boundary_conditions[0].components[1]",
                              "'z' does not exist in 2D; expected 'x' or 'y'"],
                       at=position(text, "[x, z]", "z]"))


# --- command line and output directory -------------------------------------------------

def test_output_directory_not_creatable():
    # -o names a folder inside a regular file; rank 0 alone creates folders, so on 3 ranks
    # the others must hear of the failure instead of waiting for rank 0.
    work = workdir([("case.yaml", BASE), ("afile", "not a folder\n")])
    try:
        for np in (1, 3):
            args = ["run", "case.yaml", "-o", "afile/out", "--quiet"]
            code, out, err = H.run(args, np=np, cwd=work, check=False, timeout=300)
            check_clean(out + err, "np=%d" % np)
            if code != 1 or err.count("seam: input error: ") != 1 or \
                    "output directory 'afile/out' cannot be created" not in err:
                raise AssertionError("np=%d: exit code %d, expected 1 and one message naming "
                                     "the directory:\n%s" % (np, code, err[-2000:]))
            if np > 1:
                expect_every_rank(args, np, work, 1)
    finally:
        H.cleanup(work)


def test_unknown_command_line_flag():
    work = workdir([("case.yaml", BASE)])
    try:
        code, out, err = H.run(["run", "case.yaml", "--bogus"], cwd=work, check=False,
                               timeout=300)
        check_clean(out + err, "seam run --bogus")
        if code != 1 or "--bogus" not in err or "--help" not in err:
            raise AssertionError("exit code %d, expected 1 with the flag named and a hint to "
                                 "--help:\n%s" % (code, err))
        if os.path.exists(os.path.join(work, "case_out")):
            raise AssertionError("seam run --bogus wrote output")
    finally:
        H.cleanup(work)


def test_version_and_help():
    code, out, err = H.run(["--version"], check=False, timeout=60)
    if code != 0 or not re.match(r"seam \d+\.\d+\.\d+", out.strip()):
        raise AssertionError("seam --version: exit code %d, stdout %r" % (code, out))
    code, out, err = H.run(["--help"], check=False, timeout=60)
    for word in ("Usage", "run", "check", "--version"):
        if code != 0 or word not in out:
            raise AssertionError("seam --help: exit code %d, %r missing:\n%s" % (code, word, out))


# --- exit code 2 -----------------------------------------------------------------------

def expect_solver_gave_up(np):
    work = workdir([("crush.yaml", CRUSH_YAML)])
    try:
        code, out, err = H.run(["check", "crush.yaml"], np=np, cwd=work, check=False,
                               timeout=300)
        if code != 0:
            raise AssertionError("np=%d: seam check of a valid input: exit code %d\n%s"
                                 % (np, code, err))
        args = ["run", "crush.yaml", "-o", "out", "--quiet"]
        code, out, err = H.run(args, np=np, cwd=work, check=False, timeout=600)
        check_clean(out + err, "np=%d" % np)
        if code != 2 or err.count("seam: solver failed: ") != 1:
            raise AssertionError("np=%d: exit code %d, expected 2 and one 'solver failed' "
                                 "message:\n%s" % (np, code, err[-3000:]))
        if "step cuts" not in err or not re.search(r"written in \S*out", err):
            raise AssertionError("np=%d: message does not tell the step cuts and where the "
                                 "converged steps are:\n%s" % (np, err))
        outdir = os.path.join(work, "out")
        steps = H.read_csv(os.path.join(outdir, "steps.csv"))
        if len(steps) < 1:
            raise AssertionError("np=%d: steps.csv has no converged step" % np)
        if [int(r["step"]) for r in steps] != list(range(1, len(steps) + 1)):
            raise AssertionError("np=%d: steps.csv steps are not 1..n: %s" % (np, steps))
        times = [r["time"] for r in steps]
        # The faces meet at t = 2/3, so the bar fails before that; the run got past step 1.
        if not all(a < b for a, b in zip(times, times[1:])) or times[-1] >= 2.0 / 3.0:
            raise AssertionError("np=%d: converged times %s" % (np, times))
        summary = H.read_json(os.path.join(outdir, "summary.json"))
        if summary.get("status") != "failed":
            raise AssertionError("np=%d: summary.json status %r" % (np, summary.get("status")))
        reaction_steps = {int(r["step"]) for r in H.read_csv(os.path.join(outdir,
                                                                           "reactions.csv"))}
        if not {int(r["step"]) for r in steps} <= reaction_steps:
            raise AssertionError("np=%d: reactions.csv lacks converged steps" % np)
        if not os.path.exists(os.path.join(outdir, "results.pvd")):
            raise AssertionError("np=%d: results.pvd was not kept" % np)
        pvd = open(os.path.join(outdir, "results.pvd")).read()
        for piece in re.findall(r'file="([^"]+)"', pvd):
            if not os.path.exists(os.path.join(outdir, piece)):
                raise AssertionError("np=%d: results.pvd names %s, which is missing"
                                     % (np, piece))
        if np > 1:
            expect_every_rank(["run", "crush.yaml", "-o", "out_ranks", "--quiet"], np, work, 2)
    finally:
        H.cleanup(work)


def test_solver_gives_up_exit_2():
    expect_solver_gave_up(1)


# --- contact interfaces -----------------------------------------------------------------

CONTACT = BASE.replace("time:\n", """interfaces:
  - name: floor
    type: contact
    slave: bottom
    rigid_plane: {point: [0, 0], normal: [0, 1]}
time:
""", 1)


def with_friction(friction):
    return mutate("normal: [0, 1]}", "normal: [0, 1]}\n    friction: " + friction, CONTACT)


def test_friction_coefficient_negative():
    text = with_friction("{model: coulomb, coefficient: -0.3}")
    expect_input_error(text, ["interfaces[0].friction.coefficient", "must be >= 0, got -0.3"],
                       at=position(text, "friction:", "-0.3"))


def test_friction_coefficient_not_a_number():
    text = with_friction("{model: coulomb, coefficient: rough}")
    expect_input_error(text, ["interfaces[0].friction.coefficient", "rough"],
                       at=position(text, "friction:", "rough"))


def test_friction_unknown_model():
    text = with_friction("{model: viscous, coefficient: 0.3}")
    expect_input_error(text, ["interfaces[0].friction.model", "viscous", "coulomb", "tresca"],
                       at=position(text, "friction:", "viscous"))


def test_friction_tresca_without_bound():
    text = with_friction("{model: tresca}")
    expect_input_error(text, ["interfaces[0].friction", "bound"])


def test_friction_tresca_bound_negative():
    text = with_friction("{model: tresca, bound: -1}")
    expect_input_error(text, ["interfaces[0].friction.bound", "must be >= 0"],
                       at=position(text, "friction:", "-1"))


def test_friction_bound_not_a_number():
    text = with_friction("{model: tresca, bound: smooth}")
    expect_input_error(text, ["interfaces[0].friction.bound", "smooth"],
                       at=position(text, "friction:", "smooth"))


def test_friction_coefficient_with_tresca():
    text = with_friction("{model: tresca, bound: 1, coefficient: 0.3}")
    expect_input_error(text, ["interfaces[0].friction.coefficient", "coulomb"])


def test_friction_on_mesh_tying():
    text = mutate("normal: [0, 1]}", "normal: [0, 1]}", CONTACT).replace(
        "    type: contact\n    slave: bottom\n    rigid_plane: {point: [0, 0], normal: [0, 1]}",
        "    type: mesh_tying\n    slave: bottom\n    master: top\n"
        "    friction: {model: coulomb, coefficient: 0.3}")
    expect_input_error(text, ["interfaces[0].friction", "applies only to type 'contact'"],
                       at=position(text, "friction:", "{model"))


def test_friction_c_t_without_friction():
    text = mutate("normal: [0, 1]}", "normal: [0, 1]}\n    c_t: 5", CONTACT)
    expect_input_error(text, ["interfaces[0].c_t", "friction"], at=position(text, "c_t:", "5"))


def test_contact_standard_multiplier_tri6(friction=""):
    """Standard multipliers weight the gaps with N_j, whose integral vanishes at the vertices
    of a tri6 face: rejected with a pointer to the dual ones."""
    geo = ('SetFactory("OpenCASCADE");\nBox(1) = {0, 0, 0, 1, 1, 1};\n'
           'Mesh.MeshSizeMax = 0.6;\nPhysical Volume("body") = {1};\n'
           'Physical Surface("bottom") = {5};\nPhysical Surface("top") = {6};\n')
    text = """title: tet10 block on a plane
dimension: 3
mesh: {geo: box.geo, order: 2}
materials:
  steel: {model: linear_elastic, young: 200, poisson: 0.3}
bodies:
  - {region: body, material: steel}
boundary_conditions:
  - {region: top, type: dirichlet, components: [x, y, z], value: [0, 0, "-0.01*t"]}
interfaces:
  - name: floor
    type: contact
    slave: bottom
    rigid_plane: {point: [0, 0, 0], normal: [0, 0, 1]}
    multiplier: standard%s
time: {integrator: static, end: 1, steps: 1}
""" % friction
    expect_input_error(text, ["interface 'floor'", "standard multipliers on tri6/quad8",
                              "use multiplier: dual"], files=[("box.geo", geo)])


def test_friction_standard_multiplier_tri6():
    """Friction does not lift it: the frictional rows need the same weighted gaps."""
    test_contact_standard_multiplier_tri6("\n    friction: {model: coulomb, coefficient: 0.3}")


def test_contact_c_n_negative():
    text = mutate("normal: [0, 1]}", "normal: [0, 1]}\n    c_n: -5", CONTACT)
    expect_input_error(text, ["interfaces[0].c_n", "must be > 0, got -5"],
                       at=position(text, "c_n: -5", "-5"))


def test_contact_slave_region_missing():
    text = mutate("slave: bottom", "slave: bottm", CONTACT)
    expect_input_error(text, ["interfaces[0].slave", "no region 'bottm'"], at=position(text, "slave: bottm", "bottm"))


def test_contact_rigid_plane_and_master():
    text = mutate("normal: [0, 1]}", "normal: [0, 1]}\n    master: top", CONTACT)
    expect_input_error(text, ["either 'master' or 'rigid_plane', not both"])


# --- contact sides checked over the ranks' parts ---------------------------------------
# Two unit squares stacked in y and meshed apart (no node in common). 'master_overlap' is the
# lower square's top and the upper square's right side, whose end (1, 1) is the first node of
# the upper square's bottom ('upper_bottom'): one shared node, held by the ranks around that
# corner only (on 3 ranks a check made on each rank's part finds it on some ranks, and the
# others wait in the next collective). 'empty' names a curve whose elements were taken out of
# the mesh file: a boundary group without facets. With dual multipliers the sides are held in
# part on 3 ranks, with standard multipliers whole; the slave side against the rigid circle
# in part.
SIDES_GEO = """\
Geometry.AutoCoherence = 0;
Point(1) = {0, 0, 0, 0.2}; Point(2) = {1, 0, 0, 0.2};
Point(3) = {1, 1, 0, 0.2}; Point(4) = {0, 1, 0, 0.2};
Point(5) = {0, 1, 0, 0.15}; Point(6) = {1, 1, 0, 0.15};
Point(7) = {1, 2, 0, 0.15}; Point(8) = {0, 2, 0, 0.15};
Point(9) = {0.5, 3, 0, 0.2}; Point(10) = {0.7, 3, 0, 0.2};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Line(9) = {9, 10};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Physical Surface("lower") = {1}; Physical Surface("upper") = {2};
Physical Curve("bottom") = {1}; Physical Curve("top") = {7};
Physical Curve("lower_top") = {3}; Physical Curve("upper_bottom") = {5};
Physical Curve("master_overlap") = {3, 6};
Physical Curve("empty") = {9};
Physical Point("corner") = {1};
"""

SIDES_YAML = """\
title: contact sides checked on 3 ranks
dimension: 2
mesh: {file: blocks.msh}
materials:
  lo: {model: linear_elastic, young: 100, poisson: 0.3}
  up: {model: linear_elastic, young: 40, poisson: 0.3}
bodies:
  - {region: lower, material: lo}
  - {region: upper, material: up}
boundary_conditions:
  - {region: bottom, type: dirichlet, components: [x, y], value: [0, 0]}
  - {region: top, type: dirichlet, components: [x, y], value: [0, "-0.01*t"]}
interfaces:
  - {name: contact, type: contact, %s}
time: {integrator: static, end: 1, steps: 1}
"""

SIDE_CASES = {
    "dual": "slave: %s, master: %s",
    "standard": "slave: %s, master: %s, multiplier: standard",
    "rigid circle": "slave: %s, rigid_sphere: {center: [0.5, 3], radius: 0.5}",
}


@functools.lru_cache(maxsize=None)
def sides_msh():
    """SIDES_GEO meshed by Gmsh (MSH 4.1, ASCII), without the elements of curve 9."""
    work = tempfile.mkdtemp(prefix="seam_sides_")
    try:
        H.write_case(work, "blocks.geo", SIDES_GEO)
        subprocess.run([os.environ.get("GMSH", "gmsh"), "-2", "-format", "msh41", "blocks.geo",
                        "-o", "blocks.msh"], cwd=work, check=True, capture_output=True)
        with open(os.path.join(work, "blocks.msh")) as f:
            lines = f.read().split("\n")
    finally:
        H.cleanup(work)
    at = lines.index("$Elements")
    blocks, count, low, high = (int(v) for v in lines[at + 1].split())
    kept, k = [], at + 2
    while lines[k] != "$EndElements":
        dim, tag, _, n = (int(v) for v in lines[k].split())
        if (dim, tag) == (1, 9):
            blocks, count = blocks - 1, count - n
        else:
            kept += lines[k:k + 1 + n]
        k += 1 + n
    if count == int(lines[at + 1].split()[1]):
        raise AssertionError("test set-up: curve 9 has no elements in Gmsh's mesh")
    return "\n".join(lines[:at + 1] + ["%d %d %d %d" % (blocks, count, low, high)] + kept
                     + lines[k:])


def expect_side_error(case, sides, must, token):
    """The interface of SIDE_CASES[case] with `sides` fails alike on 1 and 3 ranks, within 60 s."""
    text = SIDES_YAML % (SIDE_CASES[case] % sides)
    expect_input_error(text, must, at=position(text, "name: contact", token),
                       files=[("blocks.msh", sides_msh())], nps=(1, 3), timeout=60)


def test_contact_sides_share_a_node():
    """The shared node is found by its owner and counted once; the message names it by the
    node id of the output and its position."""
    for case in ("dual", "standard"):
        expect_side_error(case, ("upper_bottom", "master_overlap"),
                          ["interfaces[0]", "'upper_bottom'", "'master_overlap'",
                           "share 1 node (the first: node ", " at (1, 1))",
                           "self contact is not available"], "{name")


def test_contact_slave_group_without_facets():
    for case in SIDE_CASES:
        sides = ("empty", "lower_top") if case != "rigid circle" else ("empty",)
        expect_side_error(case, sides, ["interfaces[0].slave", "the slave region 'empty' has no "
                                        "facets"], "empty")


def test_contact_master_group_without_facets():
    for case in ("dual", "standard"):
        expect_side_error(case, ("upper_bottom", "empty"),
                          ["interfaces[0].master", "the master region 'empty' has no facets"],
                          "empty")


def test_contact_side_of_another_dimension():
    for case, sides, key, name, dim in (
            ("dual", ("upper_bottom", "lower"), "master", "lower", 2),
            ("standard", ("upper_bottom", "corner"), "master", "corner", 0),
            ("rigid circle", ("upper",), "slave", "upper", 2)):
        expect_side_error(case, sides,
                          ["interfaces[0].%s" % key, "region '%s' has dimension %d" % (name, dim),
                           "an interface side needs a region of dimension 1"], name)


def test_tying_sides_share_a_node():
    """Mesh tying, condensed and saddle point (both distributed), the node named by its id in
    the mesh as read on every rank."""
    for extra in ("", ", multiplier: standard, strategy: saddle_point"):
        text = (SIDES_YAML % ("slave: upper_bottom, master: master_overlap" + extra)).replace(
            "type: contact", "type: mesh_tying")
        expect_input_error(text, ["interfaces[0]", "share 1 node (the first: node ", " at (1, 1))",
                                  "mesh tying couples two separate meshes"],
                           at=position(text, "name: contact", "{name"),
                           files=[("blocks.msh", sides_msh())], nps=(1, 3), timeout=60)


def test_tying_slave_node_tied_twice():
    """Two condensed interfaces with the same slave side: each node's owner finds it tied
    twice (only a run sets up the condensation)."""
    text = SIDES_YAML % "slave: upper_bottom, master: lower_top}\n" \
        "  - {name: again, type: mesh_tying, slave: upper_bottom, master: lower_top"
    text = text.replace("type: contact", "type: mesh_tying")
    expect_input_error(text, ["interface 'again': 8 slave nodes are tied by two interfaces "
                              "(the first: node ", "slave sides must not share nodes"], at=False,
                       files=[("blocks.msh", sides_msh())], nps=(1, 3), timeout=60,
                       run_only=True)


# --- on 3 ranks ------------------------------------------------------------------------

def test_bad_expression_on_3_ranks():
    text = mutate('"0.1*t"', '"q*t"')
    expect_input_error(text, ["boundary_conditions[1].value[0]", 'expression "q*t"'],
                       at=position(text, "q*t", '"q'), nps=(3,))


def test_solver_gives_up_exit_2_on_3_ranks():
    expect_solver_gave_up(3)


def test_parallel_tolerance_below_one():
    text = BASE + "parallel: {rebalance_tolerance: 0.8}\n"
    expect_input_error(text, ["parallel.rebalance_tolerance", "must be >= 1", "0.8"],
                       at=position(text, "rebalance_tolerance", "0.8"))


def test_parallel_unknown_distribution():
    text = BASE + "parallel: {interface_distribution: bluk}\n"
    expect_input_error(text, ["parallel.interface_distribution", "bluk", "independent", "bulk"],
                       at=position(text, "interface_distribution", "bluk"))


if __name__ == "__main__":
    H.main([
        test_unknown_top_level_key, test_unknown_nested_key, test_wrong_type,
        test_missing_bodies, test_missing_materials, test_missing_mesh, test_duplicate_key,
        test_empty_file, test_list_instead_of_mapping, test_input_file_missing,
        test_yaml_unclosed_bracket, test_yaml_bad_indentation, test_yaml_tab_indentation,
        test_mesh_file_missing, test_geo_gmsh_cannot_parse, test_msh_garbage,
        test_msh_truncated, test_msh_unsupported_element, test_3d_mesh_with_dimension_2,
        test_expression_syntax, test_expression_unknown_variable, test_dirichlet_value_not_finite,
        test_young_zero, test_young_negative, test_poisson_half, test_poisson_minus_one,
        test_density_negative,
        test_zero_steps, test_negative_end, test_dt_and_steps, test_checkpoint_every_zero, test_unknown_integrator,
        test_bc_region_missing, test_bc_region_wrong_dimension, test_body_region_missing,
        test_unknown_material, test_probe_outside_mesh, test_vector_too_long_for_2d,
        test_probe_with_three_coordinates_in_2d, test_component_listed_twice,
        test_component_z_in_2d,
        test_output_directory_not_creatable, test_unknown_command_line_flag,
        test_version_and_help,
        test_friction_coefficient_negative, test_friction_coefficient_not_a_number,
        test_friction_unknown_model, test_friction_tresca_without_bound,
        test_friction_tresca_bound_negative, test_friction_bound_not_a_number,
        test_friction_coefficient_with_tresca,
        test_friction_on_mesh_tying, test_friction_c_t_without_friction,
        test_contact_standard_multiplier_tri6, test_friction_standard_multiplier_tri6,
        test_contact_c_n_negative, test_contact_slave_region_missing,
        test_contact_rigid_plane_and_master,
        test_parallel_tolerance_below_one, test_parallel_unknown_distribution,
        test_solver_gives_up_exit_2, test_bad_expression_on_3_ranks,
        test_solver_gives_up_exit_2_on_3_ranks,
        test_contact_sides_share_a_node, test_contact_slave_group_without_facets,
        test_contact_master_group_without_facets, test_contact_side_of_another_dimension,
        test_tying_sides_share_a_node, test_tying_slave_node_tied_twice,
    ])
