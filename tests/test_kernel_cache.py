"""The test and run scripts keep numba's cache per state of the package's sources."""

from __future__ import annotations

import subprocess
from pathlib import Path

ROOT = Path(__file__).resolve().parent.parent


def _cache_dir(repo: Path) -> Path:
    out = subprocess.run(["bash", "-c", f"source {ROOT / 'scripts/lib.sh'}; use_kernel_cache; "
                          "echo \"$NUMBA_CACHE_DIR\""], cwd=repo, capture_output=True,
                         text=True, check=True)
    return Path(out.stdout.strip())


def test_an_edit_anywhere_in_the_package_starts_a_fresh_kernel_cache(tmp_path):
    # numba checks a cached kernel against its own file only: a kernel it calls from
    # another file, once edited, would run stale from the old cache
    package = tmp_path / "backend" / "pkg"
    package.mkdir(parents=True)
    (package / "callee.py").write_text("def f():\n    return 1\n")
    (package / "caller.py").write_text("from .callee import f\n")
    first = _cache_dir(tmp_path)
    assert first.is_dir() and first.parent == tmp_path / ".numba-cache"
    (first / "kernel.nbi").write_text("compiled")
    assert _cache_dir(tmp_path) == first and (first / "kernel.nbi").exists()
    (package / "callee.py").write_text("def f():\n    return 2\n")
    second = _cache_dir(tmp_path)
    assert second != first and second.is_dir()
    assert not first.exists()  # the old state's kernels are gone
