#!/usr/bin/env python3
"""Concurrent uploads to `smart serve` (issue 25: eight 60 MB uploads took 1.4 GB): starts a
server on a free port with a fresh data folder, has CLIENTS threads post one results folder of
MB megabytes (a states.csv) to /api/results at once, and prints the answers, the server's peak
RSS (VmHWM) and the machine. Usage: bench/serve_uploads.py [CLIENTS=8] [MB=56] [serve flags...];
SMART=path/to/smart."""
import os
import platform
import re
import subprocess
import sys
import tempfile
import threading
import urllib.error
import urllib.request

here = os.path.dirname(os.path.abspath(__file__))
smart = os.environ.get("SMART", os.path.join(here, "..", "build", "bin", "smart"))
clients = int(sys.argv[1]) if len(sys.argv) > 1 else 8
megabytes = int(sys.argv[2]) if len(sys.argv) > 2 else 56
with tempfile.TemporaryDirectory() as data:
    server = subprocess.Popen([smart, "serve", "--port", "0", "--data", data] + sys.argv[3:],
                              stdout=subprocess.PIPE, stderr=subprocess.DEVNULL, text=True)
    port = None
    while port is None:
        line = server.stdout.readline()
        if not line:
            sys.exit("smart serve ended before it listened")
        found = re.search(r"127\.0\.0\.1:(\d+)", line)
        port = int(found.group(1)) if found else None
    row = b"0.5,0,1.25,1.25,0\n"
    states = b"t_s,robot,x_m,y_m,yaw_rad\n" + row * (megabytes * 2**20 // len(row))
    part = b'--B\r\nContent-Disposition: form-data; name="files"; filename="%s"\r\n\r\n'
    body = (part % b"summary.json" + b'{"robots": 1}\r\n' + part % b"states.csv" + states +
            b"\r\n--B--\r\n")
    answers = []

    def post():
        request = urllib.request.Request(
            f"http://127.0.0.1:{port}/api/results", data=body,
            headers={"Content-Type": "multipart/form-data; boundary=B"})
        try:
            answers.append(str(urllib.request.urlopen(request, timeout=300).status))
        except urllib.error.HTTPError as e:
            answers.append(str(e.code))
        except OSError as e:
            answers.append(type(e).__name__)

    threads = [threading.Thread(target=post) for _ in range(clients)]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    with open(f"/proc/{server.pid}/status") as status:
        peak_kb = next(int(l.split()[1]) for l in status if l.startswith("VmHWM"))
    server.terminate()
    server.wait()
print({"clients": clients, "upload_mb": len(body) / 2**20, "answers": sorted(answers),
       "server_peak_rss_mb": round(peak_kb / 1024), "machine": platform.platform(),
       "cores": os.cpu_count()})
