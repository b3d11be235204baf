"""What ParaView shows of an output: run by pvpython (ParaView 5.11), not by python3.

    pvpython paraview_dump.py DIR/solution.xdmf OUT.json [DIR2/solution.xdmf OUT2.json ...]

Opens each XDMF file with each ParaView reader that offers it (Xdmf3ReaderS, Xdmf3ReaderT, the legacy XDMFReader) and
writes, per reader, the class of the dataset it gives, its time steps, and at the last time step the blocks in order
with their points (x, y, z), cell connectivity and every point and cell array: its component names as ParaView's array
information gives them (the names a user picks in the GUI) and its values. The per-block files beside it (body.xdmf,
obstacle.xdmf, contact_boundary.xdmf, where they exist) are dumped the same way under "files".
"""
import json
import os
import sys

from paraview import servermanager
from paraview.simple import XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT

READERS = {"Xdmf3ReaderS": lambda path: Xdmf3ReaderS(FileName=[path]),
           "Xdmf3ReaderT": lambda path: Xdmf3ReaderT(FileName=[path]),
           "XDMFReader": lambda path: XDMFReader(FileNames=[path])}


def arrays(data, info):
    out = {}
    for i in range(data.GetNumberOfArrays()):
        a = data.GetArray(i)
        name = a.GetName()
        n = a.GetNumberOfComponents()
        out[name] = {"components": [info[name].GetComponentName(k) if n > 1 else "" for k in range(n)],
                     "values": [list(a.GetTuple(t)) for t in range(a.GetNumberOfTuples())]}
    return out


def block(b, reader):
    cells = []
    for c in range(b.GetNumberOfCells()):
        ids = b.GetCell(c).GetPointIds()
        cells.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
    return {"points": [list(b.GetPoint(p)) for p in range(b.GetNumberOfPoints())], "cells": cells,
            "point_data": arrays(b.GetPointData(), reader.PointData),
            "cell_data": arrays(b.GetCellData(), reader.CellData)}


def dump(reader):
    # One load step gives a number, several a list.
    times = reader.TimestepValues
    times = [times] if isinstance(times, float) else list(times)
    reader.UpdatePipeline(times[-1] if times else 0.0)
    data = servermanager.Fetch(reader)
    blocks = []
    if data.IsA("vtkCompositeDataSet"):
        it = data.NewIterator()
        it.InitTraversal()
        while not it.IsDoneWithTraversal():
            blocks.append(block(it.GetCurrentDataObject(), reader))
            it.GoToNextItem()
    else:
        blocks.append(block(data, reader))
    return {"class": data.GetClassName(), "times": times, "blocks": blocks}


def main():
    for path, out in zip(sys.argv[1::2], sys.argv[2::2]):
        result = {name: dump(make(path)) for name, make in READERS.items()}
        result["files"] = {}
        for name in ("body", "obstacle", "contact_boundary"):
            single = os.path.join(os.path.dirname(path), name + ".xdmf")
            if os.path.exists(single):
                result["files"][name] = {reader: dump(make(single)) for reader, make in READERS.items()}
        with open(out, "w") as f:
            json.dump(result, f)


if __name__ == "__main__":
    main()
