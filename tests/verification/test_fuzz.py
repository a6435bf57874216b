"""Fuzzed input (issue 17): mutated example inputs and meshes never crash seam.

A deterministic generator (fixed seed) takes the small example inputs of examples/ (solids,
mesh tying, contact, friction, dynamics, fluid-structure interaction) and the meshes Gmsh
writes from their .geo files, and breaks them: keys dropped, renamed or
duplicated, values of the wrong type, numbers out of range (negative young, poisson >= 0.5,
steps 0, ...), unknown regions, empty lists and sections, vectors of the wrong length,
broken expressions and YAML syntax, and .msh files truncated or corrupted (counts, element
types, node indices, coordinates, section markers) in the 2.2 and 4.1 formats. Most cases are
`seam check`, those on small 2D meshes also `seam run` with one step, a few on 2 ranks.

Each case must end with
  * exit code 0, or
  * exit code 1 with one message `seam: input error: FILE...` on stderr, where FILE is the
    input (with line:column and key path) or the mesh file it names, or
  * for `seam run`, exit code 2 with `seam: solver failed:` (an input that is valid but that
    no solver can handle, such as young: 1e308, whose stiffness overflows);
and never with a crash (signal, exit code 3), a hang, a PETSc traceback or "terminate called"
in the output. A hang is a case whose seam process has used 30 s of time of its own: wall
time less the time it spent waiting for a CPU (the run queue wait of Linux's schedstat), so a
case that loops or that sleeps is stopped after 30 s however loaded the machine is, and a slow
case on a machine shared by other builds is not (the wall time alone timed out spuriously).
A case is also stopped after 20 x 30 s of wall time whatever its accounting says.

SEAM_FUZZ_SEED and SEAM_FUZZ_CASES choose another seed and number of cases (for longer
hunts outside CI); SEAM_FUZZ_KEEP=DIR keeps the folders of failing cases there.
"""
import concurrent.futures
import os
import random
import re
import shutil
import subprocess
import sys
import tempfile
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import harness as H  # noqa: E402

EXAMPLES_DIR = os.path.normpath(os.path.join(H.HERE, "..", "..", "examples"))
SEED = int(os.environ.get("SEAM_FUZZ_SEED", "17"))
N_CASES = int(os.environ.get("SEAM_FUZZ_CASES", "320"))
TIMEOUT = float(os.environ.get("SEAM_FUZZ_TIMEOUT", "30"))  # seconds of a case's own time
WALL_LIMIT = 20 * TIMEOUT  # the backstop

# (folder, input, runnable with one step in CI): the small examples only.
EXAMPLES = [
    ("cantilever_2d", "cantilever.yaml", True),
    ("hertz_2d", "hertz_2d.yaml", True),
    ("tied_2d_quadratic", "plate.yaml", True),
    ("neo_hooke_block", "block.yaml", False),
    ("tied_blocks", "blocks.yaml", False),
    ("twisted_bar", "twist.yaml", False),
    ("cylinder_inclusion", "inclusion.yaml", False),
    ("l_block", "l_block.yaml", False),
    ("cattaneo_mindlin", "cattaneo.yaml", False),  # friction (the flagship)
    ("turek_hron", "fsi1.yaml", False),  # fluid-structure interaction: fluid keys, fsi interface
]

FORBIDDEN = ("PETSc", "Traceback", "terminate called", "Segmentation", "core dumped",
             "internal error", "MPI_ABORT", "exited on signal", "what():", "AddressSanitizer",
             "runtime error:")
PREFIX = "seam: input error: "
LOCATED = re.compile(r"^[\w./+-]+\.(yaml|msh|geo)(:\d+:\d+)?: ")

# --- the example inputs, read once -------------------------------------------------------


class Example:
    def __init__(self, folder, name, runnable):
        self.folder, self.name, self.runnable = folder, name, runnable
        with open(os.path.join(EXAMPLES_DIR, folder, name)) as f:
            self.text = f.read()
        self.dim = int(re.search(r"^dimension: (\d)", self.text, re.M).group(1))
        self.geo = re.search(r"geo: (\w+\.geo)", self.text).group(1)
        self.order = 2 if re.search(r"^(\s*|mesh: \{.*)order: 2", self.text, re.M) else 1
        self.msh = self.geo.replace(".geo", ".msh")

    def with_mesh_file(self, msh):
        """The input with its mesh section replaced by `mesh: {file: MSH}`."""
        lines = self.text.splitlines()
        start = next(i for i, l in enumerate(lines) if l.startswith("mesh:"))
        end = start + 1
        while end < len(lines) and (lines[end].startswith(" ") or not lines[end].strip()):
            end += 1
        return "\n".join(lines[:start] + ["mesh: {file: %s}" % msh] + lines[end:]) + "\n"

    def for_run(self, text):
        """One static step (the time line is then left alone by the mutations)."""
        text = re.sub(r"^time:.*\n(  .*\n)*", "time: {integrator: static, end: 1, steps: 1}\n",
                      text, flags=re.M)
        return re.sub(r"^output:.*\n(  .*\n)*", "", text, flags=re.M)


def mesh_examples(work, examples):
    """Each example's .geo meshed by Gmsh into WORK/FOLDER/ as .msh 2.2 and 4.1."""
    for ex in examples:
        dest = os.path.join(work, ex.folder)
        shutil.copytree(os.path.join(EXAMPLES_DIR, ex.folder), dest)
        for fmt, suffix in (("msh22", ".msh"), ("msh41", "_41.msh")):
            out = os.path.join(dest, ex.msh.replace(".msh", suffix))
            subprocess.run(["gmsh", "-%d" % ex.dim, "-order", str(ex.order), "-format", fmt,
                            os.path.join(dest, ex.geo), "-o", out],
                           check=True, capture_output=True, timeout=120)


# --- YAML mutations (on the text: the point is what a user can type) ---------------------

PAIR = re.compile(r"(?P<key>[A-Za-z_]\w*)(?P<colon>\s*:[ ]*)"
                  r"(?P<val>\[[^\[\]\n]*\]|\"[^\"\n]*\"|'[^'\n]*'|[^,{}\[\]\n#]*)")
NUMBER = re.compile(r"^-?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$")

WRONG_TYPES = ["abc", "[1, 2]", "{a: 1}", "", "null", "~", "true", "1e999", "-1e999", ".nan",
               ".inf", "0x1F", "'1'", "[[]]", "[]", "{}", "1.5.2", "\"\"", "[x, y]", "- 1"]
OUT_OF_RANGE = {
    "young": ["0", "-1", "-1e-300", "1e308", "1e-320"],
    "poisson": ["0.5", "0.51", "-1", "-1.5", "0.4999999999999", "1e10"],
    "density": ["-1", "-1e-12", "0", "1e308"],
    "steps": ["0", "-1", "1.5", "2147483648", "99999999999999999999", "1e3"],
    "end": ["0", "-1", "1e-320", "-0.0"],
    "dt": ["0", "-0.1", "1e-320"],
    "rho_inf": ["-0.1", "1.5", "2"],
    "tolerance": ["0", "-1e-10", "1e10"],
    "max_iterations": ["0", "-1", "2.5"],
    "max_step_cuts": ["-1", "0", "1.5"],
    "every": ["0", "-1", "1.5"],
    "order": ["0", "3", "-1", "1.5"],
    "size": ["0", "-1", "1e-320"],
    "dimension": ["1", "4", "0", "-3", "2.5"],
}
EXPRESSIONS = ["0.1*t*(", "q*t", "sin()", "1/0", "t^^2", "", "_pi*", "0.1*t,0", "sqrt(-1)",
               "x y", "1e999*t", "(((((t)))))", "t?1", "$t"]
REGION_KEYS = ("region", "slave", "master")


def pairs(text, skip_line=None):
    """key: value matches outside comments (and outside the line `skip_line` starts with)."""
    out = []
    for m in PAIR.finditer(text):
        line_start = text.rfind("\n", 0, m.start()) + 1
        line = text[line_start:text.find("\n", m.start())]
        if line.lstrip().startswith("#"):
            continue
        if skip_line and line.startswith(skip_line):
            continue
        # Inside a quoted string (e.g. an expression with ':'): not a key.
        if text.count('"', line_start, m.start()) % 2:
            continue
        out.append(m)
    return out


def replace_span(text, start, end, new):
    return text[:start] + new + text[end:]


def typo(rng, word):
    i = rng.randrange(len(word))
    kind = rng.randrange(5)
    if kind == 0 and len(word) > 1:
        return word[:i] + word[i + 1:]
    if kind == 1:
        return word[:i] + rng.choice("aeiouxs_") + word[i:]
    if kind == 2 and i + 1 < len(word):
        return word[:i] + word[i + 1] + word[i] + word[i + 2:]
    if kind == 3:
        return word.upper()
    return rng.choice(["young", "steps", "region", "mesh", "value", "type", "slave", "title",
                       "integrator", "poisson", "geo", "file", "components"])


def mutate_yaml(rng, text, skip_line=None):
    """One mutation of the input text; returns (kind, new text)."""
    ps = pairs(text, skip_line)
    kind = rng.choice(["drop_key", "rename_key", "wrong_type", "out_of_range", "region",
                       "empty_list", "vector_length", "expression", "syntax", "duplicate_line",
                       "drop_line", "empty_section", "swap_values"])
    if kind == "drop_key":
        m = rng.choice(ps)
        start, end = m.start(), m.end()
        rest = text[end:]
        if rest.startswith(", "):
            end += 2
        elif text[:start].endswith(", "):
            start -= 2
        return kind, replace_span(text, start, end, "")
    if kind == "rename_key":
        m = rng.choice(ps)
        return kind, replace_span(text, m.start("key"), m.end("key"), typo(rng, m.group("key")))
    if kind == "wrong_type":
        m = rng.choice(ps)
        return kind, replace_span(text, m.start("val"), m.end("val"), rng.choice(WRONG_TYPES))
    if kind == "out_of_range":
        cands = [m for m in ps if m.group("key") in OUT_OF_RANGE]
        if cands:
            m = rng.choice(cands)
            new = rng.choice(OUT_OF_RANGE[m.group("key")])
        else:
            cands = [m for m in ps if NUMBER.match(m.group("val").strip())] or ps
            m = rng.choice(cands)
            new = rng.choice(["-1", "0", "1e308", "-1e308", "1e-320"])
        return kind, replace_span(text, m.start("val"), m.end("val"), new)
    if kind == "region":
        cands = [m for m in ps if m.group("key") in REGION_KEYS or m.group("key") == "material"]
        if not cands:
            return mutate_yaml(rng, text, skip_line)
        m = rng.choice(cands)
        names = sorted({p.group("val").strip() for p in cands} - {m.group("val").strip()})
        new = rng.choice(["nowhere", "", "'1'", m.group("val").strip() + "x"] + names)
        return kind, replace_span(text, m.start("val"), m.end("val"), new)
    if kind == "empty_list":
        cands = [m for m in ps if m.group("val").startswith("[")]
        if not cands:
            return mutate_yaml(rng, text, skip_line)
        m = rng.choice(cands)
        return kind, replace_span(text, m.start("val"), m.end("val"), rng.choice(["[]", "[[]]"]))
    if kind == "vector_length":
        cands = [m for m in ps if m.group("val").startswith("[") and "," in m.group("val")]
        if not cands:
            return mutate_yaml(rng, text, skip_line)
        m = rng.choice(cands)
        items = [s.strip() for s in m.group("val")[1:-1].split(",")]
        if rng.random() < 0.5:
            items = items[:-1]
        else:
            items = items + [rng.choice(["0", "1", '"t"'])]
        return kind, replace_span(text, m.start("val"), m.end("val"), "[" + ", ".join(items) + "]")
    if kind == "expression":
        quoted = [m for m in re.finditer(r'"[^"\n]*"', text)
                  if not text[text.rfind("\n", 0, m.start()) + 1:m.start()].lstrip().startswith("#")
                  and not (skip_line and text[text.rfind("\n", 0, m.start()) + 1:].startswith(skip_line))]
        if not quoted:
            return mutate_yaml(rng, text, skip_line)
        m = rng.choice(quoted)
        return kind, replace_span(text, m.start(), m.end(), '"%s"' % rng.choice(EXPRESSIONS))
    lines = text.splitlines(keepends=True)
    body = [i for i, l in enumerate(lines) if l.strip() and not l.lstrip().startswith("#")
            and not (skip_line and l.startswith(skip_line))]
    i = rng.choice(body)
    if kind == "syntax":
        l = lines[i]
        op = rng.randrange(6)
        if op == 0:
            lines[i] = "\t" + l
        elif op == 1 and ("}" in l or "]" in l):
            c = rng.choice([k for k, ch in enumerate(l) if ch in "}]"])
            lines[i] = l[:c] + l[c + 1:]
        elif op == 2:
            lines[i] = l.replace(":", ": :", 1)
        elif op == 3:
            lines[i] = "   " + l
        elif op == 4:
            lines.insert(i, "- stray item\n")
        else:
            lines[i] = l.rstrip("\n")[: max(1, len(l) // 2)] + "\n"
        return kind, "".join(lines)
    if kind == "duplicate_line":
        lines.insert(i, lines[i])
        return kind, "".join(lines)
    if kind == "drop_line":
        del lines[i]
        return kind, "".join(lines)
    if kind == "empty_section":
        tops = [k for k in body if re.match(r"^[a-z_]+:\s*$", lines[k])]
        if not tops:
            return mutate_yaml(rng, text, skip_line)
        k = rng.choice(tops)
        end = k + 1
        while end < len(lines) and (lines[end].startswith(" ") or not lines[end].strip()):
            end += 1
        key = lines[k].split(":")[0]
        return kind, "".join(lines[:k] + ["%s: %s\n" % (key, rng.choice(["[]", "{}", "", "0"]))]
                             + lines[end:])
    # swap_values
    if len(ps) < 2:
        return mutate_yaml(rng, text, skip_line)
    a, b = sorted(rng.sample(ps, 2), key=lambda m: m.start())
    va, vb = a.group("val"), b.group("val")
    text = replace_span(text, b.start("val"), b.end("val"), va)
    return kind, replace_span(text, a.start("val"), a.end("val"), vb)


# --- mesh mutations -----------------------------------------------------------------------


def mutate_msh(rng, text):
    """One corruption of a .msh text; returns (kind, new text)."""
    lines = text.splitlines(keepends=True)
    kind = rng.choice(["truncate", "truncate", "corrupt_number", "corrupt_number", "count",
                       "element_type", "node_index", "coordinate", "marker", "physical_names",
                       "drop_lines", "garbage", "empty", "duplicate_section"])
    sections = {}
    for i, l in enumerate(lines):
        if l.startswith("$") and not l.startswith("$End"):
            sections.setdefault(l.strip()[1:], i)
    def section_lines(name):
        s = sections.get(name)
        if s is None:
            return []
        end = s + 1
        while end < len(lines) and not lines[end].startswith("$End"):
            end += 1
        return list(range(s + 1, end))
    if kind == "truncate":
        cut = rng.randrange(len(text))
        return kind, text[:cut]
    if kind == "empty":
        return kind, rng.choice(["", "\n", "$MeshFormat\n", "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n"])
    if kind == "garbage":
        i = rng.randrange(len(lines))
        junk = "".join(rng.choice("0123456789 .-eE$\x00\xff\t,abc") for _ in range(rng.randrange(1, 40)))
        lines[i] = junk + "\n"
        return kind, "".join(lines)
    if kind == "marker":
        marks = [i for i, l in enumerate(lines) if l.startswith("$")]
        i = rng.choice(marks)
        lines[i] = rng.choice(["", "$Nodes\n", "$EndElements\n", "$Foo\n", lines[i].lower()])
        return kind, "".join(lines)
    if kind == "physical_names":
        idx = section_lines("PhysicalNames")
        if not idx:
            return mutate_msh(rng, text)
        i = rng.choice(idx)
        lines[i] = rng.choice(['1 1 "unclosed\n', "3 1 \"x\"\n", "9 9\n", "1 1 \"\"\n", "-1\n",
                               "2147483647\n", lines[i].replace('"', "")])
        return kind, "".join(lines)
    if kind == "drop_lines":
        i = rng.randrange(len(lines))
        del lines[i:i + rng.randrange(1, 6)]
        return kind, "".join(lines)
    if kind == "duplicate_section":
        name = rng.choice([n for n in ("Nodes", "Elements") if n in sections] or ["MeshFormat"])
        idx = section_lines(name)
        if not idx:
            return mutate_msh(rng, text)
        block = lines[idx[0] - 1: idx[-1] + 2]
        at = idx[-1] + 2
        return kind, "".join(lines[:at] + block + lines[at:])
    if kind == "count":
        name = rng.choice(["Nodes", "Elements", "PhysicalNames", "Entities"])
        idx = section_lines(name)
        if not idx:
            return mutate_msh(rng, text)
        fields = lines[idx[0]].split()
        k = rng.randrange(len(fields))
        fields[k] = rng.choice(["0", "-1", "1", "2147483648", "99999999999", str(int(float(fields[k])) + 1)
                                if NUMBER.match(fields[k]) else "1", "x"])
        lines[idx[0]] = " ".join(fields) + "\n"
        return kind, "".join(lines)
    # Per-record corruptions inside $Nodes / $Elements.
    name = "Elements" if kind in ("element_type", "node_index") else rng.choice(["Nodes", "Elements"])
    idx = section_lines(name)[1:]
    if not idx:
        return mutate_msh(rng, text)
    i = rng.choice(idx)
    fields = lines[i].split()
    if not fields:
        return mutate_msh(rng, text)
    if kind == "element_type" and len(fields) > 1:
        fields[1] = rng.choice(["6", "15", "99", "0", "-2", "7", "4", "5", "1"])
    elif kind == "node_index":
        k = rng.randrange(len(fields))
        fields[k] = rng.choice(["0", "-1", "999999", "4294967297", "1"])
    elif kind == "coordinate":
        k = rng.randrange(len(fields))
        fields[k] = rng.choice(["nan", "inf", "1e400", "-1e308", "0", "1e-320"])
    else:
        k = rng.randrange(len(fields))
        fields[k] = rng.choice(["x", "-1", "1.5", "", "0", "1e999", "999999"])
    lines[i] = " ".join(fields) + "\n"
    return kind, "".join(lines)


def mutate_geo(rng, text):
    lines = text.splitlines(keepends=True)
    kind = rng.choice(["truncate", "physical_name", "drop_line", "size"])
    if kind == "truncate":
        return "geo_" + kind, text[:rng.randrange(len(text))]
    if kind == "physical_name":
        names = re.findall(r'Physical \w+\("(\w+)"\)', text)
        if names:
            n = rng.choice(names)
            return "geo_" + kind, text.replace('"%s"' % n, '"%s_renamed"' % n, 1)
    if kind == "size":
        return "geo_" + kind, re.sub(r"=\s*[\d.]+;", "= 0;", text, count=1)
    del lines[rng.randrange(len(lines))]
    return "geo_drop_line", "".join(lines)


# --- cases ------------------------------------------------------------------------------


class Case:
    def __init__(self, number, example, kind, command, files, np=1):
        self.number, self.example, self.kind, self.command = number, example, kind, command
        self.files, self.np = files, np  # files: {name: text} written over the example's copy

    def label(self):
        return "case %d (%s, %s, seam %s, np=%d)" % (self.number, self.example.folder, self.kind,
                                                    self.command, self.np)


def generate(rng, examples, n_cases):
    cases = []
    for number in range(n_cases):
        ex = rng.choice(examples)
        roll = rng.random()
        msh = ex.msh if rng.random() < 0.6 else ex.msh.replace(".msh", "_41.msh")
        base = ex.with_mesh_file(msh)
        run = ex.runnable and rng.random() < 0.6
        np = 2 if run and rng.random() < 0.15 else 1
        if run:
            base = ex.for_run(base)
        files = {}
        if roll < 0.62:
            n = 1 if rng.random() < 0.8 else rng.randint(2, 3)
            text, kinds = base, []
            for _ in range(n):
                k, text = mutate_yaml(rng, text, skip_line="time:" if run else None)
                kinds.append(k)
            kind = "+".join(kinds)
            files["case.yaml"] = text
        elif roll < 0.95:
            files["case.yaml"] = base
            files["mesh"] = msh  # the mesh text is mutated when the case runs (it is large)
            kind = "msh"
        else:
            files["case.yaml"] = ex.for_run(ex.text) if run else ex.text
            files["geo"] = ex.geo
            kind = "geo"
        cases.append(Case(number, ex, kind, "run" if run else "check", files, np))
    return cases


def prepare(case, work, rng):
    """Writes the case's folder: a copy of the meshed example with the mutated files."""
    src = os.path.join(work, case.example.folder)
    dest = os.path.join(work, "case_%04d" % case.number)
    os.makedirs(dest)
    for name in os.listdir(src):
        if name.endswith((".geo", ".msh")):
            os.symlink(os.path.join(src, name), os.path.join(dest, name))
    for name, value in case.files.items():
        if name == "mesh":
            with open(os.path.join(src, value), encoding="latin-1") as f:
                kind, text = mutate_msh(rng, f.read())
            case.kind = "msh_" + kind
            os.unlink(os.path.join(dest, value))
            with open(os.path.join(dest, value), "w", encoding="latin-1") as f:
                f.write(text)
        elif name == "geo":
            with open(os.path.join(src, value)) as f:
                case.kind, text = mutate_geo(rng, f.read())
            os.unlink(os.path.join(dest, value))
            H.write_case(dest, value, text)
        else:
            H.write_case(dest, name, value)
    return dest


def verdict(case, code, out, err):
    """None if the case ended as it must, else what went wrong."""
    both = out + err
    for word in FORBIDDEN:
        if word in both:
            return "output contains %r" % word
    if code == 0:
        return None
    if code == 2 and case.command == "run" and "seam: solver failed: " in err:
        return None  # valid input the solver cannot handle (young: 1e308): CONTRACT.md's exit 2
    if code != 1:
        return "exit code %d" % code
    if err.count(PREFIX) != 1:
        return "expected one %r message, got %d" % (PREFIX, err.count(PREFIX))
    message = err[err.index(PREFIX) + len(PREFIX):]
    if not LOCATED.match(message):
        return "message does not start with a located file name: %r" % message[:200]
    return None


def descendants(pid):
    """pid and the processes it started (mpirun, orted, the ranks), from /proc."""
    out, todo = [], [pid]
    while todo:
        p = todo.pop()
        out.append(p)
        try:
            for task in os.listdir("/proc/%d/task" % p):
                with open("/proc/%d/task/%s/children" % (p, task)) as f:
                    todo += [int(c) for c in f.read().split()]
        except OSError:
            pass  # it ended meanwhile
    return out


TICK = os.sysconf("SC_CLK_TCK")


def own_time(pid):
    """(command name, seconds since the process started less the seconds it waited for a CPU:
    what it ran plus what it slept), or None once it has ended."""
    try:
        with open("/proc/%d/stat" % pid) as f:
            stat = f.read()
        with open("/proc/uptime") as f:
            now = float(f.read().split()[0])
    except (OSError, ValueError, IndexError):
        return None
    try:
        with open("/proc/%d/schedstat" % pid) as f:
            wait_ns = int(f.read().split()[1])
    except (OSError, ValueError, IndexError):
        wait_ns = 0  # a kernel without schedstat: wall time, as before
    name = stat[stat.index("(") + 1:stat.rindex(")")]
    started = int(stat[stat.rindex(")") + 2:].split()[19]) / TICK
    return name, now - started - wait_ns * 1e-9


def case_time(pid):
    """A case's own time: the largest of its seam processes' (the ranks), or of the whole tree
    while mpirun has not started them yet."""
    times = [t for t in map(own_time, descendants(pid)) if t is not None]
    seam = [t for name, t in times if name == os.path.basename(H.SEAM)[:15]]
    return max(seam or [t for _, t in times] or [0.0])


def run_watched(cmd, cwd, env, limit=None, used=None):
    """Runs cmd; returns (exit code, stdout bytes, stderr bytes, None) or, when the case has
    used `limit` seconds of its own time (case_time) or WALL_LIMIT of wall time, kills its
    process group and returns (None, stdout, stderr, what was exceeded). `used`, a list,
    receives the own time last seen (sampled every 0.25 s)."""
    limit = TIMEOUT if limit is None else limit
    start = time.monotonic()
    with tempfile.TemporaryFile() as out, tempfile.TemporaryFile() as err:
        p = subprocess.Popen(cmd, cwd=cwd, env=env, stdout=out, stderr=err,
                             start_new_session=True)
        why = None
        while True:
            try:
                p.wait(timeout=0.25)
                break
            except subprocess.TimeoutExpired:
                pass
            own, wall = case_time(p.pid), time.monotonic() - start
            if used is not None:
                used[:] = [own]
            if own > limit or wall > WALL_LIMIT:
                why = "%.1f s of its own time, %.1f s of wall time" % (own, wall)
                tree = descendants(p.pid)
                os.killpg(p.pid, 9)
                for q in tree:  # a rank that left the process group
                    try:
                        os.kill(q, 9)
                    except OSError:
                        pass
                p.wait()
                break
        out.seek(0)
        err.seek(0)
        return (None if why else p.returncode), out.read(), err.read(), why


def execute(case, dest):
    args = [case.command, "case.yaml"]
    if case.command == "run":
        args += ["-o", "out", "--quiet"]
    cmd = [H.SEAM] + args
    if case.np > 1:
        cmd = [H.MPIEXEC, "--oversubscribe", "-np", str(case.np)] + cmd
    start = time.time()
    # A corrupted mesh may hold any bytes, and a message may quote them.
    own = [0.0]
    code, out, err, hang = run_watched(cmd, dest, H.mpi_env(), used=own)
    if hang:
        return case, "hang (stopped after %s)" % hang, -999, "", time.time() - start, own[0]
    out = out.decode("utf-8", "replace")
    err = err.decode("utf-8", "replace")
    return case, verdict(case, code, out, err), code, err, time.time() - start, own[0]


def test_fuzz():
    rng = random.Random(SEED)
    examples = [Example(*e) for e in EXAMPLES]
    work = tempfile.mkdtemp(prefix="seam_fuzz_")
    try:
        start = time.time()
        mesh_examples(work, examples)
        cases = generate(rng, examples, N_CASES)
        folders = [prepare(c, work, rng) for c in cases]
        print("   %d cases (seed %d), meshes ready in %.1f s" % (len(cases), SEED, time.time() - start))
        results = []
        workers = max(1, min(4, os.cpu_count() or 1))
        with concurrent.futures.ThreadPoolExecutor(max_workers=workers) as pool:
            for r in pool.map(lambda cd: execute(*cd), zip(cases, folders)):
                results.append(r)
        failures = [r for r in results if r[1] is not None]
        tally = {}
        for case, _, code, _, _, _ in results:
            key = case.kind.split("+")[0].split("_")[0] + " " + case.command
            tally.setdefault(key, [0, 0, 0])
            tally[key][0 if code == 0 else 1 if code == 1 else 2] += 1
        print("   outcomes (exit 0 / exit 1 / other) by mutation and command:")
        for key in sorted(tally):
            print("     %-22s %4d %4d %4d" % ((key,) + tuple(tally[key])))
        slowest = max(results, key=lambda r: r[4])
        busiest = max(results, key=lambda r: r[5])
        print("   %d cases in %.1f s (slowest %.1f s of wall time: %s; largest own time seen "
              "%.1f s of the %.0f s allowed: %s)"
              % (len(results), time.time() - start, slowest[4], slowest[0].label(), busiest[5],
                 TIMEOUT, busiest[0].label()))
        keep = os.environ.get("SEAM_FUZZ_KEEP")
        for case, why, code, err, _, _ in failures[:20]:
            print("   FAILED %s: %s\n     %s" % (case.label(), why, err.strip()[-600:].replace("\n", "\n     ")))
        if keep:
            for case, _, _, _, _, _ in failures:
                shutil.copytree(os.path.join(work, "case_%04d" % case.number),
                                os.path.join(keep, "case_%04d" % case.number), symlinks=False)
        if failures:
            raise AssertionError("%d of %d fuzzed cases failed" % (len(failures), len(results)))
        n_run = sum(1 for c in cases if c.command == "run")
        if len(cases) >= 300 and (n_run < 30 or sum(1 for r in results if r[2] == 1) < 150):
            raise AssertionError("the generator lost its bite: %d run cases, %d input errors"
                                 % (n_run, sum(1 for r in results if r[2] == 1)))
    finally:
        H.cleanup(work)


def test_hangs_are_caught_under_load():
    """The fuzzer's watchdog (run_watched) with a 3 s limit: a fake seam that sleeps and one
    that loops are stopped after 3 s of their own time (the one that sleeps after at most 13 s
    of wall time); a fake seam that needs 2 s of CPU while three busy processes per core (at
    most 8) share the machine with it finishes although its wall time may exceed the limit (it
    was waiting for a CPU, which is not its own time: 4.1 s and 7.1 s of wall time were seen)."""
    work = tempfile.mkdtemp(prefix="seam_fuzz_hang_")
    burners = []
    try:
        fake = os.path.join(work, os.path.basename(H.SEAM) or "seam")
        scripts = {
            "sleeps": "sleep 600",
            "loops": "while :; do :; done",
            "computes": "exec %s -c 'import time\nwhile time.process_time() < 2: pass'"
                        % sys.executable,
        }
        results = {}
        for what, body in scripts.items():
            with open(fake, "w") as f:
                f.write("#!/bin/sh\n%s\n" % body)
            os.chmod(fake, 0o755)
            if what == "computes":
                burners = [subprocess.Popen([sys.executable, "-c", "while True: pass"])
                           for _ in range(min(8, 3 * (os.cpu_count() or 1)))]
            start = time.monotonic()
            code, _, _, why = run_watched([fake], work, os.environ, limit=3.0)
            results[what] = (code, why, time.monotonic() - start)
            print("   a seam that %s: %s after %.1f s of wall time"
                  % (what, ("stopped (%s)" % why) if why else "exit %s" % code,
                     results[what][2]))
        for what in ("sleeps", "loops"):
            code, why, wall = results[what]
            if why is None:
                raise AssertionError("a seam that %s was not stopped (exit %s)" % (what, code))
        # Sleeping is its own time whatever the load (a loop's wall time grows with the load).
        if results["sleeps"][2] > 3.0 + 10.0:
            raise AssertionError("a seam that sleeps was stopped after %.1f s"
                                 % results["sleeps"][2])
        code, why, wall = results["computes"]
        if why is not None or code != 0:
            raise AssertionError("a seam that computes 2 s on a loaded machine was stopped "
                                 "(%s, exit %s, %.1f s)" % (why, code, wall))
    finally:
        for b in burners:
            b.kill()
            b.wait()
        H.cleanup(work)


if __name__ == "__main__":
    H.main([test_hangs_are_caught_under_load, test_fuzz])
