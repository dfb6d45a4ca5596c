"""Settings every test shares."""

import os
import tempfile

# Starlette's TestClient sends "Host: testserver"; the real server keeps its default
# (localhost only), which the browser tests use.
os.environ.setdefault("BREAKAWAY_ALLOWED_HOSTS", "localhost,127.0.0.1,[::1],testserver")
# the fit jobs' store of this test run (the servers the tests start inherit it)
os.environ.setdefault("BREAKAWAY_DATA_DIR", tempfile.mkdtemp(prefix="breakaway-test-data-"))


import subprocess  # noqa: E402
import sys  # noqa: E402
from pathlib import Path  # noqa: E402

import pytest  # noqa: E402

REPO = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="session")
def built_docs(tmp_path_factory):
    """docs/ built from scratch as scripts/docs builds it (-W: a warning fails), into a
    temporary folder: ``(html_dir, completed_process)``."""
    out = tmp_path_factory.mktemp("docs")
    done = subprocess.run([sys.executable, "-m", "sphinx", "-W", "--keep-going", "-E", "-q",
                           "-b", "html", "-d", str(out / "doctrees"), str(REPO / "docs"),
                           str(out / "html")], capture_output=True, text=True, timeout=900)
    return out / "html", done
