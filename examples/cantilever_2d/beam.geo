// A 10 x 1 beam of 40 x 4 quadrilaterals.
L = 10; H = 1;
Point(1) = {0, 0, 0}; Point(2) = {L, 0, 0}; Point(3) = {L, H, 0}; Point(4) = {0, H, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 41; Transfinite Curve{2, 4} = 5;
Transfinite Surface{1}; Recombine Surface{1};
Physical Curve("clamped") = {4};
Physical Curve("tip") = {2};
Physical Surface("beam") = {1};
