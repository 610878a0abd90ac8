#!/usr/bin/env python3
"""Single points while a large batch runs: the latency a small request sees behind a batch.

    bench/fair_bench.py [--runs N] [--points N] [--half-width W] SERVER [SERVER...]

SERVER is a footpoint-server binary; with several (e.g. a build of main and one of a branch) the
runs are interleaved (run 1 of each, then run 2 of each, ...) so that each sees the same machine
load, and the medians over the runs are compared. Each run starts the binary on 127.0.0.1 with its
default settings (numerical threads = the CPUs), posts the [GSA] Example 1 surface
(x = u+v, y = sin(u)+2cos(v), z = sin(u+v) on [-W,W]^2), then:
  1. idle: 200 single-point requests, one after the other on one keep-alive connection;
  2. alone: the batch of --points random points (JSON) posted with nothing else running: its wall
     time is the batch throughput the fair scheduling must keep;
  3. under load: one client posts the batch again, and while it is being
     answered single-point requests are sent open-loop, one due every --period seconds, over
     --clients keep-alive connections (a single's latency counts from when it was due, so a client
     held up by a slow answer does not hide the wait); the batch's wall time and the single
     points' latencies are recorded.
With --keys, fair shares between API keys instead: the server gets two keys; key "flood" has
--flood clients posting --flood-points-point batches without pause, and a --light-points batch is
timed alone, then beside the flood sent with key "light" (its own tenant: with fair queues per key
it gets about half the workers), then with key "flood" (one more job among the flood's: about
1/(flood + 1) of them).
The default half-width 25 is the reference cases' domain, where the surface covers itself ~16
times and the batch's time is mostly projection (at 3 it is mostly reading and writing JSON).
Printed per binary: the medians over the runs of the idle p50, the single points' p50 and p90
under the batch, and the batch's seconds alone (its throughput: points / seconds) and under load.
Only 127.0.0.1 is contacted; each run is bounded by timeouts.
"""
import argparse
import http.client
import json
import os
import random
import socket
import statistics
import subprocess
import sys
import threading
import time


def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def post(conn, path, body, key=None):
    headers = {"Content-Type": "application/json"}
    if key:
        headers["Authorization"] = "Bearer " + key
    conn.request("POST", path, body=body, headers=headers)
    r = conn.getresponse()
    data = r.read()
    if r.status != 200 and r.status != 201:
        raise RuntimeError(f"{path}: {r.status} {data[:200]!r}")
    return data


def start(server, port, *flags):
    proc = subprocess.Popen([server, "--host", "127.0.0.1", "--port", str(port), "--log-level", "warn", *flags],
                            stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    for _ in range(200):
        try:
            c = http.client.HTTPConnection("127.0.0.1", port, timeout=1)
            c.request("GET", "/healthz")
            if c.getresponse().status == 200:
                c.close()
                return proc
        except OSError:
            time.sleep(0.05)
    proc.kill()
    raise RuntimeError(f"{server} did not start")


def random_point(rng):
    return [rng.random() * 40 - 20, rng.random() * 6 - 3, rng.random() * 3 - 1.5]


def one_run(server, args, batch_body):
    port = free_port()
    proc = start(server, port)
    try:
        w = args.half_width
        surface = {"type": "parametric_surface", "x": "u+v", "y": "sin(u)+2*cos(v)", "z": "sin(u+v)",
                   "domain": {"u": [-w, w], "v": [-w, w]}}
        c = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
        gid = json.loads(post(c, "/v1/geometries", json.dumps(surface)))["geometry_id"]
        path = f"/v1/geometries/{gid}/project"
        rng = random.Random(7)
        singles = [json.dumps({"point": random_point(rng)}).encode() for _ in range(4096)]

        idle = []
        for i in range(200):
            t = time.perf_counter()
            post(c, path, singles[i])
            idle.append(time.perf_counter() - t)

        t = time.perf_counter()
        post(c, path, batch_body)
        alone = time.perf_counter() - t

        done = threading.Event()
        batch_time = []

        def batch():
            b = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
            t = time.perf_counter()
            post(b, path, batch_body)
            batch_time.append(time.perf_counter() - t)
            done.set()
            b.close()

        # Open loop: single k is due at start + head_start + k * period, sent by client k % K on
        # its own connection; its latency is counted from when it was due (a client still busy
        # with its previous single sends late, and the lateness counts).
        loaded = []
        lock = threading.Lock()
        start_at = time.perf_counter() + args.head_start

        def singles_client(k):
            s = http.client.HTTPConnection("127.0.0.1", port, timeout=120)
            j = k
            while True:
                due = start_at + j * args.period
                now = time.perf_counter()
                if due > now:
                    time.sleep(due - now)
                if done.is_set():
                    break
                post(s, path, singles[j % len(singles)])
                if not done.is_set():
                    with lock:
                        loaded.append(time.perf_counter() - due)
                j += args.clients
            s.close()

        th = threading.Thread(target=batch)
        th.start()
        clients = [threading.Thread(target=singles_client, args=(k,)) for k in range(args.clients)]
        for t in clients:
            t.start()
        th.join()
        for t in clients:
            t.join()
        c.close()
        return {"idle_p50": statistics.median(idle) * 1e3,
                "p50": statistics.median(loaded) * 1e3 if loaded else float("nan"),
                "p90": statistics.quantiles(loaded, n=10)[-1] * 1e3 if len(loaded) > 1 else float("nan"),
                "singles": len(loaded),
                "batch_s": batch_time[0],
                "alone_s": alone}
    finally:
        proc.terminate()
        try:
            proc.wait(timeout=30)
        except subprocess.TimeoutExpired:
            proc.kill()


def keys_run(server, args):
    """--keys: one key floods the server with batches; how long does another key's batch take?"""
    import hashlib
    import tempfile
    secrets = {"flood": "flood-secret-0123456789", "light": "light-secret-0123456789"}
    with tempfile.NamedTemporaryFile("w", suffix=".keys", delete=False) as f:
        for name, secret in secrets.items():
            f.write("%s project,write %s\n" % (name, hashlib.sha256(secret.encode()).hexdigest()))
        keys_file = f.name
    port = free_port()
    proc = start(server, port, "--api-keys", keys_file, "--max-inflight-points", "10000000")
    try:
        w = args.half_width
        surface = {"type": "parametric_surface", "x": "u+v", "y": "sin(u)+2*cos(v)", "z": "sin(u+v)",
                   "domain": {"u": [-w, w], "v": [-w, w]}}
        c = http.client.HTTPConnection("127.0.0.1", port, timeout=600)
        gid = json.loads(post(c, "/v1/geometries", json.dumps(surface), secrets["flood"]))["geometry_id"]
        path = f"/v1/geometries/{gid}/project"
        rng = random.Random(3)
        light_body = json.dumps({"points": [random_point(rng) for _ in range(args.light_points)]}).encode()
        flood_body = json.dumps({"points": [random_point(rng) for _ in range(args.flood_points)]}).encode()

        def light(key):
            t = time.perf_counter()
            post(c, path, light_body, secrets[key])
            return time.perf_counter() - t

        alone = light("light")
        stop = threading.Event()

        def flood_client():
            f = http.client.HTTPConnection("127.0.0.1", port, timeout=600)
            while not stop.is_set():
                post(f, path, flood_body, secrets["flood"])
            f.close()

        flood = [threading.Thread(target=flood_client) for _ in range(args.flood)]
        for t in flood:
            t.start()
        time.sleep(args.head_start * 3)  # every flood batch read and queued
        own, shared = light("light"), light("flood")
        stop.set()
        for t in flood:
            t.join()
        return {"alone": alone, "own": own, "shared": shared}
    finally:
        proc.terminate()
        proc.wait(timeout=120)
        os.unlink(keys_file)


def main_keys(args):
    results = {s: [] for s in args.servers}
    for r in range(args.runs):
        for s in args.servers:
            res = keys_run(s, args)
            results[s].append(res)
            print(f"run {r + 1} {s}: light batch alone {res['alone']:.2f} s, beside the flood with its own key "
                  f"{res['own']:.2f} s, with the flood's key {res['shared']:.2f} s", file=sys.stderr, flush=True)
    print(f"{args.light_points}-point batch beside {args.flood} clients posting {args.flood_points}-point batches "
          f"without pause, half-width {args.half_width:g}, medians of {args.runs} interleaved runs:")
    for s, rs in results.items():
        med = {k: statistics.median(r[k] for r in rs) for k in rs[0]}
        print(f"  {s}: alone {med['alone']:.2f} s | own key {med['own']:.2f} s ({med['own'] / med['alone']:.1f}x) | "
              f"the flood's key {med['shared']:.2f} s ({med['shared'] / med['alone']:.1f}x)")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("servers", nargs="+")
    p.add_argument("--runs", type=int, default=5)
    p.add_argument("--points", type=int, default=100000)
    p.add_argument("--half-width", type=float, default=25.0)
    p.add_argument("--head-start", type=float, default=0.3, help="seconds between the batch and the singles")
    p.add_argument("--period", type=float, default=0.1, help="seconds between two singles' due times")
    p.add_argument("--clients", type=int, default=4, help="connections the singles are sent on")
    p.add_argument("--keys", action="store_true", help="the API-key flood comparison instead (see above)")
    p.add_argument("--flood", type=int, default=4, help="--keys: clients posting batches without pause")
    p.add_argument("--flood-points", type=int, default=20000, help="--keys: points of each flood batch")
    p.add_argument("--light-points", type=int, default=2000, help="--keys: points of the other key's batch")
    args = p.parse_args()
    if args.keys:
        return main_keys(args)
    rng = random.Random(11)
    batch_body = json.dumps({"points": [random_point(rng) for _ in range(args.points)]}).encode()
    results = {s: [] for s in args.servers}
    for r in range(args.runs):
        for s in args.servers:
            res = one_run(s, args, batch_body)
            results[s].append(res)
            print(f"run {r + 1} {s}: idle p50 {res['idle_p50']:.2f} ms, under batch p50 {res['p50']:.2f} ms "
                  f"p90 {res['p90']:.2f} ms ({res['singles']} singles), batch alone {res['alone_s']:.2f} s, "
                  f"under load {res['batch_s']:.2f} s",
                  file=sys.stderr, flush=True)
    print(f"{args.points}-point batch, half-width {args.half_width:g}, medians of {args.runs} interleaved runs:")
    for s, rs in results.items():
        med = {k: statistics.median(r[k] for r in rs) for k in rs[0]}
        print(f"  {s}: idle p50 {med['idle_p50']:.2f} ms | under batch p50 {med['p50']:.2f} ms, "
              f"p90 {med['p90']:.2f} ms | batch alone {med['alone_s']:.3f} s "
              f"({args.points / med['alone_s']:.0f} points/s), with the singles {med['batch_s']:.3f} s")


if __name__ == "__main__":
    main()
