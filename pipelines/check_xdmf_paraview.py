"""Opens an XDMF particle-field file with ParaView's reader and prints what ParaView sees.

usage: xvfb-run -a pvpython pipelines/check_xdmf_paraview.py FILE.xdmf
(ParaView is not a project dependency: apt-get install paraview python3-paraview xvfb)
"""
import sys

from paraview import servermanager
from paraview.simple import XDMFReader


def main(path: str) -> None:
    reader = XDMFReader(FileNames=[path])
    reader.UpdatePipelineInformation()
    times = list(reader.TimestepValues) or [0.0]
    print(f"{path}: {len(times)} time steps {times[0]:g} .. {times[-1]:g} s")
    for t in times:
        reader.UpdatePipeline(t)
        data = servermanager.Fetch(reader)
        if data.IsA("vtkMultiBlockDataSet"):
            data = data.GetBlock(0)
        arrays = data.GetPointData()
        names = [f"{arrays.GetArray(i).GetName()}[{arrays.GetArray(i).GetNumberOfComponents()}]"
                 for i in range(arrays.GetNumberOfArrays())]
        print(f"  t = {t:g}: {data.GetNumberOfPoints()} points, {data.GetNumberOfCells()} cells, "
              f"bounds {tuple(round(b, 6) for b in data.GetBounds())}, arrays {', '.join(names)}")


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    main(sys.argv[1])
