#!/usr/bin/env bash
# README command 1: installs the dependencies (apt), builds in Release and runs the main job on
# the embedded default: the project's simulated substation, no download. Until `hylo demo`
# exists (issue 9) this is the most complete end-to-end run: simulate -> inspect the log ->
# SLAM with the IESKF -> evaluate against ground truth -> craft -> ground -> costmap.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/setup.sh
bash scripts/build.sh
hylo=build/apps/hylo
out="${HYLO_DEMO_OUT:-out/demo}"
duration="${HYLO_DEMO_DURATION:-60}"
rm -rf "$out"
mkdir -p "$out/craft" "$out/ground"

step() { printf '\n== %s\n' "$*"; }

step "1/7 simulate ${duration} s of session A on the substation site (VLP-16 + 200 Hz IMU)"
$hylo simulate --out "$out/sim" --session a --duration "$duration" --json "$out/sim/summary.json"

step "2/7 what the log holds"
$hylo info "$out/sim/session_a.bag" --json "$out/sim/info.json"

step "3/7 SLAM from scratch with the IESKF back-end"
$hylo map --log "$out/sim/session_a.bag" --config config/sim_vlp16.yaml --out "$out/map" \
  --json "$out/map/summary.json"

step "4/7 trajectory error against the simulator's ground truth (SE(3) alignment)"
$hylo eval ate --est "$out/map/trajectory.tum" --gt "$out/sim/session_a_truth.tum" \
  --json "$out/map/ate.json"

step "5/7 craft the site's map: uniform sampling + moving least squares"
$hylo craft --in "$out/map/map_dense.pcd" --out "$out/craft/map_clean.pcd" \
  --json "$out/craft/summary.json"

step "6/7 ground extraction (cloth simulation filter)"
$hylo ground --in "$out/craft/map_clean.pcd" --out-ground "$out/ground/ground.pcd" \
  --out-objects "$out/ground/objects.pcd" --json "$out/ground/summary.json"

step "7/7 traversability grid map and costmap"
$hylo traversability --ground "$out/ground/ground.pcd" --objects "$out/ground/objects.pcd" \
  --out "$out/costmap" --json "$out/costmap/summary.json"

step "done: outputs in $out"
ls -1 "$out"/*
