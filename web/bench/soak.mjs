// Soak benchmark (not a test: it runs for half an hour): `p4track track --ui --realtime --loop`
// over a simulated 3-camera match, watched by 20 clients for SOAK_MINUTES (default 30): one real
// Chromium page on the live view and 19 HTTP clients that poll as that page does (the state at
// 20 Hz, every camera's picture at 10 Hz). It prints, and writes as JSON to SOAK_OUT:
//   - memory over time: p4track's resident set every 30 s; "flat" is judged on the growth from
//     the fifth minute (buffers, caches and the encoder are warm by then) to the end;
//   - late frame sets: from the run's own summary (finished more than 3 frame periods behind);
//   - lost events: every client keeps the numbers (`n`) of the events it saw in the state; a
//     number between its first and its last one that it never saw is lost for it;
//   - requests served and failed, and script errors of the page.
// Exit status 1 when a target is missed: memory growth over 5 % after the fifth minute (or
// 20 MB, whichever is larger), a late frame set, a lost event, a failed request or a page error.
//
// Environment: P4TRACK (the binary), CHROMIUM (default /usr/bin/chromium), SOAK_MINUTES,
// SOAK_CLIENTS (default 20), SOAK_PAGE (1, the default: one of the clients is the Chromium page;
// 0: all are HTTP clients), SOAK_OUT (default soak.json in the working folder; p4track's log is
// written beside it, .log).
import os from 'node:os';
import { readdirSync, readFileSync, writeFileSync } from 'node:fs';
import { join } from 'node:path';
import { tempDir, removeDir, p4track, startServing, stop, launchBrowser, openPage, pollLikeThePage } from '../tests/support.mjs';

const minutes = Number(process.env.SOAK_MINUTES || 30);
const nClients = Number(process.env.SOAK_CLIENTS || 20);
const outFile = process.env.SOAK_OUT || 'soak.json';
const withPage = (process.env.SOAK_PAGE || '1') !== '0';
if (!process.env.P4TRACK) throw new Error('set P4TRACK to the p4track binary');
if (!(minutes > 0) || !(nClients >= 1)) throw new Error('SOAK_MINUTES > 0 and SOAK_CLIENTS >= 1');

const log = s => console.log(`[soak ${new Date().toISOString().slice(11, 19)}] ${s}`);
const rssMb = pid => {
  const m = /VmRSS:\s+(\d+) kB/.exec(readFileSync(`/proc/${pid}/status`, 'utf8'));
  return m ? Number(m[1]) / 1024 : NaN;
};

// Chromium raises its own browser and GPU processes' priority (nice -8) where it may (as root,
// on this CI-like machine; a user's browser may not): every process under this one is put
// back at nice 19 (p4track, `except`, keeps its priority), as if the browser ran elsewhere.
function niceDescendants(except) {
  const parent = new Map();
  for (const name of readdirSync('/proc')) {
    if (!/^\d+$/.test(name)) continue;
    try {
      const stat = readFileSync(`/proc/${name}/stat`, 'utf8');
      parent.set(Number(name), Number(stat.slice(stat.lastIndexOf(')') + 2).split(' ')[1]));
    } catch (e) { /* ended meanwhile */ }
  }
  const mine = new Set([process.pid]);
  for (let grew = true; grew;) {
    grew = false;
    for (const [pid, ppid] of parent) if (pid !== except && !mine.has(pid) && mine.has(ppid)) { mine.add(pid); grew = true; }
  }
  for (const pid of mine) {
    if (pid === process.pid) continue;
    let threads = [];
    try { threads = readdirSync(`/proc/${pid}/task`).map(Number); } catch (e) { /* ended */ }
    for (const tid of threads) {  // nice is per thread on Linux
      try { if (os.getPriority(tid) < 19) os.setPriority(tid, 19); } catch (e) { /* ended */ }
    }
  }
}

const dir = tempDir('soak');
let run, browser;
const result = { minutes, clients: nClients, page: withPage, machine: `${os.cpus()[0].model}, ${os.cpus().length} cores` };
try {
  log('simulating 3 cameras, 1280x720 at 60 fps, 6 points');
  p4track(['simulate', '--out', join(dir, 'sim'), '--cameras', '3', '--fps', '60', '--points', '6', '--seed', '5']);
  // Chromium starts before the run (its launch takes a core for seconds; users open the page on
  // a browser that is running already).
  if (withPage) browser = await launchBrowser();
  run = await startServing(['track', '--rig', join(dir, 'sim', 'rig.yaml'), '--out', join(dir, 'run'),
    ...[0, 1, 2].map(c => join(dir, 'sim', `cam${c}.mp4`)), '--ui', '--realtime', '--loop'], 'live view');
  const pid = run.proc.pid;
  log(`p4track ${pid} serving ${run.url}`);
  // The clients stand for tablets and laptops around the table: on this machine they run at the
  // lowest priority (p4track, started first, keeps its own).
  if (os.getPriority() < 19) os.setPriority(19);

  let stopClients = false;
  const counts = { requests: 0, failed: 0 };
  const seen = [];  // per client: event numbers seen
  const poller = () => {
    const numbers = new Set();
    seen.push(numbers);
    return pollLikeThePage(run.url, 3, () => stopClients, counts,
      state => { for (const e of state.events) numbers.add(e.n); });
  };
  const clients = [];
  for (let c = withPage ? 1 : 0; c < nClients; ++c) clients.push(poller());

  // The real page: the live view as a user opens it.
  const pageErrors = [];
  niceDescendants(pid);
  const page = withPage ? await openPage(browser, run.url, pageErrors) : null;
  const pageSeen = new Set();
  if (page) seen.push(pageSeen);

  const memory = [];
  const start = Date.now();
  const end = start + minutes * 60e3;
  let nextSample = start;
  while (Date.now() < end && run.proc.exitCode === null) {
    niceDescendants(pid);
    if (Date.now() >= nextSample) {
      const t = (Date.now() - start) / 60e3;
      memory.push({ minute: Number(t.toFixed(2)), rss_mb: Number(rssMb(pid).toFixed(1)) });
      const states = page ? await page.evaluate(() => window.p4live.states).catch(() => -1) : '-';
      log(`minute ${t.toFixed(1)}: rss ${memory.at(-1).rss_mb} MB, ${counts.requests} requests (${counts.failed} failed), page states ${states}`);
      nextSample += 30e3;
    }
    const events = page ? await page.evaluate(() => (window.p4live.state ? window.p4live.state.events.map(e => e.n) : [])).catch(() => []) : [];
    for (const n of events) pageSeen.add(n);
    await new Promise(r => setTimeout(r, 200));
  }
  if (run.proc.exitCode !== null) throw new Error(`p4track ended early (${run.proc.exitCode}): ${run.log.join('').slice(-2000)}`);
  memory.push({ minute: Number(((Date.now() - start) / 60e3).toFixed(2)), rss_mb: Number(rssMb(pid).toFixed(1)) });
  stopClients = true;
  await Promise.all(clients);
  if (browser) await browser.close();
  browser = null;
  const code = await stop(run.proc);
  const text = run.log.join('');
  run = null;
  writeFileSync(outFile.replace(/\.json$/, '') + '.log', text);  // p4track's own log beside

  const [, sets] = (/(\d+) frame sets \(/.exec(text) || [0, NaN]).map(Number);
  const [, lag, late] = (/worst lag ([\d.]+) ms, (\d+) frame sets late/.exec(text) || [0, NaN, NaN]).map(Number);
  const written = readFileSync(join(dir, 'run', 'events.jsonl'), 'utf8').split('\n').filter(l => l.trim()).length;
  const lost = seen.map(numbers => {
    if (numbers.size === 0) return 0;
    const first = Math.min(...numbers), last = Math.max(...numbers);
    return last - first + 1 - numbers.size;
  });
  const warm = memory.filter(m => m.minute >= Math.min(5, minutes / 2));
  const base = warm.length ? warm[0].rss_mb : memory[0].rss_mb;
  const peak = Math.max(...warm.map(m => m.rss_mb));
  Object.assign(result, {
    exit_code: code, frame_sets: sets, worst_lag_ms: lag, late_frame_sets: late,
    events_written: written, events_seen_per_client_min: Math.min(...seen.map(s => s.size)),
    lost_events_per_client: lost, requests: counts.requests, failed_requests: counts.failed, page_errors: pageErrors,
    memory, rss_growth_mb: Number((peak - base).toFixed(1)),
  });
  writeFileSync(outFile, JSON.stringify(result, null, 2) + '\n');
  const growthOk = peak - base <= Math.max(20, 0.05 * base);
  const lostTotal = lost.reduce((a, b) => a + b, 0);
  console.log(`soak ${minutes} min, ${nClients} clients (${result.machine}): ${sets} frame sets, ` +
    `${late} late (worst lag ${lag} ms); memory ${memory[0].rss_mb} MB at start, ${base} MB at minute ` +
    `${warm.length ? warm[0].minute : 0}, peak ${peak} MB after (growth ${(peak - base).toFixed(1)} MB); ` +
    `${written} events written, ${lostTotal} lost by the clients; ${counts.requests} requests, ${counts.failed} failed; ` +
    `${pageErrors.length} page errors; exit ${code}. Wrote ${outFile}`);
  const ok = code === 0 && growthOk && late === 0 && lostTotal === 0 && counts.failed === 0 && pageErrors.length === 0;
  if (!ok) {
    console.log('soak: a target was missed (memory flat, 0 late frame sets, 0 lost events, 0 failures)');
    process.exitCode = 1;
  }
} finally {
  if (browser) await browser.close();
  if (run) await stop(run.proc);
  removeDir(dir);
}
