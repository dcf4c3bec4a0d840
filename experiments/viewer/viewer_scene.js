// The 3-D scene of one cloth (cloth mesh, dress form, hands, markers), shared by `drapelab view`
// (RunView: a recorded run at a given time, from the JSON of experiments/viewer/page_data.cpp,
// docs/viewer.md) and `drapelab live` (experiments/live/live_main.js: the streamed frames).
'use strict';

var drape = window.drape || (window.drape = {});

// Colours of the page, one place: the legend is built from this table.
drape.colours = {
  cloth_front: 0x3d7cc9, cloth_back: 0xa9c4e4, grid: 0x15325a, dress_form: 0xd9cbb8,
  object_particle: 0x7a6a58, pinned: 0xd62728, fixed: 0xff8c1a, held: 0xc21cc2,
  candidate: 0xf5d000, right_hand: 0x2ca02c, left_hand: 0x17becf, hand_outline: 0x1f2933,
  attach_target: 0x6a00ff
};
drape.legend = [
  ['cloth_front', 'cloth, front side', 'square'], ['cloth_back', 'cloth, back side', 'square'],
  ['dress_form', 'dress form', 'square'], ['pinned', 'pinned particle'],
  ['fixed', 'other fixed particle (attached, mapped edge)'], ['held', 'held by a hand'],
  ['candidate', 'hold candidate (nearest to a hand)'], ['right_hand', 'right hand'],
  ['left_hand', 'left hand'], ['attach_target', 'attach target (object particle)']
];

drape.base64_bytes = function (text) {
  var raw = atob(text), bytes = new Uint8Array(raw.length);
  for (var i = 0; i < raw.length; ++i) bytes[i] = raw.charCodeAt(i);
  return bytes;
};

// Index of the last value <= t in a sorted array (0 when t is before the first).
drape.last_at_or_before = function (values, t) {
  var lo = 0, hi = values.length - 1;
  if (hi < 0 || t < values[0]) return 0;
  while (lo < hi) {
    var mid = (lo + hi + 1) >> 1;
    if (values[mid] <= t) lo = mid; else hi = mid - 1;
  }
  return lo;
};

// The scene of a cloth of spec.rows x spec.cols particles at `positions` (a Float32Array of xyz,
// the scene keeps and draws it), with spec.pins, spec.dummy and spec.events as page_data.cpp
// writes them. show() puts the markers and hands of one moment.
drape.ClothScene = function (spec, positions) {
  this.run = spec;
  this.scene = new THREE.Scene();
  this.particles = spec.rows * spec.cols;
  if (positions.length !== 3 * this.particles) throw new Error((spec.name || 'cloth') + ': positions size');
  this.positions = positions;
  this.pin_set = {};
  for (var p = 0; p < spec.pins.length; ++p) this.pin_set[spec.pins[p][0] * spec.cols + spec.pins[p][1]] = true;
  this.add_lights();
  this.add_cloth();
  this.add_dress_form();
  this.markers = { pinned: [], fixed: [], held: [], candidate: [] };
  // The scene's cloth.spacing when the page has it (the live page: its first frame may be
  // mid-run, stretched); else the first frame's particle distance (a recorded run's t = 0).
  this.marker_radius = Math.max(0.004, 0.35 * (spec.spacing || this.spacing()));
  this.hand_meshes = {};
  this.attach_targets = [];
  this.set_attach_targets(spec.events);
};

// Where a recorded run ends: its last frame, its sim_time or its last energy row, the latest (a
// trace interval that does not divide the duration leaves the last frame just before the end).
drape.run_end = function (run) {
  var f = run.frames, e = run.energy.t;
  return Math.max(f.times[f.count - 1], run.sim_time, e.length ? e[e.length - 1] : 0);
};

drape.RunView = function (run) {
  var f = run.frames, n = run.rows * run.cols;
  this.quanta = new Int16Array(drape.base64_bytes(f.positions).buffer);
  if (this.quanta.length !== 3 * n * f.count) throw new Error(run.name + ': frame data size');
  var positions = new Float32Array(3 * n);
  for (var i = 0; i < 3 * n; ++i) positions[i] = f.centre[i % 3] + f.step * this.quanta[i];
  drape.ClothScene.call(this, run, positions);
  this.bounds = new THREE.Box3();
  var half = 32767 * f.step;
  this.bounds.min.set(f.centre[0] - half, f.centre[1] - half, f.centre[2] - half);
  this.bounds.max.set(f.centre[0] + half, f.centre[1] + half, f.centre[2] + half);
  this.cloth_bounds = this.frame_bounds();
};
drape.RunView.prototype = Object.create(drape.ClothScene.prototype);
drape.RunView.prototype.constructor = drape.RunView;

drape.RunView.prototype.frame_bounds = function () {
  var box = new THREE.Box3(), f = this.run.frames, v = new THREE.Vector3();
  for (var i = 0; i < this.quanta.length; i += 3) {
    v.set(f.centre[0] + f.step * this.quanta[i], f.centre[1] + f.step * this.quanta[i + 1],
          f.centre[2] + f.step * this.quanta[i + 2]);
    box.expandByPoint(v);
  }
  return box;
};

// Distance between particles (0, 0) and (0, 1) or (1, 0) at the first positions.
drape.ClothScene.prototype.spacing = function () {
  var q = this.positions, j = this.run.cols > 1 ? 3 : 3 * this.run.cols;
  if (this.particles < 2) return 0.01;
  var dx = q[j] - q[0], dy = q[j + 1] - q[1], dz = q[j + 2] - q[2];
  return Math.sqrt(dx * dx + dy * dy + dz * dz);
};

drape.ClothScene.prototype.add_lights = function () {
  this.scene.add(new THREE.HemisphereLight(0xffffff, 0x8a8275, 0.55));
  var key = new THREE.DirectionalLight(0xffffff, 0.75);
  key.position.set(0.6, 1.0, 1.2);
  this.scene.add(key);
  var rim = new THREE.DirectionalLight(0xffffff, 0.3);
  rim.position.set(-1.0, 0.4, -0.8);
  this.scene.add(rim);
};

drape.ClothScene.prototype.add_cloth = function () {
  var run = this.run, rows = run.rows, cols = run.cols, index = [];
  for (var r = 0; r + 1 < rows; ++r)
    for (var c = 0; c + 1 < cols; ++c) {
      var a = r * cols + c, b = a + 1, d = a + cols, e = d + 1;
      index.push(a, d, b, b, d, e);
    }
  var geometry = new THREE.BufferGeometry();
  geometry.setIndex(index);
  this.cloth_position = new THREE.BufferAttribute(this.positions, 3);
  this.cloth_position.setUsage ? this.cloth_position.setUsage(THREE.DynamicDrawUsage)
                               : this.cloth_position.setDynamic(true);
  geometry.setAttribute('position', this.cloth_position);
  this.cloth_geometry = geometry;
  var c = drape.colours;
  // Two meshes on one geometry: each side its own colour, so folds read at a glance.
  var front = new THREE.MeshPhongMaterial({ color: c.cloth_front, side: THREE.FrontSide, shininess: 12,
                                           polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
  var back = new THREE.MeshPhongMaterial({ color: c.cloth_back, side: THREE.BackSide, shininess: 12,
                                          polygonOffset: true, polygonOffsetFactor: 1, polygonOffsetUnits: 1 });
  this.scene.add(new THREE.Mesh(geometry, front));
  this.scene.add(new THREE.Mesh(geometry, back));
  // The grid lines of the particle-spring sheet.
  var lines = [];
  for (r = 0; r < rows; ++r) for (c = 0; c < cols; ++c) {
    var i = r * cols + c;
    if (c + 1 < cols) lines.push(i, i + 1);
    if (r + 1 < rows) lines.push(i, i + cols);
  }
  var grid_geometry = new THREE.BufferGeometry();
  grid_geometry.setIndex(lines);
  grid_geometry.setAttribute('position', this.cloth_position);
  this.grid = new THREE.LineSegments(grid_geometry, new THREE.LineBasicMaterial(
    { color: drape.colours.grid, transparent: true, opacity: 0.22 * Math.min(1, 24 / Math.max(rows, cols)) }));
  this.scene.add(this.grid);
};

// Object particles are sections x points, each section a closed ring (dummy.csv).
drape.ClothScene.prototype.add_dress_form = function () {
  var d = this.run.dummy;
  this.object_particles = null;
  if (!d.positions.length) return;
  var positions = new Float32Array(d.positions);
  var geometry = new THREE.BufferGeometry();
  geometry.setAttribute('position', new THREE.BufferAttribute(positions, 3));
  if (d.points >= 3 && d.sections >= 2) {
    var index = [];
    for (var s = 0; s + 1 < d.sections; ++s)
      for (var p = 0; p < d.points; ++p) {
        var a = s * d.points + p, b = s * d.points + (p + 1) % d.points;
        index.push(a, b, a + d.points, b, b + d.points, a + d.points);
      }
    geometry.setIndex(index);
    geometry.computeVertexNormals();
    var surface = new THREE.Mesh(geometry, new THREE.MeshPhongMaterial(
      { color: drape.colours.dress_form, side: THREE.DoubleSide, shininess: 4 }));
    this.scene.add(surface);
  }
  this.object_particles = new THREE.Points(geometry, new THREE.PointsMaterial(
    { color: drape.colours.object_particle, size: 2.5, sizeAttenuation: false }));
  this.object_particles.visible = !d.points || d.points < 3 || d.sections < 2;
  this.dummy_bounds = new THREE.Box3().setFromBufferAttribute(geometry.getAttribute('position'));
  this.scene.add(this.object_particles);
};

// The attach targets of `events` (the live page calls it again as events come).
drape.ClothScene.prototype.set_attach_targets = function (events) {
  var d = this.run.dummy, self = this;
  this.attach_targets.forEach(function (m) { self.scene.remove(m); });
  this.attach_targets = [];
  for (var i = 0; i < events.length; ++i) {
    var e = events[i];
    if (e.type !== 'attach' || e.object_particle === undefined || e.object_particle < 0) continue;
    var k = 3 * e.object_particle;
    if (k + 2 >= d.positions.length) continue;
    if (!this.attach_geometry) this.attach_geometry = new THREE.OctahedronBufferGeometry(1.6 * this.marker_radius);
    var marker = new THREE.Mesh(this.attach_geometry, new THREE.MeshPhongMaterial({ color: drape.colours.attach_target }));
    marker.position.set(d.positions[k], d.positions[k + 1], d.positions[k + 2]);
    marker.userData.t = e.t;
    this.attach_targets.push(marker);
    this.scene.add(marker);
  }
};

// The k-th sphere of a kind, made when first needed and shared geometry per kind.
drape.ClothScene.prototype.marker = function (kind, k) {
  var list = this.markers[kind];
  if (k < list.length) return list[k];
  if (!this.marker_geometry) this.marker_geometry = new THREE.SphereBufferGeometry(1, 12, 8);
  var mesh = new THREE.Mesh(this.marker_geometry, new THREE.MeshPhongMaterial({ color: drape.colours[kind] }));
  var scale = this.marker_radius * (kind === 'pinned' || kind === 'fixed' ? 1 : 1.35);
  mesh.scale.set(scale, scale, scale);
  this.scene.add(mesh);
  list.push(mesh);
  return mesh;
};

drape.ClothScene.prototype.place_markers = function (kind, particles) {
  var list = this.markers[kind], p = this.positions;
  for (var k = 0; k < particles.length; ++k) {
    var i = particles[k];
    this.marker(kind, k).position.set(p[3 * i], p[3 * i + 1], p[3 * i + 2]);
    this.markers[kind][k].visible = true;
  }
  for (k = particles.length; k < list.length; ++k) list[k].visible = false;
};

drape.ClothScene.prototype.hand_mesh = function (name) {
  if (!this.hand_meshes[name]) {
    var colour = name === 'left' ? drape.colours.left_hand : drape.colours.right_hand;
    // Translucent, so that the particle the hand holds shows inside it; drawn last and over
    // everything (no depth test), so that a fold of the cloth in front of the hand does not
    // hide it: where the hand is is what the reader looks for (docs/viewer.md, Colours).
    var mesh = new THREE.Mesh(new THREE.SphereBufferGeometry(0.016, 20, 14), new THREE.MeshPhongMaterial(
      { color: colour, shininess: 40, transparent: true, opacity: 0.55, depthWrite: false, depthTest: false }));
    mesh.renderOrder = 10;
    this.scene.add(mesh);
    // A dark outline ring facing the camera, also over everything: the hand reads on the
    // cloth's blue where its translucent colour alone would blend in.
    var outline = new THREE.Mesh(new THREE.RingBufferGeometry(0.016, 0.0195, 32), new THREE.MeshBasicMaterial(
      { color: drape.colours.hand_outline, depthTest: false, depthWrite: false, transparent: true }));
    outline.renderOrder = 11;
    outline.onBeforeRender = function (renderer, scene, camera) { outline.quaternion.copy(camera.quaternion); };
    mesh.add(outline);
    // A line from the hand to its candidate or held particle: which hand a marker belongs to.
    var link = new THREE.Line(new THREE.BufferGeometry().setFromPoints([new THREE.Vector3(), new THREE.Vector3()]),
                              new THREE.LineBasicMaterial({ color: colour, transparent: true, opacity: 0.8 }));
    this.scene.add(link);
    mesh.userData.link = link;
    this.hand_meshes[name] = mesh;
  }
  return this.hand_meshes[name];
};

// Shows the run at time t: cloth interpolated between the frames around t (the last frame
// after the run's end), markers of the frame at or before t, hands of the hands.csv row at or
// before t. Returns what the label shows.
drape.RunView.prototype.set_time = function (t) {
  var f = this.run.frames, times = f.times, n3 = 3 * this.particles;
  var k = drape.last_at_or_before(times, t), k1 = Math.min(k + 1, f.count - 1);
  var alpha = k1 > k && times[k1] > times[k] ? Math.min(1, Math.max(0, (t - times[k]) / (times[k1] - times[k]))) : 0;
  var q = this.quanta, a = k * n3, b = k1 * n3, pos = this.positions;
  for (var i = 0; i < n3; ++i)
    pos[i] = f.centre[i % 3] + f.step * ((1 - alpha) * q[a + i] + alpha * q[b + i]);
  var fixed = f.fixed[drape.last_at_or_before(f.fixed.map(function (c) { return c.frame; }), k)];
  var hands = this.run.hands.map(function (hand) {
    var r = drape.last_at_or_before(hand.t, t), p = hand.positions;
    return { name: hand.name, available: hand.t.length > 0 && hand.available[r] === 1,
             position: [p[3 * r], p[3 * r + 1], p[3 * r + 2]], held: hand.held[r], candidate: hand.candidate[r] };
  });
  this.show(t, fixed ? fixed.particles : [], hands);
  // Ended past the run's own end, not its last frame (0.999999 s of a 1 s run).
  return { frame: k, frames: f.count, frame_t: times[k], ended: t > drape.run_end(this.run) + 1e-9 };
};

// Draws this.positions with the fixed particles (pins red, others orange), the hands (each
// {name, available, position, held, candidate}) with their held or candidate particle, and the
// attach targets from their time on.
drape.ClothScene.prototype.show = function (t, fixed_particles, hands) {
  var pos = this.positions;
  this.cloth_position.needsUpdate = true;
  this.cloth_geometry.computeVertexNormals();
  this.cloth_geometry.computeBoundingSphere();
  var pinned = [], other = [], held = [], candidates = [], i;
  for (i = 0; i < fixed_particles.length; ++i)
    (this.pin_set[fixed_particles[i]] ? pinned : other).push(fixed_particles[i]);
  for (var h = 0; h < hands.length; ++h) {
    var hand = hands[h], mesh = this.hand_mesh(hand.name);
    mesh.visible = hand.available;
    var link = mesh.userData.link, target = -1;
    if (mesh.visible) {
      mesh.position.fromArray(hand.position);
      target = hand.held >= 0 ? hand.held : hand.candidate;
      if (hand.held >= 0) held.push(hand.held);
      else if (hand.candidate >= 0) candidates.push(hand.candidate);
    }
    link.visible = target >= 0;
    if (link.visible) {
      var ends = link.geometry.getAttribute('position');
      ends.setXYZ(0, mesh.position.x, mesh.position.y, mesh.position.z);
      ends.setXYZ(1, pos[3 * target], pos[3 * target + 1], pos[3 * target + 2]);
      ends.needsUpdate = true;
      link.geometry.computeBoundingSphere();
    }
  }
  other = other.filter(function (p) { return held.indexOf(p) < 0; });
  this.place_markers('pinned', pinned);
  this.place_markers('fixed', other);
  this.place_markers('held', held);
  this.place_markers('candidate', candidates);
  for (i = 0; i < this.attach_targets.length; ++i)
    this.attach_targets[i].visible = t >= this.attach_targets[i].userData.t;
};

// Puts `camera` and `controls` at a preset looking at `bounds`. Front: from +z (the dress form's
// front) looking along -z; side: from -x, so +z is to the right as in analysis/plot_state.py;
// 3/4: between the two, a little from above. The nearest distance that shows every corner.
drape.camera_preset = function (camera, controls, bounds, kind) {
  var directions = { front: [0, 0, 1], side: [-1, 0, 0], three_quarter: [-0.75, 0.35, 1] };
  var d = new THREE.Vector3().fromArray(directions[kind] || directions.front).normalize();
  var centre = bounds.getCenter(new THREE.Vector3()), box = bounds;
  var right = new THREE.Vector3().crossVectors(d, new THREE.Vector3(0, 1, 0)).negate();
  if (right.lengthSq() < 1e-9) right.set(1, 0, 0);
  right.normalize();
  var up = new THREE.Vector3().crossVectors(right, d).negate();
  var tan_v = Math.tan(camera.fov * Math.PI / 360), tan_h = tan_v * camera.aspect;
  var distance = 0, corner = new THREE.Vector3();
  for (var k = 0; k < 8; ++k) {
    corner.set(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z).sub(centre);
    distance = Math.max(distance, corner.dot(d) + Math.max(Math.abs(corner.dot(right)) / tan_h,
                                                           Math.abs(corner.dot(up)) / tan_v));
  }
  distance *= 1.06;
  controls.target.copy(centre);
  camera.position.copy(centre).addScaledVector(d, distance);
  camera.up.set(0, 1, 0);
  camera.lookAt(centre);
  controls.update();
};
