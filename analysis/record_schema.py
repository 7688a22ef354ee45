"""The kdrt record's schema (cc/tools/kdrt_record.schema.json) and a
validator for it: the one declaration of the record's fields, which kdrt's
test (cc/tools/kdrt_test.sh) and the analysis both check against.

    /usr/bin/python3 analysis/record_schema.py [--schema S] [--sections
        kdrt,run_matrix] RECORDS.json ...

validates every record (one JSON object per line) of the files and prints
each error; exit code 1 when any. Standard library only (kdrt_test.sh runs it
as a script).

A schema section (kdrt, run_matrix, ...) maps field names to specs: type (a
JSON type name or a list of them), nullable, required, doc, and for an array
its items, for an object its fields (closed: no other member) or its values
(a map), or ref (the spec of defs[ref]). A record validates against a list of
sections: their fields together, every required one present with its type,
and no other top-level field.
"""

import argparse
import json
import os
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCHEMA = os.path.join(ROOT, "cc", "tools", "kdrt_record.schema.json")
# What a successful matrix record is: kdrt's fields and the runner's.
MATRIX_RECORD = ("kdrt", "run_matrix")
SECTIONS = ("kdrt", "run_matrix", "run_matrix_failure", "accuracy", "planar")

_TYPES = {
    "string": lambda v: isinstance(v, str),
    "integer": lambda v: isinstance(v, int) and not isinstance(v, bool),
    "number": lambda v: isinstance(v, (int, float)) and not isinstance(v, bool),
    "boolean": lambda v: isinstance(v, bool),
    "array": lambda v: isinstance(v, list),
    "object": lambda v: isinstance(v, dict),
}


def load(path=SCHEMA):
    with open(path, encoding="utf-8") as f:
        return json.load(f)


def fields_of(schema, sections=("kdrt",)):
    """{name: spec} of the sections together."""
    out = {}
    for section in sections:
        out.update(schema[section])
    return out


def resolve(schema, spec):
    """The spec with its ref replaced by defs[ref] (its own members kept)."""
    if "ref" not in spec:
        return spec
    merged = dict(schema["defs"][spec["ref"]])
    merged.update((k, v) for k, v in spec.items() if k != "ref")
    return merged


def _type_names(spec):
    t = spec.get("type")
    return t if isinstance(t, list) else [t]


def _check_value(schema, spec, value, where, errors):
    spec = resolve(schema, spec)
    if value is None:
        if not spec.get("nullable"):
            errors.append("%s: null, expected %s" % (where, "/".join(_type_names(spec))))
        return
    names = _type_names(spec)
    if not any(_TYPES[n](value) for n in names):
        errors.append("%s: expected %s, got %s %r"
                      % (where, "/".join(names), type(value).__name__, value))
        return
    if isinstance(value, list) and "items" in spec:
        for i, item in enumerate(value):
            _check_value(schema, spec["items"], item, "%s[%d]" % (where, i), errors)
    elif isinstance(value, dict) and "fields" in spec:
        _check_object(schema, spec["fields"], value, where + ".", errors)
    elif isinstance(value, dict) and "values" in spec:
        for key, item in value.items():
            _check_value(schema, spec["values"], item, "%s.%s" % (where, key), errors)


def _check_object(schema, fields, obj, prefix, errors):
    for name, spec in fields.items():
        if name in obj:
            _check_value(schema, spec, obj[name], prefix + name, errors)
        elif resolve(schema, spec).get("required", True):
            errors.append("%s%s: missing" % (prefix, name))
    for name in obj:
        if name not in fields:
            errors.append("%s%s: not declared in the schema" % (prefix, name))


def validate(record, schema, sections=("kdrt",)):
    """[error] of a record against the schema's sections (empty: valid)."""
    if not isinstance(record, dict):
        return ["the record is not a JSON object"]
    errors = []
    _check_object(schema, fields_of(schema, sections), record, "", errors)
    return errors


def spec_at(schema, path, sections=SECTIONS):
    """The spec of a dotted path ("embree.T_R"), or None when undeclared."""
    fields = fields_of(schema, sections)
    spec = None
    for part in path.split("."):
        if fields is None or part not in fields:
            return None
        spec = resolve(schema, fields[part])
        fields = spec.get("fields")
    return spec


def section_of(schema, name):
    """The first section declaring top-level field `name` (None: none)."""
    return next((s for s in SECTIONS if name in schema[s]), None)


def check_schema(schema):
    """[error] of the schema itself: every spec has a doc and known types,
    every ref a def; no field of a runner section repeats a kdrt one."""
    errors = []

    def walk(fields, where):
        for name, spec in fields.items():
            here = where + name
            if not spec.get("doc"):
                errors.append(here + ": no doc")
            if "ref" in spec and spec["ref"] not in schema["defs"]:
                errors.append("%s: unknown ref %s" % (here, spec["ref"]))
            spec = resolve(schema, spec)
            if any(n not in _TYPES for n in _type_names(spec)):
                errors.append("%s: unknown type %s" % (here, spec.get("type")))
            walk(spec.get("fields", {}), here + ".")
    for section in SECTIONS:
        walk(schema[section], section + ":")
        if section != "kdrt" and section != "run_matrix_failure":
            errors += ["%s: %s repeats a kdrt field" % (section, n)
                       for n in schema[section] if n in schema["kdrt"]]
    walk(schema["defs"], "defs:")
    return errors


def _records(path):
    with open(path, encoding="utf-8") as f:
        text = f.read()
    lines = [line for line in text.splitlines() if line.strip()]
    try:
        return [json.loads(line) for line in lines]
    except ValueError:
        return [json.loads(text)]  # one record over several lines


def main(argv=None):
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--schema", default=SCHEMA)
    p.add_argument("--sections", default="kdrt",
                   help="comma-separated sections the records hold")
    p.add_argument("files", nargs="+")
    args = p.parse_args(argv)
    schema = load(args.schema)
    sections = args.sections.split(",")
    bad = 0
    for path in args.files:
        for i, rec in enumerate(_records(path)):
            for error in validate(rec, schema, sections):
                bad += 1
                print("%s:%d: %s" % (path, i + 1, error), file=sys.stderr)
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
