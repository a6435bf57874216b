#!/usr/bin/env python3
"""The chunked .msh reader (docs/parallel.md, "Reading the mesh"): a run from a .msh file is read
in chunks by every rank and partitioned in parallel (PT-Scotch), so no rank holds the whole mesh.

- The tied blocks (hexahedra below, tetrahedra above, dual mortar, condensed) from a binary
  MSH 4.1 file: reactions at np = 1 and np = 3 through the chunked reader equal each other and
  the rank-0 path (SEAM_MESH_READER=rank0, METIS partition) to 1e-10 relative, and the interface
  output names the same slave nodes (node ids as read) in the same order.
- Bad .msh files (truncated ASCII and binary, an unknown version) exit 1 with a message naming
  the file, at np = 3.
"""
import os
import subprocess
import tempfile

import harness as H


def make_msh(folder, binary, geo="blocks.geo"):
    msh = os.path.join(folder, "blocks.msh")
    cmd = ["gmsh", "-3", "-format", "msh41", os.path.join(folder, geo), "-o", msh]
    if binary:
        cmd.insert(1, "-bin")
    subprocess.run(cmd, check=True, capture_output=True)
    return msh


def located(err):
    return [line for line in err.splitlines() if "blocks.msh" in line][0][:200]


def reactions(out):
    rows = H.last_step_rows(H.read_csv(os.path.join(out, "reactions.csv")))
    return {r["region"]: [r[k] for k in r if k.startswith("f")] for r in rows}


def test_tied_blocks_from_msh_np1_np3():
    work, yaml = H.copy_example("tied_blocks", "blocks.yaml",
                                [("geo: blocks.geo", "file: blocks.msh"),
                                 ("steps: 5}", "steps: 2}")])
    make_msh(work, binary=True)
    outs = {}
    for label, np, env in [("chunked np1", 1, {}), ("chunked np3", 3, {}),
                           ("rank0 np3", 3, {"SEAM_MESH_READER": "rank0"})]:
        os.environ.pop("SEAM_MESH_READER", None)
        os.environ.update(env)
        out = tempfile.mkdtemp(prefix="seam_verif_")
        _, stdout, _ = H.run(["run", yaml, "-o", out], np=np)
        if not env and "read on rank 0" in stdout:
            raise AssertionError("%s: the chunked reader fell back to Gmsh:\n%s" % (label, stdout))
        outs[label] = out
    os.environ.pop("SEAM_MESH_READER", None)
    ref = reactions(outs["chunked np1"])
    worst = 0.0
    for label in ("chunked np3", "rank0 np3"):
        got = reactions(outs[label])
        scale = max(abs(v) for f in ref.values() for v in f)
        for region, f in ref.items():
            for a, b in zip(got[region], f):
                worst = max(worst, abs(a - b) / scale)
                H.assert_close(a, b, atol=1e-10 * scale, what="%s %s reaction" % (label, region))
        ids = [r["node"] for r in H.read_csv(os.path.join(outs[label], "interface_tie.csv"))]
        ref_ids = [r["node"] for r in H.read_csv(os.path.join(outs["chunked np1"],
                                                              "interface_tie.csv"))]
        if ids != ref_ids:
            raise AssertionError("%s: interface node ids differ" % label)
    print("   reactions np3 (chunked, rank 0) vs np1 chunked: max rel. diff %.2e" % worst)
    H.cleanup(work, *outs.values())


def test_bad_msh_files_name_the_file():
    work, yaml = H.copy_example("tied_blocks", "blocks.yaml", [("geo: blocks.geo",
                                                                "file: blocks.msh")])
    for binary in (False, True):
        msh = make_msh(work, binary)
        size = os.path.getsize(msh)
        with open(msh, "r+b") as f:
            f.truncate(size * 2 // 3)
        code, out, err = H.run(["run", yaml, "-o", os.path.join(work, "out")], np=3, check=False)
        if code != 1 or "blocks.msh" not in err:
            raise AssertionError("truncated %s: exit %d\n%s" % ("binary" if binary else "ascii",
                                                              code, err[-2000:]))
        print("   truncated %s: %s" % ("binary" if binary else "ASCII", located(err)))
    with open(os.path.join(work, "blocks.msh"), "w") as f:
        f.write("$MeshFormat\n9.9 0 8\n$EndMeshFormat\n")
    code, out, err = H.run(["run", yaml, "-o", os.path.join(work, "out")], np=3, check=False)
    if code != 1 or "blocks.msh" not in err:
        raise AssertionError("version 9.9: exit %d\n%s" % (code, err[-2000:]))
    print("   version 9.9: %s" % located(err))
    H.cleanup(work)


if __name__ == "__main__":
    H.main([test_tied_blocks_from_msh_np1_np3, test_bad_msh_files_name_the_file])
