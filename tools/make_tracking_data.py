#!/usr/bin/env python3
"""Makes the shipped tracker data of data/tracking/: what an NDI Aurora behind
PlusServer would have streamed while a hand with a 6-DOF sensor on each of three fingers
palpated paper 002's phantom, and the calibration sessions before it.

The tracker's frame is not the scene's: the Aurora's field generator sits beside the phantom,
its frame turned 30 degrees about the vertical and upside down (z into the table), offset by
(-150, 40, -200) mm. Each finger's sensor rides on the nail, its fingertip pad 12 mm along the
sensor's -z axis (the tip offset a calibration finds); fingers tilt a little as they move, so the
offset matters. Positions carry 0.1 mm of seeded Gaussian noise (the Aurora's 6-DOF accuracy is
about 0.5 mm; paper 003 uses 0.5 mm). 40 poses a second per tool, as the Aurora sends.

  phantom_three_fingers_pass.csv  three fingers (Finger1..3ToTracker) press 4 mm deep (2 N on a
                                  0.5 N/mm phantom) on tumor B, A, C and on soft tissue, lifting
                                  between; Finger3 leaves the field for 0.5 s over tumor C
  registration_touches.csv        a calibrated stylus (StylusTipToTracker: its tip) rests 1.2 s
                                  on each of the four fiducials in phantom_fiducials.csv
  pivot_finger1.csv               Finger1ToTracker pivots about its fingertip in a divot, 3 s
  digitize_finger1.csv            the stylus tip rests on finger 1's fingertip while the hand moves
  phantom_fiducials.csv           the fiducials' scene coordinates (the phantom's corners' marks)
Run from the repository root:
    python3 tools/make_tracking_data.py
"""
import math
import random

RATE_HZ = 40.0
TIP_LOCAL = (0.0, 0.0, -12.0)  # the fingertip pad in a finger sensor's frame
FIDUCIALS = [("F1", 10.0, 10.0, 0.0), ("F2", 150.0, 10.0, 0.0), ("F3", 150.0, 110.0, 0.0), ("F4", 10.0, 110.0, 5.0)]


def matmul(a, b):
    return [[sum(a[i][k] * b[k][j] for k in range(3)) for j in range(3)] for i in range(3)]


def apply(r, p):
    return [sum(r[i][k] * p[k] for k in range(3)) for i in range(3)]


def rot_x(deg):
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    return [[1, 0, 0], [0, c, -s], [0, s, c]]


def rot_y(deg):
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    return [[c, 0, s], [0, 1, 0], [-s, 0, c]]


def rot_z(deg):
    a = math.radians(deg)
    c, s = math.cos(a), math.sin(a)
    return [[c, -s, 0], [s, c, 0], [0, 0, 1]]


# Scene -> tracker (the field generator's frame).
SCENE_TO_TRACKER_R = matmul(rot_z(30.0), rot_x(180.0))
SCENE_TO_TRACKER_T = [-150.0, 40.0, -200.0]


def to_tracker(r_scene, o_scene):
    return matmul(SCENE_TO_TRACKER_R, r_scene), [a + b for a, b in zip(apply(SCENE_TO_TRACKER_R, o_scene), SCENE_TO_TRACKER_T)]


def quaternion(r):
    """Rotation matrix -> (x, y, z, w)."""
    t = r[0][0] + r[1][1] + r[2][2]
    if t > 0:
        s = math.sqrt(t + 1.0) * 2
        return ((r[2][1] - r[1][2]) / s, (r[0][2] - r[2][0]) / s, (r[1][0] - r[0][1]) / s, 0.25 * s)
    if r[0][0] > r[1][1] and r[0][0] > r[2][2]:
        s = math.sqrt(1.0 + r[0][0] - r[1][1] - r[2][2]) * 2
        return (0.25 * s, (r[0][1] + r[1][0]) / s, (r[0][2] + r[2][0]) / s, (r[2][1] - r[1][2]) / s)
    if r[1][1] > r[2][2]:
        s = math.sqrt(1.0 + r[1][1] - r[0][0] - r[2][2]) * 2
        return ((r[0][1] + r[1][0]) / s, 0.25 * s, (r[1][2] + r[2][1]) / s, (r[0][2] - r[2][0]) / s)
    s = math.sqrt(1.0 + r[2][2] - r[0][0] - r[1][1]) * 2
    return ((r[0][2] + r[2][0]) / s, (r[1][2] + r[2][1]) / s, 0.25 * s, (r[1][0] - r[0][1]) / s)


class Writer:
    def __init__(self, path, comment, seed):
        self.f = open(path, "w")
        self.rng = random.Random(seed)
        for line in comment:
            self.f.write("# " + line + "\n")
        self.f.write("t_s,tool,x_mm,y_mm,z_mm,qx,qy,qz,qw\n")

    def pose(self, t, tool, r_scene, o_scene, noise_mm=0.1):
        r, o = to_tracker(r_scene, o_scene)
        o = [v + self.rng.gauss(0.0, noise_mm) for v in o]
        q = quaternion(r)
        self.f.write(f"{t:.3f},{tool},{o[0]:.3f},{o[1]:.3f},{o[2]:.3f},{q[0]:.6f},{q[1]:.6f},{q[2]:.6f},{q[3]:.6f}\n")

    def close(self):
        self.f.close()


def finger_pose(tip_scene, yaw_deg, pitch_deg):
    """The sensor pose (scene frame) that puts the fingertip pad at tip_scene."""
    r = matmul(rot_z(yaw_deg), rot_y(pitch_deg))
    off = apply(r, TIP_LOCAL)
    return r, [tip_scene[i] - off[i] for i in range(3)]


def smooth(u):
    u = min(max(u, 0.0), 1.0)
    return u * u * (3 - 2 * u)


def write_pass(path):
    # Fingers side by side across the hand (y), 16 mm apart; finger 2 (middle) leads.
    spread = [-16.0, 0.0, 16.0]
    # Where finger 2 goes: B under finger 2, A under finger 1 (40, 40), C under finger 2, soft tissue.
    stops = [("B", 110.0, 50.0), ("A", 40.0, 56.0), ("C", 70.0, 90.0), ("soft", 140.0, 100.0)]
    legs = []
    t = 0.0
    pos = (130.0, 20.0)
    for name, x, y in stops:
        legs.append(("move", t, t + 1.0, pos, (x, y)))
        t += 1.0
        legs.append(("press", t, t + 1.6, (x, y), (x, y)))
        t += 1.6
        pos = (x, y)
    end = t + 0.3
    w = Writer(path, ["Three tracked fingers palpating paper 002's phantom (tools/make_tracking_data.py):",
                      "Finger1..3ToTracker press 4 mm deep on tumors B, A, C and soft tissue; Finger3 leaves the",
                      "field for 0.5 s over tumor C. Tracker frame: the Aurora's (see tracking_three_fingers.json)."], 26)
    n = int(end * RATE_HZ)
    for k in range(n + 1):
        tk = k / RATE_HZ
        hand = pos
        depth = 0.0
        for kind, t0, t1, a, b in legs:
            if t0 <= tk <= t1:
                if kind == "move":
                    u = smooth((tk - t0) / (t1 - t0))
                    hand = (a[0] + (b[0] - a[0]) * u, a[1] + (b[1] - a[1]) * u)
                    depth = 0.0
                else:
                    hand = a
                    # Down in 0.3 s, held, up in 0.3 s.
                    u = min((tk - t0) / 0.3, (t1 - tk) / 0.3, 1.0)
                    depth = 4.0 * smooth(u)
                break
        for i, tool in enumerate(["Finger1ToTracker", "Finger2ToTracker", "Finger3ToTracker"]):
            if i == 2 and 7.0 <= tk < 7.5:
                continue  # out of the field: PlusServer sends valid transforms only
            # From 3 mm above the surface down to 4 mm into it.
            tip = [hand[0], hand[1] + spread[i], 3.0 - 7.0 * depth / 4.0]
            yaw = 10.0 * math.sin(0.7 * tk)
            pitch = 25.0 + 5.0 * math.sin(1.3 * tk + i)
            r, o = finger_pose(tip, yaw, pitch)
            w.pose(tk, tool, r, o)
    w.close()


def write_registration(path):
    w = Writer(path, ["A calibrated stylus (StylusTipToTracker: the pose of its tip) rests 1.2 s on each fiducial of",
                      "phantom_fiducials.csv in turn (tools/make_tracking_data.py)."], 27)
    t = 0.0
    prev = (80.0, 60.0, 30.0)
    for name, x, y, z in FIDUCIALS:
        # 0.5 s on the way (30 mm up), then the rest.
        for k in range(int(0.5 * RATE_HZ)):
            u = smooth(k / (0.5 * RATE_HZ))
            p = [prev[0] + (x - prev[0]) * u, prev[1] + (y - prev[1]) * u, 30.0 * (1 - u) + z * u]
            w.pose(t, "StylusTipToTracker", rot_y(20.0), p)
            t += 1 / RATE_HZ
        for k in range(int(1.2 * RATE_HZ)):
            w.pose(t, "StylusTipToTracker", matmul(rot_z(5.0 * k / 48), rot_y(20.0)), [x, y, z])
            t += 1 / RATE_HZ
        prev = (x, y, 30.0)
    w.close()


def write_pivot(path):
    w = Writer(path, ["Finger1ToTracker pivots about its fingertip resting in a divot at (80, 60, 0) mm on the scene,",
                      "in a cone of about 25 degrees, for 3 s (tools/make_tracking_data.py)."], 28)
    n = int(3.0 * RATE_HZ)
    for k in range(n):
        tk = k / RATE_HZ
        yaw = 360.0 * tk / 1.5
        tilt = 25.0
        r = matmul(rot_z(yaw), rot_y(tilt))
        r = matmul(r, rot_z(-yaw))  # a cone: the sensor's z axis circles the vertical
        off = apply(r, TIP_LOCAL)
        w.pose(tk, "Finger1ToTracker", r, [80.0 - off[0], 60.0 - off[1], 0.0 - off[2]], noise_mm=0.15)
    w.close()


def write_digitize(path):
    w = Writer(path, ["The stylus tip (StylusTipToTracker) rests on finger 1's fingertip pad for 2 s while the hand",
                      "drifts a little; both tracked (tools/make_tracking_data.py)."], 29)
    n = int(2.0 * RATE_HZ)
    for k in range(n):
        tk = k / RATE_HZ
        tip = [80.0 + 2.0 * tk, 60.0 + 1.0 * math.sin(tk), 10.0]
        r, o = finger_pose(tip, 15.0 * math.sin(0.5 * tk), 30.0)
        w.pose(tk, "Finger1ToTracker", r, o, noise_mm=0.05)
        w.pose(tk, "StylusTipToTracker", rot_y(-30.0), tip, noise_mm=0.05)
    w.close()


def write_fiducials(path):
    with open(path, "w") as f:
        f.write("# The phantom's four fiducial marks on the scene (mm; F4 on a 5 mm post); tools/make_tracking_data.py\n")
        f.write("name,x_mm,y_mm,z_mm\n")
        for name, x, y, z in FIDUCIALS:
            f.write(f"{name},{x:g},{y:g},{z:g}\n")


def print_registration():
    """The tracker -> scene transform, for the shipped tracking files."""
    rt = [[SCENE_TO_TRACKER_R[j][i] for j in range(3)] for i in range(3)]
    t = [-v for v in apply(rt, SCENE_TO_TRACKER_T)]
    print("rotation", [[round(v, 6) for v in row] for row in rt])
    print("translation_mm", [round(v, 4) for v in t])


if __name__ == "__main__":
    write_pass("data/tracking/phantom_three_fingers_pass.csv")
    write_registration("data/tracking/registration_touches.csv")
    write_pivot("data/tracking/pivot_finger1.csv")
    write_digitize("data/tracking/digitize_finger1.csv")
    write_fiducials("data/tracking/phantom_fiducials.csv")
    print_registration()
