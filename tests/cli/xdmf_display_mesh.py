#!/usr/bin/python3
"""The display mesh of implicit runs (display_mesh.h5/.xmf): triangles over the body with u^h,
stresses and the equivalent plastic strain at their vertices.

- On fields the discretisation reproduces, the vertex values are the exact ones: the linear
  patch test (elastic; meshfree with VCI, whose Galerkin solution is the linear field to
  round-off, on the node lattice's grid and on the graded cloud's own triangles around a
  refinement box, and finite elements T3, Q4, Q8), where u = u0 + G x and the stress is C sym(G)
  everywhere; and the bar in uniaxial stress stretched into the plastic range (elastoplastic),
  whose state is homogeneous (meshfree with VCI: the Gauss points agree to 2e-10 of the stress,
  against 1e-3 without): at every vertex of every frame the stresses and plastic strain
  are those of the Gauss points, all equal, and u^h is linear in x and y.
- A finite-element display mesh carries the nodal values themselves; a meshfree one of a body
  with a hole (the perforated strip) covers it, through the nodes. A hole with three nodes on it
  is too coarse for the nodes' triangles to follow: gmsh meshes that body, and says so; with
  more nodes on it the nodes' triangles are used again.
- Every .xmf of each run is whole (tests/cli/xdmf_frames.py's checks: one grid per time, times
  increasing, no empty grid, every DataItem's dimensions those of its HDF5 dataset); the display
  mesh is a grid of triangles whose times are those of fields.xmf.
- With ParaView's Python installed, its three XDMF readers see every point and array of every
  frame, and the display mesh's triangles as cells. Skipped otherwise, with a line saying so.

    tests/cli/xdmf_display_mesh.py MESHFREE ROOT
"""
import json
import os
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import xdmf_frames  # noqa: E402

# The patch test's boundary held by a stiff penalty (1e13 against E = 1; the penalty's own error
# falls as its inverse: 1.8e-7 at the file's 1e10). A wrong transfer or interpolation errs by
# 1e-3 or more.
STIFF = "boundary.0.penalty=1e13"
TOL = 1e-8

PATCH = {"u0": np.array([0.01, -0.02]), "G": np.array([[0.1, 0.05], [-0.03, 0.2]]),
         "E": 1.0, "nu": 0.25}


def run(meshfree, problem, out, sets):
    args = [a for s in sets for a in ("--set", s)]
    r = subprocess.run([meshfree, "run", problem, "--out", out] + args, capture_output=True,
                       text=True)
    assert r.returncode == 0, f"{problem} {sets}: exit {r.returncode}\n{r.stderr[-2000:]}"


def frames_of(out):
    """[(time, vertices, triangles, {array: values})] of display_mesh.xmf."""
    xmf = os.path.join(out, "display_mesh.xmf")
    root = ET.parse(xmf).getroot()
    frames = []
    with h5py.File(os.path.join(out, "display_mesh.h5"), "r") as h5:
        for grid in root.find("Domain/Grid").findall("Grid"):
            topo = grid.find("Topology")
            assert topo.get("TopologyType") == "Triangle", f"{xmf}: {topo.get('TopologyType')}"
            read = lambda item: h5[item.text.strip().split(":", 1)[1]][...]  # noqa: E731
            x = read(grid.find("Geometry/DataItem"))
            tri = read(topo.find("DataItem"))
            arrays = {a.get("Name"): read(a.find("DataItem")) for a in grid.findall("Attribute")}
            frames.append((float(grid.find("Time").get("Value")), x, tri, arrays))
    return frames


def times_of(xmf):
    grids = ET.parse(xmf).getroot().find("Domain/Grid").findall("Grid")
    return [float(g.find("Time").get("Value")) for g in grids]


def relative(a, b):
    return np.max(np.abs(a - b)) / max(np.max(np.abs(b)), 1e-300)


def check_triangles(x, tri, area):
    """Triangles name existing vertices, turn counter-clockwise and cover the body."""
    assert tri.min() >= 0 and tri.max() < len(x)
    p = x[tri][:, :, :2]
    a = 0.5 * ((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
               - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    assert (a > 0).all(), f"{np.sum(a <= 0)} triangles not counter-clockwise"
    assert area is None or abs(a.sum() - area) <= 1e-9 * area, \
        f"triangles cover {a.sum()}, the body {area}"


def patch_test(meshfree, root, work, label, sets):
    out = os.path.join(work, "patch_" + label)
    run(meshfree, os.path.join(root, "problems", "patch_test.yaml"), out, [STIFF] + sets)
    [(time, x, tri, arrays)] = frames_of(out)
    check_triangles(x, tri, 1.0)
    u_exact = PATCH["u0"] + x[:, :2] @ PATCH["G"].T
    G, E, nu = PATCH["G"], PATCH["E"], PATCH["nu"]
    exx, eyy, gxy = G[0, 0], G[1, 1], G[0, 1] + G[1, 0]
    s = {"stress_xx": E / (1 - nu ** 2) * (exx + nu * eyy),
         "stress_yy": E / (1 - nu ** 2) * (eyy + nu * exx),
         "stress_xy": E / (2 * (1 + nu)) * gxy, "stress_zz": 0.0}
    s["von_mises"] = np.sqrt(s["stress_xx"] ** 2 - s["stress_xx"] * s["stress_yy"]
                             + s["stress_yy"] ** 2 + 3 * s["stress_xy"] ** 2)
    errors = {"u": relative(arrays["displacement"][:, :2], u_exact)}
    assert np.all(arrays["displacement"][:, 2] == 0.0)
    scale = max(abs(v) for v in s.values())
    for name, value in s.items():
        errors[name] = np.max(np.abs(arrays[name] - value)) / scale
    assert np.all(arrays["plastic_strain"] == 0.0)
    worst = max(errors, key=errors.get)
    print(f"patch test, {label}: {len(x)} vertices, {len(tri)} triangles; largest relative "
          f"error {errors[worst]:.2e} ({worst})")
    assert errors[worst] <= TOL, f"patch test {label}: {errors}"
    if "fem" in label:  # a finite-element display mesh is the mesh: its u^h, the nodal values
        with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
            assert np.array_equal(f["geometry/coordinates"][...], x)
            # fields.h5 evaluates the elements' shape functions at each node: 1 to round-off
            assert relative(arrays["displacement"], f["step_000000/displacement"][...]) <= 1e-12
    return out


def holed_body(meshfree, root, work):
    """The perforated strip (a hole, a refinement box), meshfree: the triangles cover the body and
    the slivers between the hole's arc and its chords, at about the node count."""
    out = os.path.join(work, "strip")
    run(meshfree, os.path.join(root, "problems", "perforated_strip.yaml"), out,
        ["steps=[{name: pull, load_factor: 0.05, increments: 2}]"])
    time, x, tri, arrays = frames_of(out)[-1]
    area = 10 * 18 - np.pi * 25 / 4
    check_triangles(x, tri, None)
    p = x[tri][:, :, :2]
    covered = 0.5 * np.sum((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                           - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        nodes = len(f["geometry/coordinates"])
    r = np.hypot(x[:, 0], x[:, 1])
    print(f"perforated strip: {len(x)} vertices for {nodes} nodes, triangles cover "
          f"{covered / area:.5f} of the body, nearest vertex to the hole centre at r = "
          f"{r.min():.6f}")
    assert 1.0 < covered / area < 1.001, covered / area  # chords cut into the hole
    assert r.min() >= 5 - 1e-9 and 0.5 < len(x) / nodes < 2
    assert np.all(np.isfinite(arrays["von_mises"])) and arrays["von_mises"].max() > 0
    return out


def sparse_hole(meshfree, root, work, spacing):
    """The unit square with a hole of radius 0.2 in its middle: at spacing 0.5 three nodes lie on
    the hole, the nodes' triangles would cut across it and gmsh meshes the body; at 0.25 the
    nodes' own triangles follow it. Either covers the body up to chords of the hole."""
    out = os.path.join(work, f"sparse_hole_{spacing}")
    args = ["--set", f"discretisation.spacing={spacing}",
            "--set", "geometry.holes=[{center: [0.5, 0.5], radius: 0.2, name: hole}]"]
    r = subprocess.run([meshfree, "run", os.path.join(root, "problems", "patch_test.yaml"),
                        "--out", out] + args, capture_output=True, text=True)
    assert r.returncode == 0, f"sparse hole {spacing}: exit {r.returncode}\n{r.stderr[-2000:]}"
    by_gmsh = "the nodes' triangles do not follow the boundary; gmsh meshes it" in r.stdout
    time, x, tri, arrays = frames_of(out)[-1]
    check_triangles(x, tri, None)
    p = x[tri][:, :, :2]
    covered = 0.5 * np.sum((p[:, 1, 0] - p[:, 0, 0]) * (p[:, 2, 1] - p[:, 0, 1])
                           - (p[:, 2, 0] - p[:, 0, 0]) * (p[:, 1, 1] - p[:, 0, 1]))
    area = 1.0 - np.pi * 0.04
    r_min = np.min(np.hypot(x[:, 0] - 0.5, x[:, 1] - 0.5))
    with h5py.File(os.path.join(out, "fields.h5"), "r") as f:
        nodes = len(f["geometry/coordinates"])
    who = "gmsh's" if by_gmsh else "the nodes'"
    print(f"hole of radius 0.2 at spacing {spacing}: {who} triangles, {len(x)} vertices for {nodes} nodes, covering {covered / area:.4f} of the "
          f"body")
    assert by_gmsh == (spacing == 0.5), f"spacing {spacing}: gmsh used: {by_gmsh}"
    assert by_gmsh or len(x) == nodes
    # The chords of a hole cut into it: at most the hole's area less that of the inscribed
    # triangle (three points on the circle).
    assert 1.0 <= covered / area <= 1.0 + (np.pi - 3 * np.sqrt(3) / 4) * 0.04 / area, covered
    assert r_min >= 0.2 - 1e-9, r_min
    return out


def uniaxial_bar(meshfree, root, work, label, sets):
    """Stretched to 1% (10 increments, about 8 of them plastic); every second one written."""
    out = os.path.join(work, "bar_" + label)
    steps = ["steps=[{name: stretch, load_factor: 0.02, increments: 10}]",
             "output.fields_every=2"]
    run(meshfree, os.path.join(root, "problems", "bar_uniaxial_cyclic.yaml"), out, steps + sets)
    frames = frames_of(out)
    assert [f[0] for f in frames] == times_of(os.path.join(out, "fields.xmf"))
    gauss = h5py.File(os.path.join(out, "gauss_points.h5"), "r")
    steps_h5 = sorted(k for k in gauss if k.startswith("step_"))
    assert len(steps_h5) == len(frames)
    worst = 0.0
    for (time, x, tri, arrays), step in zip(frames, steps_h5):
        check_triangles(x, tri, 2.0)
        for name in ("stress_xx", "stress_yy", "stress_xy", "stress_zz", "von_mises",
                     "plastic_strain"):
            g = gauss[step][name][...]
            scale = max(np.max(np.abs(gauss[step]["von_mises"][...])), 1e-300)
            if name == "plastic_strain":
                scale = max(np.max(g), 1e-300)
            assert np.ptp(g) <= TOL * scale, f"{label} t = {time}: {name} not uniform"
            worst = max(worst, np.max(np.abs(arrays[name] - g.mean())) / scale)
        u = arrays["displacement"][:, :2]
        A = np.c_[np.ones(len(x)), x[:, :2]]
        fit = A @ np.linalg.lstsq(A, u, rcond=None)[0]
        worst = max(worst, relative(u, fit) if np.any(u) else 0.0)
    final = frames[-1][3]["plastic_strain"]
    assert final.min() > 1e-3, f"{label}: the bar did not yield ({final.min()})"
    print(f"uniaxial bar, {label}: {len(frames)} frames of {len(frames[-1][1])} vertices, final "
          f"plastic strain {final.mean():.4g}; largest relative departure from the Gauss points "
          f"and from a linear u {worst:.2e}")
    assert worst <= TOL, f"uniaxial bar {label}: {worst}"
    return out


def paraview_cells(pvpython, outs, work):
    """ParaView's readers make one cell per triangle of the display mesh."""
    script = os.path.join(work, "cells.py")
    open(script, "w").write(
        "import sys, paraview.simple as pv\n"
        "for path, cells in zip(sys.argv[1::2], sys.argv[2::2]):\n"
        "    for reader, key in (('XDMFReader', 'FileNames'), ('Xdmf3ReaderS', 'FileName')):\n"
        "        s = getattr(pv, reader)(**{key: [path]})\n"
        "        ts = s.TimestepValues\n"
        "        s.UpdatePipeline(max(ts) if hasattr(ts, '__len__') else ts or 0.0)\n"
        "        n = s.GetDataInformation().GetNumberOfCells()\n"
        "        assert n == int(cells), (path, reader, n, cells)\n"
        "print('ok')\n")
    args = []
    for out in outs:
        args += [os.path.join(out, "display_mesh.xmf"), str(len(frames_of(out)[-1][2]))]
    r = subprocess.run(pvpython + [script] + args, capture_output=True, text=True)
    assert r.returncode == 0 and r.stdout.strip().endswith("ok"), f"{r.stdout}\n{r.stderr}"
    print(f"ParaView: the triangles of {len(outs)} display meshes as cells")


def main():
    meshfree, root = sys.argv[1], sys.argv[2]
    with tempfile.TemporaryDirectory() as work:
        vci = "discretisation.quadrature.correction=vci"
        outs = [patch_test(meshfree, root, work, "meshfree VCI", [vci])]
        # A refinement box: the graded cloud's own triangles.
        outs.append(patch_test(meshfree, root, work, "meshfree VCI refined", [
            vci, "discretisation.refinement=[{box: [[0.3, 0.3], [0.6, 0.6]], spacing: 0.05}]"]))
        for element in ("t3", "q4", "q8"):
            outs.append(patch_test(meshfree, root, work, "fem " + element,
                                   ["discretisation.method=fem",
                                    "discretisation.fem.element=" + element]))
        outs.append(uniaxial_bar(meshfree, root, work, "meshfree VCI",
                                 ["discretisation.quadrature.correction=vci"]))
        outs.append(uniaxial_bar(meshfree, root, work, "fem q8",
                                 ["discretisation.method=fem", "discretisation.fem.element=q8"]))
        outs.append(holed_body(meshfree, root, work))
        outs += [sparse_hole(meshfree, root, work, spacing) for spacing in (0.5, 0.25)]
        series = []
        for out in outs:
            series += xdmf_frames.check_folder(out, [])
        pvpython = xdmf_frames.pvpython_command()
        if not pvpython:
            print("pvpython not found: ParaView's own reading of the display mesh is skipped")
            return
        xdmf_frames.paraview_check(pvpython, series, work)
        paraview_cells(pvpython, outs, work)


if __name__ == "__main__":
    main()
