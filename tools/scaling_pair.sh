#!/usr/bin/env bash
# Strong and weak scaling of the Table 6.1 channel from 1 to 2 ranks, next to what this machine
# allows any code: two independent one-rank runs side by side (each pinned to a core), whose
# rates bound what two ranks can reach (they share the memory bandwidth and caches alike, and
# have no messages to wait for).
#
# Usage: bash tools/scaling_pair.sh [NARROWS] [REPEATS] [STEPS] [BALANCE]
#   (defaults: build/narrows, 3, 200, none). BALANCE is the two-rank runs' domain.balance, checked
#   every 20 steps: "none", "work" or "time" (the cores of a VM need not run alike, and a slab of
#   equal work on the slower core keeps the other waiting).
# Prints per repeat, then the ranges, in fluid particle-steps/s: one rank alone on core 0 and on
# core 1 (the cores of a VM need not be alike: the mean of the two is the one-rank rate), two
# ranks (l = 600 b and l = 1200 b), and two one-rank runs side by side (l = 600 b each);
#   strong = two ranks (600) / the one-rank rate; weak = two ranks (1200) / (core 0 + core 1);
#   side by side = (the two side by side) / (core 0 + core 1): the machine's own weak bound;
#   weak / side by side: what the code's messages, ghost work and waiting cost.
# Needs 2 cores. Nothing is asserted: a measurement, best on a quiet machine.
set -euo pipefail
here=$(cd "$(dirname "$0")/.." && pwd)
narrows=${1:-$here/build/narrows}
repeats=${2:-3}
steps=${3:-200}
balance=${4:-none}
case $balance in none | work | time) ;; *)
  echo "scaling_pair: BALANCE = '$balance'; allowed: none, work, time" >&2
  exit 2
  ;;
esac
scene=$here/run/pulses_table6_1.toml
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
mpi=(mpirun --oversubscribe)
[ "$(id -u)" -eq 0 ] && mpi+=(--allow-run-as-root)
common=(--set run.steps="$steps" --set output.every=100000 --set output.checkpoint_every=0 --overwrite)
two=(--set "domain.balance=\"$balance\"" --set domain.balance_every=20)
echo "two-rank runs: domain.balance = \"$balance\", checked every 20 steps"
rate() { sed -n 's/^Loop time .*(\([0-9.e+]*\) particle-steps\/s)$/\1/p' "$1"; }
run() { # LOG COMMAND...: the run must succeed and print its rate
  local log=$1
  shift
  if ! "$@" >"$log" 2>&1; then
    echo "scaling_pair: failed: $* (log: $log)" >&2
    tail -3 "$log" >&2
    exit 1
  fi
}
results=()
for r in $(seq "$repeats"); do
  run "$dir/one0.log" taskset -c 0 "$narrows" run "$scene" "${common[@]}" --out "$dir/one0"
  run "$dir/one1.log" taskset -c 1 "$narrows" run "$scene" "${common[@]}" --out "$dir/one1"
  taskset -c 0 "$narrows" run "$scene" "${common[@]}" --out "$dir/a" >"$dir/a.log" 2>&1 &
  first=$!
  run "$dir/b.log" taskset -c 1 "$narrows" run "$scene" "${common[@]}" --out "$dir/b"
  wait "$first" || { echo "scaling_pair: the first side-by-side run failed ($dir/a.log)" >&2; exit 1; }
  run "$dir/strong.log" "${mpi[@]}" -n 2 "$narrows" run "$scene" "${common[@]}" "${two[@]}" \
    --out "$dir/strong"
  run "$dir/weak.log" "${mpi[@]}" -n 2 "$narrows" run "$scene" "${common[@]}" "${two[@]}" \
    --set "domain.size=[1200.0, 50.0]" --out "$dir/weak"
  line="$(rate "$dir/one0.log") $(rate "$dir/one1.log") $(rate "$dir/strong.log") $(rate "$dir/weak.log") $(rate "$dir/a.log") $(rate "$dir/b.log")"
  results+=("$line")
  /usr/bin/python3 - "$r" $line <<'PY'
import sys
r, o0, o1, strong, weak, a, b = sys.argv[1], *map(float, sys.argv[2:])
print(f"repeat {r}: one rank {o0:.3e} (core 0), {o1:.3e} (core 1); two ranks {strong:.3e} "
      f"(l = 600 b), {weak:.3e} (l = 1200 b); side by side {a:.3e} + {b:.3e}: "
      f"strong {2 * strong / (o0 + o1):.2f}x, weak {weak / (o0 + o1):.2f}, side by side "
      f"{(a + b) / (o0 + o1):.2f}, weak / side by side {weak / (a + b):.2f}")
PY
done
/usr/bin/python3 - "${results[@]}" <<'PY'
import sys
rows = [list(map(float, s.split())) for s in sys.argv[1:]]
def span(values):
    return f"{min(values):.2f}-{max(values):.2f}"
print(f"strong scaling 1 -> 2 ranks: {span([2 * s / (o0 + o1) for o0, o1, s, w, a, b in rows])}x")
print(f"weak scaling (l and ranks doubled): {span([w / (o0 + o1) for o0, o1, s, w, a, b in rows])}")
print(f"two one-rank runs side by side (the machine's bound on weak scaling): "
      f"{span([(a + b) / (o0 + o1) for o0, o1, s, w, a, b in rows])}")
print(f"weak scaling / side by side (the code's own cost): "
      f"{span([w / (a + b) for o0, o1, s, w, a, b in rows])}")
PY
