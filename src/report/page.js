/* faultmesh report.html: sorting and filtering of its tables, and the
 * fault panel, which draws a fault from the packed triangles of the page
 * (mesh_pack.c tells their format) when it is opened: a still picture
 * (2D canvas, no WebGL needed) and a 3D view of the fault and its
 * neighbours (WebGL, else the same 2D drawing). No network, no library:
 * the page must open from a disk anywhere. */
(function () {
  'use strict';
  var doc = document, root = doc.documentElement;
  function $(id) { return doc.getElementById(id); }
  function each(list, fn) { Array.prototype.forEach.call(list, fn); }
  var D = JSON.parse($('fm-data').textContent);
  var byName = {};
  D.f.forEach(function (f, i) { byName[f.n] = i; });

  /* ---- tables: click a heading to sort, type to filter ---- */
  function key(td) {
    var v = td.getAttribute('data-v');
    if (v !== null) return +v;
    var t = td.textContent.trim();
    return /^[-+]?[0-9.]/.test(t) ? parseFloat(t) : t.toLowerCase();
  }
  function cmp(x, y) {
    var nx = typeof x === 'number', ny = typeof y === 'number';
    if (nx !== ny) return nx ? -1 : 1; /* blanks and words after numbers */
    return x < y ? -1 : x > y ? 1 : 0;
  }
  each(doc.querySelectorAll('table.sort'), function (tb) {
    var heads = tb.tHead.rows[0].cells;
    each(heads, function (th, i) {
      th.tabIndex = 0;
      th.title = 'sort by ' + th.textContent;
      function sort() {
        var dir = th.getAttribute('aria-sort') === 'ascending' ? -1 : 1;
        each(heads, function (h) { h.removeAttribute('aria-sort'); });
        th.setAttribute('aria-sort', dir > 0 ? 'ascending' : 'descending');
        var body = tb.tBodies[0], rows = Array.prototype.slice.call(body.rows);
        var keys = rows.map(function (r) { return key(r.cells[i]); });
        var idx = rows.map(function (r, k) { return k; });
        idx.sort(function (a, b) { return dir * cmp(keys[a], keys[b]) || a - b; });
        idx.forEach(function (k) { body.appendChild(rows[k]); });
      }
      th.addEventListener('click', sort);
      th.addEventListener('keydown', function (e) { if (e.key === 'Enter') sort(); });
    });
  });
  function filter(box) {
    var tb = $(box.getAttribute('data-for')), inp = box.querySelector('input');
    var sel = box.querySelector('select'), out = box.querySelector('.shown');
    var q = inp.value.trim().toLowerCase(), want = sel ? sel.value : '';
    var col = sel ? +sel.getAttribute('data-col') : 0, n = 0, rows = tb.tBodies[0].rows;
    each(rows, function (r) {
      var ok = (!q || r.textContent.toLowerCase().indexOf(q) >= 0) &&
        (!want || r.cells[col].textContent.trim() === want);
      r.hidden = !ok;
      n += ok;
    });
    out.textContent = n + ' of ' + rows.length + ' shown';
  }
  each(doc.querySelectorAll('.filter'), function (box) {
    each(box.querySelectorAll('input,select'), function (el) {
      el.addEventListener('input', function () { filter(box); });
    });
    filter(box);
  });
  /* links that show a table filtered: data-for, data-q, data-sel */
  doc.addEventListener('click', function (e) {
    var a = e.target.closest('a[data-for]');
    if (a) {
      var box = doc.querySelector('.filter[data-for="' + a.getAttribute('data-for') + '"]');
      box.querySelector('input').value = a.getAttribute('data-q') || '';
      var sel = box.querySelector('select');
      if (sel) sel.value = a.getAttribute('data-sel') || '';
      filter(box);
      return;
    }
    var td = e.target.closest('td.fn');
    if (td && byName[td.textContent.trim()] !== undefined)
      location.hash = 'fault=' + encodeURIComponent(td.textContent.trim());
  });

  /* ---- the packed triangles, inflated once when a fault is first opened ---- */
  var pending = null;
  function meshes() {
    if (pending) return pending;
    var text = $('fm-mesh').textContent.trim();
    if (typeof DecompressionStream === 'undefined' || typeof Response === 'undefined')
      return (pending = Promise.reject(new Error('this browser cannot inflate the triangles (no DecompressionStream)')));
    var bin = atob(text), u = new Uint8Array(bin.length);
    for (var i = 0; i < bin.length; i++) u[i] = bin.charCodeAt(i);
    var s = new Blob([u]).stream().pipeThrough(new DecompressionStream('deflate'));
    pending = new Response(s).arrayBuffer().then(function (b) { return unpack(new Uint8Array(b)); });
    return pending;
  }
  function unpack(b) {
    var at = 0, out = [];
    function uint() {
      var x = 0, s = 1, c;
      do { c = b[at++]; x += (c & 127) * s; s *= 128; } while (c & 128);
      return x;
    }
    function sint() { var u = uint(); return u % 2 ? -(u + 1) / 2 : u / 2; }
    for (var g = 0; g < D.ntags; g++) {
      var nt = uint(), T = new Uint32Array(3 * nt), Q = [], last = [0, 0, 0], parent = 0;
      var vertex = function (pred) {
        var r = uint();
        if (r) return Q.length / 3 - r;
        var p = pred || last.slice();
        for (var c = 0; c < 3; c++) last[c] = p[c] + sint();
        Q.push(last[0], last[1], last[2]);
        return Q.length / 3 - 1;
      };
      for (var t = 0; t < nt; t++) {
        var sym = uint();
        if (!sym) {
          for (var c = 0; c < 3; c++) T[3 * t + c] = vertex(null);
        } else {
          parent += Math.floor((sym - 1) / 3);
          var e = (sym - 1) % 3, a = T[3 * parent + e], bb = T[3 * parent + (e + 1) % 3];
          var o = T[3 * parent + (e + 2) % 3], pred = [];
          for (var k = 0; k < 3; k++) pred[k] = Q[3 * a + k] + Q[3 * bb + k] - Q[3 * o + k];
          T[3 * t] = bb;
          T[3 * t + 1] = a;
          T[3 * t + 2] = vertex(pred);
        }
      }
      var nj = uint(), J = new Uint32Array(2 * nj);
      for (var j = 0; j < 2 * nj; j++) J[j] = uint();
      var O = [], at0 = [0, 0, 0];
      for (var no = uint(); no > 0; no--) {
        var np = uint(), L = new Float32Array(3 * np);
        for (var i = 0; i < 3 * np; i++) {
          at0[i % 3] += sint();
          L[i] = at0[i % 3] * D.step / 1000;
        }
        O.push(L);
      }
      var P = new Float32Array(Q.length);
      for (var q = 0; q < Q.length; q++) P[q] = Q[q] * D.step / 1000; /* km from the origin */
      out.push({ P: P, T: T, J: J, O: O });
    }
    return out;
  }

  /* ---- drawing ---- */
  function norm(v) { var l = Math.hypot(v[0], v[1], v[2]) || 1; return [v[0] / l, v[1] / l, v[2] / l]; }
  function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
  function rotate(v, axis, ang) { /* Rodrigues */
    var c = Math.cos(ang), s = Math.sin(ang), k = axis, d = dot(k, v);
    return [v[0] * c + (k[1] * v[2] - k[2] * v[1]) * s + k[0] * d * (1 - c),
      v[1] * c + (k[2] * v[0] - k[0] * v[2]) * s + k[1] * d * (1 - c),
      v[2] * c + (k[0] * v[1] - k[1] * v[0]) * s + k[2] * d * (1 - c)];
  }
  /* A view: basis r (right), u (up), d (into the screen), the centre c
   * (km), pixels per km k and a pan in km. */
  function view(f, m, W, H) {
    var v = { r: f.c.slice(0, 3), u: f.c.slice(3, 6), d: f.c.slice(6, 9), pan: [0, 0] };
    var lo = [1e30, 1e30, 1e30], hi = [-1e30, -1e30, -1e30], P = m.P;
    for (var i = 0; i < P.length; i += 3)
      for (var c = 0; c < 3; c++) { lo[c] = Math.min(lo[c], P[i + c]); hi[c] = Math.max(hi[c], P[i + c]); }
    v.c = [0, 1, 2].map(function (c) { return (lo[c] + hi[c]) / 2; });
    var wx = 0, wy = 0;
    for (i = 0; i < P.length; i += 3) {
      var p = [P[i] - v.c[0], P[i + 1] - v.c[1], P[i + 2] - v.c[2]];
      wx = Math.max(wx, Math.abs(dot(p, v.r)));
      wy = Math.max(wy, Math.abs(dot(p, v.u)));
    }
    v.k = 0.92 * Math.min(W / (2 * wx || 1), H / (2 * wy || 1));
    v.k0 = v.k;
    v.R = Math.hypot(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]) || 1;
    return v;
  }
  function shadeOf(n, v) {
    var l = norm([-v.d[0] + 0.6 * v.u[0] - 0.4 * v.r[0], -v.d[1] + 0.6 * v.u[1] - 0.4 * v.r[1],
      -v.d[2] + 0.6 * v.u[2] - 0.4 * v.r[2]]);
    return 0.45 + 0.55 * Math.abs(dot(n, l));
  }
  function rgbText(c, s) {
    return 'rgb(' + Math.round(255 * c[0] * s) + ',' + Math.round(255 * c[1] * s) + ',' + Math.round(255 * c[2] * s) + ')';
  }
  /* Painter's drawing on a 2D canvas: items {m, rgb, edges}, far first;
   * junction edges of the first item over everything. */
  function paint(cv, items, v) {
    var ctx = cv.getContext('2d'), W = cv.width, H = cv.height, tris = [];
    ctx.fillStyle = '#fff';
    ctx.fillRect(0, 0, W, H);
    function sx(P, i) { return W / 2 + v.k * ((P[i] - v.c[0]) * v.r[0] + (P[i + 1] - v.c[1]) * v.r[1] + (P[i + 2] - v.c[2]) * v.r[2] - v.pan[0]); }
    function sy(P, i) { return H / 2 - v.k * ((P[i] - v.c[0]) * v.u[0] + (P[i + 1] - v.c[1]) * v.u[1] + (P[i + 2] - v.c[2]) * v.u[2] - v.pan[1]); }
    function sz(P, i) { return (P[i] - v.c[0]) * v.d[0] + (P[i + 1] - v.c[1]) * v.d[1] + (P[i + 2] - v.c[2]) * v.d[2]; }
    items.forEach(function (it, w) {
      var P = it.m.P, T = it.m.T;
      for (var t = 0; t < T.length; t += 3) {
        var a = 3 * T[t], b = 3 * T[t + 1], c = 3 * T[t + 2];
        var e = [P[b] - P[a], P[b + 1] - P[a + 1], P[b + 2] - P[a + 2]];
        var f = [P[c] - P[a], P[c + 1] - P[a + 1], P[c + 2] - P[a + 2]];
        var n = norm([e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]]);
        tris.push([sz(P, a) + sz(P, b) + sz(P, c), w, sx(P, a), sy(P, a), sx(P, b), sy(P, b), sx(P, c), sy(P, c), shadeOf(n, v)]);
      }
    });
    tris.sort(function (x, y) { return y[0] - x[0]; });
    var edges = D.H / 1000 * v.k > 5;
    ctx.lineJoin = 'round';
    tris.forEach(function (t) {
      var it = items[t[1]];
      ctx.beginPath();
      ctx.moveTo(t[2], t[3]);
      ctx.lineTo(t[4], t[5]);
      ctx.lineTo(t[6], t[7]);
      ctx.closePath();
      ctx.fillStyle = rgbText(it.rgb, t[8]);
      ctx.fill();
      ctx.strokeStyle = it.edges && edges ? rgbText(it.rgb, t[8] * 0.55) : ctx.fillStyle;
      ctx.lineWidth = it.edges && edges ? 0.8 : 0.5;
      ctx.stroke();
    });
    var m = items[0].m, P = m.P;
    ctx.strokeStyle = '#333';
    ctx.lineWidth = 1.2;
    ctx.setLineDash([6, 4]);
    ctx.beginPath();
    m.O.forEach(function (L) {
      for (var i = 0; i < L.length; i += 3)
        (i ? ctx.lineTo : ctx.moveTo).call(ctx, sx(L, i), sy(L, i));
    });
    ctx.stroke();
    ctx.setLineDash([]);
    ctx.strokeStyle = '#000';
    ctx.lineWidth = 2.5;
    ctx.beginPath();
    for (var j = 0; j < m.J.length; j += 2) {
      ctx.moveTo(sx(P, 3 * m.J[j]), sy(P, 3 * m.J[j]));
      ctx.lineTo(sx(P, 3 * m.J[j + 1]), sy(P, 3 * m.J[j + 1]));
    }
    ctx.stroke();
    scaleBar(ctx, v.k, H);
  }
  function scaleBar(ctx, k, H) {
    var target = 120 / k, km = Math.pow(10, Math.floor(Math.log10(target)));
    km *= target >= 5 * km ? 5 : target >= 2 * km ? 2 : 1;
    ctx.strokeStyle = ctx.fillStyle = '#333';
    ctx.lineWidth = 2;
    ctx.beginPath();
    ctx.moveTo(10, H - 10);
    ctx.lineTo(10 + km * k, H - 10);
    ctx.stroke();
    ctx.font = '12px sans-serif';
    ctx.fillText(km + ' km', 16 + km * k, H - 6);
  }

  /* WebGL: the same picture, redrawn as the view turns. */
  function glView(cv, items) {
    var gl = null;
    try { gl = cv.getContext('webgl', { antialias: true }); } catch (e) { gl = null; }
    if (!gl) return null;
    var vs = 'attribute vec3 p;attribute vec3 n;attribute vec3 c;uniform mat4 M;uniform mat3 B;' +
      'uniform float lit;varying vec3 col;void main(){gl_Position=M*vec4(p,1.0);' +
      'vec3 l=normalize(vec3(-0.4,0.6,-1.0));float s=0.45+0.55*abs(dot(normalize(B*n),l));' +
      'col=c*mix(1.0,s,lit);}';
    var fs = 'precision mediump float;varying vec3 col;void main(){gl_FragColor=vec4(col,1.0);}';
    function shader(type, src) {
      var s = gl.createShader(type);
      gl.shaderSource(s, src);
      gl.compileShader(s);
      if (!gl.getShaderParameter(s, gl.COMPILE_STATUS)) throw new Error(gl.getShaderInfoLog(s));
      return s;
    }
    var prog = gl.createProgram();
    gl.attachShader(prog, shader(gl.VERTEX_SHADER, vs));
    gl.attachShader(prog, shader(gl.FRAGMENT_SHADER, fs));
    gl.linkProgram(prog);
    if (!gl.getProgramParameter(prog, gl.LINK_STATUS)) throw new Error(gl.getProgramInfoLog(prog));
    var tri = [], line = [];
    function push(a, P, i, n, c) { a.push(P[i], P[i + 1], P[i + 2], n[0], n[1], n[2], c[0], c[1], c[2]); }
    items.forEach(function (it, w) {
      var P = it.m.P, T = it.m.T, dark = it.rgb.map(function (x) { return x * 0.45; });
      for (var t = 0; t < T.length; t += 3) {
        var a = 3 * T[t], b = 3 * T[t + 1], c = 3 * T[t + 2];
        var e = [P[b] - P[a], P[b + 1] - P[a + 1], P[b + 2] - P[a + 2]];
        var f = [P[c] - P[a], P[c + 1] - P[a + 1], P[c + 2] - P[a + 2]];
        var n = norm([e[1] * f[2] - e[2] * f[1], e[2] * f[0] - e[0] * f[2], e[0] * f[1] - e[1] * f[0]]);
        push(tri, P, a, n, it.rgb); push(tri, P, b, n, it.rgb); push(tri, P, c, n, it.rgb);
        if (w === 0)
          for (var k = 0; k < 3; k++) {
            push(line, P, 3 * T[t + k], n, dark);
            push(line, P, 3 * T[t + (k + 1) % 3], n, dark);
          }
      }
    });
    var m = items[0].m;
    for (var j = 0; j < m.J.length; j++) push(line, m.P, 3 * m.J[j], [0, 0, 1], [0, 0, 0]);
    m.O.forEach(function (L) {
      for (var i = 3; i < L.length; i += 3) {
        push(line, L, i - 3, [0, 0, 1], [0.2, 0.2, 0.2]);
        push(line, L, i, [0, 0, 1], [0.2, 0.2, 0.2]);
      }
    });
    function buffer(a) {
      var b = gl.createBuffer();
      gl.bindBuffer(gl.ARRAY_BUFFER, b);
      gl.bufferData(gl.ARRAY_BUFFER, new Float32Array(a), gl.STATIC_DRAW);
      return { b: b, n: a.length / 9 };
    }
    var bt = buffer(tri), bl = buffer(line);
    var loc = { p: gl.getAttribLocation(prog, 'p'), n: gl.getAttribLocation(prog, 'n'), c: gl.getAttribLocation(prog, 'c') };
    return function draw(v) {
      gl.viewport(0, 0, cv.width, cv.height);
      gl.clearColor(1, 1, 1, 1);
      gl.clear(gl.COLOR_BUFFER_BIT | gl.DEPTH_BUFFER_BIT);
      gl.enable(gl.DEPTH_TEST);
      gl.useProgram(prog);
      var sx = 2 * v.k / cv.width, sy = 2 * v.k / cv.height, r = v.r, u = v.u, d = v.d, c = v.c;
      var M = [r[0] * sx, u[0] * sy, d[0] / v.R, 0, r[1] * sx, u[1] * sy, d[1] / v.R, 0,
        r[2] * sx, u[2] * sy, d[2] / v.R, 0,
        -(dot(c, r) + v.pan[0]) * sx, -(dot(c, u) + v.pan[1]) * sy, -dot(c, d) / v.R, 1];
      gl.uniformMatrix4fv(gl.getUniformLocation(prog, 'M'), false, new Float32Array(M));
      gl.uniformMatrix3fv(gl.getUniformLocation(prog, 'B'), false,
        new Float32Array([r[0], u[0], d[0], r[1], u[1], d[1], r[2], u[2], d[2]]));
      [[bt, gl.TRIANGLES, 1], [bl, gl.LINES, 0]].forEach(function (x) {
        gl.bindBuffer(gl.ARRAY_BUFFER, x[0].b);
        ['p', 'n', 'c'].forEach(function (a, i) {
          gl.enableVertexAttribArray(loc[a]);
          gl.vertexAttribPointer(loc[a], 3, gl.FLOAT, false, 36, 12 * i);
        });
        gl.uniform1f(gl.getUniformLocation(prog, 'lit'), x[2]);
        if (x[2]) { gl.enable(gl.POLYGON_OFFSET_FILL); gl.polygonOffset(1, 1); }
        else gl.disable(gl.POLYGON_OFFSET_FILL);
        gl.drawArrays(x[1], 0, x[0].n);
      });
    };
  }

  /* drag turns (about the vertical and the screen's horizontal), the wheel
   * zooms, shift-drag pans, a double click goes back */
  function interact(cv, v, redraw) {
    var home = JSON.stringify(v), drag = null;
    cv.addEventListener('pointerdown', function (e) { drag = [e.clientX, e.clientY, e.shiftKey]; cv.setPointerCapture(e.pointerId); });
    cv.addEventListener('pointerup', function () { drag = null; });
    cv.addEventListener('pointermove', function (e) {
      if (!drag) return;
      var dx = e.clientX - drag[0], dy = e.clientY - drag[1];
      drag[0] = e.clientX;
      drag[1] = e.clientY;
      if (drag[2]) {
        v.pan[0] -= dx / v.k * (cv.width / cv.clientWidth);
        v.pan[1] += dy / v.k * (cv.height / cv.clientHeight);
      } else {
        var up = [0, 0, 1];
        v.r = rotate(v.r, up, -dx * 0.01); v.u = rotate(v.u, up, -dx * 0.01); v.d = rotate(v.d, up, -dx * 0.01);
        v.u = rotate(v.u, v.r, -dy * 0.01); v.d = rotate(v.d, v.r, -dy * 0.01);
      }
      redraw();
    });
    cv.addEventListener('wheel', function (e) {
      e.preventDefault();
      v.k *= Math.exp(-e.deltaY * 0.002);
      redraw();
    }, { passive: false });
    cv.addEventListener('dblclick', function () {
      var h = JSON.parse(home);
      for (var x in h) v[x] = h[x];
      redraw();
    });
  }

  /* ---- the map: a click opens the meshed fault nearest to it (within
   * 12 pixels), found among the packed nodes ---- */
  var map = $('fm-map');
  if (map) {
    var img = map.querySelector('img'), fr = map.getAttribute('data-frame').split(' ').map(Number);
    img.style.cursor = 'crosshair';
    img.title = 'click a fault to open it';
    img.addEventListener('click', function (e) {
      var box = img.getBoundingClientRect(), s = img.naturalWidth / box.width;
      var x = (fr[0] + (e.clientX - box.left) * s / fr[2] - D.origin[0]) / 1000;
      var y = (fr[1] - (e.clientY - box.top) * s / fr[2] - D.origin[1]) / 1000;
      meshes().then(function (M) {
        var best = -1, bd = Math.pow(12 / fr[2] / 1000, 2);
        D.f.forEach(function (f, i) {
          if (f.g < 0) return;
          var P = M[f.g].P;
          for (var k = 0; k < P.length; k += 3) {
            var d = (P[k] - x) * (P[k] - x) + (P[k + 1] - y) * (P[k + 1] - y);
            if (d < bd) { bd = d; best = i; }
          }
        });
        if (best >= 0) location.hash = 'fault=' + encodeURIComponent(D.f[best].n);
      });
    });
  }

  /* ---- the fault panel ---- */
  var panel = $('fm-panel'), shown = -1;
  function setView(how) { root.setAttribute('data-fm-view', how); }
  function show(i) {
    var f = D.f[i], row = $('fault-' + i);
    shown = i;
    panel.hidden = false;
    $('fm-name').textContent = f.n;
    var facts = $('fm-facts');
    facts.textContent = '';
    if (row) {
      var heads = $('fault-table').tHead.rows[0].cells;
      each(row.cells, function (td, k) {
        if (!td.textContent.trim()) return;
        var tr = facts.insertRow(), th = doc.createElement('th');
        th.textContent = heads[k].textContent;
        tr.appendChild(th);
        tr.appendChild(td.cloneNode(true));
      });
    }
    var nb = $('fm-neighbours');
    nb.textContent = '';
    f.nb.forEach(function (j, k) {
      if (k) nb.appendChild(doc.createTextNode(', '));
      var a = doc.createElement('a');
      a.href = '#fault=' + encodeURIComponent(D.f[j].n);
      a.textContent = D.f[j].n;
      nb.appendChild(a);
    });
    if (!f.nb.length) nb.textContent = 'none within the join distance';
    var pic = $('fm-picture'), cv3 = $('fm-3d'), note = $('fm-note');
    note.textContent = '';
    pic.hidden = cv3.hidden = f.g < 0;
    if (f.g < 0) {
      note.textContent = 'Not meshed: nothing to draw.';
      setView('none');
      root.setAttribute('data-fm-panel', f.n);
      return Promise.resolve();
    }
    return meshes().then(function (M) {
      if (shown !== i) return;
      var items = [{ m: M[f.g], rgb: D.rgb[f.k], edges: true }];
      paint(pic, items, view(f, M[f.g], pic.width, pic.height));
      f.nb.forEach(function (j) {
        if (D.f[j].g >= 0) items.push({ m: M[D.f[j].g], rgb: [0.85, 0.85, 0.85], edges: false });
      });
      var v = view(f, M[f.g], cv3.width, cv3.height), draw = null;
      v.k *= 0.7; /* room for the neighbours around it */
      items.forEach(function (it) { /* depth: every neighbour within the clip range */
        for (var i = 0; i < it.m.P.length; i += 3)
          v.R = Math.max(v.R, 2 * Math.hypot(it.m.P[i] - v.c[0], it.m.P[i + 1] - v.c[1], it.m.P[i + 2] - v.c[2]));
      });
      /* a canvas keeps the first context it gave: a new one per fault */
      var fresh = cv3.cloneNode(false);
      cv3.parentNode.replaceChild(fresh, cv3);
      cv3 = fresh;
      try { draw = glView(cv3, items); } catch (e) { draw = null; note.textContent = 'WebGL failed (' + e.message + '): drawn without it. '; }
      if (draw) setView('webgl');
      else {
        setView('2d');
        if (!note.textContent) note.textContent = 'WebGL is not available here: the 3D view is drawn without it (slower). ';
        draw = function (w) { paint(cv3, items, w); };
      }
      root.setAttribute('data-fm-triangles', M[f.g].T.length / 3);
      root.setAttribute('data-fm-3d-triangles', items.reduce(function (n, it) { return n + it.m.T.length / 3; }, 0));
      var redraw = function () { draw(v); };
      interact(cv3, v, redraw);
      redraw();
      root.setAttribute('data-fm-panel', f.n);
    }).catch(function (e) {
      note.textContent = 'Cannot draw the fault: ' + e.message;
      setView('none');
      root.setAttribute('data-fm-panel', f.n);
    });
  }
  function route() {
    var m = /^#fault=(.*)$/.exec(location.hash), i = m ? byName[decodeURIComponent(m[1])] : undefined;
    if (i === undefined) {
      panel.hidden = true;
      shown = -1;
      return;
    }
    show(i);
  }
  $('fm-close').addEventListener('click', function () { location.hash = 'faults'; });
  doc.addEventListener('keydown', function (e) { if (e.key === 'Escape' && !panel.hidden) location.hash = 'faults'; });
  window.addEventListener('hashchange', route);
  route();
  root.setAttribute('data-fm-ready', '1');
})();
