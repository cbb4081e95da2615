#!/usr/bin/python3
"""Self-test of tools/overlaps.py (ctest tools.overlaps) on a synthetic contact_statistics file
whose distribution is known: the transient is honoured, the fractions on the bin edges 0.01,
0.02 and 0.04 are exact, the median is interpolated inside its bin, the counts beyond the last
bin count as deeper, and a file without the observable is refused with one line and exit 2."""

import json
import os
import subprocess
import sys
import tempfile

import numpy as np

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
import narrows_h5  # noqa: E402
from selftest import check, summary  # noqa: E402




def synthetic(path):
    bins = 0.001 + 0.002 * np.arange(100)  # centres of 0-0.2 in 0.002
    late = np.zeros((2, 100))
    late[0, 5], late[0, 15], late[0, 25] = 50, 30, 20  # [0.010,0.012) [0.030,.032) [0.050,.052)
    late[1, 2] = 30  # wall: 30 at [0.004, 0.006) and 10 beyond the bins
    early = np.zeros((2, 100))
    early[0, 90] = 1000  # a transient that must be left out
    narrows_h5.write_observables(path, series={"contact_statistics": {
        "step": np.array([0, 500]), "time": np.array([0.0, 10.0]),
        "value": np.stack([early, late]), "bins": bins, "bin_width": np.array([0.002]),
        "contacts": np.array([[1000, 0], [100, 40]]), "beyond": np.array([[0, 0], [0, 10]]),
        "sliding_fraction": np.array([[0.9, 0.9], [0.25, 0.5]])}}, scene="[run]\n")


def main():
    with tempfile.TemporaryDirectory() as tmp:
        synthetic(os.path.join(tmp, "observables.h5"))
        done = subprocess.run([sys.executable, os.path.join(HERE, "overlaps.py"), tmp,
                               "--transient", "5"], capture_output=True, text=True)
        check("exit 0", done.returncode == 0, done.stderr)
        with open(os.path.join(tmp, "overlaps.json")) as f:
            r = json.load(f)
        cc, cw = r["colloid-colloid"], r["colloid-wall"]
        check("one sample after the transient", r["samples"] == 1 and cc["contacts"] == 100,
              (r["samples"], cc["contacts"]))
        check("fraction at 0.01-0.02 exact", abs(cc["fraction_1_to_2_percent"] - 0.5) < 1e-12,
              cc["fraction_1_to_2_percent"])
        check("fraction deeper than 0.04 exact", abs(cc["fraction_deeper_than_0_04"] - 0.2) < 1e-12,
              cc["fraction_deeper_than_0_04"])
        check("median at the top of its bin", abs(cc["median"] - 0.012) < 1e-12, cc["median"])
        check("90th percentile inside the 0.05 bin", abs(cc["p90"] - 0.051) < 1e-12, cc["p90"])
        check("mode", abs(cc["mode"] - 0.011) < 1e-12, cc["mode"])
        check("wall: beyond counts as deeper", abs(cw["fraction_deeper_than_0_04"] - 0.25) < 1e-12
              and cw["contacts"] == 40, cw)
        check("wall: sliding fraction of the kept sample", abs(cw["sliding_fraction"] - 0.5) < 1e-12,
              cw["sliding_fraction"])
        check("PNG written", os.path.getsize(os.path.join(tmp, "overlaps.png")) > 0)
        empty = os.path.join(tmp, "empty")
        os.mkdir(empty)
        narrows_h5.write_observables(os.path.join(empty, "observables.h5"), series={},
                                     scene="[run]\n")
        done = subprocess.run([sys.executable, os.path.join(HERE, "overlaps.py"), empty],
                              capture_output=True, text=True)
        check("no contact_statistics: exit 2, one line naming it", done.returncode == 2 and
              "contact_statistics" in done.stderr and len(done.stderr.strip().splitlines()) == 1,
              (done.returncode, done.stderr))
    return summary()


if __name__ == "__main__":
    sys.exit(main())
