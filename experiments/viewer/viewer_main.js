// drapelab view: starts the page. One WebGL canvas, one viewport per run, one camera and one
// time for all of them. The URL's hash sets the start (#t=1.2&view=side) and the browser
// check (#test&t=0.2&t=1.5: renders each time, reads the pixels back, and writes a JSON
// report into #test-result; docs/viewer.md).
'use strict';

(function () {
  var drape = window.drape;

  function parse_hash(hash) {
    var options = { test: false, times: [], view: 'front', play: false };
    hash.replace(/^#/, '').split('&').forEach(function (part) {
      var kv = part.split('=');
      if (kv[0] === 'test') options.test = true;
      else if (kv[0] === 'play') options.play = true;
      else if (kv[0] === 't' && isFinite(parseFloat(kv[1]))) options.times.push(parseFloat(kv[1]));
      else if (kv[0] === 'view' && kv[1]) options.view = kv[1];
    });
    return options;
  }

  function Viewer(runs, options) {
    var self = this;
    this.runs = runs;
    this.options = options;
    this.canvas = document.getElementById('gl');
    this.background = new THREE.Color(0xeef1f5);
    // The browser check reads the pixels back; software rendering is faster without MSAA.
    this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: !options.test,
                                              preserveDrawingBuffer: options.test });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(this.background);
    this.views = runs.map(function (run) { return new drape.RunView(run); });
    this.duration = Math.max.apply(null, runs.map(drape.run_end));
    this.camera = new THREE.PerspectiveCamera(30, 1, 0.01, 100);
    this.controls = new THREE.OrbitControls(this.camera, this.canvas);
    this.controls.enableDamping = false;
    this.controls.enableKeys = false;  // the arrow keys step frames
    this.controls.addEventListener('change', function () { self.dirty = true; });
    this.bounds = new THREE.Box3();
    this.views.forEach(function (v) {
      self.bounds.union(v.cloth_bounds);
      if (v.dummy_bounds) self.bounds.union(v.dummy_bounds);
    });
    this.labels = drape.build_labels(runs);
    drape.build_notice(runs);
    drape.build_legend();
    this.plot = new drape.EnergyPlot(document.getElementById('energy'), runs, this.duration);
    this.slider = document.getElementById('slider');
    this.slider.max = String(this.duration);
    this.playing = false;
    this.speed = 1;
    this.t = 0;
    // The first time every run has a frame: 0 with traces; a run with its final state only
    // (state.csv) opens at its end, where that state is, not at 0 beside the hands of t = 0.
    // A run that diverged or failed opens at its last written frame, where it went wrong.
    this.start = Math.max.apply(null, runs.map(function (run) {
      var times = run.frames.times;
      return run.status === 'ok' ? times[0] : times[times.length - 1];
    }));
    this.layout();
    this.set_camera(options.view);
    this.set_time(options.times.length ? options.times[0] : this.start);
  }

  Viewer.prototype.layout = function () {
    var w = Math.max(1, this.canvas.clientWidth), h = Math.max(1, this.canvas.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / this.views.length / h;
    this.camera.updateProjectionMatrix();
    drape.build_event_marks(this.runs, this.duration);
    this.plot.draw();
    this.dirty = true;
  };

  // The presets of drape.camera_preset (viewer_scene.js), shared with the live page.
  Viewer.prototype.set_camera = function (kind) {
    drape.camera_preset(this.camera, this.controls, this.bounds, kind);
    this.camera_kind = kind;
    var buttons = document.querySelectorAll('[data-camera]');
    for (var i = 0; i < buttons.length; ++i) buttons[i].classList.toggle('on', buttons[i].dataset.camera === kind);
    this.dirty = true;
  };

  Viewer.prototype.set_time = function (t) {
    this.t = Math.min(this.duration, Math.max(0, t));
    for (var i = 0; i < this.views.length; ++i)
      this.labels[i].textContent = drape.frame_text(this.runs[i], this.views[i].set_time(this.t));
    this.slider.value = String(this.t);
    document.getElementById('time-readout').textContent =
      't = ' + this.t.toFixed(3) + ' s / ' + this.duration.toFixed(3) + ' s';
    this.plot.t = this.t;
    this.plot.draw();
    this.dirty = true;
  };

  Viewer.prototype.render = function () {
    var r = this.renderer, size = r.getSize(new THREE.Vector2()), n = this.views.length;
    r.setScissorTest(true);
    for (var i = 0; i < n; ++i) {
      var x0 = Math.round(i * size.x / n), x1 = Math.round((i + 1) * size.x / n);
      r.setViewport(x0, 0, x1 - x0, size.y);
      r.setScissor(x0, 0, x1 - x0, size.y);
      r.render(this.views[i].scene, this.camera);
    }
    r.setScissorTest(false);
    this.dirty = false;
  };

  Viewer.prototype.set_playing = function (playing) {
    this.playing = playing;
    document.getElementById('play').innerHTML = playing ? '&#10074;&#10074; pause' : '&#9654; play';
    this.last_tick = undefined;
  };

  Viewer.prototype.step_frame = function (direction) {
    var times = this.runs[0].frames.times, k = drape.last_at_or_before(times, this.t + 1e-9);
    if (direction < 0 && times[k] >= this.t - 1e-9) k = Math.max(0, k - 1);
    else if (direction > 0) k = Math.min(times.length - 1, k + 1);
    this.set_time(times[k]);
  };

  Viewer.prototype.tick = function (now) {
    if (this.playing) {
      if (this.last_tick !== undefined) {
        var t = this.t + this.speed * (now - this.last_tick) / 1000;
        this.set_time(t > this.duration ? 0 : t);
      }
      this.last_tick = now;
    }
    if (this.dirty) this.render();
  };

  Viewer.prototype.connect = function () {
    var self = this;
    this.slider.addEventListener('input', function () { self.set_time(parseFloat(self.slider.value)); });
    document.getElementById('play').addEventListener('click', function () { self.set_playing(!self.playing); });
    document.getElementById('speed').addEventListener('change', function (e) { self.speed = parseFloat(e.target.value); });
    document.querySelectorAll('[data-camera]').forEach(function (b) {
      b.addEventListener('click', function () { self.set_camera(b.dataset.camera); });
    });
    document.querySelectorAll('[data-energy]').forEach(function (b) {
      b.addEventListener('click', function () {
        self.plot.mode = b.dataset.energy;
        document.querySelectorAll('[data-energy]').forEach(function (o) { o.classList.toggle('on', o === b); });
        self.plot.draw();
      });
    });
    document.getElementById('show-particles').addEventListener('change', function (e) {
      self.views.forEach(function (v) { if (v.object_particles) v.object_particles.visible = e.target.checked; });
      self.dirty = true;
    });
    document.getElementById('show-grid').addEventListener('change', function (e) {
      self.views.forEach(function (v) { v.grid.visible = e.target.checked; });
      self.dirty = true;
    });
    var plot_canvas = document.getElementById('energy'), dragging = false;
    var seek = function (e) { self.set_time(self.plot.to_time(e.clientX - plot_canvas.getBoundingClientRect().left)); };
    plot_canvas.addEventListener('mousedown', function (e) { dragging = true; seek(e); });
    window.addEventListener('mousemove', function (e) { if (dragging) seek(e); });
    window.addEventListener('mouseup', function () { dragging = false; });
    window.addEventListener('keydown', function (e) {
      // Focused controls keep their own keys: space presses a button, arrows move the slider.
      var tag = e.target.tagName;
      if (tag === 'SELECT' || tag === 'INPUT' || (tag === 'BUTTON' && e.key === ' ')) return;
      if (e.key === ' ') { self.set_playing(!self.playing); e.preventDefault(); }
      else if (e.key === 'ArrowLeft' || e.key === 'ArrowRight') {
        self.set_playing(false);
        self.step_frame(e.key === 'ArrowLeft' ? -1 : 1);
        e.preventDefault();
      }
    });
    window.addEventListener('resize', function () { self.layout(); });
    var loop = function (now) { self.tick(now); window.requestAnimationFrame(loop); };
    window.requestAnimationFrame(loop);
    if (this.options.play) this.set_playing(true);
  };

  // The browser check: for each requested time, render, read the pixels and count those that
  // differ from the background, in the whole canvas and in each run's viewport.
  Viewer.prototype.test_report = function () {
    var gl = this.renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    var bg = [this.background.r, this.background.g, this.background.b].map(function (c) { return Math.round(255 * c); });
    var pixels = new Uint8Array(4 * w * h), renders = [], self = this;
    var times = this.options.times.length ? this.options.times : [this.start];
    times.forEach(function (t) {
      self.set_time(t);
      self.render();
      gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
      var count = 0, per_view = self.views.map(function () { return 0; }), hash = 2166136261;
      for (var i = 0; i < w * h; ++i) {
        var p = 4 * i;
        if (Math.abs(pixels[p] - bg[0]) > 3 || Math.abs(pixels[p + 1] - bg[1]) > 3 || Math.abs(pixels[p + 2] - bg[2]) > 3) {
          ++count;
          ++per_view[Math.min(self.views.length - 1, Math.floor((i % w) * self.views.length / w))];
        }
        hash = Math.imul(hash ^ (pixels[p] | pixels[p + 1] << 8 | pixels[p + 2] << 16), 16777619) >>> 0;
      }
      renders.push({ t: self.t, nonbackground: count, per_view: per_view, checksum: hash.toString(16),
                     labels: self.labels.map(function (l) { return l.textContent; }) });
    });
    var notice = document.getElementById('notice'), box = function (id) {
      var r = document.getElementById(id).getBoundingClientRect();
      return { top: r.top, bottom: r.bottom, left: r.left, right: r.right };
    };
    return { ok: true, three: THREE.REVISION, width: w, height: h, renders: renders, ui: this.ui_check(),
             notice: notice.hidden ? '' : notice.textContent, start: this.start,
             energy_notes: this.plot.notes,
             layout: { canvas: box('gl'), labels: box('labels'), legend: box('legend'),
                       window_height: window.innerHeight },
             milliseconds: Math.round(performance.now()),
             runs: this.runs.map(function (r) { return { name: r.name, frames: r.frames.count }; }) };
  };

  // The controls as a user drives them: the slider, play for 0.5 s of (synthetic) clock at
  // 1x, and the side camera button. Headless chromium runs requestAnimationFrame only once,
  // so the check calls tick() itself.
  Viewer.prototype.ui_check = function () {
    this.slider.value = '0.2';
    this.slider.dispatchEvent(new Event('input'));
    var slider_t = this.t;
    this.set_playing(true);
    this.tick(1000);
    this.tick(1500);
    this.set_playing(false);
    var played = this.t - slider_t;
    document.querySelector('[data-camera="side"]').click();
    // The lines of each button's label: its content height over its line height.
    var lines = {};
    document.querySelectorAll('button').forEach(function (b) {
      var style = getComputedStyle(b), px = function (v) { return parseFloat(v) || 0; };
      var content = b.getBoundingClientRect().height - px(style.paddingTop) - px(style.paddingBottom) -
                    px(style.borderTopWidth) - px(style.borderBottomWidth);
      lines[b.textContent.trim()] = Math.round(content / px(style.lineHeight));
    });
    return { slider_t: slider_t, played: played, camera: this.camera_kind, button_lines: lines };
  };

  function write_test_result(result) {
    result.errors = window.drape_errors.slice();
    var box = document.getElementById('test-result');
    box.textContent = JSON.stringify(result);
    box.setAttribute('data-done', '1');
  }

  var options = parse_hash(window.location.hash);
  try {
    var data = JSON.parse(document.getElementById('drape-data').textContent);
    var viewer = new Viewer(data.runs, options);
    window.drape.viewer = viewer;
    viewer.connect();
    if (options.test) write_test_result(viewer.test_report());
  } catch (e) {
    console.error('drapelab view: ' + (e && e.stack ? e.stack : e));
    if (options.test) write_test_result({ ok: false });
  }
})();
