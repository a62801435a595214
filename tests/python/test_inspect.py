"""hylo.inspect: the plan `hylo inspect` writes for the same files, on a small yard whose
targets each have a known fate (seen in the open, seen around a wall, shut in a box, on a
fenced island, out of range), and a route that never touches a lethal or unknown cell."""

import csv

import numpy as np
import pytest

import hylo
from conftest import run_hylo


def box_surface(lo, hi, step=0.05):
    """Points on the faces of the axis-aligned box [lo, hi], every `step` m."""
    axes = [np.arange(a, b + 1e-6, step) for a, b in zip(lo, hi)]
    x, y, z = (v.ravel() for v in np.meshgrid(*axes, indexing="ij"))
    on_face = np.zeros(x.size, bool)
    for v, a, b in ((x, lo[0], hi[0]), (y, lo[1], hi[1]), (z, lo[2], hi[2])):
        on_face |= (np.abs(v - a) < 1e-3) | (np.abs(v - b) < 1e-3)
    return np.column_stack([x, y, z])[on_face]


TARGETS = """id,x,y,z
open,6,10,1.5
behind_wall,16,5,1.5
in_box,21,16,1.0
island,27.5,3,1.0
far,100,10,1.5
"""


@pytest.fixture(scope="module")
def yard(tmp_path_factory):
    """30 x 20 m of flat ground (a point every 0.1 m); a 3 m wall at x = 12 (y 0..14); a 2 m
    box closed on every side around (21, 16, 1); an island x > 24.5, y < 6.5 fenced by 3 m
    walls. The costmap is `hylo traversability`'s, the targets a CSV in the map frame."""
    d = tmp_path_factory.mktemp("yard")
    x, y = np.meshgrid(np.arange(0.05, 30, 0.1), np.arange(0.05, 20, 0.1))
    ground = np.column_stack([x.ravel(), y.ravel(), np.zeros(x.size)])
    objects = np.vstack([
        box_surface((12.0, 0.0, 0.0), (12.2, 14.0, 3.0)),
        box_surface((20.0, 15.0, 0.0), (22.0, 17.0, 2.0)),
        box_surface((24.4, 0.0, 0.0), (24.6, 6.6, 3.0)),
        box_surface((24.4, 6.4, 0.0), (30.0, 6.6, 3.0)),
    ])
    hylo.write_cloud(d / "ground.pcd", ground)
    hylo.write_cloud(d / "objects.pcd", objects)
    hylo.write_cloud(d / "map.pcd", np.vstack([ground, objects]))
    run_hylo("traversability", "--ground", d / "ground.pcd", "--objects", d / "objects.pcd",
             "--out", d / "costmap")
    (d / "targets.csv").write_text(TARGETS)
    run_hylo("inspect", "--map", d / "map.pcd", "--costmap", d / "costmap", "--targets",
             d / "targets.csv", "--start", "2 2", "--out", d / "cli")
    return d


def plan_of(yard, **kwargs):
    return hylo.inspect(yard / "map.pcd", yard / "costmap", yard / "targets.csv", start=(2, 2),
                        progress=False, **kwargs)


def read_ascii_grid(path):
    """An ESRI ASCII grid: (values with row 0 at the south, x0, y0, cell size)."""
    lines = path.read_text().splitlines()
    header = {k.lower(): float(v) for k, v in (line.split() for line in lines[:6])}
    values = np.loadtxt(lines[6:], ndmin=2)[::-1]
    return values, header["xllcorner"], header["yllcorner"], header["cellsize"]


def test_each_target_gets_its_status_and_reason(yard):
    plan = plan_of(yard)
    status = {t["id"]: t["status"] for t in plan.targets}
    assert status == {"open": "planned", "behind_wall": "planned", "in_box": "occluded",
                      "island": "unreachable", "far": "occluded"}
    assert "none reachable" in plan.target("island")["reason"]
    assert "15.0 m" in plan.target("far")["reason"]
    assert plan.target("in_box")["view"] is None and plan.target("in_box")["order"] == 0
    for tid in ("open", "behind_wall"):
        t = plan.target(tid)
        assert t["reason"] == "" and t["order"] in (1, 2)
        assert 1.0 <= t["range_m"] <= 15.0
        assert abs(t["view"][2] - 1.2) < 0.1  # the camera 1.2 m above flat ground
        assert np.hypot(*(t["view"][:2] - np.array([2.0, 2.0]))) > 0  # not the start itself
    # Seen around the wall's end: the camera stands east of the wall (x > 12.2).
    assert plan.target("behind_wall")["view"][0] > 12.2
    assert plan.summary["targets"] == {"total": 5, "planned": 2, "occluded": 2, "unreachable": 1}
    # A closed tour: it starts and ends at the start, and stops once per planned target.
    assert np.allclose(plan.route[0], plan.route[-1])
    assert np.hypot(*(plan.route[0] - [2.0, 2.0])) < 0.2
    assert sorted(i for stop in plan.route_stops for i in stop) == ["behind_wall", "open"]


def test_route_never_touches_lethal_or_unknown_cells(yard):
    plan = plan_of(yard)
    classes, x0, y0, cell = read_ascii_grid(yard / "costmap" / "layers" / "class.asc")
    assert (classes == 3).sum() > 100  # the walls are lethal
    for a, b in zip(plan.route[:-1], plan.route[1:]):
        for s in np.linspace(0.0, 1.0, max(2, int(np.hypot(*(b - a)) / 0.02))):
            x, y = a + s * (b - a)
            c = classes[int((y - y0) // cell), int((x - x0) // cell)]
            assert c in (1, 2), f"route point ({x:.2f}, {y:.2f}) on a cell of class {c}"


def test_plan_equals_the_commands_files(yard, tmp_path):
    plan = plan_of(yard, out=tmp_path / "py")
    for name in ("plan.csv", "route.csv"):
        assert (tmp_path / "py" / name).read_text() == (yard / "cli" / name).read_text(), name
    assert str(tmp_path / "py" / "plan.png") in plan.files
    with open(yard / "cli" / "plan.csv") as f:
        rows = {r["target_id"]: r for r in csv.DictReader(f)}
    for t in plan.targets:
        row = rows[t["id"]]
        assert row["status"] == t["status"] and row["reason"] == t["reason"]
        if t["status"] == "planned":
            assert np.allclose([float(row[k]) for k in ("view_x", "view_y", "view_z")], t["view"],
                               atol=5e-4)
            assert int(row["order"]) == t["order"]
            assert float(row["path_length_m"]) == pytest.approx(t["path_length_m"], abs=5e-4)
    with open(yard / "cli" / "route.csv") as f:
        route = np.array([[float(r["x"]), float(r["y"])] for r in csv.DictReader(f)])
    assert np.allclose(route, plan.route, atol=5e-4)


def test_options_and_config_change_the_plan(yard):
    # Out of reach at 3 m: only targets within 3 m of a standable cell could be planned.
    short = plan_of(yard, max_range=3.0)
    assert short.summary["options"]["visibility"]["max_range_m"] == 3.0
    assert "3.0 m" in short.target("far")["reason"]
    from_config = plan_of(yard, config={"inspection": {"tour": {"return_to_start": False}}})
    assert not np.allclose(from_config.route[0], from_config.route[-1])
    assert from_config.summary["route"]["return_to_start"] is False


def test_bad_input_raises_clear_errors(yard, tmp_path):
    with pytest.raises(FileNotFoundError, match="nothing.pcd"):
        hylo.inspect(tmp_path / "nothing.pcd", yard / "costmap", yard / "targets.csv")
    with pytest.raises(ValueError, match="max_range_m"):
        plan_of(yard, max_range=-1.0)
    with pytest.raises(ValueError, match=r"start \(500.000, 5.000\) in the map frame"):
        hylo.inspect(yard / "map.pcd", yard / "costmap", yard / "targets.csv", start=(500, 5))
    with pytest.raises(ValueError, match="start: expected two"):
        hylo.inspect(yard / "map.pcd", yard / "costmap", yard / "targets.csv", start=(1, 2, 3))
    bad = tmp_path / "bad.csv"
    bad.write_text("id,x,y\na,1,2\n")
    with pytest.raises(OSError, match="bad.csv"):
        hylo.inspect(yard / "map.pcd", yard / "costmap", bad)
    with pytest.raises(TypeError, match="targets: expected a path"):
        hylo.inspect(yard / "map.pcd", yard / "costmap", 3)
