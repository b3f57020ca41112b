// The virtual table in three.js (paper §4: "a virtual table with the ball"): world frame of
// DESIGN.md — origin at the centre of the playing surface, x along the table (A at x < 0), y
// across, z up; metres. Shared by the live view and the replay.
import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';

export const TABLE = { length: 2.74, width: 1.525, netHeight: 0.1525, netHalfLength: 0.915, floorZ: -0.76, ballRadius: 0.02 };

// Preset viewpoints: [camera position, target].
export const VIEWS = {
  umpire: [[0, -3.3, 1.3], [0, 0, 0]],
  behindA: [[-4.3, 0, 1.6], [0.3, 0, 0]],
  behindB: [[4.3, 0, 1.6], [-0.3, 0, 0]],
  top: [[0, -0.4, 5.2], [0, 0, 0]],
};

export function createTableScene(container, table = TABLE) {
  const renderer = new THREE.WebGLRenderer({ antialias: true, preserveDrawingBuffer: true });
  renderer.setPixelRatio(Math.min(window.devicePixelRatio || 1, 2));
  container.appendChild(renderer.domElement);
  const scene = new THREE.Scene();
  scene.background = new THREE.Color(0x0c0e11);
  const camera = new THREE.PerspectiveCamera(40, 1, 0.05, 100);
  camera.up.set(0, 0, 1);
  const controls = new OrbitControls(camera, renderer.domElement);
  controls.enableDamping = false;

  scene.add(new THREE.HemisphereLight(0xffffff, 0x404040, 1.6));
  const sun = new THREE.DirectionalLight(0xffffff, 1.4);
  sun.position.set(-2, -3, 5);
  scene.add(sun);

  const L = table.length, W = table.width;
  const box = (sx, sy, sz, color, x, y, z) => {
    const m = new THREE.Mesh(new THREE.BoxGeometry(sx, sy, sz), new THREE.MeshLambertMaterial({ color }));
    m.position.set(x, y, z);
    scene.add(m);
    return m;
  };
  box(L, W, 0.03, 0x1f5fa8, 0, 0, -0.015);  // the top, surface at z = 0
  const white = 0xf4f4f4, lz = 0.0008;
  box(L, 0.02, 0.001, white, 0, W / 2 - 0.01, lz);
  box(L, 0.02, 0.001, white, 0, -W / 2 + 0.01, lz);
  box(0.02, W, 0.001, white, L / 2 - 0.01, 0, lz);
  box(0.02, W, 0.001, white, -L / 2 + 0.01, 0, lz);
  box(L, 0.003, 0.001, white, 0, 0, lz);  // centre line
  for (const sx of [-1, 1]) for (const sy of [-1, 1]) {
    box(0.05, 0.05, -table.floorZ - 0.03, 0x222222, sx * (L / 2 - 0.25), sy * (W / 2 - 0.15), (table.floorZ - 0.03) / 2);
  }
  const net = new THREE.Mesh(new THREE.PlaneGeometry(2 * table.netHalfLength, table.netHeight),
    new THREE.MeshBasicMaterial({ color: 0xdddddd, transparent: true, opacity: 0.35, side: THREE.DoubleSide }));
  net.rotation.set(Math.PI / 2, Math.PI / 2, 0);
  net.position.set(0, 0, table.netHeight / 2);
  scene.add(net);
  box(0.004, 2 * table.netHalfLength, 0.012, white, 0, 0, table.netHeight - 0.006);  // the cord
  for (const sy of [-1, 1]) box(0.02, 0.02, table.netHeight, 0x333333, 0, sy * table.netHalfLength, table.netHeight / 2);
  const floor = new THREE.Mesh(new THREE.PlaneGeometry(14, 10), new THREE.MeshLambertMaterial({ color: 0x5a2e22 }));
  floor.position.z = table.floorZ;
  scene.add(floor);

  const ball = new THREE.Mesh(new THREE.SphereGeometry(table.ballRadius, 24, 16),
    new THREE.MeshLambertMaterial({ color: 0xff8c1a, emissive: 0x552200 }));
  ball.visible = false;
  scene.add(ball);
  const trailMax = 400;
  const trailGeometry = new THREE.BufferGeometry();
  trailGeometry.setAttribute('position', new THREE.BufferAttribute(new Float32Array(trailMax * 3), 3));
  trailGeometry.setDrawRange(0, 0);
  const trail = new THREE.Line(trailGeometry, new THREE.LineBasicMaterial({ color: 0xffc266 }));
  scene.add(trail);
  const marks = new THREE.Group();  // bounce marks on the table
  scene.add(marks);

  function resize() {
    const w = container.clientWidth || 640, h = container.clientHeight || 420;
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  function setView(name) {
    const [p, target] = VIEWS[name];
    camera.position.set(...p);
    controls.target.set(...target);
    controls.update();
  }
  function setBall(p) {
    ball.visible = !!p;
    if (p) ball.position.set(p[0], p[1], p[2]);
  }
  function setTrail(points) {
    const n = Math.min(points.length, trailMax);
    const a = trailGeometry.attributes.position.array;
    for (let i = 0; i < n; ++i) {
      const p = points[points.length - n + i];
      a[3 * i] = p[0]; a[3 * i + 1] = p[1]; a[3 * i + 2] = p[2];
    }
    trailGeometry.attributes.position.needsUpdate = true;
    trailGeometry.setDrawRange(0, n);
  }
  function setBounceMarks(points) {
    marks.clear();
    for (const p of points) {
      const m = new THREE.Mesh(new THREE.CircleGeometry(0.02, 16), new THREE.MeshBasicMaterial({ color: 0xffe066 }));
      m.position.set(p[0], p[1], 0.0015);
      marks.add(m);
    }
  }
  // The ball's place on the screen (pixels of the canvas), or null when hidden.
  function ballOnScreen() {
    if (!ball.visible) return null;
    const v = ball.position.clone().project(camera);
    const c = renderer.domElement;
    return [(v.x + 1) / 2 * c.width, (1 - v.y) / 2 * c.height];
  }
  function render() { controls.update(); renderer.render(scene, camera); }
  window.addEventListener('resize', resize);
  resize();
  setView('umpire');
  return { renderer, scene, camera, controls, ball, setView, setBall, setTrail, setBounceMarks, ballOnScreen, render, resize };
}

// Buttons for the preset views.
export function addViewButtons(parent, view) {
  const labels = { umpire: 'Umpire', behindA: 'Behind A', behindB: 'Behind B', top: 'Top' };
  const box = document.createElement('div');
  box.className = 'views';
  for (const [name, label] of Object.entries(labels)) {
    const b = document.createElement('button');
    b.textContent = label;
    b.dataset.view = name;
    b.onclick = () => view.setView(name);
    box.appendChild(b);
  }
  parent.appendChild(box);
}

// The scoreboard: score.json-like {players, score, games, next_server}.
export function renderScore(element, s, players) {
  const names = (s && s.players) || players || ['A', 'B'];
  const score = (s && s.score) || [0, 0], games = (s && s.games) || [0, 0];
  const server = s && s.next_server;
  element.innerHTML = ['A', 'B'].map((p, i) =>
    `<span class="name ${server === p ? 'serving' : ''}">${escapeHtml(names[i])}</span>` +
    `<span class="points">${score[i]}</span><span class="games">(${games[i]})</span>`).join('<span>–</span>');
}

export function escapeHtml(s) {
  return String(s).replace(/[&<>"']/g, c => ({ '&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;', "'": '&#39;' }[c]));
}

export function describeEvent(e) {
  const t = e.t.toFixed(3);
  switch (e.type) {
    case 'bounce': return `${t} bounce ${e.side} (${e.x.toFixed(2)}, ${e.y.toFixed(2)})`;
    case 'hit': return `${t} stroke ${e.player}`;
    case 'serve': return `${t} serve ${e.player}`;
    case 'point': return `${t} point ${e.winner}: ${e.reason} — ${e.score[0]}-${e.score[1]}`;
    default: return `${t} ${e.type}`;
  }
}
