#!/usr/bin/pvpython
"""The two ParaView images of docs/images/, remade from runs of the problems:

- strip_display_mesh.png: problems/perforated_strip.yaml at its last increment (v = 0.1 mm), on
  its display mesh (display_mesh.xmf), warped by the displacement x 20, in two panels: von Mises
  stress and the equivalent plastic strain, both filled contours;
- pmma_crack.png: problems/staged_pmma_impact.yaml's peridynamic stage at its end
  (t = 150 us, the whole run), the particles at their current positions coloured by damage.

    xvfb-run -a pvpython scripts/paraview_images.py [--meshfree build/meshfree] [--out docs/images]

About 35 s on 2 cores, most of it the two runs.
"""
import argparse
import os
import subprocess
import sys
import tempfile

import paraview.simple as pv

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
WARP = 20.0  # the strip's displacement is 0.1 mm on an 18 mm body
SPACING = 0.0005  # m, the PMMA plate's particle spacing


def run(meshfree, problem, out):
    subprocess.run([meshfree, "run", os.path.join(ROOT, "problems", problem), "--out", out],
                   check=True, stdout=subprocess.DEVNULL)


def last_time(source):
    times = source.TimestepValues  # a list, or one number for a single time
    return max(times) if hasattr(times, "__len__") else (times or 0.0)


def coloured(view, source, array, title, preset):
    shown = pv.Show(source, view)
    shown.SetRepresentationType("Surface")
    pv.ColorBy(shown, ("POINTS", array))
    shown.RescaleTransferFunctionToDataRange(True, False)
    lut = pv.GetColorTransferFunction(array)
    lut.ApplyPreset(preset, True)
    bar = pv.GetScalarBar(lut, view)
    bar.Title, bar.ComponentTitle = title, ""
    bar.Visibility = 1
    bar.TitleFontSize, bar.LabelFontSize = 16, 14
    bar.TitleColor = bar.LabelColor = [0, 0, 0]
    bar.WindowLocation = "Any Location"
    bar.Orientation = "Horizontal"
    bar.Position, bar.ScalarBarLength = [0.15, 0.03], 0.7
    return shown


def plane_view(size):
    view = pv.CreateView("RenderView")
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    view.UseColorPaletteForBackground = 0
    view.CameraParallelProjection = 1
    return view


def fit(view):
    view.CameraPosition, view.CameraFocalPoint, view.CameraViewUp = [0, 0, 1], [0, 0, 0], [0, 1, 0]
    view.ResetCamera(False)


def strip_image(folder, png):
    reader = pv.XDMFReader(FileNames=[os.path.join(folder, "display_mesh.xmf")])
    t = last_time(reader)
    warp = pv.WarpByVector(Input=reader, Vectors=["POINTS", "displacement"], ScaleFactor=WARP)
    layout = pv.CreateLayout("strip")
    views = []
    for array, title in (("von_mises", "von Mises (kgf/mm^2)"),
                         ("plastic_strain", "equivalent plastic strain")):
        view = plane_view([520, 640])
        view.ViewTime = t
        coloured(view, warp, array, title, "Turbo")
        fit(view)
        views.append(view)
    layout.SplitHorizontal(0, 0.5)
    layout.AssignView(1, views[0])
    layout.AssignView(2, views[1])
    layout.SetSize(1040, 640)
    pv.SaveScreenshot(png, layout, ImageResolution=[1040, 640], CompressionLevel="9")


def pmma_image(folder, png):
    reader = pv.XDMFReader(FileNames=[os.path.join(folder, "fields.xmf")])
    view = plane_view([900, 760])
    view.ViewTime = last_time(reader)
    shown = coloured(view, reader, "damage", "damage (broken bond fraction)", "Inferno (matplotlib)")
    shown.SetRepresentationType("Point Gaussian")
    shown.ShaderPreset = "Plain circle"
    shown.GaussianRadius = SPACING  # the particles touch: a filled plate, the crack open
    fit(view)
    pv.SaveScreenshot(png, view, ImageResolution=[900, 760], CompressionLevel="9")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--meshfree", default=os.path.join(ROOT, "build", "meshfree"))
    p.add_argument("--out", default=os.path.join(ROOT, "docs", "images"))
    a = p.parse_args()
    os.makedirs(a.out, exist_ok=True)
    with tempfile.TemporaryDirectory() as work:
        strip, pmma = os.path.join(work, "strip"), os.path.join(work, "pmma")
        run(a.meshfree, "perforated_strip.yaml", strip)
        strip_image(strip, os.path.join(a.out, "strip_display_mesh.png"))
        run(a.meshfree, "staged_pmma_impact.yaml", pmma)
        pmma_image(pmma, os.path.join(a.out, "pmma_crack.png"))
    for name in ("strip_display_mesh.png", "pmma_crack.png"):
        path = os.path.join(a.out, name)
        print(f"{path}: {os.path.getsize(path) // 1024} KB")


if __name__ == "__main__":
    main()
    # ParaView 5.11 under xvfb fails on closing its GLX context at the interpreter's exit (X error
    # GLXBadContext, exit 1), after the images are written: end without that teardown.
    sys.stdout.flush()
    os._exit(0)
