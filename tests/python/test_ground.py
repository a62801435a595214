"""ground_mask / extract_ground: the labels `hylo ground` gives the same points."""

import json

import numpy as np
import pytest

import hylo
from conftest import run_hylo


def site():
    """40 x 40 m field rising 2 % along x, a point every 0.5 m with 1 cm noise, and a 6 x 6 m
    building 4 m high; float32-exact, so the file the command reads holds these very values."""
    rng = np.random.default_rng(3)
    x, y = np.meshgrid(np.arange(0, 40.01, 0.5), np.arange(0, 40.01, 0.5))
    x, y = x.ravel(), y.ravel()
    roof = (np.abs(x - 20) <= 3) & (np.abs(y - 20) <= 3)
    z = 0.02 * x + 4.0 * roof + rng.normal(0, 0.01, x.size)
    return np.column_stack([x, y, z]).astype(np.float32).astype(np.float64)


def command_split(tmp_path, points, *options):
    """The ground and object clouds `hylo ground` writes, and its JSON summary."""
    hylo.write_cloud(tmp_path / "site.pcd", points)
    run_hylo("ground", "--in", tmp_path / "site.pcd", "--out-ground", tmp_path / "g.pcd",
             "--out-objects", tmp_path / "o.pcd", "--json", tmp_path / "g.json", *options)
    return (hylo.read_cloud(tmp_path / "g.pcd"), hylo.read_cloud(tmp_path / "o.pcd"),
            json.loads((tmp_path / "g.json").read_text()))


@pytest.mark.parametrize("method, options, flags", [
    ("smrf", None, []),
    ("smrf", {"smrf": {"elevation_threshold_m": 0.1}}, ["--smrf-threshold", "0.1"]),
    ("csf", None, ["--method", "csf"]),
])
def test_labels_are_the_commands(tmp_path, method, options, flags):
    points = site()
    ground, objects, summary = command_split(tmp_path, points, *flags)
    result = hylo.extract_ground(points, method, options)
    np.testing.assert_array_equal(points[result.mask], ground)
    np.testing.assert_array_equal(points[~result.mask], objects)
    assert (result.num_ground, result.num_objects) == (summary["points"]["ground"],
                                                      summary["points"]["objects"])
    assert result.method == summary["method"]
    assert ground.shape[0] > 0.9 * len(points) - 200  # the field is ground, the roof is not
    roof = (np.abs(points[:, 0] - 20) < 2.5) & (np.abs(points[:, 1] - 20) < 2.5)
    assert not result.mask[roof].any()
    np.testing.assert_array_equal(hylo.ground_mask(points, method, options), result.mask)


def test_height_above_ground_and_invalid_points():
    points = site()
    points[7] = np.nan
    result = hylo.extract_ground(points)
    assert result.mask.dtype == bool and result.mask.shape == (len(points),)
    assert not result.mask[7] and np.isnan(result.height_above_ground_m[7])
    assert result.num_invalid == 1
    roof = (np.abs(points[:, 0] - 20) < 2.5) & (np.abs(points[:, 1] - 20) < 2.5)
    assert np.all(result.height_above_ground_m[roof] > 3.0)


def test_float32_and_strided_arrays_give_the_same_labels():
    points = site()
    wide = np.zeros((len(points), 5))
    wide[:, 1:4] = points
    mask = hylo.ground_mask(points)
    np.testing.assert_array_equal(hylo.ground_mask(wide[:, 1:4]), mask)
    np.testing.assert_array_equal(hylo.ground_mask(points.astype(np.float32)), mask)


def test_progress_reports_the_openings():
    calls = []
    hylo.ground_mask(site(), progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1][0] == calls[-1][1] > 0


def test_bad_input_raises_value_error():
    points = site()
    with pytest.raises(ValueError, match="method: 'pmf' is not one of smrf, csf"):
        hylo.ground_mask(points, method="pmf")
    with pytest.raises(ValueError, match=r"ground\.smrf\.cell_m = -1"):
        hylo.ground_mask(points, options={"smrf": {"cell_m": -1}})
    with pytest.raises(ValueError, match=r"ground\.smrf\.cel: unknown key"):
        hylo.ground_mask(points, options={"smrf": {"cel": 1}})
    with pytest.raises(ValueError, match="method="):
        hylo.ground_mask(points, options={"method": "csf"})
    with pytest.raises(ValueError, match=r"points: expected shape \(N, 3\)"):
        hylo.ground_mask(points[:, :2])
    with pytest.raises(ValueError, match="points: "):
        hylo.ground_mask(np.zeros((0, 3)))
