// Turek-Hron FSI1 extruded to 3D (fsi.geo with quads = 1 and depth > 0): the 2D quadrilateral
// mesh of fsi.geo with quads = 1 (quad9) swept through z in [0, depth] by two layers of hex27,
// fluid and flag alike. With u_z = 0 on the planes z = 0 and z = depth (`fluid_sides`,
// `flag_sides`) the 2D solution on that quad9 mesh, extended constantly in z, solves this
// problem (docs/fsi.md, "Three dimensions").
// refine 0.25 (the coarsest FSI1 mesh; 802 hex27, 39 371 unknowns): refine 1 would make
// 7 888 hex27.
refine = 0.25;
quads = 1;
depth = 0.05;
Include "fsi.geo";
