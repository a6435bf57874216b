// The seed paper's hollow half-torus (Sect. 4.2): major radius 76, minor radius 24, wall
// thickness 4.5, standing as an arch in the plane y = 0 on its two end faces at z = 0.
// Structured hexahedra: an annulus cross-section (nc elements per quarter of the tube's
// circumference, nt through the wall) swept about the y axis in two quarter turns of na
// layers each. nc, nt and na may be set before this file is included (torus_hex20.geo).
Ra = 76;               // major radius
r = 24;                // minor (outer tube) radius
w = 4.5;               // wall thickness
If (!Exists(nc)) nc = 12; EndIf  // elements per quarter of the tube's circumference
If (!Exists(nt)) nt = 2; EndIf   // elements through the wall
If (!Exists(na)) na = 30; EndIf  // elements per quarter turn of the arch

ri = r - w;
// Cross-section at the foot x = Ra, in the ground plane z = 0.
Point(1) = {Ra, 0, 0};
Point(2) = {Ra + r, 0, 0};  Point(3) = {Ra, r, 0};  Point(4) = {Ra - r, 0, 0};  Point(5) = {Ra, -r, 0};
Point(6) = {Ra + ri, 0, 0}; Point(7) = {Ra, ri, 0}; Point(8) = {Ra - ri, 0, 0}; Point(9) = {Ra, -ri, 0};
Circle(1) = {2, 1, 3}; Circle(2) = {3, 1, 4}; Circle(3) = {4, 1, 5}; Circle(4) = {5, 1, 2};   // outer
Circle(5) = {6, 1, 7}; Circle(6) = {7, 1, 8}; Circle(7) = {8, 1, 9}; Circle(8) = {9, 1, 6};   // inner
Line(9) = {6, 2}; Line(10) = {7, 3}; Line(11) = {8, 4}; Line(12) = {9, 5};                      // radial
Curve Loop(1) = {9, 1, -10, -5};   Plane Surface(1) = {1};
Curve Loop(2) = {10, 2, -11, -6};  Plane Surface(2) = {2};
Curve Loop(3) = {11, 3, -12, -7};  Plane Surface(3) = {3};
Curve Loop(4) = {12, 4, -9, -8};   Plane Surface(4) = {4};
Transfinite Curve{1:8} = nc + 1;
Transfinite Curve{9:12} = nt + 1;
Transfinite Surface{1:4};
Recombine Surface{1:4};

// Rotating by -Pi/2 about +y takes the foot (x > 0, z = 0) up to the crown (x = 0, z > 0).
// For each swept surface Extrude returns: the far face, the volume, then one lateral face per
// curve of its loop, in loop order; the outer arc is the second curve of every loop.
q1[] = Extrude {{0, 1, 0}, {0, 0, 0}, -Pi/2} { Surface{1:4}; Layers{na}; Recombine; };
q2[] = Extrude {{0, 1, 0}, {0, 0, 0}, -Pi/2} { Surface{q1[0], q1[6], q1[12], q1[18]}; Layers{na}; Recombine; };

Physical Volume("torus") = {q1[1], q1[7], q1[13], q1[19], q2[1], q2[7], q2[13], q2[19]};
Physical Surface("bottom") = {1:4, q2[0], q2[6], q2[12], q2[18]};
Physical Surface("outer") = {q1[3], q1[9], q1[15], q1[21], q2[3], q2[9], q2[15], q2[21]};
