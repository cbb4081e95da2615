#!/usr/bin/env bash
# The restart state check of overlaps and contacts, part of issue 35 item 1
# (tests/cli/restart_checks.bash), on 3 ranks: no overlap beyond the contact model's allowance
# (hard: none; spring: each centre outside the other colloid; MD: a 48-24 force a run can hold)
# and spring contacts exactly between the touching bodies (a deleted contact group, removed
# rows, a contact between distant colloids or far from a wall) with a tangential spring within
# the Coulomb cap.
source "$(dirname "$0")/common.bash"
source "$(dirname "$0")/restart_checks.bash"

# Overlaps within the contact model's allowance.
case_ "hard: on another's centre" hard "colloid ids 0 and 1 overlap.*allowed: hard contacts allow none" \
  set $C/position/value 1,0 4.0
case_ "MD: on another's centre" md "colloid ids 0 and 1 overlap.*allowed: MD colloids allow a 48-24 pair force below" \
  set $C/position/value 1,0 4.0 set $C/position/value 1,1 6.0
case_ "spring: all at one point" spring "overlap: centres 0 apart.*allowed: spring contacts allow overlaps with each centre outside" \
  fill $C/position/value 6
# Contacts exactly between the touching bodies.
case_ "contact between distant colloids" spring "holds a contact of colloid ids 0 and 13: .*which do not touch" \
  set $K/partner_id/value 0 13
case_ "wall contact far from the wall" spring "holds a contact of colloid id 1 and the wall y = L_y: .*which do not touch" \
  set $K/owner_id/value 2 1
case_ "tangential displacement 1e300" spring "$K/tangential_displacement/value row 1 (contact of colloid ids 0 and 12: .*) has length 1.0*1e+300; allowed: at most .* (mu k_n delta / k_t, the Coulomb cap)" \
  set $K/tangential_displacement/value 1,0 1e300
case_ "contact group deleted" spring "no contact row of colloid id 0 and colloid id 2, which overlap" delete $K
case_ "contact rows removed" spring "no contact row of colloid id .*, which overlap" \
  drop $K/owner_id/value drop $K/partner_id/value drop $K/tangential_displacement/value

untouched spring
echo "restart cases: $n refused"
finish restart_contact_checks
