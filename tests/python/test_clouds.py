"""read_cloud / write_cloud: the project's readers and writers, arrays in and out."""

import numpy as np
import pytest

import hylo
from conftest import data_dir, run_hylo


def cloud(n=500, seed=0):
    # float32-exact values: every format (float32 PCD/PLY/KITTI) reads them back exactly
    return np.random.default_rng(seed).uniform(-50, 50, (n, 3)).astype(np.float32).astype(np.float64)


@pytest.mark.parametrize("name", ["c.pcd", "c.ply", "c.bin", "c.las"])
def test_written_clouds_read_back(tmp_path, name):
    points = cloud()
    if name.endswith(".las"):
        points = np.round(points, 3)  # on LAS's 0.1 mm grid
    hylo.write_cloud(tmp_path / name, points, intensity=np.arange(len(points), dtype=float))
    back = hylo.read_cloud(tmp_path / name)
    assert back.shape == points.shape and back.dtype == np.float64
    np.testing.assert_allclose(back, points, rtol=0, atol=1e-9 if not name.endswith(".las") else 1e-4)


def test_read_cloud_hands_over_the_readers_memory(tmp_path):
    hylo.write_cloud(tmp_path / "c.pcd", cloud())
    points = hylo.read_cloud(str(tmp_path / "c.pcd"))
    assert points.flags.c_contiguous and not points.flags.owndata  # the library's vector, not a copy
    del points  # freed with the array (no leak, no double free)


def test_read_cloud_matches_what_the_command_reads(tmp_path):
    # `hylo eval c2c` of a file against itself reads both through the same reader.
    hylo.write_cloud(tmp_path / "c.ply", cloud(2000))
    run_hylo("eval", "c2c", "--cloud", tmp_path / "c.ply", "--ref", tmp_path / "c.ply",
             "--json", tmp_path / "c2c.json")
    import json

    summary = json.loads((tmp_path / "c2c.json").read_text())
    assert summary["num_points"] == len(hylo.read_cloud(tmp_path / "c.ply"))


def test_real_las_files():
    simple = data_dir() / "las" / "simple.las"
    if not simple.exists():
        pytest.skip(f"real data absent: {simple} (set HYLO_DATA_DIR)")
    points = hylo.read_cloud(simple)
    assert points.shape == (1065, 3) and np.isfinite(points).all()
    with pytest.raises(OSError, match="LAZ"):
        hylo.read_cloud(simple.with_suffix(".laz"))


def test_bad_files_raise_os_error_naming_the_file(tmp_path):
    with pytest.raises(FileNotFoundError, match="missing.pcd"):
        hylo.read_cloud(tmp_path / "missing.pcd")
    (tmp_path / "c.xyz").write_text("1 2 3\n")
    with pytest.raises(OSError, match="c.xyz"):
        hylo.read_cloud(tmp_path / "c.xyz")
    (tmp_path / "cut.pcd").write_text("VERSION 0.7\nFIELDS x y z\nSIZE 4 4 4\nTYPE F F F\n"
                                      "COUNT 1 1 1\nWIDTH 5\nHEIGHT 1\nPOINTS 5\nDATA binary\n")
    with pytest.raises(OSError, match="cut.pcd"):
        hylo.read_cloud(tmp_path / "cut.pcd")
    with pytest.raises(OSError):
        hylo.write_cloud(tmp_path / "no_such_dir" / "c.pcd", cloud(3))


def test_bad_arrays_raise_value_error(tmp_path):
    with pytest.raises(ValueError, match=r"points: expected shape \(N, 3\), got \(4, 2\)"):
        hylo.write_cloud(tmp_path / "c.pcd", np.zeros((4, 2)))
    with pytest.raises(ValueError, match="points: expected a numeric array"):
        hylo.write_cloud(tmp_path / "c.pcd", [["a", "b", "c"]])
    with pytest.raises(ValueError, match="intensity: expected one value per point"):
        hylo.write_cloud(tmp_path / "c.pcd", np.zeros((4, 3)), intensity=np.zeros(3))
    assert not (tmp_path / "c.pcd").exists()
