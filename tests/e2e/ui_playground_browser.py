#!/usr/bin/env python3
"""The browser pages in a real browser: Debian's chromium, headless, driven through the DevTools
protocol (python3-websocket), against the built footpoint-server on a loopback port.

  - GET / loads with no console error, draws the first preset, and its security policy holds
    (Content-Security-Policy default-src 'self', no request to another origin);
  - a geometry set in the form, a point projected: the distance the page shows equals the API's
    answer to the same request, byte for byte as a double;
  - a click on the canvas adds a point and projects it;
  - canvas screenshots are not blank, and differ between two geometries;
  - a bad formula: the error is shown under its field with the API's position marked;
  - a point cloud of 100,000 points off a torus, generated here as PLY binary and XYZ files (and
    smaller CSV and PLY ascii ones) and loaded through the file input (the PLY ascii one dropped
    on the view): the count, mean, RMS, min
    and max shown and the legend's range equal the closed-form signed distances', the histogram's
    bins add up, the canvas shows the cloud, the exported CSV (downloaded by the browser) holds
    every point with its closed-form signed distance; bad files show their line;
  - the mesh endpoint from the page (JSON, OBJ);
  - /docs (Swagger UI) shows every operation of openapi.yaml (as PyYAML reads it) with its summary,
    under the same policy, and its "Try it out" on GET /v1/methods shows the API's answer;
  - page weight and time to first render are printed.

Screenshots go to --out (the build folder). Exit 77 (ctest: skipped) when chromium or
python3-websocket is missing.

  tests/e2e/ui_playground_browser.py --server build/footpoint-server --source . --out build/screenshots
"""
import argparse
import base64
import json
import math
import os
import queue
import re
import shutil
import struct
import subprocess
import sys
import tempfile
import threading
import time
import urllib.request
import zlib

SKIP = 77
TIMEOUT = 40.0  # seconds for any one wait


def skip(message):
    print("SKIP: " + message)
    sys.exit(SKIP)


try:
    import websocket  # python3-websocket
except ImportError:
    skip("python3-websocket is not installed (apt-get install python3-websocket; scripts/install-deps.sh installs it)")
import yaml  # python3-yaml, a test dependency of the openapi checks


class Failure(Exception):
    pass


def check(condition, message):
    if not condition:
        raise Failure(message)
    print("ok: " + message)


# ---- PNG (what Page.captureScreenshot returns): 8-bit RGB/RGBA, not interlaced ------------------

def decode_png(data):
    if data[:8] != b"\x89PNG\r\n\x1a\n":
        raise Failure("screenshot is not a PNG")
    at, idat, width = 8, b"", 0
    while at < len(data):
        length, kind = struct.unpack(">I4s", data[at:at + 8])
        chunk = data[at + 8:at + 8 + length]
        if kind == b"IHDR":
            width, height, depth, color, _, _, interlace = struct.unpack(">IIBBBBB", chunk)
            if depth != 8 or color not in (2, 6) or interlace:
                raise Failure(f"unexpected PNG format depth={depth} color={color} interlace={interlace}")
            channels = 3 if color == 2 else 4
        elif kind == b"IDAT":
            idat += chunk
        at += 12 + length
    raw = zlib.decompress(idat)
    stride = width * channels
    rows, previous, pos = [], bytearray(stride), 0
    for _ in range(height):
        kind, line = raw[pos], bytearray(raw[pos + 1:pos + 1 + stride])
        pos += 1 + stride
        for i in range(stride):
            a = line[i - channels] if i >= channels else 0
            b = previous[i]
            c = previous[i - channels] if i >= channels else 0
            if kind == 1:
                line[i] = (line[i] + a) & 255
            elif kind == 2:
                line[i] = (line[i] + b) & 255
            elif kind == 3:
                line[i] = (line[i] + (a + b) // 2) & 255
            elif kind == 4:
                p = a + b - c
                pa, pb, pc = abs(p - a), abs(p - b), abs(p - c)
                line[i] = (line[i] + (a if pa <= pb and pa <= pc else b if pb <= pc else c)) & 255
        rows.append(bytes(line))
        previous = line
    pixels = [tuple(r[x * channels:x * channels + 3]) for r in rows for x in range(width)]
    return width, height, pixels


def colourful_fraction(pixels):
    """Share of pixels that are not grey (the background and grid are greys; the geometry is not)."""
    return sum(1 for (r, g, b) in pixels if max(r, g, b) - min(r, g, b) > 40) / len(pixels)


def difference_fraction(a, b):
    if len(a) != len(b):
        return 1.0
    return sum(1 for p, q in zip(a, b) if sum(abs(x - y) for x, y in zip(p, q)) > 60) / len(a)


# ---- the DevTools protocol --------------------------------------------------------------------

class Page:
    def __init__(self, ws_url):
        self.ws = websocket.create_connection(ws_url, timeout=TIMEOUT, suppress_origin=True)
        self.next_id = 0
        self.events = []

    def call(self, method, **params):
        self.next_id += 1
        mine = self.next_id
        self.ws.send(json.dumps({"id": mine, "method": method, "params": params}))
        deadline = time.time() + TIMEOUT
        while time.time() < deadline:
            message = json.loads(self.ws.recv())
            if message.get("id") == mine:
                if "error" in message:
                    raise Failure(f"{method}: {message['error']}")
                return message.get("result", {})
            if "method" in message:
                self.events.append(message)
        raise Failure(f"{method}: no answer in {TIMEOUT} s")

    def evaluate(self, expression, await_promise=False):
        r = self.call("Runtime.evaluate", expression=expression, returnByValue=True, awaitPromise=await_promise)
        if "exceptionDetails" in r:
            raise Failure(f"evaluating {expression[:80]!r}: {r['exceptionDetails'].get('exception', {}).get('description', r['exceptionDetails'])}")
        return r["result"].get("value")

    def wait_for(self, expression, what, timeout=TIMEOUT):
        deadline = time.time() + timeout
        guarded = f"(() => {{ try {{ return ({expression}); }} catch (e) {{ return null; }} }})()"  # during navigation
        while time.time() < deadline:
            value = self.evaluate(guarded)
            if value:
                return value
            time.sleep(0.05)
        raise Failure(f"timed out after {timeout} s waiting for {what} ({expression})")

    def idle(self):
        """Waits until no request of the page is running (data-state is not busy) and a frame is drawn."""
        self.wait_for("document.body.dataset.state === 'ready' || document.body.dataset.state === 'error'", "the page to settle")
        self.evaluate("new Promise(r => requestAnimationFrame(() => requestAnimationFrame(r)))", await_promise=True)

    def screenshot(self, selector, path):
        rect = self.evaluate(f"(() => {{ const r = document.querySelector({json.dumps(selector)}).getBoundingClientRect();"
                             " return {x: r.x, y: r.y, width: r.width, height: r.height}; })()")
        shot = self.call("Page.captureScreenshot", format="png", clip=dict(rect, scale=1), captureBeyondViewport=False)
        data = base64.b64decode(shot["data"])
        with open(path, "wb") as f:
            f.write(data)
        return decode_png(data)

    def click(self, x, y):
        for kind in ("mousePressed", "mouseReleased"):
            self.call("Input.dispatchMouseEvent", type=kind, x=x, y=y, button="left", clickCount=1)

    def set_value(self, selector, value):
        self.evaluate(f"(() => {{ const e = document.querySelector({json.dumps(selector)}); e.value = {json.dumps(value)};"
                      " e.dispatchEvent(new Event('input', {bubbles: true})); })()")

    def press(self, selector):
        self.evaluate(f"document.querySelector({json.dumps(selector)}).click()")


# ---- the point cloud ------------------------------------------------------------------------------

TORUS_R, TORUS_r = 2.0, 0.6  # the torus the test sets in the form


def torus_scan(n, seed=37):
    """n points off the torus (R, r) along its outward normal s_u x s_v = (cos u cos v, sin u cos v,
    sin v), offsets Gaussian (mean 0.01, sigma 0.02, within +-0.25 so that the foot is the nearest
    point of the tube's circle), and their signed distances in closed form from the coordinates:
    sqrt((sqrt(x^2 + y^2) - R)^2 + z^2) - r."""
    import math
    import random
    rng = random.Random(seed)
    points, signed = [], []
    for _ in range(n):
        u, v = rng.uniform(0, 2 * math.pi), rng.uniform(0, 2 * math.pi)
        d = max(-0.25, min(0.25, rng.gauss(0.01, 0.02)))
        normal = (math.cos(u) * math.cos(v), math.sin(u) * math.cos(v), math.sin(v))
        rho = TORUS_R + TORUS_r * math.cos(v)
        p = (rho * math.cos(u) + d * normal[0], rho * math.sin(u) + d * normal[1], TORUS_r * math.sin(v) + d * normal[2])
        points.append(p)
        signed.append(math.hypot(math.hypot(p[0], p[1]) - TORUS_R, p[2]) - TORUS_r)
    return points, signed


def write_ply_binary(path, points):
    """binary_little_endian: x, y, z as double and an intensity float between them and after."""
    header = ("ply\nformat binary_little_endian 1.0\ncomment footpoint test scan\nelement vertex %d\n"
              "property double x\nproperty float intensity\nproperty double y\nproperty double z\n"
              "property uchar quality\nelement face 0\nproperty list uchar int vertex_indices\nend_header\n" % len(points))
    with open(path, "wb") as f:
        f.write(header.encode())
        f.write(b"".join(struct.pack("<dfddB", x, 0.5, y, z, 7) for x, y, z in points))


def write_text(path, points, kind):
    with open(path, "w") as f:
        if kind == "xyz":
            f.write("# footpoint test scan: x y z intensity\n")
            f.writelines("%r %r %r 0.5\n" % p for p in points)
        elif kind == "csv":  # a header naming the columns in another order
            f.write("id,z,x,y\n")
            f.writelines("%d,%r,%r,%r\n" % (i, z, x, y) for i, (x, y, z) in enumerate(points))
        else:  # PLY ascii with a face after the vertices
            f.write("ply\nformat ascii 1.0\nelement vertex %d\nproperty float nx\nproperty double x\nproperty double y\n"
                    "property double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n" % len(points))
            f.writelines("0 %r %r %r\n" % p for p in points)
            f.write("3 0 1 2\n")


def load_cloud(page, path, timeout=180.0, drop=False):
    """Sets the file input to `path` (DOM.setFileInputFiles fires its change event), or with drop
    drags the file onto the view and drops it there (Input.dispatchDragEvent), and waits until the
    page has read and projected it, or shown an error; returns the seconds it took."""
    page.evaluate("delete document.body.dataset.cloudCount; document.getElementById('error-cloud').hidden = true")
    started = time.time()
    if drop:
        box = page.evaluate("(() => { const r = document.getElementById('canvas').getBoundingClientRect();"
                            " return [r.x + r.width / 2, r.y + r.height / 2]; })()")
        data = {"items": [], "files": [os.path.abspath(path)], "dragOperationsMask": 1}
        for kind in ("dragEnter", "dragOver", "drop"):
            page.call("Input.dispatchDragEvent", type=kind, x=box[0], y=box[1], data=data)
    else:
        document = page.call("DOM.getDocument", depth=1)
        node = page.call("DOM.querySelector", nodeId=document["root"]["nodeId"], selector="#cloud-file")["nodeId"]
        page.call("DOM.setFileInputFiles", files=[os.path.abspath(path)], nodeId=node)
    page.wait_for("(document.body.dataset.cloudCount || !document.getElementById('error-cloud').hidden) && "
                  "document.body.dataset.state === 'ready'", "the point cloud " + os.path.basename(path), timeout)
    return time.time() - started


def shown_stats(page):
    return page.evaluate("Object.fromEntries([...document.querySelectorAll('#cloud-stats dd')]"
                         ".map(d => [d.dataset.field, Number(d.dataset.value)]))")


def relative(a, b):
    return abs(a - b) / max(abs(b), 1e-300)


def check_point_cloud(page, out, pixels_before):
    import math
    n = 100000
    points, signed = torus_scan(n)
    ply = os.path.join(out, "scan_torus_binary.ply")
    xyz = os.path.join(out, "scan_torus.xyz")
    write_ply_binary(ply, points)
    write_text(xyz, points, "xyz")
    expected = {"count": n, "mean": math.fsum(signed) / n, "rms": math.sqrt(math.fsum(s * s for s in signed) / n),
                "min": min(signed), "max": max(signed)}

    seconds = load_cloud(page, ply)
    error = page.evaluate("document.getElementById('error-cloud').hidden ? '' : document.getElementById('error-cloud').textContent")
    check(not error, "the PLY binary scan loaded" + (": " + error if error else ""))
    page.idle()
    timings = page.evaluate("({...document.body.dataset})")
    print(f"figure: 100,000 points (PLY binary) loaded and projected in {seconds:.2f} s in headless chromium "
          f"(read {timings['cloudReadMs']} ms, projected over the stream {timings['cloudProjectMs']} ms, "
          f"in all {timings['cloudTotalMs']} ms by the page's clock)")
    stats = shown_stats(page)
    check(stats["count"] == n and stats["no_answer"] == 0, f"the count shown is {stats['count']:.0f}, every point answered")
    for name in ("mean", "rms", "min", "max"):
        check(relative(stats[name], expected[name]) <= 1e-9,
              f"the {name} shown ({stats[name]!r}) is the closed form's ({expected[name]!r}) to 1e-9")
    counts = json.loads(page.evaluate("document.getElementById('cloud-histogram').dataset.counts"))
    edges = json.loads(page.evaluate("document.getElementById('cloud-histogram').dataset.edges"))
    width = (edges[-1] - edges[0]) / len(counts)
    reference = [0] * len(counts)
    for s in signed:
        reference[min(len(counts) - 1, int((s - edges[0]) / width))] += 1
    near_edge = sum(1 for s in signed for e in edges[1:-1] if abs(s - e) <= 1e-9 * width)
    moved = sum(abs(a - b) for a, b in zip(counts, reference))
    check(sum(counts) == n and moved <= 2 * near_edge,
          f"the histogram's {len(counts)} bins add up to {sum(counts)} and equal the closed form's binning "
          f"({moved} counts differ, {near_edge} values within 1e-9 of a bin's width of an edge)")
    scale = max(abs(expected["min"]), abs(expected["max"]))
    legend = page.evaluate("[Number(document.getElementById('cloud-legend-min').dataset.value),"
                           " Number(document.getElementById('cloud-legend-max').dataset.value),"
                           " document.getElementById('cloud-legend').hidden]")
    check(not legend[2] and relative(legend[0], -scale) <= 1e-9 and relative(legend[1], scale) <= 1e-9,
          f"the legend spans +-max|deviation| = +-{scale:.6g} (symmetric about 0)")
    _, _, pixels_cloud = page.screenshot("#canvas", os.path.join(out, "playground_cloud.png"))
    check(difference_fraction(pixels_before, pixels_cloud) > 0.05,
          f"the canvas shows the coloured cloud ({difference_fraction(pixels_before, pixels_cloud):.0%} of the pixels changed)")
    page.evaluate("document.getElementById('cloud-histogram').scrollIntoView()")
    _, _, pixels_histogram = page.screenshot("#cloud-histogram", os.path.join(out, "playground_cloud_histogram.png"))
    check(colourful_fraction(pixels_histogram) > 0.05,
          f"the histogram is drawn ({colourful_fraction(pixels_histogram):.0%} coloured pixels)")
    page.screenshot("body", os.path.join(out, "playground_cloud_page.png"))

    # the export: the page's download, saved by the browser into the build folder
    downloads = os.path.join(out, "downloads")
    shutil.rmtree(downloads, ignore_errors=True)
    os.makedirs(downloads)
    page.call("Browser.setDownloadBehavior", behavior="allow", downloadPath=os.path.abspath(downloads))
    page.evaluate("document.getElementById('cloud-export').click()")
    target = os.path.join(downloads, "deviations.csv")
    deadline = time.time() + TIMEOUT
    while not os.path.exists(target) and time.time() < deadline:
        time.sleep(0.1)
    check(os.path.exists(target), "the export downloads deviations.csv")
    with open(target) as f:
        rows = f.read().splitlines()
    header, rows = rows[0].split(","), [r.split(",") for r in rows[1:]]
    column = {name: k for k, name in enumerate(header)}
    check(header == ["x", "y", "z", "foot_x", "foot_y", "foot_z", "distance", "signed_distance"] and len(rows) == n,
          f"the CSV has the columns x, y, z, foot x, y, z, distance, signed_distance and {len(rows)} rows")
    worst = max(abs(float(r[column["signed_distance"]]) - s) for r, s in zip(rows, signed))
    same_points = all(tuple(float(r[k]) for k in range(3)) == p for r, p in zip(rows, points))
    consistent = all(abs(float(r[column["distance"]]) - abs(float(r[column["signed_distance"]]))) <= 1e-15 for r in rows)
    check(worst <= 1e-12 and same_points and consistent,
          f"its rows are the file's points in order, their signed distances the closed form's (largest difference {worst:.1e})")

    # the same scan as XYZ, and smaller ones as CSV (a header, other columns) and PLY ascii
    seconds = load_cloud(page, xyz)
    page.idle()
    again = shown_stats(page)
    check(all(again[k] == stats[k] for k in ("count", "mean", "rms", "min", "max")),
          f"the XYZ file gives the same statistics ({seconds:.2f} s)")
    few = points[:2000]
    for kind in ("csv", "ply"):
        path = os.path.join(out, "scan_torus_small." + kind)
        write_text(path, few, kind if kind == "csv" else "ply_ascii")
        load_cloud(page, path, drop=kind == "ply")
        page.idle()
        small = shown_stats(page)
        check(small.get("count") == 2000 and relative(small["mean"], math.fsum(signed[:2000]) / 2000) <= 1e-9,
              f"{kind.upper()}{' ascii, dropped on the view' if kind == 'ply' else ' with a header'}: "
              "2000 points, the closed form's mean")

    # bad files: the message names the line (or the byte) in the page
    bad = os.path.join(out, "scan_bad.xyz")
    with open(bad, "w") as f:
        f.write("0.1 0.2 0.3\n0.4 0.5 0.6\n0.7 abc 0.9\n")
    load_cloud(page, bad)
    message = page.evaluate("document.getElementById('error-cloud').hidden ? '' : document.getElementById('error-cloud').textContent")
    check("line 3" in message and "abc" in message, f"a bad XYZ file shows its line: {message}")
    page.screenshot("#cloud", os.path.join(out, "playground_cloud_error.png"))
    cut = os.path.join(out, "scan_cut.ply")
    with open(ply, "rb") as f, open(cut, "wb") as g:
        g.write(f.read()[:-1000])
    load_cloud(page, cut)
    message = page.evaluate("document.getElementById('error-cloud').textContent")
    check(f"ends after vertex {n - math.ceil(1000 / 29)} of {n}" in message, f"a cut PLY file shows where it ends: {message}")
    check(page.evaluate("document.getElementById('cloud-report').hidden"), "and no report of a cloud is left")


def start_server(binary):
    server = subprocess.Popen([binary, "--host", "127.0.0.1", "--port", "0", "--threads", "2"],
                              stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True)
    deadline = time.time() + TIMEOUT
    while time.time() < deadline:
        line = server.stdout.readline()
        if not line:
            break
        record = json.loads(line)
        if record.get("msg") == "listening":
            threading.Thread(target=lambda: [None for _ in server.stdout], daemon=True).start()  # drain the log
            return server, int(record["port"])
    server.kill()
    raise Failure("the server did not start")


def start_chromium(executable, profile):
    flags = ["--headless=new", "--no-sandbox", "--disable-gpu", "--use-angle=swiftshader", "--enable-unsafe-swiftshader",
             "--disable-background-networking", "--disable-component-update", "--disable-sync", "--no-first-run",
             "--disable-default-apps", "--disable-extensions", "--mute-audio", "--hide-scrollbars",
             f"--user-data-dir={profile}", "--remote-debugging-address=127.0.0.1", "--remote-debugging-port=0",
             "--window-size=1440,900", "about:blank"]
    browser = subprocess.Popen([executable] + flags, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    lines = queue.Queue()
    threading.Thread(target=lambda: [lines.put(l) for l in browser.stderr], daemon=True).start()
    deadline = time.time() + TIMEOUT
    while time.time() < deadline:
        try:
            line = lines.get(timeout=1)
        except queue.Empty:
            continue
        m = re.search(r"DevTools listening on (ws://[^\s]+)", line)
        if m:
            port = int(re.search(r":(\d+)/", m.group(1)).group(1))
            return browser, port
    browser.kill()
    raise Failure("chromium did not open its DevTools port")


def http(port, method, path, body=None):
    data = None if body is None else json.dumps(body).encode()
    request = urllib.request.Request(f"http://127.0.0.1:{port}{path}", data=data, method=method,
                                     headers={"Content-Type": "application/json"} if data else {})
    try:
        with urllib.request.urlopen(request, timeout=TIMEOUT) as r:
            return r.status, dict(r.headers), r.read()
    except urllib.error.HTTPError as e:
        return e.code, dict(e.headers), e.read()


def console_problems(events, allowed):
    """Errors the page reported: exceptions, console.error, and the browser's own log entries at
    level error (a failed request) other than `allowed` (a predicate on the entry's text)."""
    problems, warnings = [], []
    for e in events:
        method, params = e["method"], e.get("params", {})
        if method == "Runtime.exceptionThrown":
            problems.append("exception: " + json.dumps(params.get("exceptionDetails", {}))[:400])
        elif method == "Runtime.consoleAPICalled":
            text = " ".join(str(a.get("value", a.get("description", ""))) for a in params.get("args", []))
            if params.get("type") in ("error", "assert"):
                problems.append("console.error: " + text)
            elif params.get("type") == "warning":
                warnings.append(text)
        elif method == "Log.entryAdded":
            entry = params.get("entry", {})
            if entry.get("level") == "error" and not allowed(entry):
                problems.append(f"log ({entry.get('source')}): {entry.get('text')} {entry.get('url', '')}")
            elif entry.get("level") == "warning":
                warnings.append(entry.get("text", ""))
    return problems, warnings


def run(args):
    executable = shutil.which("chromium") or shutil.which("chromium-browser")
    if not executable:
        skip("chromium is not installed (apt-get install chromium; scripts/install-deps.sh installs it)")
    os.makedirs(args.out, exist_ok=True)
    server, port = start_server(args.server)
    profile = tempfile.mkdtemp(prefix="footpoint-chromium-")
    browser = None
    started = time.time()
    try:
        browser, devtools = start_chromium(executable, profile)
        with urllib.request.urlopen(f"http://127.0.0.1:{devtools}/json/list", timeout=TIMEOUT) as r:
            target = next(t for t in json.load(r) if t["type"] == "page")
        page = Page(target["webSocketDebuggerUrl"])
        for domain in ("Page", "Runtime", "Log", "Network"):
            page.call(domain + ".enable")
        origin = f"http://127.0.0.1:{port}"

        # ---- GET /: the first preset drawn ---------------------------------------------------
        page.call("Page.navigate", url=origin + "/")
        page.wait_for("document.body.dataset.firstRenderMs", "the first render")
        page.idle()
        first_render_ms = int(page.evaluate("document.body.dataset.firstRenderMs"))
        responses = {e["params"]["requestId"]: e["params"]["response"] for e in page.events
                     if e["method"] == "Network.responseReceived"}
        requests = [e["params"]["request"]["url"] for e in page.events if e["method"] == "Network.requestWillBeSent"]
        sizes = {e["params"]["requestId"]: e["params"]["encodedDataLength"] for e in page.events
                 if e["method"] == "Network.loadingFinished"}
        static = sum(sizes.get(i, 0) for i, r in responses.items() if "/v1/" not in r["url"])
        api_bytes = sum(sizes.get(i, 0) for i, r in responses.items() if "/v1/" in r["url"])
        check(all(u.startswith(origin + "/") for u in requests),
              f"every request goes to the page's own origin ({len(requests)} requests)")
        page_response = next(r for r in responses.values() if r["url"] == origin + "/")
        headers = {k.lower(): v for k, v in page_response["headers"].items()}
        check(headers.get("content-security-policy") == "default-src 'self'", "GET / sends Content-Security-Policy: default-src 'self'")
        mesh_requests = [r for r in responses.values() if re.search(r"/v1/geometries/[0-9a-f]{32}/mesh\?resolution=\d+$", r["url"])]
        check(mesh_requests and all(r["status"] == 200 for r in mesh_requests), "the page read the mesh from GET /v1/geometries/{id}/mesh")
        print(f"figure: page weight {static / 1024:.0f} KiB (HTML, scripts, styles, icon; three.js is "
              f"{os.path.getsize(args.three) / 1024:.0f} KiB of it), API answers {api_bytes / 1024:.0f} KiB "
              f"(the first preset's mesh and projection)")
        print(f"figure: time to first render {first_render_ms} ms after navigation (headless chromium, SwiftShader)")
        width, height, pixels_gsa = page.screenshot("#canvas", os.path.join(args.out, "playground_gsa_example1.png"))
        check(colourful_fraction(pixels_gsa) > 0.05, f"the canvas shows the first preset ({colourful_fraction(pixels_gsa):.0%} coloured pixels)")

        # ---- a geometry set in the form, a point projected: the page shows the API's distance --
        page.evaluate("document.getElementById('type').value = 'parametric_surface';"
                      "document.getElementById('type').dispatchEvent(new Event('change'))")
        torus = {"x": "(R+r*cos(v))*cos(u)", "y": "(R+r*cos(v))*sin(u)", "z": "r*sin(v)"}
        for field, formula in torus.items():
            page.set_value(f'#formulas input[data-field="{field}"]', formula)
        for name in ("u", "v"):
            page.set_value(f'#domain input[data-field="domain.{name}"][data-end="0"]', "0")
            page.set_value(f'#domain input[data-field="domain.{name}"][data-end="1"]', "2*pi")
        page.set_value("#constants", "R=2, r=0.6")
        page.set_value("#points", "3.2, 0.8, 1.2")
        page.set_value("#opt-initial", "")
        page.evaluate("document.getElementById('opt-trace').checked = false; document.getElementById('opt-all-minima').checked = false")
        page.evaluate("document.getElementById('method').value = 'auto'")
        page.press("#show")
        page.wait_for("document.querySelectorAll('#results tbody tr').length === 1 && document.body.dataset.state === 'ready'", "the torus's result")
        page.idle()
        geometry_id = page.evaluate("document.body.dataset.geometryId")
        shown = page.evaluate("document.querySelector('#results tbody td.distance').textContent")
        status, _, body = http(port, "POST", f"/v1/geometries/{geometry_id}/project", {"points": [[3.2, 0.8, 1.2]]})
        answer = json.loads(body)["results"][0]
        check(status == 200 and float(shown) == answer["distance"],
              f"the distance shown ({shown}) is the API's answer to the same request ({answer['distance']!r})")
        definition = {"type": "parametric_surface", **torus, "domain": {"u": [0, 6.283185307179586], "v": [0, 6.283185307179586]},
                      "constants": {"R": 2, "r": 0.6}}
        status, _, body = http(port, "POST", "/v1/geometries", definition)
        check(json.loads(body)["geometry_id"] == geometry_id, "the page posted the definition in the form (same id)")
        page.press("#copy-curl")
        curl = page.wait_for("document.getElementById('curl').textContent", "the curl command")
        check(f"/v1/geometries/{geometry_id}/project" in curl and "'Content-Type: application/json'" in curl,
              "copy as curl repeats the request the page made")
        _, _, pixels_torus = page.screenshot("#canvas", os.path.join(args.out, "playground_torus.png"))
        check(colourful_fraction(pixels_torus) > 0.05, f"the canvas shows the torus ({colourful_fraction(pixels_torus):.0%} coloured pixels)")
        check(difference_fraction(pixels_gsa, pixels_torus) > 0.05,
              f"two geometries give different pictures ({difference_fraction(pixels_gsa, pixels_torus):.0%} of the pixels differ)")

        # ---- a click on the geometry adds a point and projects it ------------------------------
        box = page.evaluate("(() => { const r = document.getElementById('canvas').getBoundingClientRect(); return [r.x, r.y, r.width, r.height]; })()")
        page.click(box[0] + box[2] * 0.5, box[1] + box[3] * 0.5)
        page.wait_for("document.querySelectorAll('#results tbody tr').length === 2", "the clicked point's result")
        page.idle()
        status_text = page.evaluate("document.querySelectorAll('#results tbody tr')[1].querySelector('.status').textContent")
        check(status_text.startswith("converged"), f"a click on the canvas added a point, projected: {status_text}")

        # ---- the mesh endpoints from the page ---------------------------------------------------
        obj = page.evaluate("fetch(document.getElementById('download-obj').href)"
                            ".then(r => r.text().then(t => r.status + ' ' + r.headers.get('Content-Type') + '\\n' + t))",
                            await_promise=True)
        head, _, text = obj.partition("\n")
        check(head == "200 model/obj" and text.startswith("# footpoint mesh of geometry " + geometry_id) and "\nf " in text,
              f"the page's OBJ link answers a Wavefront OBJ mesh ({head}: {text[:60]!r})")
        vertices = page.evaluate("fetch(document.getElementById('download-json').href).then(r => r.json()).then(m => m.vertices.length / 3)",
                                 await_promise=True)
        check(vertices > 1000, f"the page's JSON link answers the mesh ({vertices} vertices)")

        # ---- a point cloud: a noisy torus scan from PLY binary, XYZ, CSV and PLY ascii files ------
        check_point_cloud(page, args.out, pixels_torus)

        # ---- a bad formula: the error at its position ---------------------------------------
        bad = "sin(u)+2*cos(w)"
        page.set_value('#formulas input[data-field="y"]', bad)
        page.press("#show")
        page.wait_for("!document.querySelector('[data-error-for=\"y\"]').hidden", "the formula error")
        page.idle()
        status, _, body = http(port, "POST", "/v1/geometries", dict(definition, y=bad))
        error = json.loads(body)["error"]
        mark = page.evaluate("(() => { const m = document.querySelector('[data-error-for=\"y\"] mark'); return m && [m.dataset.position, m.textContent]; })()")
        message = page.evaluate("document.querySelector('[data-error-for=\"y\"] .message').textContent")
        check(status == 422 and mark == [str(error["position"]), bad[error["position"]]] and message == error["message"],
              f"the formula error is shown under y with character {error['position']} ('{bad[error['position']]}') marked: {message}")
        page.screenshot("#panel", os.path.join(args.out, "playground_formula_error.png"))

        def show_preset(match, what, picture):
            """Selects the preset whose name matches (a JavaScript test of its text), waits for its
            three results and returns the canvas' pixels (saved as `picture`)."""
            index = page.evaluate(f"[...document.getElementById('preset').options].findIndex(o => {match})")
            page.evaluate(f"document.getElementById('preset').value = '{index}';"
                          "document.getElementById('preset').dispatchEvent(new Event('change'))")
            # (the change event marks the page busy before it returns)
            page.wait_for("document.body.dataset.state === 'ready' && document.querySelectorAll('#results tbody tr').length === 3", what)
            page.idle()
            return page.screenshot("#canvas", os.path.join(args.out, picture))[2]

        # ---- a planar curve, from its preset -------------------------------------------------
        pixels_curve = show_preset("o.textContent.startsWith('Lemniscate')", "the lemniscate's results", "playground_lemniscate.png")
        check(difference_fraction(pixels_torus, pixels_curve) > 0.05, "the lemniscate's picture differs from the torus's")

        # ---- an implicit surface, from its preset (a mesh without parameter lines) --------------
        pixels_implicit = show_preset("o.textContent.startsWith('Torus as f')", "the implicit torus' results",
                                      "playground_implicit_surface.png")
        check(difference_fraction(pixels_curve, pixels_implicit) > 0.05, "the implicit torus' picture differs from the lemniscate's")

        # ---- a NURBS surface, from its preset: the net in the form, distances in closed form -------
        pixels_nurbs = show_preset("o.textContent.startsWith('Rational sphere')", "the rational sphere's results",
                                   "playground_nurbs_sphere.png")
        check(difference_fraction(pixels_implicit, pixels_nurbs) > 0.05, "the NURBS sphere's picture differs from the implicit torus'")
        shown = page.evaluate("[...document.querySelectorAll('#results tbody td.distance')].map(td => Number(td.textContent))")
        want = [abs(math.sqrt(1.2**2 + 0.9**2 + 0.7**2) - 1), abs(math.sqrt(0.01 + 0.04 + 0.09) - 1), 0.5]
        check(len(shown) == 3 and all(abs(a - b) <= 1e-6 * (1 + b) for a, b in zip(shown, want)),
              f"the NURBS sphere's distances are | |p| - 1 | ({shown} against {want})")
        page.set_value("#net", '{"degree": [1, 1], "knots": {"u": [0, 0, 1], "v": [0, 0, 1, 1]}, '
                               '"control_points": [[[0, 0, 0], [0, 1, 0]], [[1, 0, 0], [1, 1, 0]]]}')
        page.press("#show")
        page.wait_for("!document.querySelector('[data-error-for=\"net\"]').hidden", "the net's error")
        page.idle()
        message = page.evaluate("document.querySelector('[data-error-for=\"net\"] .message').textContent")
        check(message.startswith("knots.u "), f"a bad net's error is shown under the net: {message}")

        # ---- the README's picture (docs/playground.png): the torus preset, its minima ----------
        show_preset("o.textContent === 'Torus'", "the torus preset", "playground_torus_preset.png")
        page.screenshot("body", os.path.join(args.out, "playground.png"))

        # ---- /docs: Swagger UI on openapi.yaml, under the same policy, "Try it out" ----------------
        docs_from = len(page.events)
        page.call("Page.navigate", url=origin + "/docs")
        page.wait_for("document.body.dataset.state === 'ready' || document.body.dataset.state === 'error'", "the API reference")
        check(page.evaluate("document.body.dataset.state") == "ready", "/docs rendered openapi.yaml")
        with open(os.path.join(args.source, "openapi.yaml")) as f:
            spec = yaml.safe_load(f)
        shown = page.evaluate("[...document.querySelectorAll('.opblock')].map(o => [o.querySelector('.opblock-summary-method').textContent,"
                              " o.querySelector('.opblock-summary-path').dataset.path,"
                              " o.querySelector('.opblock-summary-description').textContent])")
        operations = sorted([m.upper(), p, op["summary"]] for p, item in spec["paths"].items()
                            for m, op in item.items() if m in ("get", "post", "delete"))
        check(sorted(shown) == operations, f"/docs shows every operation of openapi.yaml with its summary ({len(operations)})")
        check(page.evaluate("document.querySelector('.info .title').textContent").startswith(spec["info"]["title"]),
              "/docs shows openapi.yaml's title")
        # "Try it out" on GET /v1/methods: the request goes to this server, the answer is shown.
        page.evaluate("document.querySelector('#operations-projection-listMethods .opblock-summary-control').click()")
        page.wait_for("!!document.querySelector('#operations-projection-listMethods .try-out__btn')", "the Try it out button")
        page.press("#operations-projection-listMethods .try-out__btn")
        page.wait_for("!!document.querySelector('#operations-projection-listMethods .execute')", "the Execute button")
        page.press("#operations-projection-listMethods .execute")
        answer = "#operations-projection-listMethods .live-responses-table"
        body = page.wait_for(f"document.querySelector('{answer} .microlight')?.textContent", "the answer of Try it out")
        status = page.evaluate(f"document.querySelector('{answer} tr.response .response-col_status').textContent.trim()")
        want = http(port, "GET", "/v1/methods")[2]
        check(status == "200" and body is not None and json.loads(body) == json.loads(want),
              f"Try it out on GET /v1/methods shows the API's answer (status {status}, {len(body or '')} characters)")
        docs_events = page.events[docs_from:]
        docs_requests = [e["params"]["request"]["url"] for e in docs_events if e["method"] == "Network.requestWillBeSent"]
        check(docs_requests and all(u.startswith(origin + "/") for u in docs_requests),
              f"every request of /docs goes to the page's own origin ({len(docs_requests)} requests)")
        docs_response = next(e["params"]["response"] for e in docs_events
                             if e["method"] == "Network.responseReceived" and e["params"]["response"]["url"] == origin + "/docs")
        check({k.lower(): v for k, v in docs_response["headers"].items()}.get("content-security-policy") == "default-src 'self'",
              "GET /docs sends Content-Security-Policy: default-src 'self'")
        docs_weight = sum(e["params"]["encodedDataLength"] for e in docs_events if e["method"] == "Network.loadingFinished")
        print(f"figure: /docs weight {docs_weight / 1024:.0f} KiB (Swagger UI, openapi.yaml, one Try it out)")
        page.evaluate("document.querySelector('#operations-projection-listMethods').scrollIntoView()")
        page.screenshot("body", os.path.join(args.out, "docs.png"))  # the operation and its answer

        # ---- the console ---------------------------------------------------------------------
        # The one failed request the test asked for: the 422 of the bad formula.
        expected = lambda entry: entry.get("source") == "network" and "422" in entry.get("text", "") and entry.get("url", "").endswith("/v1/geometries")
        problems, warnings = console_problems(page.events, expected)
        for w in warnings:
            if "GPU stall due to ReadPixels" not in w:  # the screenshots read the canvas back
                print("console warning: " + w)
        check(not problems, "the console has no errors" + ("" if not problems else ": " + "; ".join(problems)))
        print(f"browser test took {time.time() - started:.1f} s")
        server.terminate()
        check(server.wait(timeout=30) == 0, "the server ended cleanly on SIGTERM")
    finally:
        if browser:
            browser.terminate()
            try:
                browser.wait(timeout=10)
            except subprocess.TimeoutExpired:
                browser.kill()
        if server.poll() is None:
            server.kill()
            server.wait()
        shutil.rmtree(profile, ignore_errors=True)


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--server", required=True)
    parser.add_argument("--source", required=True, help="the repository (openapi.yaml)")
    parser.add_argument("--three", required=True, help="three.min.js the server embeds (its size is a figure)")
    parser.add_argument("--out", required=True, help="where the screenshots go")
    args = parser.parse_args()
    try:
        run(args)
    except Failure as e:
        print("FAIL: " + str(e))
        sys.exit(1)


if __name__ == "__main__":
    main()
