// The age of a material between the steps of a series: every primitive's material variants
// (KHR_materials_variants, one per age, in the asset's order) and one material per primitive
// that mixes two neighbouring steps' base colour, metallic-roughness and normal maps and
// factors with a weight (three.js's standard material, its map chunks replaced).
import * as THREE from 'three';

const MIXED_CHUNKS = {
  'vec4 diffuseColor = vec4( diffuse, opacity );':
    'vec4 diffuseColor = vec4( mix(diffuse, ageDiffuse2, ageMix), opacity );',
  '#include <map_fragment>': `
    #ifdef USE_MAP
      diffuseColor *= mix(texture2D(map, vMapUv), texture2D(ageMap2, vMapUv), ageMix);
    #endif`,
  '#include <roughnessmap_fragment>': `
    float roughnessFactor = mix(roughness, ageRoughness2, ageMix);
    #ifdef USE_ROUGHNESSMAP
      roughnessFactor *= mix(texture2D(roughnessMap, vRoughnessMapUv).g,
                             texture2D(ageRoughnessMap2, vRoughnessMapUv).g, ageMix);
    #endif`,
  '#include <metalnessmap_fragment>': `
    float metalnessFactor = mix(metalness, ageMetalness2, ageMix);
    #ifdef USE_METALNESSMAP
      metalnessFactor *= mix(texture2D(metalnessMap, vMetalnessMapUv).b,
                             texture2D(ageMetalnessMap2, vMetalnessMapUv).b, ageMix);
    #endif`,
};

const NORMAL_MIX = {
  'texture2D( normalMap, vNormalMapUv ).xyz':
    'mix(texture2D(normalMap, vNormalMapUv).xyz, texture2D(ageNormalMap2, vNormalMapUv).xyz, ageMix)',
};

/// A material that shows `steps` (one MeshStandardMaterial per age) at a fractional age.
class BlendedMaterial extends THREE.MeshStandardMaterial {
  constructor(steps) {
    super();
    this.copy(steps[0]);
    this.steps = steps;
    this.ageUniforms = {
      ageMix: { value: 0 },
      ageDiffuse2: { value: new THREE.Color() },
      ageRoughness2: { value: 1 },
      ageMetalness2: { value: 1 },
      ageMap2: { value: null },
      ageRoughnessMap2: { value: null },
      ageMetalnessMap2: { value: null },
      ageNormalMap2: { value: null },
    };
    this.onBeforeCompile = (shader) => {
      Object.assign(shader.uniforms, this.ageUniforms);
      let f = shader.fragmentShader.replace('void main() {', `
        uniform float ageMix;
        uniform vec3 ageDiffuse2;
        uniform float ageRoughness2, ageMetalness2;
        uniform sampler2D ageMap2, ageRoughnessMap2, ageMetalnessMap2, ageNormalMap2;
        void main() {`);
      for (const [from, to] of Object.entries(MIXED_CHUNKS)) f = f.replace(from, to);
      f = f.replace('#include <normal_fragment_maps>',
                    THREE.ShaderChunk.normal_fragment_maps.split(Object.keys(NORMAL_MIX)[0]).join(Object.values(NORMAL_MIX)[0]));
      shader.fragmentShader = f;
    };
    this.setStep(0);
  }

  /// Shows step position `t` in [0, steps - 1]: steps floor(t) and the next, mixed.
  setStep(t) {
    const last = this.steps.length - 1;
    const k = Math.min(Math.floor(t), Math.max(last - 1, 0));
    const a = this.steps[k], b = this.steps[Math.min(k + 1, last)];
    this.map = a.map;
    this.roughnessMap = a.roughnessMap;
    this.metalnessMap = a.metalnessMap;
    this.normalMap = a.normalMap;
    this.color.copy(a.color);
    this.roughness = a.roughness;
    this.metalness = a.metalness;
    const u = this.ageUniforms;
    u.ageMix.value = last > 0 ? Math.min(Math.max(t - k, 0), 1) : 0;
    u.ageDiffuse2.value.copy(b.color);
    u.ageRoughness2.value = b.roughness;
    u.ageMetalness2.value = b.metalness;
    u.ageMap2.value = b.map;
    u.ageRoughnessMap2.value = b.roughnessMap;
    u.ageMetalnessMap2.value = b.metalnessMap;
    u.ageNormalMap2.value = b.normalMap;
  }
}

/// Replaces the material of every primitive of `gltf` that has variants by a BlendedMaterial
/// of its variants; returns them.
export async function blendAges(gltf, variantCount) {
  const parser = gltf.parser;
  const json = parser.json;
  const blended = [];
  const meshes = [];
  gltf.scene.traverse((o) => { if (o.isMesh) meshes.push(o); });
  for (const mesh of meshes) {
    const assoc = parser.associations.get(mesh);
    if (!assoc || assoc.meshes === undefined) continue;
    const primitive = json.meshes[assoc.meshes].primitives[assoc.primitives ?? 0];
    const mappings = primitive.extensions?.KHR_materials_variants?.mappings;
    if (!mappings) continue;
    const byVariant = new Array(variantCount).fill(primitive.material);
    for (const m of mappings) for (const v of m.variants) byVariant[v] = m.material;
    const steps = await Promise.all(byVariant.map((i) => parser.getDependency('material', i)));
    const material = new BlendedMaterial(steps);
    mesh.material = material;
    blended.push(material);
  }
  return blended;
}
