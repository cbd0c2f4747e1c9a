#!/usr/bin/python3
"""fields.xmf is read by an independent XDMF reader (meshio's time-series reader, which follows
the XDMF3 layout ParaView reads): every step, point and field comes back with the values in
fields.h5.   tests/xdmf_readable.py MESHFREE PROBLEM.yaml"""
import subprocess
import sys
import tempfile

import h5py
import meshio
import numpy as np

meshfree, problem = sys.argv[1], sys.argv[2]
with tempfile.TemporaryDirectory() as out:
    subprocess.run([meshfree, "run", problem, "--out", out], check=True, stdout=subprocess.DEVNULL)
    with meshio.xdmf.TimeSeriesReader(f"{out}/fields.xmf") as reader, h5py.File(f"{out}/fields.h5") as h5:
        points, cells = reader.read_points_cells()
        assert np.array_equal(points, h5["geometry/coordinates"][...])
        assert cells[0].type == "vertex" and len(cells[0].data) == len(points)
        assert reader.num_steps >= 1
        for k in range(reader.num_steps):
            time, point_data, _ = reader.read_data(k)
            group = h5[f"step_{k:06d}"]
            assert set(point_data) == set(group), (set(point_data), set(group))
            for name, values in point_data.items():
                assert np.array_equal(values, group[name][...]), name
        print(f"fields.xmf: {len(points)} points, {reader.num_steps} step(s), fields {sorted(point_data)}")
