#!/usr/bin/env python3
"""Adds Gaussian noise of SIGMA rad to every relative orientation of a g2o 2-D graph, as in
Carlone's M3500a/b/c (input_M3500b_g2o.g2o is M3500 with sigma = 0.2): dtheta += N(0, sigma^2)
and the rotational information I33 becomes 1 / (1 / I33 + sigma^2). Vertices are re-chained
from the noisy odometry (edges i -> i+1). Deterministic for a seed.

Usage: bench/noisy_orientations.py IN.g2o OUT.g2o SIGMA [SEED]
"""
import math
import random
import sys


def main():
    src, dst, sigma = sys.argv[1], sys.argv[2], float(sys.argv[3])
    rng = random.Random(int(sys.argv[4]) if len(sys.argv) > 4 else 1)
    edges = []
    vertex_ids = []
    for line in open(src):
        f = line.split()
        if not f:
            continue
        if f[0] == "VERTEX_SE2":
            vertex_ids.append(int(f[1]))
        elif f[0] == "EDGE_SE2":
            i, j = int(f[1]), int(f[2])
            z = [float(v) for v in f[3:6]]
            info = [float(v) for v in f[6:12]]
            z[2] += rng.gauss(0.0, sigma)
            info[5] = 1.0 / (1.0 / info[5] + sigma * sigma)
            edges.append((i, j, z, info))
    poses = {vertex_ids[0] if vertex_ids else 0: (0.0, 0.0, 0.0)}
    for i, j, z, _ in edges:
        if j == i + 1 and i in poses and j not in poses:
            x, y, t = poses[i]
            poses[j] = (x + math.cos(t) * z[0] - math.sin(t) * z[1],
                        y + math.sin(t) * z[0] + math.cos(t) * z[1],
                        math.atan2(math.sin(t + z[2]), math.cos(t + z[2])))
    with open(dst, "w") as out:
        for v in sorted(poses):
            out.write("VERTEX_SE2 %d %.6f %.6f %.6f\n" % ((v,) + poses[v]))
        for i, j, z, info in edges:
            out.write("EDGE_SE2 %d %d %.6f %.6f %.6f %s\n"
                      % (i, j, z[0], z[1], z[2], " ".join("%.6f" % v for v in info)))


if __name__ == "__main__":
    main()
