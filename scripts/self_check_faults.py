#!/usr/bin/env python3
"""Fault variants of a CARMEN log with ODOM lines, used to validate the map self-check
(docs/self_check.md) until `gridslam perturb` lands. Seeded; every laser line and timestamp is kept.
usage: self_check_faults.py IN OUT [--glitch-period P] [--trans-period P] [--scale-t S]
                            [--scale-r S] [--max-range R] [--noise SIGMA] [--seed N]"""
import argparse, math, random

ap = argparse.ArgumentParser()
ap.add_argument("inp"); ap.add_argument("out")
ap.add_argument("--glitch-period", type=float, default=0.0)
ap.add_argument("--trans-period", type=float, default=0.0)
ap.add_argument("--scale-t", type=float, default=1.0)
ap.add_argument("--scale-r", type=float, default=1.0)
ap.add_argument("--max-range", type=float, default=0.0)
ap.add_argument("--noise", type=float, default=0.0)
ap.add_argument("--seed", type=int, default=1)
a = ap.parse_args()
rng = random.Random(a.seed)

def compose(p, q):
    x, y, t = p; c, s = math.cos(t), math.sin(t)
    return (x + c * q[0] - s * q[1], y + s * q[0] + c * q[1], t + q[2])

def inverse(p):
    x, y, t = p; c, s = math.cos(t), math.sin(t)
    return (-(c * x + s * y), -(-s * x + c * y), -t)

def wrap(t):
    return math.atan2(math.sin(t), math.cos(t))

out_pose = None; prev_raw = None
next_glitch = None; next_trans = None
glitches = 0
with open(a.inp) as fi, open(a.out, "w") as fo:
    for line in fi:
        f = line.split()
        if f and f[0] == "ODOM":
            raw = (float(f[1]), float(f[2]), float(f[3]))
            t = float(f[7])
            if out_pose is None:
                out_pose = raw
                if a.glitch_period > 0: next_glitch = t + rng.expovariate(1.0 / a.glitch_period)
                if a.trans_period > 0: next_trans = t + rng.expovariate(1.0 / a.trans_period)
            else:
                d = compose(inverse(prev_raw), raw)
                d = (d[0] * a.scale_t, d[1] * a.scale_t, wrap(d[2]) * a.scale_r)
                if next_glitch is not None and t >= next_glitch:
                    d = (d[0], d[1], d[2] + rng.choice([-1, 1]) * math.radians(rng.uniform(25, 85)))
                    next_glitch = t + rng.expovariate(1.0 / a.glitch_period); glitches += 1
                if next_trans is not None and t >= next_trans:
                    ang = rng.uniform(-math.pi, math.pi); r = rng.uniform(0.3, 1.0)
                    d = (d[0] + r * math.cos(ang), d[1] + r * math.sin(ang), d[2])
                    next_trans = t + rng.expovariate(1.0 / a.trans_period); glitches += 1
                out_pose = compose(out_pose, d)
            prev_raw = raw
            f[1], f[2], f[3] = "%.6f" % out_pose[0], "%.6f" % out_pose[1], "%.6f" % wrap(out_pose[2])
            fo.write(" ".join(f) + "\n")
        elif f and f[0] == "RAWLASER1" and (a.max_range > 0 or a.noise > 0):
            n = int(f[8])
            for k in range(9, 9 + n):
                r = float(f[k])
                if r < 80.0:
                    if a.noise > 0: r = max(0.0, r + rng.gauss(0.0, a.noise))
                    if a.max_range > 0 and r > a.max_range: r = 81.91
                f[k] = "%.3f" % r
            fo.write(" ".join(f) + "\n")
        else:
            fo.write(line)
print("glitches", glitches)
