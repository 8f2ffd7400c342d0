"""granularParaView: the ParaView scene of a granularSegregationFoam case.

A tutorial's ParaView state (tutorials/<case>/paraviewState.py) calls main()
with its fields and vertical exaggeration.  The scene is the case read by
ParaView's built-in OpenFOAM reader (an empty `<case>.foam` file, as
`paraFoam -touch` makes; created if absent) at its last written time, cell
values only (no interpolation to the points), with the panels of
granularPictures (granularPanels: the same order, labels, colour maps and
colour limits):

- a 2D case or a thin layer: one render view per field, looking along the
  mesh's thinnest direction with x to the right and z (y in an x-y mesh)
  up, a thin layer stretched vertically by the exaggeration; I (on a
  logarithmic colour scale) and the ill-posedness indicator of (2.6) in the
  grains only, the cells with phi^a < 1/2 (a threshold on the cell values:
  whole cells), the air cells grey;
- a column one cell wide: one chart per field, height against the cell
  values at the cell centres (the profiles of granularPictures).

The colour ranges are those of the last time and stay fixed when the time
is changed in the GUI.  The cameras fit the views' sizes when the state is
loaded (in the GUI, the window's): after resizing the window, Reset Camera
refits a view.

In the GUI, from the case directory after Allrun (ParaView 5.11 takes a
Python state with --state; File > Load State does the same):

    paraview --state=paraviewState.py

Headless, a screenshot of the whole layout (pvbatch needs an X display:
Xvfb, see doc/visualisation.md, ParaView states):

    pvbatch paraviewState.py --screenshot figures/paraview.png [--case DIR]

Installed by Allwmake beside granularPictures; a state file finds it
through FOAM_USER_APPBIN (source etc/openfoam.env).  Errors (not a case, no
written time, a field not written) name the case and the field; pvbatch
then exits with status 1.
"""
import math
import os
import sys

from paraview import servermanager
from paraview import simple as pv
from vtkmodules.util.numpy_support import vtk_to_numpy
import numpy as np

sys.path.insert(0, os.path.dirname(os.path.realpath(__file__)))
import granularPanels as panel                                  # noqa: E402

PRESETS = {"viridis": "Viridis (matplotlib)", "magma": "Magma (matplotlib)",
           "cividis": "Cividis", "plasma": "Plasma (matplotlib)",
           "coolwarm": "Cool to Warm"}
VIEW = (480, 420)           # pixels of a render view of a 2D case
THIN_WIDTH = 1500           # pixels across a thin layer's view
CHART = (230, 520)          # pixels of a column's chart
SCREEN = (1920, 1200)       # the largest screenshot (Xvfb's screen)
FONT = 13                   # points, titles; labels one less
GREY = [0.85, 0.85, 0.85]   # the air where a field is shown in the grains
BAR = 110                   # pixels right of a render view for its bar


class CaseError(Exception):
    """A case that cannot be shown: the message names the case and the
    field."""


def _reader(case, fields):
    """The OpenFOAM reader of case at its last written time, every field
    checked; (reader, time)."""
    if not os.path.isfile(os.path.join(case, "system", "controlDict")):
        raise CaseError(f"{case} is not a case (no system/controlDict)")
    name = os.path.basename(case)
    foam = os.path.join(case, name + ".foam")
    if not os.path.exists(foam):
        open(foam, "a").close()
    reader = pv.OpenFOAMReader(registrationName=name + ".foam",
                               FileName=foam)
    reader.MeshRegions = ["internalMesh"]
    reader.Createcelltopointfiltereddata = 0
    reader.UpdatePipelineInformation()
    times = reader.TimestepValues
    times = list(times) if hasattr(times, "__iter__") else [times]
    if not times or times[-1] <= 0:
        raise CaseError(f"{case}: no written time after 0 (run the case "
                        "first)")
    wanted = list(dict.fromkeys(list(fields) + [panel.AIR]))
    reader.CellArrays = [f for f in wanted if f in reader.CellArrays]
    return reader, times[-1]


def _fetch(source, time):
    """The cell values of a source at time: (vtk dataset, {name: array})."""
    source.UpdatePipeline(time)
    data = servermanager.Fetch(source)
    cells = data.GetCellData()
    arrays = {cells.GetArrayName(k): vtk_to_numpy(cells.GetArray(k))
              for k in range(cells.GetNumberOfArrays())}
    return data, arrays


def _cell_centres(source, time):
    """The cell centres of a source at time, (n, 3)."""
    centres = pv.CellCenters(Input=source)
    centres.UpdatePipeline(time)
    points = servermanager.Fetch(centres).GetPoints().GetData()
    pv.Delete(centres)
    return vtk_to_numpy(points)


def _threshold(source, grains):
    """The cells in the grains (phi^a < 1/2) or the others, whole cells by
    their cell value."""
    cut = pv.Threshold(registrationName="grains" if grains else "air",
                       Input=source)
    cut.Scalars = ["CELLS", panel.AIR]
    cut.ThresholdMethod = "Above Upper Threshold"     # phi^a >= 1/2
    cut.UpperThreshold = panel.GRAINS_BELOW
    cut.Invert = int(grains)
    return cut


def _colour(display, view, field, limits, log):
    """Colour display by the cell values of field with its colour map over
    limits (for I: log10 limits, on a logarithmic scale), and a colour bar
    labelled as in granularPictures."""
    if field == "U":
        pv.ColorBy(display, ("CELLS", "U", "Magnitude"))
    else:
        pv.ColorBy(display, ("CELLS", field))
    lut = pv.GetColorTransferFunction(field)
    lut.ApplyPreset(PRESETS[panel.colormap(field)], True)
    lut.AutomaticRescaleRangeMode = "Never"
    lo, hi = limits
    if log:
        lut.RescaleTransferFunction(10.0 ** lo, 10.0 ** hi)
        lut.MapControlPointsToLogSpace()
        lut.UseLogScale = 1
    else:
        lut.RescaleTransferFunction(lo, hi)
    display.SetScalarBarVisibility(view, True)
    bar = pv.GetScalarBar(lut, view)
    bar.Title = panel.label(field)
    bar.ComponentTitle = ""
    bar.HorizontalTitle = 1
    bar.TitleFontSize = FONT
    bar.LabelFontSize = FONT - 1
    bar.TitleColor = bar.LabelColor = [0.0, 0.0, 0.0]
    bar.RangeLabelFormat = "%-#.3g"
    bar.ScalarBarThickness = 12
    bar.WindowLocation = "Any Location"
    return bar


def _flat(display):
    """Unlit, so that every cell shows its colour-map colour exactly."""
    display.Ambient = 1.0
    display.Diffuse = 0.0
    display.Specular = 0.0


def _camera(view, bar, bounds, axes, scale):
    """Look along the thin axis, axes[0] to the right and axes[1] up, at
    the scaled mesh in the left of the view (as sized by its layout), the
    colour bar on the right."""
    right, up = axes
    size = view.ViewSize
    aspect = size[0] / size[1]
    space = 1.0 - BAR / size[0]       # the fraction of the width for the mesh
    bar.Position = [space + 0.1 * BAR / size[0], 12.0 / size[1]]
    bar.ScalarBarLength = max(0.3, 1.0 - 52.0 / size[1])  # title above
    lo = [bounds[2 * k] * scale[k] for k in range(3)]
    hi = [bounds[2 * k + 1] * scale[k] for k in range(3)]
    width, height = hi[right] - lo[right], hi[up] - lo[up]
    half = 0.5 * max(1.12 * height, width / (0.95 * space * aspect))
    focal = [0.5 * (lo[k] + hi[k]) for k in range(3)]
    focal[right] += (1.0 - space) * half * aspect
    into = np.cross(np.eye(3)[up], np.eye(3)[right])   # right = into x up
    view.CameraFocalPoint = focal
    view.CameraPosition = list(np.array(focal) - 10.0 * max(width, height)
                               * into)
    view.CameraViewUp = list(np.eye(3)[up])
    view.CameraParallelProjection = 1
    view.CameraParallelScale = half


def _render_views(reader, time, fields, values, grains, parts, data,
                  exaggeration, title):
    """One render view per field; (views, columns, view size, a function
    that sets the cameras once the views have their size)."""
    bounds = data.GetBounds()
    extent = [bounds[2 * k + 1] - bounds[2 * k] for k in range(3)]
    _, axes = panel.plane(extent)
    scale = [1.0, 1.0, 1.0]
    scale[axes[1]] = exaggeration
    width, shown = extent[axes[0]], extent[axes[1]] * exaggeration
    thin = panel.is_thin(width, shown)
    ncol = panel.columns(len(fields), thin)
    if thin:
        size = (THIN_WIDTH, int(max(110, (THIN_WIDTH - BAR) * shown / width
                                    + 50)))
    else:
        size = VIEW
    views, bars = [], []
    for field in fields:
        view = pv.CreateView("RenderView")
        view.ViewSize = list(size)
        view.ViewTime = time
        view.OrientationAxesVisibility = 0
        view.UseColorPaletteForBackground = 0
        view.Background = [1.0, 1.0, 1.0]
        restricted = field in panel.GRAINS_ONLY and parts
        display = pv.Show(parts[True] if restricted else reader, view)
        display.Scale = scale
        _flat(display)
        limits = panel.limits(field, values[field], grains)
        if limits is None:
            finite = values[field][np.isfinite(values[field])]
            limits = (float(finite.min()), float(finite.max()))
            if limits[1] <= limits[0]:
                limits = (limits[0] - 0.5, limits[0] + 0.5)
        bars.append(_colour(display, view, field, limits, log=field == "I"))
        if restricted:
            air = pv.Show(parts[False], view)
            air.Scale = scale
            pv.ColorBy(air, None)
            air.AmbientColor = air.DiffuseColor = GREY
            _flat(air)
        views.append(view)
    text = pv.Text(registrationName="title", Text=title)
    label = pv.Show(text, views[0])
    label.FontSize = FONT
    label.Color = [0.0, 0.0, 0.0]
    label.WindowLocation = "Upper Left Corner"

    def cameras():
        for view, bar in zip(views, bars):
            _camera(view, bar, bounds, axes, scale)
    return views, ncol, size, cameras


def _charts(reader, time, fields, parts, centres, bounds, axes, title):
    """A column: one chart per field, the height against the cell values at
    the cell centres, all over the column's height; (views, columns, view
    size, None)."""
    vertical = axes[panel.along(centres)]
    length = panel.AXES[vertical]
    points = {False: pv.CellCenters(registrationName="centres",
                                    Input=reader)}
    if parts:
        points[True] = pv.CellCenters(registrationName="grain centres",
                                      Input=parts[True])
    views = []
    for field in fields:
        source = points[bool(field in panel.GRAINS_ONLY and parts)]
        array = field
        if field == "U":
            source = pv.Calculator(registrationName="speed", Input=source,
                                   Function="mag(U)", ResultArrayName="speed")
            array = "speed"
        chart = pv.CreateView("XYChartView")
        chart.ViewSize = list(CHART)
        chart.ViewTime = time
        chart.ShowLegend = 0
        chart.LeftAxisTitle = f"{length} (m)"
        chart.LeftAxisUseCustomRange = 1
        chart.LeftAxisRangeMinimum = bounds[2 * vertical]
        chart.LeftAxisRangeMaximum = bounds[2 * vertical + 1]
        chart.BottomAxisTitle = panel.label(field)
        chart.LeftAxisTitleFontSize = chart.BottomAxisTitleFontSize = FONT
        chart.LeftAxisLabelFontSize = FONT - 1
        chart.BottomAxisLabelFontSize = FONT - 1
        chart.BottomAxisLogScale = int(field == "I")
        if field.startswith("alpha.") or field == "illPosed":
            chart.BottomAxisUseCustomRange = 1
            chart.BottomAxisRangeMinimum = -0.05
            chart.BottomAxisRangeMaximum = 1.05
        line = pv.Show(source, chart, "XYChartRepresentation")
        line.AttributeType = "Point Data"
        line.UseIndexForXAxis = 0
        line.XArrayName = array
        height = f"Points_{length.upper()}"
        line.SeriesVisibility = [height]
        line.SeriesColor = [height, "0.1", "0.3", "0.7"]
        line.SeriesMarkerStyle = [height, "4"]
        line.SeriesMarkerSize = [height, "4"]
        views.append(chart)
    views[0].ChartTitle = title
    views[0].ChartTitleFontSize = FONT
    return views, len(views), CHART, None


def _split(layout, cell, n, horizontal):
    """Split a layout cell into n equal parts; their cell indices (a layout
    is a binary tree of cells: the children of cell i are 2i + 1 and
    2i + 2)."""
    out = []
    for k in range(n - 1):
        split = layout.SplitHorizontal if horizontal else layout.SplitVertical
        first = split(cell, 1.0 / (n - k))
        out.append(first)
        cell = first + 1
    return out + [cell]


def _arrange(layout, views, ncol):
    """Views in a grid of ncol columns, row by row, the empty places
    blank."""
    nrow = math.ceil(len(views) / ncol)
    slots = [slot for row in _split(layout, 0, nrow, horizontal=False)
             for slot in _split(layout, row, ncol, horizontal=True)]
    for k, slot in enumerate(slots):
        if k < len(views):
            layout.AssignView(slot, views[k])
        else:
            blank = pv.CreateView("RenderView")
            blank.OrientationAxesVisibility = 0
            blank.UseColorPaletteForBackground = 0
            blank.Background = [1.0, 1.0, 1.0]
            layout.AssignView(slot, blank)
    return nrow


def show(fields, exaggeration=1.0, case=None, screenshot=None):
    """Build the scene of case (default: the working directory) with the
    given fields; with screenshot, save the layout as that PNG.  Returns a
    one-line summary."""
    case = os.path.abspath(case or os.getcwd())
    if not exaggeration > 0:
        raise CaseError(f"{case}: exaggeration {exaggeration}: must be > 0")
    reader, time = _reader(case, fields)
    merged = pv.MergeBlocks(registrationName="cells", Input=reader)
    data, values = _fetch(merged, time)
    missing = [f for f in fields if f not in values]
    if missing:
        raise CaseError(f"{case}: no field {' '.join(missing)} at t = "
                        f"{time:g} (written: {' '.join(sorted(values))})")
    pv.GetAnimationScene().UpdateAnimationUsingDataTimeSteps()
    pv.GetAnimationScene().AnimationTime = time
    air = values.get(panel.AIR)
    grains = panel.grains_mask(air)
    shown = dict(values)
    if "U" in shown:
        shown["U"] = np.linalg.norm(values["U"], axis=1)
    if "I" in shown:
        with np.errstate(divide="ignore"):
            shown["I"] = np.log10(np.maximum(values["I"], 1e-300))
    centres = _cell_centres(merged, time)
    bounds = data.GetBounds()
    extent = [bounds[2 * k + 1] - bounds[2 * k] for k in range(3)]
    _, axes = panel.plane(extent)
    name = os.path.basename(case)
    title = f"{name}, t = {time:g} s"
    column = panel.is_column(centres[:, axes], max(extent))
    parts = {} if grains is None else {
        True: _threshold(merged, True), False: _threshold(merged, False)}
    if column:
        scene = _charts(merged, time, fields, parts, centres[:, axes],
                        bounds, axes, title.replace(", ", "\n"))
    else:
        if exaggeration != 1.0:
            title += f", vertical exaggeration {exaggeration:g}"
        scene = _render_views(merged, time, fields, shown, grains, parts,
                              data, exaggeration, title)
    views, ncol, size, cameras = scene
    layout = pv.CreateLayout(name)
    nrow = _arrange(layout, views, ncol)
    resolution = [ncol * size[0], nrow * size[1]]
    fit = min(1.0, SCREEN[0] / resolution[0], SCREEN[1] / resolution[1])
    resolution = [int(fit * r) for r in resolution]
    if screenshot:
        layout.SetSize(*resolution)
    if cameras:
        cameras()
    counts = {k: _fetch(part, time)[0].GetNumberOfCells()
              for k, part in parts.items()}
    summary = (f"{len(centres)} cells, "
               + (f"{counts[True]} in the grains (phi^a < 1/2) and "
                  f"{counts[False]} in the air by threshold, " if parts
                  else "no air fraction, ")
               + f"t = {time:g}, fields {' '.join(fields)}, "
               + (f"{len(views)} charts" if column else
                  f"{len(views)} views, exaggeration {exaggeration:g}")
               + f", {ncol} x {nrow}, {resolution[0]} x {resolution[1]} px")
    if screenshot:
        folder = os.path.dirname(os.path.abspath(screenshot))
        os.makedirs(folder, exist_ok=True)
        pv.SaveScreenshot(screenshot, layout, ImageResolution=resolution,
                          SeparatorWidth=2, SeparatorColor=[0.6, 0.6, 0.6])
        summary = f"{screenshot}: {summary}"
    else:
        pv.SetActiveView(views[0])
    return summary


def main(fields, exaggeration=1.0):
    """Entry of a tutorial's state file: build the scene of the case the
    state file is in (the working directory if Python does not say), or of
    --case DIR; with --screenshot PNG (pvbatch) save it and print a
    summary, or exit with status 1 and a message."""
    state = sys._getframe(1).f_globals.get("__file__")
    args = [a for a in sys.argv[1:] if a.startswith("--")]
    options = {}
    for flag in ("--screenshot", "--case"):
        if flag in sys.argv[1:]:
            k = sys.argv.index(flag)
            if k + 1 >= len(sys.argv):
                sys.exit(f"granularParaView: error: {flag} needs a value")
            options[flag] = sys.argv[k + 1]
    unknown = [a for a in args if a not in ("--screenshot", "--case")]
    if options and unknown:
        sys.exit(f"granularParaView: error: unknown option {unknown[0]} "
                 "(--screenshot PNG, --case DIR)")
    try:
        summary = show(fields, exaggeration,
                       options.get("--case", state and os.path.dirname(
                           os.path.abspath(state))),
                       options.get("--screenshot"))
    except CaseError as error:
        if "--screenshot" not in options:
            raise
        sys.exit(f"granularParaView: error: {error}")
    print(summary)
