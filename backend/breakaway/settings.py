"""Settings in one place (environment variables prefixed ``BREAKAWAY_``)."""

from __future__ import annotations

from functools import lru_cache
from pathlib import Path

from pydantic import Field
from pydantic_settings import BaseSettings, SettingsConfigDict

_REPO = Path(__file__).resolve().parents[2]
_REPO_FRONTEND = _REPO / "frontend"


class Settings(BaseSettings):
    """Server and engine settings; each can be overridden by ``BREAKAWAY_<NAME>``."""

    model_config = SettingsConfigDict(env_prefix="BREAKAWAY_")

    host: str = "127.0.0.1"
    port: int = 8000
    frontend_dir: Path = _REPO_FRONTEND
    #: The built documentation (``scripts/docs``), served under /guide/.
    docs_dir: Path = _REPO / "docs" / "_build" / "html"
    #: Largest accepted upload for /api/fit [bytes] (20 MiB).
    max_upload_bytes: int = 20 * 1024 * 1024
    #: Largest request body for the JSON endpoints [bytes].
    max_json_bytes: int = 64 * 1024
    #: Caps on grid sizes and rate lists in requests.
    max_grid_points: int = 5000
    max_rates: int = 64
    #: Caps of a plan of the next experiment (POST /api/plan): runs, and candidate
    #: design points (rates, speeds, the sine's amplitudes times frequencies).
    max_plan_runs: int = 64
    max_plan_grid: int = 400
    #: Significant digits of /api/explore floats when they cannot go as float32 (see
    #: api/encoding.py; 7 digits keep the relative error below 5e-7).
    payload_digits: int = 7
    #: Ramp simulations run in a worker process so that a slow one never blocks the
    #: explorer: its wall-clock budget per request [s] and step budget per rate.
    simulate_timeout_s: float = 20.0
    simulate_max_steps: int = 1_000_000
    #: Longest simulated time of a /api/loop run [s] (its output grid is capped by
    #: max_grid_points).
    loop_max_duration: float = 60.0
    #: Simulation requests that may wait for the worker; more are answered 503 at once.
    simulate_queue: int = 16
    #: Where the server keeps its state: the fit jobs' SQLite store (``jobs.sqlite``);
    #: ``data`` under the directory the server starts in by default. Several server
    #: processes on one data directory share their jobs.
    data_dir: Path = Path("data")
    #: Fit worker processes per server process, and fits that may wait for one; a fit
    #: beyond both is refused with 429 before its upload is read.
    fit_workers: int = 2
    fit_queue: int = 2
    #: Added to the scheduling niceness of the fit processes and the upload reader (0 to
    #: 19): they are batch work, and the explorer's requests and the simulations come
    #: first when the CPU is short (benchmarks/bench_lecture.py).
    fit_niceness: int = Field(10, ge=0, le=19)
    #: A fit's time limit [s], counted from when it starts running.
    fit_timeout_s: float = 600.0
    #: Bounds of the job store: finished jobs older than this [s] are dropped, then the
    #: oldest until the stored results take at most this many bytes.
    jobs_max_age_s: float = 86_400.0
    jobs_max_bytes: int = 256 * 2**20
    #: Host names the server answers to (the Host header; a port is ignored), comma
    #: separated; "*" answers any. Localhost by default: a page elsewhere cannot reach
    #: the server through a rebound DNS name. Set the public name behind a proxy.
    allowed_hosts: str = "localhost,127.0.0.1,[::1]"
    #: Origins (scheme://host[:port]) whose pages may call the API from the browser,
    #: comma separated; empty (the default) keeps CORS off and refuses their requests.
    cors_origins: str = ""

    def cors_origin_list(self) -> list[str]:
        return [o.strip() for o in self.cors_origins.split(",") if o.strip()]

    def host_allowed(self, host: str) -> bool:
        names = [h.strip().lower() for h in self.allowed_hosts.split(",") if h.strip()]
        if "*" in names:
            return True
        name = host.lower()
        if name.startswith("["):
            name = name[: name.find("]") + 1]
        else:
            name = name.rsplit(":", 1)[0]
        return name in names


@lru_cache
def get_settings() -> Settings:
    return Settings()
