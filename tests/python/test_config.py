"""Configuration from a YAML path, a dict or both: the same keys, values and errors as the
command's --config."""

import numpy as np
import pytest

import hylo
from conftest import PRESET, cli_error


def write(path, text):
    path.write_text(text)
    return path


def test_a_dict_parses_to_what_the_same_yaml_does(tmp_path):
    keys = {"backend": "sliding_window", "imu": {"rate_hz": 100, "noise": {"gyro_noise_density": 1e-4}},
            "T_imu_lidar": {"translation_m": [0.1, 0.0, 0.3]}, "lidar": {"topic": "/velodyne_points"}}
    yaml = write(tmp_path / "c.yaml", "backend: sliding_window\nimu: {rate_hz: 100, noise: "
                 "{gyro_noise_density: 1.0e-4}}\nT_imu_lidar: {translation_m: [0.1, 0.0, 0.3]}\n"
                 "lidar: {topic: /velodyne_points}\n")
    from_dict = hylo.load_config(keys)
    assert from_dict.to_yaml() == hylo.load_config(yaml).to_yaml()
    assert from_dict.backend == "sliding_window"
    assert from_dict.source == "<dict>"


def test_numpy_values_none_and_imu_none_are_accepted():
    config = hylo.load_config({"imu": "none", "T_imu_lidar": {"translation_m": np.zeros(3)},
                               "preprocess": {"scan_voxel_m": np.float32(0.25), "max_range_m": None}})
    assert "imu: none" in config.to_yaml()
    assert hylo.load_config(None).to_yaml() == hylo.load_config({}).to_yaml()


@pytest.mark.parametrize("keys, yaml", [
    ({"imu": {"rate_hz": -1}}, "imu:\n  rate_hz: -1\n"),
    ({"lidar": {"topik": "/points"}}, "lidar:\n  topik: /points\n"),
    ({"backend": "kalman"}, "backend: kalman\n"),
    ({"map": {"voxel_size_m": "coarse"}}, "map:\n  voxel_size_m: coarse\n"),
])
def test_a_dict_fails_with_the_commands_message(tmp_path, keys, yaml):
    path = write(tmp_path / "bad.yaml", yaml)
    expected = cli_error("map", "--log", tmp_path, "--config", path, "--out", tmp_path / "out")
    with pytest.raises(ValueError) as from_file:
        hylo.load_config(path)
    assert str(from_file.value) == expected
    with pytest.raises(ValueError) as from_dict:
        hylo.load_config(keys)
    assert str(from_dict.value) == expected.replace(str(path), "<dict>")


def test_overrides_change_only_their_keys():
    preset = hylo.load_config(PRESET)
    changed = hylo.load_config(PRESET, overrides={"backend": "sliding_window",
                                                  "imu": {"rate_hz": 100}})
    assert changed.backend == "sliding_window" and preset.backend == "ieskf"
    differing = [(a, b) for a, b in zip(preset.to_yaml().splitlines(), changed.to_yaml().splitlines())
                 if a != b]
    assert [b.strip() for _, b in differing] == ["backend: sliding_window", "rate_hz: 100"]
    with pytest.raises(ValueError, match=r"<overrides>: imu.rate: unknown key"):
        hylo.load_config(PRESET, overrides={"imu": {"rate": 100}})


def test_unreadable_configuration_raises_os_error(tmp_path):
    missing = tmp_path / "missing.yaml"
    expected = cli_error("map", "--log", tmp_path, "--config", missing, "--out", tmp_path / "out")
    with pytest.raises(FileNotFoundError) as raised:
        hylo.load_config(missing)
    assert str(raised.value) == expected


def test_wrong_types_raise_type_or_value_error():
    with pytest.raises(TypeError):
        hylo.load_config(42)
    with pytest.raises(ValueError, match="key 1 is not a string"):
        hylo.load_config({1: "x"})
    with pytest.raises(ValueError, match="imu: object is not a configuration value"):
        hylo.load_config({"imu": object()})
