// Turek-Hron FSI3 on fsi3_fine.geo's fluid mesh with a matching flag: the fluid's facets on the
// flag are 0.35 / 60 (wall = 3), and the flag is meshed with 60 x 6 quad9 cells, one structure
// facet per fluid facet (fluid : structure 1 : 1). fsi3_fine.geo has 20 x 2 (3 : 1),
// fsi3_fine_1to3.geo 180 x 18 (1 : 3). fluid_ratio counts against the flag's 20 x 2 of refine 1.
wall = 3;
wake = 0.01;
fluid_ratio = 1 / 3;
Include "fsi.geo";
