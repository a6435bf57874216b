// The elastic flag of the Turek-Hron benchmarks (Turek & Hron 2006): a 0.35 x 0.02 strip
// attached to the rigid cylinder of radius 0.05 centred at (0.2, 0.2); its left end is the arc
// of the cylinder it is glued to, its tip point A is (0.6, 0.2).
// Structured quadrilaterals: nx along the flag, ny across it (refine scales both).
refine = 1;
nx = 40 * refine;
ny = 4 * refine;
xc = 0.2; yc = 0.2; r = 0.05; h = 0.02;
x0 = xc + Sqrt(r * r - (h / 2) * (h / 2));   // where the flag meets the cylinder

Point(1) = {x0, yc - h / 2, 0};
Point(2) = {0.6, yc - h / 2, 0};
Point(3) = {0.6, yc + h / 2, 0};
Point(4) = {x0, yc + h / 2, 0};
Point(5) = {xc, yc, 0};
Line(1) = {1, 2};        // lower face
Line(2) = {2, 3};        // tip
Line(3) = {3, 4};        // upper face
Circle(4) = {4, 5, 1};   // glued to the cylinder
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = nx + 1;
Transfinite Curve{2, 4} = ny + 1;
Transfinite Surface{1};
Recombine Surface{1};

Physical Surface("flag") = {1};
Physical Curve("clamped") = {4};
Physical Curve("tip") = {2};
Physical Curve("wet") = {1, 2, 3};   // the faces the fluid wets in the FSI benchmarks
