/* simiam replay: draws a recorded QuickBot run (the packed Seam-2 trace in #simiam-data) on a canvas.
   Controls follow the original Sim.I.am GUI: home, rewind, play/pause, zoom (buttons and wheel), pan by
   dragging, click the robot to follow it; plus a time slider, playback speed and keyboard shortcuts.
   window.simiam is a small API for tests and for curious students in the browser console. */
(function () {
  "use strict";

  // The run's data: JSON as it is, or (a batch's replay pages) deflated and base64-encoded, unpacked by the
  // browser's own DecompressionStream before the page starts.
  var DATA = document.getElementById("simiam-data");
  if (DATA.type === "application/json") {
    start(JSON.parse(DATA.textContent));
  } else {
    unpacked(DATA.textContent).then(function (text) { start(JSON.parse(text)); }, function (err) {
      var line = document.getElementById("status");
      if (line) { line.textContent = "This browser could not unpack the replay (" + err + "): it needs " +
                  "Chrome 80, Firefox 113, Safari 16.4 or later."; }
    });
  }

  function unpacked(text) {
    try {
      var bytes = Uint8Array.from(atob(text.trim()), function (c) { return c.charCodeAt(0); });
      return new Response(new Blob([bytes]).stream().pipeThrough(new DecompressionStream("deflate"))).text();
    } catch (err) {
      return Promise.reject(err);
    }
  }

  function start(D) {
  var S = D.steps;
  var SIGS = D.signals || [], SD = D.signal_data || {};   // the run's declared debug signals, by name
  var N = S.t.length;
  var T0 = S.t[0], TEND = S.t[N - 1];
  // A run that stops for good long before its end (week 5 at its goal after 9 s of a 60 s run): the plots
  // end a little after the robot last moved, instead of squeezing the run into the first sixth of the axis.
  var TPLOT = (function () {
    var k = N - 1, eps = 1e-6;
    while (k > 0 && Math.abs(S.x[k] - S.x[k - 1]) < eps && Math.abs(S.y[k] - S.y[k - 1]) < eps &&
           Math.abs(S.theta[k] - S.theta[k - 1]) < eps) { k--; }
    var last = D.states.length ? D.states[D.states.length - 1][0] : 0;   // nor did its state change since
    var still = S.t[Math.max(k, last)];
    if (still <= T0) { return TEND; }        // a robot that never moved: nothing to zoom on
    return TEND - still > 0.25 * (TEND - T0) ? Math.min(TEND, still + Math.max(1, 0.1 * (still - T0))) : TEND;
  })();

  var COLORS = {
    body: "#3d6fb6", bodyEdge: "#16325c", ghost: "rgba(120,120,130,0.55)", trail: "#3d6fb6",
    trailEst: "#8a8f98", heading: "#1f4fd1", cross: "#111",
    goal: "#1a7f37", obstacle: "#9aa3ae", obstacleEdge: "#5b6573", grid: "#eef0f3", crash: "#d1242f",
    series: ["#1f4fd1", "#d1242f", "#1a7f37", "#b35900", "#7a3db8", "#0f8b8d"],
    overlay: ["#d1242f", "#1a7f37", "#b35900", "#7a3db8", "#0f8b8d", "#c2185b", "#5d4037"],
    unnamed: "#8a8f98"
  };

  // ---------- the debug signals the trace declares: vectors, points and headings are toggled overlays ----------
  var OVERLAYS = [];
  (function () {
    var hasVector = SIGS.some(function (g) { return g.kind === "vector2" && g.unit !== "coefficients"; }), colour = 0;
    SIGS.forEach(function (g) {
      // two coefficients (unit "coefficients": week 7's sigma) are no vector in the world: plotted, not drawn
      var world = g.kind === "vector2" && g.unit !== "coefficients";
      if (world || g.kind === "points" || (g.kind === "scalar" && g.unit === "rad")) {
        var heading = g.kind === "scalar";
        OVERLAYS.push({ name: g.name, kind: g.kind, data: SD[g.name],
                        color: g.kind === "points" ? COLORS.cross : COLORS.overlay[colour++ % COLORS.overlay.length],
                        // a heading is drawn by default only when no vector is (week 4: u_ao, not θ_ao)
                        on: !(heading && hasVector) });
      }
    });
  })();

  var ICON_PLAY = document.getElementById("btn-play").innerHTML;
  var ICON_PAUSE = "<svg viewBox=\"0 0 16 16\" width=\"16\" height=\"16\" fill=\"currentColor\" aria-hidden=\"true\"><rect x=\"3\" y=\"2\" width=\"3.5\" height=\"12\"/>" +
    "<rect x=\"9.5\" y=\"2\" width=\"3.5\" height=\"12\"/></svg>";
  var canvas = document.getElementById("world");
  var ctx = canvas.getContext("2d");
  var slider = document.getElementById("slider");
  var clock = document.getElementById("clock");
  var statusEl = document.getElementById("status");
  var playBtn = document.getElementById("btn-play");
  var followBtn = document.getElementById("btn-follow");
  var speedSel = document.getElementById("speed");

  var st = { t: T0, index: 0, playing: false, speed: 1, following: false,
             cx: 0, cy: 0, zoom: 100, atHome: true, W: 1, H: 1, lastFrame: null, lastStatusIndex: -1 };

  // ---------- geometry ----------
  function pose(i) { return [S.x[i], S.y[i], S.theta[i]]; }
  function poseEst(i) {
    if (S.x_est[i] === null || S.x_est[i] === undefined) { return null; }
    return [S.x_est[i], S.y_est[i], S.theta_est[i]];
  }
  function toWorld(p, q) {           // p: robot-frame point, q: pose
    var c = Math.cos(q[2]), s = Math.sin(q[2]);
    return [q[0] + c * p[0] - s * p[1], q[1] + s * p[0] + c * p[1]];
  }
  function sx(x) { return st.W / 2 + (x - st.cx) * st.zoom; }
  function sy(y) { return st.H / 2 - (y - st.cy) * st.zoom; }
  function wx(px) { return st.cx + (px - st.W / 2) / st.zoom; }
  function wy(py) { return st.cy - (py - st.H / 2) / st.zoom; }

  // The original's 6-vertex cone (ProximitySensor): apex, five far points on the circle of radius r.
  function cone(r) {
    var phi = D.robot.ir_spread, r1 = r * Math.tan(phi / 4), r2 = r * Math.tan(phi / 2);
    return [[0, 0], [Math.sqrt(r * r - r2 * r2), r2], [Math.sqrt(r * r - r1 * r1), r1], [r, 0],
            [Math.sqrt(r * r - r1 * r1), -r1], [Math.sqrt(r * r - r2 * r2), -r2]];
  }

  function worldBounds() {
    var b = [Infinity, Infinity, -Infinity, -Infinity];
    function add(x, y) {
      if (x === null || y === null || !isFinite(x) || !isFinite(y)) { return; }
      if (x < b[0]) { b[0] = x; } if (y < b[1]) { b[1] = y; }
      if (x > b[2]) { b[2] = x; } if (y > b[3]) { b[3] = y; }
    }
    D.world.obstacles.forEach(function (poly) { poly.forEach(function (p) { add(p[0], p[1]); }); });
    for (var i = 0; i < N; i++) { add(S.x[i], S.y[i]); }
    if (D.goal) { add(D.goal[0], D.goal[1]); }
    if (!isFinite(b[0])) { b = [-1, -1, 1, 1]; }
    return b;
  }
  var BOUNDS = worldBounds();

  function indexAt(t) {                 // last row with S.t <= t
    var lo = 0, hi = N - 1;
    if (t <= S.t[0]) { return 0; }
    if (t >= S.t[hi]) { return hi; }
    while (hi - lo > 1) {
      var mid = (lo + hi) >> 1;
      if (S.t[mid] <= t) { lo = mid; } else { hi = mid; }
    }
    return lo;
  }

  // ---------- view ----------
  function resize() {
    var r = canvas.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
    st.W = Math.max(1, r.width); st.H = Math.max(1, r.height);
    canvas.width = Math.round(st.W * dpr); canvas.height = Math.round(st.H * dpr);
    ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    plots.forEach(function (p) { p.resize(); });
  }
  function home() {
    var w = BOUNDS[2] - BOUNDS[0], h = BOUNDS[3] - BOUNDS[1];
    // the world fits above the legend, which would otherwise cover the bottom wall
    var legend = document.getElementById("legend"), below = legend ? legend.offsetHeight + 10 : 0;
    var room = Math.max(st.H - below, st.H / 2);
    st.zoom = Math.max(5, 0.92 * Math.min(st.W / Math.max(w, 0.6), room / Math.max(h, 0.6)));
    st.cx = (BOUNDS[0] + BOUNDS[2]) / 2; st.cy = (BOUNDS[1] + BOUNDS[3]) / 2 - (st.H - room) / 2 / st.zoom;
    setFollowing(false);
    st.atHome = true;
  }
  function zoomAt(factor, px, py) {
    var z = Math.min(20000, Math.max(5, st.zoom * factor));
    st.atHome = false;
    if (px === undefined || st.following) { st.zoom = z; return; }
    var x = wx(px), y = wy(py);        // keep the world point under the cursor fixed
    st.zoom = z;
    st.cx = x - (px - st.W / 2) / st.zoom; st.cy = y + (py - st.H / 2) / st.zoom;
  }
  function setFollowing(on) {
    st.following = !!on;
    if (st.following) { st.atHome = false; }
    followBtn.setAttribute("aria-pressed", st.following ? "true" : "false");
    if (st.following) { centreOnRobot(); }
  }
  function centreOnRobot() { st.cx = S.x[st.index]; st.cy = S.y[st.index]; }

  // ---------- drawing the world ----------
  function pathPoly(pts, close) {
    ctx.beginPath();
    pts.forEach(function (p, k) { if (k === 0) { ctx.moveTo(sx(p[0]), sy(p[1])); } else { ctx.lineTo(sx(p[0]), sy(p[1])); } });
    if (close) { ctx.closePath(); }
  }
  function drawGrid() {
    var step = niceStep(80 / st.zoom);
    var x0 = Math.floor(wx(0) / step) * step, x1 = wx(st.W), y0 = Math.floor(wy(st.H) / step) * step, y1 = wy(0);
    ctx.strokeStyle = COLORS.grid; ctx.lineWidth = 1; ctx.beginPath();
    for (var x = x0; x <= x1; x += step) { ctx.moveTo(sx(x), 0); ctx.lineTo(sx(x), st.H); }
    for (var y = y0; y <= y1; y += step) { ctx.moveTo(0, sy(y)); ctx.lineTo(st.W, sy(y)); }
    ctx.stroke();
    // scale bar, bottom right; lifted above the legend where the legend (wrapped on a narrow page) reaches it
    var len = step * st.zoom, bx = st.W - 16 - len, by = st.H - 14;
    var legend = document.getElementById("legend");
    if (legend) {
      var cr = canvas.getBoundingClientRect(), lr = legend.getBoundingClientRect();
      if (lr.width > 0 && lr.right - cr.left > bx - 24) { by = Math.min(by, lr.top - cr.top - 8); }
    }
    st.scaleBar = [bx - 20, by - 18, len + 40, 24];   // its box (label included), in canvas pixels
    ctx.strokeStyle = "#3a4450"; ctx.lineWidth = 2; ctx.beginPath();
    ctx.moveTo(bx, by); ctx.lineTo(bx + len, by); ctx.moveTo(bx, by - 4); ctx.lineTo(bx, by + 4);
    ctx.moveTo(bx + len, by - 4); ctx.lineTo(bx + len, by + 4); ctx.stroke();
    ctx.fillStyle = "#3a4450"; ctx.font = "11px system-ui, sans-serif"; ctx.textAlign = "center";
    ctx.fillText(fmtLen(step), bx + len / 2, by - 6); ctx.textAlign = "left";
  }
  function niceStep(raw) {
    var p = Math.pow(10, Math.floor(Math.log10(raw))), m = raw / p;
    return p * (m < 1.5 ? 1 : m < 3.5 ? 2 : m < 7.5 ? 5 : 10);
  }
  function fmtLen(m) { return m >= 1 ? m + " m" : Math.round(m * 1000) / 10 + " cm"; }

  function drawTrail(xs, ys, upto, color, dash) {
    ctx.strokeStyle = color; ctx.lineWidth = 1.5; ctx.setLineDash(dash || []); ctx.beginPath();
    var started = false;
    for (var i = 0; i <= upto; i++) {
      if (xs[i] === null) { started = false; continue; }
      if (!started) { ctx.moveTo(sx(xs[i]), sy(ys[i])); started = true; } else { ctx.lineTo(sx(xs[i]), sy(ys[i])); }
    }
    ctx.stroke(); ctx.setLineDash([]);
  }
  function drawRobot(q, ghost) {
    var plate = D.robot.base_plate.map(function (p) { return toWorld(p, q); });
    pathPoly(plate, true);
    if (ghost) {
      ctx.setLineDash([4, 3]); ctx.strokeStyle = COLORS.ghost; ctx.lineWidth = 1.5; ctx.stroke();
      ctx.fillStyle = "rgba(140,140,150,0.12)"; ctx.fill(); ctx.setLineDash([]);
      return;
    }
    ctx.fillStyle = COLORS.body; ctx.globalAlpha = 0.85; ctx.fill(); ctx.globalAlpha = 1;
    ctx.strokeStyle = COLORS.bodyEdge; ctx.lineWidth = 1.2; ctx.stroke();
    // wheels (drawing only, as in the original) to show which way is forward
    [[-0.0384, 0.0335, 0.0254, 0.0595], [-0.0384, -0.0595, 0.0254, -0.0335]].forEach(function (w) {
      pathPoly([[w[0], w[1]], [w[2], w[1]], [w[2], w[3]], [w[0], w[3]]].map(function (p) { return toWorld(p, q); }), true);
      ctx.fillStyle = "#222"; ctx.fill();
    });
  }
  function drawCones(i, q) {
    var mounts = D.robot.ir_mounts, lo = D.robot.ir_min_range, hi = D.robot.ir_max_range;
    for (var k = 0; k < mounts.length; k++) {
      var r = S["ir" + k] ? S["ir" + k][i] : null;
      var seen = r !== null && r !== undefined;
      if (!seen) { r = hi; }
      var m = mounts[k];
      var pts = cone(r).map(function (p) { return toWorld(toWorld(p, m), q); });
      var near = seen ? Math.min(1, Math.max(0, (hi - r) / (hi - lo))) : 0;   // 0 far .. 1 touching
      pathPoly(pts, true);
      ctx.fillStyle = "rgba(" + Math.round(120 + 135 * near) + "," + Math.round(170 - 120 * near) + "," +
        Math.round(220 - 170 * near) + "," + (0.18 + 0.5 * near).toFixed(3) + ")";
      ctx.fill();
      ctx.strokeStyle = near > 0.001 ? "rgba(209,36,47,0.8)" : "rgba(80,120,170,0.6)"; ctx.lineWidth = 1; ctx.stroke();
    }
  }
  function arrow(x0, y0, x1, y1, color, width, dash) {
    var a = Math.atan2(y1 - y0, x1 - x0), h = 7;
    ctx.strokeStyle = color; ctx.fillStyle = color; ctx.lineWidth = width; ctx.setLineDash(dash || []);
    ctx.beginPath(); ctx.moveTo(x0, y0); ctx.lineTo(x1, y1); ctx.stroke(); ctx.setLineDash([]);
    if (Math.hypot(x1 - x0, y1 - y0) < 2) { return; }
    ctx.beginPath(); ctx.moveTo(x1, y1);
    ctx.lineTo(x1 - h * Math.cos(a - 0.4), y1 - h * Math.sin(a - 0.4));
    ctx.lineTo(x1 - h * Math.cos(a + 0.4), y1 - h * Math.sin(a + 0.4)); ctx.closePath(); ctx.fill();
  }
  function drawGoal() {
    if (!D.goal) { return; }
    var gx = sx(D.goal[0]), gy = sy(D.goal[1]), r = Math.max(5, 0.03 * st.zoom);
    ctx.strokeStyle = COLORS.goal; ctx.lineWidth = 2;
    ctx.beginPath(); ctx.arc(gx, gy, r, 0, 2 * Math.PI); ctx.stroke();
    ctx.beginPath(); ctx.arc(gx, gy, r / 3, 0, 2 * Math.PI); ctx.fillStyle = COLORS.goal; ctx.fill();
    ctx.font = "11px system-ui, sans-serif"; ctx.fillText("goal", gx + r + 3, gy - r);
  }
  function drawCollision() {
    var c = D.collision;
    if (!c) { return; }
    var hit = st.t >= c.t - 1e-9, x = sx(c.pose[0]), y = sy(c.pose[1]), r = 9;
    ctx.globalAlpha = hit ? 1 : 0.35;
    // the body where it touched, outlined in red
    pathPoly(D.robot.base_plate.map(function (p) { return toWorld(p, c.pose); }), true);
    ctx.setLineDash([3, 2]); ctx.strokeStyle = COLORS.crash; ctx.lineWidth = 1.5; ctx.stroke(); ctx.setLineDash([]);
    ctx.strokeStyle = COLORS.crash; ctx.lineWidth = 3; ctx.beginPath();
    ctx.moveTo(x - r, y - r); ctx.lineTo(x + r, y + r); ctx.moveTo(x + r, y - r); ctx.lineTo(x - r, y + r); ctx.stroke();
    ctx.beginPath(); ctx.arc(x, y, r + 5, 0, 2 * Math.PI); ctx.lineWidth = 1.5; ctx.stroke();
    ctx.fillStyle = COLORS.crash; ctx.font = "bold 12px system-ui, sans-serif";
    var label = "collision at t = " + c.t.toFixed(2) + " s", lw = ctx.measureText(label).width, h = 17;
    // right of the mark, else left, above or below it: the first place on the canvas that covers no wall
    // (a crash happens at a wall, so the label's first choice often lies over one); else the least bad
    var places = [[x + r + 8, y - 9], [x - r - 8 - lw, y - 9], [x - lw / 2, y - r - 10 - h], [x - lw / 2, y + r + 10]];
    var best = null;
    places.forEach(function (p) {
      var box = [p[0] - 3, p[1], lw + 6, h];
      var off = box[0] < 0 || box[1] < 0 || box[0] + box[2] > st.W || box[1] + box[3] > st.H;
      var cost = (off ? 1000 : 0) + wallsUnder(box);
      if (best === null || cost < best.cost) { best = { cost: cost, lx: p[0], top: p[1] }; }
    });
    st.crashLabel = [best.lx, lw];
    st.crashBox = [best.lx - 3, best.top, lw + 6, h];
    ctx.fillStyle = "rgba(255,255,255,0.85)"; ctx.fillRect(best.lx - 3, best.top, lw + 6, h);  // readable over the trail
    ctx.fillStyle = COLORS.crash; ctx.fillText(label, best.lx, best.top + 13);
    ctx.globalAlpha = 1;
  }
  // How many obstacle edges cross the canvas box [x, y, w, h], plus one for an obstacle that holds its middle.
  function wallsUnder(box) {
    var n = 0, x0 = box[0], y0 = box[1], x1 = box[0] + box[2], y1 = box[1] + box[3];
    D.world.obstacles.forEach(function (poly) {
      var pts = poly.map(function (p) { return [sx(p[0]), sy(p[1])]; }), inside = false;
      for (var k = 0, j = pts.length - 1; k < pts.length; j = k++) {
        if (segmentMeetsBox(pts[j], pts[k], x0, y0, x1, y1)) { n++; }
        var a = pts[j], b = pts[k], my = (y0 + y1) / 2, mx = (x0 + x1) / 2;
        if ((a[1] > my) !== (b[1] > my) && mx < a[0] + (my - a[1]) * (b[0] - a[0]) / (b[1] - a[1])) { inside = !inside; }
      }
      if (inside) { n++; }
    });
    return n;
  }
  function segmentMeetsBox(a, b, x0, y0, x1, y1) {   // Liang-Barsky clipping: any part of a-b inside the box
    var t0 = 0, t1 = 1, dx = b[0] - a[0], dy = b[1] - a[1];
    var ps = [-dx, dx, -dy, dy], qs = [a[0] - x0, x1 - a[0], a[1] - y0, y1 - a[1]];
    for (var k = 0; k < 4; k++) {
      if (ps[k] === 0) { if (qs[k] < 0) { return false; } continue; }
      var u = qs[k] / ps[k];
      if (ps[k] < 0) { t0 = Math.max(t0, u); } else { t1 = Math.min(t1, u); }
      if (t0 > t1) { return false; }
    }
    return true;
  }
  function drawDebug(i, q, qe) {
    var from = qe || q, L = Math.max(0.25, 60 / st.zoom);
    // the heading line (theta, from the estimate as the original drew it), blue
    arrow(sx(from[0]), sy(from[1]), sx(from[0] + L * Math.cos(from[2])), sy(from[1] + L * Math.sin(from[2])),
          COLORS.heading, 2);
    OVERLAYS.forEach(function (o) {
      if (!o.on) { return; }
      if (o.kind === "scalar") {                    // a heading: a dashed direction from the estimate
        var a = o.data[i];
        if (a !== null && a !== undefined) {
          arrow(sx(from[0]), sy(from[1]), sx(from[0] + L * Math.cos(a)), sy(from[1] + L * Math.sin(a)), o.color, 2, [5, 3]);
        }
      } else if (o.kind === "vector2") {            // a vector in the world frame: an arrow from the estimate
        var ux = o.data.x[i], uy = o.data.y[i];
        if (ux !== null && ux !== undefined && uy !== null && uy !== undefined) {
          arrow(sx(from[0]), sy(from[1]), sx(from[0] + ux), sy(from[1] + uy), o.color, 2.5);
        }
      } else {                                      // points in the world frame: crosses
        ctx.strokeStyle = o.color; ctx.lineWidth = 1.8;
        for (var k = 0; k < o.data.x.length; k++) {
          var px = o.data.x[k][i], py = o.data.y[k][i];
          if (px === null || px === undefined || py === null || py === undefined) { continue; }
          var x = sx(px), y = sy(py);
          ctx.beginPath(); ctx.moveTo(x - 5, y - 5); ctx.lineTo(x + 5, y + 5); ctx.moveTo(x + 5, y - 5); ctx.lineTo(x - 5, y + 5); ctx.stroke();
        }
      }
    });
  }
  function draw() {
    var i = st.index, q = pose(i), qe = poseEst(i);
    ctx.clearRect(0, 0, st.W, st.H);
    drawGrid();
    D.world.obstacles.forEach(function (poly) {
      pathPoly(poly, true); ctx.fillStyle = COLORS.obstacle; ctx.fill();
      ctx.strokeStyle = COLORS.obstacleEdge; ctx.lineWidth = 1; ctx.stroke();
    });
    drawGoal();
    drawTrail(S.x_est, S.y_est, i, COLORS.trailEst, [4, 4]);
    drawTrail(S.x, S.y, i, COLORS.trail);
    drawCones(i, q);
    if (qe) { drawRobot(qe, true); }
    drawRobot(q, false);
    drawDebug(i, q, qe);
    drawCollision();
  }

  // ---------- plots linked to the time cursor ----------
  var LABEL_FONT = "10px system-ui, sans-serif";
  function wrap(a) { return a === null || a === undefined ? null : Math.atan2(Math.sin(a), Math.cos(a)); }
  function Plot(title, series, fixed, rows) {
    var box = document.createElement("div"), h = document.createElement("h2"), c = document.createElement("canvas");
    box.className = rows ? "plot timeline" : "plot";
    h.textContent = title;
    series.forEach(function (s) {
      var key = document.createElement("span"); key.className = "key";
      key.style.color = s.color; key.textContent = (s.dash ? "╌ " : "— ") + s.label;
      h.appendChild(key);
    });
    box.appendChild(h); box.appendChild(c);
    document.getElementById("plots").appendChild(box);
    var lo = Infinity, hi = -Infinity;
    series.forEach(function (s) { s.ys.forEach(function (v) { if (v !== null && isFinite(v)) { lo = Math.min(lo, v); hi = Math.max(hi, v); } }); });
    if (!isFinite(lo)) { lo = 0; hi = 1; }
    if (fixed) { lo = Math.min(lo, fixed[0]); hi = Math.max(hi, fixed[1]); }
    if (hi - lo < 1e-9) { lo -= 0.5; hi += 0.5; }
    var pad = 0.06 * (hi - lo); lo -= pad; hi += pad;
    var self = { canvas: c, w: 1, h: 1, back: null };
    var ML = 38, MR = 4, MT = 4, MB = 14;
    function px(t) { return ML + (Math.min(t, TPLOT) - T0) / Math.max(TPLOT - T0, 1e-9) * (self.w - ML - MR); }
    function py(v) { return MT + (hi - v) / (hi - lo) * (self.h - MT - MB); }
    if (rows) {   // the row labels' margin fits the widest label ("obstacle_cleared" lost its "o" at 92 px)
      var m = document.createElement("canvas").getContext("2d"); m.font = LABEL_FONT;
      ML = 8 + Math.ceil(Math.max.apply(null, rows.map(function (row) { return m.measureText(rowLabel(row)).width; })));
      c.style.height = (MT + MB + 16 * rows.length) + "px";
    }
    self.labelMargin = ML;
    self.tAt = function (clientX) {
      var r = c.getBoundingClientRect();
      return T0 + (clientX - r.left - ML) / (self.w - ML - MR) * (TPLOT - T0);
    };
    self.resize = function () {
      var r = c.getBoundingClientRect(), dpr = window.devicePixelRatio || 1;
      self.w = Math.max(1, r.width); self.h = Math.max(1, r.height);
      c.width = Math.round(self.w * dpr); c.height = Math.round(self.h * dpr);
      // draw the lines once into an offscreen canvas; each frame only blits it and adds the cursor
      var b = document.createElement("canvas"); b.width = c.width; b.height = c.height;
      var g = b.getContext("2d"); g.setTransform(dpr, 0, 0, dpr, 0, 0);
      g.font = LABEL_FONT; g.fillStyle = "#5b6573"; g.strokeStyle = "#e3e7ec"; g.lineWidth = 1;
      if (rows) { paintRows(g, rows, px, ML, MT); }
      (rows ? [] : [lo + pad, (lo + hi) / 2, hi - pad]).forEach(function (v) {
        g.beginPath(); g.moveTo(ML, py(v)); g.lineTo(self.w - MR, py(v)); g.stroke();
        g.fillText(fmtNum(v), 1, py(v) + 3);
      });
      g.fillText(T0.toFixed(0) + " s", ML, self.h - 2);
      var end = TPLOT < TEND ? TPLOT.toFixed(1) + " s (still until " + TEND.toFixed(0) + " s)" : TEND.toFixed(1) + " s";
      g.textAlign = "right"; g.fillText(end, self.w - MR, self.h - 2); g.textAlign = "left";
      series.forEach(function (s) {
        g.strokeStyle = s.color; g.lineWidth = s.width || 1.3; g.setLineDash(s.dash || []); g.beginPath();
        var on = false;
        for (var k = 0; k < N && S.t[k] <= TPLOT; k++) {
          var v = s.ys[k];
          if (v === null || !isFinite(v)) { on = false; continue; }
          if (s.breakOnWrap && on && k > 0 && s.ys[k - 1] !== null && Math.abs(v - s.ys[k - 1]) > Math.PI) { on = false; }
          if (!on) { g.moveTo(px(S.t[k]), py(v)); on = true; } else { g.lineTo(px(S.t[k]), py(v)); }
        }
        g.stroke(); g.setLineDash([]);
      });
      if (D.collision) {
        g.strokeStyle = COLORS.crash; g.lineWidth = 1; g.beginPath();
        g.moveTo(px(D.collision.t), MT); g.lineTo(px(D.collision.t), self.h - MB); g.stroke();
      }
      self.back = b;
    };
    self.draw = function () {
      var g = c.getContext("2d");
      g.setTransform(1, 0, 0, 1, 0, 0); g.clearRect(0, 0, c.width, c.height);
      if (self.back) { g.drawImage(self.back, 0, 0); }
      var dpr = window.devicePixelRatio || 1; g.setTransform(dpr, 0, 0, dpr, 0, 0);
      var x = px(st.t);
      g.strokeStyle = "#111"; g.lineWidth = 1; g.beginPath(); g.moveTo(x, MT); g.lineTo(x, self.h - MB); g.stroke();
      if (rows) { g.fillStyle = "#1d2530"; g.fillText(visible(stateAt(st.index)).slice(0, 40), Math.min(x + 4, self.w - 60), self.h - 2); }
      series.forEach(function (s) {
        var v = s.ys[st.index];
        if (v === null || !isFinite(v)) { return; }
        g.fillStyle = s.color; g.beginPath(); g.arc(x, py(v), 2.5, 0, 2 * Math.PI); g.fill();
      });
    };
    var scrubbing = false;
    c.addEventListener("pointerdown", function (e) { scrubbing = true; c.setPointerCapture(e.pointerId); seek(self.tAt(e.clientX)); });
    c.addEventListener("pointermove", function (e) { if (scrubbing) { seek(self.tAt(e.clientX)); } });
    c.addEventListener("pointerup", function () { scrubbing = false; });
    return self;
  }
  // A timeline: a band per row, coloured per state or label value; an event row is marked where it is true.
  function Timeline(title, rows) { return Plot(title, [], null, rows); }
  function rowLabel(row) { return visible(row.label).slice(0, 24); }
  function paintRows(g, rows, px, ML, MT) {
    rows.forEach(function (row, r) {
      var y = MT + 16 * r;
      g.fillStyle = "#3a4450"; g.textAlign = "right"; g.fillText(rowLabel(row), ML - 4, y + 11); g.textAlign = "left";
      if (row.runs) {
        row.runs.forEach(function (run, j) {
          var k0 = run[0], k1 = j + 1 < row.runs.length ? row.runs[j + 1][0] : N - 1;
          var x0 = px(S.t[k0]), x1 = px(S.t[Math.max(k0, k1)]);
          if (run[1] === "") { return; }
          g.fillStyle = stateColor(run[1]); g.fillRect(x0, y + 1, Math.max(1, x1 - x0), 13);
          var text = visible(run[1]);
          if (g.measureText(text).width < x1 - x0 - 4) { g.fillStyle = "#fff"; g.fillText(text, x0 + 2, y + 11); }
        });
      } else {
        g.fillStyle = "#1d2530";
        for (var k = 0; k < N; k++) { if (row.flag[k] === 1) { g.fillRect(px(S.t[k]), y + 3, Math.max(1, px(S.t[Math.min(k + 1, N - 1)]) - px(S.t[k])), 9); } }
      }
    });
  }
  function fmtNum(v) { var a = Math.abs(v); return a >= 10 ? v.toFixed(0) : a >= 1 ? v.toFixed(1) : v.toFixed(2); }

  var plots = [];
  function stateColor(name) {        // the report's colour of the name (simiam.viewer.state_colours), sent in the data
    return (D.state_colors || {})[name] || COLORS.unnamed;
  }
  (function buildPlots() {
    // the state timeline (which controller ran when), then one row per label signal and per event
    var rows = [{ label: "state", runs: D.states }];
    SIGS.forEach(function (g) {
      if (g.kind === "label") { rows.push({ label: g.name, runs: SD[g.name] }); }
      if (g.kind === "flag") { rows.push({ label: g.name, flag: SD[g.name] }); }
    });
    var named = D.states.some(function (run) { return run[1] !== ""; });
    if (named || rows.length > 1) { plots.push(Timeline(rows.length > 1 ? "States and events" : "States", rows)); }
    var thetaEst = S.theta_est.map(wrap);
    var hs = [{ label: "θ (estimate)", ys: thetaEst, color: COLORS.series[0], breakOnWrap: true, width: 1.6 }];
    var headings = [];
    OVERLAYS.forEach(function (o) {
      if (o.kind === "scalar") {
        // the controller's own value (the report's static chart draws θ_g from the true position)
        hs.push({ label: o.name + " (controller)", ys: o.data, color: o.color, dash: [5, 3], breakOnWrap: true, width: 1.6 });
        headings.push(o.name + " (controller)");
      }
    });
    hs.push({ label: "θ (true)", ys: S.theta.map(wrap), color: "#9aa3ae", breakOnWrap: true, width: 1 });
    plots.push(Plot(headings.length ? "Heading θ and " + headings.join(", ") + " (rad)" : "Heading θ (rad)", hs));
    if (D.goal) {
      var dg = S.x.map(function (x, k) { return Math.hypot(D.goal[0] - x, D.goal[1] - S.y[k]); });
      plots.push(Plot("Distance to goal (m)", [{ label: "true", ys: dg, color: COLORS.series[2] }]));
    }
    plots.push(Plot("Wheel speeds (rad/s)", [
      { label: "right", ys: S.vel_r, color: COLORS.series[0] }, { label: "left", ys: S.vel_l, color: COLORS.series[3] }]));
    var irs = [];
    for (var k = 0; S["ir" + k]; k++) { irs.push({ label: "IR" + (k + 1), ys: S["ir" + k], color: COLORS.series[k % COLORS.series.length] }); }
    if (irs.length) { plots.push(Plot("IR distances (m)", irs, [0, D.robot.ir_max_range])); }
    // every other number the run declared: one plot per unit (counts on their own)
    var byUnit = {}, units = [];
    SIGS.forEach(function (g) {
      var pair = g.kind === "vector2" && g.unit === "coefficients";
      if (!((g.kind === "scalar" && g.unit !== "rad") || g.kind === "count" || pair)) { return; }
      var unit = g.kind === "count" ? "count" : (g.unit || "");
      if (!byUnit[unit]) { byUnit[unit] = []; units.push(unit); }
      byUnit[unit].push(g.name);
    });
    units.forEach(function (unit) {
      var series = [];
      byUnit[unit].forEach(function (name) {
        var d = SD[name], parts = d && d.x ? [[name + " 1", d.x], [name + " 2", d.y]] : [[name, d]];
        parts.forEach(function (p) { series.push({ label: p[0], ys: p[1], color: COLORS.series[series.length % COLORS.series.length] }); });
      });
      plots.push(Plot(byUnit[unit].join(", ") + (unit ? " (" + unit + ")" : ""), series));
    });
  })();

  // ---------- status line and clock ----------
  function runAt(runs, i) {
    var name = "";
    for (var k = 0; k < runs.length && runs[k][0] <= i; k++) { name = runs[k][1]; }
    return name;
  }
  function stateAt(i) { return runAt(D.states, i); }
  function f3(v) { return v === null || v === undefined ? "–" : v.toFixed(3); }
  // The status line's parts at step i, each [key, html]; a part that comes and goes (a label such as
  // fw_direction, an event that holds) keeps its key, so the widest line of the run can be put together.
  function statusParts(i) {
    var parts = [["step", "<b>step</b> " + i], ["state", "<b>state</b> " + escapeHtml(visible(stateAt(i)))],
                 ["true", "<b>true</b> (" + f3(S.x[i]) + ", " + f3(S.y[i]) + ", " + f3(wrap(S.theta[i])) + ")"],
                 ["estimate", "<b>estimate</b> (" + f3(S.x_est[i]) + ", " + f3(S.y_est[i]) + ", " + f3(wrap(S.theta_est[i])) + ")"],
                 ["wheels", "<b>wheels</b> " + f3(S.vel_r[i]) + " / " + f3(S.vel_l[i]) + " rad/s"]];
    var irs = [];
    for (var k = 0; S["ir" + k]; k++) { irs.push(f3(S["ir" + k][i])); }
    if (irs.length) { parts.push(["IR", "<b>IR</b> " + irs.join(" ")]); }
    SIGS.forEach(function (g) {             // the values that are not drawn: labels, counts, events that hold
      var d = SD[g.name], key = "signal " + g.name;
      if (g.kind === "label") { var v = runAt(d, i); if (v) { parts.push([key, "<b>" + escapeHtml(g.name) + "</b> " + escapeHtml(visible(v))]); } }
      if (g.kind === "count" && d[i] !== null) { parts.push([key, "<b>" + escapeHtml(g.name) + "</b> " + d[i]]); }
      if (g.kind === "flag" && d[i] === 1) { parts.push([key, "<b>" + escapeHtml(g.name) + "</b>"]); }
    });
    if (D.ending && D.ending.message && i === N - 1) { parts.push(["ending", "<span class=\"crash\">ended: " + escapeHtml(visible(D.ending.message)) + "</span>"]); }
    if (D.collision && S.t[i] >= D.collision.t - 1e-9) { parts.push(["collision", "<span class=\"crash\">collided at t = " + D.collision.t.toFixed(2) + " s</span>"]); }
    return parts;
  }
  function statusLine(parts) { return parts.map(function (p) { return p[1]; }).join(" &nbsp; "); }
  // The widest status line of the whole run: every part that ever shows, each at its widest (measured in the
  // status line's own font). The line keeps the height that one needs, so the page never jumps while a run
  // plays (at 1024 px it wrapped to a second line when fw_direction appeared, covering the lowest chart).
  var widestStatus = null;
  function widestStatusLine() {
    if (widestStatus !== null) { return widestStatus; }
    var g = document.createElement("canvas").getContext("2d"), cs = getComputedStyle(statusEl);
    g.font = "600 " + cs.fontSize + " " + cs.fontFamily;   // bold: the widest the parts' words get
    var order = [], widest = {}, every = Math.max(1, Math.floor(N / 4000));   // a very long run: a sample
    function see(i) {
      statusParts(i).forEach(function (p) {
        var w = g.measureText(p[1].replace(/<[^>]*>/g, "")).width;
        if (!(p[0] in widest)) { order.push(p[0]); widest[p[0]] = { w: -1 }; }
        if (w > widest[p[0]].w) { widest[p[0]] = { w: w, html: p[1] }; }
      });
    }
    for (var i = 0; i < N; i += every) { see(i); }
    see(N - 1);
    widestStatus = order.map(function (k) { return widest[k].html; }).join(" &nbsp; ");
    return widestStatus;
  }
  function reserveStatusHeight() {
    var now = statusEl.innerHTML;
    statusEl.style.minHeight = "";
    statusEl.innerHTML = widestStatusLine();
    statusEl.style.minHeight = statusEl.getBoundingClientRect().height + "px";
    statusEl.innerHTML = now;
  }
  function updateStatus() {
    var i = st.index;
    clock.textContent = "t = " + S.t[i].toFixed(2) + " / " + TEND.toFixed(2) + " s";
    if (String(slider.value) !== String(i)) { slider.value = i; }
    if (i === st.lastStatusIndex) { return; }
    st.lastStatusIndex = i;
    statusEl.innerHTML = statusLine(statusParts(i));
  }
  // A state name comes from student code: control and bidi characters are shown (\x1b, \u202e), not obeyed.
  function visible(s) {
    return String(s).replace(/[\u0000-\u001f\u007f-\u009f\u00ad\u061c\u200b-\u200f\u2028-\u202e\u2060-\u206f\ufeff\ufff9-\ufffb]/g, function (c) {
      var h = c.charCodeAt(0).toString(16);
      return c.charCodeAt(0) < 0x100 ? "\\x" + ("0" + h).slice(-2) : "\\u" + ("000" + h).slice(-4);
    });
  }
  function escapeHtml(s) {
    return String(s).replace(/[&<>"']/g, function (c) { return { "&": "&amp;", "<": "&lt;", ">": "&gt;", "\"": "&quot;", "'": "&#39;" }[c]; });
  }

  // ---------- time ----------
  function seek(t) {
    st.t = Math.min(TEND, Math.max(T0, t));
    st.index = indexAt(st.t + 1e-9);
    render();
  }
  function stepBy(n) { seek(S.t[Math.min(N - 1, Math.max(0, st.index + n))]); }
  function setPlaying(on) {
    if (on && st.t >= TEND) { st.t = T0; st.index = 0; }
    st.playing = !!on && N > 1;
    st.lastFrame = null;
    playBtn.innerHTML = st.playing ? ICON_PAUSE : ICON_PLAY;
    playBtn.setAttribute("aria-label", st.playing ? "pause" : "play");
    if (st.playing) { requestAnimationFrame(frame); }
  }
  function frame(now) {
    if (!st.playing) { return; }
    if (st.lastFrame !== null) {
      st.t += Math.min(0.25, (now - st.lastFrame) / 1000) * st.speed;
      if (st.t >= TEND) { st.t = TEND; st.playing = false; setPlaying(false); }
      st.index = indexAt(st.t + 1e-9);
    }
    st.lastFrame = now;
    render();
    if (st.playing) { requestAnimationFrame(frame); }
  }
  function render() {
    if (st.following) { centreOnRobot(); }
    draw();
    plots.forEach(function (p) { p.draw(); });
    updateStatus();
  }

  // ---------- input ----------
  function robotHit(px, py) {
    var q = pose(st.index), x = wx(px), y = wy(py);
    var plate = D.robot.base_plate.map(function (p) { return toWorld(p, q); }), inside = false;
    for (var a = 0, b = plate.length - 1; a < plate.length; b = a++) {
      if ((plate[a][1] > y) !== (plate[b][1] > y) &&
          x < (plate[b][0] - plate[a][0]) * (y - plate[a][1]) / (plate[b][1] - plate[a][1]) + plate[a][0]) { inside = !inside; }
    }
    return inside || Math.hypot(px - sx(q[0]), py - sy(q[1])) < 12;
  }
  var drag = null;
  canvas.addEventListener("pointerdown", function (e) {
    var r = canvas.getBoundingClientRect();
    drag = { x: e.clientX, y: e.clientY, cx: st.cx, cy: st.cy, moved: false, px: e.clientX - r.left, py: e.clientY - r.top };
    canvas.setPointerCapture(e.pointerId);
    canvas.focus();
  });
  canvas.addEventListener("pointermove", function (e) {
    var r = canvas.getBoundingClientRect();
    if (!drag) { canvas.classList.toggle("over-robot", robotHit(e.clientX - r.left, e.clientY - r.top)); return; }
    var dx = e.clientX - drag.x, dy = e.clientY - drag.y;
    if (!drag.moved && Math.hypot(dx, dy) > 3) { drag.moved = true; setFollowing(false); canvas.classList.add("dragging"); }
    if (drag.moved) { st.atHome = false; st.cx = drag.cx - dx / st.zoom; st.cy = drag.cy + dy / st.zoom; render(); }
  });
  canvas.addEventListener("pointerup", function () {
    if (drag && !drag.moved && robotHit(drag.px, drag.py)) { setFollowing(!st.following); render(); }
    drag = null; canvas.classList.remove("dragging");
  });
  canvas.addEventListener("wheel", function (e) {
    e.preventDefault();
    var r = canvas.getBoundingClientRect();
    zoomAt(Math.pow(1.0015, -e.deltaY), e.clientX - r.left, e.clientY - r.top);
    render();
  }, { passive: false });

  document.getElementById("btn-home").addEventListener("click", function () { home(); render(); });
  document.getElementById("btn-rewind").addEventListener("click", function () { seek(T0); });
  playBtn.addEventListener("click", function () { setPlaying(!st.playing); });
  // after a click, give the keyboard back to the page so space toggles play once, not twice
  Array.prototype.forEach.call(document.querySelectorAll("#toolbar button"), function (b) {
    b.addEventListener("click", function () { b.blur(); });
  });
  document.getElementById("btn-zoom-in").addEventListener("click", function () { zoomAt(1.25); render(); });
  document.getElementById("btn-zoom-out").addEventListener("click", function () { zoomAt(0.8); render(); });
  followBtn.addEventListener("click", function () { setFollowing(!st.following); render(); });
  speedSel.addEventListener("change", function () { st.speed = parseFloat(speedSel.value) || 1; });
  slider.max = String(N - 1);
  slider.addEventListener("input", function () { seek(S.t[parseInt(slider.value, 10)]); });
  document.addEventListener("keydown", function (e) {
    if (e.target && (e.target.tagName === "SELECT" || e.target.tagName === "INPUT") && e.key !== " ") { return; }
    var big = e.shiftKey ? Math.max(1, Math.round(1 / D.dt)) : 1, handled = true;
    switch (e.key) {
      case " ": setPlaying(!st.playing); break;
      case "ArrowRight": stepBy(big); break;
      case "ArrowLeft": stepBy(-big); break;
      case "ArrowUp": stepBy(Math.max(1, Math.round(1 / D.dt))); break;
      case "ArrowDown": stepBy(-Math.max(1, Math.round(1 / D.dt))); break;
      case "+": case "=": zoomAt(1.25); render(); break;
      case "-": case "_": zoomAt(0.8); render(); break;
      case "h": case "H": case "Home": home(); render(); break;
      case "r": case "R": seek(T0); break;
      case "f": case "F": setFollowing(!st.following); render(); break;
      default: handled = false;
    }
    if (handled) { e.preventDefault(); }
  });
  // the canvas changes size when the status line wraps or the window changes: keep the drawing buffer in step
  if (window.ResizeObserver) {
    new ResizeObserver(function () {
      resize();
      if (st.atHome) { home(); }   // an untouched view stays fitted to the world
      render();
      document.body.setAttribute("data-ready", "1");
    }).observe(canvas);
  } else {
    window.addEventListener("resize", function () { resize(); render(); });
  }

  // collision mark on the timeline
  if (D.collision && TEND > T0) {
    var m = document.createElement("div");
    m.className = "mark"; m.title = "collision at t = " + D.collision.t.toFixed(2) + " s";
    m.style.left = (100 * (D.collision.t - T0) / (TEND - T0)) + "%";
    document.getElementById("marks").appendChild(m);
  }
  document.getElementById("legend").innerHTML =
    "<span><i style=\"background:" + COLORS.body + "\"></i>robot (true pose)</span>" +
    "<span><i style=\"border-top:2px dashed #888;height:0\"></i>odometry estimate</span>" +
    "<span><i style=\"background:" + COLORS.heading + "\"></i>heading θ</span>" +
    OVERLAYS.map(function (o, j) {
      var mark = o.kind === "points" ? "<b>×</b> " : "<i style=\"background:" + o.color + "\"></i>";
      return "<label><input type=\"checkbox\" data-overlay=\"" + j + "\"" + (o.on ? " checked" : "") + "> " +
             mark + escapeHtml(visible(o.name)) + "</label>";
    }).join("");
  Array.prototype.forEach.call(document.querySelectorAll("#legend input[data-overlay]"), function (box) {
    box.addEventListener("change", function () { OVERLAYS[parseInt(box.getAttribute("data-overlay"), 10)].on = box.checked; render(); });
  });

  // ---------- the test / console API ----------
  window.simiam = {
    state: function () {
      var r = canvas.getBoundingClientRect(), q = pose(st.index);
      return { t: st.t, index: st.index, playing: st.playing, speed: st.speed, zoom: st.zoom,
               center: [st.cx, st.cy], following: st.following, tEnd: TEND, rows: N,
               robotScreenXY: [r.left + sx(q[0]), r.top + sy(q[1])],
               canvasRect: [r.left, r.top, r.width, r.height], collisionLabel: st.crashLabel || null,
               collisionBox: st.crashBox || null, statusWidest: widestStatusLine(),
               scaleBar: st.scaleBar || null, plotEnd: TPLOT,
               labelMargins: plots.map(function (p) { return p.labelMargin; }) };
    },
    play: function () { setPlaying(true); }, pause: function () { setPlaying(false); },
    seek: seek, stepBy: stepBy, home: function () { home(); render(); },
    zoomIn: function () { zoomAt(1.25); render(); }, zoomOut: function () { zoomAt(0.8); render(); },
    follow: function (on) { setFollowing(on === undefined ? true : on); render(); },
    setSpeed: function (v) { st.speed = v; speedSel.value = String(v); },
    worldToScreen: function (x, y) { var r = canvas.getBoundingClientRect(); return [r.left + sx(x), r.top + sy(y)]; },
    stateColor: stateColor,
    signalRows: function () { return SIGS.filter(function (g) { return g.kind === "label" || g.kind === "flag"; }).map(function (g) { return g.name; }); },
    overlays: function () { return OVERLAYS.map(function (o) { return { name: o.name, kind: o.kind, on: o.on, color: o.color }; }); },
    setOverlay: function (name, on) {
      OVERLAYS.forEach(function (o, j) {
        if (o.name === name) { o.on = on; document.querySelector("#legend input[data-overlay=\"" + j + "\"]").checked = on; }
      });
      render();
    },
    trace: D
  };

  reserveStatusHeight();
  window.addEventListener("resize", reserveStatusHeight);
  resize();
  home();
  render();
  if (!window.ResizeObserver) { document.body.setAttribute("data-ready", "1"); }
  }
})();
