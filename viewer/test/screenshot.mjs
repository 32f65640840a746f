// A screenshot of a viewer page at a point of its plan (docs/viewer/*.png).
// Usage: node screenshot.mjs PAGE.html OUT.png [FRACTION_OF_THE_DURATION] [pieces]
import { haveChromium, openBrowser, openPage } from './browser.mjs';

const [file, out, fraction = '0.5', look = ''] = process.argv.slice(2);
if (!out || !haveChromium()) {
  console.error(
    out
      ? 'screenshot.mjs: no Chromium (scripts/setup.sh)'
      : 'usage: node screenshot.mjs PAGE.html OUT.png [FRACTION] [pieces]',
  );
  process.exit(2);
}
const browser = await openBrowser();
try {
  const { page, errors } = await openPage(browser.context, file);
  if (errors.length) throw new Error(`console errors: ${errors.join(' | ')}`);
  await page.evaluate(
    ({ fraction, pieces }) => {
      window.kaboum.showPieces(pieces);
      window.kaboum.seek(window.kaboum.duration() * fraction);
    },
    { fraction: Number(fraction), pieces: look === 'pieces' },
  );
  await page.waitForTimeout(200);
  await page.screenshot({ path: out });
} finally {
  await browser.close();
}
