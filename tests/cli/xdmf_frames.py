#!/usr/bin/python3
"""Every frame of every explicit and staged problem in problems/ is whole in ParaView, and of an
implicit run whose cloud is refined between increments (its series change their points). Each runs
briefly, its field interval half its end time (a periodic field step falls on the end, where the
run also writes its final state), and each .xmf it writes must have:

- one grid per time, the times increasing (ParaView's XDMF readers drop one of two grids with the
  same time and show the other empty);
- no empty grid, and every DataItem's dimensions those of the HDF5 dataset it names;
- in an explicit run's frames, the deformed configuration as the geometry: the points at
  reference_position + displacement;
- with ParaView's Python (pvpython, under xvfb-run when there) installed: every time of the series
  in each of ParaView's three XDMF readers, with every point and every array at each time.
  Without it that part is skipped, with a line saying so.

    tests/cli/xdmf_frames.py MESHFREE ROOT [PROBLEM ...]   (problem names; all of them by default)
    tests/cli/xdmf_frames.py --check DIR                   (the .xmf files of a run's folder, no ParaView)
"""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile
import xml.etree.ElementTree as ET

import h5py
import numpy as np
import yaml

EXPLICIT = ("peridynamics", "sph", "staged")  # analyses whose fields.xmf is an explicit run's
FRACTION = 0.01  # of each run's end time: a few steps, enough for three field steps


def shortened(problem):
    """--set arguments that end the explicit run (a staged run's second stage) early, at twice
    its field interval, and shorten a staged run's settle likewise."""
    spec = yaml.safe_load(open(problem))
    if spec["analysis"] == "staged":
        stage, prefix = spec["stages"][1], "stages.1."
    else:
        stage, prefix = spec, ""
    end = float("%.6g" % (FRACTION * float(stage["time"]["end"])))
    sets = [f"{prefix}time.end={end:.6g}", f"{prefix}output.fields_interval={end / 2:.6g}"]
    if "settle" in stage:
        sets.append(f"{prefix}settle.time={FRACTION * float(stage['settle']['time']):.6g}")
    return [a for s in sets for a in ("--set", s)]


def dimensions(item):
    return tuple(int(d) for d in item.get("Dimensions").split())


def dataset(folder, item, files):
    """The HDF5 dataset a DataItem names ('fields.h5:/step_000001/velocity')."""
    name, path = item.text.strip().split(":", 1)
    if name not in files:
        files[name] = h5py.File(os.path.join(folder, name), "r")
    return files[name][path]


def check_series(xmf, explicit):
    """Checks one .xmf against its HDF5 file; returns what ParaView should show at each time."""
    folder, files = os.path.dirname(xmf), {}
    collection = ET.parse(xmf).getroot().find("Domain/Grid")
    assert collection.get("CollectionType") == "Temporal", f"{xmf}: not a time series"
    grids = collection.findall("Grid")
    times = [float(grid.find("Time").get("Value")) for grid in grids]
    assert times, f"{xmf}: no grid"
    assert all(a < b for a, b in zip(times, times[1:])), f"{xmf}: times not distinct and " \
        f"increasing: {times}"
    frames = []
    try:
        for grid, time in zip(grids, times):
            where = f"{os.path.basename(xmf)} {grid.get('Name')}"
            for item in grid.iter("DataItem"):
                shape = dataset(folder, item, files).shape
                assert dimensions(item) == shape, f"{where}: {item.text} is {shape}, the .xmf " \
                    f"says {dimensions(item)}"
            points = dimensions(grid.find("Geometry/DataItem"))[0]
            cells = int(grid.find("Topology").get("NumberOfElements"))
            assert points > 0 and cells > 0, f"{where}: an empty grid"
            arrays = {a.get("Name"): a.find("DataItem") for a in grid.findall("Attribute")}
            if explicit:
                deformed(where, grid, arrays, folder, files)
            frames.append({"time": time, "points": points, "arrays": sorted(arrays)})
    finally:
        for f in files.values():
            f.close()
    return frames


def deformed(where, grid, arrays, folder, files):
    """An explicit run's frame: the points are the reference positions moved by the
    displacement."""
    assert "reference_position" in arrays, f"{where}: no reference_position"
    x = dataset(folder, grid.find("Geometry/DataItem"), files)[...]
    X = dataset(folder, arrays["reference_position"], files)[...]
    u = dataset(folder, arrays["displacement"], files)[...]
    assert np.array_equal(x, X + u), f"{where}: the points are not X + u"


PVPYTHON_SCRIPT = r"""
import json, sys
import paraview.simple as pv
READERS = {"XDMFReader": "FileNames", "Xdmf3ReaderS": "FileName", "Xdmf3ReaderT": "FileName"}
def check(path, frames, reader, key):
    source = getattr(pv, reader)(**{key: [path]})
    expected = [f["time"] for f in frames]
    times = list(source.TimestepValues) if len(frames) > 1 else expected
    assert len(times) == len(expected) and all(
        abs(a - b) <= 1e-9 * max(abs(b), 1e-300) for a, b in zip(times, expected)), (
        "%s %s: times %s, the .xmf has %s" % (path, reader, times, expected))
    for t, frame in zip(times, frames):
        source.UpdatePipeline(t)
        points = source.GetDataInformation().GetNumberOfPoints()
        arrays = sorted(source.PointData.keys())
        assert points == frame["points"], "%s %s at t = %g: %d points, the .xmf has %d" % (
            path, reader, t, points, frame["points"])
        assert arrays == frame["arrays"], "%s %s at t = %g: arrays %s, the .xmf has %s" % (
            path, reader, t, arrays, frame["arrays"])
    pv.Delete(source)
for path, frames in json.load(open(sys.argv[1])):
    for reader, key in READERS.items():
        check(path, frames, reader, key)
print("ok")
"""


def pvpython_command():
    """pvpython, under xvfb-run where there is one and no display; None without ParaView."""
    pvpython = shutil.which("pvpython")
    if not pvpython:
        return None
    if not os.environ.get("DISPLAY") and shutil.which("xvfb-run"):
        return ["xvfb-run", "-a", pvpython]
    return [pvpython]


def paraview_check(pvpython, series, work):
    """Every series [(xmf, frames)] in ParaView's three XDMF readers, in one pvpython."""
    script, expected = os.path.join(work, "check.py"), os.path.join(work, "frames.json")
    open(script, "w").write(PVPYTHON_SCRIPT)
    json.dump(series, open(expected, "w"))
    run = subprocess.run(pvpython + [script, expected], capture_output=True, text=True)
    assert run.returncode == 0 and run.stdout.strip().endswith("ok"), \
        f"ParaView:\n{run.stdout}\n{run.stderr}"
    print(f"ParaView's XDMFReader, Xdmf3ReaderS and Xdmf3ReaderT: every point and array of "
          f"{sum(len(frames) for _, frames in series)} frames in {len(series)} series")


def check_folder(folder, explicit_series):
    """Every .xmf of a run's folder (`explicit_series`: the stems of explicit runs' series);
    returns [(xmf, frames)]."""
    paths = sorted(glob.glob(os.path.join(folder, "*.xmf")))
    assert paths, f"{folder}: no .xmf"
    series = []
    for xmf in paths:
        stem = os.path.basename(xmf)[:-4]
        frames = check_series(xmf, stem in explicit_series)
        series.append((xmf, frames))
        print(f"  {os.path.basename(xmf)}: {len(frames)} frames of {frames[-1]['points']} points")
    return series


def explicit_problems(root):
    names = []
    for path in sorted(glob.glob(os.path.join(root, "problems", "*.yaml"))):
        analysis = yaml.safe_load(open(path)).get("analysis")
        if analysis in EXPLICIT:
            names.append(os.path.basename(path)[:-5])
    return names


# Cook's membrane on a coarse cloud refined twice at the second of its four increments.
REFINED = ("cook_membrane", ["--set", "discretisation.spacing=4", "--set",
                             "discretisation.adapt={target: 0.01, passes: 3, every: 2}",
                             "--set", "steps.0.increments=4"])


def refined_run(meshfree, root, work):
    """The implicit series of a run refined between increments: whole, and on more points at the
    end than at the start."""
    name, sets = REFINED
    out = os.path.join(work, name + "_refined")
    run = subprocess.run([meshfree, "run", os.path.join(root, "problems", name + ".yaml"),
                          "--out", out] + sets, capture_output=True, text=True)
    assert run.returncode == 0, f"{name}: exit {run.returncode}\n{run.stderr[-2000:]}"
    print(name, "refined between increments")
    series = check_folder(out, [])
    for xmf, frames in series:
        if os.path.basename(xmf) in ("fields.xmf", "gauss_points.xmf", "display_mesh.xmf"):
            assert frames[-1]["points"] > frames[0]["points"], \
                f"{xmf}: the same points before and after refinement"
    return series


def main():
    if sys.argv[1] == "--check":
        folder = sys.argv[2]
        analysis = json.load(open(os.path.join(folder, "summary.json")))["analysis"]
        check_folder(folder, ["fields"] if analysis in EXPLICIT else [])
        return
    meshfree, root = sys.argv[1], sys.argv[2]
    names = sys.argv[3:] or explicit_problems(root)
    assert names, f"no explicit or staged problem in {root}/problems"
    pvpython = pvpython_command()
    if not pvpython:
        print("pvpython not found: ParaView's own reading of the frames is skipped "
              "(apt-get install paraview python3-paraview xvfb)")
    with tempfile.TemporaryDirectory() as work:
        series = []
        for name in names:
            problem = os.path.join(root, "problems", name + ".yaml")
            out = os.path.join(work, name)
            run = subprocess.run([meshfree, "run", problem, "--out", out] + shortened(problem),
                                 capture_output=True, text=True)
            assert run.returncode == 0, f"{name}: exit {run.returncode}\n{run.stderr[-2000:]}"
            print(name)
            # A staged run's explicit stage writes fields.xmf; its implicit preload, a prefix.
            series += check_folder(out, ["fields"])
        if not sys.argv[3:]:
            series += refined_run(meshfree, root, work)
        if pvpython:
            paraview_check(pvpython, series, work)


if __name__ == "__main__":
    main()
