#!/usr/bin/env bash
# Hard case: NaN or Inf in a checkpoint's fluid positions or velocities is refused on restart
# with one line naming the file, the dataset and the particle (exit 2), on 1 and 3 ranks, and
# the refused restart writes no observables or checkpoint.
source "$(dirname "$0")/common.bash"

# A small SRD channel (a restart must name the scene the checkpoint was written by).
scene=$tmp/channel.toml
cat > "$scene" << 'TOML'
[run]
dimensions = 2
steps = 10
[domain]
size = [12.0, 6.0]
[fluid]
collision = "srd"
density = 5
dt = 0.5
angle = 130.0
[body_force]
value = [0.001, 0.0]
[walls]
[output]
every = 5
progress = false
TOML
again=(--set run.steps=20) # a restart may change only run.steps and output.*
runs "first run" "$narrows" run "$scene" --out "$tmp/good" > /dev/null 2>&1

# inject DIR FIELD ROW COMPONENT VALUE keep|strip: copy the good run to DIR and poison one entry;
# with strip, also remove the checksums (an older checkpoint), so that the state check must see it.
inject() {
  rm -rf "$1" && cp -r "$tmp/good" "$1" &&
    /usr/bin/python3 -c '
import sys, h5py
d, field, row, k, value, strip = sys.argv[1:]
with h5py.File(d + "/checkpoint-0000000010.h5", "r+") as f:
    ds = f["particles/fluid/" + field + "/value"]
    ds[int(row), int(k)] = float(value)
    if strip == "strip":  # as narrows wrote checkpoints before they carried checksums
        f.visititems(lambda name, obj: obj.attrs.__delitem__("checksum") if "checksum" in obj.attrs else None)' "$@"
}

for ranks in 1 3; do
  for poison in "position 7 0 nan" "velocity 200 1 inf" "velocity 3 0 -inf"; do
    read -r field row k value <<< "$poison"
    d=$tmp/bad_${ranks}_${field}_${value}
    runs "$poison: injected" inject "$d" "$field" "$row" "$k" "$value" keep
    refused "$ranks ranks, $value in $field" \
      "checkpoint-0000000010.h5: damaged checkpoint: /particles/fluid/$field/value does not match" \
      "${mpi[@]}" -n "$ranks" "$narrows" run "$scene" "${again[@]}" \
      --restart "$d" --out "$d"
    l=$tmp/legacy_${ranks}_${field}_${value}
    runs "$poison: injected without checksums" inject "$l" "$field" "$row" "$k" "$value" strip
    exits 2 --err "$tmp/lerr" "$ranks ranks, $value in $field, no checksums" \
      "${mpi[@]}" -n "$ranks" "$narrows" run "$scene" "${again[@]}" --restart "$l" --out "$l"
    check "$ranks ranks, $value in $field, no checksums: the state check names the row" \
      'grep -q "/particles/fluid/$field/value row $row component $k = $value" "$tmp/lerr"'
    # (the run shell opens log-<step>.txt before it reads the fluid; that is its business)
    check "$ranks ranks, $value in $field: no observables or checkpoint written" \
      '[ -z "$(ls "$d" | grep -e "^observables-" -e "^trajectory-" -e "checkpoint-0000000020")" ]'
  done
done

# The untouched checkpoint still restarts.
"${mpi[@]}" -n 3 "$narrows" run "$scene" "${again[@]}" --restart "$tmp/good" \
  --out "$tmp/good" > /dev/null 2>&1
code=$?
check "clean checkpoint restarts on 3 ranks (got $code)" '[ "$code" -eq 0 ]'
finish hard_checkpoint_nan
