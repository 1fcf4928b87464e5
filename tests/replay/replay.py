#!/usr/bin/env python3
"""Replays a recorded set of HTTP requests (and a few CLI runs) and compares the answers with recorded ones.

  replay.py SERVER_BIN [--cli LIENEWTON_BIN] [--only NAME,...] [--record]

requests.json holds the requests: every route of the service with realistic bodies, the NDJSON and SSE streams
and requests the service refuses (/openapi.json is left out: its form is not a promise). An entry is name,
method, path and one of body (sent as JSON), raw (sent as is) or pad_bytes (a body that large); optional:
headers, "compare": "status" (status and type only), "unordered": true (a stream whose records come in the order
parallel runs finish: compared sorted) and "cli": the lienewton command that takes the same body.
answers/NAME.json holds what the server answered when they were recorded: status, content type and the body,
read by its content type (JSON; NDJSON and SSE record by record; a PNG as its width and height; /metrics as its
HELP and TYPE lines; a text/html page by status and type only). Entries with "cli" are also run as
`lienewton CLI < body` and compared with answers/cli-NAME.json (exit status, stdout, the JSON error on stderr).

--record rewrites the answers from the given binaries instead of comparing: do it only from a build whose
answers are the reference (the build before a change that must not change them), then review `git diff`.

Comparison: status and content type exactly; JSON structurally (same keys, same array lengths, same types,
strings equal) after removing the wall and CPU timing fields (TIMING_FIELDS) at every depth. Numbers compare
within |a - b| <= 1e-9 * max(1, |a|, |b|) (the convergence rate to 1e-2: FIELD_TOLERANCE): the answers were recorded on one CPU, and another one (other vector
width, other FMA contraction of -march=native) rounds differently in the last bits; the requests are chosen
well-conditioned (small h and N, tol 1e-10 mostly; every run converges within 30 iterations without an erratic
excursion, bar one stopped after 5, and no final residual lies within 5 % of its tol) so that a rounding
difference moves a number by far less than 1e-9, while any change of a formula, a default or an iteration count
moves it by far more. The max(1, .) makes the bound absolute for small numbers, so residuals at the rounding
floor (1e-16 here, 3e-16 there) agree.
Numbers inside strings (the "reason" and error messages) compare the same way, the rest of the text exactly: a
residual at the floor printed as 5.55e-17 here may read 1.25e-16 there. (A well-conditioned number printed
with 3 digits crosses a rounding boundary of its last digit with a probability of about 1e-9.)
Exit status: 0 when every answer matches, 1 otherwise (every difference is printed with its JSON path).
"""
import argparse
import http.client
import json
import math
import os
import re
import socket
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
ANSWERS = os.path.join(HERE, "answers")
TIMEOUT = 300.0  # seconds one exchange may take (the largest request takes ~1 s on an idle machine)

# Wall-clock and CPU times in the answers (server/json_codec.cpp: results, trace records, work-precision points,
# integrations' reference solution). No answer carries a request id.
TIMING_FIELDS = {"seconds", "cpu_seconds", "reference_seconds"}
RELATIVE_TOLERANCE = 1e-9
# Fields whose value is ill-conditioned by definition, with their own bound. rate = log(f_{p-1}/f_{p-2}) /
# log(f_{p-2}/f_{p-3}) is made of the last residuals, f_{p-1} near tol (1e-10): rounding moves such a residual by
# about eps/tol = 1e-6 of itself, and the rate by up to 5e-4 between a -march=native (AVX-512) build and a
# generic x86-64 one (measured on these requests); a change of its formula or of the residuals moves it by more.
FIELD_TOLERANCE = {"rate": 1e-2}


# ---------------------------------------------------------------- the server
def free_port():
    with socket.socket() as s:
        s.bind(("127.0.0.1", 0))
        return s.getsockname()[1]


def request(port, method, path, body=None, headers=None):
    """One exchange on a fresh connection: (status, content type, body bytes)."""
    conn = http.client.HTTPConnection("127.0.0.1", port, timeout=TIMEOUT)
    try:
        conn.request(method, path, body=body, headers=headers or {})
        resp = conn.getresponse()
        return resp.status, resp.getheader("Content-Type", ""), resp.read()
    finally:
        conn.close()


def start_server(server_bin, log):
    port = free_port()
    # Generous deadlines: the replay may share a 2-core machine with the rest of the suite.
    server = subprocess.Popen([server_bin, "--host", "127.0.0.1", "--port", str(port), "--web-root",
                               os.path.join(ROOT, "web"), "--request-timeout", "240", "--sweep-timeout", "240"],
                              stdout=log, stderr=log)
    for _ in range(100):
        try:
            if request(port, "GET", "/livez")[0] == 200:
                return server, port
        except OSError:
            pass
        if server.poll() is not None:
            break
        time.sleep(0.1)
    server.kill()
    server.wait()
    raise SystemExit(f"replay: {server_bin} did not answer /livez")


# ---------------------------------------------------------------- answers as comparable documents
def strip_timing(value):
    if isinstance(value, dict):
        return {k: strip_timing(v) for k, v in value.items() if k not in TIMING_FIELDS}
    if isinstance(value, list):
        return [strip_timing(v) for v in value]
    return value


def png_size(data):
    if data[:8] != b"\x89PNG\r\n\x1a\n" or data[12:16] != b"IHDR":
        return {"not_a_png": data[:40].decode("latin-1")}
    return {"width": int.from_bytes(data[16:20], "big"), "height": int.from_bytes(data[20:24], "big")}


def sse_events(text):
    events = []
    for block in text.split("\n\n"):
        if not block.strip():
            continue
        event = {}
        for line in block.split("\n"):
            key, _, value = line.partition(":")
            event[key] = value[1:] if value.startswith(" ") else value
        events.append({"event": event.get("event"), "data": json.loads(event["data"])})
    return events


def document(content_type, data, compare):
    """The body as the comparable document its content type makes it."""
    kind = content_type.split(";")[0].strip()
    if compare == "status" or kind == "text/html":
        return None
    if kind == "application/json":
        return json.loads(data)
    if kind == "application/x-ndjson":
        return [json.loads(line) for line in data.decode().splitlines() if line.strip()]
    if kind == "text/event-stream":
        return sse_events(data.decode())
    if kind == "image/png":
        return png_size(data)
    if kind == "text/plain":  # Prometheus metrics: the families are fixed, the values are counters and times
        return [line for line in data.decode().splitlines() if line.startswith(("# HELP", "# TYPE"))]
    return {"bytes": len(data)}


def exchange(port, entry):
    """Sends a requests.json entry (its body, raw text or padding; its headers) and returns status, type, bytes."""
    headers = dict(entry.get("headers", {}))
    body = None
    if "body" in entry:
        body = json.dumps(entry["body"]).encode()
    elif "raw" in entry:
        body = entry["raw"].encode()
    elif "pad_bytes" in entry:
        body = ('{"n":3,"pad":"' + "x" * entry["pad_bytes"] + '"}').encode()
    if body is not None:
        headers.setdefault("Content-Type", "application/json")
    return request(port, entry["method"], entry["path"], body, headers)


def http_answer(port, entry):
    status, content_type, data = exchange(port, entry)
    answer = strip_timing(document(content_type, data, entry.get("compare")))
    if entry.get("unordered") and isinstance(answer, list):  # records in the order parallel runs finished
        answer.sort(key=lambda record: json.dumps(record, sort_keys=True))
    return {"status": status, "content_type": content_type, "body": answer}


def cli_answer(cli_bin, entry):
    proc = subprocess.run([cli_bin, *entry["cli"].split()], input=json.dumps(entry["body"]).encode(),
                          capture_output=True, timeout=TIMEOUT)
    if entry["cli"].startswith("render"):
        out = png_size(proc.stdout)
    else:
        out = json.loads(proc.stdout) if proc.stdout.strip() else None
    err = json.loads(proc.stderr) if proc.stderr.strip() else None
    return {"exit": proc.returncode, "stdout": strip_timing(out), "stderr": err}


# ---------------------------------------------------------------- comparison
NUMBER = re.compile(r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?")


def close(a, b, tolerance=RELATIVE_TOLERANCE):
    return abs(a - b) <= tolerance * max(1.0, abs(a), abs(b))


def compare_strings(want, got):
    """Texts equal apart from numbers that agree as numbers do (see the module's docstring)."""
    if want == got:
        return True
    want_parts, got_parts = NUMBER.split(want), NUMBER.split(got)
    want_numbers, got_numbers = NUMBER.findall(want), NUMBER.findall(got)
    if want_parts != got_parts or len(want_numbers) != len(got_numbers):
        return False
    return all(close(float(w), float(g)) for w, g in zip(want_numbers, got_numbers))


def kind(value):
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "number"
    return {dict: "object", list: "array", str: "string", type(None): "null"}[type(value)]


def differences(want, got, path="$", tolerance=RELATIVE_TOLERANCE):
    """Every difference between the recorded document want and the answer got, with its JSON path."""
    if kind(want) != kind(got):
        return [f"{path}: recorded {kind(want)} {json.dumps(want)[:80]}, got {kind(got)} {json.dumps(got)[:80]}"]
    if isinstance(want, dict):
        out = [f"{path}.{k}: recorded, missing now" for k in want if k not in got]
        out += [f"{path}.{k}: new, not recorded" for k in got if k not in want]
        for k in want:
            if k in got:
                out += differences(want[k], got[k], f"{path}.{k}", FIELD_TOLERANCE.get(k, RELATIVE_TOLERANCE))
        return out
    if isinstance(want, list):
        out = [] if len(want) == len(got) else [f"{path}: recorded {len(want)} elements, got {len(got)}"]
        for i, (w, g) in enumerate(zip(want, got)):
            out += differences(w, g, f"{path}[{i}]")
        return out
    if isinstance(want, str):
        return [] if compare_strings(want, got) else [f"{path}: recorded {want!r}, got {got!r}"]
    if isinstance(want, (int, float)) and not isinstance(want, bool):
        if math.isfinite(want) and close(want, got, tolerance):
            return []
        return [f"{path}: recorded {want!r}, got {got!r}"]
    return [] if want == got else [f"{path}: recorded {want!r}, got {got!r}"]


# ---------------------------------------------------------------- main
def answer_path(name):
    return os.path.join(ANSWERS, name + ".json")


def check(name, answer, record):
    """Records the answer, or compares it with the recorded one; returns the differences."""
    if record:
        with open(answer_path(name), "w") as f:
            json.dump(answer, f, indent=1, ensure_ascii=False)
            f.write("\n")
        return []
    try:
        with open(answer_path(name)) as f:
            recorded = json.load(f)
    except FileNotFoundError:
        return [f"no recorded answer {os.path.relpath(answer_path(name), ROOT)} (run with --record)"]
    return differences(recorded, answer)


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("server_bin")
    ap.add_argument("--cli", help="the lienewton CLI binary: also replays the entries that name a CLI command")
    ap.add_argument("--only", default="", help="comma-separated request names")
    ap.add_argument("--record", action="store_true", help="rewrite the recorded answers instead of comparing")
    args = ap.parse_args()
    with open(os.path.join(HERE, "requests.json")) as f:
        entries = json.load(f)
    only = {n for n in args.only.split(",") if n}
    entries = [e for e in entries if not only or e["name"] in only]
    if args.record:
        os.makedirs(ANSWERS, exist_ok=True)
    failed, checked, server_died = [], 0, False
    with tempfile.TemporaryFile() as log:
        server, port = start_server(os.path.realpath(args.server_bin), log)
        try:
            for entry in entries:
                runs = [(entry["name"], lambda e=entry: http_answer(port, e))]
                if args.cli and "cli" in entry:
                    runs.append(("cli-" + entry["name"], lambda e=entry: cli_answer(args.cli, e)))
                for name, run in runs:
                    start = time.monotonic()
                    try:
                        found = check(name, run(), args.record)
                    except (OSError, ValueError, subprocess.SubprocessError, http.client.HTTPException) as e:
                        found = [f"{type(e).__name__}: {e}"]
                        if isinstance(e, (ConnectionError, http.client.RemoteDisconnected)):
                            try:  # a server that crashed may take a moment (a core dump) to exit
                                server.wait(timeout=5)
                            except subprocess.TimeoutExpired:
                                pass
                    checked += 1
                    secs = time.monotonic() - start
                    if found:
                        failed.append(name)
                        print(f"replay: DIFF {name} ({secs:.2f} s)")
                        for line in found:
                            print(f"    {line}")
                    else:
                        print(f"replay: {'recorded' if args.record else 'ok'} {name} ({secs:.2f} s)")
                if server.poll() is not None:  # everything after would be "connection refused"
                    server_died = True
                    print(f"replay: FAIL the server exited with status {server.returncode} after {entry['name']}")
                    break
        finally:
            server.terminate()
            try:
                server.wait(timeout=10)
            except subprocess.TimeoutExpired:
                server.kill()
                server.wait()
            if failed:
                log.seek(0)
                tail = log.read().decode(errors="replace").splitlines()[-20:]
                print("server log (last lines):", *tail, sep="\n    ")
    if args.record and not only:  # answers of requests no longer in requests.json
        kept = {os.path.basename(answer_path(n)) for e in entries for n in (e["name"], "cli-" + e["name"])}
        for stale in set(os.listdir(ANSWERS)) - kept:
            os.remove(os.path.join(ANSWERS, stale))
    planned = len(entries) + (sum("cli" in e for e in entries) if args.cli else 0)
    print(f"replay: {checked - len(failed)} of {planned} answers as recorded" if not args.record
          else f"replay: {checked} answers recorded in {os.path.relpath(ANSWERS, ROOT)}")
    return 1 if failed or server_died else 0


if __name__ == "__main__":
    sys.exit(main())
