// Frames per second of a viewer page while its plan plays (headless Chromium, software WebGL), the
// CPU time the browser's processes spend per frame (Linux: /proc; what the frame rate would be on
// an idle machine follows from it and the cores) and how long the page takes to open:
// bench/viewer_page.sh's measurement. Prints one JSON line.
// Usage: node frame_rate.mjs PAGE.html [SECONDS]
import { readFileSync, readdirSync } from 'node:fs';
import { haveChromium, openBrowser, openPage, playingFrameRate } from './browser.mjs';

// Seconds of CPU time (user and system) of the processes started with profile folder `profile`.
function cpuSeconds(profile) {
  let ticks = 0;
  for (const pid of readdirSync('/proc').filter((name) => /^\d+$/.test(name))) {
    try {
      if (!readFileSync(`/proc/${pid}/cmdline`, 'utf8').includes(profile)) continue;
      const stat = readFileSync(`/proc/${pid}/stat`, 'utf8');
      const fields = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
      ticks += Number(fields[11]) + Number(fields[12]);  // utime, stime
    } catch {
      // The process ended meanwhile.
    }
  }
  return ticks / 100;  // USER_HZ
}

const [file, seconds = '10'] = process.argv.slice(2);
if (!file || !haveChromium()) {
  console.error(
    file
      ? 'frame_rate.mjs: no Chromium (scripts/setup.sh)'
      : 'usage: node frame_rate.mjs PAGE.html [SECONDS]',
  );
  process.exit(2);
}
const browser = await openBrowser();
try {
  const started = performance.now();
  const { page, errors } = await openPage(browser.context, file);
  const openSeconds = (performance.now() - started) / 1000;
  if (errors.length) throw new Error(`console errors: ${errors.join(' | ')}`);
  const cpuBefore = cpuSeconds(browser.profile);
  const fps = await playingFrameRate(page, Number(seconds));
  const cpuPerFrame = (cpuSeconds(browser.profile) - cpuBefore) / (fps * Number(seconds));
  const renderer = await page.evaluate(() => {
    const gl = document.createElement('canvas').getContext('webgl2');
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : 'unknown';
  });
  const result = { page: file, open_seconds: openSeconds, frames_per_second: fps, renderer };
  const cpu = { cpu_milliseconds_per_frame: cpuPerFrame * 1000 };
  console.log(JSON.stringify({ ...result, ...cpu, viewport: '1280x720' }));
} finally {
  await browser.close();
}
