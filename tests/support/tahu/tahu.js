// Eclipse Tahu's JavaScript Sparkplug B library, an implementation eip2mqtt did not write, for
// the tests (tests/support/tahu.hpp):
//   node tahu.js decode FILE       prints the payload in FILE as JSON (64-bit integers as
//                                  decimal strings)
//   node tahu.js decode-lines FILE prints each payload of FILE (one in base64 a line) as JSON,
//                                  one a line: thousands of payloads in one run of node
//   node tahu.js encode JSON OUT   writes to OUT the payload that the JSON file describes
//                                  ({"timestamp": .., "metrics": [{"name", "type", "value"}..]})
'use strict';
const fs = require('fs');
const sparkplug = require('sparkplug-payload').get('spBv1.0');

function decoded(bytes) {
    const payload = sparkplug.decodePayload(new Uint8Array(bytes));
    return JSON.stringify(payload, (key, value) => {
        if (typeof value === 'bigint') return value.toString();
        if (value !== null && typeof value === 'object' && typeof value.low === 'number' &&
            typeof value.high === 'number' && typeof value.unsigned === 'boolean') {
            return value.toString();  // a Long
        }
        return value;
    }) + '\n';
}

const [mode, input, output] = process.argv.slice(2);
if (mode === 'encode') {
    const payload = JSON.parse(fs.readFileSync(input, 'utf8'));
    fs.writeFileSync(output, Buffer.from(sparkplug.encodePayload(payload)));
} else if (mode === 'decode') {
    process.stdout.write(decoded(new Uint8Array(fs.readFileSync(input))));
} else if (mode === 'decode-lines') {
    const lines = fs.readFileSync(input, 'utf8').split('\n').filter((line) => line.length > 0);
    for (const line of lines) process.stdout.write(decoded(Buffer.from(line, 'base64')));
} else {
    process.stderr.write('usage: node tahu.js decode FILE | decode-lines FILE | encode JSON OUT\n');
    process.exit(2);
}
