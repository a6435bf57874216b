// The Turek-Hron FSI benchmarks (Turek & Hron 2006): the channel [0, 2.5] x [0, 0.41] with the
// rigid cylinder of radius 0.05 at (0.2, 0.2) and the elastic flag 0.35 x 0.02 behind it
// (tip point A = (0.6, 0.2)) cut out: the fluid; and the flag itself as a surface of its own,
// with its own nodes: the structure. The two meet at the fluid's group `flag_wet_fluid` and
// the flag's group `wet`, joined by an `fsi` interface (mortar, so their nodes need not
// match).
//   refine: scales every mesh parameter (cells per length double when refine doubles);
//   nx, ny: the fluid's facets along the flag and across its tip; fluid_ratio: fluid facets
//   per structure facet on the interface (1 = matching nodes; 2, 3 or 0.5 = non-matching),
//   made by coarsening or refining the flag: the fluid mesh stays the same.
//   quads: 1 makes every cell a quadrilateral (Blossom recombination, then each cell
//   subdivided: quads into 4, the remaining triangles into 3; the flag's cells and facets
//   double per direction). depth > 0 extrudes fluid and flag by a layer of that depth in z,
//   with quads subdivided into two layers of hexahedra: the 3D case that equals the 2D one
//   (fsi_extruded.geo; docs/fsi.md, "Three dimensions"). Its groups: the 2D names for the
//   extruded entities and the planes z = 0 and z = depth as `fluid_sides` and `flag_sides`.
//   structure = 0 leaves the flag out: the fluid alone, the flag's wet boundary
//   `flag_wet_fluid` a rigid wall (CFD3, cfd3.geo). wall > 1 refines the fluid at the walls
//   of cylinder and flag: its facets there are hc / wall, growing back to hc within
//   wall_layer (0.02) of them (the flag's own cells stay: non-matching when structure = 1).
//   wake > 0 holds the fluid's cells at that size in the box [0.1, 1.4] x [0.1, 0.31].
//   refine, fluid_ratio, quads, depth, structure, wall, wall_layer and wake may be set before this file
//   is included.
// Mesh with order 2: quad9 structure, tri6 fluid (Taylor-Hood).
If (!Exists(refine))
  refine = 1;
EndIf
If (!Exists(fluid_ratio))
  fluid_ratio = 1;
EndIf
If (!Exists(quads))
  quads = 0;
EndIf
If (!Exists(depth))
  depth = 0;
EndIf
If (!Exists(structure))
  structure = 1;
EndIf
If (!Exists(wall))
  wall = 1;
EndIf
If (!Exists(wall_layer))
  wall_layer = 0.02;
EndIf
If (!Exists(wake))
  wake = 0;
EndIf
nx = Round(20 * refine);
ny = Round(2 * refine) > 1 ? Round(2 * refine) : 1;
h = 0.05 / refine;                 // far from the obstacle
hc = 0.35 / nx;                    // on the cylinder and the flag (fluid)
xc = 0.2; yc = 0.2; r = 0.05; th = 0.02;
x0 = xc + Sqrt(r * r - (th / 2) * (th / 2));   // where the flag meets the cylinder

// ---- The fluid.
Point(1) = {0, 0, 0, h};
Point(2) = {2.5, 0, 0, h};
Point(3) = {2.5, 0.41, 0, h};
Point(4) = {0, 0.41, 0, h};
Point(5) = {xc, yc, 0, hc};
Point(6) = {x0, yc - th / 2, 0, hc};     // flag's lower attachment
Point(7) = {0.6, yc - th / 2, 0, hc};
Point(8) = {0.6, yc + th / 2, 0, hc};
Point(9) = {x0, yc + th / 2, 0, hc};     // flag's upper attachment
Point(10) = {xc - r, yc, 0, hc};         // the cylinder's front
Line(1) = {1, 2};
Line(2) = {2, 3};
Line(3) = {3, 4};
Line(4) = {4, 1};
Circle(5) = {9, 5, 10};                  // the cylinder's wetted arc, upper half
Circle(6) = {10, 5, 6};                  // lower half
Line(7) = {6, 7};                        // the flag's lower face, from the fluid
Line(8) = {7, 8};                        // its tip
Line(9) = {8, 9};                        // its upper face
Curve Loop(1) = {1, 2, 3, 4};
Curve Loop(2) = {5, 6, 7, 8, 9};
Plane Surface(1) = {1, 2};
nxf = Round(nx * wall);
nyf = Round(ny * wall);
Transfinite Curve{7, 9} = nxf + 1;
Transfinite Curve{8} = nyf + 1;
Field[1] = Distance;
Field[1].CurvesList = {5, 6, 7, 8, 9};
Field[1].NumPointsPerCurve = 200;
Field[2] = Threshold;
Field[2].InField = 1;
Field[2].SizeMin = hc;
Field[2].SizeMax = h;
Field[2].DistMin = 0.0;
Field[2].DistMax = 0.4;
fields[] = {2};
If (wall > 1)
  Field[3] = Threshold;              // the walls' layer: hc / wall, hc at wall_layer (linear)
  Field[3].InField = 1;
  Field[3].SizeMin = hc / wall;
  Field[3].SizeMax = h;
  Field[3].DistMin = 0.0;
  Field[3].DistMax = wall_layer * (h - hc / wall) / (hc - hc / wall);
  fields[] += {3};
EndIf
If (wake > 0)
  Field[4] = Box;                    // the wake
  Field[4].VIn = wake;
  Field[4].VOut = h;
  Field[4].XMin = 0.1;
  Field[4].XMax = 1.4;
  Field[4].YMin = 0.1;
  Field[4].YMax = 0.31;
  fields[] += {4};
EndIf
Field[5] = Min;
Field[5].FieldsList = {fields[]};
Background Field = 5;
Mesh.MeshSizeExtendFromBoundary = 0;
Mesh.MeshSizeFromPoints = 0;
Mesh.MeshSizeFromCurvature = 0;

If (structure)
  // ---- The flag (own points and curves: own nodes).
  Point(21) = {x0, yc - th / 2, 0};
  Point(22) = {0.6, yc - th / 2, 0};
  Point(23) = {0.6, yc + th / 2, 0};
  Point(24) = {x0, yc + th / 2, 0};
  Point(25) = {xc, yc, 0};
  Line(21) = {21, 22};        // lower face
  Line(22) = {22, 23};        // tip
  Line(23) = {23, 24};        // upper face
  Circle(24) = {24, 25, 21};  // glued to the cylinder
  Curve Loop(21) = {21, 22, 23, 24};
  Plane Surface(21) = {21};
  nxs = Round(nx / fluid_ratio);
  nys = Round(ny / fluid_ratio) > 1 ? Round(ny / fluid_ratio) : 1;
  Transfinite Curve{21, 23} = nxs + 1;
  Transfinite Curve{22, 24} = nys + 1;
  Transfinite Surface{21};
  Recombine Surface{21};
EndIf

If (quads)
  Recombine Surface{1};
  Mesh.SubdivisionAlgorithm = depth > 0 ? 2 : 1;
EndIf
If (depth == 0)
  Physical Surface("fluid") = {1};
  Physical Curve("inflow") = {4};
  Physical Curve("outflow") = {2};
  Physical Curve("walls") = {1, 3};
  Physical Curve("cylinder") = {5, 6};
  Physical Curve("flag_wet_fluid") = {7, 8, 9};
  If (structure)
    Physical Surface("flag") = {21};
    Physical Curve("clamped") = {24};
    Physical Curve("wet") = {21, 22, 23};
  EndIf
ElseIf (!structure)
  Error("fsi.geo: depth > 0 needs the flag (structure = 1)");
Else
  // A layer of cells in z. The flag's extruded entities lie on the fluid's but must stay
  // separate (own nodes), and the extrusion merges coinciding entities: the flag is extruded
  // away from the fluid (z in [-1, depth - 1]) and moved back with the merging off. The groups
  // are found by bounding boxes (e), the fluid's while the flag is away.
  e = 1e-4;
  Translate {0, 0, -1} { Surface{21}; Point{25}; }
  fl[] = Extrude {0, 0, depth} { Surface{1}; Layers{1}; Recombine; };
  st[] = Extrude {0, 0, depth} { Surface{21}; Layers{1}; Recombine; };
  z0 = -e; z1 = depth + e;
  Physical Volume("fluid") = {fl[1]};
  Physical Surface("walls") = {Surface In BoundingBox{-e, -e, z0, 2.5 + e, e, z1},
                               Surface In BoundingBox{-e, 0.41 - e, z0, 2.5 + e, 0.41 + e, z1}};
  Physical Surface("outflow") = {Surface In BoundingBox{2.5 - e, -e, z0, 2.5 + e, 0.41 + e, z1}};
  Physical Surface("inflow") = {Surface In BoundingBox{-e, -e, z0, e, 0.41 + e, z1}};
  Physical Surface("cylinder") = {Surface In BoundingBox{xc - r - e, yc - r - e, z0, xc + r + e,
                                                         yc + r + e, z1}};
  Physical Surface("flag_wet_fluid") = {Surface In BoundingBox{x0 - e, yc - th / 2 - e, z0,
                                                               0.6 + e, yc + th / 2 + e, z1}};
  Physical Surface("fluid_sides") = {1, fl[0]};
  z0 = -1 - e; z1 = depth - 1 + e;
  Physical Volume("flag") = {st[1]};
  Physical Surface("wet") = {Surface In BoundingBox{x0 - e, yc - th / 2 - e, z0, 0.6 + e,
                                                    yc - th / 2 + e, z1},
                             Surface In BoundingBox{x0 - e, yc + th / 2 - e, z0, 0.6 + e,
                                                    yc + th / 2 + e, z1},
                             Surface In BoundingBox{0.6 - e, yc - th / 2 - e, z0, 0.6 + e,
                                                    yc + th / 2 + e, z1}};
  Physical Surface("clamped") = {Surface In BoundingBox{x0 - e, yc - th / 2 - e, z0, xc + r + e,
                                                        yc + th / 2 + e, z1}};
  Physical Surface("flag_sides") = {21, st[0]};
  Geometry.AutoCoherence = 0;
  Translate {0, 0, 1} { Volume{st[1]}; }
EndIf
