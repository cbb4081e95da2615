#!/usr/bin/env bash
# The restart state check, part of issue 35 item 1 (tests/cli/restart_checks.bash), on 3 ranks:
# every field of a species of one shape and row count on every rank before any rank reads (a
# short contact field deadlocked 2 and 3 ranks), every dataset's checksum verified whatever its
# row count (a partner_id with one row more went unchecked), each field's step and time those
# of /parameters, and /parameters/scene one scene with /parameters/canonical_scene.
source "$(dirname "$0")/common.bash"
source "$(dirname "$0")/restart_checks.bash"

# Row counts agreed before any rank reads; the checksum of a longer field still verified.
case_ "contacts: owner_id a row short" spring \
  "$K/owner_id/value has [0-9]* rows, the other fields of $K [0-9]*; allowed" drop $K/owner_id/value
case_ "contacts: partner_id a row more" spring \
  "$K/partner_id/value has [0-9]* rows, the other fields of $K [0-9]*; allowed: the same number of rows" \
  append $K/partner_id/value
case_ "contacts: partner_id a row more, checksum old" spring \
  "damaged checkpoint: $K/partner_id/value does not match its checksum" \
  append $K/partner_id/value nochecksum $K/partner_id/value
case_ "colloids: radius a row short" hard "$C/radius/value has 2 rows" drop $C/radius/value
# Step and time of every field those of /parameters.
case_ "step of a field" spring "$C/radius/step = 3 but /parameters/step = 4" \
  set $C/radius/step "" 3
case_ "/parameters/step" hard "/particles/fluid/position/step = 4 but /parameters/step = 2" \
  set /parameters/step "" 2
case_ "time of a field" hard "/particles/fluid/velocity/time = 0.2.* but /parameters/time" \
  set /particles/fluid/velocity/time "" 0.2
# The scene text edited, its canonical text not.
case_ "scene edited" hard "/parameters/scene has 'fluid.dt = 0.2' where /parameters/canonical_scene has 'fluid.dt = 0.1'" \
  replace /parameters/scene "dt = 0.1" "dt = 0.2"

untouched hard spring
echo "restart cases: $n refused"
finish restart_rows_checks
