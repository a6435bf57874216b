"""Exact finite-strain solutions and Newton's convergence rate (issue: foundation).

Uniaxial stretch lambda of a bar [0,2] x [0,1] (x [0,1]) on symmetry supports, right face
displaced by (lambda - 1) * 2, with Poisson's ratio 0 (so the Lame lambda vanishes and the
lateral stretch is exactly 1):

    neo_hooke:               P11 = mu (lambda - 1/lambda)
    saint_venant_kirchhoff:  P11 = mu lambda (lambda^2 - 1)

The reaction on the left face is -P11 * area, the displacement ux = (lambda - 1) x; both to
1e-10. Then Newton's method on a compressed Neo-Hookean block must converge quadratically:
the observed order log(r_{k+1}/r_k) / log(r_k/r_{k-1}) is near 2 in the asymptotic range.
"""
import math
import os
import sys
import tempfile

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import geometry  # noqa: E402
import harness as H  # noqa: E402

E = 10.0
MU = E / 2.0
STRETCH = 1.6


def stretch_yaml(dim, model, geo, order, steps=8):
    if dim == 2:
        bcs = ["  - {region: left, type: dirichlet, components: [x], value: [0]}",
               "  - {region: bottom, type: dirichlet, components: [y], value: [0]}",
               "  - {region: right, type: dirichlet, components: [x], value: ['%.17g*t']}"
               % ((STRETCH - 1) * 2)]
        probes = [[0.7, 0.3], [1.5, 0.8]]
    else:
        bcs = ["  - {region: left, type: dirichlet, components: [x], value: [0]}",
               "  - {region: front, type: dirichlet, components: [y], value: [0]}",
               "  - {region: bottom, type: dirichlet, components: [z], value: [0]}",
               "  - {region: right, type: dirichlet, components: [x], value: ['%.17g*t']}"
               % ((STRETCH - 1) * 2)]
        probes = [[0.7, 0.3, 0.6], [1.5, 0.8, 0.1]]
    return "\n".join([
        "dimension: %d" % dim,
        "mesh: {geo: %s, order: %d}" % (geo, order),
        "materials:",
        "  m: {model: %s, young: %g, poisson: 0.0}" % (model, E),
        "bodies: [{region: body, material: m}]",
        "boundary_conditions:",
    ] + bcs + [
        "time: {integrator: static, end: 1, steps: %d}" % steps,
        "solver: {newton: {tolerance: 1.0e-12, max_iterations: 20}}",
        "output: {every: 100, probes: %s}" % probes,
    ]) + "\n"


def p11(model):
    lam = STRETCH
    if model == "neo_hooke":
        return MU * (lam - 1.0 / lam)
    return MU * lam * (lam * lam - 1.0)


def check_stretch(dim, kind, model, order=1, np=1):
    work = tempfile.mkdtemp(prefix="seam_fs_")
    geo = geometry.rectangle(kind, 0.4, order) if dim == 2 else geometry.box(kind, 0.6, order)
    H.write_case(work, "body.geo", geo)
    yaml = H.write_case(work, "case.yaml", stretch_yaml(dim, model, "body.geo", order))
    out = H.solve(yaml, np=np)
    reactions = H.last_step_rows(H.read_csv(os.path.join(out, "reactions.csv")))
    left = [r for r in reactions if r["region"] == "left"][0]
    H.assert_close(left["fx"], -p11(model) * 1.0, rtol=1e-10, what="%s %s reaction" % (model, kind))
    for p in H.last_step_rows(H.read_csv(os.path.join(out, "probes.csv"))):
        H.assert_close(p["ux"], (STRETCH - 1) * p["x"], atol=1e-10, what="ux")
        H.assert_close(p["uy"], 0.0, atol=1e-10, what="uy")
    steps = H.read_csv(os.path.join(out, "steps.csv"))
    # Strain energy of the homogeneous state: W(F) * volume, volume 2 (2D: area 2, thickness 1).
    lam = STRETCH
    if model == "neo_hooke":
        w = MU / 2 * (lam * lam - 1) - MU * math.log(lam)
    else:
        e11 = (lam * lam - 1) / 2
        w = MU * e11 * e11
    H.assert_close(steps[-1]["internal_energy"], 2.0 * w, rtol=1e-9, what="strain energy")
    H.cleanup(out, work)


def test_neo_hooke_hex8(): check_stretch(3, "hex", "neo_hooke")
def test_neo_hooke_tet10(): check_stretch(3, "tet", "neo_hooke", order=2)
def test_neo_hooke_quad4_np3(): check_stretch(2, "quad", "neo_hooke", np=3)
def test_neo_hooke_tri6(): check_stretch(2, "tri", "neo_hooke", order=2)
def test_svk_hex8_np3(): check_stretch(3, "hex", "saint_venant_kirchhoff", np=3)
def test_svk_quad9(): check_stretch(2, "quad", "saint_venant_kirchhoff", order=2)


def test_newton_quadratic():
    """Newton's observed order of convergence on the compressed Neo-Hookean block."""
    work = tempfile.mkdtemp(prefix="seam_newton_")
    H.write_case(work, "body.geo", geometry.box("hex", 0.5, 1))
    yaml = H.write_case(work, "case.yaml", "\n".join([
        "dimension: 3",
        "mesh: {geo: body.geo, order: 1}",
        "materials: {rubber: {model: neo_hooke, young: 10, poisson: 0.3}}",
        "bodies: [{region: body, material: rubber}]",
        "boundary_conditions:",
        "  - {region: left, type: dirichlet, value: [0, 0, 0]}",
        "  - {region: right, type: dirichlet, components: [x, y], value: ['-0.6*t', '0.2*t']}",
        "time: {integrator: static, end: 1, steps: 2}",
        "solver: {newton: {tolerance: 1.0e-13, max_iterations: 30}}",
    ]) + "\n")
    out = H.solve(yaml)
    rows = H.read_csv(os.path.join(out, "newton.csv"))
    orders = []
    for step in sorted(set(r["step"] for r in rows)):
        # Iteration 0 is the predictor (it carries the prescribed boundary motion).
        res = [r["residual"] for r in rows if r["step"] == step and r["iteration"] >= 1]
        # Asymptotic range: residuals well above round-off and below the pre-asymptotic phase.
        for k in range(1, len(res) - 1):
            if res[k + 1] > 1e-11 * res[0] and res[k] < 1e-1 * res[0]:
                orders.append(math.log(res[k + 1] / res[k]) / math.log(res[k] / res[k - 1]))
        print("step %d residuals: %s" % (step, " ".join("%.2e" % r for r in res)))
    if not orders:
        raise AssertionError("no asymptotic Newton iterations to measure")
    best = max(orders)
    print("observed orders:", " ".join("%.2f" % o for o in orders))
    if best < 1.8:
        raise AssertionError("Newton is not quadratic: observed orders %s" % orders)
    H.cleanup(out, work)


if __name__ == "__main__":
    H.main([test_neo_hooke_hex8, test_neo_hooke_tet10, test_neo_hooke_quad4_np3,
            test_neo_hooke_tri6, test_svk_hex8_np3, test_svk_quad9, test_newton_quadratic])
