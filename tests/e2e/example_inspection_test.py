#!/usr/bin/env python3
"""examples/inspection/inspection.py against a live footpoint-server started here: the outputs
exist (CSV, two PNGs, summary.json) and the deviations found are the offsets the synthetic scan was
given (Gaussian noise of known sigma plus a known dent), point by point and in the statistics.

    example_inspection_test.py --server build/footpoint-server --source . --out build/inspection
"""
import argparse
import csv
import importlib.util
import json
import math
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_server import LiveServer  # noqa: E402


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--server", required=True)
    parser.add_argument("--source", required=True)
    parser.add_argument("--out", required=True)
    args = parser.parse_args()
    if importlib.util.find_spec("matplotlib") is None:
        print("skip: python3-matplotlib is not installed (install-deps.sh --test)")
        return 77
    sys.path.insert(0, os.path.join(args.source, "examples", "inspection"))
    import inspection

    n, sigma, dent, seed, band = 6000, 0.01, 0.08, 5, (-0.025, 0.025)
    with LiveServer(args.server, "--threads", "2") as server:
        assert inspection.main(["--server", server.url, "--out", args.out, "--points", str(n), "--sigma", str(sigma),
                                "--dent", str(dent), "--seed", str(seed), "--batch-size", "2500",
                                "--band", str(band[0]), str(band[1])]) == 0

    for name in ("deviation_map.png", "histogram.png"):
        with open(os.path.join(args.out, name), "rb") as f:
            head = f.read(8)
        assert head == b"\x89PNG\r\n\x1a\n", name + " is no PNG"
        assert os.path.getsize(os.path.join(args.out, name)) > 10000, name + " is nearly empty"
    print("ok: deviation_map.png and histogram.png")

    points, offsets, dents = inspection.synthetic_scan(n, sigma, dent, seed)
    with open(os.path.join(args.out, "deviations.csv")) as f:
        rows = list(csv.DictReader(f))
    assert len(rows) == n, len(rows)
    worst = 0.0
    for row, p, e in zip(rows, points, offsets):
        assert row["status"] == "converged", row
        assert [float(row[k]) for k in ("x", "y", "z")] == p
        worst = max(worst, abs(float(row["signed_distance"]) - e))
    assert worst < 1e-9, worst
    print("ok: every signed deviation is the offset the point was given (worst difference %.1e)" % worst)

    with open(os.path.join(args.out, "summary.json")) as f:
        summary = json.load(f)
    mean = math.fsum(offsets) / n
    rms = math.sqrt(math.fsum(e * e for e in offsets) / n)
    within = sum(1 for e in offsets if band[0] <= e <= band[1]) / n
    assert summary["count"] == n and summary["converged"] == n, summary
    assert abs(summary["mean"] - mean) < 1e-9 and abs(summary["rms"] - rms) < 1e-9, (summary, mean, rms)
    assert abs(summary["min"] - min(offsets)) < 1e-9 and abs(summary["max"] - max(offsets)) < 1e-9, summary
    assert abs(summary["share_within"] - within) < 1e-12, (summary, within)
    # and the noise itself: the deviations less the dent are N(0, sigma): their root mean square
    # within 5 % of sigma (n = 6000: the estimate's relative error is ~1 %)
    noise = [float(r["signed_distance"]) - d for r, d in zip(rows, dents)]
    spread = math.sqrt(math.fsum(e * e for e in noise) / n)
    assert abs(spread - sigma) < 0.05 * sigma, spread
    # the dent: its deepest point is found near -dent
    assert summary["min"] < -0.8 * dent, summary
    print("ok: summary (mean %.5f, rms %.5f, share within the band %.3f) and the noise's sigma %.5f"
          % (summary["mean"], summary["rms"], summary["share_within"], spread))
    return 0


if __name__ == "__main__":
    sys.exit(main())
