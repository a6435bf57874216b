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


def tied_rectangles(h_lower, h_upper, order=1, kind="tri"):
    """Two unit squares stacked in y, meshed independently (non-matching at y = 1).
    Regions: lower, upper (surfaces); bottom (y = 0), top (y = 2), left (x = 0, both),
    right (x = 1, both), lower_top, upper_bottom (the two sides of the interface)."""
    lines = ["Geometry.AutoCoherence = 0;",
             "Point(1) = {0, 0, 0, %g}; Point(2) = {1, 0, 0, %g};" % (h_lower, h_lower),
             "Point(3) = {1, 1, 0, %g}; Point(4) = {0, 1, 0, %g};" % (h_lower, h_lower),
             "Point(5) = {0, 1, 0, %g}; Point(6) = {1, 1, 0, %g};" % (h_upper, h_upper),
             "Point(7) = {1, 2, 0, %g}; Point(8) = {0, 2, 0, %g};" % (h_upper, h_upper),
             "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};",
             "Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};",
             "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};",
             "Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};"]
    if kind == "quad":
        lines += ["Recombine Surface{1, 2};"]
    lines += ['Physical Surface("lower") = {1};', 'Physical Surface("upper") = {2};',
              'Physical Curve("bottom") = {1};', 'Physical Curve("top") = {7};',
              'Physical Curve("left") = {4, 8};', 'Physical Curve("right") = {2, 6};',
              'Physical Curve("lower_top") = {3};', 'Physical Curve("upper_bottom") = {5};',
              "Mesh.ElementOrder = %d;" % order]
    return "\n".join(lines) + "\n"


def tied_boxes(h_lower, h_upper, order=1, kind="tet", serendipity=False):
    """Two unit cubes stacked in z, meshed independently (non-matching at z = 1); kind "tet",
    "hex" (structured) or "hex_split" (tetrahedra split into hexahedra).
    Regions: lower, upper; bottom (z = 0), top (z = 2), left (x = 0), right (x = 1),
    front (y = 0), back (y = 1) over both cubes; lower_top, upper_bottom."""
    lines = ['SetFactory("OpenCASCADE");',
             "Box(1) = {0, 0, 0, 1, 1, 1};",
             "Box(2) = {0, 0, 1, 1, 1, 1};"]
    if kind == "hex":
        # OpenCASCADE numbers the 12 edges of box 1 as curves 1-12, those of box 2 as 13-24.
        for first, h in ((1, h_lower), (13, h_upper)):
            n = max(1, round(1.0 / h))
            lines += ["Transfinite Curve{%d:%d} = %d;" % (first, first + 11, n + 1)]
        lines += ["Transfinite Surface{:};", "Recombine Surface{:};", "Transfinite Volume{1, 2};"]
    else:
        lines += ["MeshSize{PointsOf{Volume{1};}} = %g;" % h_lower,
                  "MeshSize{PointsOf{Volume{2};}} = %g;" % h_upper]
        if kind == "hex_split":  # tetrahedra split into hexahedra: non-parallelogram faces
            lines += ["Mesh.SubdivisionAlgorithm = 2;"]
    lines += ['Physical Volume("lower") = {1};', 'Physical Volume("upper") = {2};',
              'Physical Surface("bottom") = {5};', 'Physical Surface("top") = {12};',
              'Physical Surface("left") = {1, 7};', 'Physical Surface("right") = {2, 8};',
              'Physical Surface("front") = {3, 9};', 'Physical Surface("back") = {4, 10};',
              'Physical Surface("lower_top") = {6};', 'Physical Surface("upper_bottom") = {11};',
              "Mesh.ElementOrder = %d;" % order,
              "Mesh.SecondOrderIncomplete = %d;" % (1 if serendipity else 0)]
    return "\n".join(lines) + "\n"


def plate_with_inclusion(h_plate, h_disk, order=1, radius=0.5):
    """The square [-1, 1]^2 with a circular hole of the given radius and a disk filling it,
    meshed independently (non-matching curved interface). Regions: plate, disk; left, right,
    bottom, top (the square's sides); hole (the plate's circle), rim (the disk's circle)."""
    r = radius
    lines = ["Geometry.AutoCoherence = 0;",
             "Point(1) = {-1, -1, 0, %g}; Point(2) = {1, -1, 0, %g};" % (h_plate, h_plate),
             "Point(3) = {1, 1, 0, %g}; Point(4) = {-1, 1, 0, %g};" % (h_plate, h_plate),
             "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};",
             "Point(5) = {0, 0, 0, %g};" % h_plate]
    for k, (x, y) in enumerate(((r, 0), (0, r), (-r, 0), (0, -r))):
        lines.append("Point(%d) = {%g, %g, 0, %g};" % (6 + k, x, y, h_plate))
    lines += ["Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8};",
              "Circle(7) = {8, 5, 9}; Circle(8) = {9, 5, 6};",
              "Curve Loop(1) = {1, 2, 3, 4}; Curve Loop(2) = {5, 6, 7, 8};",
              "Plane Surface(1) = {1, 2};",
              "Point(10) = {0, 0, 0, %g};" % h_disk]
    for k, (x, y) in enumerate(((r, 0), (0, r), (-r, 0), (0, -r))):
        lines.append("Point(%d) = {%g, %g, 0, %g};" % (11 + k, x, y, h_disk))
    lines += ["Circle(9) = {11, 10, 12}; Circle(10) = {12, 10, 13};",
              "Circle(11) = {13, 10, 14}; Circle(12) = {14, 10, 11};",
              "Curve Loop(3) = {9, 10, 11, 12}; Plane Surface(2) = {3};",
              'Physical Surface("plate") = {1};', 'Physical Surface("disk") = {2};',
              'Physical Curve("bottom") = {1};', 'Physical Curve("right") = {2};',
              'Physical Curve("top") = {3};', 'Physical Curve("left") = {4};',
              'Physical Curve("hole") = {5, 6, 7, 8};', 'Physical Curve("rim") = {9, 10, 11, 12};',
              "Mesh.ElementOrder = %d;" % order]
    return "\n".join(lines) + "\n"


def block_with_cylinder(h_block, h_cylinder, order=1, radius=0.5, height=1.0):
    """The block [-1, 1]^2 x [0, height] with a cylindrical hole along z and a cylinder filling
    it, meshed independently by tetrahedra (non-matching curved interface; plate_with_inclusion
    in 3D). Regions: block, cylinder; left, right, bottom, top (the block's sides at x = -1,
    x = 1, y = -1, y = 1), base (z = 0, both bodies); hole (the block's cylindrical face),
    mantle (the cylinder's)."""
    r, H, e = radius, height, 1e-3
    lines = ['SetFactory("OpenCASCADE");',
             "Box(1) = {-1, -1, 0, 2, 2, %g};" % H,
             "Cylinder(2) = {0, 0, 0, 0, 0, %g, %g};" % (H, r),
             "BooleanDifference(3) = {Volume{1}; Delete;}{Volume{2}; Delete;};",
             # A new cylinder: its faces are not the hole's (the tool's would be).
             "Cylinder(2) = {0, 0, 0, 0, 0, %g, %g};" % (H, r),
             "MeshSize{PointsOf{Volume{3};}} = %g;" % h_block,
             "MeshSize{PointsOf{Volume{2};}} = %g;" % h_cylinder,
             # The curved faces: those of each volume that are not horizontal (the block's
             # narrower than its sides).
             "hole = -1; mantle = -1;",
             "s[] = Boundary{Volume{3};};",
             "For i In {0:#s[]-1}",
             "  bb[] = BoundingBox Surface{s[i]};",
             "  If (bb[5] - bb[2] > %g && bb[3] - bb[0] < 1.5 && bb[4] - bb[1] < 1.5)" % (H / 2),
             "    hole = s[i];",
             "  EndIf",
             "EndFor",
             "s[] = Boundary{Volume{2};};",
             "For i In {0:#s[]-1}",
             "  bb[] = BoundingBox Surface{s[i]};",
             "  If (bb[5] - bb[2] > %g)" % (H / 2),
             "    mantle = s[i];",
             "  EndIf",
             "EndFor",
             'Physical Volume("block") = {3};', 'Physical Volume("cylinder") = {2};',
             'Physical Surface("left") = Surface In BoundingBox{%g, %g, %g, %g, %g, %g};'
             % (-1 - e, -1 - e, -e, -1 + e, 1 + e, H + e),
             'Physical Surface("right") = Surface In BoundingBox{%g, %g, %g, %g, %g, %g};'
             % (1 - e, -1 - e, -e, 1 + e, 1 + e, H + e),
             'Physical Surface("bottom") = Surface In BoundingBox{%g, %g, %g, %g, %g, %g};'
             % (-1 - e, -1 - e, -e, 1 + e, -1 + e, H + e),
             'Physical Surface("top") = Surface In BoundingBox{%g, %g, %g, %g, %g, %g};'
             % (-1 - e, 1 - e, -e, 1 + e, 1 + e, H + e),
             'Physical Surface("base") = Surface In BoundingBox{%g, %g, %g, %g, %g, %g};'
             % (-1 - e, -1 - e, -e, 1 + e, 1 + e, e),
             'Physical Surface("hole") = {hole};', 'Physical Surface("mantle") = {mantle};',
             "Mesh.ElementOrder = %d;" % order]
    return "\n".join(lines) + "\n"
