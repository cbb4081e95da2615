#!/usr/bin/env bash
# One shock three ways (issue 22 item 4, acceptance 5; Tabatabaei (2008) ch.5): runs the three-state
# lattice gas with a shock (kmc, run/kmc_family2_shock.toml), the sedimenting colloid chain
# (mpcd with colloids, run/sedimentation_chain_31.toml, cut to --chain-steps) and writes the report
# with the continuum engine's predictions for both (tools/shock_report.py --chain): OUT/shock_three_ways.png
# and OUT/shock_three_ways.txt, the table of shock speed and diffusion constant from each.
#
# Size: the chain is Tabatabaei's 31 colloids at spacing 5 in a 300 x 10 channel; 50000 steps
# (t = 750) are about 1.3e9 particle-steps, one to two minutes on an idle core. The head moves
# ~40 in that time, a few spacings: speed errors of ~10 % and a spread D_s from one run
# (increments about the mean drift), where Tabatabaei (2008) asks for many more colloids.
# --tiny: a smoke-test size (kmc L = 100; 6 colloids in a 60 x 10 channel for 1000 steps) whose
# numbers mean nothing.
#
# Usage: tools/shock_three_ways.sh [--out DIR] [--narrows PATH] [--chain-steps N] [--tiny]
#                                  [--overwrite] [-- extra shock_report.py options]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
src=$(dirname "$here")
out=out/shock_three_ways
narrows=""
steps=50000
tiny=0
overwrite=()
while [ $# -gt 0 ]; do
  case "$1" in
    --out) out=$2; shift 2 ;;
    --narrows) narrows=$2; shift 2 ;;
    --chain-steps) steps=$2; shift 2 ;;
    --tiny) tiny=1; shift ;;
    --overwrite) overwrite=(--overwrite); shift ;;
    --) shift; break ;;
    *) echo "shock_three_ways.sh: unknown option '$1'; allowed: --out DIR, --narrows PATH," \
         "--chain-steps N, --tiny, --overwrite, -- (then shock_report.py options)" >&2; exit 2 ;;
  esac
done
case "$steps" in
  '' | *[!0-9]*) echo "shock_three_ways.sh: --chain-steps '$steps'; allowed: a positive integer" >&2
    exit 2 ;;
esac
if [ -z "$narrows" ]; then
  narrows=${NARROWS:-$src/build/narrows}
fi
if [ ! -x "$narrows" ]; then
  echo "shock_three_ways.sh: the narrows binary '$narrows' was not found; allowed: --narrows" \
    "PATH, \$NARROWS or build/narrows" >&2
  exit 2
fi

kmc=(--set output.progress=false)
chain=(--set run.steps="$steps" --set output.progress=false)
if [ "$tiny" = 1 ]; then
  kmc+=(--set kmc.length=100 --set 'kmc.initial={kind="shock",site=50}' --set kmc.time=30.0
        --set kmc.samples=10 --set kmc.replicas=8)
  chain=(--set 'domain.size=[60.0,10.0]' --set output.every=50 --set output.progress=false
         --set 'colloids.positions=[[2.5,5.0],[7.5,5.0],[12.5,5.0],[17.5,5.0],[22.5,5.0],[27.5,5.0]]'
         --set run.steps=1000)
fi
mkdir -p "$out"
echo "shock_three_ways: kmc lattice gas -> $out/kmc"
"$narrows" run "$src/run/kmc_family2_shock.toml" "${kmc[@]}" --out "$out/kmc" "${overwrite[@]}" \
  > "$out/kmc.out"
echo "shock_three_ways: mpcd colloid chain -> $out/chain"
"$narrows" run "$src/run/sedimentation_chain_31.toml" "${chain[@]}" --out "$out/chain" \
  "${overwrite[@]}" > "$out/chain.out"
/usr/bin/python3 "$here/shock_report.py" "$out/kmc/observables.h5" --chain "$out/chain" \
  --narrows "$narrows" --png "$out/shock_three_ways.png" "$@"
