#!/usr/bin/env python3
"""bench/run.py keeps what a long run measured: a scenario that fails is noted and the run goes
on to the next, then fails; and the page's render row reports an earlier build without a status
page as not in that build, rather than waiting for a page that never comes. Python 3, stdlib
only; nothing here starts a gateway."""

import http.server
import sys
import threading
import unittest
from pathlib import Path

BENCH = Path(__file__).resolve().parents[3] / "bench"
sys.path.insert(0, str(BENCH))

import run  # noqa: E402 (bench/ on the path first)
from benchlib.builds import Build, NotInBuild  # noqa: E402
from scenarios import s16_status_page  # noqa: E402


class FakeBench:
    only = set()

    def __init__(self):
        self.notes = []
        self.paho_rates = {(1, "tuned broker"): 1}

    def wanted(self, _number):
        return True


class Failing:
    @staticmethod
    def run(_bench):
        raise RuntimeError("node failed (1): waitForFunction timed out\n    at Frame")


class Passing:
    ran = False

    @staticmethod
    def run(_bench):
        Passing.ran = True


class RunScenariosTest(unittest.TestCase):
    def test_a_failed_scenario_is_noted_and_the_next_still_runs(self):
        saved = run.SCENARIOS
        run.SCENARIOS = [((7,), Failing), ((8,), Passing)]
        try:
            bench = FakeBench()
            failed = run.run_scenarios(bench)
        finally:
            run.SCENARIOS = saved
        self.assertEqual(failed, ["7"])
        self.assertTrue(Passing.ran)
        self.assertEqual(bench.notes, ["scenario 7 stopped before its last row: node failed (1): "
                                       "waitForFunction timed out"])


class Answering(http.server.BaseHTTPRequestHandler):
    status = 200

    def do_GET(self):  # noqa: N802 (the name http.server calls)
        self.send_response(self.status)
        self.send_header("Content-Length", "0")
        self.end_headers()

    def log_message(self, *_args):
        pass


class RequirePageTest(unittest.TestCase):
    def serve(self, status):
        handler = type("Handler", (Answering,), {"status": status})
        server = http.server.HTTPServer(("127.0.0.1", 0), handler)
        threading.Thread(target=server.serve_forever, daemon=True).start()
        self.addCleanup(server.server_close)
        self.addCleanup(server.shutdown)
        return server.server_address[1]

    def test_a_listener_without_the_page_is_not_in_that_build(self):
        earlier = Build("earlier", "/nonexistent", False)
        with self.assertRaises(NotInBuild) as caught:
            s16_status_page.require_page(self.serve(404), earlier)
        self.assertEqual(caught.exception.reason, "no status page: HTTP 404 for /")

    def test_a_listener_with_the_page_passes(self):
        s16_status_page.require_page(self.serve(200), Build("this", "/nonexistent", True))


if __name__ == "__main__":
    unittest.main()
