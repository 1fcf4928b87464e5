#!/usr/bin/env bash
# Runs the README's examples and checks its links (ctest: readme_examples).
#   scripts/check_readme.sh path/to/lienewton-server
# - Every ```sh block of README.md that is directly followed by an output block (```json or ```text) is run, with
#   `localhost:8080` pointing at a server started here and `build/bin/` at the binary's directory, in a scratch
#   directory; every HTTP answer must be 200, and what the block prints must equal the output pasted below it.
#   Numbers are compared as a reader reads them: below 1e-10 (rounding: another CPU or compiler prints another
#   1e-16) as "rounding", others to 4 significant digits; `seconds` and `cpu_seconds` are timing and not compared.
# - The README has at most 250 lines.
# - Every relative link in README.md and docs/*.md names a file that exists, and an anchor a heading (or an
#   explicit id) of that file.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
server=$(realpath "${1:?usage: $0 path/to/lienewton-server}")
bindir=$(dirname "$server")
[ -x "$bindir/lienewton" ] || { echo "check_readme: no $bindir/lienewton beside the server"; exit 1; }
for tool in curl jq python3; do
  command -v "$tool" >/dev/null || { echo "check_readme: $tool is needed (scripts/packages-test.txt)"; exit 1; }
done

lines=$(wc -l < "$root/README.md")
[ "$lines" -le 250 ] || { echo "check_readme: README.md has $lines lines (at most 250)"; exit 1; }

work=$(mktemp -d)
pid=
cleanup() {
  [ -z "$pid" ] || kill "$pid" 2>/dev/null || true
  [ -z "$pid" ] || wait "$pid" 2>/dev/null || true
  rm -rf "$work"
}
trap cleanup EXIT

port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])')
"$server" --host 127.0.0.1 --port "$port" --web-root "$root/web" >"$work/server.log" 2>&1 &
pid=$!
for _ in $(seq 100); do
  curl -sf "http://127.0.0.1:$port/readyz" >/dev/null 2>&1 && break
  sleep 0.1
done
curl -sf "http://127.0.0.1:$port/readyz" >/dev/null || { echo "check_readme: server did not start"; cat "$work/server.log"; exit 1; }

# The examples and their pasted outputs, one pair of files per example.
python3 - "$root/README.md" "$work" <<'EOF'
import re, sys
text = open(sys.argv[1], encoding="utf-8").read().split("\n")
blocks, i = [], 0
while i < len(text):
    m = re.match(r"^```(\w*)$", text[i])
    if m:
        j = i + 1
        while text[j] != "```":
            j += 1
        blocks.append((m.group(1), "\n".join(text[i + 1:j]) + "\n", i + 1, j))
        i = j
    i += 1
n = 0
for (lang, body, start, end), nxt in zip(blocks, blocks[1:] + [None]):
    if lang == "sh" and nxt and nxt[0] in ("json", "text") and nxt[2] == end + 2:
        n += 1
        open(f"{sys.argv[2]}/example-{n}.sh", "w").write(body)
        open(f"{sys.argv[2]}/example-{n}.expected", "w").write(nxt[1])
        open(f"{sys.argv[2]}/example-{n}.line", "w").write(str(start))
print(f"check_readme: {n} examples with pasted output", file=sys.stderr)
EOF

normalise() {  # file: numbers as a reader compares them, timing fields blanked
  python3 - "$1" <<'EOF'
import re, sys
s = open(sys.argv[1], encoding="utf-8").read()
s = re.sub(r'("(?:cpu_)?seconds": ?)[-0-9.eE+]+', r'\1<timing>', s)
def number(m):
    x = float(m.group(0))
    return "<rounding>" if abs(x) < 1e-10 else f"{x:.4g}"
print(re.sub(r"(?<![\w.])-?\d+\.\d+(?:[eE][-+]?\d+)?(?![\w.])|(?<![\w.])-?\d+[eE][-+]?\d+(?![\w.])", number, s), end="")
EOF
}

failed=0
count=0
cd "$work"
for script in example-*.sh; do
  count=$((count + 1))
  name=${script%.sh}
  line=$(cat "$name.line")
  {
    echo "set -o pipefail"
    # Every answer's status goes to stderr (an example's own --write-out replaces it, and prints the status itself).
    echo "curl() { command curl --write-out '%{stderr}%{http_code}\n' \"\$@\"; }"
    sed -e "s#localhost:8080#127.0.0.1:$port#g" -e "s#build/bin/#$bindir/#g" "$script"
  } > "$name.run"
  if ! bash "$name.run" > "$name.out" 2> "$name.err"; then
    echo "check_readme: README line $line: the example failed"; cat "$name.err"; failed=1; continue
  fi
  if grep -E '^[0-9]{3}$' "$name.err" | grep -vx 200 >/dev/null; then
    echo "check_readme: README line $line: an answer was not 200:"; cat "$name.err"; failed=1; continue
  fi
  if ! diff -u <(normalise "$name.expected") <(normalise "$name.out") > "$name.diff"; then
    echo "check_readme: README line $line: the output differs from the README's (- README, + now):"
    cat "$name.diff"; failed=1
  fi
done
[ "$count" -gt 0 ] || { echo "check_readme: no examples found"; exit 1; }

# Relative links of the README and docs/.
python3 - "$root" <<'EOF' || failed=1
import os, re, sys
root = sys.argv[1]
def anchors(path):
    found, fence = set(), False
    for line in open(path, encoding="utf-8"):
        if line.startswith("```"):
            fence = not fence
        if fence:
            continue
        m = re.match(r"^#+\s+(.*?)\s*$", line)
        if m:  # GitHub's slug: lower case, punctuation dropped, spaces to hyphens
            found.add(re.sub(r"[^\w\- ]", "", m.group(1).lower()).replace(" ", "-"))
        found.update(re.findall(r'<a id="([^"]+)"', line))
    return found
bad = 0
files = [os.path.join(root, "README.md")] + sorted(
    os.path.join(root, "docs", f) for f in os.listdir(os.path.join(root, "docs")) if f.endswith(".md"))
for path in files:
    fence = False
    for number, line in enumerate(open(path, encoding="utf-8"), 1):
        if line.startswith("```"):
            fence = not fence
        if fence:
            continue
        line = re.sub(r"`[^`]*`", "", line)
        for target in re.findall(r"\]\(([^)\s]+)\)", line):
            if re.match(r"^[a-z]+:", target):
                continue
            file, _, anchor = target.partition("#")
            dest = os.path.normpath(os.path.join(os.path.dirname(path), file)) if file else path
            where = f"{os.path.relpath(path, root)}:{number}"
            if not os.path.exists(dest):
                print(f"check_readme: {where}: link to a missing file {target}"); bad = 1
            elif anchor and dest.endswith(".md") and anchor not in anchors(dest):
                print(f"check_readme: {where}: link to a missing heading {target}"); bad = 1
sys.exit(bad)
EOF

[ "$failed" -eq 0 ] || exit 1
echo "check_readme: $count examples and every link ok"
