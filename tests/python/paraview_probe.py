"""Run by pvpython (ParaView's Python): opens a run's field index the way a user does
(OpenDataFile picks the reader), and prints as JSON what ParaView sees: the reader, the
times, and at the first and the last time the point and cell counts, every array's range,
the length (2D) or area (3D) of the Contour phi = 0, phi sampled by Plot Over Line along
the x axis through the domain's centre, and a PNG of that contour.

    pvpython paraview_probe.py INDEX PNG_STEM [FIELD]

FIELD is the phase field to contour and sample (default phi).
"""
import json
import sys

from paraview import servermanager
from paraview.simple import (Contour, GetActiveViewOrCreate, Hide, IntegrateVariables,
                             OpenDataFile, PlotOverLine, ResetCamera, SaveScreenshot, Show)
from vtk.util.numpy_support import vtk_to_numpy

index, png_stem = sys.argv[1], sys.argv[2]
field = sys.argv[3] if len(sys.argv) > 3 else "phi"
source = OpenDataFile(index)
times = list(source.TimestepValues)
report = {"reader": source.GetXMLName(), "times": times, "at": []}
for k, t in ((0, times[0]), (len(times) - 1, times[-1])):
    source.UpdatePipeline(t)
    info = source.GetDataInformation()
    arrays = {name: list(source.PointData[name].GetRange(-1)) for name in source.PointData.keys()
              if not name.startswith("vtk")}
    contour = Contour(Input=source, ContourBy=["POINTS", field], Isosurfaces=[0.0])
    measure = IntegrateVariables(Input=contour)
    measure.UpdatePipeline(t)
    cell_data = servermanager.Fetch(measure).GetCellData()
    size = {name: cell_data.GetArray(name).GetValue(0) for name in ("Length", "Area")
            if cell_data.GetArray(name) is not None}
    (x0, x1, y0, y1, z0, z1) = info.GetBounds()
    line = PlotOverLine(Input=source)
    line.Point1 = [x0, (y0 + y1) / 2, (z0 + z1) / 2]
    line.Point2 = [x1, (y0 + y1) / 2, (z0 + z1) / 2]
    line.Resolution = 400
    line.UpdatePipeline(t)
    sampled = servermanager.Fetch(line).GetPointData()
    phi_line = vtk_to_numpy(sampled.GetArray(field))[vtk_to_numpy(sampled.GetArray("vtkValidPointMask")) == 1]
    view = GetActiveViewOrCreate("RenderView")
    view.ViewTime = t
    view.ViewSize = [400, 300]
    view.OrientationAxesVisibility = 0
    view.Background = [1, 1, 1]
    view.UseColorPaletteForBackground = 0
    display = Show(contour, view)
    display.AmbientColor = display.DiffuseColor = [0, 0, 0]
    display.LineWidth = 2
    ResetCamera(view)
    png = f"{png_stem}-{k}.png"
    SaveScreenshot(png, view, ImageResolution=[400, 300])
    report["at"].append({"time": t, "points": info.GetNumberOfPoints(),
                         "cells": info.GetNumberOfCells(), "arrays": arrays,
                         "contour": size, "line_phi": [float(phi_line.min()), float(phi_line.max())],
                         "png": png})
    view.Update()
    Hide(contour, view)
print("PROBE " + json.dumps(report))
