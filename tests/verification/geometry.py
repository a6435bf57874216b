"""Gmsh geometry files for verification cases, with known physical-group names.

2D: the rectangle [0, lx] x [0, ly] with curves left (x = 0), right (x = lx), bottom (y = 0),
top (y = ly) and the surface `body`. 3D: the box [0, lx] x [0, ly] x [0, lz] with faces left,
right, front (y = 0), back, bottom (z = 0), top and the volume `body`.

`kind` chooses the cells: "tri", "quad" (unstructured, recombined and subdivided: distorted
quadrilaterals), "tet", "hex" (tetrahedra subdivided into distorted hexahedra), "hex_structured".
`order` 1 or 2; `serendipity` gives quad8/hex20 instead of quad9/hex27.
"""


def rectangle(kind, h, order=1, serendipity=False, lx=2.0, ly=1.0):
    lines = [
        "// rectangle [0,%g] x [0,%g], %s cells" % (lx, ly, kind),
        "h = %g;" % h,
        "Point(1) = {0, 0, 0, h};",
        "Point(2) = {%g, 0, 0, h};" % lx,
        "Point(3) = {%g, %g, 0, h};" % (lx, ly),
        "Point(4) = {0, %g, 0, h};" % ly,
        "Line(1) = {1, 2};",
        "Line(2) = {2, 3};",
        "Line(3) = {3, 4};",
        "Line(4) = {4, 1};",
        "Curve Loop(1) = {1, 2, 3, 4};",
        "Plane Surface(1) = {1};",
    ]
    if kind == "quad":
        lines += ["Recombine Surface{1};", "Mesh.SubdivisionAlgorithm = 1;",
                  "Mesh.RecombinationAlgorithm = 0;"]
    elif kind == "quad_structured":
        n = max(1, round(lx / h))
        m = max(1, round(ly / h))
        lines += ["Transfinite Curve{1, 3} = %d;" % (n + 1), "Transfinite Curve{2, 4} = %d;" % (m + 1),
                  "Transfinite Surface{1};", "Recombine Surface{1};"]
    lines += [
        'Physical Curve("bottom") = {1};',
        'Physical Curve("right") = {2};',
        'Physical Curve("top") = {3};',
        'Physical Curve("left") = {4};',
        'Physical Surface("body") = {1};',
        "Mesh.ElementOrder = %d;" % order,
        "Mesh.SecondOrderIncomplete = %d;" % (1 if serendipity else 0),
    ]
    return "\n".join(lines) + "\n"


def box(kind, h, order=1, serendipity=False, lx=2.0, ly=1.0, lz=1.0):
    lines = [
        "// box [0,%g] x [0,%g] x [0,%g], %s cells" % (lx, ly, lz, kind),
        'SetFactory("OpenCASCADE");',
        "Box(1) = {0, 0, 0, %g, %g, %g};" % (lx, ly, lz),
        "Mesh.MeshSizeMax = %g;" % h,
        "Mesh.MeshSizeMin = %g;" % (0.5 * h),
    ]
    if kind == "hex":
        lines += ["Mesh.SubdivisionAlgorithm = 2;"]
    elif kind == "hex_structured":
        n = [max(1, round(v / h)) for v in (lx, ly, lz)]
        lines += [
            "For c In {1:12}",
            "  bb() = BoundingBox Curve{c};",
            "  If (Fabs(bb(3) - bb(0)) > 1e-5)",
            "    Transfinite Curve{c} = %d;" % (n[0] + 1),
            "  ElseIf (Fabs(bb(4) - bb(1)) > 1e-5)",
            "    Transfinite Curve{c} = %d;" % (n[1] + 1),
            "  Else",
            "    Transfinite Curve{c} = %d;" % (n[2] + 1),
            "  EndIf",
            "EndFor",
            "Transfinite Surface{:};",
            "Recombine Surface{:};",
            "Transfinite Volume{1};",
        ]
    lines += [
        'Physical Surface("left") = {1};',
        'Physical Surface("right") = {2};',
        'Physical Surface("front") = {3};',
        'Physical Surface("back") = {4};',
        'Physical Surface("bottom") = {5};',
        'Physical Surface("top") = {6};',
        'Physical Volume("body") = {1};',
        "Mesh.ElementOrder = %d;" % order,
        "Mesh.SecondOrderIncomplete = %d;" % (1 if serendipity else 0),
    ]
    return "\n".join(lines) + "\n"
