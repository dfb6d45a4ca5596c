"""Settings every test shares."""

import os

# Starlette's TestClient sends "Host: testserver"; the real server keeps its default
# (localhost only), which the browser tests use.
os.environ.setdefault("BREAKAWAY_ALLOWED_HOSTS", "localhost,127.0.0.1,[::1],testserver")
