// drapelab view: the parts of the page around the 3-D views: run labels, legend, event marks
// on the time slider, and the energy plot with its cursor.
'use strict';

var drape = window.drape || (window.drape = {});

// One colour per run (labels, event marks, energy curves), as matplotlib's tab10.
drape.run_colours = ['#1f77b4', '#d62728', '#2ca02c', '#9467bd', '#8c564b', '#e377c2'];

drape.hex = function (colour) { return '#' + ('000000' + colour.toString(16)).slice(-6); };

drape.element = function (tag, class_name, text) {
  var e = document.createElement(tag);
  if (class_name) e.className = class_name;
  if (text !== undefined) e.textContent = text;
  return e;
};

drape.run_title = function (run) {
  var method = run.integrator + (run.table ? ' ' + run.table : '');
  if (run.adaptive) return method + ', adaptive steps';
  return method + (run.dt ? ', dt = ' + +(run.dt * 1000).toPrecision(4) + ' ms' : '');
};

drape.build_labels = function (runs) {
  var box = document.getElementById('labels'), labels = [];
  document.getElementById('run-names').textContent = runs.map(function (r) { return r.name; }).join(' | ');
  runs.forEach(function (run, i) {
    var label = drape.element('div', 'view-label');
    var title = drape.element('div', 'title');
    var swatch = drape.element('span', 'swatch');
    swatch.style.background = drape.run_colours[i % drape.run_colours.length];
    title.appendChild(swatch);
    title.appendChild(document.createTextNode(run.name));
    label.appendChild(title);
    var meta = drape.element('div', 'meta', drape.run_title(run) + ', ' + run.rows + ' x ' + run.cols + ' cloth');
    label.appendChild(meta);
    // The reason is the banner's: repeated here it took two more lines of a short window.
    if (run.status !== 'ok')
      label.appendChild(drape.element('div', 'status-bad', run.status + ' at t = ' +
                                      run.sim_time.toFixed(3) + ' s (why: the banner above)'));
    var frame = drape.element('div', 'frame');
    label.appendChild(frame);
    if (run.description) label.title = run.description;
    box.appendChild(label);
    labels.push(frame);
  });
  return labels;
};

// A run that did not end ok: when, why (summary.json's reason) and the last frame it wrote,
// the one the page shows from then on (docs/viewer.md, Diverged runs).
drape.status_text = function (run) {
  var times = run.frames.times;
  return run.status + ' at t = ' + run.sim_time.toFixed(3) + ' s' + (run.reason ? ': ' + run.reason : '') +
    '; last frame written at t = ' + times[times.length - 1].toFixed(3) + ' s';
};

// The banner over the page for runs that diverged or failed: the view of such a run holds
// still at its last written frame, which must not read as a cloth at rest.
drape.build_notice = function (runs) {
  var box = document.getElementById('notice');
  runs.forEach(function (run) {
    if (run.status !== 'ok') box.appendChild(drape.element('div', '', run.name + ' ' + drape.status_text(run)));
  });
  box.hidden = !box.childNodes.length;
};

drape.frame_text = function (run, state) {
  if (run.source === 'state.csv') return 'final state only (state.csv: no trace.csv)';
  var text = 'frame ' + (state.frame + 1) + ' / ' + state.frames + ' (t = ' + state.frame_t.toFixed(3) + ' s)';
  return state.ended ? text + ', run ended' : text;
};

drape.build_legend = function () {
  var box = document.getElementById('legend');
  drape.legend.forEach(function (entry) {
    var item = drape.element('span', 'item');
    var dot = drape.element('span', 'dot' + (entry[2] ? ' ' + entry[2] : ''));
    dot.style.background = drape.hex(drape.colours[entry[0]]);
    item.appendChild(dot);
    item.appendChild(document.createTextNode(entry[1]));
    box.appendChild(item);
  });
};

// Event names above the slider, stacked in rows where they would overlap. The same event of
// several runs at nearly the same time gets one name and a mark in each run's colour.
drape.build_event_marks = function (runs, duration) {
  var box = document.getElementById('event-marks');
  box.textContent = '';
  var width = box.clientWidth, row_ends = [], rows = 3, all = [], groups = [];
  runs.forEach(function (run, i) {
    run.events.forEach(function (e) { all.push({ t: e.t, type: e.type, run: i, event: e }); });
  });
  all.sort(function (a, b) { return a.t - b.t; });
  all.forEach(function (e) {
    var same = groups.filter(function (g) { return g.type === e.type && Math.abs(g.t - e.t) <= 0.004 * duration; })[0];
    if (same) same.members.push(e); else groups.push({ t: e.t, type: e.type, members: [e] });
  });
  groups.forEach(function (g) {
    var x = duration > 0 ? width * g.t / duration : 0, first = g.members[0].event;
    var text = g.type + (runs.length === 1 && first.hand ? ' (' + first.hand + ')' : '');
    var text_width = 6.2 * text.length + 8, row = 0;
    while (row < rows - 1 && row_ends[row] !== undefined && row_ends[row] > x) ++row;
    row_ends[row] = x + text_width;
    g.members.forEach(function (e, k) {
      var mark = drape.element('div', 'event-mark');
      mark.style.left = (duration > 0 ? width * e.t / duration : 0) + 2 * k + 'px';
      mark.style.height = (14 + 11 * (rows - 1 - row)) + 'px';
      mark.style.background = drape.run_colours[e.run % drape.run_colours.length];
      mark.title = e.type + ' at t = ' + e.t.toFixed(4) + ' s' + (runs.length > 1 ? ' (' + runs[e.run].name + ')' : '') +
        (e.event.row !== undefined ? ', particle (' + e.event.row + ', ' + e.event.col + ')' : '');
      if (k === 0) {
        var name = drape.element('span', 'name', text);
        name.style.top = '0px';
        if (x + text_width > width) { name.style.left = 'auto'; name.style.right = '3px'; }
        mark.appendChild(name);
      }
      box.appendChild(mark);
    });
  });
};

// The energy plot: a canvas under the slider, on the slider's time axis.
drape.EnergyPlot = function (canvas, runs, duration) {
  this.canvas = canvas;
  this.runs = runs;
  this.duration = duration;
  this.mode = 'kinetic';
  this.t = 0;
  var legend = document.getElementById('plot-legend');
  runs.forEach(function (run, i) {
    var item = drape.element('span', 'item'), line = drape.element('span', 'line');
    line.style.background = drape.run_colours[i % drape.run_colours.length];
    item.appendChild(line);
    item.appendChild(document.createTextNode(run.name));
    legend.appendChild(item);
  });
};

drape.EnergyPlot.prototype.series = function (run) {
  var e = run.energy;
  if (this.mode === 'kinetic') return e.kinetic.map(function (v) { return 1000 * v; });
  var e0 = e.total.length ? e.total[0] : 0;
  return e.total.map(function (v) { return 1000 * (v - e0); });
};

// About `count` round values (1, 2 or 5 times a power of ten apart) within [lo, hi].
drape.nice_ticks = function (lo, hi, count) {
  var raw = (hi - lo) / count, magnitude = Math.pow(10, Math.floor(Math.log10(raw))), step = magnitude;
  [1, 2, 5, 10].some(function (m) { step = m * magnitude; return step >= raw; });
  var ticks = [];
  for (var v = Math.ceil(lo / step) * step; v <= hi + 1e-9 * step; v += step)
    ticks.push(Math.abs(v) < 1e-9 * step ? 0 : v);
  return ticks;
};

drape.EnergyPlot.prototype.draw = function () {
  var canvas = this.canvas, ratio = window.devicePixelRatio || 1;
  var w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== Math.round(w * ratio) || canvas.height !== Math.round(h * ratio)) {
    canvas.width = Math.round(w * ratio);
    canvas.height = Math.round(h * ratio);
  }
  var g = canvas.getContext('2d');
  g.setTransform(ratio, 0, 0, ratio, 0, 0);
  g.clearRect(0, 0, w, h);
  var inset = 8, top = 12, bottom = 20;  // the slider's thumb half-width: same time axis
  var x0 = inset, x1 = w - inset, y0 = h - bottom, y1 = top, duration = this.duration;
  var self = this, lo = Infinity, hi = -Infinity, all = this.runs.map(function (r) { return self.series(r); });
  all.forEach(function (s) { s.forEach(function (v) { if (v < lo) lo = v; if (v > hi) hi = v; }); });
  if (!isFinite(lo)) { lo = 0; hi = 1; }
  if (hi - lo < 1e-12) { hi += 0.5; lo -= 0.5; }
  var pad = 0.05 * (hi - lo);
  lo -= pad; hi += pad;
  var tx = function (t) { return x0 + (x1 - x0) * (duration > 0 ? t / duration : 0); };
  var ty = function (v) { return y0 + (y1 - y0) * (v - lo) / (hi - lo); };
  g.font = '11px system-ui, "DejaVu Sans", sans-serif';
  g.strokeStyle = '#e3e7ec'; g.fillStyle = '#66717d'; g.lineWidth = 1;
  drape.nice_ticks(lo, hi, 4).forEach(function (v) {
    var y = Math.round(ty(v)) + 0.5;
    g.beginPath(); g.moveTo(x0, y); g.lineTo(x1, y); g.stroke();
    g.fillText(String(+v.toPrecision(4)), x0 + 2, y - 2);
  });
  drape.nice_ticks(0, duration, 10).forEach(function (t) {
    var x = Math.round(tx(t)) + 0.5;
    g.beginPath(); g.moveTo(x, y0); g.lineTo(x, y0 + 4); g.stroke();
    var text = +t.toPrecision(4) + ' s', text_width = g.measureText(text).width;
    g.fillText(text, Math.min(x - text_width / 2, w - text_width - 1), h - 5);
  });
  g.fillText(this.mode === 'kinetic' ? 'kinetic energy [mJ]' : 'E(t) \u2212 E(0) [mJ]', x1 - 130, y1 + 10);
  this.runs.forEach(function (run, i) {
    g.strokeStyle = drape.run_colours[i % drape.run_colours.length];
    g.setLineDash([2, 3]);
    run.events.forEach(function (e) {
      var x = Math.round(tx(e.t)) + 0.5;
      g.beginPath(); g.moveTo(x, y0); g.lineTo(x, y1); g.stroke();
    });
    g.setLineDash([]);
    g.lineWidth = 1.4;
    g.beginPath();
    run.energy.t.forEach(function (t, k) { (k ? g.lineTo : g.moveTo).call(g, tx(t), ty(all[i][k])); });
    g.stroke();
    g.lineWidth = 1;
  });
  // A run that stopped before its second energy row has no line to draw: its one point as a dot,
  // and the plot says so (the plot stood empty beside the banner; docs/viewer.md, Diverged runs).
  this.notes = [];
  this.runs.forEach(function (run, i) {
    var t = run.energy.t, colour = drape.run_colours[i % drape.run_colours.length];
    if (t.length > 1) return;
    if (t.length) {
      g.fillStyle = colour;
      g.beginPath(); g.arc(tx(t[0]), ty(all[i][0]), 3.5, 0, 2 * Math.PI); g.fill();
    }
    var text = run.name + ': ' + (t.length ? 'energy written at t = ' + t[0].toFixed(3) + ' s only'
                                           : 'no energy row') +
               ' (the run stopped at t = ' + run.sim_time.toFixed(3) + ' s)';
    g.fillStyle = colour;
    g.fillText(text, x0 + 60, y1 + 26 + 14 * self.notes.length);
    self.notes.push(text);
  });
  g.strokeStyle = '#1f2933'; g.lineWidth = 1.5;
  var cx = Math.round(tx(this.t)) + 0.5;
  g.beginPath(); g.moveTo(cx, y0); g.lineTo(cx, y1); g.stroke();
  this.to_time = function (x) { return Math.min(duration, Math.max(0, (x - x0) / (x1 - x0) * duration)); };
};
