# pvpython script: every step of an XDMF result as ParaView's own Xdmf3
# reader gives it, one line per step:
#     time points cells  x y z body  x y z body ...   (one x y z body per point)
# where body is the "body" cell value of the cells using the point.
# Usage: pvpython --force-offscreen-rendering paraview_poses.py RESULT.xdmf TABLE.txt
import sys

from paraview import servermanager as sm
from paraview.simple import Xdmf3ReaderS

reader = Xdmf3ReaderS(FileName=[sys.argv[1]])
reader.UpdatePipelineInformation()
with open(sys.argv[2], "w") as out:
    for t in reader.TimestepValues:
        reader.UpdatePipeline(t)
        grid = sm.Fetch(reader)
        body_of_cell = grid.GetCellData().GetArray("body")
        body = [-1] * grid.GetNumberOfPoints()
        for c in range(grid.GetNumberOfCells()):
            ids = grid.GetCell(c).GetPointIds()
            for k in range(ids.GetNumberOfIds()):
                body[ids.GetId(k)] = int(body_of_cell.GetValue(c))
        out.write("%r %d %d" % (t, grid.GetNumberOfPoints(), grid.GetNumberOfCells()))
        for i in range(grid.GetNumberOfPoints()):
            out.write(" %.9g %.9g %.9g %d" % (grid.GetPoint(i) + (body[i],)))
        out.write("\n")
