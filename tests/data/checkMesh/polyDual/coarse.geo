SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1.5, 1, 0.8};
Mesh.CharacteristicLengthMax = 0.2;
Mesh.CharacteristicLengthMin = 0.2;
s() = Boundary{ Volume{1}; };
Physical Surface("walls") = {s()};
Physical Volume("fluid") = {1};
Mesh.MshFileVersion = 2.2;
