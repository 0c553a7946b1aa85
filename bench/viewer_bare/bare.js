// The peer of bench/viewer_frame_time.sh: the same .glb (from the viewer folder's data.js)
// with three.js's plain GLTFLoader, the same camera, canvas and light, and nothing else: no
// age blending, no half-float target, no OCIO pass (three's own sRGB output).
import * as THREE from 'three';
import { GLTFLoader } from 'three/examples/jsm/loaders/GLTFLoader.js';

async function start() {
const started = performance.now();
const data = window.PATINA_VIEWER;
const canvas = document.getElementById('view');
const renderer = new THREE.WebGLRenderer({ canvas });  // three's defaults, no MSAA, as the viewer
renderer.setPixelRatio(1);
const scene = new THREE.Scene();
const camera = new THREE.PerspectiveCamera(35, 1, 0.01, 100);
const bin = atob(data.model);
const bytes = new Uint8Array(bin.length);
for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
const gltf = await new GLTFLoader().parseAsync(bytes.buffer, '');
scene.add(gltf.scene);
const box = new THREE.Box3().setFromObject(gltf.scene);
const centre = box.getCenter(new THREE.Vector3());
const radius = box.getSize(new THREE.Vector3()).length() / 2 || 1;
camera.position.copy(centre).add(new THREE.Vector3(0, radius * 0.9, radius * 2.2));
camera.lookAt(centre);
const env = data.environments[0];
const sky = atob(env.rgba_f32);
const f = new Uint8Array(sky.length);
for (let i = 0; i < sky.length; ++i) f[i] = sky.charCodeAt(i);
const texture = new THREE.DataTexture(new Float32Array(f.buffer), env.width, env.height, THREE.RGBAFormat, THREE.FloatType);
texture.mapping = THREE.EquirectangularReflectionMapping;
texture.needsUpdate = true;
scene.environment = new THREE.PMREMGenerator(renderer).fromEquirectangular(texture).texture;
scene.background = texture;
const sun = new THREE.DirectionalLight(0xffffff, env.sun.irradiance);
sun.position.set(...env.sun.direction);
scene.add(sun);

const api = { ready: false, frames: 0, frameTimes: [], firstFrameMs: null };
window.patinaViewer = api;
let last = null;
function frame(now) {
  const w = canvas.clientWidth, h = canvas.clientHeight;
  if (canvas.width !== w || canvas.height !== h) {
    renderer.setSize(w, h, false);
    camera.aspect = w / h;
    camera.updateProjectionMatrix();
  }
  if (last !== null) api.frameTimes.push(now - last);
  last = now;
  renderer.render(scene, camera);
  api.frames += 1;
  if (!api.ready) {
    api.ready = true;
    api.firstFrameMs = performance.now() - started;
  }
  requestAnimationFrame(frame);
}
requestAnimationFrame(frame);
}
start();
