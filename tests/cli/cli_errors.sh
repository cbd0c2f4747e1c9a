#!/usr/bin/env bash
# Bad input: one clear message naming the key, a non-zero exit, and no result files left.
set -u
MF="$1"; ROOT="$2"
WORK="$(mktemp -d)"; trap 'rm -rf "$WORK"' EXIT
fails=0
# Runs "$MF run ARGS --out $WORK/out"; fails the case unless it exits non-zero with a message
# holding the fragment. Returns 1 when the case has already failed.
run_failing() { # run_failing "message fragment" args...
  local want="$1"; shift
  rm -rf "$WORK/out"
  msg="$("$MF" run "$@" --out "$WORK/out" 2>&1 >/dev/null)"; rc=$?
  if [ $rc -eq 0 ]; then echo "FAIL (exit 0): $*"; fails=$((fails+1)); return 1; fi
  if ! grep -qF -- "$want" <<<"$msg"; then echo "FAIL (message '$msg' lacks '$want'): $*"; fails=$((fails+1)); return 1; fi
}
# Bad input: rejected with exit 2 before anything is written (an explicit run's set-up, which
# builds every particle and bond, included).
expect_error() { # expect_error "message fragment" args...
  run_failing "$@" || return
  if [ $rc -ne 2 ]; then echo "FAIL (exit $rc, not 2): ${*:2}"; fails=$((fails+1)); return; fi
  if [ -n "$(ls -A "$WORK/out" 2>/dev/null)" ]; then echo "FAIL (left files in $WORK/out): ${*:2}"; fails=$((fails+1)); return; fi
  echo "ok: $1"
}
# A valid file whose run fails while setting up: nothing is put in place in the output folder;
# what the run wrote is kept in its folder "failed", with a summary.json of status "failed".
failed_only() { # true when $WORK/out holds only failed/, with a failed summary
  [ "$(ls -A "$WORK/out")" = "failed" ] && grep -q '"status": "failed"' "$WORK/out/failed/summary.json"
}
expect_run_failure() { # expect_run_failure "message fragment" args...
  run_failing "$@" || return
  if ! failed_only; then
    echo "FAIL (expected only failed/ with a failed summary.json in $WORK/out): ${*:2}"; fails=$((fails+1)); return
  fi
  echo "ok: $1"
}
P="$ROOT/problems/plate_tension.yaml"
expect_error "discretisation.spacing: expected a positive number, got -0.1" "$P" --set discretisation.spacing=-0.1
expect_error "materials[0].E: expected a number, got steel" "$P" --set materials.0.E=steel
expect_error "discretisation.colour: unknown key" "$P" --set discretisation.colour=red
expect_error "discretisation.quadrature.volumetric_strain: cell_mean is for plane_strain and solid_3d bodies: a plane-stress body's thickness changes with its volume freely, so nothing locks" "$P" --set discretisation.quadrature.volumetric_strain=cell_mean
expect_error "boundary[0]: selects no part of the boundary" "$P" --set 'boundary.0.box=[[5, 5], [6, 6]]'
expect_error "boundary[1].edges: no boundary piece is named 'roof'" "$P" --set boundary.1.edges=roof
expect_error "cannot open the problem file" "$WORK/missing.yaml"
expect_error "--set boundary.x: 'x' indexes a list and must be a number" "$P" --set boundary.x=1
expect_error "--set name.foo: 'name' holds a single value" "$P" --set name.foo=1
expect_error "boundary[0].edges: expected a list of boundary names" "$P" --set 'boundary.0.edges=[{a: 1}]'
expect_error "output.lines[1].name: another line is named 'y07'" "$P" --set 'output.lines.1.name=y07'
expect_error "output.lines[0].from: no sample point of the line lies in the body" "$P" --set 'output.lines.0.from=[5, 5]' --set 'output.lines.0.to=[6, 6]'
expect_error "geometry.holes[0].center: the hole 'hole0' does not cut the body" "$P" --set 'geometry.holes=[{center: [5, 5], radius: 0.1}]'
expect_error "geometry.holes[0].radius: the hole covers the whole body" "$P" --set 'geometry.holes=[{center: [0.5, 0.5], radius: 5}]'
# Holes of other outlines: two kinds at once, none, a polygon that crosses itself or has too few
# vertices, a slot without a width or with a negative one, a rectangle that misses the body or
# covers it, a key a slot does not have.
expect_error "geometry.holes[0].center: give one of a circle (center and radius), a polygon, a rectangle or a slot" "$P" --set 'geometry.holes=[{slot: {from: [0.2, 0.5], to: [0.8, 0.5], width: 0.1}, center: [0.5, 0.5], radius: 0.1}]'
expect_error "geometry.holes[0].radius: give one of a circle (center and radius), a polygon, a rectangle or a slot" "$P" --set 'geometry.holes=[{name: window}]'
expect_error "geometry.holes[0].polygon: the polygon hole's edges 0 and 2 cross: its outline must not cross itself" "$P" --set 'geometry.holes=[{polygon: [[0.2, 0.2], [0.8, 0.6], [0.8, 0.2], [0.2, 0.7]]}]'
expect_error "geometry.holes[0].polygon: a polygon hole needs at least 3 vertices, got 2" "$P" --set 'geometry.holes=[{polygon: [[0.2, 0.2], [0.8, 0.6]]}]'
expect_error "geometry.holes[0].slot.width: required value is missing" "$P" --set 'geometry.holes=[{slot: {from: [0.2, 0.5], to: [0.8, 0.5]}}]'
expect_error "geometry.holes[0].slot.width: expected a positive number, got -1" "$P" --set 'geometry.holes=[{slot: {from: [0.2, 0.5], to: [0.8, 0.5], width: -1}}]'
expect_error "geometry.holes[0].rectangle: the hole 'hole0' does not cut the body" "$P" --set 'geometry.holes=[{rectangle: {origin: [5, 5], size: [1, 1]}}]'
expect_error "geometry.holes[0].rectangle: the hole covers the whole body" "$P" --set 'geometry.holes=[{rectangle: {origin: [-1, -1], size: [3, 3]}}]'
expect_error "geometry.spheres[0].radius: 0.3: the sphere 'ball' overlaps the hole 'slot'" "$ROOT/problems/thick_perforated_plate.yaml" --set 'geometry.holes=[{slot: {from: [3, 8], to: [6, 10], width: 1}, name: slot}]' --set 'geometry.spheres=[{center: [4.5, 9, 1], radius: 0.3, name: ball}]' --set 'discretisation.refinement=[]'
expect_error "geometry.holes[0].slot.depth: unknown key (known here: from, to, width)" "$P" --set 'geometry.holes=[{slot: {from: [0.2, 0.5], to: [0.8, 0.5], width: 0.1, depth: 2}}]'
# Rounded corners: a corner that is not there, a straight one, one rounded twice, a radius that
# does not fit on an edge or is not positive, fillets not given as a list.
expect_error "geometry.fillets[0].at: no corner of the outline lies at (0.5, 0)" "$P" --set 'geometry.fillets=[{at: [0.5, 0], radius: 0.1}]'
expect_error "geometry.fillets[0].at: the corner at (0.5, 0) is straight: its edges run on in one line, nothing to round" "$P" --set 'geometry={polygon: {vertices: [[0, 0], [0.5, 0], [1, 0], [1, 1], [0, 1]]}, fillets: [{at: [0.5, 0], radius: 0.1}]}'
expect_error "geometry.fillets[1].at: the corner at (1, 1) is rounded already" "$P" --set 'geometry.fillets=[{at: [1, 1], radius: 0.1}, {at: [1, 1], radius: 0.2}]'
expect_error "geometry.fillets[0].radius: a fillet of radius 2 at (1, 1) needs 2 of edge 'right', which is 1 long" "$P" --set 'geometry.fillets=[{at: [1, 1], radius: 2}]'
expect_error "geometry.fillets[1].radius: a fillet of radius 0.6 at (1, 0) needs 1.1 of edge 'right', which is 1 long" "$P" --set 'geometry.fillets=[{at: [1, 1], radius: 0.5}, {at: [1, 0], radius: 0.6}]'
expect_error "geometry.fillets[0].radius: expected a positive number, got -1" "$P" --set 'geometry.fillets=[{at: [1, 1], radius: -1}]'
expect_error "geometry.fillets: expected a list, got {at: [1, 1], radius: 0.1}" "$P" --set 'geometry.fillets={at: [1, 1], radius: 0.1}'
# A body from a geometry file: one that is not there, a folder, a kind gmsh does not read as
# geometry, a file it cannot parse, one without a surface (an open outline), a 3D body, two bodies,
# surfaces out of their plane; a scale that is not positive, a file beside a polygon, a file
# for a 3D model, a condition on a name the file does not hold (the message lists those it does),
# fillets on an outline that has arcs.
FB="$ROOT/problems/filleted_bar_from_step.yaml"
GEO="$WORK/geometry"; mkdir -p "$GEO/folder.geo"
echo "not a STEP file" > "$GEO/bad.step"
cp "$ROOT/problems/geometry/filleted_bar.geo" "$GEO/part.igs"
printf 'Point(1) = {0, 0, 0};\nPoint(2) = {1, 0, 0};\nPoint(3) = {1, 1, 0};\nLine(1) = {1, 2};\nLine(2) = {2, 3};\n' > "$GEO/open.geo"
printf 'SetFactory("OpenCASCADE");\nBox(1) = {0, 0, 0, 1, 1, 1};\n' > "$GEO/box.geo"
printf 'SetFactory("OpenCASCADE");\nRectangle(1) = {0, 0, 0, 1, 1};\nRectangle(2) = {2, 0, 0, 1, 1};\n' > "$GEO/two.geo"
printf 'SetFactory("OpenCASCADE");\nRectangle(1) = {0, 0, 0, 1, 1};\nRotate {{1, 0, 0}, {0, 0, 0}, 0.5} { Surface{1}; }\n' > "$GEO/tilted.geo"
expect_error "geometry.file: $ROOT/problems/nowhere.step: cannot open the geometry file" "$FB" --set 'geometry.file=nowhere.step'
expect_error "geometry.file: $GEO/folder.geo: is a folder, not a geometry file" "$FB" --set "geometry.file=$GEO/folder.geo"
expect_error "geometry.file: $GEO/part.igs: not a geometry file meshfree reads (.step, .stp, .brep, .geo or .msh)" "$FB" --set "geometry.file=$GEO/part.igs"
expect_error "geometry.file: $GEO/bad.step: gmsh cannot read it: Could not read file" "$FB" --set "geometry.file=$GEO/bad.step"
expect_error "geometry.file: $GEO/open.geo: holds no surface" "$FB" --set "geometry.file=$GEO/open.geo"
expect_error "geometry.file: $GEO/box.geo: holds volumes, a 3D body: a plane model reads a file of surfaces in one plane" "$FB" --set "geometry.file=$GEO/box.geo"
expect_error "geometry.file: $GEO/two.geo: its surfaces make more than one body" "$FB" --set "geometry.file=$GEO/two.geo"
expect_error "geometry.file: $GEO/tilted.geo: its surfaces do not lie in one plane z = const" "$FB" --set "geometry.file=$GEO/tilted.geo"
expect_error "geometry.scale: expected a positive number, got 0" "$FB" --set geometry.scale=0
expect_error "geometry.rectangle: give exactly one of 'rectangle', 'polygon' or 'file'" "$FB" --set 'geometry.polygon={vertices: [[0, 0], [1, 0], [1, 1]]}'
expect_error "geometry.file: a 3D body is read from a file by the plane models only so far" "$FB" --set 'model={type: solid_3d}'
expect_error "boundary[0].edges: no boundary piece is named 'symmetry' (the body's pieces: curve1, curve2, curve3, curve4, curve5, curve6, curve7;" "$FB" --set boundary.0.edges=symmetry
expect_error "geometry.fillets[0].at: the outline has arcs of its own" "$FB" --set 'geometry.fillets=[{at: [20, 0], radius: 1}]'
# Parts: a group the file does not hold (the message lists those it does), one given twice, a
# group left without a material, parts of a body that is not from a file, an unknown material,
# a surface in no group.
BB="$ROOT/problems/bimaterial_bar.yaml"
expect_error "parts[1].group: the geometry file has no group of surfaces named 'copper' (its groups: steel, aluminium)" "$BB" --set parts.1.group=copper
expect_error "parts[1].group: 'steel' is given a material already" "$BB" --set parts.1.group=steel
expect_error "parts: the geometry file's group of surfaces 'aluminium' has no material: give {group: aluminium, material: ...}" "$BB" --set 'parts=[{group: steel, material: steel}]'
expect_error "parts: names the groups of surfaces of a geometry file (geometry.file), and the body has none" "$BB" --set 'geometry={rectangle: {size: [20, 2]}}'
expect_error "parts[0].material: no material is named 'brass' (materials: steel, aluminium)" "$BB" --set parts.0.material=brass
printf 'SetFactory("OpenCASCADE");\nRectangle(1) = {0, 0, 0, 10, 2};\nRectangle(2) = {10, 0, 0, 10, 2};\nRectangle(3) = {20, 0, 0, 5, 2};\nBooleanFragments{ Surface{1}; Delete; }{ Surface{2, 3}; Delete; }\nPhysical Surface("steel") = {1};\nPhysical Surface("aluminium") = {2};\n' > "$GEO/ungrouped.geo"
expect_error "parts: the geometry file's groups of surfaces cover an area of 40, the body 50: every surface needs one group (and one only)" "$BB" --set "geometry.file=$GEO/ungrouped.geo"
# The visibility criterion hides nodes behind a plane body's holes only.
expect_error "discretisation.visibility: hides nodes behind a plane body's holes; a 3D body has none to hide them" "$ROOT/problems/block_uniaxial_3d.yaml" --set discretisation.visibility=true
# Peridynamic parts: the same reader and messages; a body material, where given, is the default.
PB="$ROOT/tests/data/pd_bimaterial_bar.yaml"
expect_error "parts[1].group: the geometry file has no group of surfaces named 'copper' (its groups: steel, aluminium)" "$PB" --set parts.1.group=copper
expect_error "parts: the geometry file's group of surfaces 'aluminium' has no material: give {group: aluminium, material: ...}" "$PB" --set 'parts=[{group: steel, material: steel}]'
expect_error "parts: names the groups of surfaces of a geometry file (geometry.file), and the body has none" "$PB" --set 'geometry={rectangle: {size: [20, 2]}}'
# Pre-cracks drawn in a file (cracks: [{curve}]): a group of curves the file does not hold (the
# message lists those it does), a curve of a body that is not from a file.
PM="$ROOT/problems/pd_pmma_beam_from_geo.yaml"
expect_error "cracks[0].curve: the geometry file has no group of curves named 'slit' (its groups of curves: crack)" "$PM" --set 'cracks=[{curve: slit}]'
expect_error "cracks[0].curve: names a group of curves of a plane geometry file (geometry.file), and the body has none" "$PM" --set 'geometry={rectangle: {size: [0.22, 0.045]}}'
# SPH regions from a file: a file beside a box, a group the file does not hold, a file for a
# body of another dimension than 2.
TB="$ROOT/problems/sph_tunnel_blast.yaml"
expect_error "regions[0].file: a region of particles is read from a file in 2D only so far" "$ROOT/problems/sph_bar_impact.yaml" --set "regions.0={material: aluminium, file: $ROOT/problems/geometry/bimaterial_bar.geo, spacing: 0.000125}"
expect_error "regions[0].box: give exactly one of 'box', 'ring' or 'file'" "$TB" --set "regions.0.file=$ROOT/problems/geometry/bimaterial_bar.geo"
expect_error "regions[0].group: the geometry file has no group of surfaces named 'sand' (its groups: steel, aluminium)" "$TB" --set "regions.0={material: sand, file: $ROOT/problems/geometry/bimaterial_bar.geo, group: sand, spacing: 0.25}"
expect_error "discretisation.refinement[0].spacing: nodes in the box: about" "$P" --set 'discretisation.refinement=[{box: [[0, 0], [0.1, 0.1]], spacing: 1e-9}]'
expect_error "boundary[1].name: 'clamp' is used by boundary[0] already" "$P" --set boundary.1.name=clamp
expect_error "name: expected a name of letters, digits" "$P" --set name=a/b
expect_error "discretisation.quadrature.order: expected an integer from 2 to 10, got 1e30" "$P" --set discretisation.quadrature.order=1e30
# Elastoplastic inputs: plasticity, hardening laws, the load schedule, finite elements.
Q="$ROOT/problems/plate_plastic_thesis.yaml"
expect_error "materials[0].plasticity.yield_stress: expected a positive number, got -310" "$Q" --set materials.0.plasticity.yield_stress=-310
expect_error "materials[0].plasticity.hardening.type: expected one of" "$Q" --set 'materials.0.plasticity.hardening={type: cubic}'
expect_error "nonlinear.keep_tangent: expected a contraction from 0 (a new tangent every iteration) up to but not including 1, got 1" "$Q" --set nonlinear.keep_tangent=1
expect_error "nonlinear.keep_tangent: expected a number, got yes" "$Q" --set nonlinear.keep_tangent=yes
expect_error "materials[0].plasticity.hardening: 'linear' needs parameters" "$Q" --set materials.0.plasticity.hardening=linear
expect_error "materials[0].plasticity.hardening.H: expected a number >= 0, got -5" "$Q" --set 'materials.0.plasticity.hardening={type: linear, H: -5}'
expect_error "materials[0].plasticity.yield_stress: the swift law sets the initial yield stress itself" "$Q" --set 'materials.0.plasticity.hardening={type: swift, K: 500, eps0: 0.01, n: 0.2}'
expect_error "materials[0].plasticity.hardening.points: equivalent plastic strains must increase" "$Q" --set 'materials.0.plasticity={hardening: {type: table, points: [[0, 300], [0.1, 320], [0.05, 330]]}}'
expect_error "materials[0].plasticity.hardening.points: the first point must be at equivalent plastic strain 0" "$Q" --set 'materials.0.plasticity={hardening: {type: table, points: [[0.1, 300], [0.2, 320]]}}'
expect_error "materials[0].plasticity.hardening.points: the yield stress falls from 300 to 280 at equivalent plastic strain 0.1: a softening law; give softening: true if that is meant" "$Q" --set 'materials.0.plasticity={hardening: {type: table, points: [[0, 300], [0.1, 280], [0.2, 320]]}}'
expect_error "materials[0].plasticity.hardening.points: the last segment falls, and the yield stress goes on along it past the last point (zero at equivalent plastic strain 0.2); end the table with a segment that does not fall" "$Q" --set 'materials.0.plasticity={hardening: {type: table, points: [[0, 300], [0.1, 150]], softening: true}}'
# Drucker-Prager (problems/strip_footing_prandtl.yaml).
D="$ROOT/problems/strip_footing_prandtl.yaml"
expect_error "materials[0].plasticity.model: expected one of [j2, drucker_prager], got 'mohr_coulomb'" "$D" --set materials.0.plasticity.model=mohr_coulomb
expect_error "materials[0].plasticity.friction_angle: expected an angle in degrees in [0, 90), got 95" "$D" --set materials.0.plasticity.friction_angle=95
expect_error "materials[0].plasticity.friction_angle: required value is missing" "$D" --set 'materials.0.plasticity={model: drucker_prager, cohesion: 1.0e4}'
expect_error "materials[0].plasticity.dilation_angle: expected at most the friction angle 20, got 25" "$D" --set materials.0.plasticity.dilation_angle=25
expect_error "materials[0].plasticity.tension_cutoff: expected a mean stress in [0, 27474.77419) (the cone's apex, xi c / eta), got 100000" "$D" --set materials.0.plasticity.tension_cutoff=1.0e5
expect_error "materials[0].plasticity.cohesion: expected a number >= 0, got -1" "$D" --set materials.0.plasticity.cohesion=-1
expect_error "materials[0].plasticity.friction_angle: a soil without cohesion needs a friction angle above 0" "$D" --set 'materials.0.plasticity={model: drucker_prager, cohesion: 0, friction_angle: 0}'
expect_error "materials[0].plasticity.match: expected one of [plane_strain, outer, inner], got 'middle'" "$D" --set materials.0.plasticity.match=middle
expect_error "materials[0].plasticity.yield_stress: unknown key" "$D" --set materials.0.plasticity.yield_stress=300
expect_error "materials[0].plasticity: analysis elastoplastic_static needs a plasticity law" "$Q" --set 'materials.0={name: steel, E: 2.0e5, nu: 0.1}'
expect_error "materials[0].plasticity: used only by analysis elastoplastic_static" "$Q" --set analysis=elastic_static
expect_error "material_regions[0].material: no material is named 'clay'" "$Q" --set 'material_regions=[{material: clay, box: [[0, 0], [1, 1]]}]'
expect_error "materials[0].density: gravity needs the density of every material of the body" "$Q" --set 'gravity=[0, -9.81]'
expect_error "initial_stress: a geostatic initial stress needs 'gravity'" "$Q" --set 'initial_stress={type: geostatic, surface: 1, k0: 0.5}'
expect_error "steps[1].name: another step is named 'elastic'" "$Q" --set steps.1.name=elastic
expect_error "steps[0].increments: expected an integer from 1 to 1000000, got 0" "$Q" --set steps.0.increments=0
expect_error "steps[0].factors.roof: unknown key" "$Q" --set 'steps.0.factors={roof: 2}'
expect_error "steps[0].load_factor: give the step's target 'load_factor' or 'factors'" "$Q" --set 'steps.0={name: a, increments: 2}'
expect_error "steps: an elastoplastic analysis needs a load schedule" "$Q" --set 'steps=[]'
expect_error "nonlinear.tolerance: a relative residual tolerance below 1e-2 is needed, got 0.5" "$Q" --set nonlinear.tolerance=0.5
expect_error "output.gauges[0].at: the point (5, 5) is not in the body" "$Q" --set 'output.gauges.0.at=[5, 5]'
expect_error "discretisation.method: expected one of" "$Q" --set discretisation.method=bem
expect_error "discretisation.fem.element: expected one of" "$Q" --set discretisation.method=fem --set discretisation.fem.element=q9
expect_error "discretisation.fem.mesh: cannot open the mesh file" "$Q" --set discretisation.method=fem --set discretisation.fem.mesh=missing.msh
expect_error "holds Q8 elements" "$ROOT/problems/perforated_strip.yaml" --set discretisation.method=fem --set discretisation.fem.mesh=meshes/perforated_strip_q8.msh --set discretisation.fem.element=q4
expect_error "lies outside the body" "$ROOT/problems/perforated_strip.yaml" --set discretisation.method=fem --set discretisation.fem.mesh=meshes/perforated_strip_q8.msh --set 'geometry.holes.0.radius=6' --set 'output.gauges=[]'
# 3D finite elements: an element name the 3D body does not know, tetrahedra from a plane mesh
# file, one point per 10-node tetrahedron; and tetrahedra on a plane body.
T="$ROOT/problems/thick_cylinder_3d.yaml"
expect_error "discretisation.fem.element: expected one of [hex8, hex20, tet4, tet10, q4, q8, t3], got 'tet20'" "$T" --set discretisation.method=fem --set discretisation.fem.element=tet20
expect_error "discretisation.fem.element: model solid_3d extrudes hex8 or hex20 bricks (q4 or q8 plane elements), or meshes tet4 or tet10, not t3" "$T" --set discretisation.method=fem --set discretisation.fem.element=t3
expect_error "discretisation.fem.mesh: tet4 elements are meshed by gmsh from the geometry" "$T" --set discretisation.method=fem --set discretisation.fem.element=tet4 --set discretisation.fem.mesh=meshes/perforated_strip_q8.msh
expect_error "discretisation.fem.order: 1 (the centroid) leaves tet10 elements without stiffness" "$T" --set discretisation.method=fem --set discretisation.fem.element=tet10 --set discretisation.fem.order=1
expect_error "stages[0].discretisation.fem.element: expected one of [hex8, hex20, tet4, tet10, q4, q8, t3], got 'tet'" "$ROOT/problems/staged_column_blast.yaml" --set stages.0.discretisation.fem.element=tet
expect_error "discretisation.fem.element: expected one of [t3, q4, q8], got 'tet4'" "$Q" --set discretisation.method=fem --set discretisation.fem.element=tet4
expect_error "discretisation.fem.element: expected one of [t3, q4, q8], got 'hex20'" "$Q" --set discretisation.method=fem --set discretisation.fem.element=hex20
# Spherical holes in 3D bodies and face samples: a sphere outside the body, one overlapping
# another hole, a bad radius, a name taken; bricks, which cannot follow a sphere; face samples
# naming no face, or a box that is not flat or misses the body.
C="$ROOT/problems/sphere_cavity_3d.yaml"
expect_error "geometry.spheres[0].center: [5, 5, 5]: the sphere 'cavity' does not cut the body" "$C" --set 'geometry.spheres.0.center=[5, 5, 5]'
expect_error "geometry.spheres[0].radius: expected a positive number, got 0" "$C" --set geometry.spheres.0.radius=0
expect_error "geometry.spheres[1].radius: 0.8: the sphere 'other' overlaps the sphere 'cavity'" "$C" --set 'geometry.spheres=[{center: [0, 0, 0], radius: 1, name: cavity}, {center: [1, 1, 1], radius: 0.8, name: other}]'
expect_error "geometry.spheres[0].radius: 0.5: the sphere 'ball' overlaps the cylindrical hole 'bore'" "$T" --set 'geometry.spheres=[{center: [1.2, 0.5, 0.25], radius: 0.5, name: ball}]'
expect_error "geometry.spheres[0].name: 'left' already names a face of the body" "$C" --set geometry.spheres.0.name=left
expect_error "geometry.spheres: bricks extrude a plane mesh and cannot follow the sphere 'cavity'" "$C" --set discretisation.method=fem
expect_error "output.faces[0].face: no face is named 'roof' (the body's faces: bottom, right, top, left, back, front, cavity; x_min, x_max, y_min, y_max, z_min and z_max name the faces on the sides of its bounding box)" "$C" --set 'output.faces=[{name: f, face: roof}]'
expect_error "output.faces[0].box: a face sample's box is flat: give one extent zero" "$C" --set 'output.faces=[{name: f, box: [[0, 0, 0], [1, 1, 1]]}]'
expect_error "output.faces[0].box: no sample point lies in the body" "$C" --set 'output.faces=[{name: f, box: [[5, 5, 1], [6, 6, 1]]}]'
expect_error "output.faces[0].name: give exactly one of 'face' or 'box'" "$C" --set 'output.faces=[{name: f}]'
expect_error "geometry.spheres: unknown key" "$P" --set 'geometry.spheres=[{center: [0, 0, 0], radius: 1}]'
printf 'name: x\nanalysis: elastic_static\n' > "$WORK/incomplete.yaml"
expect_error "model: required value is missing" "$WORK/incomplete.yaml"
B="$ROOT/problems/pd_slab_blast.yaml"
expect_error "boundary[2].blast.tnt_mass: expected a positive number, got -10" "$B" --set boundary.2.blast.tnt_mass=-10
expect_error "boundary[2].blast.burst: expected one of" "$B" --set boundary.2.blast.burst=underwater
expect_error "boundary[2].blast: particle at (0.995, 0.195, 0): Kingery-Bulmash: scaled distance 0.049" "$B" --set 'boundary.2.blast.charge_at=[1.1, 0.21]'
expect_error "boundary[2].blast.normal: expected a non-zero vector" "$B" --set 'boundary.2.blast.normal=[0, 0]'
S="$ROOT/problems/sph_sod_tube.yaml"
expect_error "materials[0].eos.type: expected one of" "$S" --set 'materials.0.eos.type=plasma'
expect_error "regions[0].energy: give exactly one of 'energy' (J/kg) or 'pressure'" "$S" --set 'regions.0.energy=2.5'
expect_error "discretisation.smoothing: expected h / spacing between 1 and 3" "$S" --set discretisation.smoothing=5
expect_error "regions[1].material: no material is named 'air'" "$S" --set regions.1.material=air
expect_error "discretisation.smoothing_bounds: expected [min, max] multiples of the initial smoothing length with 0 < min <= 1 <= max, got [1.5, 2]" "$S" --set 'discretisation.smoothing_bounds=[1.5, 2]'
expect_error "regions[1].smoothing_bounds: expected a list of 2 numbers" "$S" --set 'regions.1.smoothing_bounds=[0.5]'
expect_error "regions[1].smoothing_bounds: expected [min, max] multiples of the initial smoothing length with 0 < min <= 1 <= max, got [0, 2]" "$S" --set 'regions.1.smoothing_bounds=[0, 2]'
# A state that makes the first time step absurd is named, not the end time it cannot reach.
expect_error "regions[0].pressure: it gives its particles a sound speed of 1.183215957e+150, faster than light" "$S" --set regions.0.pressure=1e300
expect_error "regions[1].velocity: it gives its particles a speed of 1e+200, faster than light" "$S" --set 'regions.1.velocity=[1e200]'
expect_error "time.end: 1e+20 s in time steps of" "$S" --set time.end=1e20
expect_error "materials[0].eos.unreacted.c0: expected a positive number, got -2390" "$ROOT/problems/sph_tnt_slab.yaml" --set 'materials.0.eos.unreacted.c0=-2390'
expect_error "detonation.point: give exactly one of 'point' or 'plane: {at, normal}'" "$ROOT/problems/sph_tnt_slab.yaml" --set 'detonation.plane={at: [0.0], normal: [1]}'
T="$ROOT/problems/sph_tunnel_blast.yaml"
expect_error "materials[0].eos.loading: row 3: the first column must increase (1873.8 after 1873.8)" "$T" --set 'materials.0.eos.loading.3=[1873.8, 29.15e6]'
expect_error "materials[0].eos.sound_speed: row 0: expected a positive value, got -265.2" "$T" --set 'materials.0.eos.sound_speed.0=[1674.0, -265.2]'
expect_error "materials[0].strength.shear_modulus_table: give exactly one of the material's 'shear_modulus' or 'strength.shear_modulus_table'" "$T" --set 'materials.0.shear_modulus=1.0e8'
expect_error "materials[1].strength: the HJC model needs both 'eos: {type: hjc}' and 'strength: {model: hjc}'" "$T" --set 'materials.1.strength={model: j2}'
expect_error "materials[1].hjc.P_lock: must exceed P_crush" "$T" --set 'materials.1.hjc={P_lock: 1.0e6}'
expect_error "regions[1].ring.outer_radius: must exceed inner_radius" "$T" --set 'regions.1.ring.inner_radius=3.5'
expect_error "regions[0].box: give exactly one of 'box', 'ring' or 'file'" "$T" --set 'regions.0.ring={center: [0, 0], inner_radius: 1, outer_radius: 2}'
expect_error "regions[0].energy: this equation of state does not depend on the internal energy" "$T" --set 'regions.0.energy=1.0'
expect_error "interface.n2: must be smaller than n1" "$T" --set 'interface={penalty_pressure: 1.0e6, n1: 6, n2: 12}'
expect_error "boundary[0].blast: particle at (-0.375, -0.125, 0): Kingery-Bulmash: scaled distance" "$T" --set 'boundary.0.blast.near_field=error'
# One materials list, each analysis takes its part; staged runs.
expect_error "materials[0].eos: analysis sph needs an equation of state" "$S" --set 'materials.0={name: gas}'
expect_error "materials[0].bond: analysis peridynamics needs bond parameters" "$B" --set 'materials.0={name: concrete, E: 30.0e9, density: 2400}'
# Staged runs: every link error names its key before anything runs.
G="$ROOT/problems/staged_strip_blast.yaml"
expect_error "stages[1].from: unknown stage 'nothing' (earlier stages: preload)" "$G" --set 'stages.1.from=nothing'
expect_error "stages[1].hold: the condition 'symmetry' of stage 'preload' is neither held nor released" "$G" --set 'stages.1.hold=[pull]'
expect_error "stages[1].hold: stage 'preload' has no condition 'jack'" "$G" --set 'stages.1.hold=[pull, symmetry, jack]'
expect_error "stages[1].release: 'pull' is held and released" "$G" --set 'stages.1.release=[pull]'
expect_error "model: analysis sph takes model.type uniaxial_strain, plane_strain or solid_3d" "$G" --set 'model.type=plane_stress'
expect_error "stages[1].mirror[0].axis" "$G" --set 'stages.1.mirror=[{axis: w}]'
expect_error "stages[1].regions[0].spacing" "$G" --set 'stages.1.regions.0.spacing=-1'
expect_error "stages[1].settle.damping" "$G" --set 'stages.1.settle={time: 1.0e-4}'
printf 'name: x\nanalysis: staged\nmodel: {type: plane_stress}\nmaterials: [{name: m, E: 1.0e9, nu: 0.3, density: 1000, bond: {law: pmb, critical_stretch: 0.01}, plasticity: {yield_stress: 1.0e6, hardening: perfect}}]\ngeometry: {rectangle: {origin: [0, 0], size: [1, 1]}}\nstages:\n  - {name: a, analysis: elastoplastic_static, discretisation: {spacing: 0.25}, boundary: [{name: b, edges: bottom, displacement: {x: 0, y: 0}}], steps: [{name: s, load_factor: 1, increments: 1}]}\n  - {name: i, analysis: peridynamics, from: a, hold: [b], discretisation: {spacing: 0.05, horizon: 3}, time: {end: 1.0e-6}}\n' > "$WORK/staged_pd.yaml"
expect_error "materials[0].plasticity: a plastic preload (plastic strain, hardening) cannot start a peridynamic stage" "$WORK/staged_pd.yaml"
expect_error "materials[0].nu: bond-based peridynamics in plane stress has Poisson's ratio 0.3333333333" "$WORK/staged_pd.yaml" --set 'materials.0.plasticity=null'
expect_error "stages[1].hold" "$WORK/staged_pd.yaml" --set 'stages.1.hold=[]' --set 'materials.0.plasticity=null' --set 'materials.0.nu=0.3333333333333333'
ELASTIC_PD=(--set 'materials.0.plasticity=null' --set 'materials.0.nu=0.3333333333333333')
expect_error "stages[1].settle: a peridynamic stage starts from its own static equilibrium" "$WORK/staged_pd.yaml" "${ELASTIC_PD[@]}" --set 'stages.1.settle={time: 1.0e-6, damping: 1.0}'
# A material region's law reaches the peridynamic stage as the body's own does.
TWO='materials=[{name: m, E: 1.0e9, nu: 0.3333333333333333, density: 1000, bond: {law: pmb, critical_stretch: 0.01}}, {name: soft, E: 1.0e8, nu: 0.3333333333333333, density: 1000, plasticity: {yield_stress: 1.0e5, hardening: perfect}}]'
REGION=(--set "$TWO" --set 'stages.0.material=m' --set 'stages.1.material=m' --set 'stages.0.material_regions=[{material: soft, box: [[0, 0], [0.5, 0.5]]}]')
expect_error "materials[1].plasticity: a plastic preload (plastic strain, hardening) cannot start a peridynamic stage" "$WORK/staged_pd.yaml" "${REGION[@]}"
expect_error "materials[1].nu: bond-based peridynamics in plane stress has Poisson's ratio" "$WORK/staged_pd.yaml" "${REGION[@]}" --set 'materials.1.plasticity=null' --set 'materials.1.nu=0.25'
# A 3D preload: what its layers of particles cannot hold is refused before anything runs.
C="$ROOT/problems/staged_column_blast.yaml"
expect_error "stages[1].hold: 'base' holds 2 of the 3 displacement components" "$C" --set 'stages.0.boundary.0.displacement={x: 0, y: 0}'
expect_error "stages[1].hold: SPH holds gravity, not a uniform body force: release 'body_force'" "$C" --set 'stages.0.body_force=[0, 0, -1.0e5]' --set 'stages.1.hold=[base, axial_load, body_force]'
expect_error "stages[1].hold: stage 'service' has no condition 'grip' (its conditions: base, axial_load)" "$C" --set 'stages.1.hold=[grip]'
printf 'name: x\nanalysis: staged\nmodel: {type: solid_3d}\nmaterials: [{name: m, E: 1.0e9, nu: 0.25, density: 1000, bond: {law: pmb}}]\ngeometry: {box: {origin: [0, 0, 0], size: [1, 1, 1]}}\nstages:\n  - {name: a, analysis: elastoplastic_static, discretisation: {method: fem, spacing: 0.5}, boundary: [{name: b, faces: back, displacement: {x: 0, y: 0, z: 0}}], steps: [{name: s, load_factor: 1, increments: 1}]}\n  - {name: i, analysis: peridynamics, from: a, hold: [b], discretisation: {spacing: 0.1, horizon: 3}, time: {end: 1.0e-6}}\n' > "$WORK/staged_pd_3d.yaml"
"$MF" check "$WORK/staged_pd_3d.yaml" > /dev/null
expect_error "stages[1].transfer: equilibrium: newton solves plane peridynamic bodies" "$WORK/staged_pd_3d.yaml" --set 'stages.1.transfer={equilibrium: newton}'
expect_error "materials[0].nu: bond-based peridynamics in this model has Poisson's ratio 0.25" "$WORK/staged_pd_3d.yaml" --set 'materials.0.nu=0.3'
# Slips a reader of YAML lets through, values that overflow, and keys or values that would break
# the message's line.
sed 's/{name: steel, E: 2.0e5, nu: 0.1}/{name: steel, E: 2.0e5, nu: 0.1, E: -1}/' "$P" > "$WORK/duplicate.yaml"
expect_error "materials[0].E: given twice" "$WORK/duplicate.yaml"
expect_error "--set boundary.99999999999999999999.name: index 99999999999999999999 is out of range" "$P" --set boundary.99999999999999999999.name=x
expect_error "geometry.rectangle.origin: lies too far from 0 for a body of this size" "$P" --set 'geometry.rectangle.origin=[1e30, 0]'
expect_error "name: a name of at most 64 characters, got 200" "$P" --set "name=$(printf 'x%.0s' {1..200})"
printf 'name: "a\0b"\n' > "$WORK/nul.yaml"; grep -v '^name:' "$P" >> "$WORK/nul.yaml"
expect_error "name: expected a name of letters, digits, '_' or '-', got 'a\\x00b'" "$WORK/nul.yaml"
# Error-driven refinement: its keys, and where it does not apply.
expect_error "discretisation.adapt.target: is a relative error: expected a value below 1, got 2" "$P" --set discretisation.adapt.target=2
expect_error "discretisation.adapt.fraction: is a share of the estimated error: expected (0, 1], got 1.5" "$P" --set discretisation.adapt.fraction=1.5
expect_error "discretisation.adapt.passes: expected an integer from 1 to 20, got 0" "$P" --set discretisation.adapt.passes=0
expect_error "discretisation.adapt.max_nodes: nodes of the refined cloud: about" "$P" --set discretisation.adapt.max_nodes=1e12
expect_error "discretisation.adapt.pace: unknown key" "$P" --set discretisation.adapt.pace=1
expect_error "discretisation.adapt: expected on, off or a map of keys, got 3" "$P" --set discretisation.adapt=3
expect_error "discretisation.adapt: error-driven refinement places meshfree nodes: it needs method: meshfree" "$P" --set discretisation.method=fem --set discretisation.adapt.target=0.1
expect_error "discretisation.adapt: error-driven refinement is made for plane bodies, not for this model" "$ROOT/problems/block_uniaxial_3d.yaml" --set discretisation.adapt.target=0.1
expect_error "stages[0].discretisation.adapt: a stage's cloud is not adapted" "$ROOT/problems/staged_strip_blast.yaml" --set stages.0.discretisation.adapt.target=0.1
# Refinement between increments: only where there are increments, without pilots or checkpoints.
expect_error "discretisation.adapt.every: refines between the increments of elastoplastic_static; an elastic_static solve has none" "$P" --set discretisation.adapt.every=2
expect_error "discretisation.adapt.every: expected an integer from 0 to 1000000, got -1" "$ROOT/problems/cook_membrane.yaml" --set discretisation.adapt.every=-1
expect_error "discretisation.adapt.pilot_increments: there are no pilot solves when the cloud is refined during the analysis (every: 2)" "$ROOT/problems/cook_membrane.yaml" --set "discretisation.adapt={every: 2, pilot_increments: 3}"
expect_error "output.checkpoint_every: a run whose cloud is refined during the analysis (discretisation.adapt.every) writes no checkpoints: 0 or leave it out" "$ROOT/problems/cook_membrane.yaml" --set discretisation.adapt.every=2 --set output.checkpoint_every=1
expect_error "stages[0].discretisation.adapt: a stage's cloud is not adapted" "$ROOT/problems/staged_strip_blast.yaml" --set stages.0.discretisation.adapt.every=2
expect_error "discretisation.refinement[0].box: lies outside the body" "$P" --set 'discretisation.refinement=[{box: [[5, 5], [6, 6]], spacing: 0.02}]'
# A solid's refinement box gives z or spans the depth; a range along z off the body refines nothing.
expect_error "discretisation.refinement[0].box: its range along z, [5, 6], misses the body's, [0, 2]: it refines nothing" "$ROOT/problems/block_uniaxial_3d.yaml" --set 'discretisation.refinement=[{box: [[0, 0, 5], [1, 1, 6]], spacing: 0.1}]'
expect_error "discretisation.refinement[0].box[0]: expected a list of 2 numbers, got [0, 0, 0]" "$P" --set 'discretisation.refinement=[{box: [[0, 0, 0], [1, 1, 1]], spacing: 0.02}]'
# A refinement box reaching far outside the body is clipped to it (node generation walked it whole).
if timeout 20 "$MF" check "$P" --set 'discretisation.refinement=[{box: [[-1e9, -1e9], [1e9, 1e9]], spacing: 0.02}]' >/dev/null 2>&1; then
  echo "ok: a refinement box far outside the body is clipped"
else
  echo "FAIL: a refinement box far outside the body"; fails=$((fails+1))
fi
R="$ROOT/problems/pd_rc_cantilever.yaml"
expect_error "regions[0]: holds no particle of the body" "$R" --set 'regions.0.box=[[5, 5, 5], [6, 6, 6]]'
W="$ROOT/problems/pd_cantilever_random_load.yaml"
{ echo "index,value"; echo "0,0"; echo "1,1e999"; } > "$WORK/overflow.csv"
expect_error "overflow.csv:3: not a finite number: '1,1e999'" "$W" --set "functions.0.file=$WORK/overflow.csv"
# Discretisations that would not fit in memory, refused before anything is allocated (an SPH
# spacing of 1e-9 grew to 24 GB and was killed by the kernel).
expect_error "regions[0].spacing: particles in this region: about" "$ROOT/problems/sph_plate_blast.yaml" --set regions.0.spacing=1e-9
expect_error "discretisation.spacing: nodes over the body: about" "$P" --set discretisation.spacing=1e-7
expect_error "discretisation.spacing: particles in the body: about" "$ROOT/problems/pd_pmma_beam_impact.yaml" --set discretisation.spacing=1e-9
# Results that overflow a double, or a solve that did not solve the system, are failures with
# their cause, never a "completed" run.
O="$ROOT/problems/ode_1d.yaml"
expect_run_failure "problem_1d: the source f = -y'' is not finite at x = " "$O" --set problem_1d.sine_amplitude=1e308
expect_run_failure "problem_1d: the solution's norms overflow a double" "$O" --set problem_1d.linear=1e300
# PETSc reports CONVERGED_ITS for preonly without a preconditioner (x = b); the true residual,
# 2e5 here, decides.
rm -rf "$WORK/out"
msg="$("$MF" run "$P" --out "$WORK/out" -- -pc_type none 2>&1 >/dev/null)"; rc=$?
if [ $rc -eq 1 ] && grep -qF "linear solve did not solve the system: relative residual" <<<"$msg" &&
   failed_only; then
  echo "ok: a linear solve with a large true residual fails"
else
  echo "FAIL (exit $rc, '$msg'): -pc_type none"; fails=$((fails+1))
fi
# A PETSc option nothing read (a typo) is reported; the run itself goes on.
rm -rf "$WORK/out"
msg="$("$MF" run "$P" --out "$WORK/out" -- -ksp_typo gmres 2>&1 >/dev/null)"; rc=$?
if [ $rc -eq 0 ] && grep -qF "PETSc option -ksp_typo gmres was given but not used by this run" <<<"$msg"; then
  echo "ok: an unused PETSc option is reported"
else
  echo "FAIL (exit $rc, '$msg'): -ksp_typo"; fails=$((fails+1))
fi
# usage errors
"$MF" 2>/dev/null; [ $? -eq 2 ] && echo "ok: no command -> exit 2" || { echo "FAIL: no command"; fails=$((fails+1)); }
"$MF" check "$P" >/dev/null || { echo "FAIL: check on a good problem"; fails=$((fails+1)); }
[ $fails -eq 0 ] && echo "all bad inputs rejected" || exit 1
