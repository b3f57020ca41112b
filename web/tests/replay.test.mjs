// The replay page in real headless Chromium: it loads a tracked run, plays, changes speed, jumps
// on the timeline and between preset views, and the ball it draws at a time is where
// trajectory.csv says (and on the screen where the 3D view projects it, in the ball's colour).
import { readFileSync } from 'node:fs';
import { join } from 'node:path';
import { check, tempDir, removeDir, p4track, startServing, stop, launchBrowser, openPage, ARTIFACTS, HANG_MS } from './support.mjs';

const dir = tempDir('replay');
let server, browser;
try {
  p4track(['simulate', '--out', join(dir, 'sim'), '--points', '1', '--seed', '4', '--max-duration', '5']);
  p4track(['track', '--rig', join(dir, 'sim', 'rig.yaml'), '--out', join(dir, 'run'),
    join(dir, 'sim', 'cam0.mp4'), join(dir, 'sim', 'cam1.mp4')]);
  server = await startServing(['replay', join(dir, 'run')], 'replay of');
  browser = await launchBrowser();
  const errors = [];
  const page = await openPage(browser, server.url, errors);
  await page.waitForFunction(() => window.p4replay && window.p4replay.ready, null, { timeout: HANG_MS });

  // A measured row in the middle of the run.
  const rows = readFileSync(join(dir, 'run', 'trajectory.csv'), 'utf8').trim().split('\n').slice(1)
    .map(l => l.split(',').map(Number)).filter(r => r[7] === 1);
  check(rows.length > 100, `the run has ${rows.length} measured rows`);
  const row = rows[Math.floor(rows.length / 2)];
  await page.evaluate(t => window.p4replay.seek(t), row[0]);
  const drawn = await page.evaluate(() => window.p4replay.ballPosition());
  check(drawn !== null, 'the ball is drawn at a measured time');
  const error = Math.hypot(drawn[0] - row[1], drawn[1] - row[2], drawn[2] - row[3]);
  check(error < 1e-4, `the drawn ball is where trajectory.csv puts it at t = ${row[0]} (${(error * 1000).toFixed(3)} mm)`);
  // And it is on the screen in orange, where the view projects it.
  const colour = await page.evaluate(() => {
    const [u, v] = window.p4replay.ballOnScreen();
    const gl = document.querySelector('#view3d canvas');
    const c = document.createElement('canvas');
    c.width = gl.width; c.height = gl.height;
    const ctx = c.getContext('2d');
    ctx.drawImage(gl, 0, 0);
    let best = null;
    for (let dy = -2; dy <= 2; ++dy) for (let dx = -2; dx <= 2; ++dx) {
      const p = ctx.getImageData(Math.round(u) + dx, Math.round(v) + dy, 1, 1).data;
      if (!best || p[0] - p[2] > best[0] - best[2]) best = [p[0], p[1], p[2]];
    }
    return best;
  });
  check(colour[0] > 150 && colour[0] - colour[2] > 80, `the ball's pixels are orange (rgb ${colour})`);
  await page.screenshot({ path: join(ARTIFACTS, 'replay-seek.png') });

  // Play at 1x, then at 4x through the speed control: replay time runs at the chosen speed of the
  // page's own frame clock, however slowly this machine draws frames (conditions, not timers).
  check(rows[rows.length - 1][0] - rows[0][0] > 2.5, 'the run is long enough to play 2 s at 4x');
  const advance = async (speed, span) => {
    await page.selectOption('#speed', String(speed));
    await page.evaluate(t => { window.p4replay.seek(t); window.p4replay.play(); }, rows[0][0]);
    await page.waitForFunction(() => { const c = window.p4replay.clock(); return c.playing && c.wall !== null; }, null, { timeout: HANG_MS });
    const a = await page.evaluate(() => window.p4replay.clock());
    await page.waitForFunction(s => window.p4replay.clock().time >= s, a.time + span, { timeout: HANG_MS });
    const b = await page.evaluate(() => window.p4replay.clock());
    await page.evaluate(() => window.p4replay.pause());
    return (b.time - a.time) / ((b.wall - a.wall) / 1000);
  };
  const rate1 = await advance(1, 0.5), rate4 = await advance(4, 2.0);
  check(await page.evaluate(() => window.p4replay.speed()) === 4, 'the speed control sets 4x');
  check(Math.abs(rate1 - 1) < 0.02 && Math.abs(rate4 - 4) < 0.08,
    `play runs the clock: ${rate1.toFixed(3)} s/s at 1x, ${rate4.toFixed(3)} s/s at 4x`);
  await page.screenshot({ path: join(ARTIFACTS, 'replay-playing.png') });

  // The timeline jumps; the preset views move the camera; the scoreboard is there.
  const box = await page.locator('#timeline').boundingBox();
  await page.mouse.click(box.x + box.width * 0.75, box.y + box.height / 2);
  const jumped = await page.evaluate(() => (window.p4replay.time() - window.p4replay.t0) / (window.p4replay.t1 - window.p4replay.t0));
  check(Math.abs(jumped - 0.75) < 0.02, `a click at 3/4 of the timeline jumps there (${jumped.toFixed(3)})`);
  await page.click('button[data-view="top"]');
  await page.screenshot({ path: join(ARTIFACTS, 'replay-top.png') });
  check((await page.locator('#score .points').count()) === 2, 'the scoreboard shows both players');
  check(errors.length === 0, `no script errors (${errors.join('; ')})`);
} finally {
  if (browser) await browser.close();
  if (server) await stop(server.proc);
  removeDir(dir);
}
