// Frames per second of a viewer page while its plan plays (headless Chromium, software WebGL) and
// how long it takes to open: bench/viewer_page.sh's measurement. Prints one JSON line.
// Usage: node frame_rate.mjs PAGE.html [SECONDS]
import { haveChromium, openBrowser, openPage, playingFrameRate } from './browser.mjs';

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
  const fps = await playingFrameRate(page, Number(seconds));
  const renderer = await page.evaluate(() => {
    const gl = document.createElement('canvas').getContext('webgl2');
    const info = gl.getExtension('WEBGL_debug_renderer_info');
    return info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : 'unknown';
  });
  const result = { page: file, open_seconds: openSeconds, frames_per_second: fps, renderer };
  console.log(JSON.stringify({ ...result, viewport: '1280x720' }));
} finally {
  await browser.close();
}
