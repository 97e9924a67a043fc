// The HTML plan viewer in a real browser: headless Chromium (Debian's
// /usr/bin/chromium) driven by playwright-core. Run by tests/browser/run.sh,
// which makes the structures, plans and pages with the built CLI:
//   node viewer.test.js PLAYWRIGHT_DIR CHROMIUM WORK_DIR
// WORK_DIR holds the pages and their inputs (named below); screenshots go
// to WORK_DIR/shots. Every expectation comes from the input files (the
// structure's bodies, the plan's order), never from the page's own data.
// Prints one line per check; exits 1 on any failure, including a browser
// that cannot start.
"use strict";
const fs = require("fs");
const path = require("path");

const [pwDir, chromiumPath, work] = process.argv.slice(2);
const shots = path.join(work, "shots");
fs.mkdirSync(shots, { recursive: true });
let pass = 0, fail = 0;
function check(cond, what, detail) {
  if (cond) { pass++; console.log("ok   " + what); }
  else { fail++; console.log("FAIL " + what + (detail !== undefined ? " (" + detail + ")" : "")); }
}
const readJson = (f) => JSON.parse(fs.readFileSync(path.join(work, f), "utf8"));
const pageUrl = (f) => "file://" + path.join(work, f);

// Bodies still standing after the first p steps of a plan's order.
function expectedDrawn(structure, plan, p) {
  let n = structure.bodies.length;
  for (let k = 0; k < p; k++) n -= Array.isArray(plan.order[k]) ? plan.order[k].length : 1;
  return n;
}

// Bodies and force arrows the browser actually lays out (display none has no boxes).
const visibleCount = (page, sel) =>
  page.$$eval(sel, (els) => els.filter((e) => e.getClientRects().length > 0).length);

async function open(browser, file, viewport, touch) {
  const ctx = await browser.newContext({ viewport, hasTouch: !!touch, isMobile: !!touch });
  const page = await ctx.newPage();
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("request", (r) => { if (!r.url().startsWith("file:")) errors.push("network: " + r.url()); });
  await page.goto(pageUrl(file));
  await page.waitForSelector("body[data-ready='1']", { timeout: 30000 });
  return { ctx, page, errors };
}

async function setSlider(page, p) {
  await page.$eval("#slider", (s, v) => {
    s.value = String(v);
    s.dispatchEvent(new Event("input", { bubbles: true }));
  }, p);
}

// Slider at every position: the bodies drawn are those the plan leaves.
async function testSteps(page, structure, plan) {
  const n = plan.order.length;
  check(await page.$eval("#slider", (s) => +s.max) === n, "slider has one position per step", n);
  const bad = [];
  for (let p = 0; p <= n; p++) {
    await setSlider(page, p);
    const drawn = await visibleCount(page, "#bodies .body");
    if (drawn !== expectedDrawn(structure, plan, p)) bad.push(`step ${p}: ${drawn} drawn, ${expectedDrawn(structure, plan, p)} expected`);
  }
  check(bad.length === 0, `bodies drawn match the plan at all ${n + 1} positions`, bad.join("; "));
}

// Play from the start: the step advances on its own to the end and stops.
async function testPlay(page, structure, plan) {
  const n = plan.order.length;
  await setSlider(page, 0);
  await page.click("#play");
  await page.waitForFunction(() => +document.getElementById("view").dataset.step >= 2, null, { timeout: 30000 });
  // step and count read in one script turn, so the timer cannot step between them
  const now = await page.evaluate(() => ({
    step: +document.getElementById("view").dataset.step,
    drawn: Array.from(document.querySelectorAll("#bodies .body")).filter((e) => e.getClientRects().length > 0).length,
  }));
  check(now.drawn === expectedDrawn(structure, plan, now.step), "while playing, the bodies drawn follow the step",
        `${now.drawn} at step ${now.step}`);
  await page.screenshot({ path: path.join(shots, "pyramid-playing.png") });
  await page.waitForFunction((m) => +document.getElementById("view").dataset.step === m &&
                             document.getElementById("play").dataset.playing === "0", n, { timeout: 120000 });
  check(await visibleCount(page, "#bodies .body") === expectedDrawn(structure, plan, n),
        "play runs to the end and stops with every removable body gone");
}

// Forces: none shown until toggled; arrows at the contacts of the full structure.
async function testForces(page) {
  await setSlider(page, 0);
  check(await visibleCount(page, "#forces .force") === 0, "no arrows before the force toggle");
  await page.click("#toggle-forces");
  const arrows = await visibleCount(page, "#forces .force");
  check(arrows > 0, "the force toggle shows arrows", arrows);
  const box = await page.$eval("#forces .force", (e) => { const r = e.getBoundingClientRect(); return r.width + r.height; });
  check(box > 2, "an arrow has a visible length on screen", box);
  await page.screenshot({ path: path.join(shots, "pyramid-forces.png") });
  await page.click("#toggle-forces");
  check(await visibleCount(page, "#forces .force") === 0, "toggling off removes the arrows");
}

// Hover over a body: its id in the info box.
async function testHover(page, structure, index) {
  await setSlider(page, 0);
  const poly = (await page.$$("#bodies .body"))[index];
  await poly.hover();
  const info = await page.$eval("#info", (e) => (e.hidden ? "" : e.textContent));
  check(info.includes(structure.bodies[index].id), "hover shows the body's id", JSON.stringify(info));
  check(/mass/.test(info) && /contacts/.test(info), "hover shows mass and contacts", JSON.stringify(info));
  await page.screenshot({ path: path.join(shots, "pyramid-hover.png") });
}

// Zoom and pan change the view box; fit brings it back.
async function testZoom(page) {
  const vb = () => page.$eval("#view", (v) => v.getAttribute("viewBox"));
  const start = await vb();
  await page.click("#zin");
  const zoomed = (await vb()).split(" ").map(Number);
  check(zoomed[2] < start.split(" ").map(Number)[2], "the zoom button zooms in");
  const r = await page.$eval("#view", (v) => { const b = v.getBoundingClientRect(); return [b.x + b.width / 2, b.y + b.height / 2]; });
  await page.mouse.move(r[0], r[1]);
  await page.mouse.wheel(0, 400);
  check((await vb()).split(" ").map(Number)[2] > zoomed[2], "the wheel zooms out");
  const before = await vb();
  await page.mouse.move(r[0] + 5, r[1] + 5);
  await page.mouse.down();
  await page.mouse.move(r[0] + 60, r[1] + 40, { steps: 5 });
  await page.mouse.up();
  check((await vb()) !== before, "dragging pans the view");
  await page.click("#zfit");
  check((await vb()) === start, "fit restores the first view");
}

async function testPyramid(browser) {
  const structure = readJson("pyramid.json"), plan = readJson("pyramid-plan.json");
  const { ctx, page, errors } = await open(browser, "pyramid.html", { width: 1000, height: 700 });
  await page.screenshot({ path: path.join(shots, "pyramid-start.png") });
  await testSteps(page, structure, plan);
  await testForces(page);
  await testHover(page, structure, 3);
  await testZoom(page);
  await testPlay(page, structure, plan);
  await page.screenshot({ path: path.join(shots, "pyramid-end.png") });
  check(errors.length === 0, "no script errors and no network requests", errors.join("; "));
  await ctx.close();
}

// A plan verify rejects: its failing step is shown in red.
async function testInvalid(browser) {
  const plan = readJson("column-bad-plan.json");
  const { ctx, page, errors } = await open(browser, "column-bad.html", { width: 800, height: 600 });
  await setSlider(page, 0);
  check(await page.$eval("#banner", (b) => b.hidden), "no failure shown before the failing step");
  await setSlider(page, 1);
  const banner = await page.$eval("#banner", (b) => ({ hidden: b.hidden, text: b.textContent, bg: getComputedStyle(b).backgroundColor }));
  check(!banner.hidden && /do not stand/.test(banner.text), "the failing step names what falls", banner.text);
  check(banner.bg === "rgb(198, 40, 40)", "the failure banner is red", banner.bg);
  const falls = await page.$$eval("#bodies .body.falls", (els) => els.filter((e) => e.getClientRects().length > 0).length);
  check(falls === readJson("column-bad.json").bodies.length - 1, "the bodies that fall are outlined", falls);
  check(await page.$eval("#stepinfo", (s) => getComputedStyle(s).color) === "rgb(198, 40, 40)", "the step counter is red at the failing step");
  check(plan.order.length === 3, "the bad plan removes the three blocks");
  await page.screenshot({ path: path.join(shots, "column-bad.png") });
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

// Hostile ids: nothing runs, the ids read back as text.
async function testIds(browser) {
  const structure = readJson("ids.json");
  const { ctx, page, errors } = await open(browser, "ids.html", { width: 800, height: 600 });
  check(!(await page.evaluate(() => window.pwned)), "an id cannot run a script");
  check(await page.$$eval("script", (s) => s.length) === 2, "the page has its two script elements only");
  const got = [];
  for (let i = 0; i < structure.bodies.length; i++) {
    await (await page.$$("#bodies .body"))[i].hover();
    got.push(await page.$eval("#info div", (d) => d.textContent.replace(/^id /, "")));
  }
  const want = structure.bodies.map((b) => b.id);
  check(JSON.stringify(got) === JSON.stringify(want), "hover shows each hostile id exactly", JSON.stringify(got));
  await page.screenshot({ path: path.join(shots, "ids.png") });
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

// A phone: the controls fit the width, a tap pins a body's info.
async function testPhone(browser) {
  const structure = readJson("pyramid.json");
  const { ctx, page, errors } = await open(browser, "pyramid.html", { width: 390, height: 740 }, true);
  const wide = await page.evaluate(() => document.documentElement.scrollWidth);
  check(wide <= 390, "nothing wider than a phone's screen", wide);
  const svgBox = await page.$eval("#view", (v) => { const r = v.getBoundingClientRect(); return [r.width, r.height]; });
  check(svgBox[0] >= 350 && svgBox[1] >= 200, "the drawing fills the phone's screen", svgBox.join("x"));
  const b = await (await page.$$("#bodies .body"))[0].boundingBox();
  await page.touchscreen.tap(b.x + b.width / 2, b.y + b.height / 2);
  const info = await page.$eval("#info", (e) => (e.hidden ? "" : e.textContent));
  check(info.includes(structure.bodies[0].id), "a tap shows the body's id", JSON.stringify(info));
  await page.screenshot({ path: path.join(shots, "phone.png") });
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

async function main() {
  const { chromium } = require(path.join(pwDir, "node_modules", "playwright-core"));
  let browser;
  try {
    browser = await chromium.launch({ executablePath: chromiumPath, headless: true, timeout: 60000 });
  } catch (e) {
    console.log("FAIL Chromium (" + chromiumPath + ") could not start: " + String(e.message || e).split("\n")[0]);
    process.exit(1);
  }
  console.log("browser: Chromium " + browser.version());
  try {
    await testPyramid(browser);
    await testInvalid(browser);
    await testIds(browser);
    await testPhone(browser);
  } catch (e) {
    check(false, "the browser session ran to the end", String(e.stack || e));
  } finally {
    await browser.close();
  }
  console.log(`${pass} passed, ${fail} failed; screenshots in ${shots}`);
  process.exit(fail || pass === 0 ? 1 : 0);
}
main();
