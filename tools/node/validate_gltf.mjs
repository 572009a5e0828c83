// Validate a .glb/.gltf with the Khronos glTF validator and print its JSON report.
// Usage: node tools/node/validate_gltf.mjs FILE   (exit code 1 when the report has errors)
import { readFile } from "node:fs/promises";
import validator from "gltf-validator";

const path = process.argv[2];
if (!path) {
  console.error("usage: node validate_gltf.mjs FILE.glb");
  process.exit(2);
}
const data = new Uint8Array(await readFile(path));
const report = await validator.validateBytes(data, { maxIssues: 1000, uri: path });
console.log(JSON.stringify(report, null, 1));
process.exit(report.issues.numErrors > 0 ? 1 : 0);
