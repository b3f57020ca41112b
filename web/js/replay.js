// The replay of a recorded run: the 3D table from any viewpoint (orbit, zoom, presets), play and
// pause at 0.1x-4x, scrubbing on a timeline marked with bounces, strokes and points, the score as
// it was at each moment, a bounce map of each half and the speed of each shot.
import { createTableScene, addViewButtons, renderScore, escapeHtml, describeEvent, TABLE } from './scene.js';

const $ = id => document.getElementById(id);
const status = $('status');

function parseTrajectory(text) {
  const lines = text.trim().split('\n');
  const header = lines[0].split(',');
  const col = name => header.indexOf(name);
  const ci = ['t', 'x', 'y', 'z', 'vx', 'vy', 'vz', 'measured'].map(col);
  const rows = [];
  for (let i = 1; i < lines.length; ++i) {
    const f = lines[i].split(',');
    if (f.length < header.length) continue;  // a row cut short by a crash
    rows.push(ci.map(k => Number(f[k])));
  }
  return rows;  // [t, x, y, z, vx, vy, vz, measured]
}

const info = await (await fetch('/api/run/info')).json();
const rows = parseTrajectory(await (await fetch('/api/run/trajectory.csv')).text());
const events = info.files.includes('events.jsonl')
  ? (await (await fetch('/api/run/events.jsonl')).text()).split('\n').filter(l => l.trim()).map(l => JSON.parse(l))
  : [];
const finalScore = info.files.includes('score.json') ? await (await fetch('/api/run/score.json')).json() : null;
const players = (finalScore && finalScore.players) || ['A', 'B'];
document.title = `P4 — replay of ${info.name}`;

const t0 = rows.length ? rows[0][0] : 0, t1 = rows.length ? rows[rows.length - 1][0] : 0;
const times = rows.map(r => r[0]);
const view = createTableScene($('view3d'), TABLE);
addViewButtons($('view3d'), view);

// Index of the last row at or before t (binary search).
function rowAt(t) {
  let lo = 0, hi = times.length - 1;
  if (hi < 0 || t < times[0]) return -1;
  while (lo < hi) {
    const mid = (lo + hi + 1) >> 1;
    if (times[mid] <= t) lo = mid; else hi = mid - 1;
  }
  return lo;
}
// The ball at t: rows interpolated linearly; none across a gap of more than 50 ms (no ball).
function ballAt(t) {
  const i = rowAt(t);
  if (i < 0) return null;
  const a = rows[i];
  if (t === a[0]) return [a[1], a[2], a[3]];
  const b = rows[i + 1];
  if (!b || b[0] - a[0] > 0.05) return t - a[0] < 0.02 ? [a[1], a[2], a[3]] : null;
  const f = (t - a[0]) / (b[0] - a[0]);
  return [0, 1, 2].map(k => a[k + 1] + f * (b[k + 1] - a[k + 1]));
}
function speedAt(t) {
  const i = rowAt(t);
  if (i < 0 || t - rows[i][0] > 0.05) return null;
  return Math.hypot(rows[i][4], rows[i][5], rows[i][6]);
}
function trailUntil(t) {
  const points = [];
  for (let i = rowAt(t); i >= 0 && t - rows[i][0] < 0.3; --i) {
    if (i + 1 < rows.length && rows[i + 1][0] - rows[i][0] > 0.05 && points.length) break;
    points.unshift([rows[i][1], rows[i][2], rows[i][3]]);
  }
  return points;
}
function scoreAt(t) {
  let last = null;
  for (const e of events) if (e.type === 'point' && e.t <= t) last = e;
  return last ? { players, score: last.score, games: last.games } : { players, score: [0, 0], games: [0, 0] };
}

// Shot speeds: the fastest the ball went in the 0.15 s after each stroke (the referee's serve
// events name the strokes that were serves).
const serveTimes = new Set(events.filter(e => e.type === 'serve').map(e => e.t.toFixed(4)));
const shots = events.filter(e => e.type === 'hit').map(e => {
  let best = 0;
  for (let i = Math.max(0, rowAt(e.t)); i < rows.length && rows[i][0] < e.t + 0.15; ++i) {
    if (rows[i][0] >= e.t) best = Math.max(best, Math.hypot(rows[i][4], rows[i][5], rows[i][6]));
  }
  return { t: e.t, player: e.player, kind: serveTimes.has(e.t.toFixed(4)) ? 'serve' : 'hit', speed: best };
});
$('shots').innerHTML = '<tr><td>t (s)</td><td>player</td><td>km/h</td></tr>' + shots.map(s =>
  `<tr><td>${s.t.toFixed(2)}</td><td>${escapeHtml(players[s.player === 'B' ? 1 : 0])}${s.kind === 'serve' ? ' (serve)' : ''}</td><td>${(s.speed * 3.6).toFixed(0)}</td></tr>`).join('');

// Bounce maps: each half seen from above, the net at the inner edge.
const bounces = events.filter(e => e.type === 'bounce');
function drawMaps(now) {
  for (const side of ['A', 'B']) {
    const c = $('map' + side), ctx = c.getContext('2d');
    ctx.fillStyle = '#1f5fa8';
    ctx.fillRect(0, 0, c.width, c.height);
    ctx.strokeStyle = '#fff';
    ctx.strokeRect(1, 1, c.width - 2, c.height - 2);
    for (const b of bounces) {
      if (b.side !== side) continue;
      // x: distance from the net across the canvas (net on the inner edge), y: across the table.
      const fromNet = Math.abs(b.x) / (TABLE.length / 2);
      const u = side === 'A' ? (1 - fromNet) * c.width : fromNet * c.width;
      const v = (0.5 - b.y / TABLE.width) * c.height;
      ctx.fillStyle = b.t <= now ? '#ffe066' : '#ffe06640';
      ctx.beginPath();
      ctx.arc(u, v, 3, 0, 2 * Math.PI);
      ctx.fill();
    }
  }
}

// The timeline with its marks.
const timeline = $('timeline');
function drawTimeline(now) {
  const w = timeline.width = timeline.clientWidth, h = timeline.height = timeline.clientHeight;
  const ctx = timeline.getContext('2d');
  ctx.clearRect(0, 0, w, h);
  const x = t => (t1 > t0 ? (t - t0) / (t1 - t0) : 0) * w;
  const colors = { bounce: '#ffe066', hit: '#3cff6e', serve: '#3cff6e', point: '#ff8c1a' };
  for (const e of events) {
    if (!colors[e.type]) continue;
    ctx.fillStyle = colors[e.type];
    const top = e.type === 'point' ? 0 : e.type === 'bounce' ? h / 3 : 2 * h / 3;
    ctx.fillRect(x(e.t), top, e.type === 'point' ? 3 : 1, h / 3);
  }
  ctx.fillStyle = '#fff';
  ctx.fillRect(x(now) - 1, 0, 2, h);
}
timeline.addEventListener('click', ev => {
  const r = timeline.getBoundingClientRect();
  seek(t0 + (ev.clientX - r.left) / r.width * (t1 - t0));
});

let now = t0, playing = false, speed = 1, lastWall = null;
const scrub = $('scrub');
scrub.min = t0; scrub.max = t1;

function show() {
  view.setBall(ballAt(now));
  view.setTrail(trailUntil(now));
  view.setBounceMarks(bounces.filter(b => b.t <= now && now - b.t < 1.5).map(b => [b.x, b.y]));
  const v = speedAt(now);
  $('ballspeed').textContent = v === null ? '–' : `${(v * 3.6).toFixed(0)} km/h`;
  renderScore($('score'), scoreAt(now), players);
  $('time').textContent = `${(now - t0).toFixed(3)} s`;
  scrub.value = now;
  drawTimeline(now);
  drawMaps(now);
  $('events').innerHTML = events.filter(e => e.t <= now).slice(-10).reverse()
    .map(e => `<li class="${e.type}">${escapeHtml(describeEvent(e))}</li>`).join('');
  view.render();
}
function seek(t) { now = Math.min(Math.max(t, t0), t1); show(); }
function play() { if (now >= t1) now = t0; playing = true; lastWall = null; $('play').textContent = 'Pause'; }
function pause() { playing = false; $('play').textContent = 'Play'; }
function setSpeed(s) { speed = Number(s); $('speed').value = String(s); }

$('play').onclick = () => (playing ? pause() : play());
$('speed').onchange = e => setSpeed(e.target.value);
scrub.oninput = () => { pause(); seek(Number(scrub.value)); };
window.addEventListener('keydown', e => { if (e.code === 'Space') { e.preventDefault(); playing ? pause() : play(); } });

function frame(wall) {
  if (playing) {
    if (lastWall !== null) now += (wall - lastWall) / 1000 * speed;
    lastWall = wall;
    if (now >= t1) { now = t1; pause(); }
    show();
  } else {
    view.render();
  }
  requestAnimationFrame(frame);
}

// For tests and scripts: the replay's controls and what it draws.
window.p4replay = {
  ready: true, t0, t1, rows: rows.length, events: events.length,
  seek, play, pause, setSpeed,
  time: () => now, speed: () => speed, playing: () => playing,
  clock: () => ({ time: now, wall: lastWall, playing }),
  ballPosition: () => (view.ball.visible ? [view.ball.position.x, view.ball.position.y, view.ball.position.z] : null),
  ballOnScreen: () => view.ballOnScreen(),
  score: () => scoreAt(now),
  setView: name => { view.setView(name); view.render(); },
};
status.textContent = `${info.name}: ${rows.length} rows, ${events.length} events, ${(t1 - t0).toFixed(1)} s`;
show();
requestAnimationFrame(frame);
