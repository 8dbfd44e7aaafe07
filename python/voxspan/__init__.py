"""Voxspan: in-situ rendering of SPH fluids, from Python.

The adapter inside a solver's step loop (numpy arrays are viewed, never copied)::

    import voxspan
    adapter = voxspan.Adapter.from_config_file("insitu.yaml", spacing=dx)
    for step in range(steps):
        ...advance the solver...
        status = adapter.execute(step, t, x, y, z, scalars={"density": rho},
                                 vectors={"velocity": (u, v, w)})
    adapter.finish()
    print(adapter.summary())

Offline, for arrays a notebook already has::

    pictures = voxspan.render(positions)          # {view name: (h, w, 4) uint8 array}
    data = voxspan.read_particles("dam_break_3d_1000.hdf5")

The configuration keys are those of docs/runtime.md; errors of the library are voxspan.Error
with its message; arrays that cannot be viewed are TypeError or ValueError naming them.
"""

from ._voxspan import (Adapter, Error, Grid, Status, StatusCode, __version__, estimate_spacing,
                       read_particles, read_png)

__all__ = ["Adapter", "Error", "Grid", "Status", "StatusCode", "__version__", "estimate_spacing",
           "read_particles", "read_png", "render"]


def _floats(a):
    """An array the library can view: float32 kept, anything else (lists, integers, big-endian
    or reversed arrays, record columns) copied once to contiguous native float64."""
    import numpy
    a = numpy.asarray(a)
    dtype = numpy.float32 if a.dtype == numpy.float32 else numpy.float64
    return numpy.ascontiguousarray(a, dtype=dtype)


def _config_text(config):
    """The YAML text `config` is, or None where it names a file (or is None): a dict is written
    as JSON, which YAML reads as the same map."""
    import json
    import os
    if isinstance(config, dict):
        return json.dumps(config, indent=1)  # a key a line: errors name its line
    if isinstance(config, str) and ("\n" in config or ":" in config) and not os.path.exists(config):
        return config
    return None


def render(x, y=None, z=None, *, config=None, output="voxspan-output", spacing=None, radius=None,
           scalars=None, vectors=None, step=0, time=0.0, linear=False):
    """Renders particles the caller already has, once, through the same runtime as a run:
    writes the config's files (PNG frames and stats by default) into `output` and returns the
    pictures as {view name: (height, width, 4) array} (uint8 sRGB as the PNG files; linear=True:
    float32 linear RGBA). Positions as one (n, 3) array x or as x, y, z, any numeric array or
    list (one call: what the library cannot view is copied; Adapter.execute never copies).
    spacing: the rest spacing (default: estimated, the median nearest-neighbour distance);
    radius: the sphere radius, a number or one per particle (default: the spacing); config: a
    YAML file, YAML text (a str holding a newline or a ':' and naming no file) or a dict of the
    same keys (default: every key at its default); config and output may be pathlib paths.
    No particles (zero rows) give the empty pictures. Raises voxspan.Error when the particles
    cannot be rendered."""
    import numpy
    x = _floats(x)
    if y is not None:
        y, z = _floats(y), _floats(z)
    scalars = {name: _floats(v) for name, v in (scalars or {}).items()}
    vectors = {name: tuple(_floats(c) for c in v) if isinstance(v, (tuple, list)) else _floats(v)
               for name, v in (vectors or {}).items()}
    radii = None
    if radius is not None and numpy.ndim(radius) > 0:
        radius, radii = None, _floats(radius)
    if spacing is None:
        positions = x if y is None else numpy.stack([x, y, z], axis=1)
        # With no particles nothing is drawn, so any spacing gives the same empty pictures.
        spacing = estimate_spacing(positions) if len(positions) else 1.0
        if not spacing > 0:
            raise Error("cannot estimate the particle spacing (fewer than two distinct "
                        "particles); pass spacing=")
    text = _config_text(config)
    make = Adapter.from_config_file if text is None else Adapter.from_config_text
    with make(config if text is None else text, spacing=spacing, radius=radius, offline=True,
              output=output) as adapter:
        status = adapter.execute_last(step, time, x, y, z, radius=radii, scalars=scalars,
                                      vectors=vectors)
        if not status:
            raise Error(status.message)
        return adapter.pictures(linear=linear)
