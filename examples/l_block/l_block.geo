// The seed paper's L-shaped block: a column 1.2 x 1.2 x 3.6 and a cube of side 1.2 attached
// to its upper side, meshed independently (tied by a flat mortar interface), with a
// cylindrical inclusion (radius 0.3, along y) in the column tied across its curved surface.
SetFactory("OpenCASCADE");
column_size = DefineNumber[0.3];
cube_size = DefineNumber[0.25];
inclusion_size = DefineNumber[0.2];
Box(1) = {0, 0, 0, 1.2, 1.2, 3.6};
Box(2) = {1.2, 0, 2.4, 1.2, 1.2, 1.2};
Cylinder(3) = {0.6, 0, 1.2, 0, 1.2, 0, 0.3};
BooleanDifference(4) = {Volume{1}; Delete;}{Volume{3}; Delete;};
// The inclusion, created after the cut so that it shares no surface with the column, and
// turned about its axis so that its mesh does not match the hole's.
Cylinder(3) = {0.6, 0, 1.2, 0, 1.2, 0, 0.3};
Rotate {{0, 1, 0}, {0.6, 0, 1.2}, Pi / 7} { Volume{3}; }
MeshSize{PointsOf{Volume{4};}} = column_size;
MeshSize{PointsOf{Volume{2};}} = cube_size;
MeshSize{PointsOf{Volume{3};}} = inclusion_size;
e = 1e-6;
Physical Volume("column") = {4};
Physical Volume("cube") = {2};
Physical Volume("inclusion") = {3};
Physical Surface("left") = Surface In BoundingBox{-e, -e, -e, e, 1.2 + e, 3.6 + e};
Physical Surface("right") = Surface In BoundingBox{2.4 - e, -e, 2.4 - e, 2.4 + e, 1.2 + e, 3.6 + e};
// The column's face x = 1.2 (master) and the cube's face x = 1.2 (slave).
col[] = Boundary{Volume{4};};
cube[] = Boundary{Volume{2};};
column_face[] = {};
For i In {0:#col[]-1}
  bb[] = BoundingBox Surface{col[i]};
  If (Fabs(bb[0] - 1.2) < 1e-4 && Fabs(bb[3] - 1.2) < 1e-4)
    column_face[] += col[i];
  EndIf
EndFor
cube_face[] = {};
For i In {0:#cube[]-1}
  bb[] = BoundingBox Surface{cube[i]};
  If (Fabs(bb[0] - 1.2) < 1e-4 && Fabs(bb[3] - 1.2) < 1e-4)
    cube_face[] += cube[i];
  EndIf
EndFor
// The hole in the column (master) and the inclusion's lateral surface (slave).
hole[] = {};
For i In {0:#col[]-1}
  bb[] = BoundingBox Surface{col[i]};
  If (bb[3] - bb[0] < 0.7 && bb[5] - bb[2] < 0.7 && bb[4] - bb[1] > 1.0)
    hole[] += col[i];
  EndIf
EndFor
inc[] = Boundary{Volume{3};};
rim[] = {};
For i In {0:#inc[]-1}
  bb[] = BoundingBox Surface{inc[i]};
  If (bb[4] - bb[1] > 1.0)
    rim[] += inc[i];
  EndIf
EndFor
Physical Surface("column_face") = column_face[];
Physical Surface("cube_face") = cube_face[];
Physical Surface("hole") = hole[];
Physical Surface("rim") = rim[];
