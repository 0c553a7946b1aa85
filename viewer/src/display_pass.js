// The OCIO display transform as the last pass: the scene, rendered in linear Rec.709 into a
// half-float target, times the exposure, through the view's GLSL (data.js): OCIO's own
// shader, or for a long one (the ACES output transform) a 3D LUT that OCIO baked and its
// lookup. Then, when on, antialiasing: FXAA (three.js's port of NVIDIA's FXAA) on the
// display-encoded picture, where edges are judged as the eye sees them (after the tone
// curve, an edge between two highlights is no longer a hard step). Written to the canvas.
import * as THREE from 'three';
import { FXAAShader } from 'three/examples/jsm/shaders/FXAAShader.js';

export class DisplayPass {
  constructor(views) {
    this.views = views;
    this.scene = new THREE.Scene();
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    this.uniforms = { scene: { value: null }, exposure: { value: 1.0 }, patina_lut: { value: null } };
    this.luts = new Map();
    this.mesh = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), null);
    this.scene.add(this.mesh);
    // The display-encoded picture (8 bits, as the canvas holds it) and FXAA on it.
    this.encoded = new THREE.WebGLRenderTarget(1, 1, { type: THREE.UnsignedByteType });
    this.fxaa = new THREE.ShaderMaterial({
      name: FXAAShader.name,
      uniforms: THREE.UniformsUtils.clone(FXAAShader.uniforms),
      vertexShader: FXAAShader.vertexShader,
      fragmentShader: FXAAShader.fragmentShader,
      depthTest: false,
      depthWrite: false,
    });
    this.fxaaScene = new THREE.Scene();
    const quad = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), this.fxaa);
    quad.position.z = -0.5;  // inside the camera's [0, 1] depth range
    this.fxaaScene.add(quad);
    this.antialias = true;
  }

  setView(name) {
    const view = this.views.find((v) => v.name === name);
    if (!view) throw new Error(`no view '${name}'`);
    if (this.mesh.material) this.mesh.material.dispose();
    this.uniforms.patina_lut.value = view.lut ? this.lut(view) : null;
    this.mesh.material = new THREE.RawShaderMaterial({
      glslVersion: THREE.GLSL3,
      uniforms: this.uniforms,
      depthTest: false,
      depthWrite: false,
      vertexShader: `
        in vec3 position;
        in vec2 uv;
        out vec2 vUv;
        void main() { vUv = uv; gl_Position = vec4(position.xy, 0.0, 1.0); }`,
      fragmentShader: `
        precision highp float;
        uniform sampler2D scene;
        uniform float exposure;
        in vec2 vUv;
        out vec4 color;
        ${view.glsl}
        void main() {
          vec3 linear = texture(scene, vUv).rgb * exposure;
          color = vec4(patina_display(vec4(linear, 1.0)).rgb, 1.0);
        }`,
    });
    this.view = name;
  }

  /// The view's baked table as a 3D texture (half floats, trilinear), made once.
  lut(view) {
    if (!this.luts.has(view.name)) {
      const bin = atob(view.lut.rgba_f16);
      const bytes = new Uint8Array(bin.length);
      for (let i = 0; i < bin.length; ++i) bytes[i] = bin.charCodeAt(i);
      const n = view.lut.size;
      const texture = new THREE.Data3DTexture(new Uint16Array(bytes.buffer), n, n, n);
      texture.format = THREE.RGBAFormat;
      texture.type = THREE.HalfFloatType;
      texture.minFilter = texture.magFilter = THREE.LinearFilter;
      texture.wrapS = texture.wrapT = texture.wrapR = THREE.ClampToEdgeWrapping;
      texture.unpackAlignment = 1;
      texture.needsUpdate = true;
      this.luts.set(view.name, texture);
    }
    return this.luts.get(view.name);
  }

  render(renderer, target, exposure) {
    this.uniforms.scene.value = target.texture;
    this.uniforms.exposure.value = exposure;
    if (!this.antialias) {
      renderer.setRenderTarget(null);
      renderer.render(this.scene, this.camera);
      return;
    }
    const w = target.width, h = target.height;
    if (this.encoded.width !== w || this.encoded.height !== h) this.encoded.setSize(w, h);
    renderer.setRenderTarget(this.encoded);
    renderer.render(this.scene, this.camera);
    this.fxaa.uniforms.tDiffuse.value = this.encoded.texture;
    this.fxaa.uniforms.resolution.value.set(1 / w, 1 / h);
    renderer.setRenderTarget(null);
    renderer.render(this.fxaaScene, this.camera);
  }
}
