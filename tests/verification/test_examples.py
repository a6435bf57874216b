"""Every input under examples/ passes `seam check`: it parses, its mesh is read or generated,
its regions, materials, interfaces and keys are those seam knows (exit code 0 and the line
"INPUT: ok"). An example that an edit of the input language or of a .geo breaks fails here,
before a user finds it. About 20 s (gmsh meshes the .geo files)."""
import glob
import os

import harness as H

EXAMPLES = os.path.normpath(os.path.join(H.HERE, "..", "..", "examples"))


def test_examples_check():
    inputs = sorted(glob.glob(os.path.join(EXAMPLES, "*", "*.yaml")))
    assert len(inputs) >= 30, "only %d example inputs found under %s" % (len(inputs), EXAMPLES)
    failures = []
    for path in inputs:
        code, out, err = H.run(["check", path], check=False, timeout=600)
        if code != 0 or "%s: ok" % path not in out:
            failures.append("%s: exit %d\n%s" % (os.path.relpath(path, EXAMPLES), code,
                                                 (out + err).strip()[-600:]))
    print("   %d example inputs checked" % len(inputs))
    assert not failures, "\n".join(failures)


if __name__ == "__main__":
    H.main([test_examples_check])
