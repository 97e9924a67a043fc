  // The plan viewer's 3D view (docs/viewer.md, "3D"). src/render/html.c
  // puts this file into the script of src/render/viewer.html, inside its
  // closure, for a 3D structure only; view3() then replaces the 2D view's
  // functions (fit, draw, bodyAt, zoomAt, panBy, dragBy, flat, seen), and all the
  // rest of the page (steps, hands, forces, verify, info box, controls) is
  // the 2D page's own, with the dimension as a parameter.
  //
  // Projection: orthographic, on the axes of the static 3D pictures
  // (src/render/scene3.c): toward the viewer e = (sin az cos el, -cos az
  // cos el, sin el), the picture's right r = (cos az, sin az, 0), its up
  // u = e x r. A world point p is drawn at X = ox + k (p . r), Y = oy -
  // k (p . u) (CSS pixels from the canvas's top left) at depth p . e
  // (larger is nearer). The canvas's data-view is "az el k ox oy".
  //
  // Hidden surfaces: each part is convex, so a face whose outward normal n
  // has n . e <= 0 is culled; the others are painted far to near by the
  // depth of their vertex centroid (the painter's algorithm, ties by body
  // then face), each face outlined right after it is filled so that nearer
  // faces cover the outlines behind them. Its limits are scene3.c's (a
  // long face beside a short one, cyclic overlaps). A body's number sits
  // on its largest face that is seen at its centre; contact dots are drawn
  // where no face is nearer than the point; force arrows everywhere, faint
  // where their point is hidden so (most contacts are inside, between two
  // bodies).
  //
  // The pointer: the face under it with the nearest plane there (exact for
  // convex parts: the depth of the plane n . x = d along the view ray),
  // found through a grid of the frame's face boxes in screen pixels.
  function view3() {
    var V = {az: +D.view[0], el: +D.view[1], k: 1, ox: 0, oy: 0}, R = [1, 0, 0], U = [0, 0, 1], E = [0, -1, 0];
    var DEG = Math.PI / 180;
    function dot(a, b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
    function axes() {
      var ca = Math.cos(V.az * DEG), sa = Math.sin(V.az * DEG), ce = Math.cos(V.el * DEG), se = Math.sin(V.el * DEG);
      E = [sa * ce, -ca * ce, se]; R = [ca, sa, 0];
      U = [E[1] * R[2] - E[2] * R[1], E[2] * R[0] - E[0] * R[2], E[0] * R[1] - E[1] * R[0]];
    }
    function px(p) { return [V.ox + V.k * dot(p, R), V.oy - V.k * dot(p, U)]; }

    // ---- faces, once: vertices, outward normal (Newell), plane d, centroid
    var lo3 = [Infinity, Infinity, Infinity], hi3 = [-Infinity, -Infinity, -Infinity];
    var faces = [], sizes = [], ext = new Float64Array(NB); // ext: a body's smallest box side
    D.bodies.forEach(function (b, i) {
      var lo = b.c.slice(), hi = b.c.slice();
      (b.parts || []).forEach(function (part) {
        var v = part.v;
        for (var q = 0; q < v.length; q += 3)
          for (var d = 0; d < 3; d++) { lo[d] = Math.min(lo[d], v[q + d]); hi[d] = Math.max(hi[d], v[q + d]); }
        part.f.forEach(function (f) {
          var pts = f.map(function (j) { return [v[3 * j], v[3 * j + 1], v[3 * j + 2]]; });
          var n = [0, 0, 0], c = [0, 0, 0];
          pts.forEach(function (a, m) {
            var b2 = pts[(m + 1) % pts.length];
            n[0] += (a[1] - b2[1]) * (a[2] + b2[2]); n[1] += (a[2] - b2[2]) * (a[0] + b2[0]); n[2] += (a[0] - b2[0]) * (a[1] + b2[1]);
            for (var d2 = 0; d2 < 3; d2++) c[d2] += a[d2] / pts.length;
          });
          var len = Math.hypot(n[0], n[1], n[2]);
          if (!(len > 0)) return;
          n = n.map(function (x) { return x / len; });
          faces.push({i: i, pts: pts, n: n, d: dot(n, pts[0]), c: c});
        });
      });
      for (var d3 = 0; d3 < 3; d3++) { lo3[d3] = Math.min(lo3[d3], lo[d3]); hi3[d3] = Math.max(hi3[d3], hi[d3]); }
      ext[i] = Math.min(hi[0] - lo[0], hi[1] - lo[1], hi[2] - lo[2]);
      if (ext[i] > 0) sizes.push(ext[i]);
    });
    if (!(lo3[0] <= hi3[0])) { lo3 = [0, 0, 0]; hi3 = [1, 1, 1]; }
    var mid = [0, 1, 2].map(function (d) { return (lo3[d] + hi3[d]) / 2; });
    span = Math.max(hi3[0] - lo3[0], hi3[1] - lo3[1], hi3[2] - lo3[2]) || 1;
    sizes.sort(function (a, b) { return a - b; });
    typical = sizes.length ? sizes[sizes.length >> 1] : span / 10;

    // ---- colours: the 2D page's (fill), shaded by face orientation as
    // scene3.c does: f = 0.70 + 0.30 n_z - 0.12 (n . r) in [0.25, 1]
    function baseRGB(i) {
      if (D.bodies[i].fixed) return [160, 160, 160];
      if (blocked[i]) return [232, 132, 122];
      if (step[i] >= 0) return rampRGB(stepT(step[i]));
      return NS ? [228, 228, 228] : [217, 199, 163];
    }
    var rgb = D.bodies.map(function (b, i) { return baseRGB(i); });
    function shade(c, n) {
      var f = Math.min(1, Math.max(0.25, 0.70 + 0.30 * n[2] - 0.12 * dot(n, R)));
      return "rgb(" + c.map(function (x) { return Math.round(x * f); }).join(",") + ")";
    }

    // ---- a frame: the front faces of the bodies present, far to near,
    // in screen pixels, with a grid of their boxes for the pointer and
    // each body's list
    var G = 24, frameKey = "", F = null;
    function frame() {
      var key = [pos, V.az, V.el, V.k, V.ox, V.oy, cw, ch].join(" ");
      if (key === frameKey && F) return F;
      axes();
      var list = [];
      faces.forEach(function (f, fi) {
        if (!present(f.i) || !(dot(f.n, E) > 1e-9)) return;
        var xy = [], x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
        f.pts.forEach(function (p) {
          var s = px(p);
          xy.push(s[0], s[1]);
          x0 = Math.min(x0, s[0]); y0 = Math.min(y0, s[1]); x1 = Math.max(x1, s[0]); y1 = Math.max(y1, s[1]);
        });
        list.push({f: f, fi: fi, xy: xy, z: dot(f.c, E), box: [x0, y0, x1, y1]});
      });
      list.sort(function (a, b) { return a.z - b.z || a.f.i - b.f.i || a.fi - b.fi; });
      var cells = [], byBody = [];
      list.forEach(function (e, q) {
        (byBody[e.f.i] || (byBody[e.f.i] = [])).push(e);
        var c = [cellX(e.box[0]), cellY(e.box[1]), cellX(e.box[2]), cellY(e.box[3])];
        for (var gx = c[0]; gx <= c[2]; gx++)
          for (var gy = c[1]; gy <= c[3]; gy++) (cells[gy * G + gx] || (cells[gy * G + gx] = [])).push(q);
      });
      frameKey = key;
      F = {list: list, cells: cells, byBody: byBody};
      return F;
    }
    function cellX(x) { return Math.min(G - 1, Math.max(0, Math.floor(x / cw * G))); }
    function cellY(y) { return Math.min(G - 1, Math.max(0, Math.floor(y / ch * G))); }
    function insidePoly(xy, x, y) {
      var c = false, n = xy.length;
      for (var k = 0, j = n - 2; k < n; j = k, k += 2)
        if ((xy[k + 1] > y) !== (xy[j + 1] > y) &&
            x < (xy[j] - xy[k]) * (y - xy[k + 1]) / (xy[j + 1] - xy[k + 1]) + xy[k]) c = !c;
      return c;
    }
    // the nearest face at canvas pixel (x, y) ({e: entry, z: its depth
    // there}), or null
    function hit(x, y) {
      var fr = frame(), best = null, bz = -Infinity;
      if (x < 0 || y < 0 || x > cw || y > ch) return null;
      (fr.cells[cellY(y) * G + cellX(x)] || []).forEach(function (q) {
        var e = fr.list[q], b = e.box;
        if (x < b[0] || x > b[2] || y < b[1] || y > b[3] || !insidePoly(e.xy, x, y)) return;
        var a = (x - V.ox) / V.k, c = (V.oy - y) / V.k, n = e.f.n; // the ray a r + c u + t e
        var z = (e.f.d - a * dot(n, R) - c * dot(n, U)) / dot(n, E);
        if (z > bz) { bz = z; best = e; }
      });
      return best ? {e: best, z: bz} : null;
    }
    // a world point on a surface is seen when no face is nearer there
    function visible(p) {
      var s = px(p), h = hit(s[0], s[1]);
      return !h || dot(p, E) >= h.z - 1e-6 * span;
    }

    // ---- drawing
    function grid() {
      if (!D.ground) return;
      var m = 0.1 * Math.max(hi3[0] - lo3[0], hi3[1] - lo3[1], span / 10);
      var x0 = lo3[0] - m, x1 = hi3[0] + m, y0 = lo3[1] - m, y1 = hi3[1] + m;
      var raw = Math.max(x1 - x0, y1 - y0) / 8, p10 = Math.pow(10, Math.floor(Math.log10(raw)));
      var step_ = [1, 2, 5, 10].map(function (f) { return f * p10; }).filter(function (s) { return s >= raw; })[0] || raw;
      ctx.beginPath();
      function seg(a, b) { var s = px(a), t = px(b); ctx.moveTo(s[0], s[1]); ctx.lineTo(t[0], t[1]); }
      for (var x = Math.ceil(x0 / step_) * step_; x <= x1; x += step_) seg([x, y0, 0], [x, y1, 0]);
      for (var y = Math.ceil(y0 / step_) * step_; y <= y1; y += step_) seg([x0, y, 0], [x1, y, 0]);
      ctx.strokeStyle = "#b4b4b4"; ctx.lineWidth = 1; ctx.stroke();
    }
    function outlineOf(i, failing) {
      if (hovered === i) return [INK.hover, 2.5];
      if (failing) return [INK.fail, 2];
      if (ACT) return held(i) ? [INK.hand, 2.5] : null;
      if (step[i] === pos) return [INK.next, 2.5];
      return blocked[i] ? [INK.fail, 1.5] : null;
    }
    function drawFaces(fr, failing) {
      ctx.lineJoin = "round";
      fr.list.forEach(function (e) {
        var i = e.f.i, xy = e.xy;
        ctx.beginPath();
        ctx.moveTo(xy[0], xy[1]);
        for (var k = 2; k < xy.length; k += 2) ctx.lineTo(xy[k], xy[k + 1]);
        ctx.closePath();
        ctx.fillStyle = shade(failing && D.verify.unstable_body === i ? [198, 40, 40] : rgb[i], e.f.n);
        ctx.fill();
        var o = outlineOf(i, failing);
        ctx.strokeStyle = o ? o[0] : "#000"; ctx.lineWidth = o ? o[1] : Math.min(1, 0.08 * typical * V.k);
        ctx.stroke();
      });
    }
    // a body's number on its largest face that is seen at its centre
    // (never over a nearer body), sized to the body and to that face
    function area(xy) {
      var a = 0;
      for (var k = 0, j = xy.length - 2; k < xy.length; j = k, k += 2) a += xy[j] * xy[k + 1] - xy[k] * xy[j + 1];
      return Math.abs(a) / 2;
    }
    function labelAt(fr, i) {
      var best = null;
      (fr.byBody[i] || []).forEach(function (e) {
        var s = px(e.f.c), h = hit(s[0], s[1]), a = area(e.xy);
        if (h && h.e === e && (!best || a > best.a)) best = {s: s, a: a};
      });
      return best;
    }
    function drawLabels(fr) {
      ctx.textAlign = "center"; ctx.textBaseline = "middle";
      var n = 0;
      for (var i = 0; i < NB; i++) {
        if (!present(i) || step[i] < 0) continue;
        var text = String(step[i] + 1), at = labelAt(fr, i);
        var size = at ? Math.min(ext[i] * V.k, Math.sqrt(at.a)) : 0;
        var fs = Math.round(2 * Math.min(0.45 * size, 0.9 * size / (0.6 * text.length))) / 2;
        if (!(fs >= 5)) continue;
        ctx.font = fs + "px sans-serif";
        ctx.fillStyle = stepT(step[i]) < 0.6 ? "#fff" : "#000";
        ctx.fillText(text, at.s[0], at.s[1]);
        n++;
      }
      canvas.dataset.labels = n;
    }
    function drawHands() {
      if (!ACT) return;
      ctx.beginPath();
      heldAt[pos].forEach(function (i) {
        var s = px(D.bodies[i].c), r = Math.max(7, 0.25 * typical * V.k);
        ctx.moveTo(s[0] + r, s[1]); ctx.arc(s[0], s[1], r, 0, 2 * Math.PI);
      });
      ctx.strokeStyle = INK.hand; ctx.lineWidth = 2.5; ctx.stroke();
    }
    // contact points where no face is nearer
    function drawDots() {
      var r = Math.min(typical * 0.04 * V.k, 4);
      if (!(r >= 0.7)) return;
      ctx.beginPath();
      for (var j = 0; j < NC; j++) {
        var c = D.contacts[j];
        if (!contactOn(c)) continue;
        var p = pointOf(c), s = px(p);
        if (!visible(p)) continue;
        ctx.moveTo(s[0] + r, s[1]); ctx.arc(s[0], s[1], r, 0, 2 * Math.PI);
      }
      ctx.fillStyle = INK.dot; ctx.fill();
    }
    draw = function () {
      var fr = frame(), failing = fail && fail.pos === pos && fail.kind === "fail";
      ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
      ctx.clearRect(0, 0, cw, ch);
      grid();
      drawFaces(fr, failing);
      drawLabels(fr);
      drawHands();
      drawDots();
      drawForces({k: V.k, ox: V.ox, oy: V.oy});
      canvas.dataset.faces = fr.list.length;
    };
    flat = function (v) { return [dot(v, R), dot(v, U)]; };
    seen = function (e) { return visible(e.p); };

    // ---- the view: fit, zoom about a point, pan, orbit about the centre
    function setView() {
      canvas.dataset.view = [V.az, V.el, V.k, V.ox, V.oy].join(" ");
      schedule();
    }
    fit = function () {
      V.az = +D.view[0]; V.el = +D.view[1]; V.k = 1; V.ox = V.oy = 0;
      axes();
      var x0 = Infinity, x1 = -Infinity, y0 = Infinity, y1 = -Infinity;
      faces.forEach(function (f) {
        f.pts.forEach(function (p) {
          var s = px(p);
          x0 = Math.min(x0, s[0]); x1 = Math.max(x1, s[0]); y0 = Math.min(y0, s[1]); y1 = Math.max(y1, s[1]);
        });
      });
      if (!(x0 <= x1)) { x0 = y0 = -1; x1 = y1 = 1; }
      var pad = 0.06 * Math.max(x1 - x0, y1 - y0, 1e-9);
      V.k = Math.min(cw / (x1 - x0 + 2 * pad), ch / (y1 - y0 + 2 * pad));
      V.ox = cw / 2 - V.k * (x0 + x1) / 2; V.oy = ch / 2 - V.k * (y0 + y1) / 2;
      setView();
    };
    zoomAt = function (f, clientX, clientY) {
      var r = canvas.getBoundingClientRect(), x = clientX - r.left, y = clientY - r.top;
      V.k /= f; V.ox = x - (x - V.ox) / f; V.oy = y - (y - V.oy) / f;
      setView();
    };
    panBy = function (dx, dy) { V.ox += dx; V.oy += dy; setView(); };
    function orbit(dx, dy) {
      axes();
      var before = px(mid);
      V.az = ((V.az - 0.5 * dx) % 360 + 360) % 360;
      V.el = Math.max(-89, Math.min(89, V.el + 0.5 * dy));
      axes();
      var after = px(mid);
      V.ox += before[0] - after[0]; V.oy += before[1] - after[1];
      setView();
    }
    dragBy = function (dx, dy, e) {
      if (e && (e.shiftKey || (e.buttons & 2))) panBy(dx, dy); else orbit(dx, dy);
    };
    bodyAt = function (clientX, clientY) {
      var r = canvas.getBoundingClientRect(), h = hit(clientX - r.left, clientY - r.top);
      return h ? h.e.f.i : null;
    };
    canvas.addEventListener("contextmenu", function (e) { e.preventDefault(); });
  }
