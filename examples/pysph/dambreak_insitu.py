"""PySPH's own 3D dam break with Voxspan in its step loop.

    PYTHONPATH=build/python python3 examples/pysph/dambreak_insitu.py [--config FILE]
        [--arrays fluid] [--render-every N] [--app MODULE:CLASS] [PySPH's options...]

PySPH's Application (pysph.examples.dam_break_3d.DamBreak3D by default; --app names any other
PySPH application) parses its own options (--dx, --tf, --pfreq, -d ...) and runs its own solver;
the adapter is attached through Solver.add_post_step_callback and renders the fluid arrays
(--arrays, comma-separated; default: fluid) every N solver steps (--render-every; default:
PySPH's output frequency --pfreq, so that every rendered step is also a file PySPH writes), the
initial state and the last step, with the views and outputs of the YAML config (default:
insitu.yaml beside this script: two views of the water and a slice of the pressure as PNG, the
stats, an OpenVDB snapshot at the end; insitu_2d.yaml beside it has views for a 2D application,
--app pysph.examples.dam_break_2d:DamBreak2D). The application's other arrays (the tank's
`boundary`, the `obstacle`) are its scenery: handed over once, they are drawn as opaque walls.

The particles are handed over as PySPH holds them: x, y, z, u, v, w, rho, p and m of the array,
numpy views of its own memory, not copies, under PySPH's names (rho, p, velocity), as the
HDF5 reader of render_particles names them (with several arrays named, they are concatenated
first, which copies). The post-step callback runs after the integrator's step and before
PySPH advances its counter: the state it sees is the one PySPH writes as step count + 1.
"""
import argparse
import importlib
import os
import sys
import time

import numpy

import voxspan

HERE = os.path.dirname(os.path.abspath(__file__))


def parse():
    p = argparse.ArgumentParser(description=__doc__.split("\n\n")[0], add_help=False)
    p.add_argument("--config", default=os.path.join(HERE, "insitu.yaml"))
    p.add_argument("--arrays", default="fluid")
    p.add_argument("--render-every", type=int, default=None)
    p.add_argument("--app", default="pysph.examples.dam_break_3d:DamBreak3D")
    p.add_argument("--voxspan-output", default=None, help="the output folder (default: config's)")
    return p.parse_known_args()


def application(name):
    module, _, cls = name.partition(":")
    return getattr(importlib.import_module(module), cls)()


def rest_spacing(arrays, dim):
    """The median (m / rho)^(1/dim) of the arrays' particles: the spacing at rest density (in a
    2D run m / rho is an area)."""
    volume = numpy.concatenate([pa.m / pa.rho for pa in arrays])
    return float(numpy.median(volume ** (1.0 / dim)))


class Insitu:
    """The adapter as a PySPH post-step callback."""

    def __init__(self, solver, arrays, scenery, config, every, output):
        self.arrays = arrays
        self.every = every
        self.spacing = rest_spacing(arrays, solver.dim)
        print(f"voxspan: particle spacing {self.spacing!r} (rest volume of {len(arrays)} "
              f"array(s)), rendering every {every} steps")
        self.adapter = voxspan.Adapter.from_config_file(config, spacing=self.spacing,
                                                        output=output or "")
        print("voxspan:", self.adapter.description())
        if scenery:  # walls stand still: given once, copied by the adapter
            walls = [numpy.concatenate([getattr(pa, n) for pa in scenery]) for n in "xyz"]
            kept = self.adapter.set_scenery(*walls)
            print(f"voxspan: scenery {', '.join(pa.name for pa in scenery)} ({kept} particles)")
        self.rendered = None  # the last step rendered
        self.python_seconds = 0.0  # wall time of execute() calls, seen from Python

    def particles(self):
        """Views of the arrays' own memory (one array), else concatenated copies."""
        names = ("x", "y", "z", "u", "v", "w", "rho", "p", "m")
        if len(self.arrays) == 1:
            return [getattr(self.arrays[0], n) for n in names]
        return [numpy.concatenate([getattr(pa, n) for pa in self.arrays]) for n in names]

    def render(self, step, t, last=False):
        x, y, z, u, v, w, rho, p, m = self.particles()
        start = time.perf_counter()
        call = self.adapter.execute_last if last else self.adapter.execute
        status = call(step, t, x, y, z, scalars={"rho": rho, "p": p, "m": m},
                      vectors={"velocity": (u, v, w)})
        self.python_seconds += time.perf_counter() - start
        self.rendered = step
        if not status:
            print(f"voxspan: step {step}: {status.message}", file=sys.stderr)

    def __call__(self, solver):
        step = solver.count + 1  # the step PySPH is about to count and maybe write
        if step % self.every == 0:
            self.render(step, solver.t + solver.dt)

    def close(self, solver):
        if self.rendered != solver.count:
            self.render(solver.count, solver.t, last=True)
        self.adapter.finish()
        print("voxspan:", self.adapter.summary())
        inside = self.adapter.seconds_in_situ
        calls = self.adapter.render_steps
        if calls:
            print(f"voxspan: {calls} render steps; per step {1e3 * self.python_seconds / calls:.2f}"
                  f" ms from Python, {1e3 * inside / calls:.2f} ms in the library")


def main():
    ours, theirs = parse()
    app = application(ours.app)
    app.setup(theirs)
    solver = app.solver
    arrays = [pa for name in ours.arrays.split(",") for pa in app.particles if pa.name == name]
    if len(arrays) != len(ours.arrays.split(",")):
        have = ", ".join(pa.name for pa in app.particles)
        sys.exit(f"dambreak_insitu: --arrays {ours.arrays}: the application has {have}")
    scenery = [pa for pa in app.particles if pa not in arrays]
    insitu = Insitu(solver, arrays, scenery, ours.config, ours.render_every or solver.pfreq,
                    ours.voxspan_output)
    insitu.render(solver.count, solver.t)  # the initial state, PySPH's first file
    solver.add_post_step_callback(insitu)
    app.solve()
    insitu.close(solver)


if __name__ == "__main__":
    main()
