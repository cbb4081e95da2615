#!/usr/bin/env bash
# The restart state check of the continuum fields and the restart's scene comparison by value
# (issue 35 items 1 and 4), on 3 ranks: a density outside the model's range (a conservation law
# outside the range of its initial and boundary data, a jamming area fraction outside 0..1 or a
# velocity beyond the Courant limit, segregation fractions negative or a kind's amount changed)
# is refused with exit 2, one line naming the file, the field and what is allowed, nothing
# written; a key given at its documented default (colloids.spring.kn = 2500) or inf for "inf"
# restarts; a key that differs names the default of the side that did not set it.
source "$(dirname "$0")/common.bash"
edit=(/usr/bin/python3 "$src/tests/hostile/edit_checkpoint.py")

# Three models, each run with a checkpoint halfway, from which the restarts continue.
B=(--set continuum.time=40 --set continuum.samples=4 --set output.checkpoint_every=100)
J=(--set continuum.time=1 --set continuum.samples=2 --set continuum.cells=512
  --set output.checkpoint_every=100)
S=(--set continuum.time=2000 --set continuum.samples=2 --set output.checkpoint_every=1000)
runs "burgers: first run" "$narrows" run "$src/run/continuum_burgers_riemann.toml" "${B[@]}" \
  --out "$tmp/b" > /dev/null 2>&1
runs "jamming: first run" "$narrows" run "$src/run/continuum_jamming_pulses.toml" "${J[@]}" \
  --out "$tmp/j" > /dev/null 2>&1
runs "segregation: first run" "$narrows" run "$src/run/continuum_segregation_2d.toml" "${S[@]}" \
  --out "$tmp/s" > /dev/null 2>&1

n=0
# case NAME DIR SCENE PATTERN EDIT...: the first checkpoint of DIR, edited, refused on 3 ranks.
case_() {
  local name=$1 dir=$2 scene=$3 pattern=$4 sets
  shift 4
  case $dir in b) sets=("${B[@]}") ;; j) sets=("${J[@]}") ;; s) sets=("${S[@]}") ;; esac
  n=$((n + 1))
  local d=$tmp/c$n ck
  ck=$(ls "$tmp/$dir"/checkpoint-*.h5 | head -1)
  mkdir -p "$d"
  "${edit[@]}" "$ck" "$d/ck.h5" "$@" || check "$name: edited" false
  refused "$name" "ck.h5: $pattern" timeout 60 "${mpi[@]}" -n 3 "$narrows" run \
    "$src/run/$scene.toml" "${sets[@]}" --restart "$d/ck.h5" --out "$d/out"
  check "$name: nothing written" '[ ! -e "$d/out" ] || [ -z "$(ls -A "$d/out")" ]'
}
case_ "burgers: density 1.5" b continuum_burgers_riemann \
  "/continuum/density\[5\] = 1.5; allowed: 0 to 1, the range of the scene's initial and boundary densities" \
  set /continuum/density 5 1.5
case_ "burgers: density -1" b continuum_burgers_riemann "/continuum/density\[7\] = -1; allowed: 0 to 1" \
  set /continuum/density 7 -1
case_ "jamming: phi 1.5" j continuum_jamming_pulses \
  "/continuum/density\[5\] = 1.5; allowed: an area fraction 0 to 1" set /continuum/density 5 1.5
case_ "jamming: phi -1" j continuum_jamming_pulses "/continuum/density\[5\] = -1; allowed: an area fraction" \
  set /continuum/density 5 -1
case_ "jamming: v 1e10" j continuum_jamming_pulses \
  "/continuum/velocity\[3\] = 10000000000; allowed: |v| dt <= dx" set /continuum/velocity 3 1e10
case_ "segregation: a kind all zero" s continuum_segregation_2d \
  "/continuum/fraction_1 has the mean 0; allowed: 0.25, the kind's fraction in the scene" \
  fill /continuum/fraction_1 0
case_ "segregation: a fraction < 0" s continuum_segregation_2d \
  "/continuum/fraction_0\[3\] = -0.1.*allowed: fractions >= 0 whose sum is below close packing" \
  set /continuum/fraction_0 3 -0.1
case_ "segregation: a kind's amount changed" s continuum_segregation_2d \
  "/continuum/fraction_0 has the mean 0.250.*allowed: 0.25" set /continuum/fraction_0 3 0.3
# The step and the time one state (time = step x time_step): /parameters/step edited alone was
# restarted from (the campaign, tests/hostile/campaign_models.py, found it).
case_ "burgers: /parameters/step edited" b continuum_burgers_riemann \
  "/parameters/time = 20 but /parameters/step = 99 is t = 19.8.*; allowed: /parameters/time = /parameters/step x /continuum/time_step" \
  set /parameters/step "" 99
case_ "segregation: /parameters/step edited" s continuum_segregation_2d \
  "/parameters/time = 1592.35.* but /parameters/step = 2001 is t = 1593.1" set /parameters/step "" 2001
runs "burgers: untouched checkpoint restarts on 3 ranks" timeout 60 "${mpi[@]}" -n 3 "$narrows" \
  run "$src/run/continuum_burgers_riemann.toml" "${B[@]}" \
  --restart "$(ls "$tmp"/b/checkpoint-*.h5 | head -1)" --out "$tmp/b2" > /dev/null 2>&1

# Item 4: the scene comparison by value. A spring-contact scene with mu_cw = "inf".
cat > "$tmp/spring.toml" << 'TOML'
[run]
engine = "mpcd"
dimensions = 2
seed = 5
steps = 2
[domain]
size = [24.0, 12.0]
[fluid]
collision = "srd"
density = 5
dt = 0.1
[walls]
[colloids]
radius = 2.0
placement = "list"
positions = [[4.0, 6.0], [12.0, 6.0]]
coupling = "no-slip"
contacts = "spring"
[colloids.spring]
mu_cw = "inf"
[output]
progress = false
TOML
runs "spring: first run" "$narrows" run "$tmp/spring.toml" --out "$tmp/sp" > /dev/null 2>&1
runs "restart with colloids.spring.kn = 2500, the default" "${mpi[@]}" -n 3 "$narrows" run \
  "$tmp/spring.toml" --restart "$tmp/sp" --set run.steps=3 --set colloids.spring.kn=2500 \
  --out "$tmp/sp" > /dev/null 2>&1
runs "restart with mu_cw = inf against the checkpoint's \"inf\"" "${mpi[@]}" -n 3 "$narrows" run \
  "$tmp/spring.toml" --restart "$tmp/sp" --set run.steps=4 --set colloids.spring.mu_cw=inf \
  --out "$tmp/sp" > /dev/null 2>&1
refused "restart with kt = 2501" \
  "colloids.spring.kt = 2501 but checkpoint .* has (not set: the default 2500)" \
  "${mpi[@]}" -n 3 "$narrows" run "$tmp/spring.toml" --restart "$tmp/sp" --set run.steps=5 \
  --set colloids.spring.kt=2501 --out "$tmp/sp"
echo "restart cases: $n refused"
finish restart_continuum_checks
