#!/usr/bin/env python3
"""The ground filter on a cloud: ground and object clouds, and a figure (the cloud from above
coloured by label, and the objects' heights above the ground).

    python3 examples/python/ground_filter.py map_dense.pcd --threshold 0.1 --out out/ground
    python3 examples/python/ground_filter.py --out out/ground     # the simulated site's cloud

The labels are those of `hylo ground` with the same options. Needs the hylo package
(docs/python.md) and Debian's python3-matplotlib.
"""

import argparse
import shutil
import subprocess
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")  # files only, no display
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

import hylo  # noqa: E402

REPO = Path(__file__).resolve().parents[2]


def simulated_site(out, hylo_given):
    """The simulated substation's reference cloud (`hylo simulate`)."""
    exe = next((str(c) for c in (hylo_given, REPO / "build" / "apps" / "hylo", shutil.which("hylo"))
                if c and Path(c).exists()), None)
    if exe is None:
        sys.exit("no cloud given and the hylo command was not found (--hylo)")
    subprocess.run([exe, "simulate", "--out", str(out / "sim"), "--session", "a", "--duration",
                    "1"], check=True)
    return out / "sim" / "site_reference.pcd"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("cloud", nargs="?", help="PCD/PLY/LAS cloud (default: the simulated site)")
    parser.add_argument("--method", default="smrf", choices=["smrf", "csf"])
    parser.add_argument("--threshold", type=float,
                        help="SMRF elevation threshold, m (0.1 for a ground robot's map; "
                             "default: hylo ground's 0.5)")
    parser.add_argument("--out", default="out/ground_filter", help="output folder")
    parser.add_argument("--hylo", help="the hylo executable (to simulate the site)")
    args = parser.parse_args()
    out = Path(args.out)
    out.mkdir(parents=True, exist_ok=True)
    path = args.cloud or simulated_site(out, args.hylo)

    points = hylo.read_cloud(path)
    options = {"smrf": {"elevation_threshold_m": args.threshold}} if args.threshold else None
    ground = hylo.extract_ground(points, args.method, options)
    hylo.write_cloud(out / "ground.pcd", points[ground.mask])
    hylo.write_cloud(out / "objects.pcd", points[~ground.mask])
    print(f"{path}: {ground.message}")

    figure, (top, heights) = plt.subplots(1, 2, figsize=(13, 5.5))
    step = max(1, len(points) // 200_000)  # enough dots for a figure
    shown = slice(None, None, step)
    top.scatter(points[shown, 0][ground.mask[shown]], points[shown, 1][ground.mask[shown]], s=0.2,
                c="tab:green", label="ground")
    top.scatter(points[shown, 0][~ground.mask[shown]], points[shown, 1][~ground.mask[shown]], s=0.2,
                c="tab:red", label="objects")
    top.set(xlabel="x [m]", ylabel="y [m]", title=f"{args.method}: from above")
    top.axis("equal")
    top.legend(markerscale=20)
    above = ground.height_above_ground_m[~ground.mask]
    heights.hist(above[np.isfinite(above)], bins=80, color="tab:red")
    heights.set(xlabel="height above the ground surface [m]", ylabel="object points",
                title="objects' heights")
    figure.savefig(out / "ground.png", dpi=120, bbox_inches="tight")
    print(f"wrote {out / 'ground.pcd'}, {out / 'objects.pcd'} and {out / 'ground.png'}")


if __name__ == "__main__":
    main()
