// validate.mjs: runs the Khronos glTF validator (npm gltf-validator) on every file named on the command line.
// Prints one summary line per file plus every error (and warning) message; exits 1 if any file has an error
// or cannot be read, 2 on bad usage. Used by ctest (unit.gltf_validator_scenes) on the project's scenes/*.gltf.
import { createRequire } from 'node:module';
import { readFile } from 'node:fs/promises';
import path from 'node:path';

const require = createRequire(import.meta.url);
let validator;
try {
  validator = require('gltf-validator');
} catch (e) {
  console.error(`gltf-validator is not installed (${e.code ?? e}); run scripts/setup_node.sh`);
  process.exit(1);
}

const kSeverityNames = ['error', 'warning', 'info', 'hint'];

async function validateFile(file) {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0, // 0: report every issue
    externalResourceFunction: (uri) =>
      readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then((data) => new Uint8Array(data)),
  });
  const issues = report.issues;
  console.log(`${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
              `${issues.numInfos} infos, ${issues.numHints} hints (gltf-validator ${validator.version()})`);
  for (const m of issues.messages) {
    if (m.severity <= 1) {
      console.log(`  ${kSeverityNames[m.severity]} ${m.code} at ${m.pointer ?? '(root)'}: ${m.message}`);
    }
  }
  return issues.numErrors === 0;
}

const files = process.argv.slice(2);
if (files.length === 0) {
  console.error('usage: node validate.mjs FILE.gltf|FILE.glb...');
  process.exit(2);
}
let ok = true;
for (const file of files) {
  try {
    ok = (await validateFile(file)) && ok;
  } catch (e) {
    console.log(`${file}: cannot be validated: ${e}`);
    ok = false;
  }
}
process.exit(ok ? 0 : 1);
