#!/usr/bin/env python3
"""Validates the service's answers against its own /openapi.json.

  validate_answers.py SERVER_BIN [--cli LIENEWTON_BIN]

Starts the server, fetches /openapi.json and
- replays every request of requests.json (replay.py's) and validates the answer as sent (timing fields kept):
  its status must be a documented response of its operation (any JSON error must be the Error schema), its
  content type one of that response's, a JSON body valid by the response's schema, and every NDJSON line and
  every SSE data field valid by the route's stream schema (its oneOf chosen by type); a request answered 200 must
  itself be valid by the operation's request schema;
- sends every request example of the document to its POST route: it must be valid by the request schema and
  answered 200 with a valid answer; every README request body (curl -d '...') must be one of its route's examples;
- checks that every error code the sources throw is in ErrorDetail's enum;
- with --cli, runs each CLI entry of a streaming route as `lienewton COMMAND --stream`: every line must be valid by
  the route's stream schema and the records those of the server's NDJSON stream of the same request (timing
  aside, in any order: a sweep's cells come as they finish).
OpenAPI 3.0's schemas are JSON Schema draft 4 plus nullable, which is rewritten as a type that admits null.
Exit status 0 when everything validates.
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import urllib.parse

import jsonschema

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import replay  # noqa: E402  (the server start, the exchange and the SSE reader)

ROOT = replay.ROOT


def draft4(schema):
    """An OpenAPI 3.0 schema as JSON Schema draft 4: nullable becomes null admitted."""
    if isinstance(schema, list):
        return [draft4(s) for s in schema]
    if not isinstance(schema, dict):
        return schema
    out = {k: draft4(v) for k, v in schema.items() if k not in ("nullable", "discriminator", "deprecated", "example")}
    if schema.get("nullable"):
        if "type" in out:
            out["type"] = [out["type"], "null"]
            if "enum" in out:
                out["enum"] = out["enum"] + [None]
        else:
            out = {"anyOf": [out, {"type": "null"}]}
    return out


class Document:
    def __init__(self, doc):
        self.doc = doc
        self.components = draft4(doc["components"])

    def validate(self, value, schema):
        """The messages of value's faults against an OpenAPI schema (a $ref or inline)."""
        root = {"components": self.components, "allOf": [draft4(schema)]}
        validator = jsonschema.Draft4Validator(root)
        return [f"{'/'.join(map(str, e.absolute_path)) or '$'}: {e.message[:300]}"
                for e in validator.iter_errors(value)]

    def operation(self, method, path):
        item = self.doc["paths"].get(path)
        return item and item.get(method.lower())


def schema_ref(name):
    return {"$ref": "#/components/schemas/" + name}


def check_answer(doc, method, path, status, content_type, data):
    faults = []
    kind = content_type.split(";")[0].strip()
    op = doc.operation(method, path)
    if kind == "application/json" and status >= 400:
        faults += doc.validate(json.loads(data), schema_ref("Error"))
    if op is None:
        return faults if status in (404, 405) else faults + [f"no operation {method} {path} in the document"]
    response = op["responses"].get(str(status))
    if response is None:
        return faults + [f"status {status} is not a documented response of {method} {path}"]
    content = response.get("content", {})
    if status == 304 or not data and not content:
        return faults
    if kind not in content:
        return faults + [f"content type {kind} is not one of {sorted(content)}"]
    schema = content[kind].get("schema")
    if kind == "application/json":
        faults += doc.validate(json.loads(data), schema)
    elif kind == "application/x-ndjson":
        lines = [line for line in data.decode().splitlines() if line.strip()]
        for i, line in enumerate(lines):
            faults += [f"line {i + 1}: {f}" for f in doc.validate(json.loads(line), schema)]
        if not lines or json.loads(lines[-1]).get("type") not in ("result", "error"):
            faults.append("the stream does not end with a result or error record")
    elif kind == "text/event-stream":
        events = replay.sse_events(data.decode())
        for i, event in enumerate(events):
            faults += [f"event {i + 1}: {f}" for f in doc.validate(event["data"], schema)]
        if not events or events[-1]["data"].get("type") not in ("result", "error"):
            faults.append("the stream does not end with a result or error event")
    return faults


def readme_requests():
    """(route path, body) of every README curl that sends a single-quoted JSON body to an /api/v1 route."""
    text = open(os.path.join(ROOT, "README.md")).read().replace("\\\n", " ")
    out = []
    for m in re.finditer(r"localhost:8080/api/v1/([a-z/-]+)\s+-d\s+'((?:[^']|'\\'')*)'", text):
        out.append(("/api/v1/" + m.group(1), json.loads(m.group(2).replace("'\\''", "'"))))
    for m in re.finditer(r"png \w+ ([a-z-]+) -d '([^']*)'", text):
        out.append(("/api/v1/render/" + m.group(1), json.loads(m.group(2))))
    return out


CODE_PATTERNS = [r'(?:FieldError|ApiError|error_response|error_body)\((?:[0-9]+, )?"([a-z_]+)"',
                 r'\bfail\([0-9]+, "([a-z_]+)"',
                 r'Rejection\{[0-9]+, "([a-z_]+)"', r'\bcode = "([a-z_]+)"']


def source_codes():
    codes = set()
    for folder in ("server", "server/cli"):
        for name in os.listdir(os.path.join(ROOT, folder)):
            if name.endswith(".cpp"):
                text = open(os.path.join(ROOT, folder, name)).read()
                for pattern in CODE_PATTERNS:
                    codes.update(re.findall(pattern, text))
    return codes


STREAM_ROUTES = {"/api/v1/solve", "/api/v1/sweep", "/api/v1/basins", "/api/v1/integrate", "/api/v1/work-precision"}


def check_cli_stream(doc, port, cli_bin, entry):
    """The CLI's --stream against the schema and against the server's NDJSON stream of the same body."""
    proc = subprocess.run([cli_bin, *entry["cli"].split(), "--stream"], input=json.dumps(entry["body"]).encode(),
                          capture_output=True, timeout=replay.TIMEOUT)
    status, _, data = replay.request(port, "POST", entry["path"], json.dumps(entry["body"]).encode(),
                                     {"Content-Type": "application/json", "Accept": "application/x-ndjson"})
    if status != 200:  # refused before any record, as the server refuses before its stream: the same error
        want = json.loads(data)["error"]["code"]
        got = json.loads(proc.stderr)["error"]["code"] if proc.stderr.strip() else None
        return [] if proc.returncode == 2 and not proc.stdout and got == want else [
            f"the server refused with {want}; the CLI exited {proc.returncode} with {proc.stderr[:200]!r}"]
    if proc.returncode != 0:
        return [f"exit {proc.returncode}: {proc.stderr[:300]!r}"]
    schema = doc.operation("POST", entry["path"])["responses"]["200"]["content"]["application/x-ndjson"]["schema"]
    lines = [json.loads(line) for line in proc.stdout.decode().splitlines() if line.strip()]
    faults = [f"line {i + 1}: {f}" for i, line in enumerate(lines) for f in doc.validate(line, schema)]
    served = [json.loads(line) for line in data.decode().splitlines() if line.strip()]
    key = lambda record: json.dumps(record, sort_keys=True)  # noqa: E731
    ours = sorted((replay.strip_timing(r) for r in lines), key=key)
    theirs = sorted((replay.strip_timing(r) for r in served), key=key)
    return faults + [f"differs from the server's stream: {d}" for d in replay.differences(theirs, ours)][:10]


def main():
    server_bin = os.path.realpath(sys.argv[1])
    cli_bin = os.path.realpath(sys.argv[3]) if len(sys.argv) > 3 and sys.argv[2] == "--cli" else None
    with open(os.path.join(replay.HERE, "requests.json")) as f:
        entries = json.load(f)
    failures, checked = [], 0

    def report(name, faults):
        nonlocal checked
        checked += 1
        if faults:
            failures.append(name)
            print(f"validate: FAIL {name}")
            for fault in faults[:12]:
                print(f"    {fault}")
        else:
            print(f"validate: ok {name}")

    with tempfile.TemporaryFile() as log:
        server, port = replay.start_server(server_bin, log)
        try:
            status, _, data = replay.request(port, "GET", "/openapi.json")
            doc = Document(json.loads(data))
            for entry in entries:
                path = urllib.parse.urlsplit(entry["path"]).path
                status, content_type, data = replay.exchange(port, entry)
                faults = check_answer(doc, entry["method"], path, status, content_type, data)
                op = doc.operation(entry["method"], path)
                if status == 200 and op and "requestBody" in op and "body" in entry:
                    schema = op["requestBody"]["content"]["application/json"]["schema"]
                    faults += [f"request: {f}" for f in doc.validate(entry["body"], schema)]
                report(entry["name"], faults)
            examples = {}
            for path, item in doc.doc["paths"].items():
                op = item.get("post")
                if not op or "requestBody" not in op:
                    continue
                media = op["requestBody"]["content"]["application/json"]
                named = media.get("examples", {})
                if not named:
                    report(f"examples of {path}", [f"POST {path} has no request example"])
                for name, example in named.items():
                    examples.setdefault(path, []).append(example["value"])
                    faults = [f"request: {f}" for f in doc.validate(example["value"], media["schema"])]
                    status, content_type, data = replay.request(
                        port, "POST", path, json.dumps(example["value"]).encode(), {"Content-Type": "application/json"})
                    faults += [] if status == 200 else [f"answered {status}: {data[:200]!r}"]
                    faults += check_answer(doc, "POST", path, status, content_type, data)
                    report(f"example {name} of {path}", faults)
            for path, body in readme_requests():
                faults = [] if body in examples.get(path, []) else [
                    f"the README sends {json.dumps(body)} to {path}, which is not among its examples"]
                report(f"README request to {path}", faults)
            for entry in entries if cli_bin else []:
                if "cli" in entry and entry["path"] in STREAM_ROUTES:
                    report(f"cli-{entry['name']} --stream", check_cli_stream(doc, port, cli_bin, entry))
            codes = set(doc.doc["components"]["schemas"]["ErrorDetail"]["properties"]["code"]["enum"])
            missing = sorted(source_codes() - codes)
            report("error codes of the sources", [f"code {c} is not in ErrorDetail's enum" for c in missing])
        finally:
            server.terminate()
            server.wait(timeout=10)
    print(f"validate: {checked - len(failures)} passed, {len(failures)} failed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
