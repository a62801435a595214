"""Point clouds and the ground filter: ``hylo ground`` on arrays."""

import os
from dataclasses import dataclass

import numpy as np

from . import _hylo
from ._config import yaml_text
from ._progress import make_progress


def read_cloud(path):
    """A cloud file (PCD, PLY, KITTI .bin, LAS) as an (N, 3) float64 array in the file's frame,
    without a copy; points with a NaN/inf coordinate are dropped, as every hylo command drops
    them. OSError (FileNotFoundError) naming the file and the reason."""
    return _hylo.read_cloud(os.fspath(path))


def write_cloud(path, points, intensity=None):
    """Writes an (N, 3) array as PCD, PLY, KITTI .bin or LAS (by the extension), whole or not at
    all; float64 positions keep UTM millimetres where the format can."""
    _hylo.write_cloud(os.fspath(path), points, intensity)


@dataclass(frozen=True)
class GroundResult:
    """The split of :func:`extract_ground`.

    mask:                  (N,) bool, True = ground (False also for NaN/inf points)
    height_above_ground_m: (N,) float32, z above the filter's terrain surface (NaN: invalid)
    method, message:       the back-end that ran and its one-line description
    num_ground, num_objects, num_invalid: the counts ``hylo ground --json`` reports
    """

    mask: np.ndarray
    height_above_ground_m: np.ndarray
    method: str
    message: str
    num_ground: int
    num_objects: int
    num_invalid: int


def extract_ground(points, method="smrf", options=None, *, progress=None):
    """Ground / object split of an (N, 3) array (world frame, UTM coordinates welcome), with
    ``hylo ground``'s defaults: method smrf (simple morphological filter) or csf (cloth
    simulation filter). options: the keys of a configuration's ``ground:`` section besides
    method, e.g. ``{"smrf": {"elevation_threshold_m": 0.1}}`` (the value for a ground robot's
    dense map; ``hylo ground --smrf-threshold 0.1``). ValueError names the key or the array."""
    if options is not None and "method" in options:
        raise ValueError("options: pass the method as method=, not as an option")
    text = yaml_text(options) if options else ""
    bar = make_progress(progress, method, "steps")
    try:
        raw = _hylo.extract_ground(points, method, text, "<options>", bar)
    finally:
        bar.close()
    raw.pop("origin_world")
    return GroundResult(**raw)


def ground_mask(points, method="smrf", options=None, *, progress=None):
    """(N,) bool, True = ground: :func:`extract_ground`'s mask, the labels ``hylo ground``
    gives the same points."""
    return extract_ground(points, method, options, progress=progress).mask
