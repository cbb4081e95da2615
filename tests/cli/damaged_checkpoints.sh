#!/usr/bin/env bash
# Damaged checkpoints are refused (issue 18, items 2 and 6): a single flipped bit in the stored
# data of every dataset of an mpcd checkpoint with colloids, of an lgca checkpoint (with a
# colloid: /colloid/*) and of a kmc checkpoint is refused with exit 2 and one line naming the file and the dataset, on 1, 2 and 3 ranks, and
# the damaged file is left as it was. A checkpoint without checksums (as narrows wrote them
# before) is accepted with a warning, and its state is validated: a position outside the box,
# a NaN velocity, a duplicate id, a seed or box that differ from the stored scene are refused
# naming the dataset and the first bad row, on 1, 2 and 3 ranks (no rank waits for another).
set -u
source "$(dirname "$0")/common.bash"
py=/usr/bin/python3

cat > "$tmp/c.toml" <<'TOML'
[run]
engine = "mpcd"
dimensions = 2
seed = 8
steps = 4
[domain]
size = [24.0, 12.0]
[fluid]
collision = "srd"
dt = 0.1
[colloids]
radius = 2.0
count = 2
placement = "random"
[output]
every = 2
observables = ["temperature"]
progress = false
TOML
"$narrows" run "$tmp/c.toml" --out "$tmp/c" > /dev/null 2> "$tmp/err"
check "mpcd checkpoint written" '[ -s "$tmp/c/checkpoint-0000000004.h5" ]'
good=$tmp/c/checkpoint-0000000004.h5

cat > "$tmp/flip.py" <<'PY'
# flip.py IN BYTE_FRACTION BIT OUT1 DATASET1 [OUT2 DATASET2 ...]: each OUTk = IN with one bit of
# DATASETk's stored data flipped (at the given fraction of its bytes). One python start for all
# the copies (importing h5py takes ~0.5 s).
import shutil, sys, h5py
src, frac, bit = sys.argv[1], float(sys.argv[2]), int(sys.argv[3])
pairs = list(zip(sys.argv[4::2], sys.argv[5::2]))
with h5py.File(src, "r") as f:
    where = {name: (f[name].id.get_offset(), f[name].id.get_storage_size()) for _, name in pairs}
for dst, name in pairs:
    off, size = where[name]
    shutil.copy(src, dst)
    at = off + min(int(frac * size), size - 1)
    with open(dst, "r+b") as f:
        f.seek(at); b = f.read(1)[0]; f.seek(at); f.write(bytes([b ^ (1 << bit)]))
PY

ranks=0
# One flipped bit in each dataset a restart reads: refused naming the dataset, file untouched.
datasets=(/particles/fluid/position/value /particles/fluid/velocity/value /particles/fluid/id/value
  /particles/colloids/position/value /particles/colloids/velocity/value
  /particles/colloids/radius/value /particles/fluid/box/edges
  /parameters/scene /parameters/step /parameters/time /parameters/seed)
flips=()
for i in "${!datasets[@]}"; do flips+=("$tmp/bad$i.h5" "${datasets[i]}"); done
runs "write the damaged copies" $py "$tmp/flip.py" "$good" 0.37 5 "${flips[@]}"
for i in "${!datasets[@]}"; do
  ds=${datasets[i]}
  cp "$tmp/bad$i.h5" "$tmp/bad.h5" # the messages name bad.h5
  sum=$(md5sum < "$tmp/bad.h5")
  ranks=$((ranks % 3 + 1)) # 1, 2, 3 ranks in turn: the checksum is verified collectively
  for n in $ranks; do
    refused "flip in $ds, $n ranks" "bad.h5: damaged checkpoint: $ds does not match its checksum" \
      timeout 60 "${mpi[@]}" -n $n "$narrows" run "$tmp/c.toml" --restart "$tmp/bad.h5" \
      --set run.steps=6 --out "$tmp/r$n"
  done
  check "flip in $ds: the damaged file is left as it was" '[ "$(md5sum < "$tmp/bad.h5")" = "$sum" ]'
done

# The undamaged checkpoint still restarts (on 2 ranks).
timeout 60 "${mpi[@]}" -n 2 "$narrows" run "$tmp/c.toml" --restart "$good" --set run.steps=6 \
  --out "$tmp/ok" > /dev/null 2> "$tmp/err_ok"
check "undamaged checkpoint restarts" '[ $? -eq 0 ] && [ ! -s "$tmp/err_ok" ]'

# lgca and kmc checkpoints: a flip in the lattice state and in the kmc sums.
cat > "$tmp/l.toml" <<'TOML'
[run]
engine = "lgca"
seed = 3
steps = 4
[lattice]
model = "fhp-ii"
size = [32, 16]
density = 0.2
[output]
every = 2
observables = ["shear_wave"]
progress = false
TOML
"$narrows" run "$tmp/l.toml" --out "$tmp/l" > /dev/null 2> "$tmp/err"
$py "$tmp/flip.py" "$tmp/l/checkpoint-0000000004.h5" 0.5 0 "$tmp/badl.h5" /particles/lattice/state/value
for n in 1 2; do
  refused "lgca flip, $n ranks" "damaged checkpoint: /particles/lattice/state/value does not match" \
    timeout 60 "${mpi[@]}" -n $n "$narrows" run "$tmp/l.toml" --restart "$tmp/badl.h5" --set run.steps=6 --out "$tmp/lr$n"
done
cat > "$tmp/k.toml" <<'TOML'
[run]
engine = "kmc"
seed = 3
steps = 0
[kmc]
length = 20
rates = { "10->01" = 1.0 }
left = { "0->1" = 0.3 }
right = { "1->0" = 0.7 }
initial = { kind = "product", probabilities = [0.5, 0.5, 0.0] }
time = 5.0
replicas = 2
[output]
observables = ["current"]
progress = false
TOML
"$narrows" run "$tmp/k.toml" --set kmc.replicas=1 --out "$tmp/k" > /dev/null 2> "$tmp/err"
kck=$(ls "$tmp"/k/checkpoint-*.h5 | head -1)
$py "$tmp/flip.py" "$kck" 0.5 6 "$tmp/badk.h5" /kmc/mean
refused "kmc flip" "damaged checkpoint: /kmc/mean does not match its checksum" \
  timeout 60 "$narrows" run "$tmp/k.toml" --restart "$tmp/badk.h5" --out "$tmp/kr"

# lgca colloid checkpoints: a flip in every /colloid dataset (the disc and its averages) is
# refused naming the dataset, on 1, 2 and 3 ranks.
cat > "$tmp/lc.toml" <<'TOML'
[run]
engine = "lgca"
seed = 5
steps = 40
[lattice]
model = "fhp-saturated"
size = [32, 32]
density = 0.5
initial = "equilibrium"
[colloid]
position = [16.0, 13.0]
radius = 2.5
mass = 100.0
held = false
max_lag = 10
displacement_lag = 20
displacement_every = 5
[output]
every = 20
observables = ["colloid_vacf", "colloid_diffusion"]
progress = false
TOML
"$narrows" run "$tmp/lc.toml" --out "$tmp/lc" > /dev/null 2> "$tmp/err"
lgood=$tmp/lc/checkpoint-0000000040.h5
check "lgca colloid checkpoint written" '[ -s "$lgood" ]'
cdatasets=(/colloid/momentum /colloid/omega /colloid/position /colloid/angle
  /colloid/correlations/layout /colloid/correlations/values)
flips=()
for i in "${!cdatasets[@]}"; do flips+=("$tmp/badc$i.h5" "${cdatasets[i]}"); done
runs "write the damaged lgca colloid copies" $py "$tmp/flip.py" "$lgood" 0.6 3 "${flips[@]}"
for i in "${!cdatasets[@]}"; do
  ds=${cdatasets[i]}
  cp "$tmp/badc$i.h5" "$tmp/badc.h5" # the messages name badc.h5
  sum=$(md5sum < "$tmp/badc.h5")
  ranks=$((ranks % 3 + 1))
  refused "lgca colloid flip in $ds, $ranks ranks" \
    "badc.h5: damaged checkpoint: $ds does not match its checksum" \
    timeout 60 "${mpi[@]}" -n $ranks "$narrows" run "$tmp/lc.toml" --restart "$tmp/badc.h5" \
    --set run.steps=60 --out "$tmp/lcr$ranks"
  check "lgca colloid flip in $ds: the damaged file is left as it was" \
    '[ "$(md5sum < "$tmp/badc.h5")" = "$sum" ]'
done
timeout 60 "${mpi[@]}" -n 3 "$narrows" run "$tmp/lc.toml" --restart "$lgood" --set run.steps=60 \
  --out "$tmp/lcok" > /dev/null 2> "$tmp/err_lcok"
check "undamaged lgca colloid checkpoint restarts on 3 ranks" '[ $? -eq 0 ] && [ ! -s "$tmp/err_lcok" ]'

# Checkpoints without checksums: accepted with a warning, their state validated.
# refused_after_warning NAME PATTERN COMMAND...: exit 2, and besides the no-checksum warning one
# line on stderr matching PATTERN.
refused_after_warning() {
  local name=$1 pattern=$2
  shift 2
  "$@" > /dev/null 2> "$tmp/lerr"
  local code=$?
  grep -v "carries no checksums" "$tmp/lerr" > "$tmp/lerr1"
  check "$name: exit 2 (got $code)" '[ "$code" -eq 2 ]'
  check "$name: one line besides the warning" '[ "$(grep -c . "$tmp/lerr1")" -eq 1 ]'
  check "$name: message matches '$pattern'" 'grep -q -- "$pattern" "$tmp/lerr1" || { cat "$tmp/lerr1"; false; }'
}
cat > "$tmp/legacy.py" <<'PY'
# legacy.py IN EDIT1 OUT1 [EDIT2 OUT2 ...]: each OUTk = IN without checksums (as older narrows
# wrote), then EDITk applied (to the fluid, or to the disc of an lgca colloid checkpoint). One
# python start for all the copies.
import shutil, sys, h5py, numpy as np
src = sys.argv[1]
for edit, dst in zip(sys.argv[2::2], sys.argv[3::2]):
  shutil.copy(src, dst)
  with h5py.File(dst, "r+") as f:
      def strip(name, obj):
          if "checksum" in obj.attrs:
              del obj.attrs["checksum"]
      f.visititems(strip)
      def edit_ds(name, fn):
          v = f[name][...]; fn(v); f[name][...] = v
      if "/colloid" in f:  # an lgca checkpoint with a disc: its state
          if edit == "outside":
              edit_ds("/colloid/position", lambda v: v.__setitem__(1, 1e300))
          elif edit == "negative":
              edit_ds("/colloid/position", lambda v: v.__setitem__(0, -0.5))
          elif edit == "omega":
              f["/colloid/omega"][()] = np.nan
          elif edit == "angle":
              f["/colloid/angle"][()] = np.inf
          elif edit == "values":
              edit_ds("/colloid/correlations/values", lambda v: v.__setitem__(7, np.nan))
          elif edit == "layout":
              edit_ds("/colloid/correlations/layout", lambda v: v.__setitem__(5, -3))
          elif edit == "moved":
              edit_ds("/colloid/position", lambda v: v.__setitem__(0, v[0] + 1.0))
          continue
      pos, vel, ids = (f["/particles/fluid/%s/value" % k] for k in ("position", "velocity", "id"))
      n = ids.shape[0]
      if edit == "outside":
          p = pos[...]; p[n - 3, 0] = 1e300; pos[...] = p
      elif edit == "beyond_wall":
          p = pos[...]; p[n // 2, 1] = 12.5; pos[...] = p
      elif edit == "nan":
          v = vel[...]; v[n - 2, 1] = np.nan; vel[...] = v
      elif edit == "duplicate":
          i = ids[...]; i[n - 1] = i[0]; ids[...] = i
      elif edit == "all_zero":
          ids[...] = np.zeros(n, dtype=np.uint64)
      elif edit == "range":
          i = ids[...]; i[n - 1] = n + 5; ids[...] = i
      elif edit == "seed":
          f["/parameters/seed"][()] = 9
      elif edit == "box":
          e = f["/particles/fluid/box/edges"][...]; e[1] = 13.0; f["/particles/fluid/box/edges"][...] = e
      elif edit == "time":
          f["/parameters/time"][()] = np.nan
      elif edit == "step":
          f["/parameters/step"][()] = 2**62
PY
edits=(outside:"position/value row .* component 0 = 1.0000000000000001e+300; allowed: inside the box"
  beyond_wall:"position/value row .* component 1 = 12.5; allowed: inside the box, 0 to 12$"
  nan:"velocity/value row .* = nan; allowed: a finite number"
  duplicate:"id/value row .* holds id 0, as does row 0; allowed: every id"
  all_zero:"id/value row 1 holds id 0, as does row 0"
  range:"id/value row .* holds id .*; allowed: 0 to"
  seed:"/parameters/seed = 9 but /parameters/scene has run.seed = 8"
  box:"box/edges\[1\] = 13 but /parameters/scene has domain.size\[1\] = 12"
  time:"/parameters/time = nan; allowed: a finite time"
  step:"/parameters/step = 4611686018427387904; allowed: 0 to 9999999999")
copies=(none "$tmp/legacy.h5")
for edit in "${edits[@]}"; do copies+=("${edit%%:*}" "$tmp/${edit%%:*}.h5"); done
runs "write the copies without checksums" $py "$tmp/legacy.py" "$good" "${copies[@]}"
timeout 60 "$narrows" run "$tmp/c.toml" --restart "$tmp/legacy.h5" --set run.steps=6 --out "$tmp/lg" > /dev/null 2> "$tmp/err_lg"
check "checkpoint without checksums: accepted" '[ $? -eq 0 ]'
check "checkpoint without checksums: a warning says so" 'grep -q "carries no checksums" "$tmp/err_lg"'
for edit in "${edits[@]}"; do
  name=${edit%%:*} pattern=${edit#*:}
  ranks=$((ranks % 2 + 2)) # 1 rank, and 2 or 3 in turn: every rank ends with the same line
  for n in 1 $ranks; do
    refused_after_warning "$name, $n ranks" "$pattern" \
      timeout 60 "${mpi[@]}" -n $n "$narrows" run "$tmp/c.toml" --restart "$tmp/$name.h5" \
      --set run.steps=6 --out "$tmp/v$n"
  done
done
# lgca colloid checkpoints without checksums (as narrows wrote them before): accepted with a
# warning; a disc state no run can have written is refused naming the dataset and row.
cedits=(outside:"/colloid/position row 1 = 1.0000000000000001e+300; allowed: 0 <= value < 27.71"
  negative:"/colloid/position row 0 = -0.5; allowed: 0 <= value < 32 (the lattice's size_x)"
  omega:"/colloid/omega row 0 = nan; allowed: a finite number"
  angle:"/colloid/angle row 0 = inf; allowed: a finite number"
  values:"/colloid/correlations/values row 7 = nan; allowed: a finite number"
  layout:"/colloid/correlations/layout row 5 = -3; allowed: at least 0")
copies=(none "$tmp/lcleg.h5")
for edit in "${cedits[@]}"; do copies+=("${edit%%:*}" "$tmp/lc_${edit%%:*}.h5"); done
runs "write the lgca colloid copies without checksums" $py "$tmp/legacy.py" "$lgood" "${copies[@]}"
timeout 60 "$narrows" run "$tmp/lc.toml" --restart "$tmp/lcleg.h5" --set run.steps=60 \
  --out "$tmp/lcl" > /dev/null 2> "$tmp/err_lcl"
check "lgca colloid checkpoint without checksums: accepted" '[ $? -eq 0 ]'
check "lgca colloid checkpoint without checksums: a warning says so" \
  'grep -q "/colloid carries no checksums" "$tmp/err_lcl"'
for edit in "${cedits[@]}"; do
  name=${edit%%:*} pattern=${edit#*:}
  ranks=$((ranks % 2 + 2))
  for n in 1 $ranks; do
    refused_after_warning "lgca colloid $name, $n ranks" "lc_$name.h5: $pattern" \
      timeout 60 "${mpi[@]}" -n $n "$narrows" run "$tmp/lc.toml" --restart "$tmp/lc_$name.h5" \
      --set run.steps=60 --out "$tmp/lcv$n"
  done
done
# A held disc is where the scene put it.
"$narrows" run "$tmp/lc.toml" --set colloid.held=true --out "$tmp/lh" > /dev/null 2> "$tmp/err"
$py "$tmp/legacy.py" "$tmp/lh/checkpoint-0000000040.h5" moved "$tmp/lc_moved.h5"
refused_after_warning "lgca held colloid moved, 2 ranks" \
  "/colloid/position row 0 = 17; allowed: 16 (colloid.held = true" \
  timeout 60 "${mpi[@]}" -n 2 "$narrows" run "$tmp/lc.toml" --set colloid.held=true \
  --restart "$tmp/lc_moved.h5" --set run.steps=60 --out "$tmp/lhm"
finish damaged_checkpoints
