"""Offline use: the readers and render() for arrays a notebook already has."""
import json
import subprocess

import numpy
import pytest

import voxspan
from conftest import SPACING


def test_render_returns_the_pictures_it_writes(tmp_path, block):
    pictures = voxspan.render(block, output=str(tmp_path))
    assert list(pictures) == ["main"]  # the default view
    picture = pictures["main"]
    assert picture.dtype == numpy.uint8 and picture.shape[2] == 4
    png = voxspan.read_png(str(next(tmp_path.rglob("main_*.png"))))
    assert numpy.array_equal(png, picture)
    # the water stands out from the background
    assert numpy.any(picture[:, :, :3] != picture[0, 0, :3])


def test_render_estimates_the_spacing(tmp_path, block):
    assert abs(voxspan.estimate_spacing(block) - SPACING) < 1e-9
    given = voxspan.render(block, spacing=SPACING, output=str(tmp_path / "a"))
    estimated = voxspan.render(block[:, 0], block[:, 1], block[:, 2], output=str(tmp_path / "b"))
    assert numpy.array_equal(given["main"], estimated["main"])


def test_render_takes_what_a_notebook_has(tmp_path, block):
    """One render() call copies what the library cannot view (a list, big-endian, reversed,
    integers) and takes a radius per particle and pathlib paths."""
    reference = voxspan.render(block, spacing=SPACING, output=tmp_path / "a")["main"]
    for name, positions in [("list", block.tolist()), ("big", block.astype(">f8")),
                            ("reversed", block[::-1])]:
        picture = voxspan.render(positions, spacing=SPACING, output=tmp_path / name)["main"]
        assert numpy.array_equal(picture, reference), name
    radii = numpy.full(len(block), SPACING)
    per_particle = voxspan.render(block, spacing=SPACING, radius=radii, output=tmp_path / "r")
    assert numpy.array_equal(per_particle["main"], reference)
    smaller = voxspan.render(block, spacing=SPACING, radius=0.5 * radii, output=tmp_path / "s")
    assert not numpy.array_equal(smaller["main"], reference)
    png = next((tmp_path / "a").rglob("main_*.png"))
    assert numpy.array_equal(voxspan.read_png(png), reference)  # a pathlib.Path


def test_render_takes_the_config_as_a_file_text_or_dict(tmp_path, block):
    """The same view from a YAML file, YAML text and a dict: one picture."""
    keys = {"views": [{"name": "small", "width": 64, "height": 48}]}
    text = "views: [{name: small, width: 64, height: 48}]\n"
    (tmp_path / "c.yaml").write_text(text)
    pictures = [voxspan.render(block, spacing=SPACING, config=config, output=tmp_path / name)
                for name, config in [("file", tmp_path / "c.yaml"), ("text", text),
                                     ("dict", keys)]]
    assert all(list(p) == ["small"] and p["small"].shape == (48, 64, 4) for p in pictures)
    assert all(numpy.array_equal(p["small"], pictures[0]["small"]) for p in pictures)


def test_a_dicts_bad_key_is_named_on_its_own_line(tmp_path, block):
    """The dict is written one key a line: the error's line is that of the key, not column 527
    of one line the user never saw."""
    keys = {"views": [{"name": "a", "width": 64, "height": 48},
                      {"name": "b", "width": 64, "height": 48, "legnd": False}]}
    with pytest.raises(voxspan.Error, match=r"<config text>:\d+:\d+: views\[1\]\.legnd") as e:
        voxspan.render(block, spacing=SPACING, config=keys, output=tmp_path)
    line, column = map(int, str(e.value).split("<config text>:")[1].split(":")[:2])
    assert line > 5 and column < 20, str(e.value)


def test_no_particles_render_the_empty_pictures(tmp_path, block):
    """Zero rows are zero particles: no spacing to estimate, a picture with no fluid in it."""
    empty = voxspan.render(numpy.zeros((0, 3)), output=str(tmp_path / "empty"))["main"]
    water = voxspan.render(block, output=str(tmp_path / "water"))["main"]
    assert empty.shape == water.shape
    stats = json.loads((tmp_path / "empty" / "stats.jsonl").read_text().splitlines()[0])
    assert stats["counters"]["particles"] == 0


def test_read_particles_round_trip(tmp_path, block):
    csv = tmp_path / "p.csv"
    numpy.savetxt(csv, numpy.column_stack([block, numpy.arange(len(block))]), delimiter=",",
                  header="x,y,z,density", comments="")
    data = voxspan.read_particles(str(csv))
    assert numpy.allclose(data["positions"], block)
    assert numpy.allclose(data["attributes"]["density"], numpy.arange(len(block)))
    assert data["positions"].flags.owndata is False  # the reader's buffer, not a copy
