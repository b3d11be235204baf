"""What ParaView shows of an output: run by pvpython (ParaView 5.11), not by python3.

    pvpython paraview_dump.py DIR/solution.xdmf OUT.json [DIR2/solution.xdmf OUT2.json ...]

Opens each XDMF file with each ParaView reader that offers it (Xdmf3ReaderS, Xdmf3ReaderT, the legacy XDMFReader) and
writes, per reader, the blocks in order with their points (x, y, z), cell connectivity and every point and cell array:
its component names as ParaView's array information gives them (the names a user picks in the GUI) and its values.
"""
import json
import sys

from paraview import servermanager
from paraview.simple import XDMFReader, Xdmf3ReaderS, Xdmf3ReaderT


def arrays(data, info):
    out = {}
    for i in range(data.GetNumberOfArrays()):
        a = data.GetArray(i)
        name = a.GetName()
        n = a.GetNumberOfComponents()
        out[name] = {"components": [info[name].GetComponentName(k) if n > 1 else "" for k in range(n)],
                     "values": [list(a.GetTuple(t)) for t in range(a.GetNumberOfTuples())]}
    return out


def dump(reader):
    reader.UpdatePipeline()
    data = servermanager.Fetch(reader)
    blocks = []
    it = data.NewIterator()
    it.InitTraversal()
    while not it.IsDoneWithTraversal():
        b = it.GetCurrentDataObject()
        cells = []
        for c in range(b.GetNumberOfCells()):
            ids = b.GetCell(c).GetPointIds()
            cells.append([ids.GetId(k) for k in range(ids.GetNumberOfIds())])
        blocks.append({"points": [list(b.GetPoint(p)) for p in range(b.GetNumberOfPoints())], "cells": cells,
                       "point_data": arrays(b.GetPointData(), reader.PointData),
                       "cell_data": arrays(b.GetCellData(), reader.CellData)})
        it.GoToNextItem()
    return blocks


def main():
    for path, out in zip(sys.argv[1::2], sys.argv[2::2]):
        result = {"Xdmf3ReaderS": dump(Xdmf3ReaderS(FileName=[path])),
                  "Xdmf3ReaderT": dump(Xdmf3ReaderT(FileName=[path])),
                  "XDMFReader": dump(XDMFReader(FileNames=[path]))}
        with open(out, "w") as f:
            json.dump(result, f)


if __name__ == "__main__":
    main()
