// 2D ironing (Yang, Laursen & Meng 2005): a slab [0, 9] x [0, 3] and a half-ring die of inner
// radius 2.8 and outer radius 3.0 whose centre starts at (3, 6), so that the die touches the
// slab at (3, 3). Both bodies are meshed with structured quadrilaterals, independently.
refine = 1;            // 2 halves every element size
h = 0.15 / refine;     // slab
hd = 0.075 / refine;   // die, along its arc
xc = 3; yc = 6; ri = 2.8; ro = 3.0;

Point(1) = {0, 0, 0}; Point(2) = {9, 0, 0}; Point(3) = {9, 3, 0}; Point(4) = {0, 3, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = Round(9 / h) + 1;
Transfinite Curve{2, 4} = Round(3 / h) + 1;
Transfinite Surface{1}; Recombine Surface{1};

Point(10) = {xc, yc, 0};
Point(11) = {xc - ro, yc, 0}; Point(12) = {xc, yc - ro, 0}; Point(13) = {xc + ro, yc, 0};
Point(14) = {xc + ri, yc, 0}; Point(15) = {xc, yc - ri, 0}; Point(16) = {xc - ri, yc, 0};
Circle(11) = {11, 10, 12}; Circle(12) = {12, 10, 13};
Line(13) = {13, 14};
Circle(14) = {14, 10, 15}; Circle(15) = {15, 10, 16};
Line(16) = {16, 11};
Curve Loop(2) = {11, 12, 13, 14, 15, 16}; Plane Surface(2) = {2};
n_arc = Round(0.5 * Pi * ro / hd) + 1;
Transfinite Curve{11, 12, 14, 15} = n_arc;
Transfinite Curve{13, 16} = 3;
Transfinite Surface{2} = {11, 13, 14, 16}; Recombine Surface{2};

Physical Surface("slab") = {1};
Physical Surface("die") = {2};
Physical Curve("slab_bottom") = {1};
Physical Curve("slab_top") = {3};
Physical Curve("die_surface") = {11, 12};
Physical Curve("die_ends") = {13, 16};
