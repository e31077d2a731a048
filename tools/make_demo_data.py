#!/usr/bin/env python3
"""Makes the bundled demo data: paper 002's silicone phantom with tumors A, B, C as a
normalised 16-bit PGM stiffness map, and a pen trace that passes over each tumor.

The phantom is 160 x 120 mm sampled every 1 mm. Background silicone (E = 14.7 kPa) is near 0
with a little measured-looking texture; the rubber tumors (E = 21.9 kPa) reach 1.0 with a
smooth 2 mm edge. T1 tumors are 20 mm or less; sizes follow the paper's sensitivity order
(A smallest, B largest, C between). Run from the repository root:
    python3 tools/make_demo_data.py
"""
import math
import random

WIDTH_MM, HEIGHT_MM, STEP_MM = 160, 120, 1.0
TUMORS = [("A", 40.0, 40.0, 4.0), ("B", 110.0, 50.0, 10.0), ("C", 70.0, 90.0, 7.0)]  # name, x, y, radius


def stiffness(x, y, rng):
    s = 0.05 + 0.02 * rng.random()
    for _, tx, ty, r in TUMORS:
        d = math.hypot(x - tx, y - ty)
        edge = 1.0 / (1.0 + math.exp((d - r) / 0.5))  # ~2 mm wide edge
        s = max(s, edge)
    return min(max(s, 0.0), 1.0)


def write_map(path):
    rng = random.Random(2)
    cols, rows = int(WIDTH_MM / STEP_MM) + 1, int(HEIGHT_MM / STEP_MM) + 1
    with open(path, "wb") as f:
        f.write(b"P5\n# palprig demo phantom: tumors A, B, C (tools/make_demo_data.py)\n")
        f.write(f"{cols} {rows}\n65535\n".encode())
        for r in range(rows):
            for c in range(cols):
                q = round(stiffness(c * STEP_MM, r * STEP_MM, rng) * 65535)
                f.write(bytes((q >> 8, q & 0xFF)))


def write_trace(path):
    """Pen path at 30 mm/s, pressing 2 N, lifting between tumors; 100 samples per second."""
    legs = [  # (x0, y0, x1, y1, force_N)
        (10, 40, 70, 40, 2.0),    # across A
        (70, 40, 80, 50, 0.0),    # lifted
        (80, 50, 140, 50, 2.0),   # across B
        (140, 50, 100, 90, 0.0),  # lifted
        (100, 90, 40, 90, 2.0),   # across C
        (40, 90, 20, 110, 0.0),
        (20, 110, 140, 110, 2.0),  # soft tissue only
    ]
    t, dt, speed = 0.0, 0.01, 30.0
    with open(path, "w") as f:
        f.write("t_s,x_mm,y_mm,force_N\n")
        for x0, y0, x1, y1, force in legs:
            n = max(1, int(math.hypot(x1 - x0, y1 - y0) / speed / dt))
            for i in range(n):
                a = i / n
                f.write(f"{t:.3f},{x0 + a * (x1 - x0):.3f},{y0 + a * (y1 - y0):.3f},{force:.3f}\n")
                t += dt
        f.write(f"{t:.3f},{legs[-1][2]:.3f},{legs[-1][3]:.3f},0.000\n")


if __name__ == "__main__":
    write_map("data/scenes/phantom_abc.pgm")
    write_trace("data/traces/phantom_abc_pass.csv")
