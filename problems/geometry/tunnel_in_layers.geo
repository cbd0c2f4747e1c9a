// A tunnel section in layered ground, for problems/staged_tunnel_layered.yaml: the ground box
// of problems/sph_tunnel_blast.yaml (32 m wide, 22.5 m deep, the surface at y = 0) in two layers,
// `upper` over -7 <= y <= 0 and `lower` below it, a concrete lining 0.5 m thick (`lining`, radii
// 2.75 and 3.25 m about (0, -13.25)) and its bore left empty. Units: m.
// OpenCASCADE's fragments cut the four shapes into pieces that share their curves (the layers'
// interface, the lining's outer circle); the bore's piece is removed, and each part is the
// physical group of the pieces in its box.
SetFactory("OpenCASCADE");
Rectangle(1) = {-16, -7, 0, 32, 7};
Rectangle(2) = {-16, -22.5, 0, 32, 15.5};
Disk(3) = {0, -13.25, 0, 3.25};
Disk(4) = {0, -13.25, 0, 2.75};
BooleanFragments{ Surface{1, 2, 3, 4}; Delete; }{}
e = 0.01;
bore() = Surface In BoundingBox{-2.75 - e, -16 - e, -e, 2.75 + e, -10.5 + e, e};
Recursive Delete{ Surface{bore()}; }
lining() = Surface In BoundingBox{-3.25 - e, -16.5 - e, -e, 3.25 + e, -10 + e, e};
lower() = Surface In BoundingBox{-16 - e, -22.5 - e, -e, 16 + e, -7 + e, e};
lower() -= lining();
upper() = Surface In BoundingBox{-16 - e, -7 - e, -e, 16 + e, e, e};
Physical Surface("upper") = {upper()};
Physical Surface("lower") = {lower()};
Physical Surface("lining") = {lining()};
