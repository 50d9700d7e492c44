#!/usr/bin/env bash
# The report page in a real browser (headless Chromium, Debian's chromium package): a short run
# of the main job writes the page; the browser must render it with no script error, every plot
# drawn and the map decoded; `cullcheck html` must rewrite the same bytes from report.json; and
# the checks must fire on a page with a script error and on one whose map is broken. The
# screenshot is kept as the test run's artifact: ARTIFACT_DIR/report-page.png.
# Usage: browser_test.sh /path/to/cullcheck ARTIFACT_DIR
set -u
cc="$1"
artifacts="$2"
browser=$(command -v chromium || command -v chromium-browser || true)
if [ -z "$browser" ]; then
  echo "FAIL: no chromium on PATH (bash ci/install-deps.sh installs Debian's chromium package)"
  exit 1
fi
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
mkdir -p "$artifacts"
failures=0
fail() { echo "FAIL: $*"; failures=$((failures + 1)); }

headless() {  # headless Chromium with its own profile; no sandbox (CI runs as root)
  timeout 180 "$browser" --headless --no-sandbox --disable-gpu --disable-dev-shm-usage --no-first-run --hide-scrollbars \
    --user-data-dir="$work/profile" "$@" 2>>"$work/browser.log"
}

# The body's verdict attributes after the page's scripts ran (data-rendered, -script-errors, -plots, -map).
body_of() { headless --virtual-time-budget=5000 --dump-dom "file://$1" | grep -o '<body[^>]*>' | head -1; }
attribute() { sed -n "s/.*$1=\"\\([^\"]*\\)\".*/\\1/p" <<<"$2"; }

# A short main job: 40 frames of the default city, a radius sweep, a small VbAoI city, the claims ledger.
(cd "$work" && "$cc" report --path-params '{"frames":40}' --region-sweep 0.5,1,2 --claim-scenes 3 \
  --vbaoi --vbaoi-params '{"blocks_x":5,"blocks_y":5}' --vbaoi-clients 5,20 --output report.json --html page.html \
  >report.out 2>&1) || { fail "cullcheck report exited $?"; tail -5 "$work/report.out"; }
[ -s "$work/page.html" ] || { fail "no page written"; exit 1; }

body=$(body_of "$work/page.html")
echo "rendered: $body"
[ "$(attribute data-rendered "$body")" = yes ] || fail "the page's script did not finish (no data-rendered)"
[ "$(attribute data-script-errors "$body")" = 0 ] || fail "script errors: $(attribute data-script-error-text "$body")"
plots=$(attribute data-plots "$body")
drawn=$(attribute data-plots-with-data "$body")
[ "${plots:-0}" -ge 9 ] || fail "expected at least 9 plots (Pareto x3, per frame x2, radius sweep x2, VbAoI x2), found ${plots:-none}"
[ "${drawn:-0}" = "${plots:-x}" ] || fail "only ${drawn:-0} of ${plots:-0} plots have data drawn"
[ "$(attribute data-map "$body")" = drawn ] || fail "the map image did not decode"
headless --window-size=1280,2400 --screenshot="$artifacts/report-page.png" "file://$work/page.html" >/dev/null
[ "$(stat -c %s "$artifacts/report-page.png" 2>/dev/null || echo 0)" -gt 50000 ] || fail "no screenshot (or a blank one) in $artifacts"
cp "$work/page.html" "$artifacts/report-page.html"

# The page from report.json alone (its scene rebuilt from the replay flags) is the same page.
"$cc" html "$work/report.json" -o "$work/again.html" >/dev/null || fail "cullcheck html exited $?"
cmp -s "$work/page.html" "$work/again.html" || fail "cullcheck html wrote a different page than report --html"

# The checks fire: a script error is counted; a broken map is reported.
sed "s|<body>|<body><script>undefinedFunction();</script>|" "$work/page.html" >"$work/error.html"
[ "$(attribute data-script-errors "$(body_of "$work/error.html")")" = 1 ] || fail "a page with a script error was not caught"
sed 's|data:image/png;base64,iVBOR|data:image/png;base64,XXXXX|' "$work/page.html" >"$work/broken.html"
[ "$(attribute data-map "$(body_of "$work/broken.html")")" = none ] || fail "a page with a broken map was not caught"

if [ "$failures" -gt 0 ]; then
  echo "browser_test: $failures failures (browser log: last lines)"; tail -5 "$work/browser.log"
  exit 1
fi
echo "browser_test: the page renders in $("$browser" --version 2>/dev/null); screenshot $artifacts/report-page.png"
