"""A client of the footpoint service (standard library only; NumPy, when present, for the binary path).

    import footpoint
    result = footpoint.project({"type": "parametric_surface", "x": "u", "y": "v", "z": "u*v",
                                "domain": {"u": [-1, 1], "v": [-1, 1]}},
                               [[0.1, 0.2, 0.5], [0.3, -0.4, 0.1]],
                               server="http://127.0.0.1:8080", max_distance=2)
    result.column("signed_distance")   # one value per point, in order (None / NaN where null)

project() sends the points in batches (batch_size each) and has every batch's answer streamed:
with NumPy the points travel as little-endian float64 and the answers as fixed-size binary records
(Accept: application/octet-stream, columns as the X-Footpoint-Record header names them); without
it, as JSON with the answers as NDJSON (one result per line, then the batch's stats). A binary
body is sent from a writer thread while the answer is read (duplex=True, the default over plain
HTTP): the server then reads the body a window at a time as it answers and holds a few windows of
it, where a client that sends the whole body first costs it the unread part of the body. A 503 is
retried after its Retry-After; a 404 geometry_not_found re-posts the definition (when project()
was given one) and tries again; any other error raises FootpointError with the server's status,
code and message. docs/inspection.md describes the formats.
"""

import http.client
import json
import math
import socket
import threading
import time
import urllib.parse

try:
    import numpy
except ImportError:  # the JSON path needs nothing else
    numpy = None

__all__ = ["Client", "FootpointError", "Projection", "project"]

# Names of the numeric status and location codes of a binary record (openapi.yaml's lists).
STATUSES = ["converged", "max_iterations", "diverged", "non_finite", "degenerate", "outside_domain",
            "not_orthogonal", "beyond_max_distance", "deadline_exceeded"]
LOCATIONS = ["interior", "edge", "corner", "endpoint", "box_face", "singular_point", "pole", "kink", "unknown"]

# Options that travel in the JSON body's "options" (and as query parameters with binary points).
OPTION_NAMES = {"tolerance", "max_iterations", "initial", "all_minima", "max_minima", "trace", "max_distance",
                "certify", "histogram_bins", "tolerance_band"}


class FootpointError(Exception):
    """An error the server answered (status, code, message, field), or a stream that was cut."""

    def __init__(self, status, code, message, field=None):
        super().__init__("%s %s: %s" % (status, code, message))
        self.status = status
        self.code = code
        self.message = message
        self.field = field


class Projection:
    """The answers of one project() call, in the order of the points.

    results: the result objects (JSON path), else None; columns: name -> NumPy array (binary path:
    shape (n,) for one number a point, (n, k) for k), else None; stats: each batch's "stats"
    (JSON path; the binary answer carries none)."""

    def __init__(self):
        self.results = None
        self.columns = None
        self.stats = []

    def __len__(self):
        if self.results is not None:
            return len(self.results)
        return len(next(iter(self.columns.values()))) if self.columns else 0

    def column(self, name):
        """One member of every result: foot_point, parameters, distance, normal, signed_distance,
        status, location, ... (a list with None for null on the JSON path; an array with NaN on
        the binary one, status and location as names)."""
        if self.columns is not None:
            values = self.columns[name]
            if name in ("status", "location"):
                names = STATUSES if name == "status" else LOCATIONS
                return [names[int(v)] for v in values]
            return values
        out = []
        for r in self.results:
            if name in r:
                out.append(r[name])
            else:
                out.append(r.get("diagnostics", {}).get(name))
        return out


def _points_list(points):
    if numpy is not None and isinstance(points, numpy.ndarray):
        return points.tolist()
    return [list(p) for p in points]


class Client:
    """A connection to one footpoint server (kept alive across requests)."""

    def __init__(self, server="http://127.0.0.1:8080", timeout=300.0, max_retries=8, duplex=None):
        """duplex: send binary bodies from a writer thread while the answer is read (default: over
        http://; an https:// server reads a body whole before it answers, and one TLS connection
        is not written and read by two threads at once)."""
        url = urllib.parse.urlsplit(server)
        if url.scheme not in ("http", "https"):
            raise ValueError("server must be an http:// or https:// URL, got %r" % server)
        self._https = url.scheme == "https"
        self._host = url.hostname
        self._port = url.port or (443 if self._https else 80)
        self._prefix = url.path.rstrip("/")
        self._timeout = timeout
        self._max_retries = max_retries
        self._duplex = (not self._https) if duplex is None else bool(duplex)
        if self._duplex and self._https:
            raise ValueError("duplex sending needs http://: over TLS the server reads the body whole first")
        self._connection = None
        self._ids = {}  # definition (canonical JSON text) -> geometry id

    def close(self):
        if self._connection is not None:
            self._connection.close()
            self._connection = None

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    # -- HTTP -------------------------------------------------------------------------------------

    def _connect(self):
        if self._connection is None:
            cls = http.client.HTTPSConnection if self._https else http.client.HTTPConnection
            self._connection = cls(self._host, self._port, timeout=self._timeout)
        return self._connection

    def _send(self, method, path, body=None, headers=None, duplex=False):
        """Sends a request and returns the response with its headers read (the body not yet),
        retrying 503 after its Retry-After; raises FootpointError for any other status >= 400.
        duplex: the body is sent from a writer thread (_start_duplex), and the caller reads the
        response's body, then calls _finish_duplex(response)."""
        headers = dict(headers or {})
        for attempt in range(self._max_retries + 1):
            try:
                connection = self._connect()
                if duplex:
                    response = self._start_duplex(connection, method, path, body, headers)
                else:
                    connection.request(method, self._prefix + path, body=body, headers=headers)
                    response = connection.getresponse()
            except (ConnectionError, http.client.HTTPException):
                # a kept-alive connection the server closed: once more on a new one
                self.close()
                if attempt == self._max_retries:
                    raise
                continue
            if response.status < 400:
                return response
            text = response.read()
            if duplex:
                self._finish_duplex(response, answered=False)
            if response.getheader("Connection", "").lower() == "close":
                self.close()
            try:
                error = json.loads(text)["error"]
            except (ValueError, KeyError, TypeError):
                error = {"code": "http_error", "message": text.decode("utf-8", "replace")}
            if response.status == 503 and attempt < self._max_retries:
                wait = response.getheader("Retry-After")
                time.sleep(float(wait) if wait and wait.isdigit() else 1.0)
                continue
            raise FootpointError(response.status, error.get("code"), error.get("message"), error.get("field"))
        raise AssertionError("unreachable")

    def _start_duplex(self, connection, method, path, body, headers):
        """Sends the request's head, starts a thread writing `body` (1 MiB at a time) to the
        connection's socket, and reads the response's head meanwhile: the server answers while
        it reads, and TCP's flow control paces the writer to the server's reading."""
        connection.putrequest(method, self._prefix + path, skip_accept_encoding=True)
        for name, value in headers.items():
            connection.putheader(name, value)
        connection.putheader("Content-Length", str(len(body)))
        connection.endheaders()
        sock = connection.sock
        failure = []

        def write():
            view = memoryview(body)
            try:
                for at in range(0, len(view), 1 << 20):
                    sock.sendall(view[at:at + (1 << 20)])
            except OSError as e:  # the server answered early (an error) and closed
                failure.append(e)

        writer = threading.Thread(target=write, name="footpoint-body-writer", daemon=True)
        writer.start()
        try:
            response = connection.getresponse()
        except BaseException:
            self._stop_writer(sock, writer)
            raise
        response.footpoint_writer = (sock, writer, failure)
        return response

    def _stop_writer(self, sock, writer):
        # shutdown() wakes a sendall() blocked on a server that reads no more; the connection,
        # whose body is cut, is not reused
        try:
            sock.shutdown(socket.SHUT_RDWR)
        except OSError:
            pass
        writer.join()
        self.close()

    def _finish_duplex(self, response, answered=True):
        """After the answer was read: waits for the writer (it has sent the body when the whole
        answer came, the server reading every point before its last answer); an answer that
        ended before the body was sent, or a failed write, leaves the connection closed."""
        sock, writer, failure = response.footpoint_writer
        if answered:
            writer.join(self._timeout)
        if writer.is_alive() or failure:
            self._stop_writer(sock, writer)

    def _json(self, method, path, payload=None):
        body = None if payload is None else json.dumps(payload).encode()
        headers = {"Content-Type": "application/json"} if body is not None else {}
        response = self._send(method, path, body, headers)
        text = response.read()
        return json.loads(text) if text else None

    # -- geometries -------------------------------------------------------------------------------

    def create_geometry(self, definition):
        """Posts a definition; returns its geometry id."""
        answer = self._json("POST", "/v1/geometries", definition)
        self._ids[json.dumps(definition, sort_keys=True)] = answer["geometry_id"]
        return answer["geometry_id"]

    def delete_geometry(self, geometry_id):
        self._send("DELETE", "/v1/geometries/" + geometry_id).read()

    # -- projection -------------------------------------------------------------------------------

    def project(self, geometry_or_id, points, fields=None, method=None, batch_size=100000, binary=None,
                **options):
        """Projects `points` (a sequence of [x, y(, z)], or an (n, 2|3) NumPy array) onto a geometry
        given by its definition (a dict, posted once and again when the server no longer holds it)
        or its id. `fields` names the members of each result (default: all, or on the binary path
        foot_point, parameters, distance, normal, signed_distance and status); `options` are the
        request's options (max_distance=..., certify=..., histogram_bins=..., tolerance_band=...).
        binary=None chooses the binary path when NumPy is present."""
        unknown = set(options) - OPTION_NAMES
        if unknown:
            raise ValueError("unknown options: %s (known: %s)" % (", ".join(sorted(unknown)),
                                                                 ", ".join(sorted(OPTION_NAMES))))
        if binary is None:
            binary = numpy is not None
        if binary and numpy is None:
            raise ValueError("the binary path needs NumPy")
        definition = geometry_or_id if isinstance(geometry_or_id, dict) else None
        if definition is not None:
            key = json.dumps(definition, sort_keys=True)
            geometry_id = self._ids.get(key) or self.create_geometry(definition)
        else:
            geometry_id = geometry_or_id
        if binary:
            points = numpy.ascontiguousarray(points, dtype="<f8")
            if points.ndim != 2 or points.shape[1] not in (2, 3):
                raise ValueError("points must have shape (n, 2) or (n, 3), got %s" % (points.shape,))
        else:
            points = _points_list(points)
        out = Projection()
        pieces = []
        for begin in range(0, len(points), batch_size):
            batch = points[begin:begin + batch_size]
            for attempt in range(2):
                try:
                    if binary:
                        pieces.append(self._project_binary(geometry_id, batch, fields, method, options))
                    else:
                        pieces.append(self._project_ndjson(geometry_id, batch, fields, method, options, out))
                    break
                except FootpointError as e:
                    if e.code != "geometry_not_found" or definition is None or attempt == 1:
                        raise
                    geometry_id = self.create_geometry(definition)
        if binary:
            out.columns = {}
            if pieces:
                for name in pieces[0]:
                    out.columns[name] = numpy.concatenate([p[name] for p in pieces])
        else:
            out.results = [r for piece in pieces for r in piece]
        return out

    def _project_ndjson(self, geometry_id, points, fields, method, options, out):
        payload = {"points": points}
        if fields:
            payload["fields"] = list(fields)
        if method:
            payload["method"] = method
        if options:
            payload["options"] = options
        response = self._send("POST", "/v1/geometries/%s/project" % geometry_id, json.dumps(payload).encode(),
                              {"Content-Type": "application/json", "Accept": "application/x-ndjson"})
        results = []
        stats = None
        for line in response:
            record = json.loads(line)
            if "stats" in record and "geometry_id" in record:
                stats = record["stats"]
            else:
                results.append(record)
        if stats is None or len(results) != len(points):
            self.close()
            raise FootpointError(response.status, "stream_cut",
                                 "the answer ended after %d of %d results" % (len(results), len(points)))
        out.stats.append(stats)
        return results

    def _project_binary(self, geometry_id, points, fields, method, options):
        query = {}
        if fields:
            query["fields"] = ",".join(fields)
        if method:
            query["method"] = method
        for name, value in options.items():
            if isinstance(value, bool):
                value = "true" if value else "false"
            elif isinstance(value, (list, tuple)):
                value = ",".join(repr(float(v)) for v in value)
            query[name] = value
        path = "/v1/geometries/%s/project" % geometry_id
        if query:
            path += "?" + urllib.parse.urlencode(query)
        response = self._send("POST", path, points.tobytes(),
                              {"Content-Type": "application/octet-stream", "Accept": "application/octet-stream"},
                              duplex=self._duplex)
        layout = [(name, int(count)) for name, count in
                  (column.split(":") for column in response.getheader("X-Footpoint-Record").split(","))]
        width = sum(count for _, count in layout)
        try:
            body = response.read()
        finally:
            if self._duplex:
                self._finish_duplex(response)
        if len(body) != len(points) * width * 8:
            self.close()
            raise FootpointError(response.status, "stream_cut",
                                 "the answer ended after %d of %d records" % (len(body) // (width * 8), len(points)))
        table = numpy.frombuffer(body, dtype="<f8").reshape(len(points), width)
        columns, at = {}, 0
        for name, count in layout:
            columns[name] = table[:, at] if count == 1 else table[:, at:at + count]
            at += count
        return columns


def project(geometry_or_id, points, server="http://127.0.0.1:8080", **options):
    """Client(server).project(geometry_or_id, points, **options) on a connection of its own."""
    with Client(server) as client:
        return client.project(geometry_or_id, points, **options)


def deviation_summary(values, band=None):
    """count, min, max, mean, rms (and the share within band = (lo, hi)) of the finite values."""
    finite = [float(v) for v in values if v is not None and math.isfinite(float(v))]
    if not finite:
        return {"count": 0}
    n = len(finite)
    summary = {"count": n, "min": min(finite), "max": max(finite), "mean": math.fsum(finite) / n,
               "rms": math.sqrt(math.fsum(v * v for v in finite) / n)}
    if band is not None:
        summary["share_within"] = sum(1 for v in finite if band[0] <= v <= band[1]) / n
    return summary
