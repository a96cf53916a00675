// Validates every .glb given on the command line with the Khronos glTF validator (npm package
// `gltf-validator`, found through NODE_PATH) and exits non-zero when any file has an error or a
// warning, printing each message with its JSON pointer. Infos and hints are counted only.
const fs = require("fs");
const validator = require("gltf-validator");

async function main(files) {
  let failed = false;
  for (const file of files) {
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)));
    const issues = report.issues;
    console.log(
      `${file}: ${issues.numErrors} errors, ${issues.numWarnings} warnings, ` +
        `${issues.numInfos} infos, ${issues.numHints} hints`
    );
    for (const m of issues.messages) {
      if (m.severity <= 1) {
        console.log(`  ${m.severity === 0 ? "error" : "warning"} ${m.code} at ${m.pointer}: ${m.message}`);
      }
    }
    failed ||= issues.numErrors > 0 || issues.numWarnings > 0;
  }
  if (files.length === 0) {
    console.error("usage: node validate_gltf.js FILE.glb...");
    failed = true;
  }
  process.exit(failed ? 1 : 0);
}

main(process.argv.slice(2)).catch((e) => {
  console.error(e);
  process.exit(1);
});
