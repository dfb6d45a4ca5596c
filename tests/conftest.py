"""Settings every test shares."""

import os
import tempfile

# Starlette's TestClient sends "Host: testserver"; the real server keeps its default
# (localhost only), which the browser tests use.
os.environ.setdefault("BREAKAWAY_ALLOWED_HOSTS", "localhost,127.0.0.1,[::1],testserver")
# the fit jobs' store of this test run (the servers the tests start inherit it)
os.environ.setdefault("BREAKAWAY_DATA_DIR", tempfile.mkdtemp(prefix="breakaway-test-data-"))
