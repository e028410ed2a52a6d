// The design studio in a real browser (Debian's chromium driven by Playwright): the page
// loads cleanly, a dragged control point changes the gauges and the page's numbers equal
// the CLI's, a search equals the CLI's one-thread run, bad input is reported and loses
// nothing, undo/redo and exports work; speeds are measured and written to
// test-results/speed.json (docs/studio.md reports them; they are not asserted).

import { test, before, after } from 'node:test';
import assert from 'node:assert/strict';
import { spawn, execFileSync } from 'node:child_process';
import { mkdtempSync, writeFileSync, readFileSync, mkdirSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, dirname } from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const studioDir = join(dirname(fileURLToPath(import.meta.url)), '..');
const repo = join(studioDir, '..');
// The cargo profile whose build the tests run: tests/run_all.sh sets `ci` (the Rust tests'
// build, reused); by hand, `release`.
const profile = process.env.NONCIRC_PROFILE || 'release';
const cli = join(repo, 'target', profile, 'noncirc');
const results = join(studioDir, 'test-results');
const tmp = mkdtempSync(join(tmpdir(), 'noncirc-studio-'));
mkdirSync(results, { recursive: true });

let server, browser, page;
const problems = [];
const speed = {};

/** The CLI's output for `args`, as JSON. */
function cliJson(...args) {
  return JSON.parse(execFileSync(cli, [...args, '--format', 'json'], { encoding: 'utf8', stdio: ['ignore', 'pipe', 'pipe'] }));
}

/** The CLI's JSON output for `args` when it exits with one of `codes` (a fit or a repair
 *  that misses exits 3, its summary printed). */
function cliJsonExit(codes, ...args) {
  try {
    return cliJson(...args);
  } catch (e) {
    if (!codes.includes(e.status)) throw e;
    return JSON.parse(e.stdout);
  }
}

/** `value` without its `seconds` fields (the page's clock is not the CLI's). */
function withoutSeconds(value) {
  if (Array.isArray(value)) return value.map(withoutSeconds);
  if (value === null || typeof value !== 'object') return value;
  return Object.fromEntries(Object.entries(value).filter(([k]) => k !== 'seconds').map(([k, v]) => [k, withoutSeconds(v)]));
}

/** Writes `text` to a temporary scene file and returns its path. */
function sceneFile(name, text) {
  const path = join(tmp, name);
  writeFileSync(path, text);
  return path;
}

/**
 * Asserts that two JSON values agree: the same keys and strings, numbers within `rel` of
 * each other (relative to the larger, or to `floor` where both are smaller: a quantity
 * crossing zero). Returns the largest relative difference seen.
 */
function assertClose(a, b, rel, path = '', floor = 1e-300) {
  if (typeof a === 'number' && typeof b === 'number') {
    const d = Math.abs(a - b) / Math.max(Math.abs(a), Math.abs(b), floor);
    assert.ok(a === b || d <= rel, `${path}: ${a} against ${b} (relative ${d})`);
    return a === b ? 0 : d;
  }
  if (a === null || b === null || typeof a !== 'object') {
    assert.deepEqual(a, b, path);
    return 0;
  }
  assert.deepEqual(Object.keys(a).sort(), Object.keys(b).sort(), `${path}: keys`);
  return Math.max(0, ...Object.keys(a).map((k) => assertClose(a[k], b[k], rel, `${path}.${k}`, floor)));
}

/** Median, least, 90th percentile and largest of a list. */
function spread(xs) {
  const s = [...xs].sort((p, q) => p - q);
  const at = (q) => s[Math.min(s.length - 1, Math.floor(q * s.length))];
  return { median: at(0.5), min: s[0], p90: at(0.9), max: s[s.length - 1], n: s.length };
}

const pageScene = () => page.evaluate(() => window.studio.state.design.toToml());
const pageReport = () => page.evaluate(() => window.studio.state.out.report);

before(async () => {
  server = spawn(cli, ['studio', '--port', '0'], { stdio: ['ignore', 'pipe', 'inherit'] });
  const url = await new Promise((resolve, reject) => {
    server.stdout.on('data', (d) => { const m = String(d).match(/http:\/\/[0-9.:]+\//); if (m) resolve(m[0]); });
    server.on('exit', (code) => reject(new Error(`noncirc studio exited with ${code}`)));
  });
  browser = await chromium.launch({
    executablePath: process.env.CHROMIUM ?? '/usr/bin/chromium',
    args: ['--no-sandbox', '--disable-gpu', '--enable-unsafe-swiftshader', '--disable-quic', '--no-first-run', '--disable-background-networking', '--disable-component-update', '--disable-sync'],
  });
  const context = await browser.newContext({ viewport: { width: 1500, height: 1100 }, acceptDownloads: true });
  page = await context.newPage();
  // SwiftShader's note on reading a WebGL canvas back is the 3D view's test reading its
  // pixels, not the page's doing.
  const readBack = /GL Driver Message .*GPU stall due to ReadPixels/;
  page.on('console', (m) => { if ((m.type() === 'error' || m.type() === 'warning') && !readBack.test(m.text())) problems.push(`${m.type()}: ${m.text()}`); });
  page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
  page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()}`));
  // Nothing may come from the network: every request stays on the studio's server.
  page.on('request', (r) => { if (!r.url().startsWith(url) && !r.url().startsWith('data:') && !r.url().startsWith('blob:')) problems.push(`outside request: ${r.url()}`); });
  await page.goto(url);
  await page.waitForSelector('body[data-ready=true]', { timeout: 30000 });
});

after(async () => {
  writeFileSync(join(results, 'speed.json'), JSON.stringify(speed, null, 2) + '\n');
  console.log(JSON.stringify(speed, null, 2));
  await browser?.close();
  server?.kill();
});

test('the page loads the default design and its numbers are the CLI\'s', async () => {
  const report = await pageReport();
  const expected = cliJson('evaluate', sceneFile('loaded.toml', await pageScene()));
  speed.loaded_max_relative_difference = assertClose(report, expected, 1e-12);
  await page.screenshot({ path: join(results, 'studio_loaded.png'), fullPage: true });
  assert.equal(await page.locator('.gauge').count(), expected.objectives.length);
});

test('a control point dragged with the mouse changes the gauges, and the page equals the CLI', async () => {
  const before = await pageReport();
  const handle = page.locator('[data-point="7"]');
  const box = await handle.boundingBox();
  const [x, y] = [box.x + box.width / 2, box.y + box.height / 2];
  const timingsBefore = await page.evaluate(() => window.studio.state.timings.length);
  // Point 7 sits at 225°: outward is down and to the left on the screen. The pointer goes
  // 20 px along the ray in 40 moves; the radius follows by the plot's scale (px per mm).
  const scale = await page.evaluate(() => {
    const svg = document.getElementById('polar');
    return svg.getScreenCTM().a * Number(svg.dataset.scale);
  });
  await page.mouse.move(x, y);
  await page.mouse.down();
  const step = Math.SQRT1_2;
  for (let i = 1; i <= 40; i++) await page.mouse.move(x - i * step / 2, y + i * step / 2);
  await page.mouse.up();
  const after = await pageReport();
  const radius = await page.evaluate(() => window.studio.state.design.get('gear.curve.radii_mm[7]'));
  // Within a pixel: the browser rounds pointer positions.
  assert.ok(Math.abs(radius - (12 + 20 / scale)) < 1 / scale, `radius 7 is ${radius} mm, expected ${12 + 20 / scale}`);
  const module = (r) => r.objectives.find((o) => o.name === 'module').value;
  assert.notEqual(module(after), module(before), 'the module changed');
  for (const o of after.objectives) {
    const shown = await page.locator(`[data-objective="${o.name}"] .value-text`).textContent();
    assert.equal(Number(shown), +o.value.toPrecision(4), `the ${o.name} gauge shows the new value`);
  }
  const expected = cliJson('evaluate', sceneFile('dragged.toml', await pageScene()));
  speed.dragged_max_relative_difference = assertClose(after, expected, 1e-12);
  const timings = await page.evaluate((n) => window.studio.state.timings.slice(n), timingsBefore);
  assert.ok(timings.length >= 5, `the drag updated the design ${timings.length} times`);
  speed.drag_update_ms = spread(timings);
});

test('undo and redo step through the design\'s history', async () => {
  const dragged = await pageScene();
  await page.click('#undo');
  assert.equal(await page.evaluate(() => window.studio.state.design.get('gear.curve.radii_mm[7]')), 12);
  await page.click('#redo');
  assert.equal(await pageScene(), dragged);
});

test('the scene menu names where the design came from and marks it modified; Ctrl+Shift+Z redoes', async () => {
  const original = await pageScene();
  const menu = () => page.locator('#builtin option:checked').textContent();
  const noFocus = () => page.evaluate(() => document.activeElement?.blur());
  // The built-in afresh (the tests above left their edits).
  await page.selectOption('#builtin', 'two-arm');
  await page.selectOption('#builtin', 'paper-search');
  const scene = await pageScene();
  assert.equal(await menu(), 'paper-search');
  const field = page.locator('input[data-path="train.arm_length_mm"]');
  const length = Number(await field.inputValue());
  await field.fill(String(length + 1));
  await field.press('Enter');
  assert.equal(await menu(), 'paper-search (modified)');
  await noFocus();
  await page.keyboard.press('Control+z');
  assert.equal(await pageScene(), scene);
  assert.equal(await menu(), 'paper-search');
  await page.keyboard.press('Control+Shift+Z');
  assert.equal(await page.evaluate(() => window.studio.state.design.get('train.arm_length_mm')), length + 1);
  assert.equal(await menu(), 'paper-search (modified)');
  await page.keyboard.press('Control+z');
  // A file: the menu names it; undo goes back to the built-in.
  await page.setInputFiles('#open', { name: 'mine.toml', mimeType: 'text/plain', buffer: Buffer.from(scene) });
  await page.waitForFunction(() => document.querySelector('#builtin option:checked').textContent === 'file: mine.toml');
  await noFocus();
  await page.keyboard.press('Control+z');
  assert.equal(await menu(), 'paper-search');
  assert.equal(await pageScene(), scene);
  // Back through the two built-ins to the design the tests above left.
  await page.keyboard.press('Control+z');
  await page.keyboard.press('Control+z');
  assert.equal(await pageScene(), original);
});

test('the file buttons are in the Tab order and open with Enter or Space; no accessible name holds markup', async () => {
  // Each file input records the clicks that would open its chooser (the headless browser
  // shows none; waiting for Playwright's "filechooser" event proved flaky under load).
  await page.evaluate(() => {
    window.fileClicks = [];
    for (const input of document.querySelectorAll('input[type=file]')) {
      input.addEventListener('click', (ev) => { window.fileClicks.push(input.id); ev.preventDefault(); });
    }
  });
  await page.focus('#builtin');
  await page.keyboard.press('Tab');
  assert.equal(await page.evaluate(() => document.activeElement.textContent.trim()), 'Open…');
  await page.keyboard.press('Enter');
  for (const id of ['target-open', 'search-resume']) {
    const label = page.locator(`label.button:has(#${id})`);
    assert.equal(await label.getAttribute('tabindex'), '0', id);
    await label.press(' ');
  }
  assert.deepEqual(await page.evaluate(() => window.fileClicks), ['open', 'target-open', 'search-resume']);
  const marked = await page.evaluate(() => [...document.querySelectorAll('[aria-label]')]
    .map((e) => e.getAttribute('aria-label')).filter((n) => /[<>]/.test(n)));
  assert.deepEqual(marked, []);
});

test('an emptied picking rate is unset: the carrier speed sets the working speed again', async () => {
  const scene = await pageScene();
  const rate = page.locator('input[data-path="train.picks_per_minute"]');
  const rpm = page.locator('input[data-path="train.carrier_speed_rpm"]');
  await rate.fill('240');
  await rate.press('Enter');
  await page.waitForFunction(() => /picks_per_minute = 240/.test(window.studio.state.design.toToml()));
  assert.ok(await rpm.isDisabled(), 'the rate sets the carrier speed');
  await rate.fill('');
  await rate.press('Enter');
  await page.waitForFunction(() => !/picks_per_minute/.test(window.studio.state.design.toToml()));
  assert.ok(!(await rpm.isDisabled()));
  assert.equal(await rate.getAttribute('placeholder'), 'unset');
  assert.equal(await page.locator('.row:has(input[data-path="train.picks_per_minute"]) .msg').textContent(), '');
  assert.equal(await pageScene(), scene);
});

test('typed text is evaluated when complete (Enter or leaving the field), never a prefix; an arrow key steps at once', async () => {
  const scene = await pageScene();
  const length = page.locator('input[data-path="train.arm_length_mm"]');
  const lengthMessage = page.locator('.row:has(input[data-path="train.arm_length_mm"]) .msg');
  const original = await length.inputValue();
  await length.fill('');
  await length.pressSequentially('-50');
  // No "-5 is out of range" on the way, no evaluation.
  assert.equal(await lengthMessage.textContent(), '');
  assert.equal(await pageScene(), scene);
  await length.press('Enter');
  assert.match(await lengthMessage.textContent(), /= -50 is out of range/);
  assert.equal(await pageScene(), scene);
  const arms = page.locator('input[data-path="train.arms"]');
  await arms.fill('');
  await arms.pressSequentially('2.5');
  // No two-arm design on the way to 2.5.
  assert.equal(await page.evaluate(() => window.studio.state.out.report.events.arms.length), 3);
  await arms.press('Tab');
  assert.match(await page.locator('.row:has(input[data-path="train.arms"]) .msg').textContent(), /train\.arms/);
  assert.equal(await pageScene(), scene);
  for (const [field, value] of [[length, original], [arms, '3']]) {
    await field.fill(value);
    await field.press('Enter');
  }
  assert.equal(await pageScene(), scene);
  await length.focus();
  await page.keyboard.press('ArrowUp');
  assert.equal(await page.evaluate(() => window.studio.state.design.get('train.arm_length_mm')), Number(original) + 1);
  await page.keyboard.press('ArrowDown');
  assert.equal(await pageScene(), scene);
});

test('the gauges read at a glance (colour, margin, off-scale arrows) and stay in view while the train is edited', async () => {
  const report = await pageReport();
  const missed = report.objectives.filter((o) => o.violation > 0);
  assert.ok(missed.length > 0, 'the design misses an objective');
  for (const o of report.objectives) {
    const g = page.locator(`[data-objective="${o.name}"]`);
    const cls = await g.getAttribute('class');
    assert.equal(cls.includes('missed'), o.violation > 0, o.name);
    // The margin in its unit, signed.
    const margin = await g.locator('.margin').textContent();
    assert.match(margin, new RegExp(`^margin ${o.margin >= 0 ? '\\+' : '−'}`), `${o.name}: ${margin}`);
    // An off-scale marker carries an arrow, and only then.
    const arrow = await g.locator('.offscale').textContent();
    assert.equal(arrow !== '', /off-(low|high)/.test(cls), `${o.name}: ${cls} '${arrow}'`);
  }
  const red = await page.locator(`[data-objective="${missed[0].name}"] .value`).evaluate((e) => getComputedStyle(e).backgroundColor);
  assert.equal(red, 'rgb(198, 40, 40)');
  await page.setViewportSize({ width: 1280, height: 800 });
  try {
    await page.locator('input[data-path="train.gamma0_deg"]').scrollIntoViewIfNeeded();
    await page.locator('#f-agronomy-housing-margin-mm').scrollIntoViewIfNeeded();
    const box = await page.locator('#gauges').boundingBox();
    assert.ok(box.y >= 0 && box.y < 800 - 100, `the gauges are at y = ${box.y}`);
  } finally {
    await page.setViewportSize({ width: 1500, height: 1100 });
    await page.evaluate(() => window.scrollTo(0, 0));
  }
});

test('constraints typed on one line become gauges with the CLI\'s values, count in the verdict, and go when cleared', async () => {
  const field = page.locator('#constraints');
  const before = await page.locator('#gauges .gauge').count();
  await field.fill('picking_height_mm <= -90;  loop_width_mm >= 1000');
  await field.press('Enter');
  const report = await pageReport();
  assert.deepEqual(report.constraints.map((c) => c.label), ['picking_height_mm <= -90', 'loop_width_mm >= 1000']);
  const expected = cliJson('evaluate', sceneFile('constrained.toml', await pageScene()));
  assertClose(report, expected, 1e-12);
  assert.equal(await page.locator('#gauges .gauge').count(), before + 2);
  for (const c of expected.constraints) {
    const g = page.locator(`[data-constraint="${c.label}"]`);
    assert.equal(Number(await g.locator('.value-text').textContent()), +c.value.toPrecision(4), c.label);
    assert.equal((await g.getAttribute('class')).includes('missed'), c.violation > 0, c.label);
  }
  // No loop is a metre wide: that gauge is missed, and the verdict counts it.
  assert.ok(expected.constraints[1].violation > 0);
  const met = expected.objectives.filter((o) => o.violation === 0).length + expected.constraints.filter((c) => c.violation === 0).length;
  assert.equal(await page.locator('#verdict').textContent(), `${met} of ${before + 2} met (2 constraints)`);
  await page.locator('#judge').screenshot({ path: join(results, 'studio_constraints.png') });
  // A misspelt name is refused beside the field, naming the nearest, and the design stays.
  await field.fill('loop_widht_mm <= 50');
  await field.press('Enter');
  assert.match(await page.locator('#constraints ~ .msg').textContent(), /loop_width_mm/);
  assert.equal((await pageReport()).constraints.length, 2);
  await field.fill('');
  await field.press('Enter');
  assert.equal((await pageReport()).constraints.length, 0);
  assert.equal(await page.locator('#gauges .gauge').count(), before);
  assert.equal(await field.getAttribute('aria-invalid'), 'false');
});

test('a plot zooms around the pointer, pans when zoomed, reads out the point under it and shows it whole on a double click', async () => {
  const svg = page.locator('#mechanism');
  const full = await svg.getAttribute('viewBox');
  // The pointer at the sun's centre, (0, 0) mm, to the pixel; `under` is the data point
  // exactly under it.
  const centre = await page.evaluate(() => window.studio.toScreen('mechanism', [0, 0]));
  const at = { x: Math.round(centre.x), y: Math.round(centre.y) };
  await page.mouse.move(at.x, at.y);
  const under = await page.evaluate(({ x, y }) => {
    const svg = document.getElementById('mechanism');
    const pt = svg.createSVGPoint(); pt.x = x; pt.y = y;
    const p = pt.matrixTransform(svg.getScreenCTM().inverse());
    return [svg.axesCache.ix(p.x), svg.axesCache.iy(p.y)];
  }, at);
  const readout = page.locator('#mechanism ~ figcaption .readout, figure:has(#mechanism) .readout');
  const read = (await readout.textContent()).match(/^x \(mm\) (\S+), y \(mm\) (\S+)$/);
  assert.ok(read && Math.abs(Number(read[1])) < 2 && Math.abs(Number(read[2])) < 2, `readout '${read?.[0]}'`);
  for (let i = 0; i < 6; i++) await page.mouse.wheel(0, -100);
  await page.waitForFunction((f) => document.getElementById('mechanism').getAttribute('viewBox') !== f, full);
  const [, , w] = (await svg.getAttribute('viewBox')).split(' ').map(Number);
  assert.ok(Math.abs(w - 520 / 1.25 ** 6) < 0.01, `zoomed to a width of ${w}`);
  // Zoomed around the pointer: the point under it is still under it.
  const still = await page.evaluate((p) => window.studio.toScreen('mechanism', p), under);
  assert.ok(Math.hypot(still.x - at.x, still.y - at.y) < 0.5, `moved by ${still.x - at.x}, ${still.y - at.y}`);
  // A drag pans: the point follows the pointer.
  await page.mouse.down();
  await page.mouse.move(at.x + 40, at.y + 25, { steps: 5 });
  await page.mouse.up();
  const panned = await page.evaluate((p) => window.studio.toScreen('mechanism', p), under);
  assert.ok(Math.hypot(panned.x - at.x - 40, panned.y - at.y - 25) < 0.5, `panned to ${panned.x - at.x}, ${panned.y - at.y}`);
  await svg.dblclick({ position: { x: 20, y: 20 } });
  assert.equal(await svg.getAttribute('viewBox'), full);
});

test('the guide follows the objective chosen, and names every missed one', async () => {
  const report = await pageReport();
  const missed = report.objectives.filter((o) => o.violation > 0).map((o) => o.name);
  assert.equal(await page.locator('#guide-missed').textContent(), missed.length ? `missed: ${missed.join(', ')}` : 'every objective met');
  const train = ['train.phi0_deg', 'train.beta0_deg', 'train.arm_length_mm', 'train.pusher_offset_mm', 'train.gamma0_deg'];
  const texts = () => page.evaluate((paths) => paths.map((p) => document.querySelector(`.row [data-guide="${p}"]`).textContent), train);
  await page.selectOption('#guide-by', 'picking_angle');
  assert.equal(await page.locator('#guide-head').textContent(), 'guide: picking_angle');
  // The picking angle turns with the arm's installation angle: not "no effect" on every
  // train parameter, as the module (which the train does not move) would say.
  const picking = await texts();
  assert.ok(picking.some((t) => /raise it|lower it/.test(t)), picking.join(' | '));
  await page.selectOption('#guide-by', 'module');
  assert.ok((await texts()).every((t) => /no effect/.test(t)), (await texts()).join(' | '));
  await page.selectOption('#guide-by', '');
  assert.match(await page.locator('#guide-head').textContent(), /^guide: /);
});

test('a bad value in a field is reported beside it, kept as typed, and the design stays', async () => {
  const scene = await pageScene();
  const field = page.locator('input[data-path="train.arm_length_mm"]');
  await field.fill('-5');
  await field.press('Enter');
  const message = page.locator('.row:has(input[data-path="train.arm_length_mm"]) .msg');
  assert.match(await message.textContent(), /train\.arm_length_mm \(S\) = -5 is out of range/);
  assert.equal(await field.inputValue(), '-5');
  assert.equal(await pageScene(), scene);
  await field.fill('145');
  await field.press('Enter');
  assert.equal(await message.textContent(), '');
  assert.equal(await pageScene(), scene);
});

test('a scene file that does not parse, or that the model refuses, gives the message and keeps the design', async () => {
  const scene = await pageScene();
  const bad = readFileSync(join(repo, 'scenes/paper.toml'), 'utf8').replace('phi0_deg = 86', 'phi0_deg = "86"');
  await page.setInputFiles('#open', { name: 'bad.toml', mimeType: 'text/plain', buffer: Buffer.from(bad) });
  await page.waitForSelector('#file-error:not([hidden])');
  assert.match(await page.locator('#file-error').textContent(), /bad\.toml: line \d+: key 'train\.phi0_deg'/);
  assert.equal(await pageScene(), scene);
  const refused = readFileSync(join(repo, 'scenes/paper.toml'), 'utf8').replace('arm_length_mm = 145', 'arm_length_mm = -145');
  await page.setInputFiles('#open', { name: 'refused.toml', mimeType: 'text/plain', buffer: Buffer.from(refused) });
  await page.waitForFunction(() => /arm_length_mm/.test(document.getElementById('file-error').textContent));
  assert.match(await page.locator('#file-error').textContent(), /train\.arm_length_mm \(S\) = -145 is out of range/);
  assert.equal(await pageScene(), scene);
});

test('exported pitch curves are the CLI\'s files', async () => {
  const downloads = [];
  page.on('download', (d) => downloads.push(d));
  await page.click('#export-pitch');
  await page.waitForFunction(() => true);
  for (let i = 0; i < 50 && downloads.length < 2; i++) await page.waitForTimeout(100);
  assert.deepEqual(downloads.map((d) => d.suggestedFilename()).sort(), ['pitch_curves.dxf', 'pitch_curves.svg']);
  const dir = join(tmp, 'gear');
  execFileSync(cli, ['gear', sceneFile('export.toml', await pageScene()), '--export', dir]);
  for (const d of downloads) {
    const path = join(tmp, `page-${d.suggestedFilename()}`);
    await d.saveAs(path);
    sameUpToLastDigit(readFileSync(path, 'utf8'), readFileSync(join(dir, d.suggestedFilename()), 'utf8'), d.suggestedFilename());
  }
});

test('one evaluation in the browser against the native one', async () => {
  const wasm = await page.evaluate(() => {
    const d = window.studio.state.design;
    d.evaluateRepeatedly(200);
    const rounds = [];
    for (let r = 0; r < 15; r++) {
      const t0 = performance.now();
      d.evaluateRepeatedly(2000);
      rounds.push((performance.now() - t0) / 2000 * 1000);
    }
    return rounds;
  });
  const file = sceneFile('timed.toml', await pageScene());
  const native = JSON.parse(execFileSync('cargo', ['run', '--profile', profile, '--quiet', '--example', 'evaluation_time', '--', file], { cwd: repo, encoding: 'utf8' }));
  speed.evaluation_us = { wasm: spread(wasm), native };
  speed.evaluation_ratio = spread(wasm).median / native.median_us;
  assert.ok(Number.isFinite(speed.evaluation_ratio));
});

test('a search in the worker reaches a feasible design equal to the CLI\'s one-thread run', async () => {
  await page.selectOption('#builtin', 'paper-search');
  await page.waitForFunction(() => window.studio.state.design.get('gear.curve.radii_mm[7]') === 12);
  await page.selectOption('#algorithm', 'de');
  await page.fill('#budget', '20000');
  await page.fill('#seed', '1');
  const scene = await pageScene();
  await page.click('#search-start');
  await page.waitForSelector('#search-load:not([disabled])', { timeout: 180000 });
  const run = await page.evaluate(() => window.studio.lastSearch);
  const s = run.result.summary;
  assert.equal(s.feasible, true, 'the search found a design meeting every objective');
  const native = cliJson('optimise', sceneFile('search.toml', scene), '--algorithm', 'de', '--budget', '20000', '--seed', '1', '--threads', '1');
  assert.deepEqual(s.best, native.best, 'the same design, bit for bit');
  speed.search_objectives_max_relative_difference = assertClose(s.objectives, native.objectives, 1e-12);
  assert.equal(s.evaluations, native.evaluations);
  assert.equal(s.first_feasible_evaluations, native.first_feasible_evaluations);
  // Throughput: a longer native run, so that its start-up does not count.
  const long = cliJson('optimise', sceneFile('search.toml', scene), '--algorithm', 'de', '--budget', '60000', '--seed', '1', '--threads', '1');
  speed.search_per_s = { wasm_worker: run.rate, native_one_thread: long.evaluations / long.seconds };
  speed.search_ratio = run.rate / speed.search_per_s.native_one_thread;
  await page.click('#search-load');
  const loaded = await pageReport();
  assert.equal(loaded.feasible, true, 'the loaded result meets every objective in the editor');
  assert.equal(await page.locator('#verdict').textContent(), `${loaded.objectives.length} of ${loaded.objectives.length} met`);
  await page.screenshot({ path: join(results, 'studio_search.png'), fullPage: true });
});

// The same text, but a number may differ by one in its last printed digit: the
// WebAssembly build's sine and cosine round differently from the native libm in the last
// bit, which can carry a value printed to 12 decimals across a rounding boundary.
function sameUpToLastDigit(page, cli, name) {
  const [a, b] = [page.split('\n'), cli.split('\n')];
  assert.equal(a.length, b.length, `${name}: line count`);
  const number = /^-?\d+\.(\d+)$/;
  for (let i = 0; i < a.length; i++) {
    if (a[i] === b[i]) continue;
    const [ma, mb] = [number.exec(a[i]), number.exec(b[i])];
    assert.ok(ma && mb && ma[1].length === mb[1].length, `${name}, line ${i + 1}: ${a[i]} vs ${b[i]}`);
    const unit = 10 ** -ma[1].length;
    assert.ok(Math.abs(Number(a[i]) - Number(b[i])) <= 1.5 * unit, `${name}, line ${i + 1}: ${a[i]} vs ${b[i]}`);
  }
}

test('the cut teeth are drawn and exported as the CLI cuts them', async () => {
  const pitchPoints = await page.evaluate(() => JSON.parse(window.studio.state.design.frame(0)).sun.length);
  await page.check('#teeth');
  assert.match(await page.locator('#teeth-msg').textContent(), /teeth cut/);
  const toothedPoints = await page.evaluate(() => JSON.parse(window.studio.state.design.frame(0)).sun.length);
  assert.ok(toothedPoints > 5 * pitchPoints, `a toothed outline has ${toothedPoints} points against the pitch curve's ${pitchPoints}`);
  await page.locator('#mechanism').screenshot({ path: join(results, 'mechanism_teeth.png') });
  const downloads = [];
  page.on('download', (d) => downloads.push(d));
  const dir = join(tmp, 'teeth');
  // --force: the CLI refuses to export teeth that fail a check (exit code 3) unless asked,
  // and so does the page unless "even if a check fails" is ticked.
  let fails = false;
  try {
    execFileSync(cli, ['teeth', sceneFile('teeth.toml', await pageScene()), '--export', dir, '--carrier-deg', '0', '--force'], { stdio: 'pipe' });
  } catch (e) {
    if (e.status !== 3) throw e;
    fails = true;
  }
  await page.click('#export-teeth');
  if (fails) {
    await page.waitForTimeout(300);
    assert.equal(downloads.length, 0, 'failing teeth exported without asking');
    assert.match(await page.locator('#teeth-msg').textContent(), /not exported: the teeth fail \d+ check/);
    await page.check('#export-force');
    await page.click('#export-teeth');
  }
  for (let i = 0; i < 50 && downloads.length < 7; i++) await page.waitForTimeout(100);
  const names = downloads.map((d) => d.suggestedFilename()).sort();
  assert.deepEqual(names, ['driven.csv', 'driven.dxf', 'driver.csv', 'driver.dxf', 'pitch_driver.csv', 'train.dxf', 'train.svg']);
  for (const d of downloads) {
    const path = join(tmp, `page-${d.suggestedFilename()}`);
    await d.saveAs(path);
    sameUpToLastDigit(readFileSync(path, 'utf8'), readFileSync(join(dir, d.suggestedFilename()), 'utf8'), d.suggestedFilename());
  }
  await page.uncheck('#export-force');
  await page.uncheck('#teeth');
});

test('teeth that fail a check are exported only when asked, as the CLI exports them only with --force', async () => {
  const scene = await pageScene();
  assert.ok(!scene.includes('[gear.teeth]'), 'the page scene already sets the teeth');
  // Tips taller than the roots are deep: the teeth overlap.
  const failing = `${scene}\n[gear.teeth]\naddendum = 1.45\n`;
  const file = sceneFile('failing.toml', failing);
  assert.throws(() => execFileSync(cli, ['teeth', file], { stdio: 'pipe' }), (e) => e.status === 3);
  await page.setInputFiles('#open', { name: 'failing.toml', mimeType: 'text/plain', buffer: Buffer.from(failing) });
  await page.waitForFunction(() => window.studio.state.design.toToml().includes('addendum = 1.45'));
  const downloads = [];
  page.on('download', (d) => downloads.push(d));
  await page.click('#export-teeth');
  await page.waitForTimeout(300);
  assert.equal(downloads.length, 0, 'failing teeth exported without asking');
  assert.match(await page.locator('#teeth-msg').textContent(), /not exported: the teeth fail \d+ checks? \(.*overlap/);
  await page.check('#export-force');
  await page.click('#export-teeth');
  for (let i = 0; i < 50 && downloads.length < 7; i++) await page.waitForTimeout(100);
  assert.equal(downloads.length, 7);
  await page.uncheck('#export-force');
  await page.setInputFiles('#open', { name: 'restored.toml', mimeType: 'text/plain', buffer: Buffer.from(scene) });
  await page.waitForFunction(() => !window.studio.state.design.toToml().includes('addendum = 1.45'));
  assert.equal(await pageScene(), scene);
});

test('a figure downloads as standalone SVG', async () => {
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('button.fig[data-fig="trajectory"]:not(.png)')]);
  const path = join(tmp, 'trajectory.svg');
  await download.saveAs(path);
  const text = readFileSync(path, 'utf8');
  assert.match(text, /^<svg[^>]*xmlns="http:\/\/www\.w3\.org\/2000\/svg"/);
  assert.match(text, /seedling removal/);
});

test('the keyboard reaches a control point and steps its radius', async () => {
  const r0 = await page.evaluate(() => window.studio.state.design.get('gear.curve.radii_mm[3]'));
  await page.locator('[data-point="3"]').focus();
  await page.keyboard.press('ArrowUp');
  await page.keyboard.press('ArrowUp');
  assert.equal(await page.evaluate(() => window.studio.state.design.get('gear.curve.radii_mm[3]')), r0 + 1);
  await page.keyboard.press('Control+z');
  assert.equal(await page.evaluate(() => window.studio.state.design.get('gear.curve.radii_mm[3]')), r0 + 0.5);
});

test('a stopped search\'s checkpoint resumes in the CLI to the uninterrupted run\'s result', async () => {
  await page.fill('#budget', '200000');
  await page.fill('#seed', '4');
  const scene = await pageScene();
  await page.click('#search-start');
  await page.waitForFunction(() => /evaluations,/.test(document.getElementById('search-status').textContent));
  await page.click('#search-stop');
  await page.waitForSelector('#search-checkpoint:not([disabled])', { timeout: 60000 });
  const stopped = await page.evaluate(() => window.studio.lastSearch);
  assert.equal(stopped.result.summary.stopped_early, true);
  assert.ok(stopped.result.summary.evaluations < 200000);
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#search-checkpoint')]);
  const checkpoint = join(tmp, 'checkpoint.json');
  await download.saveAs(checkpoint);
  const resumed = cliJson('optimise', '--resume', checkpoint, '--threads', '1');
  const whole = cliJson('optimise', sceneFile('whole.toml', scene), '--algorithm', 'de', '--budget', '200000', '--seed', '4', '--threads', '1');
  assert.deepEqual(resumed.best, whole.best);
  assert.equal(resumed.evaluations, whole.evaluations);
  // And in the page itself.
  await page.setInputFiles('#search-resume', checkpoint);
  await page.waitForFunction(() => window.studio.lastSearch?.result.summary.evaluations >= 200000, null, { timeout: 180000 });
  const inPage = await page.evaluate(() => window.studio.lastSearch.result.summary);
  assert.deepEqual(inPage.best, whole.best);
  assert.equal(inPage.stopped_early, false);
});

test('a target drawn by clicking spline points and two placed poses shows the CLI\'s fit measures as gauges', async () => {
  await page.selectOption('#builtin', 'paper-search');
  await page.waitForFunction(() => window.studio.state.design.get('gear.curve.radii_mm[7]') === 12 && !window.studio.state.out.view.target);
  assert.equal(await page.locator('#fit-gauges .gauge').count(), 0);
  // The repository's drawn peach: twelve points along the paper's trajectory.
  const drawn = readFileSync(join(repo, 'scenes/targets/drawn-peach.toml'), 'utf8');
  const list = (key) => JSON.parse(drawn.match(new RegExp(`^${key} = (\\[.*\\])$`, 'm'))[1]);
  const [xs, ys] = [list('x_mm'), list('y_mm')];
  await page.click('#target-draw');
  for (let i = 0; i < xs.length; i++) {
    // Where the point is now: the plot rescales as the target grows.
    const at = await page.evaluate((q) => window.studio.toScreen('trajectory', q), [xs[i], ys[i]]);
    await page.mouse.click(at.x, at.y);
  }
  await page.click('#target-draw');
  const target = await page.evaluate(() => window.studio.state.out.view.target);
  assert.equal(target.table.kind, 'spline');
  assert.equal(target.table.x_mm.length, xs.length);
  for (let i = 0; i < xs.length; i++) {
    const miss = Math.hypot(target.table.x_mm[i] - xs[i], target.table.y_mm[i] - ys[i]);
    assert.ok(miss < 2, `point ${i} landed ${miss} mm from where it was clicked`);
  }
  assert.ok(target.path.length > 100, 'the spline is drawn through the points');
  // The picking and planting poses, clicked where the paper's design picks and plants.
  for (const [pose, at] of [['picking', [277.9, -98.3]], ['planting', [3.3, -293.9]]]) {
    await page.click(`#pose-${pose}`);
    const p = await page.evaluate((q) => window.studio.toScreen('trajectory', q), at);
    await page.mouse.click(p.x, p.y);
  }
  const report = await pageReport();
  assert.deepEqual(report.fit.poses.map((p) => p.name), ['picking', 'planting']);
  const expected = cliJson('evaluate', sceneFile('drawn.toml', await pageScene()));
  // 1e-9, not 1e-12: a pose's errors are differences of nearly equal numbers (an attitude
  // asked to 0.01° of the design's own), where the last bit of an angle is 1e-11 of them.
  speed.target_fit_max_relative_difference = assertClose(report.fit, expected.fit, 1e-9);
  // A gauge per fit measure, showing fit.json's value.
  const rows = await page.evaluate(() => window.studio.state.out.fit_measures);
  assert.ok(rows.length >= 6, `${rows.length} fit measures`);
  // As the page writes a gauge's value (plots.js fmt: four digits, small ones in e-notation).
  const fmt = (v) => (Math.abs(v) !== 0 && (Math.abs(v) < 1e-3 || Math.abs(v) >= 1e5) ? v.toExponential(1) : String(+v.toPrecision(6)));
  for (const m of rows) {
    const shown = await page.locator(`[data-fit="${m.name}"] .value-text`).textContent();
    assert.equal(shown, fmt(+m.value.toPrecision(4)), m.name);
  }
  // The saved target is the page's, and the CLI reads it.
  const [download] = await Promise.all([page.waitForEvent('download'), page.click('#target-save')]);
  await download.saveAs(join(tmp, 'target.toml'));
  assert.match(readFileSync(join(tmp, 'target.toml'), 'utf8'), /^\[target\]$/m);
  await page.locator('#see').screenshot({ path: join(results, 'studio_target.png') });
});

test('a fit in the worker gives the CLI\'s noncirc fit for the same scene, target and seed', async () => {
  await page.selectOption('#algorithm', 'de');
  await page.fill('#budget', '3000');
  await page.fill('#seed', '1');
  // The scene with its target inline; the CLI takes the saved file's, the same target.
  const scene = await pageScene();
  await page.click('#fit-start');
  await page.waitForSelector('#fit-load:not([disabled])', { timeout: 300000 });
  const run = await page.evaluate(() => window.studio.lastFit);
  const native = cliJsonExit([0, 3], 'fit', sceneFile('fit.toml', scene), '--target', join(tmp, 'target.toml'),
    '--algorithm', 'de', '--budget', '3000', '--seed', '1', '--threads', '1');
  // The same search (its evaluations) and the same refinement's path (its evaluations and
  // ending); the numbers within 1e-6: Levenberg–Marquardt's difference Jacobian magnifies
  // the last bit by which WebAssembly's sine and cosine differ from the native libm
  // (about 2e-9 of a parameter after a thousand evaluations).
  assert.equal(run.fit.run.evaluations, native.run.evaluations);
  assert.equal(run.fit.run.local.evaluations, native.run.local.evaluations);
  assert.equal(run.fit.run.local.termination, native.run.local.termination);
  speed.fit_max_relative_difference = assertClose(withoutSeconds(run.fit), withoutSeconds(native), 1e-6);
  await page.click('#fit-load');
  const loaded = await pageReport();
  assert.ok(Math.abs(loaded.fit.path_hausdorff_mm - native.fit.path_hausdorff_mm) <= 1e-6 * native.fit.path_hausdorff_mm);
  await page.screenshot({ path: join(results, 'studio_fit.png'), fullPage: true });
  // Clearing the target takes its gauges away; undo brings it back.
  await page.click('#target-clear');
  assert.equal(await page.locator('#fit-gauges .gauge').count(), 0);
  await page.click('#undo');
  assert.ok(await page.evaluate(() => window.studio.state.out.view.target !== null));
});

test('Repair in the worker gives the CLI\'s noncirc repair for the same scene and seed', async () => {
  await page.selectOption('#builtin', 'paper-search');
  await page.waitForFunction(() => window.studio.state.design.get('gear.curve.radii_mm[7]') === 12);
  await page.fill('#budget', '3000');
  await page.fill('#seed', '1');
  const scene = await pageScene();
  await page.click('#repair-start');
  await page.waitForFunction(() => window.studio.lastRepair?.repair.scene === 'paper-search', null, { timeout: 300000 });
  const run = await page.evaluate(() => window.studio.lastRepair.repair);
  const native = cliJsonExit([0, 3], 'repair', sceneFile('repair.toml', scene), '--algorithm', 'de', '--budget', '3000', '--seed', '1', '--threads', '1');
  assert.equal(run.repaired, native.repaired);
  speed.repair_max_relative_difference = assertClose(withoutSeconds(run), withoutSeconds(native), 1e-9);
});

test('the two-arm scene draws two arm sets half a turn apart, as the CLI reports them', async () => {
  const scene = await pageScene();
  const hadResults = await page.evaluate(() => [!document.getElementById('search-load').disabled, !document.getElementById('fit-load').disabled]);
  assert.ok(hadResults.some(Boolean), 'the tests above left a result to load');
  await page.selectOption('#builtin', 'two-arm');
  await page.waitForFunction(() => window.studio.state.out.report.events.arms.length === 2);
  // The paper's search or repair result is not the two-arm scene's to load.
  assert.ok(await page.locator('#search-load').isDisabled());
  assert.ok(await page.locator('#fit-load').isDisabled());
  const expected = cliJson('evaluate', join(repo, 'scenes/two-arm.toml'));
  assertClose(await pageReport(), expected, 1e-12);
  const [first, second] = expected.events.arms;
  assert.equal((second.picking_carrier_deg - first.picking_carrier_deg + 360) % 360, 180);
  const frame = await page.evaluate(() => JSON.parse(window.studio.state.design.frame(0)));
  assert.equal(frame.arms.length, 2);
  assert.equal(await page.locator('input[data-path="train.arms"]').inputValue(), '2');
  assert.equal(await page.locator('input[data-path="train.picks_per_minute"]').inputValue(), '180');
  assert.ok(await page.locator('input[data-path="train.carrier_speed_rpm"]').isDisabled(), 'the rate sets the carrier speed');
  await page.click('#undo');
  assert.equal(await pageScene(), scene);
  const three = await page.evaluate(() => JSON.parse(window.studio.state.design.frame(0)));
  assert.equal(three.arms.length, 3);
  assert.ok(!(await page.locator('input[data-path="train.carrier_speed_rpm"]').isDisabled()));
});

/** The dynamics panel's table once it follows the design (it waits for the design to rest):
 *  key → the number it shows (full precision; null for none). */
async function dynamicsTable() {
  await page.waitForFunction(() => window.studio.state.dynamicsTimer === null);
  assert.equal(await page.locator('#dynamics-panel.stale').count(), 0, 'the panel is greyed though up to date');
  return page.evaluate(() => Object.fromEntries([...document.querySelectorAll('#dynamics-table tr')]
    .map((tr) => [tr.dataset.key, tr.cells[1].dataset.value === '' ? null : Number(tr.cells[1].dataset.value)])));
}

/** Asserts that the dynamics panel shows `noncirc dynamics`'s numbers for the page's
 *  scene; returns the CLI's report. */
async function assertDynamicsAreTheCli(name) {
  const cli = cliJson('dynamics', sceneFile(name, await pageScene()));
  const rpm = 60 / (2 * Math.PI);
  const speeds = cli.speed.carrier_speed_rad_s;
  const { mesh_force_peak_n: mesh, formulations_rel_diff: rounding, ...summary } = cli.summary;
  const expected = {
    carrier_rpm: cli.carrier_speed_rad_s * rpm, ...summary,
    'mesh_force_peak_n.0': mesh[0], 'mesh_force_peak_n.1': mesh[1],
    drive_torque_nm: cli.speed.drive_torque_nm,
    carrier_rpm_least: Math.min(...speeds) * rpm, carrier_rpm_largest: Math.max(...speeds) * rpm,
    speed_fluctuation: cli.speed.coefficient, flywheel_needed_kg_m2: cli.flywheel_needed_kg_m2,
  };
  const { formulations_rel_diff: shownRounding, ...shown } = await dynamicsTable();
  assertClose(shown, expected, 1e-12);
  // The two formulations' torques differ by rounding, in the browser as natively.
  assert.ok(shownRounding < 1e-12 && rounding < 1e-12, `${shownRounding}, ${rounding}`);
  return cli;
}

test('the dynamics panel shows noncirc dynamics\' numbers, follows the picking rate, and plots every quantity', async () => {
  const scene = await pageScene();
  const at180 = await assertDynamicsAreTheCli('dynamics-180.toml');
  await page.locator('#f-train-picks-per-minute').fill('300');
  await page.locator('#f-train-picks-per-minute').press('Enter');
  await page.waitForFunction(() => Math.abs(Number(document.querySelector('#dynamics-table tr[data-key=carrier_rpm] td.num').dataset.value) - 100) < 1e-9);
  const at300 = await assertDynamicsAreTheCli('dynamics-300.toml');
  // The inertia's share of the torque grows with the speed squared: the peak grows, the
  // loads' share (gravity and the tip's forces) does not.
  assert.ok(at300.summary.torque_peak_nm > 2 * at180.summary.torque_peak_nm, `${at300.summary.torque_peak_nm} against ${at180.summary.torque_peak_nm}`);
  const curveCount = { input_torque: 2, mesh_forces: 2, axle_forces: 4, shaking_force: 1, shaking_moment: 1, carrier_speed: 2 };
  for (const [quantity, n] of Object.entries(curveCount)) {
    await page.selectOption('#dynamics-quantity', quantity);
    const drawn = await page.evaluate(() => document.querySelectorAll('#dynamics-plot g[clip-path] path[stroke-width="1.5"]').length);
    assert.equal(drawn, n, `${quantity}: ${drawn} curves drawn`);
  }
  // Each update of the panel (the quantities above, the two designs), timed.
  speed.dynamics_update_ms = spread(await page.evaluate(() => window.studio.state.dynamicsTimings));
  // The plotted torque is the CLI's, point by point.
  await page.selectOption('#dynamics-quantity', 'input_torque');
  const plotted = await page.evaluate(() => window.studio.state.dynamics.quantity.curves[0][1]);
  assertClose(plotted, at300.input_torque_nm, 1e-12);
  // The stresses wait for the strength.
  assert.ok(await page.locator('#dynamics-quantity option[value=root_stress]').isDisabled());
  // The marker follows the mechanism's carrier angle.
  await page.evaluate(() => { const c = document.getElementById('carrier'); c.value = '90'; c.dispatchEvent(new Event('input')); });
  const markerX = await page.evaluate(() => Number(document.querySelector('#dynamics-plot [data-marker=carrier]').getAttribute('x1')));
  assert.ok(Math.abs(markerX - await page.evaluate(() => document.getElementById('dynamics-plot').axesCache.sx(90))) < 1e-9);
  await page.locator('#dynamics-plot').screenshot({ path: join(results, 'dynamics_panel.png') });
  await page.setInputFiles('#open', { name: 'restored.toml', mimeType: 'text/plain', buffer: Buffer.from(scene) });
  await page.waitForFunction((s) => window.studio.state.design.toToml() === s, scene);
});

test('a bad flywheel is reported beside its field and changes nothing; a good one lowers the speed fluctuation as the CLI computes it', async () => {
  const field = page.locator('#f-dynamics-flywheel-inertia-kg-m2');
  const before = await dynamicsTable();
  await field.fill('-1');
  await field.press('Enter');
  assert.match(await field.locator('xpath=..').locator('.msg').textContent(), /dynamics\.flywheel_inertia_kg_m2/);
  assert.equal(await field.inputValue(), '-1');
  assert.deepEqual(await dynamicsTable(), before);
  await field.fill('0.5');
  await field.press('Enter');
  await page.waitForFunction(() => document.querySelector('#dynamics-table tr[data-key=speed_fluctuation] td').textContent.includes('0.5'));
  const after = await dynamicsTable();
  assert.ok(after.speed_fluctuation < before.speed_fluctuation, `δ ${after.speed_fluctuation} against ${before.speed_fluctuation} without a flywheel`);
  assert.equal(after.flywheel_needed_kg_m2, before.flywheel_needed_kg_m2);
  await assertDynamicsAreTheCli('dynamics-flywheel.toml');
  await field.fill('0');
  await field.press('Enter');
  await page.waitForFunction(() => document.querySelector('#dynamics-table tr[data-key=speed_fluctuation] td').textContent.includes('Jf = 0 '));
});

test('Tooth strength gives noncirc dynamics\' safety factors, or says why the teeth cannot be cut', async () => {
  const scene = await pageScene();
  await page.click('#strength-start');
  await page.waitForFunction(() => !document.getElementById('strength-start').disabled);
  const cliPaper = cliJson('dynamics', sceneFile('strength-paper.toml', scene));
  assert.equal(await page.locator('#strength-status').textContent(), cliPaper.strength_unavailable);
  // The two-arm design cut by a shaper of 100 teeth (docs/dynamics.md's example).
  const twoArm = `${readFileSync(join(repo, 'scenes/two-arm.toml'), 'utf8')}\n[gear.teeth]\ncutter = { kind = "shaper", teeth = 100 }\n`;
  await page.setInputFiles('#open', { name: 'two-arm-shaper.toml', mimeType: 'text/plain', buffer: Buffer.from(twoArm) });
  await page.waitForFunction(() => window.studio.state.out.report.events?.arms.length === 2);
  await page.click('#strength-start');
  await page.waitForFunction(() => !document.getElementById('strength-start').disabled, null, { timeout: 60000 });
  const cli = cliJson('dynamics', sceneFile('strength-two-arm.toml', await pageScene()));
  const shown = await page.evaluate(() => window.studio.state.strength);
  // Stresses near zero (a tooth leaving the mesh) are compared against 1 MPa.
  // The teeth are cut by iterative solves, whose last digits follow the platform's libm.
  assertClose(shown, cli.strength, 1e-10, 'strength', 1);
  for (const g of cli.strength.gears) {
    const row = page.locator(`#strength-table tr[data-gear="${g.name}"] td`);
    assert.equal(await row.nth(6).textContent(), g.bending_safety.toFixed(2));
    assert.equal(await row.nth(10).textContent(), g.contact_safety.toFixed(2));
  }
  assert.match(await page.locator('#strength-status').textContent(), new RegExp(`bending ${cli.strength.bending_safety_min.toFixed(2)}, contact ${cli.strength.contact_safety_min.toFixed(2)}`));
  // Each gear's stresses over the cycle, and a change drops them.
  await page.selectOption('#dynamics-quantity', 'contact_stress');
  assert.equal(await page.evaluate(() => document.querySelectorAll('#dynamics-plot g[clip-path] path[stroke-width="1.5"]').length), cli.strength.gears.length);
  await page.locator('#dynamics-plot').screenshot({ path: join(results, 'dynamics_contact_stress.png') });
  await page.locator('#f-dynamics-face-width-mm').fill('15');
  await page.locator('#f-dynamics-face-width-mm').press('Enter');
  await page.waitForFunction(() => window.studio.state.strength === null);
  assert.equal(await page.locator('#dynamics-quantity').inputValue(), 'input_torque');
  assert.equal(await page.locator('#strength-table tr').count(), 0);
  await page.setInputFiles('#open', { name: 'restored.toml', mimeType: 'text/plain', buffer: Buffer.from(scene) });
  await page.waitForFunction((s) => window.studio.state.design.toToml() === s, scene);
});

test('the 3D view places noncirc cad\'s solids as the CLI does, turns with the scrubber, and downloads the CLI\'s files', async () => {
  const scene = await pageScene();
  const twoArm = `${readFileSync(join(repo, 'scenes/two-arm.toml'), 'utf8')}\n[gear.teeth]\ncutter = { kind = "shaper", teeth = 100 }\n`;
  await page.setInputFiles('#open', { name: 'two-arm-solids.toml', mimeType: 'text/plain', buffer: Buffer.from(twoArm) });
  await page.waitForFunction(() => window.studio.state.out.report.events?.arms.length === 2);
  await page.click('#solid-open');
  await page.waitForFunction(() => window.studio.state.solid !== null || document.getElementById('solid-status').className === 'msg', null, { timeout: 60000 });
  assert.equal(await page.locator('#solid-status').getAttribute('class'), '', await page.locator('#solid-status').textContent());
  const file = sceneFile('solids.toml', await pageScene());
  const setCarrier = (deg) => page.evaluate((d) => { const c = document.getElementById('carrier'); c.value = String(d); c.dispatchEvent(new Event('input')); }, deg);
  // Non-white pixels of the view (the WebGL canvas drawn onto a 2D one), and their hash.
  const picture = () => page.evaluate(() => {
    const src = document.getElementById('solid');
    const c = document.createElement('canvas'); c.width = src.width; c.height = src.height;
    const ctx = c.getContext('2d'); ctx.drawImage(src, 0, 0);
    const d = ctx.getImageData(0, 0, c.width, c.height).data;
    let inked = 0, hash = 0;
    for (let i = 0; i < d.length; i += 4) {
      if (d[i] < 245 || d[i + 1] < 245 || d[i + 2] < 245) inked++;
      hash = (hash * 31 + d[i] + 7 * d[i + 1] + 13 * d[i + 2]) >>> 0;
    }
    return { inked: inked / (d.length / 4), hash };
  });
  const pictures = [];
  for (const deg of [40, 130]) {
    await setCarrier(deg);
    const dir = join(tmp, `solids-${deg}`);
    execFileSync(cli, ['cad', file, '--format', 'stl', '--carrier-deg', String(deg), '--out', dir], { stdio: 'ignore' });
    const manifest = JSON.parse(readFileSync(join(dir, 'assembly.json'), 'utf8'));
    const shown = await page.evaluate(() => window.studio.state.solid.placements);
    // The same copies at the same places, to the last digits of the kinematics.
    assertClose(shown, manifest.instances, 1e-12, `placements at ${deg}°`, 1e-9);
    pictures.push(await picture());
    if (deg === 40) {
      await page.locator('#solid-figure').screenshot({ path: join(results, 'studio_solids.png') });
      // Each part's STL and assembly.json: the CLI's, up to the last digits of the teeth's
      // iterative solves (which follow the platform's libm): the same triangles to 1e-5 mm
      // (single precision), the same numbers to 1e-10.
      const names = [...manifest.parts.map((p) => `${p.name}.stl`), 'assembly.json'];
      const downloads = [];
      page.on('download', (d) => downloads.push(d));
      await page.click('#solid-stl');
      for (let i = 0; i < 50 && downloads.length < names.length; i++) await new Promise((r) => setTimeout(r, 100));
      page.removeAllListeners('download');
      assert.deepEqual(downloads.map((d) => d.suggestedFilename()).sort(), [...names].sort());
      for (const d of downloads) {
        const got = readFileSync(await d.path());
        const want = readFileSync(join(dir, d.suggestedFilename()));
        if (d.suggestedFilename().endsWith('.json')) {
          assertClose(JSON.parse(got.toString('utf8')), JSON.parse(want.toString('utf8')), 1e-10, 'assembly.json', 1e-9);
          continue;
        }
        assert.equal(got.length, want.length, d.suggestedFilename());
        assert.ok(got.subarray(0, 84).equals(want.subarray(0, 84)));
        let worst = 0;
        for (let at = 84; at < got.length; at += 50) {
          for (let k = 12; k < 48; k += 4) worst = Math.max(worst, Math.abs(got.readFloatLE(at + k) - want.readFloatLE(at + k)));
        }
        assert.ok(worst <= 1e-5, `${d.suggestedFilename()}: vertices differ by ${worst} mm`);
      }
    }
  }
  // The view shows the assembly (a twentieth of the canvas or more inked) and moves with the carrier.
  for (const p of pictures) assert.ok(p.inked > 0.05, JSON.stringify(pictures));
  assert.notEqual(pictures[0].hash, pictures[1].hash);
  // A change closes the view (its solids belong to the old design).
  await page.locator('#f-dynamics-face-width-mm').fill('15');
  await page.locator('#f-dynamics-face-width-mm').press('Enter');
  await page.waitForFunction(() => window.studio.state.solid === null);
  assert.equal(await page.locator('#solid-figure').isHidden(), true);
  await setCarrier(0);
  await page.setInputFiles('#open', { name: 'restored.toml', mimeType: 'text/plain', buffer: Buffer.from(scene) });
  await page.waitForFunction((s) => window.studio.state.design.toToml() === s, scene);
});

test('a screenshot of the page is saved, and nothing went wrong in the console', async () => {
  await page.screenshot({ path: join(results, 'studio.png'), fullPage: true });
  assert.deepEqual(problems, []);
});
