"""tools/bench/bench_python.py [--repeats N] [--sizes N,...]: the cost of the Python layer.

For each particle count, an adapter with one 640x360 view is called from Python on render
steps and on steps that are not render steps; per call, the wall time seen from Python against
the library's own time for the step (last_stats["seconds_total"], measured inside the C++
execute()). Their difference is what the bindings add: argument checks, building the views of
the numpy arrays, releasing the GIL. Prints a Markdown table of medians (docs/benchmarks.md).

    PYTHONPATH=build/python /usr/bin/python3 tools/bench/bench_python.py
"""
import argparse
import statistics
import tempfile
import time

import numpy

import voxspan

CONFIG = """
views: [{{name: v, width: 640, height: 360, shading: translucent}}]
outputs: {{png: {{enabled: false}}, stats: {{enabled: false}}}}
trigger: {{every_steps: 2}}
output_folder: {folder}
"""


def block(n, spacing):
    side = round((n / 2) ** (1 / 3))
    g = numpy.mgrid[0:2 * side, 0:side, 0:side].reshape(3, -1).T
    return numpy.ascontiguousarray((g + 0.5) * spacing)


def measure(n, repeats):
    spacing = 0.01
    x = block(n, spacing)
    rho = numpy.full(len(x), 1000.0)
    u = numpy.zeros((len(x), 3))
    with tempfile.TemporaryDirectory() as folder:
        adapter = voxspan.Adapter.from_config_text(CONFIG.format(folder=folder), spacing=spacing)
        render, idle, inside = [], [], []
        for step in range(2 * repeats + 2):
            start = time.perf_counter()
            status = adapter.execute(step, 0.0, x, scalars={"rho": rho}, vectors={"velocity": u})
            wall = time.perf_counter() - start
            assert status.ok, status.message
            if step < 2:
                continue  # warm-up
            if step % 2 == 0:
                render.append(wall)
                inside.append(adapter.last_stats["seconds_total"])
            else:
                idle.append(wall)
        adapter.finish()
    overhead = [w - i for w, i in zip(render, inside)]
    return len(x), statistics.median(render), statistics.median(inside), \
        statistics.median(overhead), statistics.median(idle)


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--repeats", type=int, default=9)
    p.add_argument("--sizes", default="10000,100000,1000000")
    a = p.parse_args()
    print("| particles | render step from Python (ms) | in the library (ms) | Python layer (ms) "
          "| not a render step, from Python (us) |")
    print("|---:|---:|---:|---:|---:|")
    for n in (int(s) for s in a.sizes.split(",")):
        count, render, inside, overhead, idle = measure(n, a.repeats)
        print(f"| {count} | {1e3 * render:.2f} | {1e3 * inside:.2f} | {1e3 * overhead:.3f} "
              f"| {1e6 * idle:.1f} |")


if __name__ == "__main__":
    main()
