#!/usr/bin/env python3
"""clients/python/footpoint.py against a live footpoint-server started here (loopback, port 0).

Checks, against the closed form of a sphere of radius 2 (the signed distance of p is 2 - |p| for
its parametrisation, whose s_u x s_v points inwards): the JSON/NDJSON path (NumPy hidden) and the
binary path, in batches, in order; the binary path's duplex sending (the body written from a
thread while the answer is read) against sending the whole body first, on 10^6 points in one
request, with the server's peak resident memory above idle printed for each; an error answered
while a large duplex body is still being sent; re-posting a definition the server no longer
holds; errors raised with the server's status, code and message; and a 503 (a second server
answering one request at a time, busy with a long stream) retried after Retry-After until it
succeeds.

    client_python_test.py --server build/footpoint-server --client clients/python
"""
import argparse
import math
import os
import sys
import threading
import time
import urllib.request

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from live_server import LiveServer  # noqa: E402

SPHERE = {"type": "parametric_surface", "x": "2*sin(v)*cos(u)", "y": "2*sin(v)*sin(u)", "z": "2*cos(v)",
          "domain": {"u": [0, "2*_pi"], "v": [0, "_pi"]}}


def points_and_expected(n):
    points, expected = [], []
    for i in range(n):
        u, v, r = 0.1 + 6.0 * i / n, 0.4 + 2.3 * ((i * 7) % n) / n, 1.5 + (i % 11) / 10.0
        points.append([r * math.sin(v) * math.cos(u), r * math.sin(v) * math.sin(u), r * math.cos(v)])
        expected.append(2.0 - r)
    return points, expected


def metric(base, name):
    text = urllib.request.urlopen(base + "/metrics").read().decode()
    total = 0.0
    for line in text.splitlines():
        if line.startswith(name):
            total += float(line.rsplit(" ", 1)[1])
    return total


def sphere_points_numpy(numpy, n):
    """points_and_expected(n) in NumPy: the points and 2 - |p| from their coordinates."""
    i = numpy.arange(n)
    u, v, r = 0.1 + 6.0 * i / n, 0.4 + 2.3 * ((i * 7) % n) / n, 1.5 + (i % 11) / 10.0
    points = numpy.stack([r * numpy.sin(v) * numpy.cos(u), r * numpy.sin(v) * numpy.sin(u), r * numpy.cos(v)], axis=1)
    return points, 2.0 - numpy.sqrt((points * points).sum(axis=1))


def status_kib(pid, field):
    with open("/proc/%d/status" % pid) as f:
        for line in f:
            if line.startswith(field + ":"):
                return int(line.split()[1])
    raise KeyError(field)


def check(condition, what):
    if not condition:
        raise AssertionError(what)
    print("ok:", what)


def close(a, b, tol=1e-12):
    return abs(a - b) <= tol * max(1.0, abs(b))


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("--server", required=True)
    parser.add_argument("--client", required=True)
    args = parser.parse_args()
    sys.path.insert(0, args.client)
    import footpoint

    # The 10^6-point requests below may take minutes on an instrumented build (scripts/sanitize.sh):
    # no request deadline or read deadline cuts them there.
    with LiveServer(args.server, "--threads", "2", "--max-body-bytes", "64000000", "--deadline-ms", "1200000",
                    "--read-timeout-s", "0") as server:
        base = server.url
        points, expected = points_and_expected(250)
        client = footpoint.Client(base)

        # JSON in, NDJSON out, three batches
        numpy_module, footpoint.numpy = footpoint.numpy, None
        try:
            result = client.project(SPHERE, points, batch_size=100, tolerance_band=[-0.2, 0.2])
        finally:
            footpoint.numpy = numpy_module
        check(len(result) == 250 and len(result.stats) == 3, "NDJSON path: 250 results in 3 batches")
        check(all(close(s, e) for s, e in zip(result.column("signed_distance"), expected)),
              "NDJSON path: signed distances are 2 - |p|, in order")
        check(sum(s["deviation"]["count"] for s in result.stats) == 250, "NDJSON path: each batch's stats")
        check(all(s == "converged" for s in result.column("status")), "NDJSON path: every point converged")

        if footpoint.numpy is not None:
            numpy = footpoint.numpy
            result = client.project(SPHERE, numpy.array(points), batch_size=64, max_distance=0.45)
            sd = result.columns["signed_distance"]
            check(sd.shape == (250,) and result.columns["foot_point"].shape == (250, 3), "binary path: columns")
            for s, e, status in zip(sd, expected, result.column("status")):
                if abs(e) > 0.45:
                    assert math.isnan(s) and status == "beyond_max_distance", (s, e, status)
                else:
                    assert close(s, e) and status == "converged", (s, e, status)
            check(True, "binary path: signed distances, NaN and beyond_max_distance past max_distance")
            result = client.project(SPHERE, points, fields=["distance"], binary=True)
            check(list(result.columns) == ["distance"] and close(result.columns["distance"][3], abs(expected[3])),
                  "binary path: fields")

            # 10^6 points in one request, the body sent from a writer thread while the answer is
            # read (duplex), and sent whole before (http.client's way): the same answers
            many, many_expected = sphere_points_numpy(numpy, 10 ** 6)
            for duplex in (True, False):
                with open("/proc/%d/clear_refs" % server.process.pid, "w") as f:
                    f.write("5")  # VmHWM starts again from the current resident size
                idle = status_kib(server.process.pid, "VmRSS")
                started = time.time()
                with footpoint.Client(base, duplex=duplex) as c:
                    sd = c.project(SPHERE, many, batch_size=10 ** 6, fields=["signed_distance"]).columns["signed_distance"]
                    seconds = time.time() - started
                    again = c.project(SPHERE, numpy.array(points[:3]), fields=["signed_distance"])
                peak = (status_kib(server.process.pid, "VmHWM") - idle) / 1024.0
                worst = float(numpy.max(numpy.abs(sd - many_expected)))
                check(sd.shape == (10 ** 6,) and worst <= 1e-12 and close(again.columns["signed_distance"][2], expected[2]),
                      "%s: 10^6 signed distances are 2 - |p| in order (largest difference %.1e), the connection "
                      "serves the next request" % ("duplex" if duplex else "whole body first", worst))
                print("figure: %s, 10^6 points in one request: %.1f s, server peak RSS %.1f MiB above idle"
                      % ("duplex" if duplex else "whole body first", seconds, peak))

            # an error answered while a large duplex body is being sent: raised, not a hang
            bad = many.copy()
            bad[5, 1] = float("nan")
            try:
                client.project(SPHERE, bad, batch_size=10 ** 6, fields=["signed_distance"])
                check(False, "a NaN coordinate raises")
            except footpoint.FootpointError as e:
                check(e.status == 400 and e.code == "number_out_of_range" and e.field == "points[5][1]",
                      "duplex: a NaN at point 5 of 10^6 raises 400 number_out_of_range while the body is sent")
            result = client.project(SPHERE, numpy.array(points[:4]), fields=["signed_distance"])
            check(close(result.columns["signed_distance"][3], expected[3]), "and the client goes on with a new connection")
        else:
            print("skip: NumPy is not installed (binary path)")

        # the server forgets the geometry: the client posts it again
        geometry_id = client.create_geometry(SPHERE)
        client.delete_geometry(geometry_id)
        result = client.project(SPHERE, points[:5], binary=False)
        check(close(result.column("signed_distance")[4], expected[4]), "a deleted geometry is posted again")
        check(urllib.request.urlopen(base + "/v1/geometries/" + geometry_id).status == 200, "and held again")

        # errors raise with the server's status, code and message
        try:
            client.project(dict(SPHERE, x="sinn(v)"), points)
            check(False, "a bad formula raises")
        except footpoint.FootpointError as e:
            check(e.status == 422 and e.code == "unknown_function" and "sin" in e.message,
                  "a bad formula raises 422 unknown_function")
        try:
            client.project("0" * 32, points)
            check(False, "an id not held raises")
        except footpoint.FootpointError as e:
            check(e.status == 404 and e.code == "geometry_not_found", "an id not held (no definition) raises 404")
        try:
            client.project(SPHERE, [[1, 2]], binary=False)
            check(False, "a 2-D point on a surface raises")
        except footpoint.FootpointError as e:
            check(e.status == 400 and e.code == "wrong_dimension", "a 2-D point on a surface raises 400")
        client.close()

    # 503: a server answering one request at a time, busy with a long stream
    with LiveServer(args.server, "--threads", "1", "--max-inflight", "1", "--connection-threads", "2") as server:
        base = server.url
        busy = footpoint.Client(base)
        geometry_id = busy.create_geometry(SPHERE)
        long_points, _ = points_and_expected(60000)
        outcome = {}

        def long_request():
            outcome["n"] = len(busy.project(geometry_id, long_points, batch_size=60000, binary=False,
                                            fields=["distance"]))

        worker = threading.Thread(target=long_request)
        worker.start()
        deadline = time.time() + 60
        while metric(base, "footpoint_http_requests_in_flight") < 1 and time.time() < deadline:
            time.sleep(0.01)
        check(metric(base, "footpoint_http_requests_in_flight") >= 1, "the long stream is in flight")
        started = time.time()
        result = footpoint.Client(base, max_retries=200).project(geometry_id, points[:3], binary=False)
        waited = time.time() - started
        worker.join()
        text = urllib.request.urlopen(base + "/metrics").read().decode()
        refused = sum(float(line.rsplit(" ", 1)[1]) for line in text.splitlines()
                      if line.startswith("footpoint_http_requests_total") and 'status="503"' in line)
        check(refused >= 1 and len(result) == 3 and outcome.get("n") == 60000,
              "503 overloaded retried after Retry-After (%d refused, %.1f s waited)" % (refused, waited))
    return 0


if __name__ == "__main__":
    sys.exit(main())
