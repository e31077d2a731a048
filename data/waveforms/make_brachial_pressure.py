#!/usr/bin/env python3
"""Writes brachial_pressure.csv: ONE SYNTHESISED beat of a brachial arterial pressure wave, for
the pulse's lookup-table waveform (paper 004). It is not a recording (none ships with palprig):
it is a textbook-shaped model, 80/120 mmHg at 75 BPM (0.8 s), made of wrapped Gaussians:
  - the systolic upstroke and peak (0.13 s after the beat starts, width 0.05 s),
  - the late systolic shoulder of the reflected wave (0.26 s, 40 % of the peak, width 0.06 s),
  - the dicrotic wave after the notch (0.42 s, 25 %, width 0.05 s),
  - a slow diastolic run-off (0.35 s, 30 %, width 0.22 s).
Each Gaussian is summed over neighbouring beats so the table is exactly periodic: its last row
(t = 0.8 s) repeats the first. 100 samples per second. Run from data/waveforms:
    python3 make_brachial_pressure.py
"""
import math

PERIOD_S = 0.8
TERMS = [(0.13, 1.00, 0.050), (0.26, 0.40, 0.060), (0.42, 0.25, 0.050), (0.35, 0.30, 0.220)]


def shape(t):
    s = 0.0
    for centre, height, width in TERMS:
        for k in (-2, -1, 0, 1, 2):
            s += height * math.exp(-(((t - centre - k * PERIOD_S) / width) ** 2))
    return s


def main():
    n = 80
    ts = [PERIOD_S * i / n for i in range(n + 1)]
    raw = [shape(t) for t in ts]
    lo, hi = min(raw), max(raw)
    with open("brachial_pressure.csv", "w") as f:
        f.write("# One synthesised brachial pressure beat (not a recording): make_brachial_pressure.py\n")
        f.write("t_s,pressure_mmHg\n")
        for t, v in zip(ts, raw):
            f.write(f"{t:.3f},{80 + 40 * (v - lo) / (hi - lo):.2f}\n")


if __name__ == "__main__":
    main()
