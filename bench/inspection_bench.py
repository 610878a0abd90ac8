#!/usr/bin/env python3
"""Streamed and binary projections against a JSON batch, on the same near points of a torus.

For each point count, the formats run interleaved, --runs times, against one footpoint-server
started here (2 worker threads, loopback): a JSON batch (JSON in, one JSON answer), NDJSON (JSON
in, one result a line, streamed), binary (float64 points in, fixed-size records streamed out;
the client sends the whole body, then reads), duplex (binary, the client sending its body from
one thread while it reads the answer in another, as a client of a 10^7-point stream should: the
server then reads the body as it answers, holding a few windows of it), client and client_whole
(clients/python/footpoint.py's binary path in one batch, with its duplex sending and without it:
the whole body sent first; NumPy needed, their first result is not measured).
Every request asks for the same fields (foot_point, parameters, distance, normal,
signed_distance, diagnostics.status). Printed per format and count, medians of the runs:
points/s (wall time of the whole request, from the first byte sent to the last received), answer
bytes per point, request bytes per point, the time to the first result (first line or record),
and the server's peak resident memory above its idle size during the request (VmHWM after
/proc/PID/clear_refs reset it to the current size before the request); then the most any run
reached above the server's size before its first request (memory freed by a request is kept for
the next, so that a run after a larger one may need no more: run one format and count at a time,
as below, for a stream's whole footprint).

    bench/inspection_bench.py --server build/footpoint-server [--counts 100000 1000000] [--runs 3]
        [--formats json ndjson binary duplex client client_whole]
    for n in 1000000 3000000 10000000; do
        bench/inspection_bench.py --server build/footpoint-server --counts $n --runs 3 --formats duplex; done
"""
import array
import argparse
import http.client
import json
import math
import os
import socket
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "clients", "python"))
import footpoint  # noqa: E402  (the client: --formats client client_whole)

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


def near_points_float64(n):
    # the same points as near_points, as little-endian float64 bytes, built a block at a time
    out = bytearray()
    golden = (math.sqrt(5) - 1) / 2
    cos, sin, two_pi = math.cos, math.sin, 2 * math.pi
    for start in range(0, n, 65536):
        block = array.array("d")
        for i in range(start, min(n, start + 65536)):
            u, v = two_pi * ((i * golden) % 1.0), two_pi * ((i * golden * golden + 0.5 * i / n) % 1.0)
            e = 0.01 * sin(7.0 * i)
            w = 3 + (1 + e) * cos(v)
            block.extend((w * cos(u), w * sin(u), (1 + e) * sin(v)))
        if sys.byteorder != "little":
            block.byteswap()
        out += block.tobytes()
    return bytes(out)


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


def read_answer(fmt, response, start, pid, idle):
    # the answer read to its end (a megabyte at a time: a 10^7-point answer is not held here
    # either); the times from `start`, the bytes, the server's peak memory above `idle` (KiB)
    if response.status != 200:
        raise SystemExit("%s: %d %s" % (fmt, response.status, response.read()[:300]))
    response.read(1)  # the first byte of the first result
    first_at = time.perf_counter() - start
    size = 1
    while True:
        piece = response.read(1 << 20)
        if not piece:
            break
        size += len(piece)
    elapsed = time.perf_counter() - start
    peak = status_kib(pid, "VmHWM")
    return {"seconds": elapsed, "first": first_at, "bytes": size, "peak_mib": (peak - idle) / 1024.0,
            "peak_kib": peak}


def run_duplex(port, pid, geometry_id, body):
    path = "/v1/geometries/%s/project?fields=%s" % (geometry_id, ",".join(FIELDS))
    head = ("POST %s HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: application/octet-stream\r\n"
            "Accept: application/octet-stream\r\nContent-Length: %d\r\n\r\n" % (path, len(body))).encode()
    with open("/proc/%d/clear_refs" % pid, "w") as f:
        f.write("5")
    idle = status_kib(pid, "VmRSS")
    sock = socket.create_connection(("127.0.0.1", port), timeout=3600)
    view = memoryview(body)

    def send():
        sock.sendall(head)
        for at in range(0, len(body), 1 << 20):
            sock.sendall(view[at:at + (1 << 20)])

    start = time.perf_counter()
    sender = threading.Thread(target=send)
    sender.start()
    response = http.client.HTTPResponse(sock)
    response.begin()
    result = read_answer("duplex", response, start, pid, idle)
    sender.join()
    sock.close()
    return result


def run_client(port, pid, geometry_id, body, duplex):
    points = footpoint.numpy.frombuffer(body, dtype="<f8").reshape(-1, 3)
    with open("/proc/%d/clear_refs" % pid, "w") as f:
        f.write("5")
    idle = status_kib(pid, "VmRSS")
    start = time.perf_counter()
    with footpoint.Client("http://127.0.0.1:%d" % port, timeout=3600, duplex=duplex) as client:
        result = client.project(geometry_id, points, fields=FIELDS, batch_size=len(points))
    elapsed = time.perf_counter() - start
    peak = status_kib(pid, "VmHWM")
    numbers = sum(column.size for column in result.columns.values())
    return {"seconds": elapsed, "first": float("nan"), "bytes": 8 * numbers, "peak_mib": (peak - idle) / 1024.0,
            "peak_kib": peak}


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
    result = read_answer(fmt, c.getresponse(), start, pid, idle)
    c.close()
    return result


def median(values):
    values = sorted(values)
    return values[len(values) // 2]


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--server", required=True)
    parser.add_argument("--counts", type=int, nargs="+", default=[100000, 1000000])
    parser.add_argument("--runs", type=int, default=3)
    parser.add_argument("--formats", nargs="+", default=["json", "ndjson", "binary", "duplex"],
                        choices=["json", "ndjson", "binary", "duplex", "client", "client_whole"])
    args = parser.parse_args()
    if {"client", "client_whole"} & set(args.formats) and footpoint.numpy is None:
        raise SystemExit("--formats client, client_whole: the client's binary path needs NumPy (python3-numpy)")
    server, port = start_server(args.server)
    try:
        c = http.client.HTTPConnection("127.0.0.1", port)
        c.request("POST", "/v1/geometries", body=json.dumps(TORUS), headers={"Content-Type": "application/json"})
        geometry_id = json.loads(c.getresponse().read())["geometry_id"]
        c.close()
        start_kib = status_kib(server.pid, "VmRSS")
        print("format       points   points/s  answer B/pt  request B/pt  first result ms  peak RSS above idle MiB"
              "  most above start MiB")
        for n in args.counts:
            bodies = {}
            if "json" in args.formats or "ndjson" in args.formats:
                bodies["json"] = bodies["ndjson"] = json.dumps({"points": near_points(n), "fields": FIELDS}).encode()
            if {"binary", "duplex", "client", "client_whole"} & set(args.formats):
                bodies["binary"] = bodies["duplex"] = bodies["client"] = bodies["client_whole"] = near_points_float64(n)
            runs = {fmt: [] for fmt in args.formats}
            for _ in range(args.runs):
                for fmt in args.formats:  # interleaved
                    if fmt == "duplex":
                        runs[fmt].append(run_duplex(port, server.pid, geometry_id, bodies[fmt]))
                    elif fmt.startswith("client"):
                        runs[fmt].append(run_client(port, server.pid, geometry_id, bodies[fmt], fmt == "client"))
                    else:
                        runs[fmt].append(run(port, server.pid, geometry_id, fmt, bodies[fmt]))
            for fmt in args.formats:
                r = runs[fmt]
                print("%-12s %-8d %9.0f  %11.1f  %12.1f  %15.1f  %8.1f  %19.1f   (runs: %s s; %s MiB)" % (
                    fmt, n, n / median([x["seconds"] for x in r]), median([x["bytes"] for x in r]) / n,
                    len(bodies[fmt]) / n, 1e3 * median([x["first"] for x in r]),
                    median([x["peak_mib"] for x in r]), (max(x["peak_kib"] for x in r) - start_kib) / 1024.0,
                    ", ".join("%.2f" % x["seconds"] for x in r), ", ".join("%.1f" % x["peak_mib"] for x in r)),
                      flush=True)
    finally:
        server.terminate()
        server.wait(timeout=60)
    return 0


if __name__ == "__main__":
    sys.exit(main())
