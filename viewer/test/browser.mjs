// Opening viewer pages in the system's Chromium (Debian `chromium`, never a downloaded browser)
// through playwright-core, headless, WebGL on Chromium's software renderer (SwiftShader), with a
// fresh profile and no network services: for the browser test, the screenshots and the frame-rate
// benchmark (docs/viewer.md).
import { chromium } from 'playwright-core';
import { existsSync, mkdtempSync, rmSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join, resolve } from 'node:path';
import { pathToFileURL } from 'node:url';

export const chromiumPath = process.env.KABOUM_CHROMIUM || '/usr/bin/chromium';

export const chromiumFlags = [
  '--headless=new',
  '--no-sandbox',
  '--disable-gpu',
  '--use-angle=swiftshader',
  '--enable-unsafe-swiftshader',
  '--disable-quic',
  '--no-first-run',
  '--disable-background-networking',
  '--disable-component-update',
  '--disable-sync',
];

export function haveChromium() {
  return existsSync(chromiumPath);
}

// A browser context on a fresh profile; close() also removes the profile.
export async function openBrowser({ width = 1280, height = 720 } = {}) {
  const profile = mkdtempSync(join(tmpdir(), 'kaboum-chromium-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: chromiumPath,
    headless: true,
    args: chromiumFlags,
    viewport: { width, height },
    offline: true,
  });
  return {
    context,
    profile,
    async close() {
      await context.close();
      rmSync(profile, { recursive: true, force: true });
    },
  };
}

// Opens `file` (a page of `kaboum view`) from a file:// URL and waits until its viewer is ready.
// Every console error and page error is collected in `errors`; every request that is not the
// file itself in `requests` (a page must fetch nothing).
export async function openPage(context, file) {
  const page = await context.newPage();
  const errors = [];
  const requests = [];
  const url = pathToFileURL(resolve(file)).href;
  page.on('console', (message) => {
    if (message.type() === 'error') errors.push(message.text());
  });
  page.on('pageerror', (error) => errors.push(String(error)));
  page.on('request', (request) => {
    if (request.url() !== url && !request.url().startsWith('data:')) requests.push(request.url());
  });
  await page.goto(url);
  await page.waitForFunction(() => window.kaboum && (window.kaboum.ready || window.kaboum.error), {
    timeout: 30000,
  });
  const failure = await page.evaluate(() => window.kaboum.error);
  if (failure) errors.push(failure);
  return { page, errors, requests };
}

// How many distinct colours the canvas shows (read back at a coarse grid): 1 for a blank canvas.
// Read in an animation frame callback after the viewer's, while its drawing is still there.
export async function canvasColours(page) {
  return page.evaluate(async () => {
    await new Promise((drawn) => requestAnimationFrame(drawn));
    const source = document.querySelector('#kaboum-view canvas');
    const copy = document.createElement('canvas');
    copy.width = 160;
    copy.height = 90;
    const context = copy.getContext('2d');
    context.drawImage(source, 0, 0, copy.width, copy.height);
    const pixels = context.getImageData(0, 0, copy.width, copy.height).data;
    const colours = new Set();
    for (let i = 0; i < pixels.length; i += 4) {
      colours.add((pixels[i] << 16) | (pixels[i + 1] << 8) | pixels[i + 2]);
    }
    return colours.size;
  });
}

// Frames drawn per second while the plan plays at `speed`, over `seconds`.
export async function playingFrameRate(page, seconds = 5, speed = 1) {
  return page.evaluate(
    async ({ seconds, speed }) => {
      window.kaboum.seek(0);
      window.kaboum.setSpeed(speed);
      window.kaboum.play();
      const frames = window.kaboum.frames();
      const start = performance.now();
      await new Promise((done) => setTimeout(done, seconds * 1000));
      const fps = ((window.kaboum.frames() - frames) * 1000) / (performance.now() - start);
      window.kaboum.pause();
      return fps;
    },
    { seconds, speed },
  );
}
