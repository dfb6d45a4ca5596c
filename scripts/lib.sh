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

# numba's on-disk cache checks a kernel's own source file, not those of the kernels it
# calls from other files: after an edit there a caller would run stale compiled code.
# The cache is kept per state of the package's sources (older states removed), so any
# change compiles afresh.
use_kernel_cache() {
  local state
  state="$(find backend -name '*.py' -print0 | LC_ALL=C sort -z | xargs -0 cat \
    | python3 -c 'import hashlib, sys; print(hashlib.sha1(sys.stdin.buffer.read()).hexdigest()[:12])')"
  export NUMBA_CACHE_DIR="$PWD/.numba-cache/$state"
  mkdir -p "$NUMBA_CACHE_DIR"
  find .numba-cache -mindepth 1 -maxdepth 1 ! -name "$state" -exec rm -rf {} +
}
