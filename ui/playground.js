// footpoint's geometry playground (GET /): edit a geometry, see its mesh
// (GET /v1/geometries/{id}/mesh), project points onto it (POST /v1/geometries/{id}/project) and
// look at the foot points, the segments to them, the other local minima and the iterates of the
// papers' methods; or load a point cloud (XYZ, CSV, PLY), project it through ui/footpoint-client.js
// and see its signed deviations as colours, statistics and a histogram, and export them as CSV.
// It uses the public API of its own origin only; three.js and its orbit controls come from
// Debian's libjs-three, served by footpoint under /ui/.
(function () {
  'use strict';

  const $ = (id) => document.getElementById(id);
  const TWO_PI = 6.283185307179586;
  const PI = 3.141592653589793;

  // ---- presets: the papers' examples and a few classic shapes ------------------------------------
  // The NURBS circle's control polygon (a square's corners and midpoints) and the half circle of a
  // sphere's meridian (rho, z), with the corners' weight √2/2 ([PieglTiller] sec. 7.5).
  const HALF_ROOT2 = Math.SQRT1_2;
  const CIRCLE = [[1, 0], [1, 1], [0, 1], [-1, 1], [-1, 0], [-1, -1], [0, -1], [1, -1], [1, 0]];
  const HALF = [[0, -1], [1, -1], [1, 0], [1, 1], [0, 1]];
  const PRESETS = [
    {
      name: 'GSA paper, Example 1: Table 5 (GSA from (1, 2))',
      geometry: {type: 'parametric_surface', x: 'u+v', y: 'sin(u)+2*cos(v)', z: 'sin(u+v)',
                 domain: {u: [-3, 3], v: [-3, 3]}},
      points: [[1, 2, 2]], method: 'gsa', options: {initial: [1, 2], trace: true},
    },
    {
      name: 'GSA paper, Example 1: Table 4 (first order from (1, 2))',
      geometry: {type: 'parametric_surface', x: 'u+v', y: 'sin(u)+2*cos(v)', z: 'sin(u+v)',
                 domain: {u: [-3, 3], v: [-3, 3]}},
      points: [[1, 2, 2]], method: 'first_order', options: {initial: [1, 2], trace: true},
    },
    {
      name: 'Hybrid paper, Example 1: every local minimum',
      geometry: {type: 'parametric_surface', x: 'u+2*v', y: 'cos(u+v)', z: 'sin(u+v)',
                 domain: {u: [-2, 2], v: [-2, 2]}},
      points: [[0.3, 0.5, 1], [2, -1.5, 0.5]], method: 'auto', options: {all_minima: true},
    },
    {
      name: 'Hybrid paper, counterexample C3 (hybrid from (1, 1))',
      geometry: {type: 'parametric_surface', x: 'u', y: 'v', z: 'cos(u+v)', domain: {u: [0, 2], v: [0, 2]}},
      points: [[4, 5, 6]], method: 'hybrid', options: {initial: [1, 1], trace: true},
    },
    {
      name: 'Torus',
      geometry: {type: 'parametric_surface', x: '(R+r*cos(v))*cos(u)', y: '(R+r*cos(v))*sin(u)',
                 z: 'r*sin(v)', domain: {u: [0, TWO_PI], v: [0, TWO_PI]}, constants: {R: 2, r: 0.6}},
      points: [[3.2, 0.8, 1.2], [0.5, 0.3, 0.9], [-1.5, -2.4, -0.9]], method: 'auto', options: {all_minima: true},
    },
    {
      name: 'Sphere',
      geometry: {type: 'parametric_surface', x: 'sin(u)*cos(v)', y: 'sin(u)*sin(v)', z: 'cos(u)',
                 domain: {u: [0, PI], v: [0, TWO_PI]}},
      points: [[1.2, 0.9, 0.7], [0.1, 0.2, 0.3]], method: 'auto', options: {},
    },
    {
      name: 'Helix',
      geometry: {type: 'parametric_curve', x: 'cos(t)', y: 'sin(t)', z: 't/4', domain: {t: [0, 2 * TWO_PI]}},
      points: [[2, 0.5, 1], [0, 0, 2]], method: 'auto', options: {all_minima: true},
    },
    {
      name: "Viviani's curve (sphere and cylinder)",
      geometry: {type: 'implicit_curve', equations: ['x^2+y^2+z^2-4', '(x-1)^2+y^2-1'],
                 domain: {x: [-2.5, 2.5], y: [-2.5, 2.5], z: [-2.5, 2.5]}},
      points: [[2, 1, 1], [0, 0, 3], [1, -1.5, -0.5]], method: 'auto', options: {all_minima: true},
    },
    {
      name: 'Spatial-curve paper, Example 1 (Algorithm 4)',
      geometry: {type: 'implicit_curve', equations: ['x^2/9+y^2/16+z^2/9-1', 'x^2+y^2-4*z'],
                 domain: {x: [-5, 5], y: [-5, 5], z: [-5, 5]}},
      points: [[2, 3, 3]], method: 'complete', options: {initial: [1.9, 2.9, 2.9], trace: true},
    },
    {
      name: 'Lemniscate (planar implicit curve, a singular point)',
      geometry: {type: 'implicit_curve', equations: ['(x^2+y^2)^2-2*(x^2-y^2)'],
                 domain: {x: [-2, 2], y: [-1.5, 1.5]}},
      points: [[0.3, 0.8], [1.6, 0.1], [-0.9, -0.7]], method: 'auto', options: {all_minima: true},
    },
    {
      name: 'Torus as f(x, y, z) = 0 (implicit surface)',
      geometry: {type: 'implicit_surface', equation: '(x^2+y^2+z^2+R^2-r^2)^2-4*R^2*(x^2+y^2)',
                 domain: {x: [-3, 3], y: [-3, 3], z: [-1, 1]}, constants: {R: 2, r: 0.6}},
      points: [[3.2, 0.8, 0.5], [0.5, 0.3, 0.4], [-1.5, -2.4, -0.9]], method: 'auto', options: {},
    },
    {
      name: 'Cone clipped at its apex (implicit surface, a singular point)',
      geometry: {type: 'implicit_surface', equation: 'x^2+y^2-z^2', domain: {x: [-1, 1], y: [-1, 1], z: [0, 1]}},
      points: [[0, 0, -1], [0.5, 0.2, 0.8], [1.5, 0.5, 0.3]], method: 'auto', options: {},
    },
    {
      name: 'NURBS circle (degree 2, nine control points)',
      geometry: {type: 'bspline_curve', degree: 2, knots: [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1],
                 control_points: [[2, 0], [2, 2], [0, 2], [-2, 2], [-2, 0], [-2, -2], [0, -2], [2, -2], [2, 0]],
                 weights: [1, HALF_ROOT2, 1, HALF_ROOT2, 1, HALF_ROOT2, 1, HALF_ROOT2, 1]},
      points: [[3, 1], [0.5, 0.2], [-1, -3]], method: 'auto', options: {},
    },
    {
      name: 'Bicubic B-spline patch (NURBS surface)',
      geometry: {type: 'bspline_surface', degree: [3, 3],
                 knots: {u: [0, 0, 0, 0, 1, 2, 2, 2, 2], v: [0, 0, 0, 0, 1, 2, 2, 2, 2]},
                 control_points: [0, 1, 2, 3, 4].map((i) => [0, 1, 2, 3, 4].map((j) =>
                   [i, j, [[0, 0.5, 0, 0.5, 0], [0.5, 1.5, 1, 1.5, 0.5], [0, 1, 2, 1, 0], [0.5, 1.5, 1, 1.5, 0.5],
                           [0, 0.5, 0, 0.5, 0]][i][j]]))},
      points: [[2, 2, 3], [0.5, 3.5, 1.5], [5, -1, 0]], method: 'auto', options: {all_minima: true},
    },
    {
      name: 'Rational sphere (NURBS surface, 9 x 5 control points)',
      geometry: {type: 'bspline_surface', degree: [2, 2],
                 knots: {u: [0, 0, 0, 0.25, 0.25, 0.5, 0.5, 0.75, 0.75, 1, 1, 1], v: [0, 0, 0, 0.5, 0.5, 1, 1, 1]},
                 control_points: CIRCLE.map(([cx, cy]) => HALF.map(([r, z]) => [cx * r, cy * r, z])),
                 weights: CIRCLE.map((c, i) => HALF.map((h, j) => (i % 2 ? HALF_ROOT2 : 1) * (j % 2 ? HALF_ROOT2 : 1)))},
      points: [[1.2, 0.9, 0.7], [0.1, 0.2, 0.3], [0, 0, 1.5]], method: 'auto', options: {},
    },
    {
      name: 'Ellipse (planar parametric curve)',
      geometry: {type: 'parametric_curve', x: 'a*cos(t)', y: 'b*sin(t)', domain: {t: [0, TWO_PI]},
                 constants: {a: 3, b: 2}},
      points: [[1, 1], [4, 1.5], [0, 0.2]], method: 'auto', options: {all_minima: true},
    },
  ];

  // The formula fields and domain names of each type; optional ones may stay empty (a planar curve).
  const TYPES = {
    parametric_surface: {
      formulas: [{field: 'x', label: 'x(u, v)'}, {field: 'y', label: 'y(u, v)'}, {field: 'z', label: 'z(u, v)'}],
      domain: ['u', 'v'], resolution: 96,
    },
    parametric_curve: {
      formulas: [{field: 'x', label: 'x(t)'}, {field: 'y', label: 'y(t)'},
                 {field: 'z', label: 'z(t)', optional: true}],
      domain: ['t'], resolution: 512,
    },
    implicit_curve: {
      formulas: [{field: 'equations[0]', label: 'f₁ = 0'}, {field: 'equations[1]', label: 'f₂ = 0', optional: true}],
      domain: ['x', 'y', 'z'], resolution: 512,
    },
    implicit_surface: {
      formulas: [{field: 'equation', label: 'f(x, y, z) = 0'}],
      domain: ['x', 'y', 'z'], resolution: 48,
    },
    // B-splines: the net as JSON (degree, knots, control_points, weights), no formulas or domain.
    bspline_surface: {formulas: [], domain: [], net: true, resolution: 64},
    bspline_curve: {formulas: [], domain: [], net: true, resolution: 256},
  };
  const NET_MEMBERS = ['degree', 'knots', 'control_points', 'weights'];
  // A net member's field in an API error ("control_points[1][2]", "knots.u").
  const isNetField = (field) => NET_MEMBERS.some((m) => field === m || field.startsWith(m + '[') || field.startsWith(m + '.'));

  const state = {
    methods: {},        // type -> [{name, description, paper}] from GET /v1/methods
    definition: null,   // the definition the shown geometry was posted with
    geometry: null,     // POST /v1/geometries' answer
    mesh: null,         // GET .../mesh's answer
    grid: null,         // a surface mesh's parameter grid (for drawing iterates)
    request: null,      // the last projection request: {path, body}
    points: [],
    results: [],
    selected: 0,
    busy: 0,
  };

  // ---- the API ---------------------------------------------------------------------------------
  async function api(method, path, body) {
    const init = {method, headers: {}};
    if (body !== undefined) {
      init.headers['Content-Type'] = 'application/json';
      init.body = JSON.stringify(body);
    }
    const started = performance.now();
    const response = await fetch(path, init);
    const text = await response.text();
    let json = null;
    if (text && (response.headers.get('Content-Type') || '').startsWith('application/json')) json = JSON.parse(text);
    // The request's time on the network (resource timing), not the page's own work meanwhile.
    const entries = performance.getEntriesByName(new URL(path, window.location.href).href);
    const entry = entries[entries.length - 1];
    const ms = entry && entry.responseEnd > 0 ? entry.responseEnd - entry.startTime : performance.now() - started;
    performance.clearResourceTimings();
    return {status: response.status, ok: response.ok, json, text, ms};
  }

  // An API error as an Error carrying the JSON error object.
  function apiError(answer) {
    const e = answer.json && answer.json.error ? answer.json.error : {code: 'http_' + answer.status, message: answer.text};
    const error = new Error(e.message);
    error.api = e;
    return error;
  }

  // ---- numbers ---------------------------------------------------------------------------------
  // A number field: a JavaScript number, or a multiple of pi ("pi", "2*pi", "-pi/2").
  function parseNumber(text) {
    const s = String(text).trim().toLowerCase();
    if (s === '') return NaN;
    const m = /^([-+]?(?:\d+\.?\d*|\.\d+)?)\s*\*?\s*pi(?:\s*\/\s*(\d+\.?\d*))?$/.exec(s);
    if (m) {
      const factor = m[1] === '' || m[1] === '+' ? 1 : m[1] === '-' ? -1 : Number(m[1]);
      return factor * PI / (m[2] ? Number(m[2]) : 1);
    }
    return /^[-+]?(\d+\.?\d*|\.\d+)(e[-+]?\d+)?$/.test(s) ? Number(s) : NaN;
  }
  const parseList = (text) => String(text).split(/[\s,;]+/).filter((s) => s !== '').map(parseNumber);
  const short = (x, digits = 7) => (x === null || x === undefined ? '—' : Number.isInteger(x) ? String(x)
                                    : String(Number(x.toPrecision(digits))));
  const vector = (v, digits) => (v ? '(' + v.map((x) => short(x, digits)).join(', ') + ')' : '—');
  const full = (v) => (Array.isArray(v) ? '(' + v.map(String).join(', ') + ')' : String(v));

  // ---- the form --------------------------------------------------------------------------------
  function buildForm(type) {
    const spec = TYPES[type];
    const formulas = $('formulas');
    formulas.textContent = '';
    $('constants').closest('label').hidden = !!spec.net;
    if (spec.net) {
      const box = document.createElement('div');
      box.className = 'formula';
      const label = document.createElement('label');
      const name = document.createElement('span');
      name.className = 'name';
      name.textContent = 'net (JSON)';
      const text = document.createElement('textarea');
      text.id = 'net';
      text.rows = 6;
      text.spellcheck = false;
      text.placeholder = '{"degree": ..., "knots": ..., "control_points": ..., "weights": ...}';
      label.append(name, text);
      const error = document.createElement('div');
      error.className = 'field-error';
      error.hidden = true;
      error.dataset.errorFor = 'net';
      box.append(label, error);
      formulas.append(box);
    }
    for (const f of spec.formulas) {
      const box = document.createElement('div');
      box.className = 'formula';
      const label = document.createElement('label');
      const name = document.createElement('span');
      name.className = 'name';
      name.textContent = f.label;
      const input = document.createElement('input');
      input.spellcheck = false;
      input.dataset.field = f.field;
      input.placeholder = f.optional ? 'empty: planar' : '';
      input.addEventListener('keydown', (e) => { if (e.key === 'Enter') showGeometry(); });
      label.append(name, input);
      const error = document.createElement('div');
      error.className = 'field-error';
      error.hidden = true;
      error.dataset.errorFor = f.field;
      box.append(label, error);
      formulas.append(box);
    }
    const domain = $('domain');
    domain.textContent = '';
    for (const name of spec.domain) {
      const label = document.createElement('span');
      label.textContent = name + ' ∈';
      const lo = document.createElement('input');
      const hi = document.createElement('input');
      lo.dataset.field = 'domain.' + name;
      hi.dataset.field = 'domain.' + name;
      lo.dataset.end = '0';
      hi.dataset.end = '1';
      lo.spellcheck = hi.spellcheck = false;
      domain.append(label, lo, hi);
    }
    const error = document.createElement('div');
    error.className = 'field-error';
    error.hidden = true;
    error.dataset.errorFor = 'domain';
    domain.append(error);
    $('resolution').value = spec.resolution;
  }

  function formulaInput(field) { return $('formulas').querySelector(`input[data-field="${field}"]`); }
  function domainInputs(name) { return $('domain').querySelectorAll(`input[data-field="domain.${name}"]`); }

  function fillForm(geometry) {
    $('type').value = geometry.type;
    buildForm(geometry.type);
    const spec = TYPES[geometry.type];
    if (spec.net) {
      const net = {};
      for (const m of NET_MEMBERS) if (geometry[m] !== undefined) net[m] = geometry[m];
      $('net').value = JSON.stringify(net);
      return;
    }
    for (const f of spec.formulas) {
      const m = /^equations\[(\d)\]$/.exec(f.field);
      formulaInput(f.field).value = (m ? (geometry.equations || [])[Number(m[1])] : geometry[f.field]) || '';
    }
    for (const name of spec.domain) {
      const [lo, hi] = domainInputs(name);
      const range = geometry.domain[name];
      lo.value = range ? String(range[0]) : '';
      hi.value = range ? String(range[1]) : '';
    }
    $('constants').value = Object.entries(geometry.constants || {}).map(([k, v]) => `${k}=${v}`).join(', ');
  }

  // The definition in the form, or throws an Error whose .api names the field.
  function readDefinition() {
    const type = $('type').value;
    const spec = TYPES[type];
    const def = {type};
    const fail = (field, message) => { const e = new Error(message); e.api = {code: 'invalid_input', message, field}; throw e; };
    if (spec.net) {
      let net;
      try {
        net = JSON.parse($('net').value);
      } catch (e) {
        fail('degree', 'net: not JSON (' + e.message + ')');
      }
      if (net === null || typeof net !== 'object' || Array.isArray(net)) fail('degree', 'net: a JSON object {"degree": ..., "knots": ..., ...}');
      return Object.assign(def, net);
    }
    let planar = false;
    for (const f of spec.formulas) {
      const text = formulaInput(f.field).value.trim();
      if (text === '' && f.optional) { planar = true; continue; }
      const m = /^equations\[(\d)\]$/.exec(f.field);
      if (m) (def.equations = def.equations || []).push(text);
      else def[f.field] = text;
    }
    def.domain = {};
    for (const name of spec.domain) {
      const [lo, hi] = domainInputs(name);
      if (type === 'implicit_curve' && name === 'z' && planar) continue;
      const a = parseNumber(lo.value), b = parseNumber(hi.value);
      if (!Number.isFinite(a) || !Number.isFinite(b)) fail('domain.' + name, `domain ${name}: two numbers, e.g. -1 and 1 (or 2*pi)`);
      def.domain[name] = [a, b];
    }
    const constants = $('constants').value.trim();
    if (constants !== '') {
      def.constants = {};
      for (const part of constants.split(/[,;\n]+/)) {
        if (part.trim() === '') continue;
        const m = /^\s*([A-Za-z_][A-Za-z0-9_]*)\s*=\s*(.+?)\s*$/.exec(part);
        const value = m ? parseNumber(m[2]) : NaN;
        if (!m || !Number.isFinite(value)) fail('constants', `constants: name=value pairs separated by commas, got '${part.trim()}'`);
        def.constants[m[1]] = value;
      }
    }
    return def;
  }

  function clearErrors() {
    for (const e of document.querySelectorAll('.field-error')) { e.hidden = true; e.textContent = ''; }
    for (const i of document.querySelectorAll('.invalid')) i.classList.remove('invalid');
  }

  // Shows an API error at its field: the message, and for a formula the text with the character at
  // `position` marked; the caret is put there too.
  function showError(error, fallbackBox) {
    const e = error.api || {code: 'error', message: String(error.message || error)};
    const field = (e.field || '').replace(/^geometry\./, '');
    let box = null, input = null;
    const formula = field && formulaInput(field);
    if (field && isNetField(field) && $('net')) {
      input = $('net');
      box = $('formulas').querySelector('[data-error-for="net"]');
    } else if (formula) {
      input = formula;
      box = $('formulas').querySelector(`[data-error-for="${field}"]`);
    } else if (field.startsWith('domain')) {
      const name = field.split(/[.[]/)[1];
      input = name ? domainInputs(name)[0] : null;
      box = $('domain').querySelector('[data-error-for="domain"]');
    } else if (field.startsWith('constants')) {
      input = $('constants');
      box = $('error-constants');
    }
    box = box || fallbackBox;
    box.textContent = '';
    const text = document.createElement('span');
    text.className = 'message';
    text.textContent = e.message;
    const code = document.createElement('code');
    code.className = 'code';
    code.textContent = ' ' + e.code;
    box.append(text, code);
    if (formula && Number.isInteger(e.position) && e.position >= 0) {
      const source = formula.value;
      const echo = document.createElement('span');
      echo.className = 'echo';
      const mark = document.createElement('mark');
      mark.dataset.position = String(e.position);
      if (e.position < source.length) {
        mark.textContent = source[e.position];
        echo.append(source.slice(0, e.position), mark, source.slice(e.position + 1));
      } else {
        mark.className = 'end';
        mark.textContent = '‸';
        echo.append(source, mark);
      }
      box.append(echo);
      formula.focus();
      formula.setSelectionRange(e.position, Math.min(source.length, e.position + 1));
    }
    if (input) input.classList.add('invalid');
    box.hidden = false;
  }

  function setStatus(text, isError) {
    const s = $('status');
    s.textContent = text;
    s.classList.toggle('error', Boolean(isError));
  }

  function busy(delta) {
    state.busy += delta;
    document.body.dataset.state = state.busy > 0 ? 'busy' : state.geometry ? 'ready' : 'error';
    $('show').disabled = $('project').disabled = state.busy > 0;
  }

  // ---- the scene -------------------------------------------------------------------------------
  const view = {};

  function initScene() {
    const canvas = $('canvas');
    view.renderer = new THREE.WebGLRenderer({canvas, antialias: true, alpha: true});
    view.renderer.setPixelRatio(window.devicePixelRatio || 1);
    view.scene = new THREE.Scene();
    view.camera = new THREE.PerspectiveCamera(38, 1, 0.01, 1000);
    view.camera.up.set(0, 0, 1);
    view.camera.position.set(4, -6, 4);
    view.scene.add(view.camera);
    view.scene.add(new THREE.HemisphereLight(0xffffff, 0x7a8699, 0.55));
    const key = new THREE.DirectionalLight(0xffffff, 0.75);
    key.position.set(0.6, 0.4, 1);
    view.camera.add(key);
    view.controls = new THREE.OrbitControls(view.camera, canvas);
    view.controls.addEventListener('change', render);
    view.geometryGroup = new THREE.Group();
    view.pointsGroup = new THREE.Group();
    view.cloudGroup = new THREE.Group();
    view.scene.add(view.geometryGroup, view.pointsGroup, view.cloudGroup);
    new ResizeObserver(resize).observe($('canvas-box'));
    resize();
    let down = null;
    canvas.addEventListener('pointerdown', (e) => { down = {x: e.clientX, y: e.clientY}; });
    canvas.addEventListener('pointerup', (e) => {
      if (down && Math.hypot(e.clientX - down.x, e.clientY - down.y) < 4) pick(e);
      down = null;
    });
  }

  function resize() {
    const box = $('canvas-box');
    const w = Math.max(1, box.clientWidth), h = Math.max(1, box.clientHeight);
    view.renderer.setSize(w, h, false);
    view.camera.aspect = w / h;
    view.camera.updateProjectionMatrix();
    render();
  }

  let renderPending = false;
  function render() {
    if (renderPending || !view.renderer) return;
    renderPending = true;
    requestAnimationFrame(() => {
      renderPending = false;
      view.renderer.render(view.scene, view.camera);
      if (state.mesh && !document.body.dataset.firstRenderMs)
        document.body.dataset.firstRenderMs = String(Math.round(performance.now()));
    });
  }

  function clearGroup(group) {
    for (const child of [...group.children]) {
      group.remove(child);
      child.traverse((o) => {
        if (o.geometry) o.geometry.dispose();
        if (o.material) o.material.dispose();
      });
    }
  }

  function bufferGeometry(positions, normals, index) {
    const g = new THREE.BufferGeometry();
    g.setAttribute('position', new THREE.BufferAttribute(positions, 3));
    if (normals) g.setAttribute('normal', new THREE.BufferAttribute(normals, 3));
    if (index) g.setIndex(new THREE.BufferAttribute(index, 1));
    g.computeBoundingSphere();
    return g;
  }

  // A surface mesh's vertices on their parameter grid: the sorted u and v lines and the vertex at
  // each crossing (-1 where the mesh left it out).
  function parameterGrid(mesh) {
    const p = mesh.parameters;
    const n = p.length / 2;
    const us = [...new Set(Array.from({length: n}, (_, k) => p[2 * k]))].sort((a, b) => a - b);
    const vs = [...new Set(Array.from({length: n}, (_, k) => p[2 * k + 1]))].sort((a, b) => a - b);
    const iu = new Map(us.map((u, i) => [u, i])), iv = new Map(vs.map((v, j) => [v, j]));
    const at = new Int32Array(us.length * vs.length).fill(-1);
    for (let k = 0; k < n; ++k) at[iu.get(p[2 * k]) * vs.length + iv.get(p[2 * k + 1])] = k;
    return {us, vs, at};
  }

  // s(u, v) interpolated bilinearly on the mesh's grid (null outside the domain or its mesh).
  function surfacePoint(u, v) {
    const g = state.grid, vtx = state.mesh.vertices;
    const cell = (lines, x) => {
      if (!(x >= lines[0] && x <= lines[lines.length - 1])) return -1;
      let lo = 0, hi = lines.length - 1;
      while (hi - lo > 1) { const mid = (lo + hi) >> 1; if (lines[mid] <= x) lo = mid; else hi = mid; }
      return lo;
    };
    const i = cell(g.us, u), j = cell(g.vs, v);
    if (i < 0 || j < 0) return null;
    const a = (u - g.us[i]) / (g.us[i + 1] - g.us[i]), b = (v - g.vs[j]) / (g.vs[j + 1] - g.vs[j]);
    const corners = [[i, j, (1 - a) * (1 - b)], [i + 1, j, a * (1 - b)], [i, j + 1, (1 - a) * b], [i + 1, j + 1, a * b]];
    const out = [0, 0, 0];
    let weight = 0;
    for (const [ci, cj, w] of corners) {
      const k = g.at[ci * g.vs.length + cj];
      if (k < 0) continue;
      for (let c = 0; c < 3; ++c) out[c] += w * vtx[3 * k + c];
      weight += w;
    }
    return weight > 0 ? out.map((x) => x / weight) : null;
  }

  // c(t) interpolated linearly along the polyline of a parametric curve's mesh.
  function curvePoint(t) {
    const p = state.mesh.parameters, vtx = state.mesh.vertices;
    for (const line of state.mesh.polylines) {
      const idx = line.vertices;
      for (let k = 0; k + 1 < idx.length; ++k) {
        const t0 = p[idx[k]], t1 = p[idx[k + 1]];
        if (t >= Math.min(t0, t1) && t <= Math.max(t0, t1)) {
          const a = t1 === t0 ? 0 : (t - t0) / (t1 - t0);
          return [0, 1, 2].map((c) => (1 - a) * vtx[3 * idx[k] + c] + a * vtx[3 * idx[k + 1] + c]);
        }
      }
    }
    return null;
  }

  // A tube along a polyline, framed by parallel transport of the tangents.
  function tube(mesh, line, radius) {
    const vtx = mesh.vertices, tan = mesh.tangents;
    const idx = line.closed ? [...line.vertices, line.vertices[0]] : line.vertices;
    const sides = 10;
    const n = idx.length;
    const positions = new Float32Array(n * sides * 3), normals = new Float32Array(n * sides * 3);
    const point = (k) => new THREE.Vector3(vtx[3 * idx[k]], vtx[3 * idx[k] + 1], vtx[3 * idx[k] + 2]);
    const tangent = (k) => {
      const t = new THREE.Vector3(tan[3 * idx[k]], tan[3 * idx[k] + 1], tan[3 * idx[k] + 2]);
      if (t.lengthSq() > 0) return t;
      const a = point(Math.max(0, k - 1)), b = point(Math.min(n - 1, k + 1));
      return b.sub(a).normalize();
    };
    let t = tangent(0);
    let normal = new THREE.Vector3(0, 0, 1);
    if (Math.abs(normal.dot(t)) > 0.9) normal.set(1, 0, 0);
    normal.sub(t.clone().multiplyScalar(normal.dot(t))).normalize();
    for (let k = 0; k < n; ++k) {
      const tk = tangent(k);
      normal.sub(tk.clone().multiplyScalar(normal.dot(tk)));
      if (normal.lengthSq() < 1e-12) normal = new THREE.Vector3(1, 0, 0).cross(tk);
      normal.normalize();
      const binormal = tk.clone().cross(normal);
      const c = point(k);
      for (let s = 0; s < sides; ++s) {
        const angle = (2 * Math.PI * s) / sides;
        const dir = normal.clone().multiplyScalar(Math.cos(angle)).addScaledVector(binormal, Math.sin(angle));
        const o = 3 * (k * sides + s);
        positions[o] = c.x + radius * dir.x; positions[o + 1] = c.y + radius * dir.y; positions[o + 2] = c.z + radius * dir.z;
        normals[o] = dir.x; normals[o + 1] = dir.y; normals[o + 2] = dir.z;
      }
    }
    const index = new Uint32Array((n - 1) * sides * 6);
    let q = 0;
    for (let k = 0; k + 1 < n; ++k)
      for (let s = 0; s < sides; ++s) {
        const a = k * sides + s, b = k * sides + (s + 1) % sides, c = a + sides, d = b + sides;
        index[q++] = a; index[q++] = b; index[q++] = d;
        index[q++] = a; index[q++] = d; index[q++] = c;
      }
    return bufferGeometry(positions, normals, index);
  }

  // Markers (points, foot points, minima, iterates) and their segments: solid where they are in
  // front, and a faint copy drawn over the geometry where they are behind it.
  function withGhost(make) {
    const group = new THREE.Group();
    const solid = make(), ghost = make();
    ghost.material.transparent = true;
    ghost.material.opacity *= 0.3;
    ghost.material.depthTest = false;
    ghost.material.depthWrite = false;
    ghost.renderOrder = 10;
    group.add(solid, ghost);
    return group;
  }

  function sphere(at, radius, color, opacity = 1, ghost = true) {
    const make = () => {
      const m = new THREE.Mesh(new THREE.SphereBufferGeometry(radius, 18, 12),
                               new THREE.MeshPhongMaterial({color, shininess: 60, transparent: opacity < 1, opacity}));
      m.position.set(at[0], at[1], at[2] || 0);
      return m;
    };
    return ghost ? withGhost(make) : make();
  }

  function polyline(points, color, opacity = 1) {
    const positions = new Float32Array(points.length * 3);
    points.forEach((p, k) => { positions[3 * k] = p[0]; positions[3 * k + 1] = p[1]; positions[3 * k + 2] = p[2] || 0; });
    return withGhost(() => new THREE.Line(bufferGeometry(positions),
                                          new THREE.LineBasicMaterial({color, transparent: opacity < 1, opacity})));
  }

  // Draws the mesh and fits the camera to it.
  function showMesh(mesh) {
    clearGroup(view.geometryGroup);
    const vertices = new Float32Array(mesh.vertices);
    const box = new THREE.Box3().setFromArray(vertices);
    const size = box.getSize(new THREE.Vector3());
    const center = box.getCenter(new THREE.Vector3());
    const diagonal = Math.max(size.length(), 1e-9);
    view.scale = diagonal;
    const planar = state.geometry.point_dim === 2;
    view.pickables = [];
    if (mesh.triangles.length > 0) {
      const g = bufferGeometry(vertices, new Float32Array(mesh.normals), new Uint32Array(mesh.triangles));
      const common = {shininess: 35, specular: 0x222222, polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1};
      const front = new THREE.Mesh(g, new THREE.MeshPhongMaterial({...common, color: 0x5b8fe6, side: THREE.FrontSide}));
      const back = new THREE.Mesh(g, new THREE.MeshPhongMaterial({...common, color: 0xf0c36d, side: THREE.BackSide}));
      view.geometryGroup.add(front, back);
      view.pickables.push(front, back);
      if (state.grid) view.geometryGroup.add(parameterLines(mesh, state.grid));  // none on an implicit surface
    }
    const radius = 0.0045 * diagonal;
    for (const line of mesh.polylines) {
      const t = new THREE.Mesh(tube(mesh, line, radius), new THREE.MeshPhongMaterial({color: 0x2f6fdf, shininess: 50}));
      view.geometryGroup.add(t);
      view.pickables.push(t);
    }
    for (const k of mesh.singular_points)
      view.geometryGroup.add(sphere([mesh.vertices[3 * k], mesh.vertices[3 * k + 1], mesh.vertices[3 * k + 2]],
                                    3 * radius, 0xd81b60, 1));
    // The plane clicks land on: z = 0 for planar curves, else the floor under the geometry.
    const floorZ = planar ? 0 : box.min.z - 0.02 * diagonal;
    const extent = 1.15 * Math.max(size.x, size.y, 0.3 * diagonal);
    const plane = new THREE.Mesh(new THREE.PlaneBufferGeometry(extent, extent),
                                 new THREE.MeshBasicMaterial({color: 0x9aa5b8, transparent: true, opacity: 0.12,
                                                              side: THREE.DoubleSide, depthWrite: false}));
    plane.position.set(center.x, center.y, floorZ);
    const grid = new THREE.GridHelper(extent, 16, 0x9aa5b8, 0xc5ccd8);
    grid.rotation.x = Math.PI / 2;
    grid.position.copy(plane.position);
    grid.material.transparent = true;
    grid.material.opacity = 0.55;
    view.geometryGroup.add(plane, grid);
    view.plane = plane;
    view.pickables.push(plane);
    // The view takes in the points of the form too, when they read.
    let points = [];
    try {
      points = readPoints().flatMap((p) => [p[0], p[1], p[2] || 0]);
    } catch (e) { /* shown when projecting */ }
    fitCamera([...mesh.vertices, ...points], planar);
  }

  // Every few parameter lines of a surface, drawn over it.
  function parameterLines(mesh, grid) {
    const vtx = mesh.vertices;
    const segments = [];
    const every = (n) => Math.max(1, Math.round(n / 16));
    const add = (k0, k1) => {
      if (k0 < 0 || k1 < 0) return;
      segments.push(vtx[3 * k0], vtx[3 * k0 + 1], vtx[3 * k0 + 2], vtx[3 * k1], vtx[3 * k1 + 1], vtx[3 * k1 + 2]);
    };
    const nu = grid.us.length, nv = grid.vs.length;
    for (let i = 0; i < nu; i += every(nu)) for (let j = 0; j + 1 < nv; ++j) add(grid.at[i * nv + j], grid.at[i * nv + j + 1]);
    for (let j = 0; j < nv; j += every(nv)) for (let i = 0; i + 1 < nu; ++i) add(grid.at[i * nv + j], grid.at[(i + 1) * nv + j]);
    return new THREE.LineSegments(bufferGeometry(new Float32Array(segments)),
                                  new THREE.LineBasicMaterial({color: 0x1d2433, transparent: true, opacity: 0.13}));
  }

  // Puts the camera on `direction` from the centre of `points` (flat x, y, z), as near as keeps
  // all of them in view.
  function fitCamera(points, planar) {
    const box = new THREE.Box3().setFromArray(points);
    const center = box.getCenter(new THREE.Vector3());
    const direction = (planar ? new THREE.Vector3(0, -0.5, 1) : new THREE.Vector3(1.25, -1.7, 1.05)).normalize();
    const camera = view.camera;
    const right = new THREE.Vector3().crossVectors(camera.up, direction).normalize();
    const up = new THREE.Vector3().crossVectors(direction, right);
    const tanV = Math.tan((camera.fov * Math.PI) / 360), tanH = tanV * camera.aspect;
    const step = Math.max(1, Math.floor(points.length / 3 / 4000));
    const x = new THREE.Vector3();
    let distance = 1e-9;
    for (let k = 0; 3 * k < points.length; k += step) {
      x.set(points[3 * k], points[3 * k + 1], points[3 * k + 2]).sub(center);
      const ahead = x.dot(direction);
      distance = Math.max(distance, ahead + Math.abs(x.dot(right)) / tanH, ahead + Math.abs(x.dot(up)) / tanV);
    }
    distance *= 1.1;
    camera.position.copy(center).addScaledVector(direction, distance);
    camera.near = distance / 100;
    camera.far = distance * 100;
    camera.updateProjectionMatrix();
    view.controls.target.copy(center);
    view.controls.update();
    render();
  }

  // The iterates of a result's trace, summed back from where the solve ended (its parameters, or
  // for an implicit curve its foot point): the trace holds the increments of the final local solve.
  // Parameters are mapped into space on the mesh; the last iterate is the foot point itself.
  function iterates(result) {
    const kind = state.geometry.num_params;
    const last = kind > 0 ? result.parameters : result.foot_point;
    if (!result.trace || !last || !result.foot_point) return null;
    let x = last.slice();
    const list = [x];
    for (let k = result.trace.length - 1; k >= 0; --k) {
      const step = result.trace[k];
      x = x.map((xi, c) => xi - step[c]);
      list.push(x);
    }
    list.reverse();
    return list.map((q, k) => ({
      at: q,
      point: k === list.length - 1 ? result.foot_point
             : kind === 2 ? surfacePoint(q[0], q[1]) : kind === 1 ? curvePoint(q[0]) : q,
    }));
  }

  function showResults() {
    clearGroup(view.pointsGroup);
    if (!state.mesh) return;
    const r = 0.01 * view.scale;
    state.points.forEach((p, i) => {
      view.pointsGroup.add(sphere(p, r * (i === state.selected ? 1.35 : 1), 0xe4572e, 1));
      const result = state.results[i];
      if (!result) return;
      for (const m of result.minima || [])
        if (m.foot_point && m.distance !== result.distance)
          view.pointsGroup.add(sphere(m.foot_point, 0.8 * r, 0xf2a541, 0.95));
      if (result.foot_point) {
        view.pointsGroup.add(sphere(result.foot_point, r * (i === state.selected ? 1.35 : 1), 0x1a9e5c, 1));
        view.pointsGroup.add(polyline([p, result.foot_point], 0x1d2433, 0.85));
      }
      const path = iterates(result);
      if (path) {
        const known = path.filter((q) => q.point);
        if (known.length > 1) view.pointsGroup.add(polyline(known.map((q) => q.point), 0x8e44ad));
        for (const q of known) view.pointsGroup.add(sphere(q.point, 0.45 * r, 0x8e44ad, 1));
      }
    });
    render();
  }

  // A click on the geometry adds a point off it along the normal (towards the viewer); on the
  // plane, the point on the plane.
  function pick(event) {
    if (!$('click-add').checked || !view.pickables || state.busy) return;
    const rect = $('canvas').getBoundingClientRect();
    const ndc = new THREE.Vector2(((event.clientX - rect.left) / rect.width) * 2 - 1,
                                  -((event.clientY - rect.top) / rect.height) * 2 + 1);
    const ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, view.camera);
    const hit = ray.intersectObjects(view.pickables, false)[0];
    if (!hit) return;
    const p = hit.point.clone();
    if (hit.object !== view.plane && hit.face) {
      const n = hit.face.normal.clone().transformDirection(hit.object.matrixWorld);
      if (n.dot(ray.ray.direction) > 0) n.negate();
      p.addScaledVector(n, parseNumber($('click-offset').value) || 0);
    }
    const coords = state.geometry.point_dim === 2 ? [p.x, p.y] : [p.x, p.y, p.z];
    const text = $('points').value.trim();
    $('points').value = (text ? text + '\n' : '') + coords.map((c) => short(c, 6)).join(', ');
    project();
  }

  // ---- results ---------------------------------------------------------------------------------
  function fillTable() {
    const body = $('results').querySelector('tbody');
    body.textContent = '';
    state.results.forEach((result, i) => {
      const row = document.createElement('tr');
      row.dataset.index = String(i);
      if (i === state.selected) row.className = 'selected';
      const d = result.diagnostics || {};
      const cells = [
        [String(i + 1)],
        [vector(state.points[i], 6), full(state.points[i])],
        [vector(result.foot_point, 6), result.foot_point && full(result.foot_point)],
        [vector(result.parameters, 6), result.parameters && full(result.parameters)],
        [result.distance === null ? '—' : String(result.distance)],
        [null],
        [d.location || '—'],
        [String(d.iterations)],
        [d.residual === null || d.residual === undefined ? '—' : d.residual.toExponential(2)],
      ];
      cells.forEach(([text, title], c) => {
        const td = document.createElement('td');
        if (c === 5) {
          const badge = document.createElement('span');
          badge.className = 'status ' + (d.status === 'converged' ? 'converged' : 'other');
          badge.textContent = d.status + (d.certificate && d.certificate.certified === true ? ' ✓ certified' : '');
          td.append(badge);
        } else {
          td.textContent = text;
        }
        if (title) td.title = title;
        if (c === 4) { td.className = 'distance'; td.dataset.value = text; }
        row.append(td);
      });
      row.addEventListener('click', () => { state.selected = i; fillTable(); showResults(); });
      body.append(row);
    });
    fillDetails();
  }

  function card(title) {
    const c = document.createElement('div');
    c.className = 'card';
    const h = document.createElement('h3');
    h.textContent = title;
    c.append(h);
    return c;
  }

  // Every field of an object as a definition list (nested objects as "a.b").
  function fields(object) {
    const dl = document.createElement('dl');
    const add = (prefix, value) => {
      if (value && typeof value === 'object' && !Array.isArray(value)) {
        for (const [k, v] of Object.entries(value)) add(prefix ? prefix + '.' + k : k, v);
        return;
      }
      const dt = document.createElement('dt');
      dt.textContent = prefix;
      const dd = document.createElement('dd');
      dd.textContent = Array.isArray(value) ? full(value) : String(value);
      dd.dataset.field = prefix;
      dl.append(dt, dd);
    };
    add('', object);
    return dl;
  }

  function smallTable(headers, rows) {
    const t = document.createElement('table');
    const head = document.createElement('tr');
    for (const h of headers) { const th = document.createElement('th'); th.textContent = h; head.append(th); }
    t.append(head);
    for (const r of rows) {
      const tr = document.createElement('tr');
      for (const x of r) { const td = document.createElement('td'); td.textContent = x; tr.append(td); }
      t.append(tr);
    }
    return t;
  }

  function fillDetails() {
    const box = $('details');
    box.textContent = '';
    const result = state.results[state.selected];
    if (!result) return;
    const answer = card(`Point ${state.selected + 1}`);
    answer.append(fields({point: state.points[state.selected], foot_point: result.foot_point,
                          ...(result.parameters ? {parameters: result.parameters} : {}), distance: result.distance}));
    const diagnostics = card('Diagnostics');
    diagnostics.id = 'diagnostics';
    diagnostics.append(fields(result.diagnostics));
    box.append(answer, diagnostics);
    if (result.minima) {
      const c = card(`All minima (${result.minima.length})`);
      c.append(smallTable(['distance', 'foot point', 'parameters', 'location'],
                          result.minima.map((m) => [short(m.distance, 10), vector(m.foot_point), vector(m.parameters), m.location])));
      box.append(c);
    }
    if (result.trace) {
      const path = iterates(result);
      const names = state.geometry.num_params === 2 ? ['Δu', 'Δv'] : state.geometry.num_params === 1 ? ['Δt']
                  : state.geometry.point_dim === 2 ? ['Δx', 'Δy'] : ['Δx', 'Δy', 'Δz'];
      const c = card(`Trace (${result.trace.length} iterations)`);
      c.append(smallTable(['k', ...names, ...(path ? ['iterate'] : [])],
                          result.trace.map((s, k) => [String(k + 1), ...s.slice(0, names.length).map((x) => x.toExponential(3)),
                                                      ...(path ? [vector(path[k + 1].at, 8)] : [])])));
      box.append(c);
    }
  }

  function curl() {
    if (!state.request) return '';
    const origin = window.location.origin;
    const quote = (s) => "'" + s.replace(/'/g, "'\\''") + "'";
    const post = (path, body) => `curl -s ${origin}${path} -H 'Content-Type: application/json' -d ${quote(JSON.stringify(body))}`;
    return post('/v1/geometries', state.definition) + '\n' + post(state.request.path, state.request.body);
  }

  // ---- actions ---------------------------------------------------------------------------------
  async function postGeometry(def) {
    const answer = await api('POST', '/v1/geometries', def);
    if (!answer.ok) throw apiError(answer);
    return answer;
  }

  async function showGeometry() {
    clearErrors();
    busy(+1);
    try {
      const def = readDefinition();
      const created = await postGeometry(def);
      const g = created.json;
      const resolution = Math.max(2, Math.round(parseNumber($('resolution').value) || TYPES[def.type].resolution));
      const meshAnswer = await api('GET', `/v1/geometries/${g.geometry_id}/mesh?resolution=${resolution}`);
      if (!meshAnswer.ok) throw apiError(meshAnswer);
      removeCloud();  // its deviations were from the geometry shown before
      state.definition = def;
      state.geometry = g;
      state.mesh = meshAnswer.json;
      state.grid = state.mesh.triangles.length && state.mesh.parameters ? parameterGrid(state.mesh) : null;
      state.results = [];
      document.body.dataset.geometryId = g.geometry_id;
      $('download-obj').href = `/v1/geometries/${g.geometry_id}/mesh?resolution=${resolution}&format=obj`;
      $('download-json').href = `/v1/geometries/${g.geometry_id}/mesh?resolution=${resolution}`;
      const mesh = state.mesh;
      $('geometry-meta').textContent = `id ${g.geometry_id} · ${g.point_dim}-D · compiled in ${short(g.compile_ms, 3)} ms`;
      fillMethods();
      showMesh(mesh);
      const counts = mesh.triangles.length ? `${(mesh.vertices.length / 3).toLocaleString('en')} vertices, ${(mesh.triangles.length / 3).toLocaleString('en')} triangles`
                                           : `${mesh.polylines.length} piece${mesh.polylines.length === 1 ? '' : 's'}, ${(mesh.vertices.length / 3).toLocaleString('en')} vertices` +
                                             (mesh.singular_points.length ? `, ${mesh.singular_points.length} singular point${mesh.singular_points.length === 1 ? '' : 's'}` : '');
      setStatus(`mesh: ${counts} (${Math.round(meshAnswer.ms)} ms)`);
      showResults();
      fillTable();
      if ($('points').value.trim() !== '') await project(true);
    } catch (e) {
      showError(e, $('error-geometry'));
      setStatus(e.api ? e.api.code : 'error', true);
    } finally {
      busy(-1);
    }
  }

  function fillMethods() {
    const select = $('method');
    const keep = select.value;
    select.textContent = '';
    const known = state.methods[state.geometry.type] || [];
    for (const name of state.geometry.methods) {
      const info = known.find((m) => m.name === name) || {name, description: '', paper: ''};
      const o = document.createElement('option');
      o.value = name;
      o.textContent = name + (info.paper ? ' — ' + info.paper.split(' (')[0] : '');
      o.dataset.description = info.description + (info.paper ? ` [${info.paper}]` : '');
      select.append(o);
    }
    select.value = state.geometry.methods.includes(keep) ? keep : 'auto';
    describeMethod();
  }

  function describeMethod() {
    const o = $('method').selectedOptions[0];
    $('method-info').textContent = o ? o.dataset.description : '';
  }

  function readPoints() {
    const dim = state.geometry.point_dim;
    const points = [];
    $('points').value.split('\n').forEach((line, k) => {
      if (line.trim() === '') return;
      const p = parseList(line);
      if (p.length !== dim || !p.every(Number.isFinite)) {
        const e = new Error(`line ${k + 1}: ${dim} numbers, got '${line.trim()}'`);
        e.api = {code: 'invalid_point', message: e.message};
        throw e;
      }
      points.push(p);
    });
    return points;
  }

  function readOptions() {
    const options = {};
    const number = (id, name, integer) => {
      const text = $(id).value.trim();
      if (text === '') return;
      const x = parseNumber(text);
      if (!Number.isFinite(x) || (integer && !Number.isInteger(x))) {
        const e = new Error(`${name}: a number, got '${text}'`);
        e.api = {code: 'invalid_option', message: e.message, field: 'options.' + name};
        throw e;
      }
      options[name] = x;
    };
    const initial = $('opt-initial').value.trim();
    if (initial !== '') {
      const x = parseList(initial);
      if (!x.every(Number.isFinite)) {
        const e = new Error(`initial: numbers, got '${initial}'`);
        e.api = {code: 'invalid_option', message: e.message, field: 'options.initial'};
        throw e;
      }
      options.initial = x;
    }
    number('opt-tolerance', 'tolerance');
    number('opt-max-iterations', 'max_iterations', true);
    number('opt-max-distance', 'max_distance');
    if ($('opt-all-minima').checked) options.all_minima = true;
    if ($('opt-trace').checked) options.trace = true;
    return options;
  }

  async function project(nested) {
    if (!state.geometry) return;
    $('error-project').hidden = true;
    if (!nested) busy(+1);
    try {
      const points = readPoints();
      state.points = points;
      if (points.length === 0) {
        state.results = [];
        fillTable();
        showResults();
        return;
      }
      const body = {points};
      const method = $('method').value;
      if (method && method !== 'auto') body.method = method;
      const options = readOptions();
      if (Object.keys(options).length) body.options = options;
      const path = `/v1/geometries/${state.geometry.geometry_id}/project`;
      state.request = {path, body};
      let answer = await api('POST', path, body);
      if (answer.status === 404 && answer.json && answer.json.error.code === 'geometry_not_found') {
        await postGeometry(state.definition);  // evicted: post it again (same id) and retry
        answer = await api('POST', path, body);
      }
      if (!answer.ok) throw apiError(answer);
      state.results = answer.json.results;
      state.selected = Math.min(state.selected, state.results.length - 1);
      fillTable();
      showResults();
      if (!$('curl').hidden) $('curl').textContent = curl();
      const converged = answer.json.stats.converged;
      setStatus(`${points.length} point${points.length === 1 ? '' : 's'}, ${converged} converged · ` +
                `${short(answer.json.stats.elapsed_ms, 3)} ms in the solver, ${Math.round(answer.ms)} ms round trip`);
    } catch (e) {
      showError(e, $('error-project'));
    } finally {
      if (!nested) busy(-1);
    }
  }

  // ---- the point cloud: a scan read from a file, projected, coloured by signed deviation ----------
  const cloud = {count: 0, dimension: 3, points: null, foot: null, distance: null, signed: null, csvUrl: null};
  let clientModule = null;  // ui/footpoint-client.js, imported when a cloud is first projected

  function cloudError(message) {
    const box = $('error-cloud');
    box.textContent = '';
    const text = document.createElement('span');
    text.className = 'message';
    text.textContent = message;
    box.append(text);
    box.hidden = false;
  }

  // The file's points (XYZ, CSV, PLY) read by ui/point-cloud-worker.js off the page's thread.
  function readCloudFile(file, dimension) {
    return file.arrayBuffer().then((buffer) => new Promise((resolve, reject) => {
      const worker = new Worker('/ui/point-cloud-worker.js');
      worker.onmessage = (e) => {
        worker.terminate();
        if (e.data.error) reject(new Error(e.data.error)); else resolve(e.data);
      };
      worker.onerror = (e) => { worker.terminate(); reject(new Error(`${file.name}: ${e.message}`)); };
      worker.postMessage({name: file.name, buffer, dimension}, [buffer]);
    }));
  }

  // The diverging colour map "cool to warm" (K. Moreland, Diverging Color Maps for Scientific
  // Visualization, ISVC 2009), linear between its stops, of t in [-1, 1]: blue below 0, grey at
  // 0, red above; the CSS ramp of the legend has the same stops.
  const RAMP = [[0x3b, 0x4c, 0xc0], [0x73, 0x96, 0xf5], [0xdd, 0xdd, 0xdd], [0xf4, 0x9a, 0x7b], [0xb4, 0x04, 0x26]];
  function rampColour(t, out, at) {
    const x = (Math.max(-1, Math.min(1, t)) + 1) * 0.5 * (RAMP.length - 1);
    const k = Math.min(RAMP.length - 2, Math.floor(x)), a = x - k;
    for (let c = 0; c < 3; ++c) out[at + c] = ((1 - a) * RAMP[k][c] + a * RAMP[k + 1][c]) / 255;
  }

  // Count, min, max, mean and RMS of the finite signed deviations (Neumaier's compensated sums),
  // and their histogram in `bins` equal bins from min to max (the last bin holds max).
  function deviationStats(values, bins) {
    let count = 0, min = Infinity, max = -Infinity;
    let sum = 0, sumC = 0, squares = 0, squaresC = 0;
    const add = (s, c, x) => {
      const t = s + x;
      return [t, c + (Math.abs(s) >= Math.abs(x) ? (s - t) + x : (x - t) + s)];
    };
    for (const d of values) {
      if (!Number.isFinite(d)) continue;
      ++count;
      if (d < min) min = d;
      if (d > max) max = d;
      [sum, sumC] = add(sum, sumC, d);
      [squares, squaresC] = add(squares, squaresC, d * d);
    }
    if (count === 0) return {count: 0};
    const counts = new Array(bins).fill(0);
    const width = (max - min) / bins;
    for (const d of values)
      if (Number.isFinite(d)) counts[width > 0 ? Math.min(bins - 1, Math.floor((d - min) / width)) : 0] += 1;
    return {count, min, max, mean: (sum + sumC) / count, rms: Math.sqrt((squares + squaresC) / count), counts,
            edges: Array.from({length: bins + 1}, (_, k) => (k === bins ? max : min + k * width))};
  }

  function drawHistogram(stats, scale) {
    const canvas = $('cloud-histogram');
    const ratio = window.devicePixelRatio || 1;
    const w = canvas.clientWidth || 340, h = canvas.clientHeight || 130;
    canvas.width = Math.round(w * ratio);
    canvas.height = Math.round(h * ratio);
    const g = canvas.getContext('2d');
    g.setTransform(ratio, 0, 0, ratio, 0, 0);
    g.clearRect(0, 0, w, h);
    const left = 8, right = w - 8, top = 8, bottom = h - 22;
    const peak = Math.max(...stats.counts);
    const bar = (right - left) / stats.counts.length;
    const colour = [0, 0, 0];
    stats.counts.forEach((n, k) => {
      rampColour((stats.edges[k] + stats.edges[k + 1]) / 2 / scale, colour, 0);
      g.fillStyle = `rgb(${colour.map((c) => Math.round(255 * c)).join(',')})`;
      const height = peak > 0 ? (bottom - top) * n / peak : 0;
      g.fillRect(left + k * bar + 0.5, bottom - height, Math.max(1, bar - 1), height);
    });
    g.strokeStyle = '#667085';
    g.beginPath();
    g.moveTo(left, bottom + 0.5);
    g.lineTo(right, bottom + 0.5);
    if (stats.min < 0 && stats.max > 0) {  // the zero line
      const x = left + (right - left) * (0 - stats.min) / (stats.max - stats.min);
      g.moveTo(x, top);
      g.lineTo(x, bottom);
    }
    g.stroke();
    g.fillStyle = '#667085';
    g.font = '11px ui-monospace, "DejaVu Sans Mono", monospace';
    g.textBaseline = 'top';
    g.textAlign = 'left';
    g.fillText(short(stats.min, 4), left, bottom + 5);
    g.textAlign = 'right';
    g.fillText(short(stats.max, 4), right, bottom + 5);
    g.textAlign = 'center';
    g.fillText(`${stats.counts.length} bins, peak ${peak.toLocaleString('en')}`, (left + right) / 2, bottom + 5);
    canvas.dataset.counts = JSON.stringify(stats.counts);
    canvas.dataset.edges = JSON.stringify(stats.edges);
  }

  function showCloudReport(stats) {
    const dl = $('cloud-stats');
    dl.textContent = '';
    const scale = Math.max(Math.abs(stats.min), Math.abs(stats.max)) || 1;
    const entries = [['count', stats.count], ['mean', stats.mean], ['min', stats.min], ['RMS', stats.rms],
                     ['max', stats.max], ['no answer', cloud.count - stats.count]];
    for (const [name, value] of entries) {
      const dt = document.createElement('dt');
      dt.textContent = name;
      const dd = document.createElement('dd');
      dd.dataset.field = name.toLowerCase().replace(' ', '_');
      dd.dataset.value = String(value);
      dd.textContent = Number.isInteger(value) ? value.toLocaleString('en') : short(value, 6);
      dd.title = String(value);
      dl.append(dt, dd);
    }
    drawHistogram(stats, scale);
    $('cloud-legend-min').textContent = short(-scale, 4);
    $('cloud-legend-min').dataset.value = String(-scale);
    $('cloud-legend-max').textContent = short(scale, 4);
    $('cloud-legend-max').dataset.value = String(scale);
    $('cloud-legend').hidden = false;
    $('cloud-report').hidden = false;
  }

  // The points drawn as dots coloured by signed deviation (grey where there is none).
  function drawCloud(scale) {
    clearGroup(view.cloudGroup);
    const n = cloud.count, dim = cloud.dimension;
    const positions = new Float32Array(3 * n), colours = new Float32Array(3 * n);
    for (let i = 0; i < n; ++i) {
      for (let c = 0; c < dim; ++c) positions[3 * i + c] = cloud.points[dim * i + c];
      if (Number.isFinite(cloud.signed[i])) rampColour(cloud.signed[i] / scale, colours, 3 * i);
      else colours.fill(0.6, 3 * i, 3 * i + 3);
    }
    const g = bufferGeometry(positions);
    g.setAttribute('color', new THREE.BufferAttribute(colours, 3));
    view.cloudGroup.add(new THREE.Points(g, new THREE.PointsMaterial({size: 3, sizeAttenuation: false,
                                                                      vertexColors: THREE.VertexColors})));
    const planar = state.geometry.point_dim === 2;
    fitCamera([...state.mesh.vertices, ...positions], planar);
  }

  // The results as CSV (point, foot point, distance, signed distance; empty where null) in the
  // export link as a Blob, made when the link is first clicked (100,000 rows take most of a second).
  function exportCloud() {
    const n = cloud.count, dim = cloud.dimension;
    const axes = ['x', 'y', 'z'].slice(0, dim);
    const value = (x) => (Number.isFinite(x) ? String(x) : '');
    const rows = [[...axes, ...axes.map((a) => 'foot_' + a), 'distance', 'signed_distance'].join(',')];
    for (let i = 0; i < n; ++i) {
      const row = [];
      for (let c = 0; c < dim; ++c) row.push(value(cloud.points[dim * i + c]));
      for (let c = 0; c < dim; ++c) row.push(value(cloud.foot[dim * i + c]));
      row.push(value(cloud.distance[i]), value(cloud.signed[i]));
      rows.push(row.join(','));
    }
    if (cloud.csvUrl) URL.revokeObjectURL(cloud.csvUrl);
    cloud.csvUrl = URL.createObjectURL(new Blob([rows.join('\n') + '\n'], {type: 'text/csv'}));
    $('cloud-export').href = cloud.csvUrl;
  }

  function removeCloud() {
    if (view.cloudGroup) clearGroup(view.cloudGroup);
    Object.assign(cloud, {count: 0, points: null, foot: null, distance: null, signed: null});
    if (cloud.csvUrl) URL.revokeObjectURL(cloud.csvUrl);
    cloud.csvUrl = null;
    $('cloud-export').href = '#';
    $('cloud-report').hidden = $('cloud-legend').hidden = $('cloud-progress').hidden = true;
    $('cloud-meta').textContent = '';
    delete document.body.dataset.cloudCount;
    render();
  }

  async function loadCloud(file) {
    if (!file || !state.geometry) return;
    if (state.busy) {
      cloudError(`${file.name}: the page is busy with a request; load the file again when it is done`);
      return;
    }
    $('error-cloud').hidden = true;
    removeCloud();
    busy(+1);
    const started = performance.now();
    try {
      const dimension = state.geometry.point_dim;
      const read = await readCloudFile(file, dimension);
      const readMs = performance.now() - started;
      const n = read.count;
      Object.assign(cloud, {count: n, dimension, points: read.points, foot: new Float64Array(n * dimension).fill(NaN),
                            distance: new Float64Array(n).fill(NaN), signed: new Float64Array(n).fill(NaN)});
      const progress = $('cloud-progress');
      progress.hidden = false;
      progress.value = 0;
      $('cloud-meta').textContent = `${file.name}: ${read.format}, ${n.toLocaleString('en')} points read in ${Math.round(readMs)} ms, projecting…`;
      clientModule = clientModule || import('/ui/footpoint-client.js');
      const client = await clientModule;
      const given = readOptions();
      const options = {dimension, fields: ['foot_point', 'distance', 'signed_distance'],
                       onProgress: (done, total) => { progress.value = total ? done / total : 1; }};
      for (const name of ['initial', 'tolerance', 'max_iterations', 'max_distance'])
        if (given[name] !== undefined) options[name] = given[name];
      if ($('method').value && $('method').value !== 'auto') options.method = $('method').value;
      const projected = performance.now();
      let i = 0;
      for await (const r of client.project(state.definition, read.points, options)) {
        if (r.foot_point) for (let c = 0; c < dimension; ++c) cloud.foot[dimension * i + c] = r.foot_point[c];
        if (r.distance !== null) cloud.distance[i] = r.distance;
        if (r.signed_distance !== null) cloud.signed[i] = r.signed_distance;
        ++i;
      }
      const projectMs = performance.now() - projected;
      const stats = deviationStats(cloud.signed, 32);
      if (stats.count === 0) throw new Error(`${file.name}: no point has a signed deviation (no foot point, or a space curve's)`);
      const scale = Math.max(Math.abs(stats.min), Math.abs(stats.max)) || 1;
      drawCloud(scale);
      showCloudReport(stats);
      const totalMs = performance.now() - started;
      $('cloud-meta').textContent = `${file.name}: ${read.format}, ${n.toLocaleString('en')} points, read in ` +
                                    `${Math.round(readMs)} ms, projected in ${Math.round(projectMs)} ms`;
      Object.assign(document.body.dataset, {cloudCount: String(n), cloudReadMs: String(Math.round(readMs)),
                                            cloudProjectMs: String(Math.round(projectMs)), cloudTotalMs: String(Math.round(totalMs))});
    } catch (e) {
      removeCloud();
      cloudError(e.code ? `${e.code}: ${e.detail}` : String(e.message || e));
    } finally {
      busy(-1);
    }
  }

  function applyPreset(preset) {
    fillForm(preset.geometry);
    $('points').value = preset.points.map((p) => p.join(', ')).join('\n');
    const o = preset.options || {};
    $('opt-initial').value = o.initial ? o.initial.join(', ') : '';
    $('opt-tolerance').value = '';
    $('opt-max-iterations').value = '';
    $('opt-max-distance').value = '';
    $('opt-all-minima').checked = Boolean(o.all_minima);
    $('opt-trace').checked = Boolean(o.trace);
    state.selected = 0;
    const select = $('method');
    select.textContent = '';
    const option = document.createElement('option');
    option.value = preset.method;
    option.textContent = preset.method;
    select.append(option);
    select.value = preset.method;
    return showGeometry();
  }

  async function start() {
    initScene();
    const presets = $('preset');
    PRESETS.forEach((p, i) => {
      const o = document.createElement('option');
      o.value = String(i);
      o.textContent = p.name;
      presets.append(o);
    });
    presets.addEventListener('change', () => applyPreset(PRESETS[Number(presets.value)]));
    $('type').addEventListener('change', () => { buildForm($('type').value); clearErrors(); });
    $('show').addEventListener('click', showGeometry);
    $('project').addEventListener('click', () => project());
    $('method').addEventListener('change', describeMethod);
    $('clear').addEventListener('click', () => { $('points').value = ''; project(); });
    $('copy-curl').addEventListener('click', async () => {
      const text = curl();
      const box = $('curl');
      box.textContent = text || 'Project some points first: the command repeats the request the page made.';
      box.hidden = false;
      if (text && navigator.clipboard && window.isSecureContext) {
        try { await navigator.clipboard.writeText(text); setStatus('curl command copied'); } catch (e) { /* shown below */ }
      }
    });
    $('cloud-file').addEventListener('change', (e) => {
      const file = e.target.files[0];
      loadCloud(file).finally(() => { e.target.value = ''; });  // the same file can be chosen again
    });
    for (const target of [$('cloud-drop'), $('canvas-box')]) {
      target.addEventListener('dragover', (e) => { e.preventDefault(); $('cloud-drop').classList.add('over'); });
      target.addEventListener('dragleave', () => $('cloud-drop').classList.remove('over'));
      target.addEventListener('drop', (e) => {
        e.preventDefault();
        $('cloud-drop').classList.remove('over');
        if (e.dataTransfer.files.length) loadCloud(e.dataTransfer.files[0]);
      });
    }
    $('cloud-clear').addEventListener('click', removeCloud);
    // Before the link's default action, which then downloads the Blob just made.
    $('cloud-export').addEventListener('click', () => { if (!cloud.csvUrl && cloud.count) exportCloud(); });
    const methods = await api('GET', '/v1/methods');
    if (methods.ok) for (const t of methods.json.geometry_types) state.methods[t.type] = t.methods;
    await applyPreset(PRESETS[0]);
  }

  window.addEventListener('DOMContentLoaded', () => {
    start().catch((e) => { setStatus(String(e.message || e), true); document.body.dataset.state = 'error'; });
  });
})();
