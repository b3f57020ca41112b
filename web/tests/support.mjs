// Shared by the browser tests: p4track started as a user would, Debian's Chromium driven by
// playwright-core, screenshots kept as test artefacts. Tests wait on conditions; the time-outs
// are ceilings that only catch a hang (a loaded 2-core machine can take a minute to load a page).
export const HANG_MS = 180000;
import { spawn, execFileSync } from 'node:child_process';
import { mkdirSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import { chromium } from 'playwright-core';

export const P4TRACK = process.env.P4TRACK;
export const ARTIFACTS = process.env.P4_ARTIFACTS || join(tmpdir(), 'p4-browser-artifacts');
mkdirSync(ARTIFACTS, { recursive: true });

export function check(condition, message) {
  if (!condition) throw new Error(`check failed: ${message}`);
  console.log(`ok - ${message}`);
}

export function tempDir(name) { return mkdtempSync(join(tmpdir(), `p4-${name}-`)); }
export function removeDir(dir) { rmSync(dir, { recursive: true, force: true }); }

// Runs p4track to completion (simulate, track without UI).
export function p4track(args) {
  return execFileSync(P4TRACK, args, { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] });
}

// Starts p4track with a web UI on a free port; resolves with the process, its URL and its log.
export function startServing(args, marker) {
  const proc = spawn(P4TRACK, [...args, '--port', '0'], { stdio: ['ignore', 'pipe', 'pipe'] });
  const log = [];
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => reject(new Error(`no URL from p4track: ${log.join('')}`)), HANG_MS);
    const onData = chunk => {
      log.push(chunk.toString());
      const m = log.join('').match(new RegExp(`${marker}.*?(http://127\\.0\\.0\\.1:\\d+/)`));
      if (m) { clearTimeout(timer); resolve({ proc, url: m[1], log }); }
    };
    proc.stdout.on('data', onData);
    proc.stderr.on('data', onData);
    proc.on('exit', code => reject(new Error(`p4track exited (${code}): ${log.join('')}`)));
  });
}

export async function stop(proc) {
  if (proc.exitCode !== null) return proc.exitCode;
  const done = new Promise(r => proc.once('exit', code => r(code)));
  proc.kill('SIGINT');
  return done;
}

export async function launchBrowser() {
  return chromium.launch({
    executablePath: process.env.CHROMIUM || '/usr/bin/chromium',
    args: ['--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader'],
  });
}

// A page that fails the test on any script error.
export async function openPage(browser, url, errors) {
  const page = await browser.newPage({ viewport: { width: 1400, height: 900 } });
  page.setDefaultTimeout(HANG_MS);
  page.setDefaultNavigationTimeout(HANG_MS);
  page.on('pageerror', e => errors.push(e.message));
  page.on('console', m => { if (m.type() === 'error') errors.push(m.text()); });
  await page.goto(url);
  return page;
}

// An HTTP client polling the live view as its page does, until stop() is true: the state every
// 50 ms, every camera's picture every other time. counts.requests grows with every answer,
// counts.failed with every request unanswered or answered otherwise than 200 or 204 ("no state
// yet"; a picture also 404, "none yet"); each state goes to onState, when given.
export async function pollLikeThePage(url, cameras, stop, counts, onState) {
  // A request that fails in the network (not by its status: the request or its body) is sent
  // again, up to twice, as a browser resends a GET whose kept-alive connection the server closed
  // as it went out (the server ends a connection after a few requests or seconds; on a loaded
  // machine the two cross more often, and a resend can meet the next close). counts.resent
  // counts those; counts.errors keeps the first few messages.
  const once = path => fetch(`${url}${path}`, { cache: 'no-store' });
  const fail = message => {
    ++counts.failed;
    (counts.errors ||= []).length < 5 && counts.errors.push(message);
  };
  const get = async (path, ok, read) => {
    for (let attempt = 0; ; ++attempt) {
      let status;
      try {
        const r = await once(path);
        status = r.status;
        await read(r);
      } catch (e) {
        if (attempt < 2) {
          counts.resent = (counts.resent || 0) + 1;
          continue;
        }
        ++counts.requests;
        fail(`${path}: ${e.cause?.code || e.message}`);
        return;
      }
      ++counts.requests;
      if (!ok.includes(status)) fail(`${path}: HTTP ${status}`);
      return;
    }
  };
  for (let k = 0; !stop(); ++k) {
    const requests = [get('api/live/state', [200, 204], async r => {
      if (r.status === 200 && onState) onState(await r.json());
      else await r.arrayBuffer();
    })];
    if (k % 2 === 0) {
      for (let i = 0; i < cameras; ++i) requests.push(get(`api/live/camera/${i}.jpg`, [200, 204, 404], r => r.arrayBuffer()));
    }
    await Promise.all(requests);
    await new Promise(r => setTimeout(r, 50));
  }
}
