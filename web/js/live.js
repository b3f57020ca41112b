// The live view (paper Figure 6): each camera's picture with the tracker's ROI (red), candidate
// regions (grey; the accepted ball green) and the epipolar lines of the ball seen by the other
// cameras (yellow); the 3D table with the ball and its trail; speed, score and the last events.
// Pictures and state are polled: a slow client only gets fewer of them.
import { createTableScene, addViewButtons, renderScore, escapeHtml, describeEvent } from './scene.js';

const status = document.getElementById('status');
const p4live = { tiles: 0, states: 0, pictures: 0, renders: 0, state: null };
window.p4live = p4live;

const config = await (await fetch('/api/live/config')).json();
const tiles = config.cameras.map((cam, i) => {
  const tile = document.createElement('div');
  tile.className = 'tile';
  tile.dataset.camera = cam.name;
  tile.innerHTML = `<img alt="${escapeHtml(cam.name)}"><canvas></canvas><span class="label">${escapeHtml(cam.name)}</span><span class="lost-note" hidden>no picture: reconnecting…</span>`;
  document.getElementById('tiles').appendChild(tile);
  const img = tile.querySelector('img'), canvas = tile.querySelector('canvas');
  canvas.width = cam.width;
  canvas.height = cam.height;
  img.style.aspectRatio = `${cam.width} / ${cam.height}`;
  // Each picture is asked for when the last one has arrived (and 80 ms later).
  let n = 0;
  const next = () => setTimeout(() => { img.src = `/api/live/camera/${i}.jpg?n=${++n}`; }, 80);
  img.onload = () => { ++p4live.pictures; next(); };
  img.onerror = () => setTimeout(next, 400);
  next();
  return { cam, canvas, ctx: canvas.getContext('2d') };
});
p4live.tiles = tiles.length;

const t = config.table;
const view = createTableScene(document.getElementById('view3d'), {
  length: t.length, width: t.width, netHeight: t.net_height, netHalfLength: t.net_half_length,
  floorZ: t.floor_z, ballRadius: t.ball_radius,
});
addViewButtons(document.getElementById('view3d'), view);
// The 3D view is drawn when something changed (a new state, the viewpoint moved, the window),
// not at the screen's rate: a laptop that tracks and shows this page keeps more of its cores
// for the tracking.
let dirty = true;
view.controls.addEventListener('change', () => { dirty = true; });
window.addEventListener('resize', () => { dirty = true; });
p4live.view = view;

// Calibration markers (with --layout): where the rig projects them (magenta) and where the
// picture shows them (cyan); their mean corner distance says how well the calibration fits.
let markers = [];
p4live.markerError = [];
async function pollMarkers() {
  try { markers = await (await fetch('/api/live/markers', { cache: 'no-store' })).json(); } catch (e) {}
  setTimeout(pollMarkers, 500);
}
function drawMarkers(i) {
  const { ctx, canvas } = tiles[i];
  const projected = (config.markers && config.markers[i]) || [];
  const found = markers[i] || [];
  const quad = (corners, colour, dash) => {
    ctx.strokeStyle = colour;
    ctx.setLineDash(dash);
    ctx.beginPath();
    corners.forEach(([u, v], k) => (k ? ctx.lineTo(u, v) : ctx.moveTo(u, v)));
    ctx.closePath();
    ctx.stroke();
    ctx.setLineDash([]);
  };
  let sum = 0, n = 0;
  for (const m of projected) quad(m.corners, '#ff4fd8', [6, 4]);
  for (const m of found) {
    quad(m.corners, '#33e0ff', []);
    const p = projected.find(q => q.id === m.id);
    if (p) m.corners.forEach(([u, v], k) => { sum += Math.hypot(u - p.corners[k][0], v - p.corners[k][1]); ++n; });
  }
  p4live.markerError[i] = n ? sum / n : null;
  if (projected.length) {
    const label = tiles[i].canvas.parentElement.querySelector('.label');
    label.textContent = `${tiles[i].cam.name} — markers: ${found.length} found` + (n ? `, ${(sum / n).toFixed(1)} px from the rig's` : '');
  }
}

function drawOverlay(tile, cam) {
  const { ctx, canvas } = tile;
  ctx.clearRect(0, 0, canvas.width, canvas.height);
  // A live camera that dropped: its last picture dimmed, its name saying so until it is back.
  const lost = !!(cam && cam.lost);
  canvas.parentElement.classList.toggle('lost', lost);
  canvas.parentElement.querySelector('.lost-note').hidden = !lost;
  ctx.lineWidth = Math.max(2, canvas.width / 400);
  drawMarkers(tiles.indexOf(tile));
  if (!cam) return;
  ctx.strokeStyle = '#ffd400';
  for (const line of cam.epipolar) {
    ctx.beginPath();
    line.forEach(([u, v], k) => (k ? ctx.lineTo(u, v) : ctx.moveTo(u, v)));
    ctx.stroke();
  }
  if (cam.roi) {
    ctx.strokeStyle = cam.fell_back ? '#ff5050a0' : '#ff3030';
    const [x0, y0, x1, y1] = cam.roi;
    ctx.strokeRect(x0, y0, x1 - x0, y1 - y0);
  }
  for (const d of cam.detections) {
    ctx.strokeStyle = d.accepted ? '#3cff6e' : '#bbbbbb';
    ctx.beginPath();
    ctx.arc(d.u, d.v, Math.max(d.d, 6) / 2 + 3, 0, 2 * Math.PI);
    ctx.stroke();
  }
}

async function poll() {
  try {
    const r = await fetch('/api/live/state', { cache: 'no-store' });
    if (r.status === 200) {
      const s = await r.json();
      if (!p4live.state || s.t !== p4live.state.t) dirty = true;
      p4live.state = s;
      ++p4live.states;
      status.textContent = `t = ${s.t.toFixed(2)} s`;
      s.cameras.forEach((cam, i) => tiles[i] && drawOverlay(tiles[i], cam));
      view.setBall(s.ball ? [s.ball.x, s.ball.y, s.ball.z] : null);
      view.setTrail(s.trail);
      document.getElementById('speed').textContent = s.ball ? `${(s.ball.speed * 3.6).toFixed(0)} km/h` : '–';
      if (s.score) renderScore(document.getElementById('score'), s.score, config.players);
      document.getElementById('events').innerHTML = s.events.slice().reverse()
        .map(e => `<li class="${e.type}">${escapeHtml(describeEvent(e))}</li>`).join('');
    } else {
      status.textContent = 'waiting for the first frames…';
    }
  } catch (e) {
    status.textContent = 'connection lost — retrying';
  }
  setTimeout(poll, 50);
}
renderScore(document.getElementById('score'), null, config.players);
poll();
if (config.markers && config.markers.length) pollMarkers();
(function frame() {
  if (dirty) { dirty = false; view.render(); ++p4live.renders; }
  requestAnimationFrame(frame);
})();
