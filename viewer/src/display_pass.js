// The OCIO display transform as the last pass: the scene, rendered in linear Rec.709 into a
// half-float target, times the exposure, through the GLSL that OCIO generated for the view
// (data.js), written to the canvas as it is.
import * as THREE from 'three';

export class DisplayPass {
  constructor(views) {
    this.views = views;
    this.scene = new THREE.Scene();
    this.camera = new THREE.OrthographicCamera(-1, 1, 1, -1, 0, 1);
    this.uniforms = { scene: { value: null }, exposure: { value: 1.0 } };
    this.mesh = new THREE.Mesh(new THREE.PlaneGeometry(2, 2), null);
    this.scene.add(this.mesh);
  }

  setView(name) {
    const view = this.views.find((v) => v.name === name);
    if (!view) throw new Error(`no view '${name}'`);
    if (this.mesh.material) this.mesh.material.dispose();
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

  render(renderer, target, exposure) {
    this.uniforms.scene.value = target.texture;
    this.uniforms.exposure.value = exposure;
    renderer.setRenderTarget(null);
    renderer.render(this.scene, this.camera);
  }
}
