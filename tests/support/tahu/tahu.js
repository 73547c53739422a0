// Eclipse Tahu's JavaScript Sparkplug B library, an implementation eip2mqtt did not write, for
// the tests (tests/support/tahu.hpp):
//   node tahu.js decode FILE       prints the payload in FILE as JSON (64-bit integers as
//                                  decimal strings)
//   node tahu.js decode-all FILE.. prints the payloads in the FILEs as one JSON array, in
//                                  their order (one Node.js start for many messages)
//   node tahu.js encode JSON OUT   writes to OUT the payload that the JSON file describes
//                                  ({"timestamp": .., "metrics": [{"name", "type", "value"}..]})
'use strict';
const fs = require('fs');
const sparkplug = require('sparkplug-payload').get('spBv1.0');

const [mode, input, output] = process.argv.slice(2);
if (mode === 'encode') {
    const payload = JSON.parse(fs.readFileSync(input, 'utf8'));
    fs.writeFileSync(output, Buffer.from(sparkplug.encodePayload(payload)));
} else if (mode === 'decode' || mode === 'decode-all') {
    const decode = (file) => sparkplug.decodePayload(new Uint8Array(fs.readFileSync(file)));
    const files = process.argv.slice(3);
    const payload = mode === 'decode' ? decode(input) : files.map(decode);
    process.stdout.write(JSON.stringify(payload, (key, value) => {
        if (typeof value === 'bigint') return value.toString();
        if (value !== null && typeof value === 'object' && typeof value.low === 'number' &&
            typeof value.high === 'number' && typeof value.unsigned === 'boolean') {
            return value.toString();  // a Long
        }
        return value;
    }) + '\n');
} else {
    process.stderr.write('usage: node tahu.js decode FILE | decode-all FILE.. | encode JSON OUT\n');
    process.exit(2);
}
