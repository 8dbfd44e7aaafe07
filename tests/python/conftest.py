"""Shared set-up of the Python tests: a small block of water and a config with small views."""
import numpy
import pytest

SPACING = 0.05

# Two small views (translucent framed automatically, refractive from another side), PNG and
# stats every step, no fsync: quick on two cores.
VIEWS = """
views:
  - {name: glass, width: 96, height: 64, shading: translucent}
  - {name: water, width: 80, height: 80, shading: refractive, camera: {direction: [1, 1, -0.5]}}
outputs:
  png: {trigger: {every_steps: 1}}
  stats: {trigger: {every_steps: 1}}
trigger: {every_steps: 1}
writer: {fsync: false}
"""


def water_block(nx=16, ny=10, nz=8, dtype=numpy.float64):
    """A rest lattice nx x ny x nz at SPACING, as an (n, 3) C-contiguous array."""
    grid = numpy.mgrid[0:nx, 0:ny, 0:nz].reshape(3, -1).T
    return numpy.ascontiguousarray((grid + 0.5) * SPACING, dtype=dtype)


@pytest.fixture
def block():
    return water_block()


@pytest.fixture
def config_file(tmp_path):
    path = tmp_path / "views.yaml"
    path.write_text(VIEWS + f"output_folder: {tmp_path / 'out'}\n")
    return str(path)
