// A square plate [-1, 1]^2 with a circular hole (radius 0.5) and a disk that fills it, meshed
// independently with 6-node triangles: the interface is a pair of non-matching 3-node arcs.
Geometry.AutoCoherence = 0;
hp = 0.25; hd = 0.12;
Point(1) = {-1, -1, 0, hp}; Point(2) = {1, -1, 0, hp};
Point(3) = {1, 1, 0, hp}; Point(4) = {-1, 1, 0, hp};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Point(5) = {0, 0, 0, hp};
Point(6) = {0.5, 0, 0, hp}; Point(7) = {0, 0.5, 0, hp};
Point(8) = {-0.5, 0, 0, hp}; Point(9) = {0, -0.5, 0, hp};
Circle(5) = {6, 5, 7}; Circle(6) = {7, 5, 8}; Circle(7) = {8, 5, 9}; Circle(8) = {9, 5, 6};
Curve Loop(1) = {1, 2, 3, 4}; Curve Loop(2) = {5, 6, 7, 8};
Plane Surface(1) = {1, 2};
Point(10) = {0, 0, 0, hd};
Point(11) = {0.5, 0, 0, hd}; Point(12) = {0, 0.5, 0, hd};
Point(13) = {-0.5, 0, 0, hd}; Point(14) = {0, -0.5, 0, hd};
Circle(9) = {11, 10, 12}; Circle(10) = {12, 10, 13};
Circle(11) = {13, 10, 14}; Circle(12) = {14, 10, 11};
Curve Loop(3) = {9, 10, 11, 12}; Plane Surface(2) = {3};
Physical Surface("plate") = {1};
Physical Surface("disk") = {2};
Physical Curve("bottom") = {1};
Physical Curve("right") = {2};
Physical Curve("top") = {3};
Physical Curve("left") = {4};
Physical Curve("hole") = {5, 6, 7, 8};
Physical Curve("rim") = {9, 10, 11, 12};
Mesh.ElementOrder = 2;
