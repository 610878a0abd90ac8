"""A footpoint-server started for a Python test: on 127.0.0.1 and a port the kernel picks (read
from its "listening" log line), its log drained on a thread; stop() ends it with SIGTERM."""
import json
import subprocess
import threading


class LiveServer:
    def __init__(self, binary, *flags):
        self.process = subprocess.Popen([binary, "--host", "127.0.0.1", "--port", "0", *flags],
                                        stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                                        errors="backslashreplace")  # a log line is never fatal
        for line in self.process.stdout:
            record = json.loads(line)
            if record.get("msg") == "listening":
                threading.Thread(target=lambda: [None for _ in self.process.stdout], daemon=True).start()
                self.port = record["port"]
                self.url = "http://127.0.0.1:%d" % self.port
                return
        self.process.kill()
        raise SystemExit("the server did not start")

    def stop(self):
        self.process.terminate()
        self.process.wait(timeout=60)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.stop()
