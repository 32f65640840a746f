// The viewer in a real browser (docs/viewer.md, "The browser test"): pages written by `kaboum
// solve --html` and `kaboum view` from the Pick and Place and Bartender examples, opened from
// file:// URLs in headless Chromium. Fails on any console error or fetched resource, a blank
// canvas, link poses that differ from kaboum's forward kinematics at the same times (`kaboum view
// --link-poses-at`), simplified meshes not drawn while the plan plays or drawn when paused, or a
// way through the sensing branches, chosen in the page, whose actions and duration differ from
// those `kaboum execute` gives it. Takes screenshots into OUT_DIR.
// Usage: node browser_test.mjs KABOUM SOURCE_DIR OUT_DIR  (exit 0 passed, 1 failed, 77 skipped)
import { execFileSync } from 'node:child_process';
import { mkdirSync, readFileSync, rmSync } from 'node:fs';
import { join } from 'node:path';
import { canvasColours, chromiumPath, haveChromium, openBrowser, openPage } from './browser.mjs';

const [kaboum, sourceDir, outDir] = process.argv.slice(2);
if (!outDir) {
  console.error('usage: node browser_test.mjs KABOUM SOURCE_DIR OUT_DIR');
  process.exit(2);
}
if (!haveChromium()) {
  console.log(`SKIPPED: no Chromium at ${chromiumPath} (scripts/setup.sh installs Debian's)`);
  process.exit(77);
}
rmSync(outDir, { recursive: true, force: true });
mkdirSync(outDir, { recursive: true });

const failures = [];
function check(condition, message) {
  if (!condition) failures.push(message);
  console.log(`${condition ? 'ok  ' : 'FAIL'} ${message}`);
}

// Runs kaboum from the source folder (the plan files name the examples relative to it).
function kaboumRun(args, input) {
  // With input (execute --ask), its prompts on stderr are not shown.
  const stdio = ['pipe', 'pipe', input ? 'ignore' : 'inherit'];
  return execFileSync(kaboum, args, { cwd: sourceDir, input, encoding: 'utf8', stdio });
}

function solve(example, problem, name) {
  const dir = join('examples', example);
  const plan = join(outDir, `${name}.json`);
  const solvedPage = join(outDir, `${name}-solve.html`);
  kaboumRun([
    'solve',
    join(dir, 'domain.pddl'),
    join(dir, problem),
    join(dir, 'scene.yaml'),
    '--plan-out',
    plan,
    '--html',
    solvedPage,
    '--quiet',
  ]);
  const page = join(outDir, `${name}.html`);
  const summary = JSON.parse(kaboumRun(['view', plan, '-o', page, '--json']));
  check(
    summary.bytes > 0 && summary.meshes > 0 && summary.pieces > 0,
    `${name}: ${summary.bytes} bytes, ${summary.meshes} meshes, ${summary.pieces} pieces`,
  );
  return { plan, page, solvedPage, summary };
}

function rotationAngle(a, b) {
  const dot = Math.abs(a.reduce((sum, value, i) => sum + value * b[i], 0));
  return 2 * Math.acos(Math.min(1, dot));
}

// The largest position (m) and rotation (rad) difference between the page's link poses and
// kaboum's at each time.
async function comparePoses(page, name, plan, times) {
  const reference = JSON.parse(
    kaboumRun(['view', plan, '--link-poses-at', times.join(','), '--json']),
  );
  let position = 0;
  let rotation = 0;
  let links = 0;
  for (const { time, robots } of reference) {
    const shown = await page.evaluate((t) => {
      window.kaboum.seek(t);
      return window.kaboum.linkPoses();
    }, time);
    for (const [robot, poses] of Object.entries(robots)) {
      for (const [link, pose] of Object.entries(poses)) {
        const other = shown[robot]?.[link];
        if (!other) {
          failures.push(`${name}: the page shows no link ${robot}/${link}`);
          continue;
        }
        ++links;
        position = Math.max(
          position,
          Math.hypot(...pose.position.map((v, i) => v - other.position[i])),
        );
        rotation = Math.max(rotation, rotationAngle(pose.quaternion_wxyz, other.quaternion_wxyz));
      }
    }
  }
  check(
    links > 0 && position < 1e-4 && rotation < 1e-4,
    `${name}: ${links} link poses at ${times.length} times as kaboum's forward kinematics ` +
      `(largest differences ${position.toExponential(1)} m, ${rotation.toExponential(1)} rad)`,
  );
}

// Every branch timing `kaboum execute` prints: "branch 1: [(test) true] 6 action(s), 31.8 s".
function executeBranches(example, problem, plan) {
  const dir = join('examples', example);
  const files = [join(dir, 'domain.pddl'), join(dir, problem), join(dir, 'scene.yaml')];
  const text = kaboumRun(['execute', ...files, plan, '--ask'], 'y\n'.repeat(16));
  return [...text.matchAll(/^branch \d+: \[(.*)\] (\d+) action\(s\), ([0-9.]+) s$/gm)].map(
    (m) => ({ outcomes: m[1], actions: Number(m[2]), seconds: Number(m[3]) }),
  );
}

async function opened(context, name, file) {
  const { page, errors, requests } = await openPage(context, file);
  check(errors.length === 0, [`${name}: no console errors`, ...errors].join(': '));
  check(requests.length === 0, [`${name}: fetches nothing`, ...requests].join(': '));
  const colours = await canvasColours(page);
  check(colours > 20, `${name}: the canvas is drawn (${colours} colours)`);
  return page;
}

const started = Date.now();
const browser = await openBrowser();
try {
  // Pick and place: one robot, no sensing; the page of `solve --html` and of `view`.
  const pick = solve('pick-and-place', 'problem.pddl', 'pick-and-place');
  const solvedPage = await opened(
    browser.context,
    'pick-and-place (solve --html)',
    pick.solvedPage,
  );
  await solvedPage.close();
  const page = await opened(browser.context, 'pick-and-place', pick.page);
  const duration = await page.evaluate(() => window.kaboum.duration());
  check(
    Math.abs(duration - pick.summary.duration) < 1e-9,
    `pick-and-place: plays ${duration.toFixed(3)} s, as kaboum times it`,
  );
  const times = [0, 0.137, 0.25, 0.5, 0.75, 0.9, 1].map((f) => Number((f * duration).toFixed(6)));
  await comparePoses(page, 'pick-and-place', pick.plan, times);
  const objects = await page.evaluate(() => {
    window.kaboum.seek(0);
    const before = window.kaboum.objectPoses().block.position;
    window.kaboum.seek(window.kaboum.duration());
    return { before, after: window.kaboum.objectPoses().block.position };
  });
  check(
    Math.hypot(...objects.before.map((v, i) => v - objects.after[i])) > 0.05,
    'pick-and-place: the block is carried away from where it started',
  );
  // The level of detail: simplified meshes while playing, the originals when paused.
  const drawn = await page.evaluate(async () => {
    const viewer = window.kaboum;
    // Two animation frames: the viewer's next frame has been drawn after the change.
    const nextFrame = () =>
      new Promise((done) => requestAnimationFrame(() => requestAnimationFrame(done)));
    viewer.seek(0);
    await nextFrame();
    const paused = viewer.triangles();
    viewer.play();
    await nextFrame();
    const playing = viewer.triangles();
    viewer.pause();
    await nextFrame();
    return { paused, playing, pausedAgain: viewer.triangles() };
  });
  check(
    drawn.playing > 0 && drawn.playing < 0.5 * drawn.paused && drawn.pausedAgain === drawn.paused,
    `pick-and-place: ${drawn.playing} triangles drawn while playing, ${drawn.paused} when ` +
      `paused (${drawn.pausedAgain} after playing)`,
  );
  await page.evaluate(() => window.kaboum.seek(window.kaboum.duration() * 0.4));
  await page.screenshot({ path: join(outDir, 'pick-and-place.png') });
  await page.evaluate(() => window.kaboum.showPieces(true));
  check((await canvasColours(page)) > 20, 'pick-and-place: the convex pieces are drawn');
  await page.screenshot({ path: join(outDir, 'pick-and-place-pieces.png') });
  await page.close();

  // Bartender with two bottles of unknown content: a plan that branches on sensing, a branch in
  // each branch. Every way through it, chosen in the page, against kaboum execute.
  const bar = solve('bartender', 'problem-2.pddl', 'bartender-2');
  const barPage = await opened(browser.context, 'bartender-2', bar.page);
  const expected = executeBranches('bartender', 'problem-2.pddl', bar.plan);
  const shown = await barPage.evaluate(() => {
    const viewer = window.kaboum;
    const ways = [];
    // Depth first, true before false, as kaboum execute lists them.
    const walk = (chosen) => {
      const branches = viewer.branches();
      const open = branches.find((branch) => !chosen.has(branch.node));
      if (!open) {
        const outcomes = branches.map((branch) => `${branch.test} ${branch.value}`).join(', ');
        ways.push({ outcomes, actions: viewer.actions().length, seconds: viewer.duration() });
        return;
      }
      for (const value of [true, false]) {
        viewer.branch(open.node, value);
        walk(new Set([...chosen, open.node]));
      }
    };
    walk(new Set());
    return ways;
  });
  check(
    expected.length === 4 && shown.length === expected.length,
    `bartender-2: ${shown.length} ways through the plan chosen in the page, ` +
      `${expected.length} in kaboum execute`,
  );
  expected.forEach((way, i) => {
    const page = shown[i] || {};
    check(
      page.outcomes === way.outcomes &&
        page.actions === way.actions &&
        Math.abs(page.seconds - way.seconds) < 1e-3,
      `bartender-2: [${way.outcomes}] ${way.actions} actions in ${way.seconds} s, as the page ` +
        `plays it (${JSON.stringify(page)})`,
    );
  });
  for (const value of [true, false]) {
    await barPage.evaluate((value) => {
      window.kaboum.branch(window.kaboum.branches()[0].node, value);
      window.kaboum.seek(window.kaboum.duration() * 0.6);
    }, value);
    await barPage.screenshot({ path: join(outDir, `bartender-2-${value}.png`) });
  }
  await barPage.close();
} finally {
  await browser.close();
}
const seconds = ((Date.now() - started) / 1000).toFixed(1);
console.log(`${failures.length ? 'FAILED' : 'passed'} in ${seconds} s`);
process.exit(failures.length ? 1 : 0);
