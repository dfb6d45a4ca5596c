# Shared set-up steps of scripts/run and scripts/test.

ensure_venv() {
  local extras="${1:-}"
  if [ ! -x .venv/bin/python ]; then
    python3 -m venv .venv
  fi
  .venv/bin/python -m pip install --quiet --disable-pip-version-check --upgrade pip
  if [ -n "$extras" ]; then
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -e ".[$extras]"
  else
    .venv/bin/python -m pip install --quiet --disable-pip-version-check -e .
  fi
}

# The browser tests use Debian's chromium where it can be installed (as root with
# apt-get) and Playwright's own browser elsewhere. BREAKAWAY_CHROMIUM tells the tests
# which executable to launch; empty means Playwright's bundled one.
ensure_chromium() {
  if [ -n "${BREAKAWAY_CHROMIUM:-}" ] && [ -x "${BREAKAWAY_CHROMIUM}" ]; then
    return
  fi
  if ! command -v chromium >/dev/null 2>&1 && [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null 2>&1; then
    echo "Installing Debian's chromium for the browser tests..."
    DEBIAN_FRONTEND=noninteractive apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
  fi
  if command -v chromium >/dev/null 2>&1; then
    export BREAKAWAY_CHROMIUM="$(command -v chromium)"
  else
    echo "No system chromium; installing Playwright's own browser..."
    .venv/bin/python -m playwright install chromium
    export BREAKAWAY_CHROMIUM=""
  fi
}
