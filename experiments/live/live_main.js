// drapelab live: the page of a live run (docs/live.md). The 3-D scene is viewer_scene.js's
// ClothScene, fed by the frames of GET /events; keys go to POST /key; with live hands the pointer
// over the view moves the right hand (POST /hand) on a plane facing the camera.
// `#test-key=m&at=0.2` posts a key once the streamed time reaches 0.2 s; `#view=side` the camera;
// `#test` drops antialiasing (software WebGL in the browser check).
'use strict';

(function () {
  var drape = window.drape;
  var spec = JSON.parse(document.getElementById('drape-data').textContent);
  var hash = new URLSearchParams(window.location.hash.slice(1));
  var hook = { key: hash.get('test-key'), at: parseFloat(hash.get('at') || '0') };
  // Real-time factor over the last second of wall clock (the frames carry sim and wall time).
  var rtf_window = 1.0;

  function Live() {
    var self = this;
    this.canvas = document.getElementById('gl');
    this.background = new THREE.Color(0xeef1f5);
    // Software WebGL (the browser check's SwiftShader) is much faster without MSAA.
    this.renderer = new THREE.WebGLRenderer({ canvas: this.canvas, antialias: !hash.has('test') });
    this.renderer.setPixelRatio(window.devicePixelRatio || 1);
    this.renderer.setClearColor(this.background);
    this.camera = new THREE.PerspectiveCamera(30, 1, 0.01, 100);
    this.controls = new THREE.OrbitControls(this.camera, this.canvas);
    this.controls.enableKeys = false;
    this.controls.addEventListener('change', function () { self.render(); });
    // Once the person turns or zooms the view, the page no longer reframes it (keep_in_view).
    this.controls.addEventListener('start', function () { self.camera_moved = true; });
    this.cloth = null;  // the ClothScene, made at the first frame
    this.history = [];  // [wall, t] of recent frames
    this.frames = 0;
    this.events = [];  // every event so far: the frames' newest ones, /event-log for a gap
    this.events_shown = -1;
    this.fetching_log = false;
    this.driving = false;
    this.hand_point = null;  // where the pointer put the hand last (scene frame)
    this.sending = false;
    this.pending = null;
    this.layout();
  }

  Live.prototype.layout = function () {
    var w = Math.max(1, this.canvas.clientWidth), h = Math.max(1, this.canvas.clientHeight);
    this.renderer.setSize(w, h, false);
    this.camera.aspect = w / h;
    this.camera.updateProjectionMatrix();
    if (this.cloth) this.render();
  };

  Live.prototype.render = function () {
    if (this.cloth) this.renderer.render(this.cloth.scene, this.camera);
  };

  Live.prototype.set_camera = function (kind) {
    drape.camera_preset(this.camera, this.controls, this.bounds, kind);
    this.camera_moved = false;
    document.querySelectorAll('[data-camera]').forEach(function (b) { b.classList.toggle('on', b.dataset.camera === kind); });
    this.camera_kind = kind;
    this.render();
  };

  Live.prototype.first_frame = function (positions) {
    this.cloth = new drape.ClothScene({ rows: spec.rows, cols: spec.cols, pins: spec.pins, dummy: spec.dummy,
                                        spacing: spec.spacing, events: [], name: 'live' }, positions);
    this.bounds = new THREE.Box3().setFromArray(positions);
    this.cloth_centre = this.bounds.getCenter(new THREE.Vector3());
    if (this.cloth.dummy_bounds) this.bounds.union(this.cloth.dummy_bounds);
    this.set_camera(hash.get('view') || 'front');
  };

  // The view frames the cloth at its start (and the object); a cloth that leaves that box (a
  // sheet swinging down from its pins, a hand carrying it off) grows it, with a tenth of its
  // size to spare so that a swing reframes a few times, not every frame, and the view is framed
  // on it again unless the person has moved the camera themselves.
  Live.prototype.keep_in_view = function (positions) {
    var now = new THREE.Box3().setFromArray(positions);
    if (this.bounds.containsBox(now)) return;
    this.bounds.union(now.expandByVector(now.getSize(new THREE.Vector3()).multiplyScalar(0.1)));
    if (!this.camera_moved) this.set_camera(this.camera_kind);
  };

  // Frames come at 30 a second; the page draws the latest one at the next animation frame, so
  // that a slow renderer drops frames instead of falling behind the stream.
  Live.prototype.receive = function (f) {
    var self = this;
    if (hook.key && f.t >= hook.at) { this.send_key(hook.key); hook.key = null; }
    if (!this.waiting) window.requestAnimationFrame(function () {
      self.waiting = null;
      self.on_frame(self.latest);
    });
    this.latest = f;
    this.waiting = true;
  };

  Live.prototype.on_frame = function (f) {
    var positions = new Float32Array(drape.base64_bytes(f.positions).buffer);
    if (!this.cloth) this.first_frame(positions.slice());
    else {
      this.cloth.positions.set(positions);
      this.keep_in_view(positions);
    }
    this.take_events(f);
    if (this.events.length !== this.events_shown) {
      this.cloth.set_attach_targets(this.events);
      this.show_events(this.events);
    }
    this.cloth.show(f.t, f.fixed, f.hands.map(function (h) {
      return { name: h.hand, available: h.available, position: h.position, held: h.held, candidate: h.candidate };
    }));
    this.render();
    this.show_rate(f);
    if (f.ended) this.show_end(f.ended);
    this.last = f;
    ++this.frames;
  };

  // The real-time factor: simulated seconds per wall-clock second, over the last second and
  // since the start; "cannot keep up" when the simulation is more than 0.1 s behind the clock.
  Live.prototype.show_rate = function (f) {
    this.history.push([f.wall, f.t]);
    while (this.history.length > 2 && f.wall - this.history[1][0] >= rtf_window) this.history.shift();
    var first = this.history[0], span = f.wall - first[0];
    var recent = span > 0 ? (f.t - first[1]) / span : f.rtf;
    document.getElementById('rtf').textContent = 'real-time factor ' + recent.toFixed(2) + ' (' +
      f.rtf.toFixed(2) + ' since the start)';
    var behind = document.getElementById('behind');
    behind.hidden = !f.behind;
    if (f.behind) behind.textContent = 'cannot keep up: ' + (f.wall - f.t).toFixed(2) + ' s behind the wall clock';
    document.getElementById('time-readout').textContent = 't = ' + f.t.toFixed(3) + ' s' +
      (spec.duration ? ' / ' + spec.duration.toFixed(3) + ' s' : '');
  };

  // The stream's last frame carries how the run ended ({status, t, reason}; docs/live.md).
  Live.prototype.show_end = function (end) {
    this.ended = end;
    var box = document.getElementById('ended');
    box.textContent = 'run ended at t = ' + end.t.toFixed(3) + ' s (' + end.status + (end.reason ? ': ' + end.reason : '') + ')';
    box.className = end.status === 'ok' || end.status === 'stopped' ? 'done' : 'bad';
    box.hidden = false;
    document.getElementById('behind').hidden = true;
  };

  // A frame carries the newest events, from index f.events_from of f.event_count (the server
  // keeps frames small however many events a run has): those after the ones known are appended;
  // a page that missed some (opened late, or more events than a frame holds between two frames
  // it read) fetches the whole list once.
  Live.prototype.take_events = function (f) {
    var known = this.events.length, self = this;
    if (f.event_count <= known) return;
    if (f.events_from <= known) {
      this.events = this.events.concat(f.events.slice(known - f.events_from));
      return;
    }
    if (this.fetching_log) return;
    this.fetching_log = true;
    fetch('/event-log').then(function (r) { return r.json(); }).then(function (log) {
      if (log.length > self.events.length) self.events = log;
    }).catch(function () {}).then(function () { self.fetching_log = false; });
  };

  Live.prototype.show_events = function (events) {
    this.events_shown = events.length;
    var box = document.getElementById('event-list');
    box.textContent = events.length ? '' : 'no events yet';
    events.slice(-6).forEach(function (e) {
      var item = document.createElement('span');
      item.innerHTML = '<b>' + e.type + '</b> ' + (e.key ? '(' + e.key + ') ' : '') + 't = ' + e.t.toFixed(3) + ' s &nbsp; ';
      box.appendChild(item);
    });
  };

  Live.prototype.send_key = function (key) {
    fetch('/key', { method: 'POST', body: key }).catch(function () {});
  };

  // The pointer's ray meets the plane that faces the camera through the hand (at first through
  // the cloth's centre); the wheel moves that plane nearer or farther by 1 cm a notch.
  Live.prototype.pointer_hand = function (e, depth) {
    var rect = this.canvas.getBoundingClientRect();
    var ndc = new THREE.Vector2(2 * (e.clientX - rect.left) / rect.width - 1, 1 - 2 * (e.clientY - rect.top) / rect.height);
    var ray = new THREE.Raycaster();
    ray.setFromCamera(ndc, this.camera);
    var normal = this.camera.getWorldDirection(new THREE.Vector3());
    var through = (this.hand_point || this.cloth_centre).clone().addScaledVector(normal, depth);
    var hit = ray.ray.intersectPlane(new THREE.Plane().setFromNormalAndCoplanarPoint(normal, through), new THREE.Vector3());
    if (hit) this.send_hand(hit);
  };

  // One request at a time; a newer position replaces one waiting.
  Live.prototype.send_hand = function (p) {
    var self = this;
    this.hand_point = p.clone();
    this.pending = { x: p.x, y: p.y, z: p.z };
    if (this.sending) return;
    var next = function () {
      if (!self.pending) { self.sending = false; return; }
      self.sending = true;
      var body = JSON.stringify(self.pending);
      self.pending = null;
      fetch('/hand', { method: 'POST', body: body }).then(function (r) {
        if (!r.ok) return r.text().then(function (t) { console.warn('POST /hand: ' + t); });
      }).catch(function () {}).then(next);
    };
    next();
  };

  Live.prototype.set_driving = function (on) {
    this.driving = on && spec.live_hands;
    this.controls.enabled = !this.driving;
    var button = document.getElementById('hand-mode');
    button.classList.toggle('on', this.driving);
    button.textContent = this.driving ? 'hand: on (pointer)' : 'hand: off';
    document.getElementById('views').classList.toggle('driving', this.driving);
  };

  Live.prototype.connect = function () {
    var self = this;
    document.addEventListener('keydown', function (e) {
      if (e.ctrlKey || e.metaKey || e.altKey || e.target.tagName === 'INPUT') return;
      if (e.key === 'r' || e.key === 'a' || e.key === 'm') self.send_key(e.key);
      else if (e.key === 'h') self.set_driving(!self.driving);
    });
    document.querySelectorAll('[data-key]').forEach(function (b) {
      b.addEventListener('click', function () { self.send_key(b.dataset.key); });
    });
    document.querySelectorAll('[data-camera]').forEach(function (b) {
      b.addEventListener('click', function () { self.set_camera(b.dataset.camera); });
    });
    document.getElementById('show-grid').addEventListener('change', function (e) {
      if (self.cloth) { self.cloth.grid.visible = e.target.checked; self.render(); }
    });
    if (spec.live_hands) {
      document.getElementById('hand-mode').hidden = false;
      document.getElementById('hand-hint').hidden = false;
      document.getElementById('hand-mode').addEventListener('click', function () { self.set_driving(!self.driving); });
      this.canvas.addEventListener('pointermove', function (e) { if (self.driving && self.cloth) self.pointer_hand(e, 0); });
      this.canvas.addEventListener('wheel', function (e) {
        if (!self.driving || !self.cloth) return;
        e.preventDefault();
        self.pointer_hand(e, e.deltaY > 0 ? 0.01 : -0.01);
      }, { passive: false });
    }
    window.addEventListener('resize', function () { self.layout(); });
    var source = new EventSource('/events');
    source.onmessage = function (m) { self.receive(JSON.parse(m.data)); };
    source.onerror = function () {
      // After the last frame the server closes the stream; without one it went away mid-run.
      // Before any frame, the server may also have refused the stream (503: as many pages as it
      // serves already watch, docs/live.md "Many connections"); EventSource does not say which.
      if (!self.ended) document.getElementById('rtf').textContent = self.latest
        ? 'connection lost: the server is gone'
        : 'no stream: the server is gone or already streams to as many pages as it allows (close one and reload)';
      source.close();
    };
  };

  // For the browser check: render now and count the pixels that differ from the background.
  Live.prototype.nonbackground_pixels = function () {
    this.render();
    var gl = this.renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
    var pixels = new Uint8Array(4 * w * h), bg = this.background, count = 0;
    gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, pixels);
    var c = [bg.r, bg.g, bg.b].map(function (v) { return Math.round(255 * v); });
    for (var i = 0; i < w * h; ++i)
      if (Math.abs(pixels[4 * i] - c[0]) > 3 || Math.abs(pixels[4 * i + 1] - c[1]) > 3 || Math.abs(pixels[4 * i + 2] - c[2]) > 3) ++count;
    return { nonbackground: count, pixels: w * h };
  };

  drape.build_legend();
  document.getElementById('scene-name').textContent = spec.rows + ' x ' + spec.cols + ' cloth' +
    (spec.live_hands ? ', live hands' : ', hands from the scene');
  var live = new Live();
  drape.live = live;
  live.connect();
})();
