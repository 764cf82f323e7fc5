#!/usr/bin/python3
"""A client the farm's scheduler must refuse: tries to reach ADDRESS (with --ca, --cert and
--key as given) and, once connected, to have a worker write the file MARKER. Exit 0: it
ran; 3: the scheduler could not be reached; 1: anything else."""
import argparse
import ssl
import sys

REFUSED = 3
CONNECT_SECONDS = 3  # the farm's scheduler answers within a second on the test's network


def main():
    p = argparse.ArgumentParser()
    p.add_argument("address")
    p.add_argument("marker")
    p.add_argument("--ca")
    p.add_argument("--cert")
    p.add_argument("--key")
    a = p.parse_args()
    from distributed import Client, Security

    class CertificateLess(Security):
        """TLS that trusts --ca but shows no certificate of its own (Security alone makes
        no TLS context without one)."""

        def get_connection_args(self, role):
            context = ssl.create_default_context(ssl.Purpose.SERVER_AUTH, cafile=a.ca)
            context.check_hostname = False  # as Dask's own contexts
            return {"ssl_context": context, "require_encryption": True, "extra_conn_args": {}}
    tls = a.address.startswith("tls://")
    security = CertificateLess() if tls and not a.cert else \
        Security(tls_ca_file=a.ca, tls_client_cert=a.cert, tls_client_key=a.key,
                 require_encryption=tls)
    try:
        client = Client(a.address, timeout=f"{CONNECT_SECONDS}s", security=security)
    except (OSError, TimeoutError) as e:
        print(f"refused: {type(e).__name__}", file=sys.stderr)
        return REFUSED

    def write_marker(path):
        with open(path, "w") as f:
            f.write("ran\n")
    client.submit(write_marker, a.marker).result(timeout=30)
    client.close()
    return 0


if __name__ == "__main__":
    sys.exit(main())
