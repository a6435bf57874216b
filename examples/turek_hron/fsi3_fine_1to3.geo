// Turek-Hron FSI3 on fsi3_fine.geo's fluid mesh with a flag three times finer than the fluid at
// the interface: 180 x 18 quad9 cells against the fluid's 60 facets along each face
// (fluid : structure 1 : 3). fsi3_fine.geo has 20 x 2 (3 : 1), fsi3_fine_1to1.geo 60 x 6 (1 : 1).
wall = 3;
wake = 0.01;
fluid_ratio = 1 / 9;
Include "fsi.geo";
