#include "experiments/live/live_page.hpp"

namespace drape {

// A front view (x right, y up) of the latest frame drawn on a 2-D canvas, a status line, keys
// r/a/m posted to /key, and the test hook `#test-key=m&at=0.2` that posts a key once the
// streamed sim time reaches `at` (tests/experiments/live/live_check.py uses it).
const std::string& live_page() {
  static const std::string page = R"livepage(<!doctype html>
<html><head><meta charset="utf-8"><title>drapelab live</title>
<style>body{margin:0;font:14px sans-serif;background:#f4f4f4}#status{padding:6px 10px}
#behind{color:#b00;font-weight:bold}canvas{display:block;margin:0 auto;background:#fff}</style>
</head><body>
<div id="status">connecting&hellip;</div>
<canvas id="view" width="640" height="640"></canvas>
<script>
"use strict";
const status = document.getElementById("status");
const canvas = document.getElementById("view");
const ctx = canvas.getContext("2d");
const hook = new URLSearchParams(location.hash.slice(1));
let hookKey = hook.get("test-key"), hookAt = parseFloat(hook.get("at") || "0");
function sendKey(key) { fetch("/key", {method: "POST", body: key}); }
document.addEventListener("keydown", e => { if ("ram".includes(e.key) && e.key.length === 1) sendKey(e.key); });
function decode(b64) {
  const bytes = Uint8Array.from(atob(b64), c => c.charCodeAt(0));
  return new Float32Array(bytes.buffer);
}
function draw(f) {
  const p = decode(f.positions), n = p.length / 3;
  let lo = [Infinity, Infinity], hi = [-Infinity, -Infinity];
  for (let i = 0; i < n; ++i) for (let k = 0; k < 2; ++k) {
    lo[k] = Math.min(lo[k], p[3 * i + k]); hi[k] = Math.max(hi[k], p[3 * i + k]);
  }
  const span = Math.max(hi[0] - lo[0], hi[1] - lo[1], 1e-3) * 1.3;
  const cx = (lo[0] + hi[0]) / 2, cy = (lo[1] + hi[1]) / 2, s = canvas.width / span;
  const X = x => canvas.width / 2 + (x - cx) * s, Y = y => canvas.height / 2 - (y - cy) * s;
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  ctx.fillStyle = "#36c";
  for (let i = 0; i < n; ++i) ctx.fillRect(X(p[3 * i]) - 1, Y(p[3 * i + 1]) - 1, 2, 2);
  for (const h of f.hands) if (h.available) {
    ctx.fillStyle = h.hand === "left" ? "#c33" : "#3a3";
    ctx.beginPath(); ctx.arc(X(h.position[0]), Y(h.position[1]), 6, 0, 7); ctx.fill();
  }
}
const source = new EventSource("/events");
source.onmessage = m => {
  const f = JSON.parse(m.data);
  draw(f);
  status.innerHTML = `t = ${f.t.toFixed(3)} s &middot; real-time factor ${f.rtf.toFixed(2)} &middot; ` +
    `${f.events.length} events` + (f.behind ? ' &middot; <span id="behind">cannot keep up</span>' : "");
  if (hookKey && f.t >= hookAt) { sendKey(hookKey); hookKey = null; }
};
source.onerror = () => { status.textContent = "run ended (or the server is gone)"; source.close(); };
</script></body></html>
)livepage";
  return page;
}

}  // namespace drape
