// Times of the HTML viewer in headless Chromium (bench/viewer.sh; not a
// test): load (navigation to the page's ready mark) and slider moves
// (the input event to the second animation frame after it, so the
// browser's style, layout and paint are in, up to two frame waits of
// 16.7 ms; and the input handler alone, which draws the canvas
// synchronously; median and worst of the moves). script_init_ms: the
// page's script from its first line to ready (null on pages before it). Usage: node viewer.js PLAYWRIGHT_DIR CHROMIUM PAGE.html [MOVES]
"use strict";
const path = require("path");
const [pwDir, chromiumPath, file, movesArg] = process.argv.slice(2);
const moves = +(movesArg || 20);

async function main() {
  const { chromium } = require(path.resolve(pwDir, "node_modules", "playwright-core"));
  const browser = await chromium.launch({ executablePath: chromiumPath, headless: true });
  const page = await (await browser.newContext({ viewport: { width: 1200, height: 800 } })).newPage();
  const t0 = Date.now();
  await page.goto("file://" + path.resolve(file));
  await page.waitForSelector("body[data-ready='1']", { timeout: 300000 });
  const wall = Date.now() - t0;
  const inPage = await page.evaluate(() => performance.now());
  const init = await page.evaluate(() => document.body.dataset.initMs || null);
  const times = await page.evaluate(async (moves) => {
    const s = document.getElementById("slider"), n = +s.max, out = [], sync = [];
    const frame = () => new Promise((r) => requestAnimationFrame(() => requestAnimationFrame(r)));
    for (let k = 1; k <= moves; k++) {
      const p = Math.round((k * 7919) % (n + 1)); // spread over the whole range
      const a = performance.now();
      s.value = String(p);
      s.dispatchEvent(new Event("input", { bubbles: true }));
      sync.push(performance.now() - a);
      await frame();
      out.push(performance.now() - a);
    }
    return { out, sync };
  }, moves);
  const stat = (v) => { v.sort((a, b) => a - b); return [+v[v.length >> 1].toFixed(1), +v[v.length - 1].toFixed(1)]; };
  const [med, worst] = stat(times.out), [smed, sworst] = stat(times.sync);
  console.log(JSON.stringify({ page: path.basename(file), load_ms_driver: wall, ready_ms_in_page: Math.round(inPage),
                               script_init_ms: init === null ? null : +init,
                               slider_ms_median: med, slider_ms_worst: worst,
                               slider_handler_ms_median: smed, slider_handler_ms_worst: sworst, moves }));
  await browser.close();
}
main().catch((e) => { console.error(String(e.stack || e)); process.exit(1); });
