// The HTML player's style and script (present/html.cpp puts the data between them). The script
// repeats in JavaScript what present/camera and present/wireframe do in C++: the same
// projection (gluLookAt's basis, a vertical field of view, a near plane), the same shapes,
// grids, arrows and ellipses, so the page shows what w:render shows.
namespace rigidlab::present {

extern const char* const html_head;
extern const char* const html_script;

const char* const html_head = R"(<style>
body { font: 14px sans-serif; margin: 16px; color: #222; background: #fff; }
h1 { font-size: 17px; font-weight: 600; }
canvas { border: 1px solid #ccc; cursor: grab; max-width: 100%; }
#controls { margin: 8px 0; display: flex; gap: 10px; align-items: center; }
#slider { width: 520px; }
#status, #clock { font-family: monospace; }
#legend span { margin-right: 1.4em; white-space: nowrap; }
.swatch { display: inline-block; width: 18px; height: 3px; vertical-align: middle; margin-right: 4px; }
.hint { color: #777; font-size: 12px; }
</style></head>
<body data-state="loading">
)";

const char* const html_script = R"JS(
window.addEventListener("error", e => document.body.setAttribute("data-state", "error: " + e.message));
const canvas = document.getElementById("view"), g = canvas.getContext("2d");
const slider = document.getElementById("slider"), play = document.getElementById("play");
const clock = document.getElementById("clock"), statusBox = document.getElementById("status");
const legendBox = document.getElementById("legend");
const BODY = ["#1f5fbf", "#2a9d3a", "#179c9c", "#a33ca3", "#c98a00", "#555555"];
const OVERLAY = [  // as present::Overlay: axes x y z, omega, L, impulse, contact, ellipsoid, trail, joint
  ["#e02020", "x", "body axes"], ["#20a020", "y", ""], ["#2050e0", "z", ""],
  ["#d4a000", "\u03c9", "angular velocity"], ["#c020c0", "L", "angular momentum"],
  ["#e04040", "J", "contact impulse"], ["#e04040", "\u00d7", "contact point"],
  ["#00a0b0", "\u25ef", "inertia ellipsoid"], ["#999999", "\u2504", "trail"],
  ["#000000", "\u25cf", "joint"]];
const cam = {eye: DATA.camera.eye.slice(), target: DATA.camera.target.slice(),
             up: DATA.camera.up.slice(), fov: DATA.camera.fov};

const sub = (a, b) => [a[0] - b[0], a[1] - b[1], a[2] - b[2]];
const add = (a, b) => [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
const mul = (a, s) => [a[0] * s, a[1] * s, a[2] * s];
const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
const cross = (a, b) => [a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]];
const norm = a => Math.sqrt(dot(a, a));
const unit = a => mul(a, 1 / norm(a));
const col = (R, k) => [R[k], R[3 + k], R[6 + k]];  // R row by row
const apply = (R, v) => [dot(R.slice(0, 3), v), dot(R.slice(3, 6), v), dot(R.slice(6, 9), v)];

function basis() {
  const f = unit(sub(cam.target, cam.eye)), r = unit(cross(f, cam.up)), u = cross(r, f);
  const focal = canvas.height / 2 / Math.tan(cam.fov * Math.PI / 360);
  return {f, r, u, focal, near: Math.max(1e-9, 1e-3 * norm(sub(cam.target, cam.eye)))};
}
function project(V, p) {
  const d = sub(p, cam.eye), z = dot(d, V.f);
  if (!(z >= V.near)) return null;
  return [canvas.width / 2 + V.focal * dot(d, V.r) / z, canvas.height / 2 - V.focal * dot(d, V.u) / z];
}
function segment(V, a, b) {  // clipped at the near plane
  const za = dot(sub(a, cam.eye), V.f), zb = dot(sub(b, cam.eye), V.f);
  if (za < V.near && zb < V.near) return null;
  if (za < V.near) a = add(a, mul(sub(b, a), (V.near - za) / (zb - za)));
  else if (zb < V.near) b = add(b, mul(sub(a, b), (V.near - zb) / (za - zb)));
  const p = project(V, a), q = project(V, b);
  if (!p || !q) return null;
  g.moveTo(p[0], p[1]);
  g.lineTo(q[0], q[1]);
  return [p, q];
}
function ellipse(V, c, u, v) {
  let prev = add(c, u);
  for (let i = 1; i <= 64; i++) {
    const t = 2 * Math.PI * i / 64, next = add(c, add(mul(u, Math.cos(t)), mul(v, Math.sin(t))));
    segment(V, prev, next);
    prev = next;
  }
}
function stroke(color, width, dash) {
  g.strokeStyle = color; g.lineWidth = width; g.setLineDash(dash || []); g.stroke(); g.beginPath();
}
function body(V, b, i) {  // [shape, position, R (rows), half extents, radius, segments' ends]
  const p = b.slice(1, 4), R = b.slice(4, 13), h = b.slice(13, 16), r = b[16];
  g.beginPath();
  if (b[0] === 2) {
    const corner = k => add(p, apply(R, [(k & 1 ? 1 : -1) * h[0], (k & 2 ? 1 : -1) * h[1], (k & 4 ? 1 : -1) * h[2]]));
    for (let k = 0; k < 8; k++)
      for (let bit = 1; bit < 8; bit <<= 1) if (!(k & bit)) segment(V, corner(k), corner(k | bit));
  } else if (b[0] === 1) {
    for (let k = 0; k < 3; k++) ellipse(V, p, mul(col(R, (k + 1) % 3), r), mul(col(R, (k + 2) % 3), r));
    const w = sub(p, cam.eye), d = norm(w);
    if (d > r) {
      const n = mul(w, 1 / d), u = unit(cross(n, Math.abs(n[1]) < 0.9 ? [0, 1, 0] : [1, 0, 0]));
      const rho = r * Math.sqrt(d * d - r * r) / d;
      ellipse(V, sub(p, mul(n, r * r / d)), mul(u, rho), mul(cross(n, u), rho));
    }
  } else {
    for (let k = 17; k + 5 < b.length; k += 6) segment(V, b.slice(k, k + 3), b.slice(k + 3, k + 6));
    const q = project(V, p);
    if (q) { g.moveTo(q[0] - 4, q[1]); g.lineTo(q[0] + 4, q[1]); g.moveTo(q[0], q[1] - 4); g.lineTo(q[0], q[1] + 4); }
  }
  stroke(BODY[i % 6], 1.6);
}
function plane(V, pl) {  // a grid at round multiples of its spacing, as present/wireframe
  const n = unit(pl.slice(0, 3)), u = unit(cross(n, Math.abs(n[0]) < 0.9 ? [1, 0, 0] : [0, 0, 1]));
  const v = cross(n, u), half = Math.max(1.5 * DATA.radius, 1);
  const spacing = nice(half / 3), o = mul(n, pl[3]);
  const a0 = dot(DATA.center, u), b0 = dot(DATA.center, v);
  g.beginPath();
  for (let k = Math.ceil((a0 - half) / spacing); k <= Math.floor((a0 + half) / spacing); k++)
    segment(V, add(o, add(mul(u, k * spacing), mul(v, b0 - half))), add(o, add(mul(u, k * spacing), mul(v, b0 + half))));
  for (let k = Math.ceil((b0 - half) / spacing); k <= Math.floor((b0 + half) / spacing); k++)
    segment(V, add(o, add(mul(u, a0 - half), mul(v, k * spacing))), add(o, add(mul(u, a0 + half), mul(v, k * spacing))));
  stroke("#b0b0b0", 1, [2, 4]);
}
function nice(x) {  // Heckbert's rounded nice number, as present/chart
  const p = Math.pow(10, Math.floor(Math.log10(x))), f = x / p;
  return (f < 1.5 ? 1 : f < 3 ? 2 : f < 7 ? 5 : 10) * p;
}
function arrow(V, a) {
  const kind = a[0], o = a.slice(1, 4), v = a.slice(4, 7), style = OVERLAY[kind];
  if (!(norm(v) > 0)) return;
  g.beginPath();
  const s = segment(V, o, add(o, v));
  if (s) {
    const [p, q] = s, dx = q[0] - p[0], dy = q[1] - p[1], l = Math.hypot(dx, dy);
    if (l > 6) {
      const ux = dx / l, uy = dy / l, h = Math.min(10, 0.4 * l);
      for (const sg of [-1, 1]) {
        const c = Math.cos(0.45), sn = Math.sin(0.45);
        g.moveTo(q[0], q[1]);
        g.lineTo(q[0] - h * (ux * c - sg * uy * sn), q[1] - h * (sg * ux * sn + uy * c));
      }
    }
    g.fillStyle = style[0];
    g.fillText(style[1], q[0] + (l > 0 ? 8 * dx / l : 8) - 4, q[1] + (l > 0 ? 8 * dy / l : 0) + 4);
  }
  stroke(style[0], 2);
}
function legend(F, kinds) {
  let html = DATA.names.map((name, i) =>
    "<span><i class=\"swatch\" style=\"background:" + BODY[i % 6] + "\"></i>" + (i + 1) + " " + escape(name) + "</span>").join("");
  for (let k = 0; k < OVERLAY.length; k++) {
    if (!kinds.has(k) || k === 1 || k === 2) continue;
    const label = k === 0 ? "x y z" : OVERLAY[k][1];
    let note = F.n.filter(n => n[0] === k).map(n => " " + escape(n[1])).join("");
    html += "<span style=\"color:" + OVERLAY[k][0] + "\">" + label + "</span><span>" + OVERLAY[k][2] + note + "</span>";
  }
  legendBox.innerHTML = html;
}
function escape(s) { return s.replace(/[&<>"]/g, c => ({"&": "&amp;", "<": "&lt;", ">": "&gt;", "\"": "&quot;"})[c]); }
function draw(k) {
  const F = DATA.frames[k];
  if (!F) return;
  const V = basis();
  g.setLineDash([]);
  g.fillStyle = "#ffffff";
  g.fillRect(0, 0, canvas.width, canvas.height);
  g.font = "14px sans-serif";
  for (const pl of DATA.planes) plane(V, pl);
  F.b.forEach((b, i) => body(V, b, i));
  const kinds = new Set();
  for (const e of F.e) {
    g.beginPath();
    const c = e.slice(0, 3), A = e.slice(3, 12), s = e.slice(12, 15);
    for (let k2 = 0; k2 < 3; k2++) {
      const i = (k2 + 1) % 3, j = (k2 + 2) % 3;
      ellipse(V, c, mul(col(A, i), s[i]), mul(col(A, j), s[j]));
    }
    stroke(OVERLAY[7][0], 1, [6, 3]);
    kinds.add(7);
  }
  for (const c of F.c) {
    g.beginPath();
    for (let i = 3; i + 2 < c.length; i += 3) segment(V, c.slice(i - 3, i), c.slice(i, i + 3));
    stroke(OVERLAY[8][0], 1.2, [2, 3]);
    kinds.add(8);
  }
  for (const m of F.m) {
    const q = project(V, m.slice(1, 4));
    kinds.add(m[0]);
    if (!q) continue;
    g.beginPath();
    g.moveTo(q[0] - 4, q[1] - 4); g.lineTo(q[0] + 4, q[1] + 4); g.moveTo(q[0] - 4, q[1] + 4); g.lineTo(q[0] + 4, q[1] - 4);
    stroke(OVERLAY[m[0]][0], 2);
  }
  for (const a of F.a) { arrow(V, a); kinds.add(a[0]); }
  for (const n of F.n) kinds.add(n[0]);
  clock.textContent = "t = " + F.t.toFixed(3) + " s";
  statusBox.textContent = F.status;
  legend(F, kinds);
  document.body.setAttribute("data-state", "frame " + k);
}

let playing = false, startWall = 0, startTime = 0;
function tick(now) {
  if (!playing) return;
  const t = startTime + (now - startWall) / 1000;
  let k = +slider.value;
  while (k + 1 < DATA.frames.length && DATA.frames[k + 1].t <= t) k++;
  if (k !== +slider.value) { slider.value = k; draw(k); }
  if (k + 1 >= DATA.frames.length) { playing = false; play.textContent = "play"; return; }
  requestAnimationFrame(tick);
}
play.addEventListener("click", () => {
  playing = !playing;
  play.textContent = playing ? "pause" : "play";
  if (!playing) return;
  if (+slider.value + 1 >= DATA.frames.length) { slider.value = 0; draw(0); }
  startWall = performance.now();
  startTime = DATA.frames[+slider.value].t;
  requestAnimationFrame(tick);
});
slider.addEventListener("input", () => draw(+slider.value));
let drag = null;
canvas.addEventListener("pointerdown", e => { drag = [e.clientX, e.clientY]; canvas.setPointerCapture(e.pointerId); });
canvas.addEventListener("pointerup", () => { drag = null; });
canvas.addEventListener("pointermove", e => {
  if (!drag) return;
  orbit(-(e.clientX - drag[0]) * 0.01, (e.clientY - drag[1]) * 0.01);
  drag = [e.clientX, e.clientY];
  draw(+slider.value);
});
function orbit(azimuth, elevation) {  // as present::orbit: about up, elevation within 85 degrees
  const up = unit(cam.up), off = sub(cam.eye, cam.target), d = norm(off);
  let lift = Math.asin(Math.max(-1, Math.min(1, dot(unit(off), up)))) + elevation;
  lift = Math.max(-85 * Math.PI / 180, Math.min(85 * Math.PI / 180, lift));
  let flat = sub(off, mul(up, dot(off, up)));
  if (norm(flat) < 1e-12 * d) flat = cross(up, [1, 0, 0]);
  flat = unit(flat);
  const side = cross(up, flat);
  const toward = add(mul(flat, Math.cos(azimuth)), mul(side, Math.sin(azimuth)));
  cam.eye = add(cam.target, mul(add(mul(toward, Math.cos(lift)), mul(up, Math.sin(lift))), d));
}
const start = /frame=(\d+)/.exec(location.hash);
if (start) slider.value = Math.min(+start[1], DATA.frames.length - 1);
draw(+slider.value);
)JS";

}  // namespace rigidlab::present
