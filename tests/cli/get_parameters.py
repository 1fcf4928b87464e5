#!/usr/bin/env python3
"""Every GET declares every query parameter it reads: for each GET form in /openapi.json, each field its CLI
command takes (`lienewton COMMAND --help`, made from the field table) is sent as ?FIELD=@; a field the route reads
answers an error naming it that is not unknown_field, and must be among the operation's parameters; every declared
parameter must be read the same way.

  get_parameters.py LIENEWTON_BIN SERVER_BIN
"""
import json
import os
import re
import subprocess
import sys
import tempfile
import urllib.parse

sys.path.insert(0, os.path.join(os.path.dirname(os.path.dirname(os.path.abspath(__file__))), "replay"))
import replay  # noqa: E402  (the server start and the exchange)

# GET path -> the CLI command that reads the same request.
ROUTES = {
    "/api/v1/solve/events": "solve",
    "/api/v1/render/frames": "render frames", "/api/v1/render/motion": "render motion",
    "/api/v1/render/heatmap": "render heatmap", "/api/v1/render/basins": "render basins",
    "/api/v1/render/work-precision": "render work-precision", "/api/v1/render/residuals": "render residuals",
    "/api/v1/render/invariants": "render invariants",
}


def table_fields(cli, command):
    """The fields `lienewton COMMAND --help` lists (its flags, dashes as underscores)."""
    text = subprocess.run([cli, *command.split(), "--help"], capture_output=True, text=True, check=True).stdout
    return [m.replace("-", "_") for m in re.findall(r"^  --(\S+) ", text, re.M)]


def reads(port, path, name, kinds):
    """Whether GET path reads the query parameter: an invalid value is refused naming it, not as unknown (in one of
    the request kinds the route tells apart by its kind parameter, e.g. render/frames of a solve or an integration)."""
    for kind in kinds:
        query = (f"kind={kind}&" if kind else "") + f"{urllib.parse.quote(name)}=@"
        status, _, data = replay.request(port, "GET", f"{path}?{query}")
        try:
            error = json.loads(data)["error"]
        except (ValueError, KeyError):
            return status != 400, f"answered {status}"
        if not (error.get("code") == "unknown_field" and error.get("field") == name):
            return True, error
    return False, error


def main():
    cli, server_bin = os.path.realpath(sys.argv[1]), os.path.realpath(sys.argv[2])
    failures, checked = [], 0
    with tempfile.TemporaryFile() as log:
        server, port = replay.start_server(server_bin, log)
        try:
            doc = json.loads(replay.request(port, "GET", "/openapi.json")[2])
            gets = {p for p, item in doc["paths"].items() if "get" in item and item["get"].get("parameters")}
            failures += [f"GET {p} has parameters but no CLI command here" for p in sorted(gets - ROUTES.keys())]
            for path, command in ROUTES.items():
                parameters = doc["paths"][path]["get"]["parameters"]
                declared = {p["name"] for p in parameters}
                kinds = [None] + [k for p in parameters if p["name"] == "kind" for k in p["schema"].get("enum", [])]
                for name in sorted(set(table_fields(cli, command)) | declared):
                    checked += 1
                    read, error = reads(port, path, name, kinds)
                    if read and name not in declared:
                        failures.append(f"GET {path} reads {name} ({error}) but does not declare it")
                    elif not read and name in declared:
                        failures.append(f"GET {path} declares {name} but refuses it: {error}")
        finally:
            server.terminate()
            server.wait(timeout=10)
    for f in failures:
        print("get_parameters: FAIL", f)
    print(f"get_parameters: {checked - len(failures)} passed, {len(failures)} failed")
    return 1 if failures or checked < 100 else 0


if __name__ == "__main__":
    sys.exit(main())
