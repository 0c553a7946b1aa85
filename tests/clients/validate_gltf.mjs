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
process.exit(issues.numErrors + issues.numWarnings > 0 ? 1 : 0);
