// 3D ironing (Puso & Laursen 2004): a Neo-Hookean slab 9 x 4 x 3 and a die, a half cylinder
// shell of outer radius 3, thickness 0.2 and width 5.2 whose axis runs along y, pressed 1.4
// into the slab and slid 4 along x. The plane y = 0 is a plane of symmetry of both bodies:
// half of each is meshed (slab y in [0, 2], die y in [0, 2.6]). Both bodies are structured
// hexahedra, meshed independently (non-matching), the die finer along its arc.
// refine = 1 (h = 0.5, 4.1k dofs) is the example; at refine = 2 (20.6k dofs) the run stops at
// t = 1.33 after its step cuts: lateral-edge nodes hold neither stick nor slip there
// (examples/ironing/README.md).
refine = 1;            // 2 halves every element size
h = 0.5 / refine;      // slab
hd = 0.25 / refine;    // die, along its arc
hy = 0.5 / refine;     // die, across its width
xc = 3; zc = 6; ri = 2.8; ro = 3.0;
W = 2; Wd = 2.6;       // half widths

// Slab: the xz rectangle extruded along y.
Point(1) = {0, 0, 0}; Point(2) = {9, 0, 0}; Point(3) = {9, 0, 3}; Point(4) = {0, 0, 3};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = Round(9 / h) + 1;
Transfinite Curve{2, 4} = Round(3 / h) + 1;
Transfinite Surface{1}; Recombine Surface{1};
slab[] = Extrude {0, W, 0} { Surface{1}; Layers{Round(W / h)}; Recombine; };
// slab[0]: face y = W, slab[1]: volume, slab[2..5]: faces swept by lines 1..4.

// Die: the half ring in the xz plane (centre (xc, zc), touching the slab at (xc, 3)),
// extruded along y.
Point(1010) = {xc, 0, zc};
Point(1011) = {xc - ro, 0, zc}; Point(1012) = {xc, 0, zc - ro}; Point(1013) = {xc + ro, 0, zc};
Point(1014) = {xc + ri, 0, zc}; Point(1015) = {xc, 0, zc - ri}; Point(1016) = {xc - ri, 0, zc};
Circle(1011) = {1011, 1010, 1012}; Circle(1012) = {1012, 1010, 1013};
Line(1013) = {1013, 1014};
Circle(1014) = {1014, 1010, 1015}; Circle(1015) = {1015, 1010, 1016};
Line(1016) = {1016, 1011};
Curve Loop(1002) = {1011, 1012, 1013, 1014, 1015, 1016}; Plane Surface(1002) = {1002};
n_arc = Round(0.5 * Pi * ro / hd) + 1;
Transfinite Curve{1011, 1012, 1014, 1015} = n_arc;
Transfinite Curve{1013, 1016} = 3;
Transfinite Surface{1002} = {1011, 1013, 1014, 1016}; Recombine Surface{1002};
die[] = Extrude {0, Wd, 0} { Surface{1002}; Layers{Round(Wd / hy)}; Recombine; };
// die[0]: face y = Wd, die[1]: volume, die[2..7]: faces swept by curves 1011..1016.

Physical Volume("slab") = {slab[1]};
Physical Volume("die") = {die[1]};
Physical Surface("slab_bottom") = {slab[2]};
Physical Surface("slab_top") = {slab[4]};
Physical Surface("slab_symmetry") = {1};
Physical Surface("die_surface") = {die[2], die[3]};
Physical Surface("die_ends") = {die[4], die[7]};
Physical Surface("die_symmetry") = {1002};
