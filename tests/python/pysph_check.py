"""pysph_check.py RENDER_PARTICLES WORKDIR: PySPH's 3D dam break at a small size (dx 0.1,
0.1 s) with the adapter in its step loop (examples/pysph/dambreak_insitu.py); then
render_particles on the HDF5 files PySPH wrote at the rendered steps, with the same config and
spacing. Every picture must equal the offline one to 1/255. Exit status 77 without PySPH."""
import pathlib
import re
import shutil
import subprocess
import sys

import numpy

import voxspan

try:
    import pysph  # noqa: F401
except ImportError:
    print("pysph_check: PySPH is not installed (python3-pysph)")
    sys.exit(77)

render_particles, work = sys.argv[1], pathlib.Path(sys.argv[2])
root = pathlib.Path(__file__).resolve().parents[2]
example = root / "examples" / "pysph" / "dambreak_insitu.py"
config = root / "examples" / "pysph" / "insitu.yaml"
every = 20
shutil.rmtree(work, ignore_errors=True)  # frames of an earlier run would count here
run = subprocess.run(
    [sys.executable, str(example), "--dx", "0.1", "--tf", "0.1", "--pfreq", str(every),
     "--no-openmp", "-d", str(work / "pysph"), "--voxspan-output", str(work / "insitu")],
    capture_output=True, text=True)
print(run.stdout[-3000:], run.stderr[-3000:])
if run.returncode != 0:
    sys.exit("pysph_check: the example failed")
spacing = re.search(r"particle spacing (\S+)", run.stdout).group(1)

# PySPH's files at the rendered steps: every 20th, the first and the last.
files = sorted((work / "pysph").glob("dambreak_insitu_*.hdf5"))
steps = [int(f.stem.rsplit("_", 1)[1]) for f in files]
last = max(steps)
chosen = [f for f, s in zip(files, steps) if s % every == 0 or s == last]
offline = work / "offline"
done = subprocess.run([render_particles, "--config", str(config), "--output", str(offline),
                       "--spacing", spacing] + [str(f) for f in chosen],
                      capture_output=True, text=True)
print(done.stdout[-2000:], done.stderr[-2000:])
if done.returncode != 0:
    sys.exit("pysph_check: render_particles failed")

worst = 0
for view in ("translucent", "refractive", "pressure"):
    live = sorted((work / "insitu" / "frames").glob(f"{view}_*.png"))
    files_ = sorted((offline / "frames").glob(f"{view}_*.png"))
    if len(live) != len(chosen) or len(files_) != len(chosen):
        sys.exit(f"pysph_check: {view}: {len(live)} live and {len(files_)} offline pictures "
                 f"for {len(chosen)} files")
    for a, b in zip(live, files_):
        d = numpy.abs(voxspan.read_png(str(a)).astype(int) -
                      voxspan.read_png(str(b)).astype(int)).max()
        worst = max(worst, d)
        print(f"{a.name} against {b.name} ({view}): largest difference {d}/255")
snapshots = list((work / "insitu" / "snapshots").glob("*.vdb"))
if len(snapshots) != 1:
    sys.exit(f"pysph_check: {len(snapshots)} snapshots, expected one (the last step)")
sys.exit(0 if worst <= 1 else 1)
