#!/usr/bin/env bash
# The restart state check of the colloid fields, part of issue 35 item 1
# (tests/cli/restart_checks.bash), on 3 ranks: unit quaternions, no colloid field silently reset
# when it is missing (orientation_w, radius, angular_velocity_z: only a checkpoint older than a
# field lacks it, and then all that came later too), and the same value checks for a checkpoint
# without checksums (as narrows wrote them before issue 18).
source "$(dirname "$0")/common.bash"
source "$(dirname "$0")/restart_checks.bash"

# Unit quaternions; no field reset when it is missing.
case_ "orientation not unit" hard "$C/orientation_\* row 0 is not a unit quaternion" \
  set $C/orientation_w/value 0 0.5
case_ "orientation deleted" hard "missing dataset $C/orientation_w/value; allowed: a checkpoint of colloid contacts holds" \
  delete $C/orientation_w delete $C/orientation_x delete $C/orientation_y delete $C/orientation_z
case_ "orientation_w deleted" hard "missing dataset $C/orientation_w/value" delete $C/orientation_w
case_ "radius deleted" hard "missing dataset $C/radius/value but $C/mass/value is there" delete $C/radius
case_ "angular_velocity_z deleted" hard "missing dataset $C/angular_velocity_z/value but $C/orientation_w/value is there" \
  delete $C/angular_velocity_z
# An old checkpoint (no checksums) gets the same value checks.
case_ "no checksums: mass 1e-300" hard "$C/mass/value row 0 (colloid id 0) = 1e-300" \
  set $C/mass/value 0 1e-300 strip
case_ "no checksums: contact between distant colloids" spring "which do not touch" \
  set $K/partner_id/value 0 13 strip

untouched hard
echo "restart cases: $n refused"
finish restart_fields_checks
