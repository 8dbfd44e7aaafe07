"""mpiexec -n N python3 mpi_check.py OUTDIR: the adapter on every rank of mpi4py's
COMM_WORLD, each with its slab of a water block (owned particles, then the neighbours' within
three spacings as ghosts) and its density; rank 0's pictures (two surface views and an SPH
slice of the density, whose sum runs over every rank's owned particles, and the particles as
glyphs coloured by density, composited by depth) must equal, to 1/255,
those of one process that renders the whole block; the two surface views exactly, in float
(the merged span image is one process's, bit for bit). Exit status 0 when they do."""
import sys

import numpy
from mpi4py import MPI

import voxspan
from conftest import SPACING, VIEWS, water_block

comm = MPI.COMM_WORLD
rank, size = comm.Get_rank(), comm.Get_size()
out = sys.argv[1]
block = water_block(24, 10, 8)
block[:, 2] += 0.02 * numpy.sin(7 * block[:, 0])  # a wavy surface, not a lattice's flat top
density = 1000 + 50 * numpy.sin(5 * block[:, 0]) * block[:, 2]
SLICE = ("  - {name: density, kind: slice, width: 96, height: 48, quantity: density,"
         " shepard: true, plane: {normal: [0, -1, 0]}}\n")
GLYPHS = "  - {name: glyphs, kind: particles, width: 96, height: 54, color_by: density}\n"
views = VIEWS.replace("views:\n", "views:\n" + SLICE + GLYPHS)

edges = numpy.linspace(block[:, 0].min(), block[:, 0].max() + 1e-9, size + 1)
lo, hi = edges[rank], edges[rank + 1]
own = (block[:, 0] >= lo) & (block[:, 0] < hi)
near = ~own & (block[:, 0] >= lo - 3 * SPACING) & (block[:, 0] < hi + 3 * SPACING)
part = numpy.ascontiguousarray(numpy.concatenate([block[own], block[near]]))
part_density = numpy.concatenate([density[own], density[near]])

config = views + f"output_folder: {out}/ranks\n"
with voxspan.Adapter.from_config_text(config, spacing=SPACING, comm=comm) as adapter:
    status = adapter.execute_last(0, 0.0, part, owned=int(own.sum()),
                                  scalars={"density": part_density})
    ranks = adapter.pictures()
    ranks_linear = adapter.pictures(linear=True)
if not status:
    print(f"rank {rank}: {status.message}", file=sys.stderr)
    sys.exit(1)
if rank != 0:
    sys.exit(0 if not ranks else 1)  # the pictures exist on rank 0 only

one = voxspan.Adapter.from_config_text(views + f"output_folder: {out}/one\n", spacing=SPACING)
assert one.execute_last(0, 0.0, block, scalars={"density": density}).ok
alone = one.pictures()
alone_linear = one.pictures(linear=True)
one.finish()
worst = 0
for view, picture in alone.items():
    d = numpy.abs(picture.astype(int) - ranks[view].astype(int)).max()
    print(f"view {view}: {size} ranks against one process, largest difference {d}/255")
    worst = max(worst, d)
exact = True
for view in ("glass", "water"):
    d = float(numpy.abs(alone_linear[view] - ranks_linear[view]).max())
    print(f"view {view}, linear: largest difference {d:.1e} (0: bit for bit)")
    exact = exact and d == 0
sys.exit(0 if worst <= 1 and exact and len(alone) == 4 else 1)
