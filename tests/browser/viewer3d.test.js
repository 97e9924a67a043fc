// The HTML plan viewer's 3D view in a real browser: headless Chromium
// (software rendering) driven by playwright-core. Run by tests/browser/run.sh
// after viewer.test.js, on 3D pages it made with the built CLI:
//   node viewer3d.test.js PLAYWRIGHT_DIR CHROMIUM WORK_DIR
// Bodies are located on screen from the structure files (their vertices)
// and the view the canvas reports (data-view: az el k ox oy, the
// orthographic projection of src/render/viewer3.js); what is expected comes
// from the structure and plan files, never from the page's data. Prints
// one line per check; exits 1 on any failure.
"use strict";
const fs = require("fs");
const path = require("path");

const [pwDir, chromiumPath, work] = process.argv.slice(2);
const shots = path.join(work, "shots");
fs.mkdirSync(shots, { recursive: true });
let pass = 0, fail = 0;
function check(cond, what, detail) {
  if (cond) { pass++; console.log("ok   3D: " + what); }
  else { fail++; console.log("FAIL 3D: " + what + (detail !== undefined ? " (" + detail + ")" : "")); }
}
const readJson = (f) => JSON.parse(fs.readFileSync(path.join(work, f), "utf8"));
const frames = (page) => page.evaluate(() => new Promise((res) => requestAnimationFrame(() => requestAnimationFrame(res))));

// The centre of a body's top face (its vertices of largest z) and that z.
function topCentre(b) {
  const v = b.vertices, z = Math.max(...v.map((p) => p[2])), top = v.filter((p) => p[2] > z - 1e-9);
  return [top.reduce((s, p) => s + p[0], 0) / top.length, top.reduce((s, p) => s + p[1], 0) / top.length, z];
}
// World points to page pixels by the canvas's data-view.
async function toScreen(page, pts) {
  return page.$eval("#view", (c, pts) => {
    const r = c.getBoundingClientRect(), [az, el, k, ox, oy] = c.dataset.view.split(" ").map(Number), D = Math.PI / 180;
    const e = [Math.sin(az * D) * Math.cos(el * D), -Math.cos(az * D) * Math.cos(el * D), Math.sin(el * D)];
    const rr = [Math.cos(az * D), Math.sin(az * D), 0];
    const u = [e[1] * rr[2] - e[2] * rr[1], e[2] * rr[0] - e[0] * rr[2], e[0] * rr[1] - e[1] * rr[0]];
    const dot = (a, b) => a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
    return pts.map((p) => [r.left + ox + k * dot(p, rr), r.top + oy - k * dot(p, u)]);
  }, pts);
}
// Canvas pixels within 12 (sum of channels) of a colour; painted pixels.
async function countColour(page, rgb) {
  await frames(page);
  return page.$eval("#view", (c, rgb) => {
    const d = c.getContext("2d").getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4)
      if (rgb ? Math.abs(d[i] - rgb[0]) + Math.abs(d[i + 1] - rgb[1]) + Math.abs(d[i + 2] - rgb[2]) < 12 && d[i + 3] > 128
              : d[i + 3] > 128 && !(d[i] >= 250 && d[i + 1] >= 250 && d[i + 2] >= 250)) n++;
    return [n, c.width * c.height];
  }, rgb);
}
const BLUE = [31, 78, 156], MAGENTA = [196, 0, 150], RED = [198, 40, 40];
const dataset = (page, key) => page.$eval("#view", (c, key) => c.dataset[key], key);

async function open(browser, file, touch) {
  const ctx = await browser.newContext(touch ? { viewport: { width: 390, height: 740 }, hasTouch: true, isMobile: true }
                                             : { viewport: { width: 1000, height: 700 } });
  const page = await ctx.newPage();
  const errors = [];
  page.on("pageerror", (e) => errors.push(String(e)));
  page.on("request", (r) => { if (!r.url().startsWith("file:")) errors.push("network: " + r.url()); });
  await page.goto("file://" + path.join(work, file));
  await page.waitForSelector("body[data-ready='1']", { timeout: 30000 });
  return { ctx, page, errors };
}
async function setSlider(page, p) {
  await page.$eval("#slider", (s, v) => { s.value = String(v); s.dispatchEvent(new Event("input", { bubbles: true })); }, p);
  await frames(page);
}
async function hoverId(page, at) {
  await page.mouse.move(at[0], at[1]);
  return page.$eval("#info", (e) => (e.hidden ? "" : e.querySelector("div").textContent.replace(/^id /, "")));
}

// The slider: at position p the page draws the bodies the plan leaves,
// and the body step p + 1 removes is under the pointer at its top face
// (checked where no body still present is higher: nothing can hide that
// face then); one step later it is gone from there.
async function testSteps(page, structure, plan) {
  const n = plan.order.length, ids = structure.bodies.map((b) => b.id), bad = [];
  check(await page.$eval("#slider", (s) => +s.max) === n, "slider has one position per step", n);
  let checked = 0;
  for (let p = 0; p < n; p++) {
    await setSlider(page, p);
    if (+(await dataset(page, "drawn")) !== structure.bodies.length - p) bad.push(`${p}: data-drawn`);
    const gone = new Set(plan.order.slice(0, p)), b = structure.bodies[ids.indexOf(plan.order[p])], top = topCentre(b);
    if (structure.bodies.some((o) => !gone.has(o.id) && Math.max(...o.vertices.map((v) => v[2])) > top[2] + 1e-9)) continue;
    checked++;
    const at = (await toScreen(page, [top]))[0];
    if ((await hoverId(page, at)) !== b.id) bad.push(`${p}: ${b.id} not under the pointer`);
    await setSlider(page, p + 1);
    if ((await hoverId(page, at)) === b.id) bad.push(`${p + 1}: ${b.id} still under the pointer`);
  }
  await page.mouse.move(1, 1);
  check(bad.length === 0 && checked >= n / 2, `each step removes its body from the picture (${checked} of ${n} steps checked by hover)`, bad.join("; "));
  await setSlider(page, 0);
  const full = (await countColour(page))[0];
  await setSlider(page, n);
  const empty = (await countColour(page))[0];
  check(empty < full / 4, "the painted area shrinks to the ground grid at the end", `${full} -> ${empty}`);
  await setSlider(page, 0);
}

async function testHoverInfo(page, structure) {
  const b = structure.bodies[0], at = (await toScreen(page, [topCentre(structure.bodies[structure.bodies.length - 1])]))[0];
  await page.mouse.move(at[0], at[1]);
  const info = await page.$eval("#info", (e) => (e.hidden ? "" : e.textContent));
  const last = structure.bodies[structure.bodies.length - 1].id;
  check(info.startsWith("id " + last) && /mass/.test(info) && /contacts \d+ \(with /.test(info), "hover shows the body's id, mass and contacts", info);
  await page.mouse.move(1, 1);
  check(await page.$eval("#info", (e) => e.hidden), "the info box hides off the bodies", b.id);
}

async function testForces(page) {
  await setSlider(page, 0);
  check((await countColour(page, BLUE))[0] === 0, "no arrows before the force toggle");
  await page.click("#toggle-forces");
  const blue = (await countColour(page, BLUE))[0];
  check(blue > 20 && +(await dataset(page, "arrows")) > 0, "the force toggle draws blue normal-force arrows", blue);
  await page.screenshot({ path: path.join(shots, "3d-pyramid-forces.png") });
  await page.selectOption("#force-style", "resultants");
  const perPair = +(await dataset(page, "arrows"));
  await page.selectOption("#force-style", "contacts");
  const perContact = +(await dataset(page, "arrows"));
  check(perPair > 0 && perPair < perContact, "resultants: fewer arrows, one per touching pair", `${perPair} < ${perContact}`);
  await page.click("#toggle-forces");
  check((await countColour(page, BLUE))[0] === 0, "toggling off removes the arrows");
}

// Orbit (drag), pan (shift-drag, right-drag), zoom (wheel, button), fit.
async function testView(page) {
  const view = async () => (await dataset(page, "view")).split(" ").map(Number);
  const start = await view();
  const r = await page.$eval("#view", (v) => { const b = v.getBoundingClientRect(); return [b.x + b.width / 2, b.y + b.height / 2]; });
  const drag = async (dx, dy, opts) => {
    await page.mouse.move(r[0], r[1]);
    await page.mouse.down(opts);
    await page.mouse.move(r[0] + dx, r[1] + dy, { steps: 5 });
    await page.mouse.up(opts);
    await frames(page);
  };
  const before = (await countColour(page))[0];
  await drag(80, 30);
  const orbited = await view();
  check(orbited[0] !== start[0] && orbited[1] !== start[1], "dragging orbits (azimuth and elevation change)", orbited.join(" "));
  check((await countColour(page))[0] !== before, "the orbited picture differs");
  await page.screenshot({ path: path.join(shots, "3d-pyramid-orbit.png") });
  await page.keyboard.down("Shift");
  await drag(40, 20);
  await page.keyboard.up("Shift");
  const panned = await view();
  check(panned[0] === orbited[0] && panned[1] === orbited[1] && (panned[3] !== orbited[3] || panned[4] !== orbited[4]),
        "shift-drag pans without turning", panned.join(" "));
  await drag(-30, 10, { button: "right" });
  const right = await view();
  check(right[0] === panned[0] && right[3] !== panned[3], "right-drag pans", right.join(" "));
  await page.mouse.move(r[0], r[1]);
  await page.mouse.wheel(0, -400);
  await page.waitForFunction((k) => +document.getElementById("view").dataset.view.split(" ")[2] > k, right[2], { timeout: 5000 }).catch(() => {});
  check((await view())[2] > right[2], "the wheel zooms in");
  const k0 = (await view())[2];
  await page.click("#zout");
  check((await view())[2] < k0, "the zoom button zooms out");
  await page.click("#zfit");
  check((await view()).join(" ") === start.join(" "), "fit restores the first view");
}

async function testPlay(page, plan) {
  await setSlider(page, 0);
  await page.selectOption("#speed", "8");
  await page.click("#play");
  await page.waitForFunction((m) => +document.getElementById("view").dataset.step === m &&
                             document.getElementById("play").dataset.playing === "0", plan.order.length, { timeout: 60000 });
  check(+(await dataset(page, "drawn")) === 0, "play runs to the end and stops with every body gone");
  await page.selectOption("#speed", "1");
}

async function testPyramid(browser) {
  const structure = readJson("pyr3.json"), plan = readJson("pyr3-plan.json");
  const { ctx, page, errors } = await open(browser, "pyr3.html");
  await page.screenshot({ path: path.join(shots, "3d-pyramid.png") });
  const [painted, all] = await countColour(page);
  check(painted > 0.05 * all, "the canvas is drawn (software rendering)", `${painted} of ${all} pixels painted`);
  await testSteps(page, structure, plan);
  await testHoverInfo(page, structure);
  await testForces(page);
  await testView(page);
  await testPlay(page, plan);
  check(errors.length === 0, "no script errors and no network requests", errors.join("; "));
  await ctx.close();
}

// Hands: the bodies held after each action (counted here from the plan
// file's actions) are marked in magenta, and only placed bodies drawn.
async function testHands(browser) {
  const structure = readJson("pyr3.json"), plan = readJson("pyr3-hands-plan.json");
  const { ctx, page, errors } = await open(browser, "pyr3-hands.html");
  const n = plan.actions.length, held = new Set(), bad = [];
  let placed = 0, marked = 0;
  check(await page.$eval("#slider", (s) => +s.max) === n, "the slider has one position per action", n);
  for (let p = 0; p <= n; p++) {
    if (p > 0) {
      const [verb, id] = plan.actions[p - 1];
      if (verb === "release") held.delete(id); else held.add(id);
      if (verb === "place") placed++;
    }
    await setSlider(page, p);
    const text = await page.$eval("#stepinfo", (e) => e.textContent);
    const want = `action ${p}/${n}: ` + (p ? plan.actions[p - 1].join(" ") : "nothing placed") + ` \u2014 held ${held.size}/${plan.hands}`;
    if (!text.startsWith(want)) bad.push(`${p}: '${text}'`);
    if (+(await dataset(page, "held")) !== held.size || +(await dataset(page, "drawn")) !== placed) bad.push(`${p}: held or drawn count`);
    const magenta = (await countColour(page, MAGENTA))[0];
    if ((magenta > 0) !== (held.size > 0)) bad.push(`${p}: ${magenta} magenta pixels with ${held.size} held`);
    if (held.size) marked++;
    if (p === 1) await page.screenshot({ path: path.join(shots, "3d-hands.png") });
  }
  check(bad.length === 0 && marked > 0, `counter, drawn bodies and hand marks match the actions at all ${n + 1} positions`, bad.join("; "));
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

// An order verify rejects: the failing step is red (outlines in the fail
// colour, banner, counter), the step before is not.
async function testInvalid(browser) {
  const { ctx, page, errors } = await open(browser, "tower3-bad.html");
  await setSlider(page, 0);
  check((await countColour(page, RED))[0] === 0 && await page.$eval("#banner", (b) => b.hidden), "no red before the failing step");
  await setSlider(page, 1);
  const red = (await countColour(page, RED))[0];
  const banner = await page.$eval("#banner", (b) => ({ hidden: b.hidden, text: b.textContent, bg: getComputedStyle(b).backgroundColor }));
  check(red > 50, "the failing step is drawn in red", red);
  check(!banner.hidden && /do not stand/.test(banner.text) && banner.bg === "rgb(198, 40, 40)", "the red banner names what falls", banner.text);
  check(await page.$eval("#stepinfo", (s) => getComputedStyle(s).color) === "rgb(198, 40, 40)", "the step counter is red");
  await page.screenshot({ path: path.join(shots, "3d-tower-bad.png") });
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

// A certificate edited in the plan file: its step says FAIL and draws no
// arrows; the next step draws them.
async function testTampered(browser) {
  const { ctx, page, errors } = await open(browser, "pyr3-neg.html");
  await setSlider(page, 0);
  check(/FAIL/.test(await page.$eval("#banner", (b) => (b.hidden ? "" : b.textContent))), "the edited step says its forces fail their check");
  await page.click("#toggle-forces");
  check((await countColour(page, BLUE))[0] === 0, "the failing forces are not drawn");
  await setSlider(page, 1);
  check((await countColour(page, BLUE))[0] > 20, "the next step's forces are drawn");
  check(errors.length === 0, "no script errors", errors.join("; "));
  await ctx.close();
}

// A phone: a tap on a body's top face pins its id; a tap off the bodies unpins.
async function testPhone(browser) {
  const structure = readJson("pyr3.json"), top = structure.bodies[structure.bodies.length - 1];
  const { ctx, page, errors } = await open(browser, "pyr3.html", true);
  check(await page.evaluate(() => document.documentElement.scrollWidth) <= 390, "nothing wider than a phone's screen");
  const at = (await toScreen(page, [topCentre(top)]))[0];
  await page.touchscreen.tap(at[0], at[1]);
  await frames(page);
  const info = await page.$eval("#info", (e) => (e.hidden ? "" : e.textContent));
  check(info.startsWith("id " + top.id), "a tap shows the body's id", JSON.stringify(info));
  const corner = await page.$eval("#view", (v) => { const r = v.getBoundingClientRect(); return [r.left + 5, r.bottom - 5]; });
  await page.touchscreen.tap(corner[0], corner[1]);
  check(await page.$eval("#info", (e) => e.hidden), "a tap on empty space unpins it");
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
  try {
    await testPyramid(browser);
    await testHands(browser);
    await testInvalid(browser);
    await testTampered(browser);
    await testPhone(browser);
  } catch (e) {
    check(false, "the browser session ran to the end", String(e.stack || e));
  } finally {
    await browser.close();
  }
  console.log(`3D: ${pass} passed, ${fail} failed; screenshots in ${shots}`);
  process.exit(fail || pass === 0 ? 1 : 0);
}
main();
