// Drives Patina's viewer (patina-texgen view) in Debian's chromium through Playwright, for
// the tests and the benchmark: opens DIR/index.html from the folder (file://), waits for the
// first frame and runs the ACTION, printing one JSON object on stdout.
//   node viewer_page.mjs DIR screenshot OUT.png [AGE]      the canvas at an age
//   node viewer_page.mjs DIR probe AGE X Y W H VIEW        mean canvas colour of a rectangle
//                                                          (fractions of the canvas)
//   node viewer_page.mjs DIR frames N [VIEW [AGE]]          frame times of N frames
//   node viewer_page.mjs DIR compare AGE VIEW REF.png X Y W H FX FY FZ TX TY TZ FOV [ENV]
//        the camera at F looking at T (vertical field of view FOV degrees) under the
//        viewer's environment ENV (an index, default 0: the lookdev sky), the canvas and
//        REF.png (a patina-render display PNG of the same view) measured in the same
//        rectangle: their CIELAB and CIEDE2000
//   node viewer_page.mjs DIR layout W H                    at a W x H window: the asset's
//        bounding box as drawn, the canvas's and the control panel's rectangles (page px)
//   node viewer_page.mjs DIR aliasing                      the canvas with antialiasing on
//        and off: the staircase corners of slanted edges, counted in each: pixels with a
//        hard step (luma differing by more than 0.7 of the picture's largest step between
//        neighbours) both to a side and above or below (a straight edge along the pixel
//        grid has none)
// Fails (exit 1) on a console error, a page error or a viewer that reports a failure.
import { chromium } from 'playwright-core';
import path from 'node:path';
import { pathToFileURL } from 'node:url';
import { readFileSync } from 'node:fs';

const [dir, action, ...args] = process.argv.slice(2);

/// CIEDE2000 (Sharma, Wu & Dalal 2005, Eq. 1-22).
function deltaE2000([L1, a1, b1], [L2, a2, b2]) {
  const rad = Math.PI / 180, deg = 180 / Math.PI;
  const C1 = Math.hypot(a1, b1), C2 = Math.hypot(a2, b2), Cm = (C1 + C2) / 2;
  const G = 0.5 * (1 - Math.sqrt(Cm ** 7 / (Cm ** 7 + 25 ** 7)));
  const ap1 = (1 + G) * a1, ap2 = (1 + G) * a2;
  const Cp1 = Math.hypot(ap1, b1), Cp2 = Math.hypot(ap2, b2);
  const h = (b, a) => (a === 0 && b === 0 ? 0 : (Math.atan2(b, a) * deg + 360) % 360);
  const hp1 = h(b1, ap1), hp2 = h(b2, ap2);
  const dL = L2 - L1, dC = Cp2 - Cp1;
  let dh = 0;
  if (Cp1 * Cp2 !== 0) dh = Math.abs(hp2 - hp1) <= 180 ? hp2 - hp1 : (hp2 <= hp1 ? hp2 - hp1 + 360 : hp2 - hp1 - 360);
  const dH = 2 * Math.sqrt(Cp1 * Cp2) * Math.sin(dh / 2 * rad);
  const Lm = (L1 + L2) / 2, Cpm = (Cp1 + Cp2) / 2;
  let hm = hp1 + hp2;
  if (Cp1 * Cp2 !== 0) hm = Math.abs(hp1 - hp2) <= 180 ? hm / 2 : (hm < 360 ? (hm + 360) / 2 : (hm - 360) / 2);
  const T = 1 - 0.17 * Math.cos((hm - 30) * rad) + 0.24 * Math.cos(2 * hm * rad) +
            0.32 * Math.cos((3 * hm + 6) * rad) - 0.2 * Math.cos((4 * hm - 63) * rad);
  const dTheta = 30 * Math.exp(-(((hm - 275) / 25) ** 2));
  const RC = 2 * Math.sqrt(Cpm ** 7 / (Cpm ** 7 + 25 ** 7));
  const SL = 1 + 0.015 * (Lm - 50) ** 2 / Math.sqrt(20 + (Lm - 50) ** 2);
  const SC = 1 + 0.045 * Cpm, SH = 1 + 0.015 * Cpm * T;
  const RT = -Math.sin(2 * dTheta * rad) * RC;
  return Math.sqrt((dL / SL) ** 2 + (dC / SC) ** 2 + (dH / SH) ** 2 + RT * (dC / SC) * (dH / SH));
}

/// CIELAB (D65 white) of an 8-bit sRGB colour: IEC 61966-2-1 decoding, the sRGB matrix to
/// XYZ, CIE 15 Lab.
function srgbToLab(rgb) {
  const lin = rgb.map((c) => { const e = c / 255; return e <= 0.04045 ? e / 12.92 : ((e + 0.055) / 1.055) ** 2.4; });
  const xyz = [
    0.4124 * lin[0] + 0.3576 * lin[1] + 0.1805 * lin[2],
    0.2126 * lin[0] + 0.7152 * lin[1] + 0.0722 * lin[2],
    0.0193 * lin[0] + 0.1192 * lin[1] + 0.9505 * lin[2],
  ];
  const white = [0.95047, 1.0, 1.08883];
  const f = (t) => (t > (6 / 29) ** 3 ? Math.cbrt(t) : t / (3 * (6 / 29) ** 2) + 4 / 29);
  const [fx, fy, fz] = xyz.map((v, i) => f(v / white[i]));
  return [116 * fy - 16, 500 * (fx - fy), 200 * (fy - fz)];
}
const executablePath = process.env.PATINA_CHROMIUM || '/usr/bin/chromium';
const errors = [];
let browser;
try {
  browser = await chromium.launch({
    executablePath,
    // WebGL through SwiftShader: no GPU on a build machine.
    // PATINA_NO_WEBGL=1: a browser without WebGL, to see the page say so.
    args: ['--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
           ...(process.env.PATINA_NO_WEBGL ? ['--disable-3d-apis'] : [])],
  });
} catch (e) {
  console.error(`cannot start ${executablePath}: install Debian's chromium (scripts/bootstrap.sh): ${e.message}`);
  process.exit(1);
}
const page = await browser.newPage({ viewport: { width: 1280, height: 720 } });
page.on('console', (m) => { if (m.type() === 'error') errors.push(`console: ${m.text()}`); });
page.on('pageerror', (e) => errors.push(`page error: ${e.message}`));
const opened = Date.now();
await page.goto(pathToFileURL(path.resolve(dir, 'index.html')).href);
await page.waitForFunction(() => window.patinaViewer && (window.patinaViewer.ready || window.patinaViewer.failed),
                           null, { timeout: 120000 });
const failed = await page.evaluate(() => window.patinaViewer.failed);
const out = { firstFrameMs: await page.evaluate(() => window.patinaViewer.firstFrameMs),
              openToFirstFrameMs: Date.now() - opened };

/// In the page: a PNG (base64) decoded by the page's own image decoder, as a 2D canvas
/// context to read pixels from, with its size.
await page.evaluate(() => {
  globalThis.patinaDecodePng = async (b64) => {
    const img = new Image();
    img.src = `data:image/png;base64,${b64}`;
    await img.decode();
    const c = new OffscreenCanvas(img.width, img.height);
    const g = c.getContext('2d');
    g.drawImage(img, 0, 0);
    return { g, width: img.width, height: img.height };
  };
});

/// The mean 8-bit sRGB colour of a PNG (bytes) in a rectangle given in fractions of it.
async function regionMean(png, x, y, w, h) {
  return page.evaluate(async ([b64, fx, fy, fw, fh]) => {
    const img = await globalThis.patinaDecodePng(b64);
    const x0 = Math.round(fx * img.width), y0 = Math.round(fy * img.height);
    const d = img.g.getImageData(x0, y0, Math.max(1, Math.round(fw * img.width)), Math.max(1, Math.round(fh * img.height))).data;
    const m = [0, 0, 0];
    for (let i = 0; i < d.length; i += 4) for (let k = 0; k < 3; ++k) m[k] += d[i + k];
    return m.map((v) => v / (d.length / 4));
  }, [Buffer.from(png).toString('base64'), Number(x), Number(y), Number(w), Number(h)]);
}

/// Waits until `n` more frames are drawn.
async function frames(n) {
  const start = await page.evaluate(() => window.patinaViewer.frames);
  await page.waitForFunction((s) => window.patinaViewer.frames >= s, start + n, { timeout: 120000 });
}

if (!failed) {
  if (action === 'screenshot') {
    if (args[1] !== undefined) await page.evaluate((a) => window.patinaViewer.setAge(a), Number(args[1]));
    await frames(3);
    await page.locator('#view').screenshot({ path: args[0] });
    out.screenshot = args[0];
  } else if (action === 'probe') {
    const [age, x, y, w, h, view] = args;
    await page.evaluate(([a, v]) => { window.patinaViewer.setAge(a); if (v) window.patinaViewer.setView(v); },
                        [Number(age), view]);
    await frames(3);
    const png = await page.locator('#view').screenshot();
    out.mean = await regionMean(png, x, y, w, h);
    out.lab = srgbToLab(out.mean);
    out.hue_deg = (Math.atan2(out.lab[2], out.lab[1]) * 180 / Math.PI + 360) % 360;
  } else if (action === 'compare') {
    const [age, view, ref, x, y, w, h, ...cam] = args;
    const [fx, fy, fz, tx, ty, tz, fov, env] = cam.map(Number);
    await page.evaluate(([a, v, c, e]) => {
      window.patinaViewer.setAge(a);
      window.patinaViewer.setView(v);
      window.patinaViewer.setEnvironment(e);
      window.patinaViewer.setCamera(c.slice(0, 3), c.slice(3, 6), c[6]);
    }, [Number(age), view, [fx, fy, fz, tx, ty, tz, fov], env || 0]);
    await frames(3);
    const png = await page.locator('#view').screenshot();
    out.viewer = srgbToLab(await regionMean(png, x, y, w, h));
    out.render = srgbToLab(await regionMean(readFileSync(ref), x, y, w, h));
    out.de2000 = deltaE2000(out.viewer, out.render);
    out.hue_viewer = (Math.atan2(out.viewer[2], out.viewer[1]) * 180 / Math.PI + 360) % 360;
    out.hue_render = (Math.atan2(out.render[2], out.render[1]) * 180 / Math.PI + 360) % 360;
  } else if (action === 'layout') {
    await page.setViewportSize({ width: Number(args[0]), height: Number(args[1]) });
    await frames(3);
    Object.assign(out, await page.evaluate(() => window.patinaViewer.assetRect()));
    out.panel = await page.evaluate(() => {
      const r = document.getElementById('panel').getBoundingClientRect();
      return [r.left, r.top, r.right, r.bottom];
    });
    out.window = [Number(args[0]), Number(args[1])];
  } else if (action === 'aliasing') {
    const shots = {};
    for (const on of [false, true]) {
      await page.evaluate((a) => window.patinaViewer.setAntialias(a), on);
      await frames(3);
      shots[on] = await page.locator('#view').screenshot();
    }
    const steps = await page.evaluate(async ([off, on]) => {
      const luma = async (b64) => {
        const img = await globalThis.patinaDecodePng(b64);
        const d = img.g.getImageData(0, 0, img.width, img.height).data;
        const y = new Float32Array(img.width * img.height);
        for (let i = 0; i < y.length; ++i) y[i] = 0.2126 * d[4 * i] + 0.7152 * d[4 * i + 1] + 0.0722 * d[4 * i + 2];
        return { y, w: img.width, h: img.height };
      };
      const a = await luma(off), b = await luma(on);
      let largest = 0;
      for (let i = 0; i + 1 < a.y.length; ++i) {
        if ((i + 1) % a.w) largest = Math.max(largest, Math.abs(a.y[i] - a.y[i + 1]));
        if (i + a.w < a.y.length) largest = Math.max(largest, Math.abs(a.y[i] - a.y[i + a.w]));
      }
      const corners = ({ y, w, h }) => {
        const hard = (i, j) => Math.abs(y[i] - y[j]) > 0.7 * largest;
        let n = 0;
        for (let r = 1; r + 1 < h; ++r)
          for (let c = 1; c + 1 < w; ++c) {
            const i = r * w + c;
            if ((hard(i, i - 1) || hard(i, i + 1)) && (hard(i, i - w) || hard(i, i + w))) ++n;
          }
        return n;
      };
      return { largest, off: corners(a), on: corners(b) };
    }, [Buffer.from(shots[false]).toString('base64'), Buffer.from(shots[true]).toString('base64')]);
    Object.assign(out, steps);
  } else if (action === 'frames') {
    // A view and an age for the viewer (the bare page of the benchmark has neither).
    await page.evaluate(([v, a]) => {
      if (v && window.patinaViewer.setView) window.patinaViewer.setView(v);
      if (a !== undefined && window.patinaViewer.setAge) window.patinaViewer.setAge(a);
    }, [args[1], args[2] === undefined ? undefined : Number(args[2])]);
    await frames(5);
    await page.evaluate(() => { window.patinaViewer.frameTimes.length = 0; });
    await frames(Number(args[0]));
    out.frameTimes = await page.evaluate(() => window.patinaViewer.frameTimes.slice());
  } else {
    errors.push(`unknown action '${action}'`);
  }
}
if (failed) {
  out.failed = failed;
  out.message = await page.locator('#message').textContent();
  errors.push(`viewer: ${failed}`);
}
await browser.close();
console.log(JSON.stringify(out));
if (errors.length) {
  console.error(errors.join('\n'));
  process.exit(1);
}
