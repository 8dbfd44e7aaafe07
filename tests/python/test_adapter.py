"""The adapter from Python: every layout numpy allows, named attributes, a grid, the stats."""
import numpy
import pytest

import voxspan
from conftest import SPACING, water_block


def make(config_file, **kw):
    return voxspan.Adapter.from_config_file(config_file, spacing=SPACING, **kw)


def test_module_has_the_library_version():
    assert voxspan.__version__.count(".") == 2


def test_every_layout_gives_the_same_pictures(config_file, block):
    """(n, 3), x/y/z, float32, and strided views into a larger array: one picture."""
    wide = numpy.zeros((len(block), 7))
    wide[:, 1:4] = block  # rows of 7 doubles: stride 56 bytes, x at offset 8
    soa = numpy.zeros((3, 2 * len(block)))
    soa[:, ::2] = block.T  # every other element: stride 16 bytes
    layouts = {
        "aos": (block, None, None),
        "soa": (block[:, 0].copy(), block[:, 1].copy(), block[:, 2].copy()),
        "aos strided": (wide[:, 1:4], None, None),
        "soa strided": (soa[0, ::2], soa[1, ::2], soa[2, ::2]),
        "fortran order": (numpy.asfortranarray(block), None, None),
    }
    pictures = {}
    for name, (x, y, z) in layouts.items():
        with make(config_file) as adapter:
            status = adapter.execute_last(0, 0.0, x, y, z)
            assert status.ok, (name, status.message)
            pictures[name] = adapter.pictures()
    for name, p in pictures.items():
        for view in ("glass", "water"):
            assert numpy.array_equal(p[view], pictures["aos"][view]), (name, view)
    with make(config_file) as adapter:
        assert adapter.execute_last(0, 0.0, block.astype(numpy.float32)).ok
        for view, picture in adapter.pictures().items():
            # float32 positions round differently: a few pixels on the silhouette may differ
            differ = numpy.any(picture != pictures["aos"][view], axis=2).mean()
            assert differ < 0.01, view


def test_the_library_reads_the_callers_buffer(block):
    """Zero copy: the view points into numpy's memory with numpy's strides."""
    base = block.__array_interface__["data"][0]
    axes = voxspan._voxspan._viewed_axes(block)
    assert axes == [(base + 8 * k, 24) for k in range(3)]
    x, y, z = block[:, 0], block[:, 1], block[:, 2]  # strided views, not copies
    axes = voxspan._voxspan._viewed_axes(x, y, z)
    assert axes == [(base + 8 * k, 24) for k in range(3)]


def test_a_rank_with_no_particles_passes_zero_rows(config_file):
    """An MPI rank with no particles passes empty arrays, however numpy strides them (zeros((0,
    3)) has strides (0, 0)): a step like any other, with nothing drawn."""
    empty = numpy.zeros((0, 3))
    with make(config_file) as adapter:
        assert adapter.execute(0, 0.0, empty).ok
        assert adapter.execute(1, 0.1, numpy.empty((0, 3), numpy.float32)).ok
        assert adapter.execute(2, 0.2, numpy.zeros(0), numpy.zeros(0), numpy.zeros(0)).ok
        status = adapter.execute_last(3, 0.3, empty, scalars={"density": numpy.zeros(0)},
                                      vectors={"velocity": numpy.zeros((0, 3))})
        assert status.ok, status.message
        assert adapter.last_stats["counts"]["particles"] == 0
        assert adapter.steps_seen == 4


def test_a_changed_element_changes_the_next_picture(config_file, block):
    adapter = make(config_file)
    assert adapter.execute(1, 0.1, block).ok
    before = adapter.pictures()["glass"]
    block[:40, 2] += 0.5  # forty particles jump up, in place
    assert adapter.execute(2, 0.2, block).ok
    after = adapter.pictures()["glass"]
    assert numpy.any(before != after)
    adapter.finish()


def test_memory_does_not_grow_between_steps(tmp_path):
    """Steps over the same 500 000 particles (12 MB of positions): the process does not grow
    by a copy of them per step."""
    def resident_bytes():
        with open("/proc/self/statm") as f:
            return int(f.read().split()[1]) * 4096

    x = water_block(100, 100, 50)
    adapter = voxspan.Adapter.from_config_text(
        "views: [{name: v, width: 64, height: 48}]\n"
        f"outputs: {{png: {{enabled: false}}, stats: {{enabled: false}}}}\n"
        f"trigger: {{every_steps: 1}}\noutput_folder: {tmp_path}\n", spacing=SPACING)
    for step in range(3):  # warm-up: the runtime sizes its buffers
        assert adapter.execute(step, 0.0, x).ok
    warm = resident_bytes()
    for step in range(3, 9):
        assert adapter.execute(step, 0.0, x).ok
    grown = resident_bytes() - warm
    assert grown < x.nbytes / 4, f"grew {grown} bytes over 6 steps of {x.nbytes} bytes each"
    adapter.finish()


def test_attributes_by_name_reach_the_snapshots(tmp_path, block):
    """A scalar and a vector (AoS and as three arrays) go into the VTK particle snapshot."""
    config = (f"output_folder: {tmp_path}\nviews: [{{name: v, width: 48, height: 32}}]\n"
              "outputs: {vtk: {enabled: true, cells: false, trigger: {every_steps: 1},\n"
              "              attributes: [density, velocity]}}\n"
              "trigger: {every_steps: 1}\nwriter: {fsync: false}\n")
    n = len(block)
    density = numpy.linspace(990, 1010, n)
    velocity = numpy.ascontiguousarray(numpy.tile([1.0, 2.0, 3.0], (n, 1)))
    for vectors in ({"velocity": velocity},
                    {"velocity": (velocity[:, 0], velocity[:, 1], velocity[:, 2])}):
        with voxspan.Adapter.from_config_text(config, spacing=SPACING) as adapter:
            status = adapter.execute_last(0, 0.0, block, scalars={"density": density},
                                          vectors=vectors)
            assert status.ok, status.message
        files = sorted(tmp_path.rglob("*.vtp")) + sorted(tmp_path.rglob("*.vtu"))
        assert files, "no VTK snapshot"
        data = voxspan.read_particles(str(files[-1]))
        assert {"density", "velocity"} <= set(data["attributes"]), data["attributes"].keys()
        v = data["attributes"]["velocity"]
        assert v.shape[1] == 3 and numpy.allclose(v, [1.0, 2.0, 3.0])


def test_a_grid_from_python_gives_the_pictures_of_the_built_one(config_file, block):
    cell = 2 * SPACING
    origin = block.min(axis=0) - 0.5 * SPACING
    dims = numpy.ceil((block.max(axis=0) + 0.5 * SPACING - origin) / cell).astype(int)
    ijk = numpy.floor((block - origin) / cell).astype(numpy.int64)
    cell_of = ijk[:, 0] + dims[0] * (ijk[:, 1] + dims[1] * ijk[:, 2])
    grid = voxspan.Grid(origin.tolist(), cell, dims.tolist(), cell_of=cell_of)
    with make(config_file, validate=True) as a:
        assert a.execute_last(0, 0.0, block, grid=grid).ok
        with_grid = a.pictures()
    order = numpy.argsort(cell_of, kind="stable")
    offsets = numpy.searchsorted(cell_of[order], numpy.arange(dims.prod() + 1)).astype(numpy.int32)
    ranges = voxspan.Grid(origin.tolist(), cell, dims.tolist(), offsets=offsets,
                          order=order.astype(numpy.int32))
    with make(config_file, validate=True) as a:
        assert a.execute_last(0, 0.0, block, grid=ranges).ok
        with_ranges = a.pictures()
        assert not a.last_stats["counts"]["grid_built"]  # the solver's cell order, used as is
    with make(config_file) as a:
        assert a.execute_last(0, 0.0, block).ok
        built = a.pictures()
    for view in built:
        assert numpy.array_equal(with_grid[view], built[view])
        assert numpy.array_equal(with_ranges[view], built[view])


def test_last_stats_and_summary(config_file, block):
    adapter = make(config_file)
    assert adapter.last_stats["step"] == -1
    assert adapter.execute(5, 0.5, block).ok
    s = adapter.last_stats
    assert s["step"] == 5 and s["rendered"] and s["ok"]
    assert s["counts"]["particles"] == len(block)
    assert 0 < s["counts"]["boundary"] < len(block)  # the inner particles are skipped
    assert s["seconds_total"] > 0
    assert adapter.render_steps == 1 and adapter.steps_seen == 1
    adapter.finish()
    assert "2 PNG" in adapter.summary()


def test_pictures_are_the_png_files(config_file, block, tmp_path):
    with make(config_file) as adapter:
        assert adapter.execute_last(3, 0.0, block).ok
        pictures = adapter.pictures()
        linear = adapter.pictures(linear=True)
    for view, picture in pictures.items():
        png = voxspan.read_png(str(next((tmp_path / "out").rglob(f"{view}_*.png"))))
        assert numpy.array_equal(png, picture), view
        assert linear[view].dtype == numpy.float32 and linear[view].shape == picture.shape
