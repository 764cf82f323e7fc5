"""The Dask cluster a job runs on: the scheduler named by --scheduler, or a local cluster
of worker processes (one task each at a time: gridrt uses every core itself)."""
import logging
import urllib.parse
import urllib.request

DASHBOARD_SECONDS = 2.0  # the longest the farm waits for the dashboard's page


class ClusterError(Exception):
    """The cluster cannot be reached or started: one line, exit 1."""


def quiet_dask_logs():
    # Dask logs lost workers and closed connections; the farm's summary and its one-line
    # errors say what matters, so its logs would only interleave with them.
    for name in ("distributed", "tornado", "asyncio"):
        logging.getLogger(name).setLevel(logging.CRITICAL)


def open_client(scheduler, workers, security=None, connect_seconds=10.0):
    """A connected Client and the LocalCluster it owns (None with --scheduler); security:
    the distributed.Security of a tls:// scheduler (security.py), else None."""
    from distributed import Client, LocalCluster
    quiet_dask_logs()
    if scheduler:
        try:
            return Client(scheduler, timeout=f"{connect_seconds}s", set_as_default=True,
                          **({"security": security} if security else {})), None
        except (OSError, TimeoutError, ValueError) as e:
            raise ClusterError(f"cannot reach the scheduler at {scheduler}: "
                               f"{str(e).splitlines()[0] if str(e) else type(e).__name__}") \
                from None
    try:
        cluster = LocalCluster(n_workers=workers, threads_per_worker=1, processes=True,
                               host="127.0.0.1",
                               dashboard_address=":0",  # a free port, never a fixed one
                               silence_logs=logging.CRITICAL)
        return Client(cluster, set_as_default=True), cluster
    except (OSError, TimeoutError, RuntimeError) as e:
        raise ClusterError(f"cannot start a local cluster: {e}") from None


def dashboard_address(client):
    """The dashboard's address when the scheduler serves one, else None. Its HTTP server
    always runs; without Bokeh its status page only says that Bokeh is missing."""
    try:
        services = client.scheduler_info().get("services", {})
    except (OSError, TimeoutError):
        return None
    port = services.get("dashboard")
    if not port:
        return None
    host = urllib.parse.urlparse(client.scheduler.address).hostname or "localhost"
    url = f"http://{host}:{port}/status"
    try:
        with urllib.request.urlopen(url, timeout=DASHBOARD_SECONDS) as page:
            if b"needs bokeh" in page.read(4096).lower():
                return None
    except (OSError, ValueError):
        return None
    return url


def alive_workers(client):
    try:
        return set(client.scheduler_info().get("workers", {}))
    except (OSError, TimeoutError):
        return set()


def close(client, cluster):
    try:
        client.close(timeout=5)
    finally:
        if cluster is not None:
            cluster.close(timeout=5)
