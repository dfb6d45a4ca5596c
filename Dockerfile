# The Breakaway explorer: the same server as `scripts/run`, on port 8000.
#
#   docker build -t breakaway .
#   docker run --rm -p 8000:8000 breakaway        # then open http://localhost:8000
#   docker run -p 8000:8000 -v breakaway-data:/app/data breakaway serve --host 0.0.0.0 --workers 4
FROM python:3.11-slim

# The installed package lives in site-packages, the static explorer stays in /app/frontend;
# numba's compiled-function cache is written at build time and read by the app user.
ENV PYTHONDONTWRITEBYTECODE=1 \
    PYTHONUNBUFFERED=1 \
    PIP_NO_CACHE_DIR=1 \
    PIP_DISABLE_PIP_VERSION_CHECK=1 \
    BREAKAWAY_FRONTEND_DIR=/app/frontend \
    BREAKAWAY_DATA_DIR=/app/data \
    NUMBA_CACHE_DIR=/app/.numba-cache

RUN useradd --create-home --uid 10001 --shell /usr/sbin/nologin breakaway
WORKDIR /app

# Dependencies first: this layer is rebuilt only when pyproject.toml changes.
COPY pyproject.toml ./
RUN python -c "import tomllib; deps = tomllib.load(open('pyproject.toml', 'rb'))['project']['dependencies']; open('/tmp/requirements.txt', 'w').write(chr(10).join(deps))" \
 && pip install -r /tmp/requirements.txt \
 && rm /tmp/requirements.txt

# Then the code.
COPY README.md ./
COPY backend/ backend/
COPY frontend/ frontend/
RUN pip install --no-deps . \
 && rm -rf build backend/*.egg-info \
 && mkdir -p "$NUMBA_CACHE_DIR" "$BREAKAWAY_DATA_DIR" \
 && chown breakaway "$NUMBA_CACHE_DIR" "$BREAKAWAY_DATA_DIR"

USER breakaway
# Compile the numba kernels once now (~15 s) instead of on the first request or fit:
# the explorer's, the ramp simulation's, and the identification's (play, lag, E6').
RUN python -c "from breakaway.frame import explore_frame; from breakaway.dynamics import simulate_breakaway, simulate_lugre_breakaway; explore_frame(); simulate_breakaway([1.0], 1.0, 1.5, 100.0, 1.0); simulate_lugre_breakaway([1.0])" \
 && python -c "from breakaway.identify import identify; from breakaway.identify.synthetic import make_dataset; identify(make_dataset('timeseries', ('backlash', 'lag'), n=2000)[0])"

# the fit jobs' store: a volume keeps finished results across container restarts
VOLUME ["/app/data"]
EXPOSE 8000
HEALTHCHECK --interval=30s --timeout=5s --start-period=30s --retries=3 \
  CMD ["python", "-c", "import sys, urllib.request; sys.exit(0 if urllib.request.urlopen('http://127.0.0.1:8000/api/health', timeout=4).status == 200 else 1)"]
CMD ["breakaway", "serve", "--host", "0.0.0.0", "--port", "8000"]
