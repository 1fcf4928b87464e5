#!/usr/bin/env python3
"""Every JSON field is also a flag: walks the request fields /openapi.json publishes (generated from the field
table) for each CLI command and checks that `lienewton COMMAND --FIELD @` reaches the request's reader, which
refuses the value naming FIELD (exit 2, an error that is not `usage`), instead of refusing the flag; the same
with the dash spelling of the name.

  fields_as_flags.py LIENEWTON_BIN SERVER_BIN
"""
import json
import os
import subprocess
import sys
import tempfile

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "replay"))
import replay  # noqa: E402  (the server start and the exchange)

# CLI command -> the operation whose request it reads (a render's GET form lists its base request's fields and
# its picture options as parameters).
COMMANDS = {
    "solve": ("post", "/api/v1/solve"), "sweep": ("post", "/api/v1/sweep"), "basins": ("post", "/api/v1/basins"),
    "integrate": ("post", "/api/v1/integrate"), "work-precision": ("post", "/api/v1/work-precision"),
    "render frames": ("get", "/api/v1/render/frames"), "render heatmap": ("get", "/api/v1/render/heatmap"),
    "render basins": ("get", "/api/v1/render/basins"), "render residuals": ("get", "/api/v1/render/residuals"),
    "render work-precision": ("get", "/api/v1/render/work-precision"),
    "render invariants": ("get", "/api/v1/render/invariants"),
}


def field_names(doc, method, path):
    op = doc["paths"][path][method]
    if method == "get":
        return [p["name"] for p in op["parameters"]]
    return list(op["requestBody"]["content"]["application/json"]["schema"]["properties"])


def main():
    cli, server_bin = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    with tempfile.TemporaryFile() as log:
        server, port = replay.start_server(server_bin, log)
        try:
            doc = json.loads(replay.request(port, "GET", "/openapi.json")[2])
        finally:
            server.terminate()
            server.wait(timeout=10)
    failures, checked = [], 0
    for command, (method, path) in COMMANDS.items():
        for name in field_names(doc, method, path):
            for spelling in sorted({name, name.replace("_", "-")}):
                proc = subprocess.run([cli, *command.split(), "--" + spelling, "@"], stdin=subprocess.DEVNULL,
                                      capture_output=True, timeout=60)
                checked += 1
                try:
                    error = json.loads(proc.stderr)["error"]
                except (ValueError, KeyError):
                    error = {}
                if proc.returncode != 2 or error.get("code") == "usage" or not str(error.get("field")).startswith(name):
                    failures.append(f"lienewton {command} --{spelling} @: exit {proc.returncode}, {proc.stderr[:300]!r}")
    for f in failures:
        print("fields_as_flags: FAIL", f)
    print(f"fields_as_flags: {checked - len(failures)} passed, {len(failures)} failed")
    return 1 if failures or checked < 100 else 0


if __name__ == "__main__":
    sys.exit(main())
