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

// A body's polygon from the structure file, its vertex mean (inside a
// convex body), and a point 60% of the way from there to its first vertex
// (inside, and clear of the step number drawn at the centre).
function poly(b) { return b.polygon || b.vertices || []; }
function centre(b) {
  const v = poly(b);
  return [v.reduce((s, p) => s + p[0], 0) / v.length, v.reduce((s, p) => s + p[1], 0) / v.length];
}
function probe(b) { const c = centre(b), v = poly(b)[0]; return [c[0] + 0.6 * (v[0] - c[0]), c[1] + 0.6 * (v[1] - c[1])]; }

// World points to page pixels, by the view the canvas reports (data-view:
// x, -top, width, height in world units, fitted and centred).
async function toScreen(page, pts) {
  return page.$eval("#view", (c, pts) => {
    const r = c.getBoundingClientRect(), v = c.dataset.view.split(" ").map(Number);
    const k = Math.min(r.width / v[2], r.height / v[3]);
    const ox = (r.width - v[2] * k) / 2 - v[0] * k, oy = (r.height - v[3] * k) / 2 - v[1] * k;
    return pts.map((p) => [r.left + ox + k * p[0], r.top + oy - k * p[1]]);
  }, pts);
}
// The canvas's pixels at page points (after the pending frame is drawn).
async function pixels(page, pts) {
  await page.evaluate(() => new Promise((res) => requestAnimationFrame(() => requestAnimationFrame(res))));
  return page.$eval("#view", (c, pts) => {
    const r = c.getBoundingClientRect(), s = c.width / r.width, g = c.getContext("2d");
    return pts.map((p) => Array.from(g.getImageData(Math.floor((p[0] - r.left) * s), Math.floor((p[1] - r.top) * s), 1, 1).data));
  }, pts);
}
const white = (px) => px[3] < 128 || (px[0] >= 250 && px[1] >= 250 && px[2] >= 250); // nothing painted, or background
// Which bodies of the structure file have paint at their probe point.
async function drawnBodies(page, structure) {
  const px = await pixels(page, await toScreen(page, structure.bodies.map(probe)));
  return px.map((p) => !white(p));
}
// Pixels of the canvas near an arrow colour (blue: normal parts).
async function countColour(page, rgb) {
  await page.evaluate(() => new Promise((res) => requestAnimationFrame(() => requestAnimationFrame(res))));
  return page.$eval("#view", (c, rgb) => {
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4)
      if (Math.abs(d[i] - rgb[0]) + Math.abs(d[i + 1] - rgb[1]) + Math.abs(d[i + 2] - rgb[2]) < 12) n++;
    return n;
  }, rgb);
}
const BLUE = [31, 78, 156];

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

// Slider at every position: the bodies painted are those the plan leaves.
async function testSteps(page, structure, plan) {
  const n = plan.order.length;
  check(await page.$eval("#slider", (s) => +s.max) === n, "slider has one position per step", n);
  const bad = [];
  for (let p = 0; p <= n; p++) {
    await setSlider(page, p);
    const drawn = (await drawnBodies(page, structure)).filter(Boolean).length;
    if (drawn !== expectedDrawn(structure, plan, p)) bad.push(`step ${p}: ${drawn} painted, ${expectedDrawn(structure, plan, p)} expected`);
  }
  check(bad.length === 0, `bodies painted match the plan at all ${n + 1} positions`, bad.join("; "));
}

// Play from the start: the step advances on its own to the end and stops;
// the speed control divides the interval between steps.
async function testPlay(page, structure, plan) {
  const n = plan.order.length;
  const interval = () => page.$eval("#play", (b) => +b.dataset.interval);
  const base = await interval();
  await page.selectOption("#speed", "4");
  const fast = await interval();
  check(fast < base && Math.abs(4 * fast - base) <= 4, "speed 4x plays four times as many steps a second", `${base} -> ${fast} ms`);
  await page.selectOption("#speed", "1");
  await setSlider(page, 0);
  await page.click("#play");
  await page.waitForFunction(() => +document.getElementById("view").dataset.step >= 2, null, { timeout: 30000 });
  await page.selectOption("#speed", "8");
  check(await page.$eval("#play", (b) => b.dataset.playing) === "1", "changing the speed while playing keeps playing");
  await page.screenshot({ path: path.join(shots, "pyramid-playing.png") });
  await page.waitForFunction((m) => +document.getElementById("view").dataset.step === m &&
                             document.getElementById("play").dataset.playing === "0", n, { timeout: 120000 });
  check((await drawnBodies(page, structure)).filter(Boolean).length === expectedDrawn(structure, plan, n),
        "play runs to the end and stops with every removable body gone");
  await page.selectOption("#speed", "1");
}

// Forces: none shown until toggled; arrows at the contacts of the full structure.
async function testForces(page) {
  await setSlider(page, 0);
  check(await countColour(page, BLUE) === 0, "no arrows before the force toggle");
  await page.click("#toggle-forces");
  const blue = await countColour(page, BLUE);
  check(blue > 20, "the force toggle draws blue normal-force arrows", blue);
  check(+(await page.$eval("#view", (v) => v.dataset.arrows)) > 0, "the page counts the arrows it drew");
  await page.screenshot({ path: path.join(shots, "pyramid-forces.png") });
  await page.selectOption("#force-style", "resultants");
  const perPair = +(await page.$eval("#view", (v) => v.dataset.arrows));
  await page.selectOption("#force-style", "contacts");
  const perContact = +(await page.$eval("#view", (v) => v.dataset.arrows));
  check(perPair > 0 && perPair < perContact, "resultants: fewer arrows, one per touching pair", `${perPair} < ${perContact}`);
  await page.click("#toggle-forces");
  check(await countColour(page, BLUE) === 0, "toggling off removes the arrows");
}

// Hover the centre of every body, forces drawn: its id in the info box
// (arrows and numbers never catch the pointer).
async function testHover(page, structure) {
  await setSlider(page, 0);
  await page.click("#toggle-forces");
  const at = await toScreen(page, structure.bodies.map(centre));
  const missed = [];
  for (let i = 0; i < structure.bodies.length; i++) {
    await page.mouse.move(at[i][0], at[i][1]);
    const info = await page.$eval("#info", (e) => (e.hidden ? "" : e.textContent));
    if (!info.includes(structure.bodies[i].id) || !/mass/.test(info) || !/contacts/.test(info)) missed.push(structure.bodies[i].id);
  }
  check(missed.length === 0, `hovering the centre of each of the ${at.length} bodies, forces on, shows its id, mass and contacts`, missed.join(", "));
  await page.screenshot({ path: path.join(shots, "pyramid-hover.png") });
  await page.click("#toggle-forces");
  await page.mouse.move(1, 1);
}

// Zoom and pan change the view; fit brings it back.
async function testZoom(page) {
  const vb = () => page.$eval("#view", (v) => v.dataset.view);
  const start = await vb();
  await page.click("#zin");
  const zoomed = (await vb()).split(" ").map(Number);
  check(zoomed[2] < start.split(" ").map(Number)[2], "the zoom button zooms in");
  const r = await page.$eval("#view", (v) => { const b = v.getBoundingClientRect(); return [b.x + b.width / 2, b.y + b.height / 2]; });
  await page.mouse.move(r[0], r[1]);
  await page.mouse.wheel(0, 400);
  await page.waitForFunction((w) => +document.getElementById("view").dataset.view.split(" ")[2] > w, zoomed[2], { timeout: 5000 }).catch(() => {});
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
  await testHover(page, structure);
  await testZoom(page);
  await testPlay(page, structure, plan);
  await page.screenshot({ path: path.join(shots, "pyramid-end.png") });
  check(errors.length === 0, "no script errors and no network requests", errors.join("; "));
  await ctx.close();
}

// A plan verify rejects: its failing step is shown in red.
async function testInvalid(browser) {
  const plan = readJson("column-bad-plan.json"), structure = readJson("column-bad.json");
  const { ctx, page, errors } = await open(browser, "column-bad.html", { width: 800, height: 600 });
  await setSlider(page, 0);
  check(await page.$eval("#banner", (b) => b.hidden), "no failure shown before the failing step");
  await setSlider(page, 1);
  const banner = await page.$eval("#banner", (b) => ({ hidden: b.hidden, text: b.textContent, bg: getComputedStyle(b).backgroundColor }));
  check(!banner.hidden && /do not stand/.test(banner.text), "the failing step names what falls", banner.text);
  check(banner.bg === "rgb(198, 40, 40)", "the failure banner is red", banner.bg);
  check(await page.$eval("#stepinfo", (s) => getComputedStyle(s).color) === "rgb(198, 40, 40)", "the step counter is red at the failing step");
  check((await drawnBodies(page, structure)).filter(Boolean).length === structure.bodies.length - 1, "the bodies that fall are still drawn at the failing step");
  check(plan.order.length === 3, "the bad plan removes the three blocks");
  await page.screenshot({ path: path.join(shots, "column-bad.png") });
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

// Certificates edited in the plan file (a negative normal force at the
// first step): that step is flagged and its forces not drawn; the others are.
async function testTampered(browser) {
  const { ctx, page, errors } = await open(browser, "pyramid-neg.html", { width: 1000, height: 700 });
  await setSlider(page, 0);
  const first = await page.$eval("#banner", (b) => ({ hidden: b.hidden, text: b.textContent }));
  check(!first.hidden && /FAIL/.test(first.text), "the edited step says its forces fail their check", first.text);
  check(/FAIL/.test(await page.$eval("#stepinfo", (s) => s.textContent)), "the step counter says FAIL at the edited step");
  check(/FAIL/.test(await page.$eval("#summary", (s) => s.textContent)), "the header names the failing forces");
  await page.click("#toggle-forces");
  check(await countColour(page, BLUE) === 0, "the failing forces are not drawn");
  await setSlider(page, 1);
  check(await page.$eval("#banner", (b) => b.hidden), "the next step, untouched, is not flagged");
  check(await countColour(page, BLUE) > 20, "the next step's forces are drawn");
  await page.screenshot({ path: path.join(shots, "pyramid-neg.png") });
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

// A plan with status none: the slider takes apart the buildable part; the
// bodies that cannot be removed stay drawn at every step.
async function testNone(browser) {
  const structure = readJson("arch.json"), plan = readJson("arch-plan.json");
  const { ctx, page, errors } = await open(browser, "arch.html", { width: 1000, height: 700 });
  const ids = structure.bodies.map((b) => b.id), blocked = new Set(plan.blocked.map((id) => ids.indexOf(id)));
  const movable = structure.bodies.filter((b) => !b.fixed).length;
  check(await page.$eval("#slider", (s) => +s.max) === movable - blocked.size,
        "the slider has one position per body of the buildable part", movable - blocked.size);
  await setSlider(page, 0);
  const atStart = await drawnBodies(page, structure);
  check(atStart.every(Boolean), "every body is drawn at the start");
  await setSlider(page, movable - blocked.size);
  const atEnd = await drawnBodies(page, structure);
  const wrong = atEnd.map((d, i) => (d !== (blocked.has(i) || !!structure.bodies[i].fixed) ? ids[i] : null)).filter((x) => x);
  check(wrong.length === 0, "at the end only the bodies that cannot be removed (and fixed ones) are left", wrong.join(", "));
  await page.screenshot({ path: path.join(shots, "arch-none.png") });
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

// A plan with hands: the slider steps through its actions; at each the
// counter names the action and the bodies held after it (counted here from
// the plan file's actions), and only the placed bodies are painted.
async function testHands(browser) {
  const structure = readJson("arch-hands.json"), plan = readJson("arch-hands-plan.json");
  const { ctx, page, errors } = await open(browser, "arch-hands.html", { width: 1000, height: 700 });
  const ids = structure.bodies.map((b) => b.id), n = plan.actions.length;
  check(await page.$eval("#slider", (s) => +s.max) === n, "the slider has one position per action", n);
  const held = new Set(), placed = new Set(), bad = [], counts = new Set();
  for (let p = 0; p <= n; p++) {
    if (p > 0) {
      const [verb, id] = plan.actions[p - 1];
      if (verb === "release") held.delete(id); else held.add(id);
      if (verb === "place") placed.add(id);
    }
    await setSlider(page, p);
    const text = await page.$eval("#stepinfo", (e) => e.textContent);
    const want = `action ${p}/${n}: ` + (p ? plan.actions[p - 1].join(" ") : "nothing placed") + ` \u2014 held ${held.size}/${plan.hands}`;
    if (!text.startsWith(want)) bad.push(`${p}: '${text}', wanted '${want}'`);
    const drawn = await drawnBodies(page, structure);
    const wrong = drawn.map((d, i) => (d !== (placed.has(ids[i]) || !!structure.bodies[i].fixed) ? ids[i] : null)).filter((x) => x);
    if (wrong.length) bad.push(`${p}: painted wrongly: ${wrong.join(", ")}`);
    counts.add(held.size);
  }
  check(bad.length === 0, `counter and painted bodies match the actions at all ${n + 1} positions`, bad.join("; "));
  check(counts.has(2) && counts.has(0), "stepping changes the held count (0 and 2 seen)", [...counts].join(","));
  await setSlider(page, 0);
  const t0 = await page.$eval("#stepinfo", (e) => e.textContent);
  await page.click("#next");
  await page.click("#next");
  const t2 = await page.$eval("#stepinfo", (e) => e.textContent);
  check(t0 !== t2 && t2.startsWith(`action 2/${n}`), "the next button steps through actions", t2);
  await page.screenshot({ path: path.join(shots, "arch-hands.png") });
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

// Hostile ids: nothing runs, the ids read back as text.
async function testIds(browser) {
  const structure = readJson("ids.json");
  const { ctx, page, errors } = await open(browser, "ids.html", { width: 800, height: 600 });
  check(!(await page.evaluate(() => window.pwned)), "an id cannot run a script");
  check(await page.$$eval("script", (s) => s.length) === 2, "the page has its two script elements only");
  const got = [], at = await toScreen(page, structure.bodies.map(centre));
  for (let i = 0; i < structure.bodies.length; i++) {
    await page.mouse.move(at[i][0], at[i][1]);
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
  const box = await page.$eval("#view", (v) => { const r = v.getBoundingClientRect(); return [r.width, r.height]; });
  check(box[0] >= 350 && box[1] >= 200, "the drawing fills the phone's screen", box.join("x"));
  const at = (await toScreen(page, [centre(structure.bodies[0])]))[0];
  await page.touchscreen.tap(at[0], at[1]);
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
    await testTampered(browser);
    await testNone(browser);
    await testHands(browser);
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
