#!/usr/bin/env python3
"""wave_spectrum_chart.py SPECTRUM.csv OUT.png

The measured wave spectrum against the target: incident and reflected
variance densities (Mansard-Funke separation) and the gauges' mean, from
the CSV `armour run` writes for a scene with [waves] (waves_spectrum.csv,
columns frequency_Hz, target_m2_per_Hz, incident_m2_per_Hz,
reflected_m2_per_Hz, gauges_m2_per_Hz, resolved). SI units.
"""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

if len(sys.argv) != 3:
    sys.exit(__doc__)
source, out = sys.argv[1], sys.argv[2]
with open(source) as f:
    rows = [r for r in csv.DictReader(line for line in f if not line.startswith("#"))]
freq = [float(r["frequency_Hz"]) for r in rows]
series = {name: [float(r[name]) for r in rows] for name in
          ("target_m2_per_Hz", "incident_m2_per_Hz", "reflected_m2_per_Hz", "gauges_m2_per_Hz")}

fig, ax = plt.subplots(figsize=(7, 4))
ax.plot(freq, series["target_m2_per_Hz"], "k-", lw=2, label="target")
ax.plot(freq, series["incident_m2_per_Hz"], "C0.-", label="incident (measured)")
ax.plot(freq, series["reflected_m2_per_Hz"], "C3.-", label="reflected (measured)")
ax.plot(freq, series["gauges_m2_per_Hz"], "C7:", label="gauges' mean")
unresolved = [f for f, r in zip(freq, rows) if r["resolved"] == "0"]
if unresolved:
    ax.plot(unresolved, [0.0] * len(unresolved), "kx", label="gauge spacing degenerate (interpolated)")
ax.set_xlabel("frequency [Hz]")
ax.set_ylabel("variance density [m²/Hz]")
ax.set_title("wave spectrum at the gauge array")
ax.legend()
ax.grid(alpha=0.3)
fig.tight_layout()
fig.savefig(out, dpi=110)
