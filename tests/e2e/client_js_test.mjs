// ui/footpoint-client.js in Node (18+: global fetch and web streams) against a live
// footpoint-server started here on a loopback port.
//
// Checks, against the closed form of a sphere of radius 2 (signed distance 2 - |p| for its
// parametrisation, whose s_u x s_v points inwards): results in the order of the points, from
// arrays and from a flat Float64Array; onProgress rising to the count as the stream is read; the
// last line's stats; query options (fields, max_distance); re-posting a definition the server no
// longer holds; errors thrown with the server's status, code and message (a bad formula, an id
// not held, a NaN coordinate, a 2-D point on a surface); a consumer that stops early; and a 503
// (a server answering one request at a time, busy with a long stream) retried after Retry-After.
//
//   node tests/e2e/client_js_test.mjs --server build/footpoint-server --client ui/footpoint-client.js
// Exit 77 (ctest: skipped) under Node older than 18.
import {spawn} from 'node:child_process';
import {createInterface} from 'node:readline';
import {pathToFileURL} from 'node:url';
import path from 'node:path';

if (Number(process.versions.node.split('.')[0]) < 18 || typeof fetch !== 'function') {
  console.log(`SKIP: Node ${process.versions.node} has no global fetch (18+ has)`);
  process.exit(77);
}

const arg = (name) => process.argv[process.argv.indexOf(name) + 1];
const client = await import(pathToFileURL(path.resolve(arg('--client'))).href);
const {project, projectAll, createGeometry, FootpointError} = client;

const SPHERE = {type: 'parametric_surface', x: '2*sin(v)*cos(u)', y: '2*sin(v)*sin(u)', z: '2*cos(v)',
                domain: {u: [0, '2*_pi'], v: [0, '_pi']}};

function pointsAndExpected(n) {
  const points = [], expected = [];
  for (let i = 0; i < n; ++i) {
    const u = 0.1 + 6.0 * i / n, v = 0.4 + 2.3 * ((i * 7) % n) / n, r = 1.5 + (i % 11) / 10.0;
    points.push([r * Math.sin(v) * Math.cos(u), r * Math.sin(v) * Math.sin(u), r * Math.cos(v)]);
    expected.push(2.0 - r);
  }
  return {points, expected};
}

function check(condition, what) {
  if (!condition) throw new Error('FAIL: ' + what);
  console.log('ok: ' + what);
}
const close = (a, b, tol = 1e-12) => Math.abs(a - b) <= tol * Math.max(1, Math.abs(b));

async function expectError(promise, what, test) {
  try {
    await promise;
  } catch (e) {
    check(e instanceof FootpointError && test(e), `${what} (${e.message})`);
    return;
  }
  check(false, what + ': no error thrown');
}

function startServer(...flags) {
  const child = spawn(arg('--server'), ['--host', '127.0.0.1', '--port', '0', ...flags], {stdio: ['ignore', 'pipe', 'inherit']});
  return new Promise((resolve, reject) => {
    const lines = createInterface({input: child.stdout});
    let started = false;
    lines.on('line', (line) => {
      if (started) return;  // the rest of the log is drained
      const record = JSON.parse(line);
      if (record.msg === 'listening') {
        started = true;
        resolve({child, url: `http://127.0.0.1:${record.port}`});
      }
    });
    child.on('exit', (code) => { if (!started) reject(new Error(`the server exited (${code}) before listening`)); });
  });
}

function stopServer(server) {
  return new Promise((resolve) => {
    server.child.on('exit', (code, signal) => resolve({code, signal}));
    server.child.kill('SIGTERM');
  });
}

const metric = async (url, name) => (await (await fetch(url + '/metrics')).text()).split('\n')
  .filter((l) => l.startsWith(name)).reduce((sum, l) => sum + Number(l.split(' ').pop()), 0);

async function main() {
  let server = await startServer('--threads', '2');
  try {
    const server_ = server.url;
    const {points, expected} = pointsAndExpected(5000);

    // arrays in, results in order, progress as the stream is read, the stats line
    const progress = [];
    let stats = null;
    const results = [];
    for await (const r of project(SPHERE, points, {server: server_, tolerance_band: [-0.25, 0.25],
                                                   onProgress: (done, total) => progress.push([done, total]),
                                                   onStats: (s) => { stats = s; }}))
      results.push(r);
    check(results.length === 5000 && results.every((r, i) => close(r.signed_distance, expected[i])),
          '5000 signed distances are 2 - |p|, in the order of the points');
    check(results.every((r) => r.diagnostics.status === 'converged'), 'every point converged');
    check(progress.length >= 3 && progress[0][0] === 0 && progress.at(-1)[0] === 5000 &&
          progress.every(([d, t], k) => t === 5000 && (k === 0 || d > progress[k - 1][0])),
          `onProgress rises from 0 to 5000 (${progress.length} calls)`);
    const band = expected.filter((e) => e >= -0.25 && e <= 0.25).length;
    check(stats && stats.deviation.count === 5000 && stats.deviation.tolerance_band.within === band,
          `onStats: the last line's stats (tolerance band: ${band} of 5000 within)`);

    // a flat Float64Array and query options
    const flat = new Float64Array(points.flat());
    const some = await projectAll(SPHERE, flat, {server: server_, fields: ['signed_distance'], max_distance: 0.45});
    check(some.results.every((r, i) => Object.keys(r).join() === 'signed_distance' &&
                             (Math.abs(expected[i]) > 0.45 ? r.signed_distance === null : close(r.signed_distance, expected[i]))),
          'a Float64Array with fields and max_distance: signed distances, null beyond max_distance');

    // the server forgets the geometry: the client posts it again
    const id = await createGeometry(SPHERE, {server: server_});
    check((await fetch(`${server_}/v1/geometries/${id}`, {method: 'DELETE'})).ok, 'the geometry deleted');
    const again = await projectAll(SPHERE, points.slice(0, 5), {server: server_});
    check(close(again.results[4].signed_distance, expected[4]), 'a deleted geometry is posted again');
    check((await fetch(`${server_}/v1/geometries/${id}`)).status === 200, 'and held again');

    // errors throw with the server's status, code and message
    await expectError(projectAll({...SPHERE, x: 'sinn(v)'}, points, {server: server_}), 'a bad formula throws 422 unknown_function',
                      (e) => e.status === 422 && e.code === 'unknown_function' && e.detail.includes('sin'));
    await expectError(projectAll('0'.repeat(32), points, {server: server_}), 'an id not held (no definition) throws 404',
                      (e) => e.status === 404 && e.code === 'geometry_not_found');
    await expectError(projectAll(SPHERE, [[1, 2, NaN]], {server: server_}), 'a NaN coordinate throws 400 number_out_of_range',
                      (e) => e.status === 400 && e.code === 'number_out_of_range' && e.field === 'points[0][2]');
    await expectError(projectAll(SPHERE, [[1, 2]], {server: server_}), 'a 2-D point on a surface throws 400',
                      (e) => e.status === 400 && e.code === 'wrong_shape');
    let typeError = null;
    try { await projectAll(SPHERE, points, {server: server_, maxDistance: 1}); } catch (e) { typeError = e; }
    check(typeError instanceof TypeError && /unknown option maxDistance/.test(typeError.message), 'an unknown option throws a TypeError');

    // a consumer that stops early: the answer is cancelled, the connection is free for the next
    const many = pointsAndExpected(200000).points;
    let taken = 0;
    for await (const r of project(SPHERE, many, {server: server_, fields: ['distance']})) {
      if (++taken === 10) break;
      void r;
    }
    const after = await projectAll(SPHERE, points.slice(0, 3), {server: server_});
    check(taken === 10 && after.results.length === 3, 'a consumer that stops after 10 of 200,000 results, then another request');
  } finally {
    const end = await stopServer(server);
    check(end.code === 0, 'the server ended cleanly on SIGTERM');
  }

  // 503: a server answering one request at a time, busy with a long stream
  // Connection threads to spare: fetch keeps the /metrics poll's connection open (a thread), and the
  // second request must reach the admission check, not wait in the accept queue.
  server = await startServer('--threads', '1', '--max-inflight', '1', '--connection-threads', '4');
  try {
    const id = await createGeometry(SPHERE, {server: server.url});
    const long = pointsAndExpected(400000).points;
    const first = projectAll(id, long, {server: server.url, fields: ['distance']});
    const deadline = Date.now() + 60000;
    let inFlight = 0;
    while ((inFlight = await metric(server.url, 'footpoint_http_requests_in_flight')) < 1 && Date.now() < deadline)
      await new Promise((r) => setTimeout(r, 10));
    check(inFlight >= 1, 'the long stream is in flight');
    const started = Date.now();
    const second = await projectAll(id, pointsAndExpected(3).points, {server: server.url, maxRetries: 200});
    const waited = (Date.now() - started) / 1000;
    const longAnswer = await first;
    const text = await (await fetch(server.url + '/metrics')).text();
    const refused = text.split('\n').filter((l) => l.startsWith('footpoint_http_requests_total') && l.includes('status="503"'))
      .reduce((s, l) => s + Number(l.split(' ').pop()), 0);
    check(refused >= 1 && second.results.length === 3 && longAnswer.results.length === 400000,
          `503 overloaded retried after Retry-After (${refused} refused, ${waited.toFixed(1)} s waited)`);
  } finally {
    await stopServer(server);
  }
}

main().catch((e) => { console.log(e.stack || String(e)); process.exit(1); });
