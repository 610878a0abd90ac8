#!/usr/bin/env python3
"""Inspection of a synthetic scan of a torus through the footpoint service and its Python client.

A torus of radii R = 3 and r = 1 is the nominal surface. The "scan" is n points on it, each moved
along the surface's unit normal (outwards: s_u x s_v of this parametrisation) by Gaussian noise of
standard deviation sigma, plus a dent: within 0.6 of the parameter point (u, v) = (1, 0.5) the
points sit up to `dent` further inwards. Every offset is smaller than r, so the nearest point of
the torus to each scanned point is the point it was moved from and its signed distance is the
offset itself: the report must find the noise and the dent that were put in.

Writes to --out: deviations.csv (x, y, z, foot point, signed distance, status per point),
deviation_map.png (the points coloured by signed deviation, with a colour bar), histogram.png
(the deviations' histogram with the tolerance band) and summary.json (count, min, max, mean, RMS,
share within the band).

    examples/inspection/inspection.py --server http://127.0.0.1:8080 --out /tmp/inspection
"""
import argparse
import csv
import json
import math
import os
import random
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "clients", "python"))
import footpoint  # noqa: E402

R, r = 3.0, 1.0
TORUS = {"type": "parametric_surface",
         "x": "(3+cos(v))*cos(u)", "y": "(3+cos(v))*sin(u)", "z": "sin(v)",
         "domain": {"u": [0, "2*_pi"], "v": [0, "2*_pi"]}}
DENT_CENTRE, DENT_RADIUS = (1.0, 0.5), 0.6


def torus_point(u, v):
    return ((R + r * math.cos(v)) * math.cos(u), (R + r * math.cos(v)) * math.sin(u), r * math.sin(v))


def torus_normal(u, v):
    # s_u x s_v = r (R + r cos v) (cos v cos u, cos v sin u, sin v): outwards, of length r (R + r cos v)
    return (math.cos(v) * math.cos(u), math.cos(v) * math.sin(u), math.sin(v))


def synthetic_scan(n, sigma, dent, seed):
    """n scanned points, the offset along the normal each was given, and the dent's part of it."""
    rng = random.Random(seed)
    points, offsets, dents = [], [], []
    while len(points) < n:
        u, v = rng.uniform(0, 2 * math.pi), rng.uniform(0, 2 * math.pi)
        # uniform over the surface: keep (u, v) with probability proportional to the area element
        if rng.uniform(0, R + r) > R + r * math.cos(v):
            continue
        du, dv = u - DENT_CENTRE[0], v - DENT_CENTRE[1]
        rho = math.hypot(du, dv) / DENT_RADIUS
        depth = -dent * (1 - rho * rho) ** 2 if rho < 1 else 0.0
        offset = rng.gauss(0.0, sigma) + depth
        s, nrm = torus_point(u, v), torus_normal(u, v)
        points.append([s[k] + offset * nrm[k] for k in range(3)])
        offsets.append(offset)
        dents.append(depth)
    return points, offsets, dents


def write_csv(path, points, projection):
    feet = projection.column("foot_point")
    signed = projection.column("signed_distance")
    statuses = projection.column("status")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["x", "y", "z", "foot_x", "foot_y", "foot_z", "signed_distance", "status"])
        for p, foot, d, status in zip(points, feet, signed, statuses):
            w.writerow([repr(float(c)) for c in p] + [repr(float(c)) for c in foot] + [repr(float(d)), status])


def plot(out, points, parameters, signed, band, bins):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    # the colour scale covers 99 % of the deviations, the rest saturates (the colour bar's arrows)
    ranked = sorted(abs(d) for d in signed)
    limit = ranked[min(len(ranked) - 1, int(0.99 * len(ranked)))]
    style = dict(c=signed, cmap="coolwarm", vmin=-limit, vmax=limit, linewidths=0)
    fig = plt.figure(figsize=(12, 5), dpi=100)
    ax = fig.add_subplot(1, 2, 1, projection="3d")
    xs, ys, zs = zip(*points)
    ax.scatter(xs, ys, zs, s=3, **style)
    ax.set_box_aspect((1, 1, 0.35))
    ax.view_init(elev=40, azim=-35)
    ax.set_axis_off()
    ax.set_title("the scan, coloured by signed deviation")
    flat = fig.add_subplot(1, 2, 2)
    us, vs = zip(*parameters)
    dots = flat.scatter(us, vs, s=4, **style)
    flat.set_xlabel("u (around the axis)")
    flat.set_ylabel("v (around the tube)")
    flat.set_aspect("equal")
    flat.set_title("the same on the parameters of the foot points")
    bar = fig.colorbar(dots, ax=flat, extend="both", shrink=0.9)
    bar.set_label("signed deviation (outwards +)")
    fig.tight_layout()
    fig.savefig(os.path.join(out, "deviation_map.png"), bbox_inches="tight")
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(8, 4), dpi=100)
    ax.hist(signed, bins=bins, color="#4a7bb7")
    ax.axvspan(band[0], band[1], color="#6ab04c", alpha=0.2, label="tolerance band [%g, %g]" % tuple(band))
    ax.set_xlabel("signed deviation")
    ax.set_ylabel("points")
    ax.legend()
    ax.set_title("Deviations of %d scanned points" % len(signed))
    fig.tight_layout()
    fig.savefig(os.path.join(out, "histogram.png"))
    plt.close(fig)


def main(argv=None):
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--server", default="http://127.0.0.1:8080")
    parser.add_argument("--out", required=True)
    parser.add_argument("--points", type=int, default=20000)
    parser.add_argument("--sigma", type=float, default=0.01)
    parser.add_argument("--dent", type=float, default=0.08)
    parser.add_argument("--band", type=float, nargs=2, default=[-0.025, 0.025])
    parser.add_argument("--bins", type=int, default=60)
    parser.add_argument("--seed", type=int, default=37)
    parser.add_argument("--batch-size", type=int, default=5000)
    args = parser.parse_args(argv)

    os.makedirs(args.out, exist_ok=True)
    points, _, _ = synthetic_scan(args.points, args.sigma, args.dent, args.seed)
    projection = footpoint.project(TORUS, points, server=args.server, batch_size=args.batch_size,
                                   fields=["foot_point", "parameters", "signed_distance", "diagnostics.status"])
    signed = [float(d) for d in projection.column("signed_distance")]
    write_csv(os.path.join(args.out, "deviations.csv"), points, projection)
    summary = footpoint.deviation_summary(signed, args.band)
    summary["converged"] = sum(1 for s in projection.column("status") if s == "converged")
    with open(os.path.join(args.out, "summary.json"), "w") as f:
        json.dump(summary, f, indent=2)
    parameters = [(float(u), float(v)) for u, v in projection.column("parameters")]
    plot(args.out, points, parameters, signed, args.band, args.bins)
    print(json.dumps(summary))
    return 0


if __name__ == "__main__":
    sys.exit(main())
