#!/usr/bin/python3
"""fields.xmf (and gauss_points.xmf, display_mesh.xmf, error_indicator.xmf) are read by an independent XDMF reader (meshio's time-series
reader, which follows the XDMF3 layout ParaView reads): every step, point, cell and field comes
back with the values in the HDF5 file.

    tests/cli/xdmf_readable.py MESHFREE PROBLEM.yaml [--set key=value ...]"""
import subprocess
import sys
import tempfile

import h5py
import meshio
import numpy as np

meshfree, problem, overrides = sys.argv[1], sys.argv[2], sys.argv[3:]
with tempfile.TemporaryDirectory() as out:
    subprocess.run([meshfree, "run", problem, "--out", out] + overrides, check=True,
                   stdout=subprocess.DEVNULL)
    for stem in ("fields", "gauss_points", "display_mesh", "error_indicator"):
        try:
            h5 = h5py.File(f"{out}/{stem}.h5")
        except FileNotFoundError:
            assert stem in ("gauss_points", "error_indicator"), f"{stem}.h5 is missing"
            continue
        with meshio.xdmf.TimeSeriesReader(f"{out}/{stem}.xmf") as reader, h5:
            points, cells = reader.read_points_cells()
            assert np.array_equal(points, h5["geometry/coordinates"][...])
            if "cells" in h5["geometry"]:  # finite elements: the element connectivity
                assert np.array_equal(cells[0].data, h5["geometry/cells"][...])
            else:  # meshfree nodes, Gauss points: one vertex per point
                assert cells[0].type == "vertex" and len(cells[0].data) == len(points)
            assert reader.num_steps >= 1
            for k in range(reader.num_steps):
                time, point_data, _ = reader.read_data(k)
                group = h5[f"step_{k:06d}"]
                assert set(point_data) == set(group), (set(point_data), set(group))
                for name, values in point_data.items():
                    assert np.array_equal(values, group[name][...]), name
            print(f"{stem}.xmf: {len(points)} points, {cells[0].type} cells, {reader.num_steps} "
                  f"step(s), fields {sorted(point_data)}")
