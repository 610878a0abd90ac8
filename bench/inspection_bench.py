#!/usr/bin/env python3
"""Streamed and binary projections against a JSON batch, on the same near points of a torus.

For each point count, the formats run interleaved, --runs times, against one footpoint-server
started here (2 worker threads, loopback): a JSON batch (JSON in, one JSON answer), NDJSON (JSON
in, one result a line, streamed), binary (float64 points in, fixed-size records streamed out).
Every request asks for the same fields (foot_point, parameters, distance, normal,
signed_distance, diagnostics.status). Printed per format and count, medians of the runs:
points/s (wall time of the whole request, from the first byte sent to the last received), answer
bytes per point, request bytes per point, the time to the first result (first line or record),
and the server's peak resident memory above its idle size during the request (VmHWM after
/proc/PID/clear_refs reset it to the current size before the request).

    bench/inspection_bench.py --server build/footpoint-server [--counts 100000 1000000] [--runs 3]
"""
import argparse
import http.client
import json
import math
import struct
import subprocess
import sys
import threading
import time

TORUS = {"type": "parametric_surface", "x": "(3+cos(v))*cos(u)", "y": "(3+cos(v))*sin(u)", "z": "sin(v)",
         "domain": {"u": [0, "2*_pi"], "v": [0, "2*_pi"]}}
FIELDS = ["foot_point", "parameters", "distance", "normal", "signed_distance", "diagnostics.status"]


def near_points(n):
    # a deterministic spread of points within 1 % of the tube's radius off the torus
    points = []
    golden = (math.sqrt(5) - 1) / 2
    for i in range(n):
        u, v = 2 * math.pi * ((i * golden) % 1.0), 2 * math.pi * ((i * golden * golden + 0.5 * i / n) % 1.0)
        e = 0.01 * math.sin(7.0 * i)
        w = 3 + (1 + e) * math.cos(v)
        points.append((w * math.cos(u), w * math.sin(u), (1 + e) * math.sin(v)))
    return points


def start_server(binary):
    server = subprocess.Popen([binary, "--host", "127.0.0.1", "--port", "0", "--threads", "2",
                               "--max-points", "20000000", "--max-body-bytes", str(2 << 30),
                               "--max-inflight-points", "20000000", "--deadline-ms", "3600000",
                               "--log-level", "info"],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    for line in server.stdout:
        record = json.loads(line)
        if record.get("msg") == "listening":
            threading.Thread(target=lambda: [None for _ in server.stdout], daemon=True).start()
            return server, record["port"]
    raise SystemExit("the server did not start")


def status_kib(pid, key):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith(key + ":"):
                return int(line.split()[1])
    return 0


def run(port, pid, geometry_id, fmt, body):
    path = "/v1/geometries/%s/project" % geometry_id
    headers = {"Content-Type": "application/json"}
    if fmt == "ndjson":
        headers["Accept"] = "application/x-ndjson"
    elif fmt == "binary":
        path += "?fields=" + ",".join(FIELDS)
        headers = {"Content-Type": "application/octet-stream", "Accept": "application/octet-stream"}
    with open("/proc/%d/clear_refs" % pid, "w") as f:
        f.write("5")  # the peak resident size starts again from the current one
    idle = status_kib(pid, "VmRSS")
    c = http.client.HTTPConnection("127.0.0.1", port, timeout=3600)
    start = time.perf_counter()
    c.request("POST", path, body=body, headers=headers)
    response = c.getresponse()
    if response.status != 200:
        raise SystemExit("%s: %d %s" % (fmt, response.status, response.read()[:300]))
    response.read(1)  # the first byte of the first result
    first_at = time.perf_counter() - start
    size = 1 + len(response.read())
    elapsed = time.perf_counter() - start
    c.close()
    peak = status_kib(pid, "VmHWM")
    return {"seconds": elapsed, "first": first_at, "bytes": size, "peak_mib": (peak - idle) / 1024.0}


def median(values):
    values = sorted(values)
    return values[len(values) // 2]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--server", required=True)
    parser.add_argument("--counts", type=int, nargs="+", default=[100000, 1000000])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--formats", nargs="+", default=["json", "ndjson", "binary"])
    args = parser.parse_args()
    server, port = start_server(args.server)
    try:
        c = http.client.HTTPConnection("127.0.0.1", port)
        c.request("POST", "/v1/geometries", body=json.dumps(TORUS), headers={"Content-Type": "application/json"})
        geometry_id = json.loads(c.getresponse().read())["geometry_id"]
        c.close()
        print("format  points   points/s  answer B/pt  request B/pt  first result ms  peak RSS above idle MiB")
        for n in args.counts:
            points = near_points(n)
            flat = [x for p in points for x in p]
            bodies = {
                "json": json.dumps({"points": points, "fields": FIELDS}).encode(),
                "binary": struct.pack("<%dd" % len(flat), *flat),
            }
            bodies["ndjson"] = bodies["json"]
            del points, flat
            runs = {fmt: [] for fmt in args.formats}
            for _ in range(args.runs):
                for fmt in args.formats:  # interleaved
                    runs[fmt].append(run(port, server.pid, geometry_id, fmt, bodies[fmt]))
            for fmt in args.formats:
                r = runs[fmt]
                print("%-7s %-8d %9.0f  %11.1f  %12.1f  %15.1f  %8.1f   (runs: %s s)" % (
                    fmt, n, n / median([x["seconds"] for x in r]), median([x["bytes"] for x in r]) / n,
                    len(bodies[fmt]) / n, 1e3 * median([x["first"] for x in r]),
                    median([x["peak_mib"] for x in r]),
                    ", ".join("%.2f" % x["seconds"] for x in r)), flush=True)
    finally:
        server.terminate()
        server.wait(timeout=60)
    return 0


if __name__ == "__main__":
    sys.exit(main())
