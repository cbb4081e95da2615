#!/usr/bin/env bash
# narrows run --restart through the command line: checkpoints every K steps, only the newest
# output.checkpoint_keep kept; a restart from the directory on another rank count ends with
# exactly the particles of an uninterrupted run (compared by id, bitwise); --set of a physics
# key and a scene that differs from the checkpoint's are refused; bad checkpoints are refused
# with exit code 2 and one line (non-HDF5, truncated, missing dataset, wrong format version,
# id count not matching the positions, a 3D checkpoint for a 2D scene).
set -u
source "$(dirname "$0")/common.bash"
same=$src/tests/cli/same_state.py
fluid=fluid:id,position,velocity
py=/usr/bin/python3

cat > "$tmp/s.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
seed = 5
steps = 60
[domain]
size = [24.0, 12.0]
[fluid]
collision = "at+a"
dt = 0.5
[body_force]
kind = "sine"
amplitude = 0.05
[output]
every = 10
checkpoint_every = 10
checkpoint_keep = 2
progress = false
TOML

# The uninterrupted run (2 ranks) and a first part (2 ranks) to step 30.
runs "straight run" "${mpi[@]}" -n 2 "$narrows" run "$tmp/s.toml" --out "$tmp/straight" > /dev/null 2> "$tmp/err0"
runs "first part" "${mpi[@]}" -n 2 "$narrows" run "$tmp/s.toml" --set run.steps=30 --out "$tmp/part" > /dev/null 2> "$tmp/err1"
check "the newest 2 checkpoints kept" '[ "$(cd "$tmp/part" && ls checkpoint-*)" = "$(printf "checkpoint-0000000020.h5\ncheckpoint-0000000030.h5")" ]'
check "no temporary files left" '! compgen -G "$tmp/part/*tmp*" > /dev/null'

# Restart from the directory on 1 rank, to the scene's run.steps.
runs "restart" "$narrows" run "$tmp/s.toml" --restart "$tmp/part" --out "$tmp/part" > "$tmp/out2" 2> "$tmp/err2"
check "restart says where it continues from" 'grep -q "restarted from .*checkpoint-0000000030.h5 at step 30" "$tmp/out2"'
check "earlier observables kept, continuation in observables-0000000030.h5" '[ -s "$tmp/part/observables.h5" ] && [ -s "$tmp/part/observables-0000000030.h5" ]'
check "2 ranks to step 30, then 1 rank to 60: bitwise the uninterrupted run" \
  '$py "$same" "$tmp/straight/checkpoint-0000000060.h5" "$tmp/part/checkpoint-0000000060.h5" $fluid'

# tools/join_observables.py joins the first part and the continuation into the series of the
# uninterrupted run (same steps; values to round-off, the 1-rank part reduces in another order).
runs "join_observables" $py "$src/tools/join_observables.py" "$tmp/part" > /dev/null 2> "$tmp/err_join"
check "joined observables equal the uninterrupted run" '$py - "$tmp/straight/observables.h5" "$tmp/part/observables-joined.h5" <<PY
import sys, h5py, numpy as np
a = h5py.File(sys.argv[1], "r")["observables"]
b = h5py.File(sys.argv[2], "r")["observables"]
assert sorted(a) == sorted(b), (sorted(a), sorted(b))
for name in a:
    assert np.array_equal(a[name]["step"][()], b[name]["step"][()]), name
    assert np.allclose(a[name]["value"][()], b[name]["value"][()], rtol=1e-12, atol=1e-14), name
PY'

# And back: 1 rank to 30, 2 ranks from the file to 60.
runs "1 rank to 30" "$narrows" run "$tmp/s.toml" --set run.steps=30 --out "$tmp/one" > /dev/null 2>&1
runs "restart on 2 ranks from a file" "${mpi[@]}" -n 2 "$narrows" run "$tmp/s.toml" --restart "$tmp/one/checkpoint-0000000030.h5" --out "$tmp/one" > /dev/null 2> "$tmp/err3"
check "1 rank to step 30, then 2 ranks to 60: bitwise the uninterrupted run" \
  '$py "$same" "$tmp/straight/checkpoint-0000000060.h5" "$tmp/one/checkpoint-0000000060.h5" $fluid'

# Refused: exit 2, one line on stderr matching a pattern.
good="$tmp/part/checkpoint-0000000060.h5"
refused "--set of a physics key" "s.toml: fluid.dt = 0.2 but checkpoint .* has 0.5; allowed: the checkpoint's scene" \
  "$narrows" run "$tmp/s.toml" --restart "$good" --set fluid.dt=0.2 --out "$tmp/x"
sed 's/dt = 0.5/dt = 0.25/' "$tmp/s.toml" > "$tmp/other.toml"
refused "scene differs from the checkpoint" "fluid.dt = 0.25 but checkpoint .* has 0.5" \
  "$narrows" run "$tmp/other.toml" --restart "$good" --out "$tmp/x"
refused "missing file" "cannot open checkpoint (no such file)" \
  "$narrows" run "$tmp/s.toml" --restart "$tmp/none.h5" --out "$tmp/x"
mkdir "$tmp/empty"
refused "directory without checkpoints" "no checkpoint-<step>.h5 in this directory" \
  "$narrows" run "$tmp/s.toml" --restart "$tmp/empty" --out "$tmp/x"
echo "not a checkpoint" > "$tmp/text.h5"
refused "non-HDF5 file" "not an HDF5 file" \
  "$narrows" run "$tmp/s.toml" --restart "$tmp/text.h5" --out "$tmp/x"
head -c 20000 "$good" > "$tmp/truncated.h5"
refused "truncated file" "truncated HDF5 file" \
  "$narrows" run "$tmp/s.toml" --restart "$tmp/truncated.h5" --out "$tmp/x"
refused "truncated file on 2 ranks" "truncated HDF5 file" \
  "${mpi[@]}" -n 2 "$narrows" run "$tmp/s.toml" --restart "$tmp/truncated.h5" --out "$tmp/x"
runs "make the bad checkpoints" $py - "$good" "$tmp" <<'PY'
import sys, shutil, h5py
good, tmp = sys.argv[1], sys.argv[2]
for name in ("missing", "version", "count"):
    shutil.copy(good, f"{tmp}/{name}.h5")
with h5py.File(f"{tmp}/missing.h5", "r+") as f:
    del f["/particles/fluid/velocity/value"]
with h5py.File(f"{tmp}/version.h5", "r+") as f:
    f["/parameters/format_version"][()] = 99
with h5py.File(f"{tmp}/count.h5", "r+") as f:
    ids = f["/particles/fluid/id/value"][:-1]
    del f["/particles/fluid/id/value"]
    f["/particles/fluid/id/value"] = ids
PY
refused "missing dataset" "missing dataset /particles/fluid/velocity/value" \
  "$narrows" run "$tmp/s.toml" --restart "$tmp/missing.h5" --set run.steps=70 --out "$tmp/x"
refused "wrong format version" "/parameters/format_version = 99; allowed: 1" \
  "$narrows" run "$tmp/s.toml" --restart "$tmp/version.h5" --out "$tmp/x"
refused "ids not matching positions" "particle count mismatch: /particles/fluid/id/value has shape \[2879\]" \
  "$narrows" run "$tmp/s.toml" --restart "$tmp/count.h5" --set run.steps=70 --out "$tmp/x"
refused "ids not matching positions on 2 ranks" "particle count mismatch" \
  "${mpi[@]}" -n 2 "$narrows" run "$tmp/s.toml" --restart "$tmp/count.h5" --set run.steps=70 --out "$tmp/x"
cat > "$tmp/s3.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 3
steps = 2
[domain]
size = [6.0, 6.0, 6.0]
[fluid]
collision = "srd"
dt = 0.5
[output]
progress = false
TOML
runs "3D run" "$narrows" run "$tmp/s3.toml" --out "$tmp/three" > /dev/null 2>&1
refused "3D checkpoint for a 2D scene" "run.dimensions = 2 but checkpoint .* has 3" \
  "$narrows" run "$tmp/s.toml" --restart "$tmp/three" --out "$tmp/x"
check "nothing written for a refused restart" '[ ! -e "$tmp/x" ]'
finish "checkpoint restart"
