// The replay page's script (harness/src/replay/replay.js, inlined into
// every page): decodes the run(s) embedded as JSON (format in
// harness/src/replay/encode.rs), draws them on the canvas and drives the
// controls. No dependencies, no network.
(function () {
  'use strict';
  // The layout's fixed boxes (CSS px) and the share of a panel the world
  // box fills: the view transform of harness/src/replay/mod.rs.
  var FILL = 0.92;
  var SPEEDS = [0.01, 0.1, 0.25, 0.5, 1, 2, 5, 10, 20, 50, 100];

  var data = JSON.parse(document.getElementById('replay-data').textContent);
  var $ = function (id) { return document.getElementById(id); };

  // A channel's second differences summed twice, times its quantum.
  function cumulative(d, q) {
    var out = new Float64Array(d.length), step = 0, n = 0;
    for (var i = 0; i < d.length; i++) { step += d[i]; n += step; out[i] = n * q; }
    return out;
  }
  function decimals(q) { return Math.max(0, Math.round(-Math.log10(q))); }

  var runs = data.runs.map(function (r) {
    return {
      label: r.label,
      short: r.short,
      samples: r.samples,
      q: r.q,
      t: cumulative(r.t, r.q.t),
      bodies: r.bodies.map(function (b) {
        if (b.fixed) { return { fixed: b.fixed }; }
        return {
          k: cumulative(b.k, 1),
          x: cumulative(b.x, r.q.p), y: cumulative(b.y, r.q.p), a: cumulative(b.a, r.q.a),
          vx: cumulative(b.vx, r.q.v), vy: cumulative(b.vy, r.q.v), w: cumulative(b.w, r.q.w)
        };
      }),
      energy: r.energy,
      events: r.events
    };
  });
  var bodies = data.bodies;
  var t0 = Infinity, t1 = -Infinity;
  runs.forEach(function (r) {
    t0 = Math.min(t0, r.t[0]);
    t1 = Math.max(t1, r.t[r.t.length - 1]);
  });
  var view = { x0: data.view[0], y0: data.view[1], x1: data.view[2], y1: data.view[3] };
  var moving = bodies.filter(function (b) { return b.kind !== 'static'; }).length;

  // ---- state -------------------------------------------------------------
  var t = t0, playing = false, stopAt = t1, last = 0, timer = null;
  var speed = 1, zoom = 1, pan = { x: 0, y: 0 }, overlay = false;
  var pinned = -1, hovered = null, traces = moving <= 200;
  var duration = t1 - t0;
  for (var k = 0; k < SPEEDS.length; k++) {
    speed = SPEEDS[k];
    if (speed >= 1 && duration / speed <= 30) { break; }
  }
  var timeDecimals = Math.max(2, Math.ceil(-Math.log10(data.step)) + 1);

  // ---- sampling ----------------------------------------------------------
  // A place in a run: [sample index i, share s of the way to sample
  // i + 1, time]. Each body keeps its own samples (indices K into the
  // run's times); between two of them the page interpolates linearly in
  // time.
  function locate(run, time) {
    var T = run.t, n = T.length;
    if (time <= T[0]) { return [0, 0, T[0]]; }
    if (time >= T[n - 1]) { return [n - 1, 0, T[n - 1]]; }
    var lo = 0, hi = n - 1;
    while (hi - lo > 1) {
      var m = (lo + hi) >> 1;
      if (T[m] <= time) { lo = m; } else { hi = m; }
    }
    var span = T[hi] - T[lo];
    return [lo, span > 0 ? (time - T[lo]) / span : 0, time];
  }
  // The last of body B's kept samples at or before sample i.
  function keptBefore(B, i) {
    var K = B.k, lo = 0, hi = K.length - 1;
    if (K[hi] <= i) { return hi; }
    while (hi - lo > 1) {
      var m = (lo + hi) >> 1;
      if (K[m] <= i) { lo = m; } else { hi = m; }
    }
    return lo;
  }
  function stateOf(run, b, loc) {
    var B = run.bodies[b];
    if (B.fixed) { return { x: B.fixed[0], y: B.fixed[1], a: B.fixed[2], vx: 0, vy: 0, w: 0 }; }
    var m = keptBefore(B, loc[0]), j = Math.min(m + 1, B.k.length - 1);
    var ta = run.t[B.k[m]], tb = run.t[B.k[j]];
    var s = tb > ta ? Math.min(1, Math.max(0, (loc[2] - ta) / (tb - ta))) : 0;
    var lerp = function (c) { return c[m] + (c[j] - c[m]) * s; };
    return { x: lerp(B.x), y: lerp(B.y), a: lerp(B.a), vx: lerp(B.vx), vy: lerp(B.vy), w: lerp(B.w) };
  }
  function energyOf(run, loc) {
    if (!run.energy) { return null; }
    var i = loc[0], s = loc[1], j = Math.min(i + 1, run.energy.length - 1);
    var a = run.energy[i], b = run.energy[j];
    return a === null || b === null ? null : a + (b - a) * s;
  }

  // ---- layout and transform ----------------------------------------------
  var canvas = $('view'), ctx = canvas.getContext('2d');
  var cssW = 1, cssH = 1, dpr = 1;
  function panels() {
    if (runs.length === 1 || overlay) { return [runs.map(function (_, i) { return i; })]; }
    return runs.map(function (_, i) { return [i]; });
  }
  function panelRect(k, n) { return { x: k * cssW / n, y: 0, w: cssW / n, h: cssH }; }
  function baseScale(p) {
    return FILL * Math.min(p.w / (view.x1 - view.x0), p.h / (view.y1 - view.y0));
  }
  function transform(p) {
    var s = baseScale(p) * zoom;
    var cx = p.x + p.w / 2 + pan.x, cy = p.y + p.h / 2 + pan.y;
    var xc = (view.x0 + view.x1) / 2, yc = (view.y0 + view.y1) / 2;
    return {
      s: s,
      X: function (x) { return cx + s * (x - xc); },
      Y: function (y) { return cy - s * (y - yc); },
      x: function (X) { return xc + (X - cx) / s; },
      y: function (Y) { return yc - (Y - cy) / s; }
    };
  }
  function resize() {
    var r = canvas.getBoundingClientRect();
    cssW = Math.max(1, r.width); cssH = Math.max(1, r.height);
    dpr = window.devicePixelRatio || 1;
    canvas.width = Math.round(cssW * dpr); canvas.height = Math.round(cssH * dpr);
    canvas.dataset.left = r.left; canvas.dataset.top = r.top;
    canvas.dataset.width = cssW; canvas.dataset.height = cssH;
    render();
  }

  // ---- drawing -----------------------------------------------------------
  function darker(hex) {
    var n = parseInt(hex.slice(1), 16);
    var c = [(n >> 16) & 255, (n >> 8) & 255, n & 255].map(function (v) { return Math.round(v * 0.6); });
    return 'rgb(' + c.join(',') + ')';
  }
  function place(st, x, y) {
    var c = Math.cos(st.a), s = Math.sin(st.a);
    return [st.x + c * x - s * y, st.y + s * x + c * y];
  }
  function bodyPath(tr, b, st) {
    var parts = bodies[b].parts;
    ctx.beginPath();
    if (parts.length === 0) {
      ctx.arc(tr.X(st.x), tr.Y(st.y), 4, 0, 2 * Math.PI);
      return;
    }
    parts.forEach(function (part) {
      if (part.circle) {
        var c = place(st, part.circle[0], part.circle[1]);
        var X = tr.X(c[0]), Y = tr.Y(c[1]);
        ctx.moveTo(X + part.circle[2] * tr.s, Y);
        ctx.arc(X, Y, part.circle[2] * tr.s, 0, 2 * Math.PI);
      } else if (part.polygon && part.polygon.length >= 6) {
        var v = part.polygon;
        for (var i = 0; i < v.length; i += 2) {
          var q = place(st, v[i], v[i + 1]);
          if (i === 0) { ctx.moveTo(tr.X(q[0]), tr.Y(q[1])); } else { ctx.lineTo(tr.X(q[0]), tr.Y(q[1])); }
        }
        ctx.closePath();
      }
    });
  }
  // The turn of a circle shows as a tick on its rim (not through its
  // centre, where the body's colour is).
  function circleTicks(tr, b, st) {
    bodies[b].parts.forEach(function (part) {
      if (!part.circle) { return; }
      var c = place(st, part.circle[0], part.circle[1]), r = part.circle[2];
      var dx = Math.cos(st.a), dy = Math.sin(st.a);
      ctx.beginPath();
      ctx.moveTo(tr.X(c[0] + 0.5 * r * dx), tr.Y(c[1] + 0.5 * r * dy));
      ctx.lineTo(tr.X(c[0] + 0.95 * r * dx), tr.Y(c[1] + 0.95 * r * dy));
      ctx.stroke();
    });
  }
  function drawBody(tr, b, st, style) {
    var colour = bodies[b].colour;
    bodyPath(tr, b, st);
    ctx.setLineDash(style === 'outline' ? [6, 4] : []);
    if (style === 'outline') {
      ctx.strokeStyle = colour; ctx.lineWidth = 2; ctx.stroke();
    } else {
      ctx.fillStyle = colour; ctx.fill();
      ctx.strokeStyle = darker(colour); ctx.lineWidth = 1; ctx.stroke();
      if (bodies[b].kind !== 'static') { circleTicks(tr, b, st); }
    }
    ctx.setLineDash([]);
  }
  function drawTrace(tr, run, b, loc, dashed) {
    var B = run.bodies[b];
    if (B.fixed) { return; }
    var st = stateOf(run, b, loc);
    ctx.beginPath();
    ctx.moveTo(tr.X(B.x[0]), tr.Y(B.y[0]));
    var last = keptBefore(B, loc[0]);
    for (var i = 1; i <= last; i++) { ctx.lineTo(tr.X(B.x[i]), tr.Y(B.y[i])); }
    ctx.lineTo(tr.X(st.x), tr.Y(st.y));
    ctx.strokeStyle = bodies[b].colour; ctx.globalAlpha = 0.55; ctx.lineWidth = 1.5;
    ctx.setLineDash(dashed ? [4, 4] : []);
    ctx.stroke();
    ctx.globalAlpha = 1; ctx.setLineDash([]);
  }
  function springEnd(end, run, loc) {
    if (end.world) { return end.world; }
    return place(stateOf(run, end.body, loc), end.local[0], end.local[1]);
  }
  function drawSpring(tr, a, b) {
    var X0 = tr.X(a[0]), Y0 = tr.Y(a[1]), X1 = tr.X(b[0]), Y1 = tr.Y(b[1]);
    var dx = X1 - X0, dy = Y1 - Y0, len = Math.hypot(dx, dy) || 1, n = 14, amp = 5;
    ctx.beginPath(); ctx.moveTo(X0, Y0);
    for (var i = 1; i < n; i++) {
      var f = i / n, side = (i % 2 ? 1 : -1) * amp;
      ctx.lineTo(X0 + dx * f - dy / len * side, Y0 + dy * f + dx / len * side);
    }
    ctx.lineTo(X1, Y1);
    ctx.strokeStyle = '#555'; ctx.lineWidth = 1; ctx.stroke();
  }
  function niceLength(px, s) {
    var m = px / s, p = Math.pow(10, Math.floor(Math.log10(m)));
    var best = p;
    [1, 2, 5, 10].forEach(function (f) { if (f * p <= m) { best = f * p; } });
    return best;
  }
  function fmtShort(v) { return Number(v.toPrecision(6)).toString(); }
  function drawScale(p, tr) {
    var len = niceLength(120, tr.s), X = p.x + 14, Y = p.y + p.h - 14;
    ctx.strokeStyle = '#333'; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.moveTo(X, Y - 5); ctx.lineTo(X, Y); ctx.lineTo(X + len * tr.s, Y); ctx.lineTo(X + len * tr.s, Y - 5);
    ctx.stroke();
    ctx.fillStyle = '#333'; ctx.font = '12px sans-serif'; ctx.textAlign = 'left'; ctx.textBaseline = 'bottom';
    ctx.fillText(fmtShort(len) + ' m', X + 4, Y - 4);
  }
  function drawPanel(k, members, n) {
    var p = panelRect(k, n), tr = transform(p);
    ctx.save();
    ctx.beginPath(); ctx.rect(p.x, p.y, p.w, p.h); ctx.clip();
    var primary = runs[members[0]], locs = members.map(function (r) { return locate(runs[r], t); });
    // Ground lines of landing events.
    ctx.strokeStyle = '#888'; ctx.lineWidth = 1; ctx.setLineDash([8, 5]);
    data.grounds.forEach(function (g) {
      ctx.beginPath(); ctx.moveTo(p.x, tr.Y(g)); ctx.lineTo(p.x + p.w, tr.Y(g)); ctx.stroke();
    });
    ctx.setLineDash([]);
    bodies.forEach(function (body, b) {
      if (body.kind === 'static') { drawBody(tr, b, stateOf(primary, b, locs[0]), 'fill'); }
    });
    if (traces) {
      members.forEach(function (r, m) {
        bodies.forEach(function (_, b) { drawTrace(tr, runs[r], b, locs[m], m > 0); });
      });
    }
    members.forEach(function (r, m) {
      data.springs.forEach(function (sp) {
        drawSpring(tr, springEnd(sp[0], runs[r], locs[m]), springEnd(sp[1], runs[r], locs[m]));
      });
    });
    members.forEach(function (r, m) {
      bodies.forEach(function (body, b) {
        if (body.kind !== 'static') {
          drawBody(tr, b, stateOf(runs[r], b, locs[m]), m === 0 ? 'fill' : 'outline');
        }
      });
    });
    if (pinned >= 0) {
      var st = stateOf(primary, pinned, locs[0]), R = Math.max(bodies[pinned].radius * tr.s, 4) + 4;
      ctx.beginPath(); ctx.arc(tr.X(st.x), tr.Y(st.y), R, 0, 2 * Math.PI);
      ctx.strokeStyle = '#000'; ctx.lineWidth = 1.5; ctx.setLineDash([3, 3]); ctx.stroke(); ctx.setLineDash([]);
    }
    // Event markers, each label once per place.
    var seen = {};
    ctx.font = '12px sans-serif'; ctx.textAlign = 'left'; ctx.textBaseline = 'bottom';
    members.forEach(function (r) {
      runs[r].events.forEach(function (e) {
        if (e.t > t || !e.at) { return; }
        var X = tr.X(e.at[0]), Y = tr.Y(e.at[1]), key = e.name + Math.round(X / 6) + ',' + Math.round(Y / 6);
        if (seen[key]) { return; }
        seen[key] = true;
        ctx.strokeStyle = '#d62728'; ctx.lineWidth = 1.5;
        ctx.beginPath(); ctx.moveTo(X - 5, Y); ctx.lineTo(X, Y - 5); ctx.lineTo(X + 5, Y); ctx.lineTo(X, Y + 5); ctx.closePath(); ctx.stroke();
        ctx.fillStyle = '#d62728'; ctx.fillText(e.name, X + 7, Y - 3);
      });
    });
    // Names above the moving bodies, when few enough to read, each where
    // it covers neither another body nor another name.
    if (moving <= 30) {
      ctx.fillStyle = '#333'; ctx.font = '12px sans-serif'; ctx.textAlign = 'center'; ctx.textBaseline = 'bottom';
      var boxes = [], placed = [];
      bodies.forEach(function (body, b) {
        var st = stateOf(primary, b, locs[0]), R = Math.max(body.radius * tr.s, 4);
        boxes.push({ b: b, x0: tr.X(st.x) - R, x1: tr.X(st.x) + R, y0: tr.Y(st.y) - R, y1: tr.Y(st.y) + R });
      });
      var overlaps = function (a, c) { return a.x0 < c.x1 && c.x0 < a.x1 && a.y0 < c.y1 && c.y0 < a.y1; };
      bodies.forEach(function (body, b) {
        if (body.kind === 'static') { return; }
        var box = boxes[b], X = (box.x0 + box.x1) / 2, Y = box.y0 - 3, w = ctx.measureText(body.name).width;
        var label = { x0: X - w / 2, x1: X + w / 2, y0: Y - 14, y1: Y };
        var blocked = boxes.some(function (o) { return o.b !== b && bodies[o.b].kind !== 'static' && overlaps(o, label); }) ||
          placed.some(function (o) { return overlaps(o, label); });
        if (!blocked) { placed.push(label); ctx.fillText(body.name, X, Y); }
      });
    }
    drawScale(p, tr);
    // The panel's label (and in an overlay, the style of each run).
    ctx.textAlign = 'left'; ctx.textBaseline = 'top'; ctx.font = '12px sans-serif';
    members.forEach(function (r, m) {
      var run = runs[r], end = run.t[run.t.length - 1];
      var text = (members.length > 1 ? (m === 0 ? 'filled: ' : 'dashed: ') : '') + run.label +
        (t > end ? ' (ended at t = ' + fmtShort(end) + ' s)' : '');
      var w = ctx.measureText(text).width;
      ctx.fillStyle = 'rgba(250,250,250,0.9)'; ctx.fillRect(p.x + 6, p.y + 6 + 18 * m, w + 8, 17);
      ctx.fillStyle = '#222'; ctx.fillText(text, p.x + 10, p.y + 8 + 18 * m);
    });
    ctx.restore();
    if (k > 0) {
      ctx.strokeStyle = '#bbb'; ctx.lineWidth = 1;
      ctx.beginPath(); ctx.moveTo(p.x + 0.5, 0); ctx.lineTo(p.x + 0.5, cssH); ctx.stroke();
    }
    return { p: p, tr: tr };
  }

  function render() {
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    ctx.fillStyle = '#ffffff'; ctx.fillRect(0, 0, cssW, cssH);
    var list = panels();
    list.forEach(function (members, k) { drawPanel(k, members, list.length); });
    var p0 = panelRect(0, list.length);
    canvas.dataset.panels = list.length;
    canvas.dataset.scale = baseScale(p0);
    canvas.dataset.zoom = zoom;
    canvas.dataset.panX = pan.x; canvas.dataset.panY = pan.y;
    canvas.dataset.t = t;
    $('time').textContent = 't = ' + t.toFixed(timeDecimals) + ' s of ' + t1.toFixed(timeDecimals) + ' s';
    $('time').dataset.t = t;
    var scrub = $('scrub');
    if (document.activeElement !== scrub || !scrubbing) {
      scrub.value = duration > 0 ? Math.round((t - t0) / duration * 10000) : 0;
    }
    $('play').textContent = playing ? '\u275a\u275a pause' : '\u25b6 play';
    readout();
    tooltip();
  }

  // ---- readouts ----------------------------------------------------------
  // A value to its quantum's decimals, or to 5 significant digits when
  // that would take more than 9 characters.
  function fixed(v, d) {
    var s = v.toFixed(d);
    if (Number(s) === 0) { return (0).toFixed(Math.min(d, 5)); }
    return s.length > 9 ? Number(v.toPrecision(5)).toString() : s;
  }
  function quantities(run, b, loc) {
    var st = stateOf(run, b, loc), body = bodies[b], q = run.q;
    var speedV = Math.hypot(st.vx, st.vy);
    var ke = body.mass === null ? null :
      0.5 * body.mass * speedV * speedV + (body.inertia === null ? 0 : 0.5 * body.inertia * st.w * st.w);
    var e = energyOf(run, loc);
    return [
      ['x', 'x (m)', fixed(st.x, decimals(q.p))],
      ['y', 'y (m)', fixed(st.y, decimals(q.p))],
      ['angle', 'angle (rad)', fixed(st.a, decimals(q.a))],
      ['vx', 'vx (m/s)', fixed(st.vx, decimals(q.v))],
      ['vy', 'vy (m/s)', fixed(st.vy, decimals(q.v))],
      ['speed', '|v| (m/s)', fixed(speedV, decimals(q.v))],
      ['omega', '\u03c9 (rad/s)', fixed(st.w, decimals(q.w))],
      ['kinetic', 'kinetic (J)', ke === null ? '-' : fmtShort(ke)],
      ['energy', 'world energy (J)', e === null ? '-' : Number(e.toPrecision(7)).toString()]
    ];
  }
  var lastReadout = '';
  function readout() {
    var b = pinned >= 0 ? pinned : (hovered ? hovered.body : -1);
    var table = $('readout');
    var key = b + ':' + t + ':' + overlay;
    if (key === lastReadout) { return; }
    lastReadout = key;
    table.textContent = '';
    if (b < 0) { $('pick').textContent = 'Hover a body to see its state; click it to pin it here.'; table.dataset.body = ''; return; }
    var body = bodies[b];
    $('pick').textContent = body.name + ' (' + body.kind + (body.mass !== null ? ', ' + fmtShort(body.mass) + ' kg' : '') +
      ')' + (pinned >= 0 ? ', pinned: click it again to unpin' : '');
    table.dataset.body = body.name;
    var head = document.createElement('thead'), row = document.createElement('tr');
    var th = document.createElement('th'); th.textContent = 'at t = ' + t.toFixed(timeDecimals) + ' s'; row.appendChild(th);
    runs.forEach(function (run) { var h = document.createElement('th'); h.textContent = run.short; row.appendChild(h); });
    head.appendChild(row); table.appendChild(head);
    var columns = runs.map(function (run) { return quantities(run, b, locate(run, t)); });
    var tbody = document.createElement('tbody');
    columns[0].forEach(function (q, i) {
      var tr = document.createElement('tr'), name = document.createElement('td');
      name.textContent = q[1]; tr.appendChild(name);
      columns.forEach(function (col, r) {
        var td = document.createElement('td');
        td.dataset.run = r; td.dataset.key = col[i][0]; td.textContent = col[i][2];
        tr.appendChild(td);
      });
      tbody.appendChild(tr);
    });
    table.appendChild(tbody);
  }
  function tooltip() {
    var tip = $('tooltip');
    if (!hovered) { tip.hidden = true; return; }
    var run = runs[hovered.run], loc = locate(run, t);
    var lines = [bodies[hovered.body].name + ' (' + run.short + ')'];
    quantities(run, hovered.body, loc).forEach(function (q) { lines.push(q[1] + ' = ' + q[2]); });
    tip.textContent = lines.join('\n');
    tip.hidden = false;
    tip.style.left = Math.min(hovered.X + 16, window.innerWidth - tip.offsetWidth - 4) + 'px';
    tip.style.top = Math.min(hovered.Y + 16, window.innerHeight - tip.offsetHeight - 4) + 'px';
  }

  // ---- picking -----------------------------------------------------------
  function inside(b, st, x, y, slack) {
    var parts = bodies[b].parts, c = Math.cos(-st.a), s = Math.sin(-st.a);
    var dx = x - st.x, dy = y - st.y, lx = c * dx - s * dy, ly = s * dx + c * dy;
    if (parts.length === 0) { return Math.hypot(dx, dy) <= slack + 1e-12; }
    return parts.some(function (part) {
      if (part.circle) { return Math.hypot(lx - part.circle[0], ly - part.circle[1]) <= part.circle[2] + slack; }
      var v = part.polygon;
      if (!v || v.length < 6) { return false; }
      for (var i = 0; i < v.length; i += 2) {
        var j = (i + 2) % v.length;
        var cross = (v[j] - v[i]) * (ly - v[i + 1]) - (v[j + 1] - v[i + 1]) * (lx - v[i]);
        if (cross < 0) { return false; }
      }
      return true;
    });
  }
  function pick(X, Y) {
    var list = panels(), n = list.length, k = Math.min(n - 1, Math.max(0, Math.floor(X / (cssW / n))));
    var p = panelRect(k, n), tr = transform(p), x = tr.x(X), y = tr.y(Y), r = list[k][0];
    var run = runs[r], loc = locate(run, t), slack = 4 / tr.s;
    for (var pass = 0; pass < 2; pass++) {
      for (var b = bodies.length - 1; b >= 0; b--) {
        if ((bodies[b].kind === 'static') !== (pass === 1)) { continue; }
        if (inside(b, stateOf(run, b, loc), x, y, slack)) { return { body: b, run: r }; }
      }
    }
    return null;
  }

  // ---- playing -----------------------------------------------------------
  function schedule() { if (timer === null) { timer = setTimeout(tick, 16); } }
  function tick() {
    timer = null;
    if (!playing) { return; }
    var now = performance.now();
    t += (now - last) / 1000 * speed;
    last = now;
    if (t >= stopAt) { t = stopAt; playing = false; }
    render();
    if (playing) { schedule(); }
  }
  function play(until) {
    if (t >= t1) { t = t0; }
    stopAt = until === undefined ? t1 : Math.min(until, t1);
    playing = true; last = performance.now();
    render(); schedule();
  }
  function pause() {
    playing = false;
    if (timer !== null) { clearTimeout(timer); timer = null; }
    render();
  }
  function seek(time) {
    playing = false;
    if (timer !== null) { clearTimeout(timer); timer = null; }
    t = Math.min(t1, Math.max(t0, time));
    render();
  }

  // ---- controls ----------------------------------------------------------
  var scrubbing = false;
  $('play').onclick = function () { if (playing) { pause(); } else { play(); } };
  $('start').onclick = function () { seek(t0); };
  $('end').onclick = function () { seek(t1); };
  $('back').onclick = function () { seek(t - data.step); };
  $('forward').onclick = function () { seek(t + data.step); };
  $('fit').onclick = function () { zoom = 1; pan = { x: 0, y: 0 }; render(); };
  $('scrub').oninput = function () { scrubbing = true; seek(t0 + this.value / 10000 * duration); };
  $('scrub').onchange = function () { scrubbing = false; };
  var select = $('speed');
  SPEEDS.forEach(function (v) {
    var o = document.createElement('option'); o.value = v; o.textContent = v + '\u00d7';
    if (v === speed) { o.selected = true; }
    select.appendChild(o);
  });
  select.onchange = function () { speed = Number(this.value); };
  $('traces').checked = traces;
  $('traces').onchange = function () { traces = this.checked; render(); };
  if (runs.length > 1) { $('mode-box').hidden = false; }
  $('overlay').onchange = function () { overlay = this.checked; render(); };
  document.addEventListener('keydown', function (e) {
    if (e.target.tagName === 'SELECT' || e.target.tagName === 'INPUT' && e.target.type === 'range') { return; }
    if (e.key === ' ') { e.preventDefault(); if (playing) { pause(); } else { play(); } }
    else if (e.key === 'ArrowRight') { seek(t + data.step); }
    else if (e.key === 'ArrowLeft') { seek(t - data.step); }
    else if (e.key === 'Home') { seek(t0); }
    else if (e.key === 'End') { seek(t1); }
  });
  canvas.addEventListener('wheel', function (e) {
    e.preventDefault();
    var r = canvas.getBoundingClientRect(), X = e.clientX - r.left, Y = e.clientY - r.top;
    var n = panels().length, p = panelRect(Math.min(n - 1, Math.floor(X / (cssW / n))), n);
    var cx = p.x + p.w / 2, cy = p.y + p.h / 2;
    var f = Math.pow(1.0015, -e.deltaY), z = Math.min(1e4, Math.max(1e-3, zoom * f));
    f = z / zoom;
    pan.x = X - cx - f * (X - cx - pan.x);
    pan.y = Y - cy - f * (Y - cy - pan.y);
    zoom = z;
    render();
  }, { passive: false });
  var drag = null;
  canvas.addEventListener('mousedown', function (e) {
    drag = { x: e.clientX, y: e.clientY, moved: false };
    canvas.classList.add('dragging');
  });
  window.addEventListener('mouseup', function (e) {
    if (drag && !drag.moved) {
      var r = canvas.getBoundingClientRect(), hit = pick(e.clientX - r.left, e.clientY - r.top);
      pinned = hit ? (hit.body === pinned ? -1 : hit.body) : -1;
      lastReadout = '';
      render();
    }
    drag = null;
    canvas.classList.remove('dragging');
  });
  canvas.addEventListener('mousemove', function (e) {
    var r = canvas.getBoundingClientRect(), X = e.clientX - r.left, Y = e.clientY - r.top;
    if (drag) {
      var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
      if (Math.abs(dx) + Math.abs(dy) > 2) { drag.moved = true; }
      if (drag.moved) { pan.x += dx; pan.y += dy; drag.x = e.clientX; drag.y = e.clientY; }
    }
    var hit = drag && drag.moved ? null : pick(X, Y);
    hovered = hit ? { body: hit.body, run: hit.run, X: e.clientX, Y: e.clientY } : null;
    lastReadout = '';
    render();
  });
  canvas.addEventListener('mouseleave', function () { hovered = null; lastReadout = ''; render(); });
  window.addEventListener('resize', resize);

  // ---- side panel --------------------------------------------------------
  $('title').textContent = data.title;
  $('subtitle').textContent = data.subtitle;
  data.notes.forEach(function (n) { var li = document.createElement('li'); li.textContent = n; $('notes').appendChild(li); });
  var list = $('events'), ticks = $('ticks'), shown = 0;
  runs.forEach(function (run, r) {
    run.events.forEach(function (e) {
      if (shown >= 300) { return; }
      shown++;
      var li = document.createElement('li');
      li.textContent = e.name + ' at t = ' + fmtShort(e.t) + ' s' + (e.body !== null ? ' (' + bodies[e.body].name + ')' : '') +
        (runs.length > 1 ? ', ' + run.short : '');
      li.onclick = function () { seek(e.t); };
      list.appendChild(li);
      if (r === 0 && duration > 0) {
        var mark = document.createElement('span');
        mark.style.left = ((e.t - t0) / duration * 100) + '%';
        mark.title = e.name + ' at t = ' + fmtShort(e.t) + ' s';
        mark.onclick = function () { seek(e.t); };
        ticks.appendChild(mark);
      }
    });
  });
  var total = runs.reduce(function (n, run) { return n + run.events.length; }, 0);
  if (total === 0) { list.innerHTML = '<li>none</li>'; }
  else if (total > shown) { var more = document.createElement('li'); more.textContent = '\u2026 and ' + (total - shown) + ' more'; list.appendChild(more); }

  // ---- start: the URL fragment -------------------------------------------
  function fromFragment() {
    var options = {};
    location.hash.replace(/^#/, '').split('&').forEach(function (kv) {
      if (!kv) { return; }
      var i = kv.indexOf('=');
      options[decodeURIComponent(i < 0 ? kv : kv.slice(0, i))] = i < 0 ? '' : decodeURIComponent(kv.slice(i + 1));
    });
    if (options.speed && Number(options.speed) > 0) {
      speed = Number(options.speed);
      if (SPEEDS.indexOf(speed) < 0) {
        var o = document.createElement('option'); o.value = speed; o.textContent = speed + '\u00d7'; select.appendChild(o);
      }
      select.value = String(speed);
    }
    if (options.mode !== undefined) { overlay = options.mode === 'overlay'; $('overlay').checked = overlay; }
    if (options.traces !== undefined) { traces = options.traces !== '0'; $('traces').checked = traces; }
    if (options.body !== undefined) {
      pinned = bodies.findIndex(function (b) { return b.name === options.body; });
      lastReadout = '';
    }
    if (options.t !== undefined && isFinite(Number(options.t))) { seek(Number(options.t)); }
    if (options.play !== undefined) {
      t = t0;
      play(options.play !== '' && isFinite(Number(options.play)) ? Number(options.play) : undefined);
    }
  }
  resize();
  fromFragment();
  window.addEventListener('hashchange', fromFragment);
})();
