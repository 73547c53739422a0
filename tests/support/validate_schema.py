#!/usr/bin/env python3
"""Validates JSON payloads against the JSON Schemas of docs/schema (python3-jsonschema).

    validate_schema.py SCHEMA < PAYLOAD
        one payload on stdin: prints nothing and exits 0 when it is valid, else prints the
        problem and exits 1.
    validate_schema.py --batch FILE
        many payloads: FILE holds records, each a line "SCHEMA<TAB>LENGTH" followed by LENGTH
        bytes of payload. Prints one line per invalid payload, "INDEX<TAB>PROBLEM" (INDEX counts
        records from 0), and exits 0 unless a schema or the file itself is unusable.

A payload must be strict JSON: NaN and Infinity tokens and duplicate keys are problems, since
other parsers refuse them. The schema itself is checked against its metaschema first.
"""

import json
import pathlib
import sys
import warnings

import jsonschema

_validators = {}


def _validator(schema_path):
    if schema_path not in _validators:
        with open(schema_path, encoding="utf-8") as f:
            schema = json.load(f)
        cls = jsonschema.validators.validator_for(schema)
        cls.check_schema(schema)
        # A "$ref" to another file ("status.json#/$defs/consumed") is read beside this one.
        base = pathlib.Path(schema_path).absolute().as_uri()
        with warnings.catch_warnings():  # deprecated in newer jsonschema, not yet removed
            warnings.simplefilter("ignore", DeprecationWarning)
            resolver = jsonschema.RefResolver(base_uri=base, referrer=schema)
        _validators[schema_path] = cls(schema, resolver=resolver)
    return _validators[schema_path]


def _reject_constant(name):
    raise ValueError(f"{name} is not JSON")


def _no_duplicates(pairs):
    result = {}
    for key, value in pairs:
        if key in result:
            raise ValueError(f"duplicate key {key!r}")
        result[key] = value
    return result


def problem(schema_path, payload):
    """The first problem of `payload` (bytes) against the schema, or "" when it is valid."""
    try:
        text = payload.decode("utf-8")
    except UnicodeDecodeError as e:
        return f"not UTF-8: {e}"
    try:
        document = json.loads(
            text, parse_constant=_reject_constant, object_pairs_hook=_no_duplicates)
    except ValueError as e:
        return f"not JSON ({e}): {text[:200]!r}"
    validator = _validator(schema_path)
    errors = list(validator.iter_errors(document))
    if not errors:
        return ""
    # As jsonschema.exceptions.best_match, without its descent into one oneOf branch.
    return _describe(max(errors, key=jsonschema.exceptions.relevance))


def _describe(error):
    """The error's message; for a oneOf or anyOf that no branch satisfies, the errors of the
    branches that came closest (those with the fewest), rather than the whole document."""
    if error.context:
        branches = {}
        for sub in error.context:
            branches.setdefault(sub.relative_schema_path[0], []).append(sub)
        fewest = min(len(b) for b in branches.values())
        closest = [b for b in branches.values() if len(b) == fewest]
        return " | ".join("; ".join(_describe(sub) for sub in b[:3]) for b in closest)
    where = "/".join(str(p) for p in error.absolute_path) or "(root)"
    return f"{where}: {error.message} (schema {'/'.join(map(str, error.absolute_schema_path))})"


def _batch(path):
    with open(path, "rb") as f:
        data = f.read()
    index = 0
    pos = 0
    while pos < len(data):
        end = data.index(b"\n", pos)
        schema_path, length = data[pos:end].decode("utf-8").split("\t")
        start = end + 1
        payload = data[start:start + int(length)]
        pos = start + int(length)
        found = problem(schema_path, payload)
        if found:
            print(f"{index}\t{found}".replace("\n", " "))
        index += 1


def main(argv):
    if len(argv) == 3 and argv[1] == "--batch":
        _batch(argv[2])
        return 0
    if len(argv) == 2:
        found = problem(argv[1], sys.stdin.buffer.read())
        if found:
            print(found)
            return 1
        return 0
    print(__doc__, file=sys.stderr)
    return 2


if __name__ == "__main__":
    sys.exit(main(sys.argv))
