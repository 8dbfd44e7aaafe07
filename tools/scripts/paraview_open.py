#!/usr/bin/env pvpython
"""tools/scripts/paraview_open.py - opens VTK files in ParaView as a user would and says what it read.

    pvpython tools/scripts/paraview_open.py FILE_OR_FOLDER...

Every .vtp, .vti, .vtu, .pvtp, .pvtu and .pvd given (folders: every such file below them) is
opened with ParaView's OpenDataFile, updated at every time step it lists, and summarised as one
line: points, cells, point arrays, cell arrays. An error from ParaView's readers (they print
"ERR|" and leave the output empty) fails the file; the exit status is the number of files
that failed. ParaView and our build dependencies cannot share a Debian 12 root
(`paraview` conflicts with `libvtk9-dev`), so this runs in a root of its own:
docs/runtime.md ("ParaView") has the commands.
"""
import os
import sys

from paraview import servermanager, simple
from paraview.vtk import vtkCommand
from vtkmodules.vtkCommonCore import vtkOutputWindow

EXTENSIONS = (".vtp", ".vti", ".vtu", ".pvtp", ".pvtu", ".pvd")


class ErrorCounter:
    """Counts the error and warning messages VTK's output window receives while a file opens."""

    def __init__(self):
        self.messages = []
        window = vtkOutputWindow.GetInstance()
        window.AddObserver(vtkCommand.ErrorEvent, self._record)
        window.AddObserver(vtkCommand.WarningEvent, self._record)

    def _record(self, _caller, _event, message=None):
        # VTK's text is "ERROR: In FILE, line N\nCLASS (ADDRESS): what"; the second line says it.
        lines = str(message or "").strip().splitlines()
        self.messages.append(lines[1] if len(lines) > 1 else (lines[0] if lines else "(no text)"))

    _record.CallDataType = "string0"  # VTK passes the message text to the observer


def files_under(arguments):
    for arg in arguments:
        if os.path.isdir(arg):
            for root, _dirs, names in sorted(os.walk(arg)):
                for name in sorted(names):
                    if name.endswith(EXTENSIONS):
                        yield os.path.join(root, name)
        else:
            yield arg


def array_names(attributes):
    return ",".join(attributes.keys()) or "-"


def summarise(path, errors):
    before = len(errors.messages)
    reader = simple.OpenDataFile(path)
    if reader is None:
        return None, "ParaView has no reader for it"
    times = list(getattr(reader, "TimestepValues", []) or [])
    lines = []
    for t in times or [None]:
        if t is None:
            reader.UpdatePipeline()
        else:
            reader.UpdatePipeline(t)
        info = reader.GetDataInformation()
        at = "" if t is None else f" t={t:g}"
        lines.append(f"{at} points={info.GetNumberOfPoints()} cells={info.GetNumberOfCells()}"
                     f" point_arrays={array_names(reader.PointData)}"
                     f" cell_arrays={array_names(reader.CellData)}")
        if info.GetNumberOfPoints() == 0:
            errors.messages.append(f"no points read{at}")
    simple.Delete(reader)
    new_errors = errors.messages[before:]
    if not new_errors:
        return lines, None
    more = f" (and {len(new_errors) - 1} more messages)" if len(new_errors) > 1 else ""
    return lines, new_errors[0] + more


def main(arguments):
    if not arguments:
        print(__doc__.strip().splitlines()[2].strip(), file=sys.stderr)
        return 2
    print(f"paraview {servermanager.vtkSMProxyManager.GetParaViewSourceVersion()}")
    errors = ErrorCounter()
    failed = 0
    for path in files_under(arguments):
        lines, error = summarise(path, errors)
        if error:
            failed += 1
            print(f"FAIL {path}: {error}")
        else:
            for line in lines:
                print(f"ok   {path}:{line}")
    return failed


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
