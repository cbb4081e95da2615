#!/usr/bin/env bash
# Trajectory output: trajectory.h5 in H5MD layout with the subsampled fluid, one frame at the
# start and every trajectory_every steps; rows ordered by id, so 1 and 2 ranks write the same
# frames bit for bit; the last frame equals the end checkpoint for the tracked ids; the XDMF
# file for ParaView is well-formed and points at the datasets with the right shapes; a
# restart writes trajectory-<step>.h5 with the frames after the checkpoint. With colloids, every
# colloid is in /particles/colloids (same on 1 and 2 ranks, last frame = checkpoint) and the
# XDMF has a second grid with their radius.
set -u
source "$(dirname "$0")/common.bash"

sed 's/^size = .*/size = [24.0, 10.0]/' "$src/run/quickstart.toml" > "$tmp/s.toml"
opts=(--set run.steps=300 --set output.every=100
      --set output.trajectory_every=100 --set output.trajectory_subsample=7
      --set output.progress=false)
runs "1-rank run" "$narrows" run "$tmp/s.toml" "${opts[@]}" --out "$tmp/one" > /dev/null 2>&1
runs "2-rank run" "${mpi[@]}" -n 2 "$narrows" run "$tmp/s.toml" "${opts[@]}" --out "$tmp/two" \
  > /dev/null 2>&1
runs "restart" "$narrows" run "$tmp/s.toml" "${opts[@]}" --set run.steps=500 --out "$tmp/one" \
  --restart "$tmp/one" > /dev/null 2>&1
check "trajectory contents" '/usr/bin/python3 - "$tmp" <<PY
import sys, h5py, numpy as np
import xml.etree.ElementTree as ET
tmp = sys.argv[1]
a = h5py.File(tmp + "/one/trajectory.h5", "r")
b = h5py.File(tmp + "/two/trajectory.h5", "r")
fl = a["particles/fluid"]
n = 24 * 10 * 10
m = (n + 6) // 7
assert list(a["h5md"].attrs["version"]) == [1, 1]
assert fl["position/value"].shape == (4, m, 2), fl["position/value"].shape
assert list(fl["position/step"][()]) == [0, 100, 200, 300]
assert np.array_equal(fl["id"][()], np.arange(m) * 7)
for f in ("position", "velocity"):
    assert np.array_equal(fl[f + "/value"][()], b["particles/fluid/" + f + "/value"][()]), f
ck = h5py.File(tmp + "/one/checkpoint-0000000300.h5", "r")["particles/fluid"]
ids = ck["id/value"][()]
order = np.argsort(ids)
pos = ck["position/value"][()][order][::7]
assert np.array_equal(pos, fl["position/value"][3]), "last frame differs from the checkpoint"
y = fl["position/value"][:, :, 1]
assert (y >= 0).all() and (y <= 10).all()
c = h5py.File(tmp + "/one/trajectory-0000000300.h5", "r")["particles/fluid/position"]
assert list(c["step"][()]) == [400, 500], c["step"][()]
root = ET.parse(tmp + "/one/trajectory.xdmf").getroot()
grids = root.findall("./Domain/Grid/Grid")
assert len(grids) == 4, len(grids)
item = grids[2].find("./Geometry/DataItem")
assert item.get("Dimensions") == f"{m} 2"
inner = item.findall("DataItem")
assert inner[0].text.split()[:3] == ["2", "0", "0"]
assert inner[1].text.strip() == "trajectory.h5:/particles/fluid/position/value"
PY'
sed -e 's/^size = .*/size = [24.0, 10.0]/' -e 's/^dt = .*/dt = 0.1/' "$src/run/quickstart.toml" \
  > "$tmp/c.toml"
printf '[colloids]\nradius = 1.5\ncount = 3\ngravity = [0.01, 0.0]\n' >> "$tmp/c.toml"
copts=(--set run.steps=200 --set output.every=100 --set output.trajectory_every=100
       --set output.trajectory_subsample=50 --set output.progress=false)
runs "1-rank colloid run" "$narrows" run "$tmp/c.toml" "${copts[@]}" --out "$tmp/c1" > /dev/null 2>&1
runs "2-rank colloid run" "${mpi[@]}" -n 2 "$narrows" run "$tmp/c.toml" "${copts[@]}" --out "$tmp/c2" > /dev/null 2>&1
check "colloid trajectory contents" '/usr/bin/python3 - "$tmp" <<PY
import sys, h5py, numpy as np
import xml.etree.ElementTree as ET
tmp = sys.argv[1]
a = h5py.File(tmp + "/c1/trajectory.h5", "r")["particles/colloids"]
b = h5py.File(tmp + "/c2/trajectory.h5", "r")["particles/colloids"]
assert a["position/value"].shape == (3, 3, 2), a["position/value"].shape
assert list(a["velocity/step"][()]) == [0, 100, 200]
assert np.array_equal(a["id"][()], np.arange(3)) and np.all(a["radius"][()] == 1.5)
for f in ("position", "velocity"):
    assert np.array_equal(a[f + "/value"][()], b[f + "/value"][()]), f
ck = h5py.File(tmp + "/c1/checkpoint-0000000200.h5", "r")["particles/colloids"]
order = np.argsort(ck["id/value"][()])
for f in ("position", "velocity"):
    assert np.array_equal(ck[f + "/value"][()][order], a[f + "/value"][2]), f
assert not np.array_equal(a["position/value"][0], a["position/value"][2]), "colloids did not move"
root = ET.parse(tmp + "/c1/trajectory.xdmf").getroot()
names = [g.get("Name") for g in root.findall("./Domain/Grid")]
assert names == ["fluid", "colloids"], names
frame = root.findall("./Domain/Grid")[1].findall("Grid")[2]
assert frame.find("./Geometry/DataItem").findall("DataItem")[1].text.strip() == \\
    "trajectory.h5:/particles/colloids/position/value"
radius = [x for x in frame.findall("Attribute") if x.get("Name") == "radius"][0]
assert radius.find("DataItem").text.strip() == "trajectory.h5:/particles/colloids/radius"
PY'
refused "subsample 0" "output.trajectory_subsample" \
  "$narrows" check "$src/run/quickstart.toml" --set output.trajectory_subsample=0
finish "trajectory"
