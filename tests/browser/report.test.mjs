// Opens the HTML reports written by the built `kontur` in headless Chromium (Debian's
// /usr/bin/chromium, driven by playwright-core) as a person would: the page loads from disk with
// no console error and no network request, every plot is drawn, and a screenshot of each report
// is saved (build/test-artifacts/report-*.png).
//   KONTUR_BINARY=build/bin/kontur node --test tests/browser/report.test.mjs
// Exit code 77 (ctest SKIP_RETURN_CODE) when Chromium or playwright-core is missing.
import { test, before, after } from "node:test";
import assert from "node:assert/strict";
import { execFileSync } from "node:child_process";
import { existsSync, mkdirSync, mkdtempSync, rmSync } from "node:fs";
import { tmpdir } from "node:os";
import { dirname, join, resolve } from "node:path";
import { fileURLToPath, pathToFileURL } from "node:url";

const here = dirname(fileURLToPath(import.meta.url));
const root = resolve(here, "..", "..");
const chromium = process.env.KONTUR_CHROMIUM || "/usr/bin/chromium";
const binary = process.env.KONTUR_BINARY || join(root, "build", "bin", "kontur");
const artifacts = process.env.KONTUR_ARTIFACTS || join(root, "build", "test-artifacts");

let playwright;
try {
  playwright = await import("playwright-core");
} catch {
  console.log("SKIP: playwright-core is not installed (run scripts/install-deps.sh)");
  process.exit(77);
}
if (!existsSync(chromium)) {
  console.log(`SKIP: ${chromium} is missing (run scripts/install-deps.sh)`);
  process.exit(77);
}
assert.ok(existsSync(binary), `kontur binary ${binary} not found (set KONTUR_BINARY)`);

const work = mkdtempSync(join(tmpdir(), "kontur-report-"));
mkdirSync(artifacts, { recursive: true });
let context;

before(async () => {
  // A fresh profile (user-data-dir) in a temporary directory for every run.
  context = await playwright.chromium.launchPersistentContext(join(work, "profile"), {
    executablePath: chromium,
    headless: true,
    viewport: { width: 1400, height: 1000 },
    args: ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
           "--disable-background-networking", "--disable-component-update", "--disable-sync"],
  });
});

after(async () => {
  if (context) await context.close();
  rmSync(work, { recursive: true, force: true });
});

// name, kontur arguments, and the number of 2-D plots the report must draw besides the 3-D view
// and its three projections.
const reports = [
  ["spline", ["spline", "examples/curves/seed_example1.json", "--step", "0.05"], 2],
  ["arc", ["arc", "110,100,50", "100,110,50", "90,100,50", "--omega", "0.5", "--steps", "4"], 4],
  ["arc-feed", ["arc", "100,200,300", "200,250,310", "260,180,400", "--feed", "600", "--period", "0.01"], 4],
  ["conic", ["conic", "105,200,300", "104,201.08,301.44", "103,201.44,301.92", "100,201.8,302.4",
             "96,201.08,301.44", "--omega", "0.5", "--steps", "4"], 4],
  // kontur run: path speed against the feed, axis velocity, acceleration, jerk, chord error.
  ["run", ["run", "examples/programs/square_arc.ngc", "-o", join(work, "run.csv"), "--quiet"], 5],
];

for (const [name, args, plots2d] of reports) {
  test(`report ${name} opens offline and draws every plot`, async () => {
    const file = join(work, `${name}.html`);
    execFileSync(binary, [...args, "--report", file], { cwd: root, stdio: ["ignore", "ignore", "inherit"] });
    const url = pathToFileURL(file).href;
    const page = await context.newPage();
    const errors = [];
    const requests = [];
    page.on("console", (m) => { if (m.type() === "error") errors.push(m.text()); });
    page.on("pageerror", (e) => errors.push(String(e)));
    page.on("request", (r) => { if (r.url() !== url) requests.push(r.url()); });
    await page.goto(url, { waitUntil: "load" });
    await page.waitForSelector("body[data-kontur-ready='1']", { timeout: 20000 });
    const expected = 4 + plots2d;
    const drawn = await page.evaluate(() => Array.from(document.querySelectorAll(".js-plotly-plot")).map((d) => ({
      id: d.id, svg: d.querySelectorAll("svg.main-svg").length, canvas: d.querySelectorAll("canvas").length,
      traces: d.querySelectorAll(".trace, .scatterlayer path").length,
    })));
    assert.equal(drawn.length, expected, `plots drawn: ${JSON.stringify(drawn)}`);
    for (const d of drawn) assert.ok(d.svg > 0, `plot ${d.id} has no svg`);
    const scene = drawn.find((d) => d.id === "scene3d");
    assert.ok(scene && scene.canvas > 0, "the 3-D view has no WebGL canvas");
    // The summary and the tables are filled.
    assert.ok(await page.locator("#summary tr").count() >= 2);
    assert.ok(await page.locator("#tables table.data tr").count() >= 2);
    await page.screenshot({ path: join(artifacts, `report-${name}.png`), fullPage: false });
    // A screenshot of every plot on its own (build/test-artifacts/report-NAME-ID.png).
    for (const d of drawn) {
      const plot = page.locator(`#${d.id}`);
      await plot.scrollIntoViewIfNeeded();
      await plot.screenshot({ path: join(artifacts, `report-${name}-${d.id}.png`) });
    }
    await page.evaluate(() => window.scrollTo(0, 0));
    // Clicking a row of a linked table marks its x on the linked plots and its point in the views.
    const row = page.locator("tr.link").nth(1);
    await row.click();
    assert.equal(await row.getAttribute("class"), "link selected");
    const marks = await page.evaluate(() => ({
      plots: Array.from(document.querySelectorAll("#plots .js-plotly-plot")).filter((d) =>
        (d.layout.shapes || []).some((s) => s.line && s.line.color === "#ff6f00")).length,
      scene: (() => { const d = document.getElementById("scene3d").data; return d[d.length - 1].x.length; })(),
    }));
    assert.ok(marks.plots >= 1, `no plot marked: ${JSON.stringify(marks)}`);
    if (name === "run") {
      // A block's row shades its time span on every time plot and zooms them to it.
      const zoom = await page.evaluate(() => Array.from(document.querySelectorAll("#plots .js-plotly-plot")).map((d) => ({
        rect: (d.layout.shapes || []).some((s) => s.type === "rect" && s.fillcolor === "#ff6f00"),
        range: d.layout.xaxis.range,
      })));
      for (const z of zoom) {
        assert.ok(z.rect, `block span not shaded: ${JSON.stringify(zoom)}`);
        assert.ok(z.range[1] - z.range[0] < 5, `not zoomed to the block: ${JSON.stringify(z.range)}`);
      }
      // The block table has a row per move of the path: the program's 8 and the 2 blends where
      // the tangent arc meets its lines.
      assert.equal(await page.locator("#tables table.data tr.link").count(), 10);
    }
    assert.equal(marks.scene, 1, "the selected point is not marked in the 3-D view");
    assert.deepEqual(errors, [], "console errors");
    assert.deepEqual(requests, [], "network requests other than the report itself");
    await page.close();
  });
}
