"""GetFEM's side of bench/peers/getfem: the 3D Hertz quarter sphere of examples/hertz_3d on a
rigid plane, with GetFEM's integral contact brick and MUMPS. Runs with /usr/bin/python3
(Debian's python3-getfem); prints one line of JSON for compare.py.

  /usr/bin/python3 hertz_getfem.py MESH.msh [--steps 1] [--r 10] [--contact-integration 2]

MESH: a Gmsh 2.2 mesh of sphere.geo (quadratic tetrahedra; physical surfaces surface, top,
symmetry_x, symmetry_y). The problem (as seam's examples/hertz_3d): R = 1, E = 1, nu = 0.3,
linear elasticity, u.n = 0 on the symmetry planes, u_z = -0.015 on the cut z = 1, frictionless
contact with the plane z = 0.

GetFEM's settings (its demo_static_contact.py, version 5, and its manual): P2 displacements on
the isoparametric P2 geometry, the contact pressure lambda_n a P2 field on the contact boundary,
the integral contact brick with the non-symmetric Alart-Curnier augmented Lagrangian (option 1)
and augmentation r = 10, Newton with the default line search, MUMPS for every linear system,
the degree-5 tetrahedron rule everywhere. On a coarse mesh of the same sphere (9,828 dofs) r = 1,
10, 100 and the demo's composite contact rule (IM_STRUCTURED_COMPOSITE(IM_TETRAHEDRON(5), 2))
gave the same load to 0.03 % and the same contact radius to 1 %; r = 10 with the plain rule
was among the fastest (8 Newton iterations; r = 1 with the composite rule took 14). The
boundary conditions on single components are normal Dirichlet conditions with P2 multipliers
on their faces (exact at the P2 nodes, as seam's nodal conditions). Only the spherical faces
below z = 0.25 are contact candidates (the contact radius is 0.127): GetFEM integrates its
contact terms on the whole region given, seam searches its candidates itself.
"""
import argparse
import json
import time

T0 = time.perf_counter()
import numpy as np  # noqa: E402
import getfem as gf  # noqa: E402

R, YOUNG, POISSON, PRESS = 1.0, 1.0, 0.3, 0.015


def physical_names(path):
    """{name: tag} of the $PhysicalNames block of a Gmsh 2.2 file."""
    names, lines = {}, open(path).read().split("$PhysicalNames")[1].split("$EndPhysicalNames")[0]
    for line in lines.strip().splitlines()[1:]:
        dim, tag, name = line.split(None, 2)
        names[name.strip().strip('"')] = int(tag)
    return names


def fit_semi_ellipse(s, p):
    """Least-squares fit of p^2 = A - B s^2; (p0, a) = (sqrt(A), sqrt(A / B)) (the fit of
    tests/verification/contact_analysis.py)."""
    x, y = np.asarray(s) ** 2, np.asarray(p) ** 2
    B, A = np.polyfit(x, y, 1)
    return np.sqrt(A), np.sqrt(A / -B)


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("mesh")
    ap.add_argument("--steps", type=int, default=1)
    ap.add_argument("--r", type=float, default=10.0, help="augmentation parameter")
    ap.add_argument("--contact-integration", type=int, default=1,
                    help="subdivisions of IM_STRUCTURED_COMPOSITE(IM_TETRAHEDRON(5), n) on the "
                    "contact faces (1: the plain degree-5 rule)")
    ap.add_argument("--tolerance", type=float, default=1e-10, help="relative residual")
    a = ap.parse_args()
    gf.util_trace_level(1)  # no per-assembly trace lines
    gf.util_warning_level(1)
    tags = physical_names(a.mesh)
    m = gf.Mesh("import", "gmsh", a.mesh)
    # GetFEM's gmsh import keeps the physical tags as region numbers.
    TOP, SX, SY, SURF, GC = tags["top"], tags["symmetry_x"], tags["symmetry_y"], tags["surface"], 100
    # Candidate faces: the spherical faces that lie below z = 0.25 R.
    m.set_region(GC, m.outer_faces_in_box([-2 * R, -2 * R, -R], [2 * R, 2 * R, 0.25 * R]))
    m.region_intersect(GC, SURF)
    mfu = gf.MeshFem(m, 3)
    mfu.set_classical_fem(2)
    mfs = gf.MeshFem(m, 1)
    mfs.set_classical_fem(2)
    mim = gf.MeshIm(m, gf.Integ("IM_TETRAHEDRON(5)"))
    rule = "IM_TETRAHEDRON(5)" if a.contact_integration <= 1 else \
        "IM_STRUCTURED_COMPOSITE(IM_TETRAHEDRON(5),%d)" % a.contact_integration
    mim_c = gf.MeshIm(m, gf.Integ(rule))
    md = gf.Model("real")
    md.add_fem_variable("u", mfu)
    lam = YOUNG * POISSON / ((1 + POISSON) * (1 - 2 * POISSON))
    mu = YOUNG / (2 * (1 + POISSON))
    md.add_initialized_data("lambda", [lam])
    md.add_initialized_data("mu", [mu])
    md.add_isotropic_linearized_elasticity_brick(mim, "u", "lambda", "mu")
    for name, region in (("sx", SX), ("sy", SY), ("top", TOP)):
        mf = gf.MeshFem("partial", mfs, mfs.basic_dof_on_region(region))
        if name == "top":
            md.add_initialized_data("press", [0.0])
            md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", mf, region, "press")
        else:
            md.add_normal_Dirichlet_condition_with_multipliers(mim, "u", mf, region)
    contact_dofs = mfs.basic_dof_on_region(GC)
    mfl = gf.MeshFem("partial", mfs, contact_dofs)
    md.add_fem_variable("lambda_n", mfl)
    md.add_initialized_data("r", [a.r])
    md.add_initialized_fem_data("obstacle", mfs, mfs.eval("z"))
    md.add_integral_contact_with_rigid_obstacle_brick(mim_c, "u", "lambda_n", "obstacle", "r",
                                                      GC, 1)
    t_setup = time.perf_counter() - T0
    iterations = []
    for k in range(1, a.steps + 1):
        # The cut's outward normal is +z: u.n = u_z = -PRESS t.
        md.set_variable("press", [-PRESS * k / a.steps])
        # GetFEM's criterion is the residual norm itself: relative to the first residual of the
        # step (that of the Dirichlet increment), as seam's.
        md.assembly("build_rhs")
        r0 = np.linalg.norm(md.rhs())
        nbit, converged = md.solve("max_res", a.tolerance * r0, "max_iter", 50, "lsolver",
                                   "mumps", "lsearch", "default")
        if not converged:
            raise SystemExit("GetFEM: step %d did not converge" % k)
        iterations.append(int(nbit))
    t_solve = time.perf_counter() - T0 - t_setup
    ln = md.variable("lambda_n")
    # Contact force: the integral of the contact pressure (lambda_n <= 0), four quarters.
    force = -4.0 * gf.asm_generic(mim_c, 0, "lambda_n", GC, md)
    pts = mfs.basic_dof_nodes(contact_dofs)
    s, p = np.hypot(pts[0], pts[1]), -ln
    keep = p >= 0.2 * p.max()
    p0, radius = fit_semi_ellipse(s[keep], p[keep])
    print(json.dumps({"code": "getfem", "dofs": int(mfu.nbdof()), "unknowns": int(md.nbdof()),
                      "newton": iterations, "force": float(force), "radius": float(radius),
                      "p0": float(p0), "active": int((p > 0).sum()), "setup": t_setup,
                      "solve": t_solve, "total": time.perf_counter() - T0}))


if __name__ == "__main__":
    main()
