// Patina's time-lapse viewer (docs/viewer.md): an exported glTF series with a continuous age
// slider, a before/after split, orbit camera, environments, exposure and the OCIO display
// transforms of patina-render. Everything it shows comes from data.js (patina-texgen view).
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';
import { OrbitControls } from 'three/examples/jsm/controls/OrbitControls.js';
import { blendAges } from './age_materials.js';
import { DisplayPass } from './display_pass.js';
import { ageScale } from './ages.js';

const $ = (id) => document.getElementById(id);

function fail(message) {
  $('message').textContent = message;
  document.body.classList.add('failed');
  window.patinaViewer = { failed: message };
}

function base64Bytes(text) {
  const bin = atob(text);
  const bytes = new Uint8Array(bin.length);
  for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
  return bytes;
}

function environmentTexture(env) {
  const data = new Float32Array(base64Bytes(env.rgba_f32).buffer);
  const texture = new THREE.DataTexture(data, env.width, env.height, THREE.RGBAFormat, THREE.FloatType);
  texture.mapping = THREE.EquirectangularReflectionMapping;
  texture.colorSpace = THREE.LinearSRGBColorSpace;
  texture.magFilter = THREE.LinearFilter;
  texture.needsUpdate = true;
  return texture;
}

async function start(data) {
  const started = performance.now();
  const canvas = $('view');
  // No multisampling: resolving a multisampled half-float target doubled the frame time in a
  // software WebGL (bench/README.md).
  const gl = canvas.getContext('webgl2', { antialias: false });
  if (!gl) {
    fail('This viewer needs WebGL2, which this browser does not offer: turn on hardware ' +
         'acceleration, or open the page in a current Firefox, Chrome or Safari.');
    return;
  }
  const renderer = new THREE.WebGLRenderer({ canvas, context: gl });
  renderer.setPixelRatio(1);
  renderer.toneMapping = THREE.NoToneMapping;
  const target = new THREE.WebGLRenderTarget(1, 1, { type: THREE.HalfFloatType });
  const scene = new THREE.Scene();
  const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 100);
  const controls = new OrbitControls(camera, canvas);
  const display = new DisplayPass(data.views);
  display.setView(data.default_view);
  document.title = `${data.title} — Patina viewer`;
  $('title').textContent = data.title;

  // The asset and its ages.
  const gltf = await new GLTFLoader().parseAsync(base64Bytes(data.model).buffer, '');
  scene.add(gltf.scene);
  const materials = await blendAges(gltf, data.ages.length);
  const ages = ageScale(data.ages, data.age_values, data.age_unit);

  // Frame the asset: seen a little from above, its bounding box's eight corners inside 90 %
  // of both fields of view; again when the window changes, until the user moves the camera.
  const box = new THREE.Box3().setFromObject(gltf.scene);
  const centre = box.getCenter(new THREE.Vector3());
  const radius = box.getSize(new THREE.Vector3()).length() / 2 || 1;
  let userMoved = false;
  controls.addEventListener('start', () => { userMoved = true; });
  function frameAsset() {
    const back = new THREE.Vector3(0, 0.38, 0.92).normalize();  // from the asset to the camera
    const right = new THREE.Vector3(0, 1, 0).cross(back).normalize();
    const up = back.clone().cross(right);
    const tanV = 0.9 * Math.tan(THREE.MathUtils.degToRad(camera.fov) / 2);
    const tanH = tanV * camera.aspect;
    let distance = 0;
    for (let i = 0; i < 8; ++i) {
      const o = new THREE.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y,
                                  i & 4 ? box.max.z : box.min.z).sub(centre);
      // A corner at (x, y) across and z towards the camera is in view from the distance
      // z + |x| / tan(h/2) (and the same for y): the largest over the corners.
      const z = o.dot(back);
      distance = Math.max(distance, z + Math.abs(o.dot(right)) / tanH, z + Math.abs(o.dot(up)) / tanV);
    }
    distance = Math.max(distance, 1e-3 * radius);
    camera.position.copy(centre).addScaledVector(back, distance);
    camera.near = distance / 100;
    camera.far = distance * 100;
    camera.updateProjectionMatrix();
    controls.target.copy(centre);
    controls.update();
  }

  // Environments: the sky as image-based light (PMREM) and background, its sun a light.
  const pmrem = new THREE.PMREMGenerator(renderer);
  const sun = new THREE.DirectionalLight(0xffffff, 0);
  scene.add(sun, sun.target);
  const environments = data.environments.map((env) => {
    const texture = environmentTexture(env);
    return { env, texture, light: pmrem.fromEquirectangular(texture).texture };
  });
  function setEnvironment(i) {
    const e = environments[i];
    scene.environment = e.light;
    scene.background = e.texture;
    sun.intensity = e.env.sun ? e.env.sun.irradiance : 0;
    if (e.env.sun) {
      const d = e.env.sun.direction;
      sun.position.set(centre.x + d[0] * radius * 4, centre.y + d[1] * radius * 4, centre.z + d[2] * radius * 4);
      sun.target.position.copy(centre);
    }
  }

  // Controls.
  const state = { age: ages.first, ageB: ages.last, split: false, exposure: 1, playing: false };
  const age = $('age'), ageB = $('age-b');
  for (const s of [age, ageB]) { s.min = ages.first; s.max = ages.last; s.step = (ages.last - ages.first) / 1000 || 1; }
  age.value = state.age;
  ageB.value = state.ageB;
  const label = (y) => ages.label(y);
  function syncLabels() {
    $('age-label').textContent = label(state.age);
    $('age-b-label').textContent = label(state.ageB);
    $('exposure-label').textContent = `${Math.log2(state.exposure).toFixed(1)} EV`;
  }
  age.addEventListener('input', () => { state.age = Number(age.value); syncLabels(); });
  ageB.addEventListener('input', () => { state.ageB = Number(ageB.value); syncLabels(); });
  $('split').addEventListener('change', (e) => { state.split = e.target.checked; document.body.classList.toggle('split', state.split); });
  $('exposure').addEventListener('input', (e) => { state.exposure = 2 ** Number(e.target.value); syncLabels(); });
  $('play').addEventListener('click', () => { state.playing = !state.playing; $('play').textContent = state.playing ? 'Pause' : 'Play'; });
  environments.forEach((e, i) => $('environment').add(new Option(e.env.name, i)));
  $('environment').addEventListener('change', (e) => setEnvironment(Number(e.target.value)));
  data.views.forEach((v) => $('display-view').add(new Option(v.name, v.name, false, v.name === data.default_view)));
  $('display-view').addEventListener('change', (e) => display.setView(e.target.value));
  $('antialias').addEventListener('change', (e) => { display.antialias = e.target.checked; });
  setEnvironment(0);
  syncLabels();

  function resize() {
    const w = canvas.clientWidth, h = canvas.clientHeight;
    if (canvas.width !== w || canvas.height !== h) {
      renderer.setSize(w, h, false);
      target.setSize(w, h);
      camera.aspect = w / h;
      camera.updateProjectionMatrix();
      if (!userMoved) frameAsset();
    }
  }

  function showAge(years) {
    const t = ages.stepOf(years);
    for (const m of materials) m.setStep(t);
  }

  // One frame: the scene at age A (and at age B right of the split) into the linear target,
  // then the display transform to the canvas.
  const api = { ready: false, frames: 0, frameTimes: [], firstFrameMs: null, materials: materials.length };
  let last = null;
  function frame(now) {
    resize();
    if (state.playing) {
      const span = ages.last - ages.first;
      state.age = ages.first + (((state.age - ages.first) + span * (last ? (now - last) / 8000 : 0)) % (span || 1));
      age.value = state.age;
      syncLabels();
    }
    if (last !== null) api.frameTimes.push(now - last);
    last = now;
    renderer.setRenderTarget(target);
    const w = target.width, h = target.height;
    if (state.split) {
      renderer.setScissorTest(true);
      showAge(state.age);
      renderer.setScissor(0, 0, Math.floor(w / 2), h);
      renderer.render(scene, camera);
      showAge(state.ageB);
      renderer.setScissor(Math.floor(w / 2), 0, w - Math.floor(w / 2), h);
      renderer.render(scene, camera);
      renderer.setScissorTest(false);
    } else {
      showAge(state.age);
      renderer.render(scene, camera);
    }
    display.render(renderer, target, state.exposure);
    api.frames += 1;
    if (!api.ready) {
      api.ready = true;
      api.firstFrameMs = performance.now() - started;
    }
    requestAnimationFrame(frame);
  }

  Object.assign(api, {
    ages: data.ages,
    views: data.views.map((v) => v.name),
    setAge(years) { state.age = years; age.value = years; syncLabels(); },
    setSplit(on, years) { state.split = on; if (years !== undefined) state.ageB = years; document.body.classList.toggle('split', on); },
    setView(name) { display.setView(name); $('display-view').value = name; },
    setExposure(ev) { state.exposure = 2 ** ev; syncLabels(); },
    setEnvironment,
    setAntialias(on) { display.antialias = on; $('antialias').checked = on; },
    /// The asset's bounding box as the canvas shows it, in page pixels (left, top, right,
    /// bottom), and the canvas's own rectangle.
    assetRect() {
      const r = canvas.getBoundingClientRect();
      let x0 = Infinity, y0 = Infinity, x1 = -Infinity, y1 = -Infinity;
      for (let i = 0; i < 8; ++i) {
        const p = new THREE.Vector3(i & 1 ? box.max.x : box.min.x, i & 2 ? box.max.y : box.min.y,
                                    i & 4 ? box.max.z : box.min.z).project(camera);
        const x = r.left + (p.x + 1) / 2 * r.width, y = r.top + (1 - p.y) / 2 * r.height;
        x0 = Math.min(x0, x); y0 = Math.min(y0, y); x1 = Math.max(x1, x); y1 = Math.max(y1, y);
      }
      return { asset: [x0, y0, x1, y1], canvas: [r.left, r.top, r.right, r.bottom] };
    },
    setCamera(from, to, fovDeg) {
      userMoved = true;
      camera.position.set(...from);
      controls.target.set(...to);
      camera.fov = fovDeg;
      camera.updateProjectionMatrix();
      controls.update();
    },
  });
  window.patinaViewer = api;
  requestAnimationFrame(frame);
}

const data = window.PATINA_VIEWER;
if (!data) fail('data.js is missing or broken: write this folder with `patina-texgen view`.');
else start(data).catch((e) => { console.error(e); fail(`The viewer could not start: ${e.message}`); });
