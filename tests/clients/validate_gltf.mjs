// The Khronos glTF validator on one asset: node validate_gltf.mjs FILE.glb|FILE.gltf
// Prints the report's counts and every issue, and exits 1 when it has an error or a
// warning (information and hints are printed, not failed), 2 when the file cannot be read.
import fs from 'node:fs';
import path from 'node:path';
import validator from 'gltf-validator';

const file = process.argv[2];
if (!file) {
    console.error('usage: node validate_gltf.mjs FILE.glb|FILE.gltf');
    process.exit(2);
}
let bytes;
try {
    bytes = fs.readFileSync(file);
} catch (e) {
    console.error(`validate_gltf: cannot read ${file}: ${e.message}`);
    process.exit(2);
}
const report = await validator.validateBytes(new Uint8Array(bytes), {
    uri: path.basename(file),
    maxIssues: 0,  // no limit
    externalResourceFunction: (uri) =>
        fs.promises.readFile(path.resolve(path.dirname(file), decodeURIComponent(uri)))
            .then((data) => new Uint8Array(data)),
});
const issues = report.issues;
console.log(`validator ${report.validatorVersion}: ${file}: ${issues.numErrors} errors, ` +
            `${issues.numWarnings} warnings, ${issues.numInfos} infos, ${issues.numHints} hints`);
for (const m of issues.messages)
    console.log(`  [${['error', 'warning', 'info', 'hint'][m.severity]}] ${m.code} ` +
                `${m.pointer ?? ''}: ${m.message}`);
if (report.info) {
    const images = (report.info.resources ?? []).filter((r) => r.image);
    const sizes = images.map((r) => `${r.image.width}x${r.image.height} ${r.image.format}`);
    console.log(`  extensions used: ${(report.info.extensionsUsed ?? []).join(', ') || 'none'}; ` +
                `materials: ${report.info.materialCount}; images: ${images.length} ` +
                `(${[...new Set(sizes)].join(', ')}); triangles: ${report.info.totalTriangleCount}`);
}
// Which materials carry which extension ("KHR_materials_clearcoat 2 of 3"): the asset's own
// JSON (a .glb's first chunk, or the .gltf), for tests that check an extension is where it
// does something and nowhere else.
const json = JSON.parse(bytes.readUInt32LE(0) === 0x46546c67
    ? bytes.subarray(20, 20 + bytes.readUInt32LE(12)).toString('utf8')
    : bytes.toString('utf8'));
const materials = json.materials ?? [];
const counts = new Map();
for (const m of materials)
    for (const name of Object.keys(m.extensions ?? {}))
        counts.set(name, (counts.get(name) ?? 0) + 1);
console.log(`  materials with an extension: ${[...counts].map(([n, c]) =>
    `${n} ${c} of ${materials.length}`).join(', ') || 'none'}`);
// A material extension the asset declares but no material uses does nothing: a defect.
const unused = (json.extensionsUsed ?? []).filter((n) => n.startsWith('KHR_materials_') &&
    n !== 'KHR_materials_variants' && !counts.has(n));
console.log(`  material extensions declared and unused: ${unused.join(', ') || 'none'}`);
process.exit(issues.numErrors + issues.numWarnings + unused.length > 0 ? 1 : 0);
