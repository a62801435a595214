"""hylo.inspect: inspection planning, as ``hylo inspect`` plans (the same C++ code), returning
the plan instead of (or besides) writing it."""

import json
import os
from dataclasses import dataclass

import numpy as np

from . import _hylo
from ._config import load_config
from ._progress import make_progress


@dataclass(frozen=True)
class InspectionPlan:
    """What :func:`inspect` gives back; positions in the map frame (the files'), m.

    targets:     one dict per target, in the file's order: ``id``, ``status`` (planned,
                 occluded, unreachable), ``reason`` (why not planned; "" when planned),
                 ``view`` ((3,) camera position at the viewpoint, None when not planned),
                 ``order`` (1-based place in the visits, 0 when not planned),
                 ``path_length_m`` (the route leg arriving there), ``along_route_m``,
                 ``range_m``, ``view_angle_deg`` (None when not planned), ``visible_cells``
                 -- plan.csv's columns
    route:       (N, 2) the route's corners x, y in driving order (route.csv); between two
                 corners the robot drives straight over passable cells only
    route_stops: (N,) tuples of the target ids seen at each corner (empty between stops)
    summary:     the dict summary.json holds (counts, route, timings, options, per target)
    files:       the paths written (empty without ``out``)
    """

    targets: list
    route: np.ndarray
    route_stops: list
    summary: dict
    files: list

    def target(self, target_id):
        """The dict of one target by its id (KeyError when there is none)."""
        for t in self.targets:
            if t["id"] == target_id:
                return t
        raise KeyError(target_id)


def inspect(map, costmap, targets, *, start=None, out=None, config=None, camera_height=None,
            min_range=None, max_range=None, clearance=None, robot_radius=None,
            return_to_start=None, progress=None):
    """Where the robot must stand to see each target, and the route there:
    ``hylo inspect --map MAP --costmap COSTMAP --targets TARGETS [--out OUT]``.

    map: the crafted map (PCD/PLY/LAS, map frame); costmap: the folder of ``hylo
    traversability``; targets: CSV or YAML (``id,x,y,z`` and optional columns, map frame; see
    docs/inspection.md). start: (x, y) where the route starts, map frame, m (None: the map
    frame's origin, where SLAM started). config: a YAML path, dict or hylo.Config whose
    ``inspection:`` section sets the options; camera_height, min_range, max_range, clearance,
    robot_radius (m) and return_to_start override it, as the command's flags do. out: also
    write the command's files there. Raises OSError (FileNotFoundError) naming an unreadable
    input, ValueError for bad options, targets or a start off the free space."""
    handle = load_config(config)
    if start is not None:
        start = [float(v) for v in np.asarray(start, dtype=float).ravel()]
    bar = make_progress(progress, "inspect", "items")
    try:
        raw = _hylo.inspect(
            map=_path(map, "map"), costmap=_path(costmap, "costmap"),
            targets=_path(targets, "targets"), config=handle,
            camera_height_m=_number(camera_height), min_range_m=_number(min_range),
            max_range_m=_number(max_range), clearance_m=_number(clearance),
            robot_radius_m=_number(robot_radius),
            return_to_start=None if return_to_start is None else bool(return_to_start),
            start=start, out_dir="" if out is None else _path(out, "out"), progress=bar)
    finally:
        bar.close()
    return InspectionPlan(targets=raw["targets"], route=raw["route"],
                          route_stops=raw["route_stops"], summary=json.loads(raw["summary_json"]),
                          files=raw["files"])


def _number(value):
    return None if value is None else float(value)


def _path(value, name):
    if isinstance(value, (str, os.PathLike)):
        return os.fspath(value)
    raise TypeError(f"{name}: expected a path, got {type(value).__name__}")
