"""Pictures of a 3D signorini output drawn by ParaView: run by pvpython (ParaView 5.11) on an X display, not by python3.

    pvpython plot3d_pvpython.py SPEC.json

scripts/plot.py writes SPEC.json (what it read with h5py: the per-block XDMF files, the displacement scale, the
direction the obstacles push the body, the box of the contact patch, the titles, the picture paths and size) and calls
this script on a private Xvfb's display. It draws, with ParaView's reader of the output's per-block XDMF files, at the
last load step:
  deformed   the body warped by displacement x scale, coloured by the von_mises cell field (on a log scale when it
             spans two decades), the obstacles translucent beside it, seen from above the contact (the obstacles at the
             bottom of the picture);
  pressure   the contact boundary coloured by the contact_pressure point field in bands, its mesh faint, the edge of
             the active set in red, seen from the obstacle's side (the camera inside the obstacle, looking at the
             contact face), framed on the contact patch.
For each picture it prints one line, "PICTURE FIELD MIN MAX": the colour bar's range, which is the range of the field
ParaView read (the test compares it with the file's values read by h5py).
"""
import json
import math
import sys

from paraview.simple import (Clip, ColorBy, Contour, CreateRenderView, ExtractEdges, ExtractSurface,
                             GetColorTransferFunction, GetScalarBar, Render, SaveScreenshot, Show, Text, WarpByVector,
                             Xdmf3ReaderS, _DisableFirstRenderCameraReset)

WHITE, BLACK, GREY = [1.0, 1.0, 1.0], [0.0, 0.0, 0.0], [0.6, 0.6, 0.6]
LOG_RATIO = 100


def unit(v):
    n = math.sqrt(sum(c * c for c in v))
    return [c / n for c in v]


def cross(a, b):
    return [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]]


def screen_up_for(push):
    """The coordinate axis least aligned with push, made perpendicular to it: up on the screen of a camera looking
    along push (the y axis when looking along z)."""
    axes = ([0.0, 1.0, 0.0], [0.0, 0.0, 1.0], [1.0, 0.0, 0.0])
    axis = min(axes, key=lambda a: abs(sum(c * p for c, p in zip(a, push))))
    d = sum(c * p for c, p in zip(axis, push))
    return unit([c - d * p for c, p in zip(axis, push)])


def side_direction(up):
    """A horizontal direction (perpendicular to up) from which to look: the side of -x and -y, where the symmetry
    planes of the default cases show the inside of the body."""
    for guess in ([-1.0, -1.6, 0.0], [0.0, -1.0, -1.0], [-1.0, 0.0, 0.0]):
        d = sum(g * u for g, u in zip(guess, up))
        side = [g - d * u for g, u in zip(guess, up)]
        if math.sqrt(sum(c * c for c in side)) > 1e-3:
            return unit(side)
    raise ValueError("no side direction for up = %s" % up)


def read(path):
    """The XDMF file at path, and its last time (load step)."""
    reader = Xdmf3ReaderS(FileName=[path])
    times = reader.TimestepValues
    time = times if isinstance(times, float) else (list(times)[-1] if times else 0.0)
    reader.UpdatePipeline(time)
    return reader, time


def view_of(spec, time):
    view = CreateRenderView()
    view.ViewSize = spec["size"]
    view.UseColorPaletteForBackground = 0
    view.Background = WHITE
    view.OrientationAxesVisibility = 1
    view.OrientationAxesLabelColor = BLACK
    view.ViewTime = time
    return view


def title(view, text):
    t = Text(Text=text)
    d = Show(t, view)
    d.WindowLocation = "Upper Center"
    d.Justification = "Center"
    d.FontSize = 15
    d.Color = BLACK
    # A white box behind the title where the scene reaches the top.
    d.ShowBorder = "Always"
    d.BorderColor = WHITE
    d.BackgroundColor = WHITE + [0.85]


def colour(source, display, view, association, field, bar_title):
    """Colour display by field over its range in source (what ParaView read: the whole body, not only the surface
    shown), with a colour bar titled bar_title. Returns (min, max)."""
    ColorBy(display, (association, field))
    info = (source.CellData if association == "CELLS" else source.PointData)[field]
    lo, hi = info.GetRange(0)
    if hi <= lo:
        hi = lo + (abs(lo) or 1.0) * 1e-6
    lut = GetColorTransferFunction(field)
    lut.ApplyPreset("Viridis (matplotlib)", True)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(lo, hi)
    # A field spread over decades (the stress under a Hertz contact) is shown on a log scale.
    log = lo > 0 and hi / lo >= LOG_RATIO
    if log:
        lut.MapControlPointsToLogSpace()
        lut.UseLogScale = 1
    bar = GetScalarBar(lut, view)
    bar.Title = bar_title + (" (log scale)" if log else "")
    bar.ComponentTitle = ""
    bar.TitleColor = BLACK
    bar.LabelColor = BLACK
    bar.TitleFontSize = 16
    bar.LabelFontSize = 14
    bar.AutomaticLabelFormat = 0
    bar.RangeLabelFormat = "%-#.4g"
    bar.LabelFormat = "%-#.3g"
    if hi - lo <= 1e-9 * max(abs(lo), abs(hi)):
        # A uniform field (the cube on a plane): one colour, the range labels alone.
        bar.Title = bar_title + " (uniform)"
        bar.DrawTickLabels = 0
        bar.DrawTickMarks = 0
    bar.ScalarBarLength = 0.5
    bar.WindowLocation = "Any Location"
    bar.Position = [0.87, 0.25]
    display.SetScalarBarVisibility(view, True)
    return lo, hi


def place_camera(view, lo, hi, direction, up, distance):
    """A parallel projection from the box's centre + distance * direction, up on the screen, framing the box [lo, hi]
    in the part of the picture left of the colour bar and below the title."""
    centre = [(a + b) / 2 for a, b in zip(lo, hi)]
    right = unit(cross(up, direction))
    corners = [[(lo, hi)[(k >> i) & 1][i] for i in range(3)] for k in range(8)]
    half_height = max(abs(sum((c - m) * u for c, m, u in zip(p, centre, up))) for p in corners)
    half_width = max(abs(sum((c - m) * r for c, m, r in zip(p, centre, right))) for p in corners)
    # The box fills at most 0.75 of the width (the colour bar is right of it) and 0.8 of the height (the title above).
    aspect = view.ViewSize[0] / view.ViewSize[1]
    parallel_scale = max(half_height / 0.8, half_width / (0.75 * aspect), 1e-12)
    width = 2 * parallel_scale * aspect
    focal = [c + 0.09 * width * r + 0.06 * parallel_scale * u for c, r, u in zip(centre, right, up)]
    cam = view.GetActiveCamera()
    view.CameraParallelProjection = 1
    cam.SetFocalPoint(*focal)
    cam.SetPosition(*[f + distance * d for f, d in zip(focal, direction)])
    cam.SetViewUp(*up)
    cam.SetParallelScale(parallel_scale)
    view.CenterOfRotation = focal


def deformed(spec):
    body, time = read(spec["body"])
    view = view_of(spec, time)
    warped = WarpByVector(Input=body, Vectors=["POINTS", "displacement"], ScaleFactor=spec["scale"])
    surface = ExtractSurface(Input=warped)
    surface.UpdatePipeline(time)
    display = Show(surface, view)
    display.Ambient, display.Diffuse = 0.3, 0.8
    lo, hi = colour(body, display, view, "CELLS", "von_mises", "von Mises stress")
    if spec.get("obstacle"):
        obstacle, _ = read(spec["obstacle"])
        od = Show(obstacle, view)
        ColorBy(od, ("POINTS", None))
        od.AmbientColor = od.DiffuseColor = GREY
        od.Opacity = 0.35
    title(view, spec["deformed_title"])
    # Frame the warped body (not the obstacles, which may be much larger), seen from the side and above the contact.
    b = surface.GetDataInformation().GetBounds()
    up = unit(spec["up"])
    side = side_direction(up)
    elevation = math.radians(25)
    direction = [math.cos(elevation) * s + math.sin(elevation) * u for s, u in zip(side, up)]
    screen_up = unit(cross(cross(direction, up), direction))
    place_camera(view, b[0::2], b[1::2], direction, screen_up, 4 * spec["body_size"])
    Render(view)
    SaveScreenshot(spec["deformed_png"], view, ImageResolution=spec["size"], TransparentBackground=0,
                   CompressionLevel="9")
    print("%s von_mises %.17g %.17g" % (spec["deformed_png"], lo, hi))


def pressure(spec):
    whole, time = read(spec["contact_boundary"])
    view = view_of(spec, time)
    # The contact boundary inside the patch's box (clip_lo, clip_hi: the box, deep along the line of sight).
    boundary = Clip(Input=whole, ClipType="Box", Invert=1, Scalars=["POINTS", "contact_pressure"])
    boundary.ClipType.UseReferenceBounds = 0
    boundary.ClipType.Position = spec["clip_lo"]
    boundary.ClipType.Length = [b - a for a, b in zip(spec["clip_lo"], spec["clip_hi"])]
    boundary.UpdatePipeline(time)
    display = Show(boundary, view)
    display.SetRepresentationType("Surface")
    # Unlit: the colours are the colour map's, whatever the curvature of the face.
    display.Ambient, display.Diffuse = 1.0, 0.0
    lo, hi = colour(whole, display, view, "POINTS", "contact_pressure", "contact pressure")
    # Bands of equal pressure, read off the colour bar.
    lut = GetColorTransferFunction("contact_pressure")
    lut.Discretize = 1
    lut.NumberOfTableValues = 12
    # The mesh, faint (a second representation of a source needs a filter of its own).
    mesh = Show(ExtractEdges(Input=boundary), view)
    ColorBy(mesh, ("POINTS", None))
    mesh.AmbientColor = mesh.DiffuseColor = WHITE
    mesh.Opacity = 0.3
    # The edge of the active set: the contour contact_active = 1/2 of the nodal 0/1 field.
    edge = Contour(Input=boundary, ContourBy=["POINTS", "contact_active"], Isosurfaces=[0.5])
    edge.UpdatePipeline(time)
    ed = Show(edge, view)
    ColorBy(ed, ("POINTS", None))
    ed.AmbientColor = ed.DiffuseColor = [0.85, 0.1, 0.1]
    ed.LineWidth = 2.5
    title(view, spec["pressure_title"])
    # The camera inside the obstacle, on the far side of the contact patch from the body, looking along the push,
    # framing the patch's box.
    push = unit(spec["up"])
    place_camera(view, spec["patch_lo"], spec["patch_hi"], [-p for p in push], screen_up_for(push),
                 4 * spec["body_size"])
    Render(view)
    SaveScreenshot(spec["pressure_png"], view, ImageResolution=spec["size"], TransparentBackground=0,
                   CompressionLevel="9")
    print("%s contact_pressure %.17g %.17g" % (spec["pressure_png"], lo, hi))


def main():
    with open(sys.argv[1]) as f:
        spec = json.load(f)
    # The cameras are placed here; paraview.simple would reset the first one to frame everything.
    _DisableFirstRenderCameraReset()
    deformed(spec)
    pressure(spec)


if __name__ == "__main__":
    main()
