// A client of the footpoint service: an ES module without dependencies, for the browser (the
// playground imports it from /ui/footpoint-client.js) and for Node 18+ (whose global fetch and
// web streams it uses).
//
//   import {project, projectAll} from './footpoint-client.js';
//   for await (const result of project(definition, points, {server: origin,  // '' in a page
//                                                          fields: ['signed_distance'],
//                                                          onProgress: (done, total) => ...}))
//     ...;                                     // one result object a point, in their order
//   const {results, stats} = await projectAll(definition, points, {max_distance: 0.5});
//
// The points travel as little-endian float64 numbers (Content-Type: application/octet-stream, 3
// a point, 2 for planar curves), the options as query parameters, and the answer comes back as
// NDJSON (Accept: application/x-ndjson): one JSON result a line in the order of the points, then
// {"geometry_id", "stats"} (docs/inspection.md). The answer is read as it arrives, line by line,
// so that results and progress come while the server is still projecting. A definition is posted
// once (its id kept per definition text) and again when the server answers 404
// geometry_not_found; a 503 is retried after its Retry-After; any other error throws a
// FootpointError with the server's status, code, message and field.

// Options that travel as query parameters (openapi.yaml's parameters of the binary body).
const QUERY_OPTIONS = new Set(['method', 'fields', 'tolerance', 'max_iterations', 'initial', 'all_minima',
                               'max_minima', 'trace', 'max_distance', 'certify', 'histogram_bins', 'tolerance_band']);
// Options of the client itself.
const CLIENT_OPTIONS = new Set(['server', 'onProgress', 'onStats', 'dimension', 'maxRetries', 'signal', 'fetch']);

export class FootpointError extends Error {
  constructor(status, code, message, field) {
    super(`${status} ${code}: ${message}`);
    this.name = 'FootpointError';
    this.status = status;
    this.code = code;
    this.detail = message;  // the server's message alone (.message also carries status and code)
    this.field = field;
  }
}

const knownIds = new Map();  // JSON text of a definition -> its geometry id
const littleEndian = new Uint8Array(new Float64Array([1]).buffer)[7] === 0x3f;

// The points as the body of a binary request: little-endian float64, `dimension` numbers a point.
// `points` is an array of [x, y(, z)] arrays, or a Float64Array of the numbers one point after the
// other (then options.dimension, default 3, says how many a point).
function pointsBody(points, dimension) {
  let flat;
  if (points instanceof Float64Array) {
    const d = dimension || 3;
    if (points.length % d !== 0)
      throw new TypeError(`a Float64Array of ${points.length} numbers is no whole number of ${d}-D points`);
    flat = points;
  } else {
    if (!Array.isArray(points)) throw new TypeError('points: an array of [x, y(, z)] or a Float64Array');
    const d = dimension || (points.length ? points[0].length : 3);
    flat = new Float64Array(points.length * d);
    points.forEach((p, i) => {
      if (!Array.isArray(p) || p.length !== d) throw new TypeError(`points[${i}]: ${d} numbers, got ${JSON.stringify(p)}`);
      for (let k = 0; k < d; ++k) flat[i * d + k] = p[k];
    });
    dimension = d;
  }
  const count = flat.length / (dimension || 3);
  if (littleEndian) return {body: flat.buffer.slice(flat.byteOffset, flat.byteOffset + flat.byteLength), count};
  const bytes = new ArrayBuffer(flat.length * 8);
  const view = new DataView(bytes);
  for (let k = 0; k < flat.length; ++k) view.setFloat64(8 * k, flat[k], true);
  return {body: bytes, count};
}

function queryString(options) {
  const query = new URLSearchParams();
  for (const [name, value] of Object.entries(options)) {
    if (!QUERY_OPTIONS.has(name) || value === undefined || value === null) continue;
    query.set(name, Array.isArray(value) ? value.map(String).join(',') : String(value));
  }
  const text = query.toString();
  return text ? '?' + text : '';
}

const sleep = (ms, signal) => new Promise((resolve, reject) => {
  const timer = setTimeout(resolve, ms);
  if (signal) signal.addEventListener('abort', () => { clearTimeout(timer); reject(signal.reason); }, {once: true});
});

// The error a non-2xx answer carries, as a FootpointError.
async function answerError(response) {
  const text = await response.text();
  let error = null;
  try { error = JSON.parse(text).error; } catch (e) { /* not JSON: the text is the message */ }
  if (!error || typeof error !== 'object') error = {code: 'http_' + response.status, message: text};
  return new FootpointError(response.status, error.code, error.message, error.field);
}

// fetch, retrying a 503 after its Retry-After (seconds; 1 when absent) up to options.maxRetries
// times; any other status >= 400 throws its FootpointError.
async function send(url, init, options) {
  const fetchFn = options.fetch || globalThis.fetch;
  const retries = options.maxRetries === undefined ? 8 : options.maxRetries;
  for (let attempt = 0; ; ++attempt) {
    const response = await fetchFn(url, {...init, signal: options.signal});
    if (response.ok) return response;
    const error = await answerError(response);
    if (response.status !== 503 || attempt >= retries) throw error;
    const header = response.headers.get('Retry-After');
    const wait = header === null || header.trim() === '' ? NaN : Number(header);
    await sleep(1000 * (Number.isFinite(wait) && wait >= 0 ? wait : 1), options.signal);
  }
}

// Posts a definition; returns its geometry id (kept for the next call with the same definition).
export async function createGeometry(definition, options = {}) {
  const response = await send((options.server || '') + '/v1/geometries',
                              {method: 'POST', headers: {'Content-Type': 'application/json'}, body: JSON.stringify(definition)},
                              options);
  const answer = await response.json();
  knownIds.set(JSON.stringify(definition), answer.geometry_id);
  return answer.geometry_id;
}

// The lines of a response body as they arrive (the last one may lack its newline).
async function* lines(response) {
  const reader = response.body.getReader();
  const decoder = new TextDecoder();
  let pending = '', finished = false;
  try {
    for (;;) {
      const {done, value} = await reader.read();
      if (done) { finished = true; break; }
      pending += decoder.decode(value, {stream: true});
      let start = 0;
      for (let end = pending.indexOf('\n'); end >= 0; end = pending.indexOf('\n', start)) {
        yield pending.slice(start, end);
        start = end + 1;
      }
      pending = pending.slice(start);
    }
    pending += decoder.decode();
    if (pending !== '') yield pending;
  } finally {
    // A consumer that stops early (or an error) cancels the body: the connection closes and the
    // server stops projecting at its next window.
    if (!finished) await reader.cancel().catch(() => {});
    reader.releaseLock();
  }
}

// Projects `points` onto a geometry given by its definition (an object) or its id (a string):
// an async generator of the result objects in the order of the points. options: the request's
// (method, fields, max_distance, tolerance_band, histogram_bins, certify, ...: openapi.yaml), and
// server (base URL; '' = the page's origin), onProgress(done, total) (after each piece of the
// answer read), onStats(stats) (the batch's statistics, from the last line), dimension (for a
// flat Float64Array), maxRetries (503s, default 8), signal (an AbortSignal), fetch.
export async function* project(geometryOrId, points, options = {}) {
  for (const name of Object.keys(options))
    if (!QUERY_OPTIONS.has(name) && !CLIENT_OPTIONS.has(name))
      throw new TypeError(`unknown option ${name} (known: ${[...QUERY_OPTIONS, ...CLIENT_OPTIONS].join(', ')})`);
  const {body, count} = pointsBody(points, options.dimension);
  const definition = typeof geometryOrId === 'string' ? null : geometryOrId;
  let id = definition ? knownIds.get(JSON.stringify(definition)) || await createGeometry(definition, options) : geometryOrId;
  const init = {method: 'POST', body,
                headers: {'Content-Type': 'application/octet-stream', 'Accept': 'application/x-ndjson'}};
  const query = queryString(options);
  let response;
  for (let attempt = 0; ; ++attempt) {
    try {
      response = await send(`${options.server || ''}/v1/geometries/${id}/project${query}`, init, options);
      break;
    } catch (e) {
      if (!(e instanceof FootpointError) || e.code !== 'geometry_not_found' || !definition || attempt > 0) throw e;
      id = await createGeometry(definition, options);  // evicted, or held by another replica: post it again
    }
  }
  let done = 0, stats = null;
  const progress = options.onProgress;
  if (progress) progress(0, count);
  for await (const line of lines(response)) {
    if (line === '') continue;
    const record = JSON.parse(line);
    if (record.error) {
      const e = record.error;
      throw new FootpointError(e.status || response.status, e.code, e.message, e.field);
    }
    if (record.stats && record.geometry_id) {
      stats = record.stats;
      continue;
    }
    ++done;
    yield record;
    if (progress && (done === count || done % 1024 === 0)) progress(done, count);
  }
  if (stats === null || done !== count)
    throw new FootpointError(response.status, 'stream_cut', `the answer ended after ${done} of ${count} results`);
  if (options.onStats) options.onStats(stats);
}

// project()'s results gathered: {results, stats}.
export async function projectAll(geometryOrId, points, options = {}) {
  let stats = null;
  const results = [];
  for await (const r of project(geometryOrId, points, {...options, onStats: (s) => { stats = s; if (options.onStats) options.onStats(s); }}))
    results.push(r);
  return {results, stats};
}
