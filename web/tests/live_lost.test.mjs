// A network camera that drops and comes back, seen in the live view in real headless Chromium:
// cam0's stream (FFmpeg serving a simulated recording over TCP) ends; its tile is dimmed and says
// so while P4 opens it again and the other camera goes on; when the test serves it again, the
// tile shows the picture again. The test waits on what the page shows, never on a clock.
import { spawn } from 'node:child_process';
import { join } from 'node:path';
import { check, tempDir, removeDir, p4track, startServing, stop, launchBrowser, openPage, ARTIFACTS, HANG_MS } from './support.mjs';

const dir = tempDir('live-lost');
const servers = [];
let run, browser;
// FFmpeg serving a file over TCP at its own pace (forever with `loop`), listening until a client
// connects.
const serve = (file, port, loop) => {
  const args = ['-v', 'error', '-re', ...(loop ? ['-stream_loop', '-1'] : ['-t', '2']), '-i', file,
    '-c', 'copy', '-f', 'mpegts', `tcp://127.0.0.1:${port}?listen=1&listen_timeout=${HANG_MS}`];
  const proc = spawn('ffmpeg', args, { stdio: 'ignore' });
  servers.push(proc);
  return proc;
};
try {
  p4track(['simulate', '--out', join(dir, 'sim'), '--points', '1', '--seed', '5', '--max-duration', '4']);
  const base = 20000 + (process.pid % 20000);
  const cam = k => join(dir, 'sim', `cam${k}.mp4`);
  serve(cam(0), base, false);  // ends after 2 s
  serve(cam(1), base + 1, true);
  run = await startServing(['track', '--rig', join(dir, 'sim', 'rig.yaml'), '--out', join(dir, 'run'), '--ui',
    `tcp://127.0.0.1:${base}`, `tcp://127.0.0.1:${base + 1}`], 'live view');
  browser = await launchBrowser();
  const errors = [];
  const page = await openPage(browser, run.url, errors);
  const note = i => `document.querySelectorAll('.tile .lost-note')[${i}]`;
  await page.waitForFunction(`${note(0)} && !${note(0)}.hidden`, null, { timeout: HANG_MS });
  await page.screenshot({ path: join(ARTIFACTS, 'live_lost.png') });
  const lost = await page.evaluate(() => [window.p4live.state.cameras.map(c => c.lost),
    [...document.querySelectorAll('.tile')].map(t => t.classList.contains('lost'))]);
  check(lost[0][0] && !lost[0][1], 'the state marks cam0 lost, cam1 not');
  check(lost[1][0] && !lost[1][1], 'cam0\'s tile is dimmed and says it is reconnecting');
  const t0 = await page.evaluate(() => window.p4live.state.t);
  await page.waitForFunction(t => window.p4live.state.t > t + 0.5, t0, { timeout: HANG_MS });
  check(true, 'the run goes on with cam1 while cam0 is away');
  serve(cam(0), base, true);  // cam0 is back
  await page.waitForFunction(`${note(0)}.hidden && !window.p4live.state.cameras[0].lost`, null, { timeout: HANG_MS });
  check(!(await page.evaluate(() => document.querySelector('.tile').classList.contains('lost'))), 'cam0 back: its tile is shown again');
  check(/back after [\d.]+ s; tracked again/.test(run.log.join('')), 'p4track says cam0 is back');
  check(errors.filter(e => !e.includes('ERR_CONNECTION')).length === 0, `no script errors (${errors.join('; ')})`);
  const code = await stop(run.proc);
  check(code === 0, `the run ends cleanly on Ctrl-C (exit ${code})`);
} finally {
  if (browser) await browser.close();
  if (run) await stop(run.proc);
  for (const s of servers) s.kill('SIGKILL');
  removeDir(dir);
}
