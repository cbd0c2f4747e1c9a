// The PMMA beam of problems/pd_pmma_beam_impact.yaml, drawn in mm, for
// problems/pd_pmma_beam_from_geo.yaml: the beam 220 x 45 (the surface `beam`) and its edge
// crack, the curve `crack` from (120, -1) to (120, 6): a line that is not part of the surface,
// which a peridynamic body takes as bonds cut (cracks: [{curve: crack}]).
SetFactory("OpenCASCADE");
Rectangle(1) = {0, 0, 0, 220, 45};
Point(10) = {120, -1, 0};
Point(11) = {120, 6, 0};
Line(10) = {10, 11};
Physical Surface("beam") = {1};
Physical Curve("crack") = {10};
