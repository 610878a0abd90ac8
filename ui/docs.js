// The API reference (GET /docs), rendered in the browser from the server's own /openapi.yaml
// (read with yaml.js): the description, every operation grouped by tag with its parameters,
// request body, examples and responses, and the schemas, $refs as links. Text goes into the page
// as text (never as HTML); `code` spans and paragraphs are the only markup read from descriptions.
(function () {
  'use strict';

  const METHODS = ['get', 'post', 'put', 'patch', 'delete'];
  let spec = null;

  function el(tag, className, ...children) {
    const e = document.createElement(tag);
    if (className) e.className = className;
    for (const c of children) if (c !== null && c !== undefined) e.append(c);
    return e;
  }

  // Paragraphs (blank lines) with `code` spans.
  function prose(text, tag = 'div') {
    const box = el(tag, 'prose');
    for (const paragraph of String(text || '').split(/\n\s*\n/)) {
      if (paragraph.trim() === '') continue;
      const p = el('p');
      String(paragraph).trim().split(/(`[^`]*`)/).forEach((part) => {
        if (part.startsWith('`') && part.endsWith('`') && part.length > 1) p.append(el('code', null, part.slice(1, -1)));
        else p.append(part.replace(/\s*\n\s*/g, ' '));
      });
      box.append(p);
    }
    return box;
  }

  function refName(ref) { return ref.split('/').pop(); }
  function resolve(node) {
    let n = node;
    for (let guard = 0; n && n.$ref && guard < 20; ++guard) {
      n = n.$ref.slice(2).split('/').reduce((o, k) => (o ? o[k.replace(/~1/g, '/').replace(/~0/g, '~')] : undefined), spec);
    }
    return n || {};
  }
  function refLink(ref) {
    const a = el('a', 'ref', refName(ref));
    a.href = '#schema-' + refName(ref);
    return a;
  }

  // One line saying what a schema is: its type, a $ref link, enum, const, bounds.
  function typeSummary(schema) {
    const out = el('span', 'ptype');
    if (!schema || typeof schema !== 'object') return out;
    if (schema.$ref) { out.append(refLink(schema.$ref)); return out; }
    const parts = [];
    if (schema.type) parts.push(Array.isArray(schema.type) ? schema.type.join(' | ') : schema.type);
    if (schema.type === 'array' && schema.items) {
      out.append((parts.length ? parts.join(' ') : 'array') + ' of ');
      out.append(typeSummary(schema.items));
      parts.length = 0;
    }
    if ('const' in schema) parts.push('= ' + JSON.stringify(schema.const));
    if (schema.enum) parts.push('one of ' + schema.enum.map((x) => JSON.stringify(x)).join(', '));
    for (const [k, label] of [['minimum', '≥'], ['exclusiveMinimum', '>'], ['maximum', '≤'], ['exclusiveMaximum', '<'],
                              ['minItems', 'items ≥'], ['maxItems', 'items ≤']])
      if (k in schema) parts.push(`${label} ${schema[k]}`);
    if (schema.pattern) parts.push('pattern ' + schema.pattern);
    if ('default' in schema) parts.push('default ' + JSON.stringify(schema.default));
    if (parts.length) out.append((out.childNodes.length ? ', ' : '') + parts.join(', '));
    return out;
  }

  // A schema as a tree: its summary, composition (oneOf, anyOf, allOf) and properties.
  function schemaTree(schema, depth = 0) {
    const box = el('div', 'schema');
    if (!schema || typeof schema !== 'object') return box;
    box.append(el('div', null, typeSummary(schema)));
    if (schema.description && depth > 0) box.append(prose(schema.description, 'div'));
    for (const k of ['oneOf', 'anyOf', 'allOf'])
      if (schema[k]) {
        box.append(el('div', 'pdesc', k === 'oneOf' ? 'exactly one of:' : k === 'anyOf' ? 'any of:' : 'all of:'));
        for (const s of schema[k]) box.append(schemaTree(s, depth + 1));
      }
    const properties = schema.properties || {};
    const required = new Set(schema.required || []);
    for (const [name, sub] of Object.entries(properties)) {
      const line = el('div', 'prop', el('span', 'pname', name), required.has(name) ? el('span', 'req', ' *') : null, ' ',
                      typeSummary(sub));
      const description = sub && (sub.description || (sub.$ref ? null : null));
      if (description) line.append(' ', el('span', 'pdesc', description.replace(/\s*\n\s*/g, ' ')));
      box.append(line);
      if (sub && !sub.$ref && depth < 6 && (sub.properties || sub.oneOf || sub.anyOf || sub.allOf ||
                                           (sub.items && (sub.items.properties || sub.items.oneOf))))
        box.append(schemaTree(sub.items && !sub.properties ? sub.items : sub, depth + 1));
    }
    if (schema.additionalProperties && typeof schema.additionalProperties === 'object')
      box.append(el('div', 'prop', el('span', 'pname', '{name}'), ' ', typeSummary(schema.additionalProperties)));
    return box;
  }

  function operation(path, method, op, shared) {
    const details = el('details', 'operation');
    details.id = op.operationId || `${method}-${path}`;
    details.dataset.method = method.toUpperCase();
    details.dataset.path = path;
    details.append(el('summary', null, el('span', 'verb ' + method, method.toUpperCase()), el('span', 'path', path),
                      el('span', 'summary', op.summary || '')));
    const body = el('div', 'body');
    if (op.description) body.append(prose(op.description));
    const parameters = [...(shared || []), ...(op.parameters || [])].map(resolve);
    if (parameters.length) {
      body.append(el('h4', null, 'Parameters'));
      const t = el('table', 'params');
      t.append(el('tr', null, el('th', null, 'name'), el('th', null, 'in'), el('th', null, 'schema'), el('th', null, 'description')));
      for (const p of parameters)
        t.append(el('tr', null, el('td', null, p.name + (p.required ? ' *' : '')), el('td', null, p.in),
                    el('td', null, typeSummary(p.schema)), el('td', null, prose(p.description))));
      body.append(t);
    }
    if (op.requestBody) {
      const rb = resolve(op.requestBody);
      body.append(el('h4', null, 'Request body' + (rb.required ? '' : ' (optional)')));
      for (const [media, content] of Object.entries(rb.content || {})) {
        body.append(el('div', 'pdesc', media));
        body.append(schemaTree(content.schema));
        for (const [name, example] of Object.entries(content.examples || {})) {
          body.append(el('div', 'pdesc', 'example: ' + name));
          body.append(el('pre', 'example', JSON.stringify(resolve(example).value, null, 2)));
        }
      }
    }
    body.append(el('h4', null, 'Responses'));
    const t = el('table', 'responses');
    for (const [status, r] of Object.entries(op.responses || {})) {
      const response = resolve(r);
      const cell = el('td', null, prose(response.description));
      for (const [media, content] of Object.entries(response.content || {}))
        cell.append(el('div', 'pdesc', media), schemaTree(content.schema));
      if (r.$ref) cell.append(el('div', 'pdesc', 'see ', refLink(r.$ref)));
      t.append(el('tr', null, el('td', null, status), cell));
    }
    body.append(t);
    details.append(body);
    return details;
  }

  function render(root) {
    const info = spec.info || {};
    root.textContent = '';
    root.append(el('h1', null, `${info.title || 'API'} `, el('span', 'muted', info.version ? 'v' + info.version : '')));
    if (info.summary) root.append(el('p', 'summary', info.summary));
    if (info.description) root.append(prose(info.description));
    const operations = [];
    for (const [path, item] of Object.entries(spec.paths || {}))
      for (const method of METHODS)
        if (item[method]) operations.push({path, method, op: item[method], shared: item.parameters});
    const tags = [...(spec.tags || []).map((t) => t.name)];
    for (const o of operations) for (const t of o.op.tags || ['other']) if (!tags.includes(t)) tags.push(t);
    const toc = el('nav', 'toc');
    root.append(el('h2', null, 'Operations'), toc);
    for (const tag of tags) {
      const mine = operations.filter((o) => (o.op.tags || ['other']).includes(tag));
      if (!mine.length) continue;
      const section = el('section', 'tag');
      section.id = 'tag-' + tag;
      section.append(el('h2', null, tag));
      for (const o of mine) {
        const d = operation(o.path, o.method, o.op, o.shared);
        section.append(d);
        const a = el('a', null, `${o.method.toUpperCase()} ${o.path}`);
        a.href = '#' + d.id;
        toc.append(a);
      }
      root.append(section);
    }
    const schemas = (spec.components || {}).schemas || {};
    root.append(el('h2', null, 'Schemas'));
    for (const [name, schema] of Object.entries(schemas)) {
      const s = el('section', 'schema-def');
      s.id = 'schema-' + name;
      s.append(el('h4', null, name));
      if (schema.description) s.append(prose(schema.description));
      s.append(schemaTree(schema));
      root.append(s);
    }
  }

  function openTarget() {
    const target = document.getElementById(decodeURIComponent(location.hash.slice(1)));
    if (target && target.tagName === 'DETAILS') target.open = true;
    if (target) target.scrollIntoView();
  }

  async function start() {
    const root = document.getElementById('docs');
    try {
      const response = await fetch('/openapi.yaml');
      if (!response.ok) throw new Error(`GET /openapi.yaml answered ${response.status}`);
      spec = FootpointYaml.parse(await response.text());
      render(root);
      window.footpointDocs = {spec};
      window.addEventListener('hashchange', openTarget);
      if (location.hash) openTarget();
      document.body.dataset.state = 'ready';
    } catch (e) {
      root.textContent = '';
      root.append(el('p', 'field-error', String(e.message || e)));
      document.body.dataset.state = 'error';
    }
  }

  window.addEventListener('DOMContentLoaded', start);
})();
