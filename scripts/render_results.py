"""Renders the last step of a seam run with ParaView (pvpython), for the pictures of the
examples' READMEs: the deformed mesh coloured by a point or cell field.

    xvfb-run -a -s "-screen 0 1280x1024x24 -noreset" pvpython scripts/render_results.py \\
        ironing_3d_out/results.pvd von_mises -o docs/figures/ironing_3d_paraview.png \\
        [--view x,y,z] [--up x,y,z] [--time T] [--clip x,y,z,nx,ny,nz] [--no-edges]

(Debian's ParaView renders through X: xvfb-run provides a virtual screen; -noreset keeps Xvfb from
resetting when pvpython's first connections close, which made window creation fail.)"""
import argparse

from paraview import simple as pv  # pvpython only


def vector(text):
    return [float(v) for v in text.split(",")]


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("pvd")
    p.add_argument("field", help="a point or cell field, e.g. von_mises, contact_status")
    p.add_argument("-o", "--output", default="results.png")
    p.add_argument("--view", type=vector, default=[1.0, -1.6, 0.9],
                   help="direction from the focal point to the camera")
    p.add_argument("--up", type=vector, default=[0.0, 0.0, 1.0])
    p.add_argument("--time", type=float, help="the step to show (default: the last)")
    p.add_argument("--clip", type=vector, help="point and normal of a plane: the part on the "
                   "normal's side is cut away, to look inside (e.g. a channel around a flap)")
    p.add_argument("--no-edges", action="store_true", help="draw the surface without the cell edges")
    args = p.parse_args()

    reader = pv.PVDReader(FileName=args.pvd)
    reader.UpdatePipelineInformation()
    time = args.time if args.time is not None else list(reader.TimestepValues)[-1]
    reader.UpdatePipeline(time)
    view = pv.CreateRenderView()
    view.ViewSize = [1000, 700]
    view.ViewTime = time
    view.OrientationAxesVisibility = 1
    source = reader
    if args.clip:
        if len(args.clip) != 6:
            p.error("--clip takes six numbers: x,y,z,nx,ny,nz")
        source = pv.Clip(Input=reader)
        source.ClipType = "Plane"
        source.ClipType.Origin = args.clip[:3]
        source.ClipType.Normal = args.clip[3:]
        source.Invert = 1
    display = pv.Show(source, view)
    display.SetRepresentationType("Surface" if args.no_edges else "Surface With Edges")
    points = [a.GetName() for a in reader.PointData]
    pv.ColorBy(display, ("POINTS" if args.field in points else "CELLS", args.field))
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    camera = view.GetActiveCamera()
    pv.ResetCamera(view)
    focal = camera.GetFocalPoint()
    distance = camera.GetDistance()
    norm = sum(v * v for v in args.view) ** 0.5
    camera.SetPosition(*[f + distance * v / norm for f, v in zip(focal, args.view)])
    camera.SetViewUp(*args.up)
    pv.ResetCamera(view)
    pv.SaveScreenshot(args.output, view, ImageResolution=[1000, 700])
    print("seam: t = %g, %s drawn in %s" % (time, args.field, args.output))


main()
