"""
A stability chart
=================

Where in the plane of crank speed and slenderness does the slider-crank run on a stable period-1
orbit, where does it double its period, where do two orbits coexist? ``crankgen.stability_chart``
runs continuations along a few lines, follows every special point they find across the plane and
names the regions between the curves (:doc:`/howto/stability-chart`). Two lines at 4 elements
here, the curves followed in steps of a tenth of the box; hatching marks orbits beyond the
model's range (deflection over 0.1 L).

The full-size chart (six lines, 8 elements; about half a minute once compiled)::

    crankgen chart --x omega,0.2,1.6 --y eps,0.005,0.05 --elements 8
"""

import tempfile
import warnings
from pathlib import Path

import matplotlib.pyplot as plt

import crankgen
from crankgen.notices import BeyondTheoryWarning

warnings.simplefilter("ignore", BeyondTheoryWarning)      # the chart hatches those orbits
chart = crankgen.stability_chart(crankgen.Mechanism(), x=("omega", 0.8, 1.4), y=("eps", 0.01, 0.04),
                                 lines=2, n_elements=4, steps_per_rev=50, follow_settings={"dq_max": 0.1})
print("\n".join(chart.summary()[:6]))
print("at Omega* = 1.0, eps = 0.02:", chart.region_at(1.0, 0.02).words)
path = Path(tempfile.mkdtemp()) / "chart.png"      # the chart's own figure, shown below
chart.plot(str(path))
fig = plt.figure(figsize=(8, 6), layout="constrained")
plt.imshow(plt.imread(path))
plt.axis("off")
