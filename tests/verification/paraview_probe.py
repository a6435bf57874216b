"""Run by pvpython (test_paraview.py): opens a results.pvd with ParaView's own reader, reports
what ParaView sees as JSON on stdout, and renders the last step to a PNG.

    pvpython paraview_probe.py RESULTS.pvd IMAGE.png COLOR_FIELD

The report: the time steps; per point and cell array of the last step its number of
components and the range of every component (and of the magnitude); the numbers of points
and cells; the PNG's size and the number of distinct colours in it.
"""
import json
import sys

from paraview import simple as pv  # noqa: E402  (pvpython only)


def arrays(collection):
    out = {}
    for name in collection.keys():
        a = collection[name]
        n = a.GetNumberOfComponents()
        out[name] = {"components": n,
                     "ranges": [list(a.GetRange(c)) for c in range(n)],
                     "magnitude": list(a.GetRange(-1))}
    return out


def main():
    pvd, png, color = sys.argv[1], sys.argv[2], sys.argv[3]
    reader = pv.PVDReader(FileName=pvd)
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues)
    reader.UpdatePipeline(times[-1])
    info = reader.GetDataInformation()
    report = {"times": times, "points": arrays(reader.PointData),
              "cells": arrays(reader.CellData),
              "n_points": info.GetNumberOfPoints(), "n_cells": info.GetNumberOfCells()}

    view = pv.CreateRenderView()
    view.ViewSize = [800, 600]
    view.ViewTime = times[-1]
    view.OrientationAxesVisibility = 0
    display = pv.Show(reader, view)
    display.SetRepresentationType("Surface With Edges")
    association = "POINTS" if color in report["points"] else "CELLS"
    pv.ColorBy(display, (association, color))
    display.RescaleTransferFunctionToDataRange(True, False)
    display.SetScalarBarVisibility(view, True)
    pv.ResetCamera(view)
    pv.SaveScreenshot(png, view, ImageResolution=[800, 600])

    # What the picture holds: its size and how many colours (a blank image has one or two).
    from vtkmodules.vtkIOImage import vtkPNGReader
    image = vtkPNGReader()
    image.SetFileName(png)
    image.Update()
    data = image.GetOutput()
    scalars = data.GetPointData().GetScalars()
    n = scalars.GetNumberOfComponents()
    colours = set()
    for i in range(0, scalars.GetNumberOfTuples(), 7):
        colours.add(tuple(int(scalars.GetComponent(i, c)) for c in range(min(n, 3))))
    report["image"] = {"size": list(data.GetDimensions())[:2], "colours": len(colours)}
    sys.stdout.write("PARAVIEW_REPORT " + json.dumps(report) + "\n")


main()
