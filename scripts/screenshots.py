"""Pictures of the shipped scenes for the README (docs/images/*.png), drawn by ParaView from
the runs' output.xdmf: each deck is run first (./pysus, into --runs) unless its uda is there.

    xvfb-run -a -s "-screen 0 1280x1024x24 +extension GLX" pvbatch scripts/screenshots.py
    pvbatch scripts/screenshots.py --runs RUNS --only disks     # one scene, with a display already

  explosion  inputs/ICE/explosion2D.ups: the blast wave's pressure at t = 0.1
  sod        inputs/ICE/sod.ups: density, velocity and pressure along the tube at t = 0.2
  disks      inputs/MPM/disks_50x50.ups to t = 1.6: the particles coloured by |stress| at the
             output of largest strain energy
  container  inputs/MPMICE/burning_container_rupture2D.ups, 1500 steps: the gas pressure, and
             the steel's particles coloured by plastic strain, as the ring ruptures
"""
import argparse
import json
import os
import shutil
import subprocess
import sys

import paraview.simple as pv

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SIZE = [880, 600]
BLACK, GREY = [0.0, 0.0, 0.0], [0.6, 0.6, 0.6]

SCENES = {     # name: deck, extra pysus arguments
    "explosion": ("inputs/ICE/explosion2D.ups", []),
    "sod": ("inputs/ICE/sod.ups", []),
    "disks": ("inputs/MPM/disks_50x50.ups", ["--maxTime", "1.6"]),
    "container": ("inputs/MPMICE/burning_container_rupture2D.ups", ["--max-timesteps", "1500"]),
}


def run(name, runs):
    """The scene's uda under `runs`, running its deck first if it is not there."""
    deck, extra = SCENES[name]
    uda = os.path.join(runs, f"{name}.uda")
    if not os.path.exists(os.path.join(uda, "output.xdmf")):
        # pvbatch runs under MPI: pysus must not see its launcher's variables, or it would join that job
        env = {k: v for k, v in os.environ.items() if not k.startswith(("PMI", "OMPI_", "HYDI_", "MPI_"))}
        subprocess.run([os.path.join(ROOT, "pysus"), "-q", "--filebase", uda, os.path.join(ROOT, deck), *extra],
                       check=True, env=env)
    return uda


def reader(uda, block):
    """The uda's output.xdmf with only the blocks whose names start with `block` (cells_,
    particles_m0_ ...; the legacy reader lists each timestep's as NAME[k])."""
    r = pv.XDMFReader(FileNames=[os.path.join(uda, "output.xdmf")])
    r.GridStatus = [g for g in r.GetProperty("GridInfo")[::2] if g.startswith(block)]
    return r


def view_2d(uda):
    """A white render view looking down z at the uda's domain, with room for a colour bar
    on either side."""
    with open(os.path.join(uda, "index.json")) as f:
        grid = json.load(f)["grid"]
    lower, upper = grid["anchor"], grid["upper"]
    v = pv.CreateRenderView()
    v.ViewSize = SIZE
    v.OrientationAxesVisibility = 0
    v.UseColorPaletteForBackground = 0
    v.Background = [1.0, 1.0, 1.0]
    v.InteractionMode = "2D"
    cx, cy = (lower[0] + upper[0]) / 2, (lower[1] + upper[1]) / 2
    v.CameraPosition, v.CameraFocalPoint, v.CameraViewUp = [cx, cy, 10.0], [cx, cy, 0.0], [0, 1, 0]
    v.CameraParallelScale = 0.54 * max(upper[1] - lower[1], (upper[0] - lower[0]) * SIZE[1] / SIZE[0] * 1.4)
    return v


def title(v, text):
    t = pv.Text(Text=text)
    d = pv.Show(t, v)
    d.WindowLocation, d.FontSize, d.Color = "Upper Center", 14, BLACK


def color(d, v, center, array, label, preset="Rainbow Uniform", component=None, bounds=None, left=False,
          log=False):
    """Colour display d by an array, with a labelled colour bar at the right (or left)."""
    pv.ColorBy(d, (center, array) if component is None else (center, array, component))
    lut = pv.GetColorTransferFunction(array)
    lut.ApplyPreset(preset, True)
    lut.UseLogScale = int(log)
    if bounds is None:
        d.RescaleTransferFunctionToDataRange(False, True)
    else:
        lut.RescaleTransferFunction(*bounds)
    d.SetScalarBarVisibility(v, True)
    bar = pv.GetScalarBar(lut, v)
    bar.Title, bar.ComponentTitle = label, ""
    bar.TitleColor = bar.LabelColor = BLACK
    bar.WindowLocation = "Any Location"
    bar.Position, bar.ScalarBarLength = [0.03 if left else 0.86, 0.15], 0.7


def particles(uda, m, v, size, spheres=True):
    """Show the particles of material m as points (round ones, or squares: a smaller PNG)."""
    d = pv.Show(reader(uda, f"particles_m{m}_"), v)
    d.Representation, d.PointSize, d.RenderPointsAsSpheres = "Points", size, int(spheres)
    return d


def cells(uda, v):
    d = pv.Show(reader(uda, "cells_"), v)
    d.Representation = "Surface"
    return d


def save(v, out, name):
    path = os.path.join(out, f"{name}.png")
    pv.SaveScreenshot(path, v, ImageResolution=SIZE, CompressionLevel="9")
    print(f"{path}: {os.path.getsize(path) // 1024} KB")


def explosion(uda, out):
    t = min(reader(uda, "cells_").TimestepValues, key=lambda x: abs(x - 0.1))
    v = view_2d(uda)
    v.ViewTime = t
    color(cells(uda, v), v, "CELLS", "press_CC_0", "pressure", preset="Inferno (matplotlib)")
    title(v, f"ICE explosion2D.ups: pressure at t = {t:.3g} s (128 x 128 cells, 4 patches)")
    save(v, out, "explosion")


def sod(uda, out):
    r = reader(uda, "cells_")
    t = r.TimestepValues[-1]
    line = pv.PlotOverLine(Input=pv.MergeBlocks(Input=r))
    line.Point1, line.Point2 = [0.0, 0.005, 0.0], [1.0, 0.005, 0.0]
    line.SamplingPattern = "Sample At Cell Boundaries"
    v = pv.CreateView("XYChartView")
    v.ViewSize = SIZE
    v.ViewTime = t
    v.ChartTitle = f"ICE sod.ups at t = {t:.3g}: 200 cells"
    v.LeftAxisTitle, v.BottomAxisTitle = "", "x"
    d = pv.Show(line, v)
    d.UseIndexForXAxis, d.XArrayName = 0, "Points_X"
    d.SeriesVisibility = ["rho_CC_0", "press_CC_0", "vel_CC_0_X"]
    d.SeriesLabel = ["rho_CC_0", "density", "press_CC_0", "pressure", "vel_CC_0_X", "velocity"]
    d.SeriesColor = ["rho_CC_0", "0.1", "0.3", "0.8", "press_CC_0", "0.85", "0.2", "0.1",
                     "vel_CC_0_X", "0.1", "0.6", "0.2"]
    d.SeriesLineThickness = ["rho_CC_0", "2", "press_CC_0", "2", "vel_CC_0_X", "2"]
    save(v, out, "sod")


def disks(uda, out):
    with open(os.path.join(uda, "StrainEnergy.dat")) as f:
        energy = [tuple(map(float, line.split()[:2])) for line in f]
    t_peak = max(energy, key=lambda te: te[1])[0]
    t = min(reader(uda, "particles_").TimestepValues, key=lambda x: abs(x - t_peak))
    v = view_2d(uda)
    v.ViewTime = t
    color(particles(uda, 0, v, 4, spheres=False), v, "POINTS", "p.stress_0", "|stress| (Pa)", component="Magnitude")
    title(v, f"MPM disks_50x50.ups: colliding disks at t = {t:.3g} s, largest strain energy")
    save(v, out, "disks")


def container(uda, out):
    t = reader(uda, "cells_").TimestepValues[-1]
    v = view_2d(uda)
    v.ViewTime = t
    color(cells(uda, v), v, "CELLS", "press_CC_0", "pressure (Pa)", preset="Cool to Warm", bounds=(1e5, 1e8),
          log=True)
    steel = particles(uda, 0, v, 4)
    color(steel, v, "POINTS", "p.plasticStrain_0", "steel plastic strain", preset="Viridis (matplotlib)",
          bounds=(0.0, 0.05), left=True)
    explosive = particles(uda, 1, v, 2)
    pv.ColorBy(explosive, None)
    explosive.AmbientColor = explosive.DiffuseColor = GREY
    title(v, f"MPMICE burning_container_rupture2D.ups at t = {t * 1e6:.0f} us: the ring ruptures at its notch")
    save(v, out, "container")


def main():
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--runs", default=os.path.join(ROOT, "screenshots_runs"), help="where the udas are (or go)")
    p.add_argument("--out", default=os.path.join(ROOT, "docs", "images"))
    p.add_argument("--only", choices=sorted(SCENES), help="this scene only, in this process")
    args = p.parse_args()
    os.makedirs(args.out, exist_ok=True)
    if args.only:
        globals()[args.only](run(args.only, args.runs), args.out)
        return 0
    # each scene in its own pvbatch, tried up to 3 times: under Xvfb, opening the display
    # now and then fails ("bad X server connection") and aborts the process
    failed = []
    for name in SCENES:
        run(name, args.runs)
        for _ in range(3):
            r = subprocess.run([shutil.which("pvbatch") or "pvbatch", os.path.abspath(__file__), "--only", name,
                                "--runs", args.runs, "--out", args.out], capture_output=True, text=True)
            line = [x for x in r.stdout.splitlines() if x.endswith(" KB")]
            if line:
                print(line[0])
                break
        else:
            failed.append(name)
            sys.stderr.write(r.stdout[-2000:] + r.stderr[-2000:])
    if failed:
        print(f"no picture of {', '.join(failed)}", file=sys.stderr)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
