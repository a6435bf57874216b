"""Patch tests of the bulk solid (issue: foundation).

A bar [0,2] x [0,1] (x [0,1]) on symmetry supports, pulled by a uniform dead traction T on its
right face. The exact solution is a homogeneous uniaxial stress state, which every element
must reproduce exactly, also on distorted (unstructured, subdivided) meshes:

    3D:           eps_xx = T/E,            eps_yy = eps_zz = -nu T/E
    plane strain: eps_xx = (1-nu^2) T/E,   eps_yy = -nu (1+nu) T/E
    plane stress: eps_xx = T/E,            eps_yy = -nu T/E

Checked: displacements at interior probes (relative 1e-10) and the reaction on the left
face, -T * area (relative 1e-10); at np = 1 and np = 3.
"""
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402

E, NU, T = 200.0, 0.3, 1.5
PROBES_2D = [[0.37, 0.61], [1.3, 0.2], [1.9, 0.95]]
PROBES_3D = [[0.37, 0.61, 0.4], [1.3, 0.2, 0.9], [1.9, 0.95, 0.05]]


def case_yaml(dim, geo, order, plane="strain"):
    probes = PROBES_3D if dim == 3 else PROBES_2D
    bcs = ["  - {region: left, type: dirichlet, components: [x], value: [0]}"]
    if dim == 2:
        bcs += ["  - {region: bottom, type: dirichlet, components: [y], value: [0]}",
                "  - {region: right, type: traction, value: [%g, 0]}" % T]
    else:
        bcs += ["  - {region: front, type: dirichlet, components: [y], value: [0]}",
                "  - {region: bottom, type: dirichlet, components: [z], value: [0]}",
                "  - {region: right, type: traction, value: [%g, 0, 0]}" % T]
    return "\n".join([
        "dimension: %d" % dim,
        ("plane: %s" % plane) if dim == 2 else "",
        "mesh: {geo: %s, order: %d}" % (geo, order),
        "materials:",
        "  steel: {model: linear_elastic, young: %g, poisson: %g}" % (E, NU),
        "bodies:",
        "  - {region: body, material: steel}",
        "boundary_conditions:",
    ] + bcs + [
        "time: {integrator: static, end: 1, steps: 1}",
        "output: {probes: %s}" % probes,
    ]) + "\n"


def exact_strains(dim, plane):
    if dim == 3 or plane == "stress":
        return T / E, -NU * T / E, -NU * T / E
    return (1 - NU ** 2) * T / E, -NU * (1 + NU) * T / E, 0.0


def check(dim, kind, order, serendipity=False, plane="strain", nps=(1, 3), h=None):
    work = tempfile.mkdtemp(prefix="seam_patch_")
    if dim == 2:
        geo = geometry.rectangle(kind, h or 0.35, order, serendipity)
    else:
        geo = geometry.box(kind, h or 0.6, order, serendipity)
    H.write_case(work, "body.geo", geo)
    yaml = H.write_case(work, "case.yaml", case_yaml(dim, "body.geo", order, plane))
    exx, eyy, ezz = exact_strains(dim, plane)
    scale = abs(exx) * 2.0
    for np in nps:
        out = H.solve(yaml, np=np)
        probes = H.last_step_rows(H.read_csv(os.path.join(out, "probes.csv")))
        for p in probes:
            for comp, eps, coord in (("ux", exx, "x"), ("uy", eyy, "y"), ("uz", ezz, "z")):
                if dim == 2 and comp == "uz":
                    continue
                H.assert_close(p[comp], eps * p[coord], atol=1e-10 * scale,
                               what="%s np=%d probe %d %s" % (kind, np, int(p["probe"]), comp))
        reactions = H.last_step_rows(H.read_csv(os.path.join(out, "reactions.csv")))
        left = [r for r in reactions if r["region"] == "left"][0]
        H.assert_close(left["fx"], -T * 1.0, rtol=1e-10, what="%s np=%d reaction left fx" % (kind, np))
        H.cleanup(out)
    H.cleanup(work)


def test_tri3(): check(2, "tri", 1)
def test_tri6(): check(2, "tri", 2)
def test_quad4(): check(2, "quad", 1)
def test_quad8(): check(2, "quad", 2, serendipity=True)
def test_quad9(): check(2, "quad", 2)
def test_quad4_plane_stress(): check(2, "quad", 1, plane="stress", nps=(1,))
def test_tet4(): check(3, "tet", 1)
def test_tet10(): check(3, "tet", 2, nps=(1,))
def test_hex8(): check(3, "hex", 1)
def test_hex20(): check(3, "hex_structured", 2, serendipity=True, nps=(1,), h=0.5)
def test_hex27(): check(3, "hex_structured", 2, nps=(1,), h=0.5)
def test_hex20_distorted(): check(3, "hex", 2, serendipity=True, nps=(1,), h=1.0)


if __name__ == "__main__":
    H.main([test_tri3, test_tri6, test_quad4, test_quad8, test_quad9, test_quad4_plane_stress,
            test_tet4, test_tet10, test_hex8, test_hex20, test_hex27, test_hex20_distorted])
