// The unit cube of the thesis' §4.1 as a mesh of all four cell types, stacked along y
// (the twist axis):
//   y in [0, 0.3]    hexahedra   9 x 9 quadrilaterals on the bottom, extruded in 3 layers
//   y in [0.3, 0.7]  tetrahedra  unstructured, with one pyramid on each hexahedron's top
//                                face (gmsh joins the quadrilaterals to the tetrahedra)
//   y in [0.7, 1]    prisms      the triangles on y = 0.7 extruded in 3 layers
// The cube spans x, z in [-0.5, 0.5] so that the y axis (x = z = 0), about which the
// thesis' eq. 4.1 rotates, is its centre line.
SetFactory("Built-in");
n = 10;             // nodes per edge of the bottom face
h = 1 / (n - 1);    // cell size
Point(1) = {-0.5, 0, -0.5, h};
Point(2) = { 0.5, 0, -0.5, h};
Point(3) = { 0.5, 0,  0.5, h};
Point(4) = {-0.5, 0,  0.5, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4};
Plane Surface(1) = {1};
Transfinite Curve{1, 2, 3, 4} = n;
Transfinite Surface{1};
Recombine Surface{1};
// Extrude returns [0] the opposite surface, [1] the volume, [2..5] the four sides.
hexes[] = Extrude {0, 0.3, 0} { Surface{1}; Layers{3}; Recombine; };
tets[] = Extrude {0, 0.4, 0} { Surface{hexes[0]}; };
prisms[] = Extrude {0, 0.3, 0} { Surface{tets[0]}; Layers{3}; Recombine; };
Physical Surface("bottom") = {1};
Physical Surface("top") = {prisms[0]};
Physical Surface("sides") = {hexes[2], hexes[3], hexes[4], hexes[5], tets[2], tets[3], tets[4], tets[5],
                             prisms[2], prisms[3], prisms[4], prisms[5]};
Physical Volume("cube") = {hexes[1], tets[1], prisms[1]};
Mesh.Algorithm3D = 1;   // Delaunay: makes the pyramids on the quadrilateral faces
