// The playground's point-cloud reader, run as a Web Worker so that a large file does not hold up
// the page: it gets {name, buffer, dimension} (the file's bytes, and 2 or 3 coordinates a point)
// and answers {points: Float64Array (x, y[, z] one point after the other), count, format} or
// {error: message naming the line or byte}.
//
// Formats: XYZ (numbers separated by white space, x y z first, further columns ignored), CSV
// (commas; a first line that is no numbers is a header, whose x, y, z columns are used when it
// names them), PLY (Greg Turk's polygon file format, 1994) in ascii or binary_little_endian, whose
// vertex element's x, y, z properties are read (any scalar type) and its other properties skipped.
// Empty lines and lines starting with # are skipped in XYZ and CSV.
'use strict';

class ReadError extends Error {}

const PLY_TYPES = {
  char: ['getInt8', 1], int8: ['getInt8', 1], uchar: ['getUint8', 1], uint8: ['getUint8', 1],
  short: ['getInt16', 2], int16: ['getInt16', 2], ushort: ['getUint16', 2], uint16: ['getUint16', 2],
  int: ['getInt32', 4], int32: ['getInt32', 4], uint: ['getUint32', 4], uint32: ['getUint32', 4],
  float: ['getFloat32', 4], float32: ['getFloat32', 4], double: ['getFloat64', 8], float64: ['getFloat64', 8],
};
const AXES = ['x', 'y', 'z'];

// A decimal number as JSON and C write them (no hex, no Infinity, no empty string).
const NUMBER = /^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$/;
function number(token, where) {
  if (!NUMBER.test(token)) throw new ReadError(`${where}: '${token}' is not a number`);
  return Number(token);
}

function shorten(line) { return line.length > 60 ? line.slice(0, 57) + '...' : line; }

// XYZ and CSV: one point a line.
function readText(text, dimension, csv) {
  const lines = text.split(/\r?\n/);
  const out = new Float64Array(lines.length * dimension);
  let count = 0, columns = null;
  for (let k = 0; k < lines.length; ++k) {
    const line = lines[k].trim();
    if (line === '' || line[0] === '#') continue;
    const tokens = csv ? line.split(',').map((t) => t.trim()) : line.split(/\s+/);
    if (csv && columns === null && count === 0 && !tokens.every((t) => NUMBER.test(t))) {
      // a header: its x, y(, z) columns, else the first ones
      const names = tokens.map((t) => t.replace(/^"|"$/g, '').toLowerCase());
      const named = AXES.slice(0, dimension).map((a) => names.indexOf(a));
      columns = named.every((i) => i >= 0) ? named : AXES.slice(0, dimension).map((_, i) => i);
      continue;
    }
    const at = columns || [0, 1, 2].slice(0, dimension);
    const need = Math.max(...at) + 1;
    if (tokens.length < need)
      throw new ReadError(`line ${k + 1}: ${need} numbers expected${csv ? ' (separated by commas)' : ''}, got '${shorten(line)}'`);
    for (let c = 0; c < dimension; ++c) {
      const x = number(tokens[at[c]], `line ${k + 1}, column ${at[c] + 1}`);
      out[count * dimension + c] = x;
    }
    ++count;
  }
  if (count === 0) throw new ReadError('no points in the file');
  return {points: out.slice(0, count * dimension), count};
}

// A PLY file's header: its format, its elements with their properties, and where its data begin.
function plyHeader(bytes) {
  const limit = Math.min(bytes.length, 65536);
  let end = -1;
  const text = new TextDecoder('latin1').decode(bytes.subarray(0, limit));
  const m = /(^|\n)end_header\r?\n/.exec(text);
  if (!m) throw new ReadError('PLY: no end_header line in the first 64 KiB');
  end = m.index + m[0].length;
  const lines = text.slice(0, end).split(/\r?\n/);
  if (lines[0].trim() !== 'ply') throw new ReadError("PLY: line 1 is not 'ply'");
  let format = null;
  const elements = [];
  lines.forEach((raw, k) => {
    const t = raw.trim().split(/\s+/);
    const where = `PLY header, line ${k + 1}`;
    if (t[0] === 'format') {
      format = t[1];
      if (format !== 'ascii' && format !== 'binary_little_endian')
        throw new ReadError(`${where}: format ${format} is not read (ascii and binary_little_endian are)`);
    } else if (t[0] === 'element') {
      const count = Number(t[2]);
      if (!Number.isInteger(count) || count < 0) throw new ReadError(`${where}: '${raw.trim()}' has no element count`);
      elements.push({name: t[1], count, properties: []});
    } else if (t[0] === 'property') {
      const element = elements[elements.length - 1];
      if (!element) throw new ReadError(`${where}: a property before any element`);
      if (t[1] === 'list') {
        if (!PLY_TYPES[t[2]] || !PLY_TYPES[t[3]]) throw new ReadError(`${where}: unknown list types in '${raw.trim()}'`);
        element.properties.push({name: t[4], list: true, countType: t[2], type: t[3]});
      } else {
        if (!PLY_TYPES[t[1]]) throw new ReadError(`${where}: unknown property type '${t[1]}'`);
        element.properties.push({name: t[2], type: t[1]});
      }
    }
  });
  if (!format) throw new ReadError('PLY: no format line');
  const vertex = elements.find((e) => e.name === 'vertex');
  if (!vertex) throw new ReadError('PLY: no vertex element');
  return {format, elements, vertex, dataStart: end, headerLines: lines.length - 1};
}

function axesOf(vertex, dimension) {
  const at = AXES.slice(0, dimension).map((a) => vertex.properties.findIndex((p) => p.name === a && !p.list));
  const missing = AXES.slice(0, dimension).filter((_, i) => at[i] < 0);
  if (missing.length) throw new ReadError(`PLY: the vertex element has no ${missing.join(', ')} propert${missing.length > 1 ? 'ies' : 'y'}`);
  return at;
}

function readPlyAscii(bytes, header, dimension) {
  const lines = new TextDecoder().decode(bytes.subarray(header.dataStart)).split(/\r?\n/);
  const at = axesOf(header.vertex, dimension);
  const out = new Float64Array(header.vertex.count * dimension);
  let k = 0;
  const next = () => {
    while (k < lines.length && lines[k].trim() === '') ++k;
    if (k >= lines.length) return null;
    return lines[k++].trim().split(/\s+/);
  };
  for (const element of header.elements) {
    for (let i = 0; i < element.count; ++i) {
      const tokens = next();
      const lineNumber = header.headerLines + k;
      if (!tokens) throw new ReadError(`PLY: the file ends in element ${element.name} ${i} of ${element.count}`);
      if (element !== header.vertex) continue;
      if (element.properties.some((p) => p.list)) throw new ReadError('PLY: list properties in the vertex element are not read');
      if (tokens.length < element.properties.length)
        throw new ReadError(`line ${lineNumber}: ${element.properties.length} vertex properties expected, got '${shorten(tokens.join(' '))}'`);
      for (let c = 0; c < dimension; ++c) out[i * dimension + c] = number(tokens[at[c]], `line ${lineNumber}`);
    }
    if (element === header.vertex) break;
  }
  return {points: out, count: header.vertex.count};
}

function readPlyBinary(bytes, header, dimension) {
  const view = new DataView(bytes.buffer, bytes.byteOffset, bytes.byteLength);
  let at = header.dataStart;
  const need = (n, what) => {
    if (at + n > bytes.length) throw new ReadError(`PLY: the file ends at byte ${bytes.length}, in ${what}`);
  };
  for (const element of header.elements) {
    if (element === header.vertex) break;
    // elements before the vertices (rare): skipped, list by list
    for (let i = 0; i < element.count; ++i)
      for (const p of element.properties) {
        if (p.list) {
          const [getter, size] = PLY_TYPES[p.countType];
          need(size, `element ${element.name} ${i}`);
          const n = view[getter](at, true);
          at += size + n * PLY_TYPES[p.type][1];
        } else {
          at += PLY_TYPES[p.type][1];
        }
      }
  }
  const vertex = header.vertex;
  if (vertex.properties.some((p) => p.list)) throw new ReadError('PLY: list properties in the vertex element are not read');
  const offsets = [];
  let stride = 0;
  for (const p of vertex.properties) { offsets.push(stride); stride += PLY_TYPES[p.type][1]; }
  const axes = axesOf(vertex, dimension);
  const getters = axes.map((i) => PLY_TYPES[vertex.properties[i].type][0]);
  const offset = axes.map((i) => offsets[i]);
  const available = Math.floor((bytes.length - at) / stride);
  if (available < vertex.count)
    throw new ReadError(`PLY: the file ends after vertex ${available} of ${vertex.count} (${stride} bytes a vertex from byte ${at})`);
  const out = new Float64Array(vertex.count * dimension);
  for (let i = 0; i < vertex.count; ++i, at += stride)
    for (let c = 0; c < dimension; ++c) {
      const x = view[getters[c]](at + offset[c], true);
      if (!Number.isFinite(x)) throw new ReadError(`PLY: vertex ${i} has ${AXES[c]} = ${x}`);
      out[i * dimension + c] = x;
    }
  return {points: out, count: vertex.count};
}

function read(name, buffer, dimension) {
  const bytes = new Uint8Array(buffer);
  const start = new TextDecoder('latin1').decode(bytes.subarray(0, 4));
  if (start === 'ply\n' || start === 'ply\r') {
    const header = plyHeader(bytes);
    const out = header.format === 'ascii' ? readPlyAscii(bytes, header, dimension) : readPlyBinary(bytes, header, dimension);
    return {...out, format: 'PLY ' + header.format};
  }
  let text;
  try {
    text = new TextDecoder('utf-8', {fatal: true}).decode(bytes);
  } catch (e) {
    throw new ReadError('not a text file (XYZ, CSV) and no PLY header');
  }
  const csv = /\.csv$/i.test(name) || (!/\.xyz$/i.test(name) && /^[^\n]*,/.test(text));
  return {...readText(text, dimension, csv), format: csv ? 'CSV' : 'XYZ'};
}

self.onmessage = (event) => {
  const {name, buffer, dimension} = event.data;
  const started = performance.now();
  try {
    const out = read(name, buffer, dimension);
    out.ms = performance.now() - started;
    self.postMessage(out, [out.points.buffer]);
  } catch (e) {
    self.postMessage({error: `${name}: ${e instanceof ReadError ? e.message : 'cannot be read (' + e + ')'}`});
  }
};
