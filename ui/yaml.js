// A reader for the part of YAML 1.1 that openapi.yaml is written in (what /docs needs to render
// it in the browser): block mappings and sequences by indentation, flow mappings and sequences
// ({a: 1}, [x, 'y']) that may span lines, literal block scalars (|, |-, |+),
// single- and double-quoted strings, plain scalars that continue on more indented lines, and
// comments. Scalars resolve as PyYAML's safe loader does: null, true/false, integers, floats with a
// dot (1.5, 1.0e+3, .inf), anything else a string. Folded scalars (>), anchors, aliases, tags and
// several documents are not read (openapi.yaml has none): they throw.
(function (global) {
  'use strict';

  class YamlError extends Error {
    constructor(message, line) {
      super(`openapi.yaml line ${line + 1}: ${message}`);
      this.line = line;
    }
  }

  function resolve(text) {
    const s = text.trim();
    if (s === '' || s === '~' || s === 'null' || s === 'Null' || s === 'NULL') return null;
    if (/^(true|True|TRUE)$/.test(s)) return true;
    if (/^(false|False|FALSE)$/.test(s)) return false;
    if (/^[-+]?(0|[1-9][0-9_]*)$/.test(s)) return Number(s.replace(/_/g, ''));
    if (/^[-+]?([0-9][0-9_]*)?\.[0-9_]*([eE][-+][0-9]+)?$/.test(s) && /[0-9]/.test(s)) return Number(s.replace(/_/g, ''));
    if (/^[-+]?\.(inf|Inf|INF)$/.test(s)) return s.startsWith('-') ? -Infinity : Infinity;
    if (/^\.(nan|NaN|NAN)$/.test(s)) return NaN;
    return s;
  }

  // Where a comment starts in a line (" #" outside quotes), or the line's length.
  function commentAt(line) {
    let quote = null;
    for (let i = 0; i < line.length; ++i) {
      const c = line[i];
      if (quote) {
        if (c === quote) {
          if (quote === "'" && line[i + 1] === "'") ++i;
          else quote = null;
        } else if (quote === '"' && c === '\\') ++i;
      } else if (c === "'" || c === '"') {
        if (i === 0 || /[\s[{,:-]/.test(line[i - 1])) quote = c;
      } else if (c === '#' && (i === 0 || /\s/.test(line[i - 1]))) {
        return i;
      }
    }
    return line.length;
  }

  function parse(text) {
    const raw = text.replace(/\r\n?/g, '\n').split('\n');
    const lines = raw.map((l) => l.slice(0, commentAt(l)).replace(/\s+$/, ''));
    let i = 0;
    const indentOf = (l) => l.length - l.replace(/^ +/, '').length;
    const skipBlank = () => { while (i < lines.length && lines[i].trim() === '') ++i; };
    for (const [n, l] of raw.entries())
      if (/^\t/.test(l)) throw new YamlError('tabs are not indentation', n);
      else if (/^(---|\.\.\.)(\s|$)/.test(l) && n > 0) throw new YamlError('several documents', n);

    // A flow or quoted value starting at `start` of line i; reads on over further lines until its
    // brackets close. Returns the value and leaves i on the next line.
    function flow(start) {
      let text = lines[i].slice(start);
      let depth = 0, quote = null;
      const balanced = () => {
        depth = 0; quote = null;
        for (let k = 0; k < text.length; ++k) {
          const c = text[k];
          if (quote) {
            if (c === quote) { if (quote === "'" && text[k + 1] === "'") ++k; else quote = null; } else if (quote === '"' && c === '\\') ++k;
          } else if (c === "'" || c === '"') quote = c;
          else if (c === '[' || c === '{') ++depth;
          else if (c === ']' || c === '}') --depth;
        }
        return depth <= 0 && !quote;
      };
      const first = i;
      while (!balanced()) {
        if (++i >= lines.length) throw new YamlError('unclosed flow collection or quote', first);
        text += (quote ? ' ' : ' ') + lines[i].trim();
      }
      ++i;
      const reader = {text, at: 0};
      const value = flowValue(reader, first, false);
      if (reader.text.slice(reader.at).trim() !== '') throw new YamlError(`unexpected '${reader.text.slice(reader.at).trim()}'`, first);
      return value;
    }

    function flowValue(r, line, inFlow) {
      const space = () => { while (r.at < r.text.length && /\s/.test(r.text[r.at])) ++r.at; };
      space();
      const c = r.text[r.at];
      if (c === '[') {
        ++r.at;
        const out = [];
        for (;;) {
          space();
          if (r.text[r.at] === ']') { ++r.at; return out; }
          out.push(flowValue(r, line, true));
          space();
          if (r.text[r.at] === ',') ++r.at;
          else if (r.text[r.at] !== ']') throw new YamlError("expected ',' or ']'", line);
        }
      }
      if (c === '{') {
        ++r.at;
        const out = {};
        for (;;) {
          space();
          if (r.text[r.at] === '}') { ++r.at; return out; }
          const key = flowKey(r, line);
          space();
          let value = null;
          if (r.text[r.at] === ':') { ++r.at; value = flowValue(r, line, true); }
          out[key] = value;
          space();
          if (r.text[r.at] === ',') ++r.at;
          else if (r.text[r.at] !== '}') throw new YamlError("expected ',' or '}'", line);
        }
      }
      if (c === "'" || c === '"') return quoted(r, line);
      if (c === '&' || c === '*' || c === '!') throw new YamlError('anchors, aliases and tags are not read', line);
      const start = r.at;
      while (r.at < r.text.length) {
        const ch = r.text[r.at];
        if (inFlow && (ch === ',' || ch === ']' || ch === '}')) break;
        if (inFlow && ch === ':' && /[\s,\]}]/.test(r.text[r.at + 1] || ' ')) break;
        ++r.at;
      }
      return resolve(r.text.slice(start, r.at));
    }

    function flowKey(r, line) {
      const c = r.text[r.at];
      if (c === "'" || c === '"') return String(quoted(r, line));
      const start = r.at;
      while (r.at < r.text.length && !(r.text[r.at] === ':' && /[\s,\]}]/.test(r.text[r.at + 1] || ' ')) &&
             r.text[r.at] !== ',' && r.text[r.at] !== '}') ++r.at;
      return r.text.slice(start, r.at).trim();
    }

    function quoted(r, line) {
      const q = r.text[r.at++];
      let out = '';
      while (r.at < r.text.length) {
        const c = r.text[r.at++];
        if (q === "'" && c === "'") {
          if (r.text[r.at] === "'") { out += "'"; ++r.at; continue; }
          return out;
        }
        if (q === '"' && c === '"') return out;
        if (q === '"' && c === '\\') {
          const e = r.text[r.at++];
          const map = {n: '\n', t: '\t', r: '\r', '"': '"', '\\': '\\', '/': '/', 0: '\0', b: '\b', f: '\f', ' ': ' '};
          if (e === 'u' || e === 'x') {
            const n = e === 'u' ? 4 : 2;
            out += String.fromCharCode(parseInt(r.text.slice(r.at, r.at + n), 16));
            r.at += n;
          } else if (e in map) out += map[e];
          else throw new YamlError(`unknown escape \\${e}`, line);
          continue;
        }
        out += c;
      }
      throw new YamlError('unclosed quote', line);
    }

    // The text after "key:" or "- " at line i (from column `start`): a block scalar, a flow or
    // quoted value, a plain scalar (continuing on lines indented more than `indent`), or a nested
    // block below.
    function value(start, indent) {
      const rest = lines[i].slice(start).trim();
      if (rest === '') {
        ++i;
        skipBlank();
        if (i >= lines.length) return null;
        const next = indentOf(lines[i]);
        if (next > indent || (next === indent && /^- |^-$/.test(lines[i].trim()))) return block(next);
        return null;
      }
      if (/^[|>][-+]?$/.test(rest)) return blockScalar(rest, indent);
      const column = lines[i].indexOf(rest, start);
      if (/^["'[{]/.test(rest)) return flow(column);
      if (/^[&*!]/.test(rest)) throw new YamlError('anchors, aliases and tags are not read', i);
      let text = rest;
      ++i;
      while (i < lines.length && lines[i].trim() !== '' && indentOf(lines[i]) > indent && !/^- /.test(lines[i].trim()) &&
             !/^[^'"]*?:(\s|$)/.test(lines[i].trim())) {
        text += ' ' + lines[i].trim();
        ++i;
      }
      return resolve(text);
    }

    function blockScalar(header, indent) {
      if (header[0] === '>') throw new YamlError('folded block scalars (>) are not read', i);
      const chomp = header[1] || '';
      const first = ++i;
      let contentIndent = -1;
      const body = [];
      while (i < raw.length) {
        const l = raw[i];
        if (l.trim() === '') { body.push(''); ++i; continue; }
        const n = indentOf(l);
        if (contentIndent < 0) contentIndent = n;
        if (n < contentIndent || n <= indent) break;
        body.push(l.slice(contentIndent));
        ++i;
      }
      if (contentIndent < 0 && i === first) return '';
      // Trailing blank lines are not content (clip keeps one newline, strip none, keep all).
      let trailing = 0;
      while (body.length && body[body.length - 1] === '') { body.pop(); ++trailing; }
      const text = body.join('\n');
      if (body.length === 0) return chomp === '+' ? '\n'.repeat(trailing) : '';
      if (chomp === '-') return text;
      if (chomp === '+') return text + '\n' + '\n'.repeat(trailing);
      return text + '\n';
    }

    function block(indent) {
      skipBlank();
      const t = lines[i].trim();
      return /^- |^-$/.test(t) ? sequence(indent) : mapping(indent);
    }

    function sequence(indent) {
      const out = [];
      for (;;) {
        skipBlank();
        if (i >= lines.length || indentOf(lines[i]) !== indent || !/^- |^-$/.test(lines[i].trim())) break;
        const item = indent + 2;
        const rest = lines[i].slice(item).trim();
        if (rest !== '' && keyOf(lines[i].slice(item)) !== null) {
          // "- key: value": a mapping whose keys line up after the dash.
          lines[i] = ' '.repeat(item) + lines[i].slice(item);
          out.push(mapping(indentOf(lines[i])));
        } else {
          out.push(value(indent + 1, indent));
        }
      }
      if (i < lines.length && indentOf(lines[i]) > indent && lines[i].trim() !== '')
        throw new YamlError('bad indentation in a sequence', i);
      return out;
    }

    // "key: ..." -> {key, at} (at: the column after the colon), or null.
    function keyOf(text) {
      const t = text.replace(/^ +/, '');
      const lead = text.length - t.length;
      let m;
      if ((m = /^'((?:[^']|'')*)'\s*:(\s|$)/.exec(t))) return {key: m[1].replace(/''/g, "'"), at: lead + m[0].length};
      if ((m = /^"((?:[^"\\]|\\.)*)"\s*:(\s|$)/.exec(t))) return {key: JSON.parse('"' + m[1] + '"'), at: lead + m[0].length};
      if ((m = /^([^\s'"[{#&*!|>%@`-][^:]*?|-[^\s:][^:]*?)\s*:(\s|$)/.exec(t))) return {key: m[1], at: lead + m[0].length};
      return null;
    }

    function mapping(indent) {
      const out = {};
      for (;;) {
        skipBlank();
        if (i >= lines.length) break;
        const n = indentOf(lines[i]);
        if (n < indent) break;
        if (n > indent) throw new YamlError('bad indentation', i);
        if (/^- |^-$/.test(lines[i].trim())) break;
        const k = keyOf(lines[i]);
        if (k === null) throw new YamlError(`expected "key: value", got '${lines[i].trim()}'`, i);
        if (Object.prototype.hasOwnProperty.call(out, k.key)) throw new YamlError(`duplicate key '${k.key}'`, i);
        out[k.key] = value(k.at, indent);
      }
      return out;
    }

    skipBlank();
    if (i < lines.length && /^---(\s|$)/.test(lines[i])) ++i;
    skipBlank();
    if (i >= lines.length) return null;
    const doc = block(indentOf(lines[i]));
    skipBlank();
    if (i < lines.length) throw new YamlError(`unexpected '${lines[i].trim()}'`, i);
    return doc;
  }

  global.FootpointYaml = {parse, YamlError};
})(window);
