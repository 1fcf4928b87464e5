#!/usr/bin/env bash
# Flags: `lienewton solve --n 8 --h 2 --method newton-group` is the solve of the same JSON on stdin (flags typed
# by the field table: integers, numbers, enum strings, lists), flags override stdin, --pretty prints the same JSON
# indented; an unknown field is refused naming it (exit 2); `render residuals`, `render work-precision` (also
# without choices) and `render invariants` draw PNGs, and --format svg gives the SVG copy with its title as text;
# heavy-top and stiff-body integrate; t_end may exceed the server's cap; nothing on stdin (empty or a terminal) runs
# the defaults; COMMAND --help lists the fields, --version the version; a misspelt flag gets a suggestion, an error
# on a terminal is a sentence, a picture is never written to one, --out FILE is the whole answer or nothing; long
# commands show progress on a terminal.
set -euo pipefail
bin=$1
dir=$(mktemp -d)
trap 'rm -rf "$dir"' EXIT
timeless() { jq -S 'del(.seconds, .cpu_seconds, .trace[]?.seconds, .trace[]?.cpu_seconds, .cells[]?.seconds)' "$1"; }
echo '{"n":8,"h":2,"method":"newton-group"}' | "$bin" solve > "$dir/stdin.json"
"$bin" solve --n 8 --h 2 --method newton-group < /dev/null > "$dir/flags.json"
cmp <(timeless "$dir/stdin.json") <(timeless "$dir/flags.json") || { echo "flags differ from the same JSON on stdin"; exit 1; }
echo '{"n":8,"h":0.5,"method":"fixed-point"}' | "$bin" solve --h 2 --method newton-group > "$dir/over.json"
cmp <(timeless "$dir/stdin.json") <(timeless "$dir/over.json") || { echo "flags do not override stdin"; exit 1; }
"$bin" solve --n 8 --h 2 --method newton-group --pretty < /dev/null > "$dir/pretty.json"
[[ $(wc -l < "$dir/pretty.json") -gt 10 ]] || { echo "--pretty did not indent"; exit 1; }
cmp <(timeless "$dir/flags.json") <(timeless "$dir/pretty.json") || { echo "--pretty changed the answer"; exit 1; }
# Lists and the dash spelling of a field name.
"$bin" sweep --problem paper-linear --differential exact --methods newton-group --n 3,4 --h 0.5,2 --max-iterations 50 \
  < /dev/null > "$dir/sweep.json"
[[ $(jq '.cells | length' "$dir/sweep.json") -eq 4 ]] || { echo "sweep flags: not a 2 x 2 grid"; exit 1; }
status=0
"$bin" solve --speed 3 < /dev/null 2> "$dir/err" > /dev/null || status=$?
[[ $status -eq 2 && $(jq -r '.error.field' "$dir/err") == speed ]] || { echo "unknown flag: status $status, $(cat "$dir/err")"; exit 1; }
status=0
"$bin" solve --h abc < /dev/null 2> "$dir/err" > /dev/null || status=$?
[[ $status -eq 2 && $(jq -r '.error.field' "$dir/err") == h ]] || { echo "bad h: status $status, $(cat "$dir/err")"; exit 1; }
png() { [[ $(head -c 8 "$1" | od -An -tx1 | tr -d ' \n') == 89504e470d0a1a0a ]]; }
"$bin" render residuals --n 3 --h 0.5 --methods newton-group,fixed-point < /dev/null > "$dir/residuals.png"
png "$dir/residuals.png" || { echo "render residuals: not a PNG"; exit 1; }
echo '{"problem":"rigid-body","h":[0.25,0.125],"choices":[{"integrator":"implicit-euler"}]}' \
  | "$bin" render work-precision --width 480 --height 320 > "$dir/wp.png"
png "$dir/wp.png" || { echo "render work-precision: not a PNG"; exit 1; }
# Without choices it takes the defaults GET and POST take (every integrator), not a 400.
"$bin" render work-precision --problem rigid-body --h 0.25,0.125 --t-end 0.5 < /dev/null > "$dir/wp-defaults.png"
png "$dir/wp-defaults.png" || { echo "render work-precision without choices: not a PNG"; exit 1; }
# The CLI takes a t_end beyond the server's cap (--max-t-end, 100 by default).
"$bin" integrate --problem rigid-body --integrator rkmk4 --h 0.5 --t-end 200 < /dev/null > "$dir/long.json"
jq -e '.status == "converged" and (.steps | length) == 400' "$dir/long.json" > /dev/null \
  || { echo "integrate t_end 200: $(head -c 300 "$dir/long.json")"; exit 1; }
"$bin" render heatmap --methods newton-group --n 3,4 --h 1,2 --format svg < /dev/null > "$dir/heatmap.svg"
grep -q '^<svg xmlns="http://www.w3.org/2000/svg"' "$dir/heatmap.svg" || { echo "render heatmap --format svg: not SVG"; exit 1; }
# The title, wrapped between words on so narrow a picture: its <text> lines read as one.
grep -o '<text[^>]*>[^<]*</text>' "$dir/heatmap.svg" | sed 's/<[^>]*>//g' | tr '\n' ' ' \
  | grep -q 'Where each method converges: paper-linear on SO(N)' || { echo "SVG without its title"; exit 1; }
# The heavy top by flags (its parameters as a JSON object), its invariants' drifts, and their picture.
"$bin" integrate --problem heavy-top --group SOxR --integrator dirk-cg2 --h 0.0078125 --t-end 0.0625 \
  --heavy-top '{"mass":10}' < /dev/null > "$dir/top.json"
jq -e '.status == "converged" and (.energy_drift > 0) and (.vertical_momentum_drift > 0) and (.steps | length) == 8' \
  "$dir/top.json" > /dev/null || { echo "integrate heavy-top: $(head -c 300 "$dir/top.json")"; exit 1; }
"$bin" render invariants --problem heavy-top --group SOxR --h 0.0078125 --t-end 0.0625 --width 320 --height 240 \
  < /dev/null > "$dir/invariants.png"
png "$dir/invariants.png" || { echo "render invariants: not a PNG"; exit 1; }
# The stiff body by flags (its group implied): it converges and, forced and damped, reports no invariants.
"$bin" integrate --problem stiff-body --integrator dirk-cg2 --h 0.0625 --t-end 0.25 \
  --stiff-body '{"k":1e5,"c":1e5}' < /dev/null > "$dir/stiff.json"
jq -e '.status == "converged" and .energy_drift == null and (.steps | length) == 4' "$dir/stiff.json" > /dev/null \
  || { echo "integrate stiff-body: $(head -c 300 "$dir/stiff.json")"; exit 1; }
# Nothing on stdin runs the command's defaults: empty (</dev/null) or a terminal (a pty by script(1)), which is
# never waited on.
"$bin" solve < /dev/null > "$dir/defaults.json"
jq -e '.status == "converged"' "$dir/defaults.json" > /dev/null || { echo "solve </dev/null: $(head -c 300 "$dir/defaults.json")"; exit 1; }
timeout 60 script -qec "$bin solve" /dev/null > "$dir/tty.txt" || { echo "solve on a terminal: no answer"; exit 1; }
grep -q '"status":"converged"' "$dir/tty.txt" || { echo "solve on a terminal: $(head -c 300 "$dir/tty.txt")"; exit 1; }
# Each command's --help (or help COMMAND) lists its fields from the request contract; --version.
"$bin" solve --help > "$dir/help.txt"
grep -q '^  --n INTEGER$' "$dir/help.txt" && grep -q 'default 1e-13' "$dir/help.txt" \
  || { echo "solve --help: $(head -c 300 "$dir/help.txt")"; exit 1; }
"$bin" help render frames | grep '^  --azimuth-deg NUMBER$' > /dev/null || { echo "help render frames: no --azimuth-deg"; exit 1; }
"$bin" help integrate | grep '^  --integrator NAME$' > /dev/null || { echo "help integrate: no --integrator"; exit 1; }
status=0
"$bin" help solvee > /dev/null 2> "$dir/err" || status=$?
[[ $status -eq 2 ]] || { echo "help of no command: status $status"; exit 1; }
"$bin" --version | grep -Eq '^lienewton [0-9]+\.[0-9]+\.[0-9]+$' || { echo "--version: $("$bin" --version)"; exit 1; }
# A misspelt flag is told its nearest field; on a terminal an error is a sentence, not JSON.
status=0
"$bin" solve --methd newton-group < /dev/null 2> "$dir/err" > /dev/null || status=$?
[[ $status -eq 2 ]] && jq -e '.error.field == "methd" and (.error.message | contains("did you mean --method?"))' \
  "$dir/err" > /dev/null || { echo "misspelt flag: status $status, $(cat "$dir/err")"; exit 1; }
status=0
script -qec "$bin solve --methd newton-group" /dev/null > "$dir/tty-err.txt" || status=$?
[[ $status -eq 2 ]] && grep -q '^lienewton: lienewton solve takes no field methd; did you mean --method?' "$dir/tty-err.txt" \
  && ! grep -q '{"error"' "$dir/tty-err.txt" || { echo "error on a terminal: status $status, $(cat "$dir/tty-err.txt")"; exit 1; }
# No picture on a terminal; --out FILE holds the whole answer or, on an error, nothing.
status=0
script -qec "$bin render residuals --n 3 --h 0.5" /dev/null > "$dir/tty-png.txt" || status=$?
[[ $status -eq 2 ]] && grep -q 'not written to a terminal' "$dir/tty-png.txt" \
  || { echo "PNG to a terminal: status $status, $(head -c 200 "$dir/tty-png.txt")"; exit 1; }
"$bin" render residuals --n 3 --h 0.5 --out "$dir/out.png" < /dev/null > "$dir/stdout.txt"
png "$dir/out.png" && [[ ! -s "$dir/stdout.txt" ]] || { echo "render --out: no PNG in the file or bytes on stdout"; exit 1; }
"$bin" solve --out "$dir/out.json" < /dev/null
cmp <(timeless "$dir/out.json") <(timeless "$dir/defaults.json") || { echo "solve --out differs from stdout"; exit 1; }
status=0
"$bin" solve --h abc --out "$dir/bad.json" < /dev/null 2> /dev/null || status=$?
[[ $status -eq 2 ]] && ! compgen -G "$dir/bad.json*" > /dev/null || { echo "--out after an error: status $status, $(ls "$dir")"; exit 1; }
# --out keeps an existing file's mode, refuses a symbolic link or FIFO unless --out-through, and leaves no
# temporary when a signal ends the write (SIGXFSZ: the file size limit is below the picture's size).
printf 'old' > "$dir/private.json" && chmod 600 "$dir/private.json"
"$bin" solve --out "$dir/private.json" < /dev/null
[[ $(stat -c %a "$dir/private.json") == 600 ]] && cmp -s <(timeless "$dir/private.json") <(timeless "$dir/defaults.json") \
  || { echo "--out over a 0600 file: mode $(stat -c %a "$dir/private.json")"; exit 1; }
ln -s private.json "$dir/link.json"
status=0
"$bin" solve --out "$dir/link.json" < /dev/null 2> "$dir/link-err.txt" || status=$?
[[ $status -eq 2 && -L "$dir/link.json" ]] && grep -q 'symbolic link' "$dir/link-err.txt" \
  || { echo "--out over a symlink: status $status, $(cat "$dir/link-err.txt")"; exit 1; }
"$bin" solve --n 4 --out "$dir/link.json" --out-through < /dev/null
"$bin" solve --n 4 < /dev/null > "$dir/n4.json"
[[ -L "$dir/link.json" && $(stat -c %a "$dir/private.json") == 600 ]] \
  && cmp -s <(timeless "$dir/private.json") <(timeless "$dir/n4.json") \
  || { echo "--out-through a symlink: not written through"; exit 1; }
mkfifo "$dir/fifo"
status=0
"$bin" solve --out "$dir/fifo" < /dev/null 2> "$dir/fifo-err.txt" || status=$?
[[ $status -eq 2 && -p "$dir/fifo" ]] && grep -q 'FIFO' "$dir/fifo-err.txt" || { echo "--out into a FIFO: status $status"; exit 1; }
cat "$dir/fifo" > "$dir/from-fifo.json" &
"$bin" solve --out "$dir/fifo" --out-through < /dev/null
wait
cmp -s <(timeless "$dir/from-fifo.json") <(timeless "$dir/defaults.json") || { echo "--out-through a FIFO: not the answer"; exit 1; }
status=0
(ulimit -f 1; exec "$bin" render residuals --n 3 --h 0.5 --out "$dir/big.png" < /dev/null 2> /dev/null) || status=$?
[[ $status -ne 0 ]] && ! compgen -G "$dir/big.png*" > /dev/null || { echo "SIGXFSZ: status $status, $(ls "$dir")"; exit 1; }
# A read error on stdin (a directory) is an error, not an empty request.
status=0
"$bin" solve < / > /dev/null 2> "$dir/dir-err.txt" || status=$?
[[ $status -ne 0 ]] && grep -q 'cannot read stdin' "$dir/dir-err.txt" || { echo "solve < /: status $status"; exit 1; }
# render frames takes an integration's fields as flags too.
"$bin" render frames --problem rigid-body --integrator dirk-cg2 --h 0.25 --t-end 1 --frames 4 --width 96 --height 96 \
  < /dev/null > "$dir/frames.png"
png "$dir/frames.png" || { echo "render frames --integrator: not a PNG"; exit 1; }
"$bin" help render frames | grep '^  --integrator NAME$' > /dev/null || { echo "help render frames: no --integrator"; exit 1; }
# Progress on a terminal's stderr (the first row at once), none with --quiet or off a terminal.
script -qec "$bin basins --size 16" /dev/null > "$dir/tty-basins.txt"
grep -q 'lienewton basins: 1 of 16 rows' "$dir/tty-basins.txt" || { echo "basins on a terminal: no progress"; exit 1; }
script -qec "$bin basins --size 16 --quiet" /dev/null > "$dir/tty-quiet.txt"
! grep -q 'lienewton basins:' "$dir/tty-quiet.txt" || { echo "basins --quiet: progress shown"; exit 1; }
"$bin" basins --size 16 < /dev/null 2> "$dir/basins-err.txt" > /dev/null
[[ ! -s "$dir/basins-err.txt" ]] || { echo "basins off a terminal: $(head -c 200 "$dir/basins-err.txt")"; exit 1; }
echo "flags, --pretty, --quiet, --help, --version, --out, empty stdin, progress, errors and the render commands behave"
