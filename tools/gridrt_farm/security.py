"""How the farm reaches a scheduler. A Dask client can run any function on every worker,
so whoever reaches an open scheduler runs code on every machine of the farm: off loopback
the farm speaks tls:// with mutual certificates (distributed.Security: the scheduler and
the workers accept only certificates signed by the farm's CA, and this client shows one
too); tcp:// only to a loopback address, or with --insecure."""
import ipaddress
import os
import socket

from .command_line import UsageError

SCHEMES = ("tcp", "tls")
# Dask's configuration keys for the client's side of TLS (dask config files, or
# DASK_DISTRIBUTED__COMM__TLS__CA_FILE and the like), used when no --tls-* flag is given.
CONFIG_KEYS = ("distributed.comm.tls.ca-file", "distributed.comm.tls.client.cert",
               "distributed.comm.tls.client.key")
TLS_FLAGS = ("--tls-ca-file", "--tls-cert", "--tls-key")


def split_address(address):
    """(scheme, host) of a Dask address: tcp://HOST:PORT, tls://HOST:PORT, [IPv6]:PORT;
    without a scheme Dask takes tcp."""
    scheme, sep, location = address.partition("://")
    if not sep:
        scheme, location = "tcp", address
    if scheme not in SCHEMES:
        raise UsageError(f"--scheduler: expected tls://HOST:PORT or tcp://HOST:PORT, got "
                         f"'{address}'")
    if location.startswith("["):
        host = location[1:location.find("]")] if "]" in location else ""
    else:
        host = location.rsplit(":", 1)[0] if ":" in location else location
    if not host:
        raise UsageError(f"--scheduler: no host in '{address}'")
    return scheme, host


def is_loopback(host):
    """Whether every address the host name resolves to is a loopback address."""
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        pass
    try:
        infos = socket.getaddrinfo(host, None)
    except OSError:
        return False
    return bool(infos) and all(ipaddress.ip_address(i[4][0].split("%")[0]).is_loopback
                               for i in infos)


def _readable(flag, path):
    try:
        with open(path, "rb"):
            pass
    except OSError as e:
        raise UsageError(f"{flag}: cannot read '{path}': {e.strerror}") from None
    return os.path.abspath(path)


def connection_security(cmd):
    """The distributed.Security for --scheduler (None: plain tcp:// as allowed), or a
    UsageError saying why the address is refused."""
    flags = dict(zip(TLS_FLAGS, (cmd.tls_ca_file, cmd.tls_cert, cmd.tls_key)))
    given = [f for f, v in flags.items() if v]
    if not cmd.scheduler:
        if given or cmd.insecure:
            raise UsageError(f"{(given or ['--insecure'])[0]}: only with --scheduler")
        return None
    scheme, host = split_address(cmd.scheduler)
    if scheme == "tcp":
        if given:
            raise UsageError(f"{given[0]}: only with a tls:// scheduler")
        if not cmd.insecure and not is_loopback(host):
            raise UsageError(f"--scheduler: tcp:// to {host}, not a loopback address, is "
                             "refused: unencrypted, and whoever reaches the scheduler runs code "
                             "on every worker; use tls:// with --tls-ca-file, --tls-cert and "
                             "--tls-key (docs/farm.md), or --insecure on a network you trust")
        return None
    from distributed import Security
    import dask
    if given:
        if len(given) != len(TLS_FLAGS):
            missing = [f for f in TLS_FLAGS if f not in given]
            raise UsageError(f"tls://: {', '.join(missing)} missing ({', '.join(TLS_FLAGS)} "
                             "go together)")
        files = {f: _readable(f, v) for f, v in flags.items()}
        return Security(tls_ca_file=files["--tls-ca-file"], tls_client_cert=files["--tls-cert"],
                        tls_client_key=files["--tls-key"], require_encryption=True)
    configured = [dask.config.get(k, None) for k in CONFIG_KEYS]
    if not all(configured[:2]):  # the key may be inside the certificate's file
        raise UsageError("tls://: give --tls-ca-file, --tls-cert and --tls-key (or Dask's "
                         + ", ".join(CONFIG_KEYS) + ")")
    return Security(require_encryption=True)
