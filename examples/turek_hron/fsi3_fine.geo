// Turek-Hron FSI3 on the fluid mesh CFD3 needs (cfd3.geo): fsi.geo at refine 1 with the
// fluid's facets on cylinder and flag three times finer (wall = 3: 0.0058 m) and the wake box
// [0.1, 1.4] x [0.1, 0.31] at 0.01 m; the flag keeps its 20 x 2 quad9 cells (the interface
// is non-matching: 3 fluid facets per structure facet).
wall = 3;
wake = 0.01;
Include "fsi.geo";
