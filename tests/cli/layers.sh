#!/usr/bin/env bash
# The layers hold: every #include "narrows/..." in src/ and include/ goes downward in the layer
# table of tools/check_layers.py (core <- species <- parallel, io; models <- scene <- run;
# kernels <- coupling <- engines <- app; docs/architecture.md). The check itself can fail: the
# same tree with one include against the layers (io including an engine) is refused.
source "$(dirname "$0")/common.bash"

runs "includes follow the layers" /usr/bin/python3 "$src/tools/check_layers.py" "$src"
mkdir -p "$tmp/tree"
cp -r "$src/src" "$src/include" "$tmp/tree/"
sed -i '1i #include "narrows/engines/mpcd/simulation.hpp"' "$tmp/tree/src/io/hdf5.cpp"
exits 1 "an include against the layers is found" /usr/bin/python3 "$src/tools/check_layers.py" "$tmp/tree" > "$tmp/found.txt"
check "the finding names the file, the line and the rule" \
  "grep -q '^src/io/hdf5.cpp:1: io includes engines/mpcd (narrows/engines/mpcd/simulation.hpp); io may include only' '$tmp/found.txt'"
finish layers
