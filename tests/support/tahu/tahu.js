// Decodes a Sparkplug B payload with Eclipse Tahu's JavaScript library, an implementation
// eip2mqtt did not write, and prints it as JSON (64-bit integers as decimal strings).
//   node decode.js FILE
'use strict';
const fs = require('fs');
const sparkplug = require('sparkplug-payload').get('spBv1.0');

const bytes = fs.readFileSync(process.argv[2]);
const payload = sparkplug.decodePayload(new Uint8Array(bytes));
process.stdout.write(JSON.stringify(payload, (key, value) => {
    if (typeof value === 'bigint') return value.toString();
    if (value !== null && typeof value === 'object' && typeof value.low === 'number' &&
        typeof value.high === 'number' && typeof value.unsigned === 'boolean') {
        return value.toString();  // a Long
    }
    return value;
}) + '\n');
