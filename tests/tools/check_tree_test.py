#!/usr/bin/env python3
"""tools/check_tree.py finds each break of its rules: a small tree where every rule holds, then
one copy of it per rule with that rule broken, and only that rule. Python 3, stdlib only;
needs ctags, as the script does."""

import json
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

SCRIPT = Path(__file__).resolve().parents[2] / "tools" / "check_tree.py"


def members(count, prefix="m"):
    return "".join(f"    int {prefix}{i}_ = 0;\n" for i in range(count))


def body(lines):
    return "".join(f"    total += {i};\n" for i in range(lines))


GOOD = {
    "include/eip2mqtt/app/gateway.hpp": (
        "#pragma once\n"
        "namespace eip2mqtt::app {\n"
        "class Gateway {\n"
        "public:\n"
        "    void start();\n"
        "    static int instances_;\n"
        "private:\n" + members(12) + "};\n"
        "}  // namespace eip2mqtt::app\n"),
    "src/app/gateway.cpp": (
        '#include "eip2mqtt/app/gateway.hpp"\n'
        "namespace eip2mqtt::app {\n"
        "// The modules: the exchanges, the pair (the composition root may name it).\n"
        "void Gateway::start() {\n"
        "    if (m0_ == 0) m1_ = 1;\n"
        "    m2_ = m0_ > 1 ? 2 : 3;\n"
        "}\n"
        "}  // namespace eip2mqtt::app\n"),
    "tests/app/gateway_test.cpp": "TEST(Gateway, Starts) {\n    EXPECT_TRUE(true);\n}\n",
    "src/app/redundancy/pair_lease.cpp": (
        "// The pair's lease: the leader renews it, the standby waits.\n"
        "int renew(int lease) { return lease > 0 ? lease : 1; }\n"),
    "tests/app/redundancy/pair_lease_test.cpp": "TEST(PairLease, Renews) {\n}\n",
    "src/app/exchanges/router.cpp": (
        "// Routes datagrams; on release of a repaired exchange, counts it.\n"
        "int route(int release) {\n"
        "    for (int i = 0; i < release; ++i) {\n"
        "    }\n"
        "    return release;\n"
        "}\n"),
    "tests/app/exchanges/router_test.cpp": "TEST(Router, Routes) {\n}\n",
    "src/app/dissector/lua_table.cpp": (
        'const char* lua_table = R"lua(\n'
        "for k, v in pairs(fields) do if v then print(k) end end\n"
        ')lua";\n'),
    "include/eip2mqtt/core/config/config.hpp": (
        "#pragma once\n"
        "#include <string>\n"
        '#include "eip2mqtt/core/net/subnet.hpp"\n'
        "namespace eip2mqtt::core::config {\n"
        "struct MqttSection {\n" + members(24, "key") + "};\n"
        "}  // namespace eip2mqtt::core::config\n"),
    "include/eip2mqtt/core/net/subnet.hpp": "#pragma once\nstruct Subnet {};\n",
    "src/core/config/config.cpp": (
        '#include "eip2mqtt/core/config/config.hpp"\n'
        "#include <string>\n"
        "std::string message() { return std::string(\"expected: a number\") + \"period_ms:\"; }\n"),
    "src/adapters/clock.cpp": (
        "#include <chrono>\n"
        "// steady_clock::now() in a comment does not count\n"
        "auto mono() { return std::chrono::steady_clock::now(); }\n"
        "auto wall() { return std::chrono::system_clock::now(); }\n"),
    "src/core/x.hpp": "#pragma once\nclass Spread {\n    void a();\n    void b();\n};\n",
    "src/core/a.cpp": '#include "core/x.hpp"\nvoid Spread::a() {}\n',
    "src/core/b.cpp": '#include "core/x.hpp"\nvoid Spread::b() {}\n',
    "src/core/long.cpp": "int sum() {\n    int total = 0;\n" + body(58) + "}\n" + "\n" * 330,
    "tests/core/long_test.cpp": "TEST(Long, Sums) {\n    int total = 0;\n" + body(59) + "}\n",
}

# Each rule, and the edit of the good tree that breaks it alone.
BREAKS = {
    "gateway-members": {"include/eip2mqtt/app/gateway.hpp": lambda t: t.replace(
        "};\n}", "    int one_more_ = 0;\n};\n}")},
    "gateway-lines": {"src/app/gateway.cpp": lambda t: t + "// a note\n" * 240},
    "gateway-files": {"src/app/gateway_extra.cpp": lambda t: "int x = 0;\n"},
    "gateway-atomic": {"include/eip2mqtt/app/gateway.hpp": lambda t: t.replace(
        "    int m0_ = 0;\n", "    std::atomic<int> m0_{0};\n")},
    "gateway-names": {"src/app/gateway.cpp": lambda t: t.replace(
        "    if (m0_", "    JsonTree* tree = nullptr;\n    if (m0_")},
    "gateway-branches": {"src/app/gateway.cpp": lambda t: t.replace(
        "m0_ > 1 ?", "config_.sparkplug.enabled ?")},
    "pair-words": {"src/app/exchanges/router.cpp": lambda t: t.replace(
        "counts it", "leaves it to the standby_")},
    "app-root": {f"src/app/part{i}.cpp": (lambda t: "int x = 0;\n") for i in range(4)},
    "data-members": {"src/core/x.hpp": lambda t: t.replace(
        "    void a();\n", "    void a();\n" + members(21))},
    "class-files": {"src/core/c.cpp": lambda t: '#include "core/x.hpp"\nvoid Spread::c() {}\n'},
    "config-includes": {
        "include/eip2mqtt/core/net/subnet.hpp": lambda t: t + '#include "core/exchange/e.hpp"\n',
        "src/core/exchange/e.hpp": lambda t: "#pragma once\n"},
    "core-yaml": {"src/core/config/config.cpp": lambda t: t.replace(
        '"period_ms:"', '"  - name: pump\\n"')},
    "clock-calls": {"src/adapters/clock.cpp": lambda t: t + (
        "using Clock = std::chrono::steady_clock;\nauto again() { return Clock::now(); }\n")},
    "app-tests": {"tests/app/exchanges/router_test.cpp": None},
    "file-lines": {"src/core/long.cpp": lambda t: t + "\n" * 10},
    "function-lines": {"src/core/long.cpp": lambda t: t.replace(
        "    int total = 0;\n", "    int total = 0;\n" * 3)},
    "test-function-lines": {"tests/core/long_test.cpp": lambda t: t.replace(
        "    int total = 0;\n", "    int total = 0;\n" * 2)},
}


def write_tree(root, edits):
    files = dict(GOOD)
    for path, edit in edits.items():
        if edit is None:
            files.pop(path)
        else:
            files[path] = edit(files.get(path, ""))
    for path, text in files.items():
        (root / path).parent.mkdir(parents=True, exist_ok=True)
        (root / path).write_text(text)


def measure(root):
    result = subprocess.run(
        [sys.executable, str(SCRIPT), "--root", str(root), "--json", "--enforce", "all"],
        capture_output=True, text=True)
    report = json.loads(result.stdout)
    return result.returncode, report


class CheckTree(unittest.TestCase):
    def test_every_rule_holds_on_the_good_tree(self):
        with tempfile.TemporaryDirectory() as root:
            write_tree(Path(root), {})
            status, report = measure(Path(root))
        failing = {r["id"]: r["offenders"] for r in report["rules"] if not r["ok"]}
        self.assertEqual(failing, {})
        self.assertEqual(status, 0)
        records = next(r for r in report["rules"] if r["id"] == "data-members")["notes"]
        self.assertIn("MqttSection 24", " ".join(records))

    def test_each_break_fails_its_rule_alone(self):
        ids = [r["id"] for r in measure_ids()]
        self.assertEqual(sorted(BREAKS), sorted(ids))
        for rule_id, edits in BREAKS.items():
            with self.subTest(rule=rule_id), tempfile.TemporaryDirectory() as root:
                write_tree(Path(root), edits)
                status, report = measure(Path(root))
                failing = [r["id"] for r in report["rules"] if not r["ok"]]
                self.assertEqual(failing, [rule_id])
                self.assertEqual(status, 1)

    def test_a_rule_left_out_of_the_enforced_set_does_not_fail_the_run(self):
        with tempfile.TemporaryDirectory() as root:
            write_tree(Path(root), BREAKS["app-root"])
            result = subprocess.run(
                [sys.executable, str(SCRIPT), "--root", root, "--enforce", "gateway-lines,8"],
                capture_output=True, text=True)
        self.assertEqual(result.returncode, 0, result.stdout + result.stderr)
        self.assertIn("FAIL  3 app-root: 5 files (at most 4)", result.stdout)


def measure_ids():
    with tempfile.TemporaryDirectory() as root:
        write_tree(Path(root), {})
        return measure(Path(root))[1]["rules"]


if __name__ == "__main__":
    unittest.main()
