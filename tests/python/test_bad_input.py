"""Bad input from Python: a clear exception naming the argument, or a counted skip as in C++;
never a crash of the interpreter."""
import numpy
import pytest

import voxspan
from conftest import SPACING


@pytest.fixture
def adapter(config_file):
    a = voxspan.Adapter.from_config_file(config_file, spacing=SPACING)
    yield a
    a.finish()


def test_wrong_dtype_is_a_type_error_naming_the_argument(adapter, block):
    with pytest.raises(TypeError, match="x must be float32 or float64, got int64"):
        adapter.execute(0, 0.0, block.astype(numpy.int64))
    with pytest.raises(TypeError, match="x must be a numpy array, got list"):
        adapter.execute(0, 0.0, block.tolist())
    with pytest.raises(TypeError, match="same dtype"):
        adapter.execute(0, 0.0, block[:, 0], block[:, 1].astype(numpy.float32), block[:, 2])
    with pytest.raises(TypeError, match="must be float32 or float64"):
        adapter.execute(0, 0.0, block.astype(">f8"))  # byte-swapped: not viewable


def test_wrong_shapes_and_lengths_are_value_errors(adapter, block):
    with pytest.raises(ValueError, match=r"x must have shape \(n, 3\)"):
        adapter.execute(0, 0.0, block[:, :2])
    with pytest.raises(ValueError, match="z has 10 values; expected"):
        adapter.execute(0, 0.0, block[:, 0], block[:, 1], block[:10, 2])
    with pytest.raises(ValueError, match="or as three arrays"):
        adapter.execute(0, 0.0, block[:, 0], block[:, 1])
    with pytest.raises(ValueError, match=r"scalars\['density'\] has 3 values"):
        adapter.execute(0, 0.0, block, scalars={"density": numpy.ones(3)})
    with pytest.raises(ValueError, match=r"vectors\['velocity'\] has"):
        adapter.execute(0, 0.0, block, vectors={"velocity": numpy.ones((4, 3))})
    with pytest.raises(ValueError, match="negative or zero stride"):
        adapter.execute(0, 0.0, block[::-1])
    with pytest.raises(ValueError, match="owned = "):
        adapter.execute(0, 0.0, block, owned=len(block) + 1)
    grid = voxspan.Grid([0, 0, 0], 0.1, [4, 4, 4], offsets=numpy.zeros(10, numpy.int32))
    with pytest.raises(ValueError, match="grid.offsets must be one-dimensional with 65 entries"):
        adapter.execute(0, 0.0, block, grid=grid)
    assert adapter.steps_seen == 0  # nothing reached the library


def test_bad_radii_and_attribute_names_are_errors_naming_them(adapter, block):
    for radius in (0.0, -1.0, float("nan"), float("inf")):
        with pytest.raises(ValueError, match=r"radius = .* is not a positive finite number"):
            adapter.execute(0, 0.0, block, radius=radius)
    ones = numpy.ones(len(block))
    with pytest.raises(ValueError, match="'velocity' is given twice"):
        adapter.execute(0, 0.0, block, scalars={"velocity": ones},
                        vectors={"velocity": numpy.ones((len(block), 3))})
    with pytest.raises(ValueError, match="scalars: an attribute name is empty"):
        adapter.execute(0, 0.0, block, scalars={"": ones})
    with pytest.raises(TypeError, match="attribute names must be str, got 1"):
        adapter.execute(0, 0.0, block, scalars={1: ones})
    assert adapter.steps_seen == 0


def test_nan_positions_are_counted_and_left_out(adapter, block):
    block[:7] = numpy.nan
    block[7, 1] = numpy.inf
    status = adapter.execute(0, 0.0, block)
    assert status.ok
    assert adapter.last_stats["counts"]["dropped_nonfinite"] == 8


def test_config_errors_are_voxspan_errors_with_the_line(tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text("views:\n  - name: a\n    widht: 100\n")
    with pytest.raises(voxspan.Error, match=r"bad.yaml:3:.*widht"):
        voxspan.Adapter.from_config_file(str(bad), spacing=SPACING)
    with pytest.raises(voxspan.Error, match="cannot read config file"):
        voxspan.Adapter.from_config_file(str(tmp_path / "missing.yaml"), spacing=SPACING)
    assert issubclass(voxspan.Error, RuntimeError)


def test_no_spacing_is_an_error_naming_it(config_file):
    with pytest.raises(voxspan.Error, match="spacing"):
        voxspan.Adapter.from_config_file(config_file)


def test_an_unwritable_output_folder_is_an_error(tmp_path):
    (tmp_path / "file").write_text("")
    with pytest.raises(voxspan.Error, match="file"):
        voxspan.Adapter.from_config_text(f"output_folder: {tmp_path / 'file' / 'out'}\n",
                                         spacing=SPACING)


def test_a_missing_particle_file_is_an_error_naming_it(tmp_path):
    with pytest.raises(voxspan.Error, match="nothing.vtp"):
        voxspan.read_particles(str(tmp_path / "nothing.vtp"))
