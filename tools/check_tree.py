#!/usr/bin/env python3
"""Measures the layout rules of the code on the tree: how big Gateway is, where the pair's words
may appear, how many files stand in src/app, class sizes, classes spread over files, what
core/config includes, YAML text in core, clock calls in app and adapters, the unit test of each
app source, file and function lengths. Prints one line per rule, OK or FAIL, its figure and its
offenders (--json: the same as one JSON document).

The exit status is 1 when a rule of the enforced set fails (ENFORCED below, or --enforce), 2
when the tree cannot be measured (no ctags) or a rule named is unknown. Python 3, stdlib only, and Universal Ctags
(Debian's universal-ctags) for the declarations: class members, where member functions are
defined, where functions end.

How each rule is measured, where a word needs a definition:
- Code text: a file with its comments, string and character literals (raw strings included)
  blanked out, line breaks kept, so that a rule about code is not met or broken by prose.
- gateway-*: the class eip2mqtt::app::Gateway, include/eip2mqtt/app/gateway.hpp and
  src/app/gateway.cpp. A data member is a non-static `member` ctags reports in its own scope
  (not those of its nested structs). The names JsonTree and SparkplugNode and std::atomic are
  looked for in the code text of the two files. gateway-branches: the condition of every `if`,
  `while`, `switch` and `?:` in the code text of the two files (a `?:` condition runs back from
  the `?` to the nearest `(`, `,`, `=`, `{`, `;` or `return`) may not name a member of an
  identifier containing `config` (`config_.sparkplug`, `next.config.metrics`) nor have one of
  FEATURE_WORDS as an identifier's part (`sparkplug_`, `has_history`).
- pair-words: pair, lease, leader, standby (and their plurals, `paired`, `leased`) as an
  identifier's part, split at underscores and at camel-case humps (`pair_`, `PairLease`,
  `is_leader`), or as a word of a comment or a string; `release` or `repair` are not them.
  Every file under src/app except src/app/redundancy/ and src/app/gateway.cpp. Raw string
  literals are left out: they hold another language's text (Lua's `pairs()` in the
  dissector), not our names.
- data-members: non-static data members per class or struct over src/ and include/. A plain
  record (a `struct` whose members are all public and that declares no member function except
  operators: options, sections, counters) is not a class: such records over the limit are
  listed apart and do not fail the rule.
- class-files: the .cpp files under src/ holding definitions of a class's member functions
  (ctags `function` tags whose scope is the class); a class defined inside a .cpp counts apart
  from a namesake elsewhere.
- config-includes: the project headers a file under src/core/config or
  include/eip2mqtt/core/config includes, directly or through other headers.
- core-yaml: a file under src/core or include/eip2mqtt/core that includes yaml-cpp, or holds a
  string literal with a YAML mapping line: `key:` or `- key:` followed by a space or the end
  of the line, where that line is indented, starts a list item or ends with a line break in
  the literal ("exchanges:\\n", "    direction: consume\\n", "  - name: "). One-line messages
  such as "expected: a number" are not YAML text.
- clock-calls: `steady_clock::now(`, `system_clock::now(`, `high_resolution_clock::now(` (and
  a `using X = ...clock;` alias's `X::now(`) in the code text of src/app, src/adapters and
  their headers under include/eip2mqtt/app and include/eip2mqtt/adapters.
- app-tests: a source "with logic" has, in its code text, a branch or a loop (if, else,
  for, while, do, switch, case, catch, `?:`); a file that only defines data, such as the Lua
  text of src/app/cli/dissector/lua_*.cpp, has none. src/app/x/y.cpp needs tests/app/x/y_test.cpp.
- file-lines: the line count of every C++ file (.cpp .hpp .h .cc) under src, include, tests
  and bench (node_modules left out), at most 400: "no file over 400 lines".
- function-lines, test-function-lines: the lines of a function's body, strictly between the
  line of its opening brace and that of its closing brace, from ctags' `line` and `end`, at
  most 60: "no function over 60 lines". function-lines covers src and include;
  test-function-lines covers tests and bench (a TEST body is a function): apart, since long
  test bodies are many and production code has none.
"""

import argparse
import fnmatch
import json
import re
import shutil
import subprocess
import sys
from collections import defaultdict
from pathlib import Path

# The rules that must keep holding: ctest runs this script with this set and fails when one of
# them breaks. Every rule holds on the tree today, so every rule is here.
ENFORCED = (
    "gateway-members",
    "gateway-lines",
    "gateway-files",
    "gateway-atomic",
    "gateway-names",
    "gateway-branches",
    "pair-words",
    "app-root",
    "data-members",
    "class-files",
    "config-includes",
    "core-yaml",
    "clock-calls",
    "app-tests",
    "file-lines",
    "function-lines",
    "test-function-lines",
)

GATEWAY_CLASS = "eip2mqtt::app::Gateway"
GATEWAY_HPP = "include/eip2mqtt/app/gateway.hpp"
GATEWAY_CPP = "src/app/gateway.cpp"
GATEWAY_MAX_MEMBERS = 12
GATEWAY_MAX_LINES = 250
MAX_APP_ROOT_FILES = 4
MAX_DATA_MEMBERS = 20
MAX_CPP_FILES_PER_CLASS = 2
MAX_CLOCK_CALLS = 2
# "No file over 400 lines and no function over 60": at most (src/app/cli/sniff.cpp has
# 400 lines).
MAX_FILE_LINES = 400
MAX_FUNCTION_LINES = 60

CPP_SUFFIXES = {".cpp", ".hpp", ".h", ".cc"}
SOURCE_ROOTS = ("src", "include", "tests", "bench")
PAIR_WORDS = {
    "pair", "pairs", "paired", "lease", "leases", "leased", "leader", "leaders", "standby",
    "standbys",
}
PAIR_ALLOWED = ("src/app/redundancy/*", GATEWAY_CPP)
# What a branch on an optional feature would test: one of the features' words as an identifier's
# part, or a member of a configuration object.
FEATURE_WORDS = {
    "sparkplug", "history", "store", "forward", "journal", "redundancy", "pair", "role",
    "command", "commands", "port", "metrics", "prometheus", "tree", "tls", "watchdog",
}
CLOCKS = ("steady_clock", "system_clock", "high_resolution_clock")

# (id, group, title): the group is the item of the list the rules come from, for --enforce N.
RULES = (
    ("gateway-members", 1, f"Gateway data members <= {GATEWAY_MAX_MEMBERS}"),
    ("gateway-lines", 1, f"gateway.hpp + gateway.cpp <= {GATEWAY_MAX_LINES} lines"),
    ("gateway-files", 1, "no src/app/**/gateway_*.cpp"),
    ("gateway-atomic", 1, "no std::atomic in Gateway"),
    ("gateway-names", 1, "Gateway names neither JsonTree nor SparkplugNode"),
    ("gateway-branches", 1, "no branch in Gateway on an optional feature"),
    ("pair-words", 2, "pair/lease/leader/standby only in src/app/redundancy and gateway.cpp"),
    ("app-root", 3, f"<= {MAX_APP_ROOT_FILES} files directly in src/app"),
    ("data-members", 4, f"no class over {MAX_DATA_MEMBERS} data members"),
    ("class-files", 5, f"no class with member bodies in > {MAX_CPP_FILES_PER_CLASS} .cpp files"),
    ("config-includes", 6, "core/config includes nothing of core/command or core/exchange"),
    ("core-yaml", 6, "no YAML text written in core"),
    ("clock-calls", 7, f"<= {MAX_CLOCK_CALLS} direct clock ::now() calls in app and adapters"),
    ("app-tests", 8, "every src/app/**/*.cpp with logic has tests/app/**/<name>_test.cpp"),
    ("file-lines", 9, f"no C++ file over {MAX_FILE_LINES} lines"),
    ("function-lines", 9, f"no function in src, include over {MAX_FUNCTION_LINES} lines"),
    ("test-function-lines", 9, f"no function in tests, bench over {MAX_FUNCTION_LINES} lines"),
)


class Tree:
    """The repository's files, their code text and their ctags declarations, read once."""

    def __init__(self, root):
        self.root = root
        self._text = {}
        self._code = {}
        self._tags = None

    def files(self, *patterns, roots=SOURCE_ROOTS):
        """Repository-relative paths of the C++ files under `roots` matching any pattern."""
        out = []
        for top in roots:
            base = self.root / top
            if not base.is_dir():
                continue
            for path in base.rglob("*"):
                if "node_modules" in path.parts or not path.is_file():
                    continue
                if path.suffix not in CPP_SUFFIXES:
                    continue
                rel = path.relative_to(self.root).as_posix()
                if not patterns or any(fnmatch.fnmatchcase(rel, p) for p in patterns):
                    out.append(rel)
        return sorted(out)

    def text(self, rel):
        if rel not in self._text:
            self._text[rel] = (self.root / rel).read_text(encoding="utf-8", errors="replace")
        return self._text[rel]

    def code(self, rel):
        """The file with comments and literals blanked, line breaks kept."""
        return self._scan(rel)[0]

    def literals(self, rel):
        """(line, content) of each string literal of the file."""
        return self._scan(rel)[1]

    def prose(self, rel):
        """The file with its raw string literals blanked: C++ code and comments, without the
        text of another language embedded in it (the dissector's Lua)."""
        text = self.text(rel)
        for start, end in reversed(self._scan(rel)[2]):
            text = text[:start] + re.sub(r"[^\n]", " ", text[start:end]) + text[end:]
        return text

    def _scan(self, rel):
        if rel not in self._code:
            self._code[rel] = scan(self.text(rel))
        return self._code[rel]

    def tags(self):
        """Every ctags tag of the C++ files under SOURCE_ROOTS, as dicts."""
        if self._tags is None:
            files = self.files()
            result = subprocess.run(
                ["ctags", "--output-format=json", "--language-force=C++",
                 "--fields=+KneaS", "--fields-C++=+{properties}", "--kinds-C++=+mp",
                 "-f", "-", "-L", "-"],
                input="\n".join(files), cwd=self.root, capture_output=True, text=True,
                check=True)
            self._tags = []
            for line in result.stdout.splitlines():
                tag = json.loads(line)
                if tag.get("_type") == "tag" and "kind" in tag:
                    self._tags.append(tag)
        return self._tags


RAW_STRING = re.compile(r'R"([^()\\\s]{0,16})\(')


def scan(text):
    """(code, literals, raw_spans): `text` with comments, string and character literals blanked
    (their quotes kept, line breaks kept, so that line numbers hold); the (line, content) of
    each string literal, escapes \\n \\t \\" \\\\ decoded; the (start, end) of each raw string."""
    out, literals, raw_spans = [], [], []
    i, n = 0, len(text)

    def blank(s):
        return re.sub(r"[^\n]", " ", s)

    while i < n:
        c = text[i]
        prev = text[i - 1] if i else " "
        if text.startswith("//", i):
            j = text.find("\n", i)
            j = n if j < 0 else j
            out.append(blank(text[i:j]))
            i = j
        elif text.startswith("/*", i):
            j = text.find("*/", i + 2)
            j = n if j < 0 else j + 2
            out.append(blank(text[i:j]))
            i = j
        elif c == "R" and raw_prefix(text, i) and RAW_STRING.match(text, i):
            m = RAW_STRING.match(text, i)
            close = ")" + m.group(1) + '"'
            j = text.find(close, m.end())
            j = n if j < 0 else j
            literals.append((line_of(text, i), text[m.end():j]))
            raw_spans.append((i, j + len(close)))
            out.append("R" + blank(text[i + 1:j + len(close)]))
            i = j + len(close)
        elif c == "'" and (prev.isalnum() or prev == "_") and not prev.isalpha():
            out.append(c)  # a digit separator: 1'000'000
            i += 1
        elif c == '"' or c == "'":
            j = i + 1
            while j < n and text[j] != c and text[j] != "\n":
                j += 2 if text[j] == "\\" else 1
            j = min(j, n - 1)
            if c == '"':
                content = (text[i + 1:j].replace("\\n", "\n").replace("\\t", "\t")
                           .replace('\\"', '"').replace("\\\\", "\\"))
                literals.append((line_of(text, i), content))
            out.append(c + blank(text[i + 1:j]) + text[j])
            i = j + 1
        else:
            out.append(c)
            i += 1
    return "".join(out), literals, raw_spans


def raw_prefix(text, i):
    """Whether the R at `i` starts a raw string: alone or after u8, u, U or L, not inside a name."""
    j = i
    while j > 0 and (text[j - 1].isalnum() or text[j - 1] == "_"):
        j -= 1
    return text[j:i] in ("", "u8", "u", "U", "L")


def line_of(text, offset):
    return text.count("\n", 0, offset) + 1


def identifier_parts(word):
    """`PairLease` -> pair, lease; `is_leader_` -> is, leader; lower case."""
    parts = []
    for piece in word.split("_"):
        parts += re.findall(r"[A-Z]+(?![a-z])|[A-Z]?[a-z]+|\d+", piece)
    return [p.lower() for p in parts]


class Result:
    def __init__(self, rule_id, group, title):
        self.id, self.group, self.title = rule_id, group, title
        self.ok = True
        self.figure = ""
        self.offenders = []
        self.notes = []

    def as_dict(self, enforced):
        return {"id": self.id, "group": self.group, "title": self.title, "ok": self.ok,
                "figure": self.figure, "offenders": self.offenders, "notes": self.notes,
                "enforced": enforced}


def data_members(tree):
    """{(path, scope): [tag]} of the non-static data members of each class and struct."""
    members = defaultdict(list)
    for tag in tree.tags():
        if tag["kind"] != "member" or tag.get("scopeKind") not in ("class", "struct"):
            continue
        if "static" in tag.get("properties", "").split(","):
            continue
        members[(tag["path"], tag["scope"])].append(tag)
    return members


def check_gateway(tree, results):
    members = [t for (path, scope), tags in data_members(tree).items()
               if scope == GATEWAY_CLASS and path.startswith(("include/", "src/"))
               for t in tags]
    found = any(t["kind"] == "class" and f"{t.get('scope', '')}::{t['name']}" == GATEWAY_CLASS
                for t in tree.tags())
    r = results["gateway-members"]
    r.figure = f"{len(members)} data members (at most {GATEWAY_MAX_MEMBERS})"
    r.ok = found and len(members) <= GATEWAY_MAX_MEMBERS
    if not found:
        r.figure = f"no class {GATEWAY_CLASS} (a renamed composition root: update this script)"
    elif not r.ok:
        r.offenders = [t["name"] for t in sorted(members, key=lambda t: t["line"])]

    present = [f for f in (GATEWAY_HPP, GATEWAY_CPP) if (tree.root / f).is_file()]
    lines = {f: tree.text(f).count("\n") for f in present}
    r = results["gateway-lines"]
    r.figure = f"{sum(lines.values())} lines (at most {GATEWAY_MAX_LINES})"
    r.ok = sum(lines.values()) <= GATEWAY_MAX_LINES
    if not r.ok:
        r.offenders = [f"{f} {n}" for f, n in lines.items()]

    r = results["gateway-files"]
    extra = tree.files("src/app/*gateway_*.cpp", roots=("src/app",))
    extra = [f for f in extra if Path(f).name.startswith("gateway_")]
    r.figure = f"{len(extra)} files"
    r.ok = not extra
    r.offenders = extra

    def code_hits(pattern):
        hits = []
        for f in present:
            code = tree.code(f)
            hits += [f"{f}:{line_of(code, m.start())}" for m in re.finditer(pattern, code)]
        return hits

    r = results["gateway-atomic"]
    hits = code_hits(r"\bstd::atomic\w*|\batomic\s*<")
    hits += [f"{t['path']}:{t['line']}" for t in members if "atomic" in t.get("typeref", "")
             and f"{t['path']}:{t['line']}" not in hits]  # an alias's member
    r.figure = f"{len(hits)} uses"
    r.ok = not hits
    r.offenders = hits

    r = results["gateway-names"]
    hits = code_hits(r"\b(?:JsonTree|SparkplugNode)\b")
    r.figure = f"{len(hits)} mentions"
    r.ok = not hits
    r.offenders = hits


def balanced_after(code, start):
    """The text inside the parentheses that open at code[start] (or the rest of the code)."""
    depth = 0
    for i in range(start, len(code)):
        depth += {"(": 1, ")": -1}.get(code[i], 0)
        if depth == 0:
            return code[start + 1:i]
    return code[start + 1:]


def branch_conditions(code):
    """(offset, condition) of each if/while/switch and ?: in a file's code text."""
    found = []
    for m in re.finditer(r"\b(?:if|while|switch)\s*(?:constexpr\s*)?\(", code):
        found.append((m.start(), balanced_after(code, m.end() - 1)))
    for m in re.finditer(r"\?(?![?:])", code):
        head = code[:m.start()]
        cut = max(head.rfind(c) for c in "(,={;")
        cut = max(cut, head.rfind("return") + len("return") - 1)
        found.append((m.start(), head[cut + 1:]))
    return found


def names_a_feature(condition):
    if re.search(r"\w*config\w*\s*(?:\.|->)\s*\w+", condition):
        return True
    return any(part in FEATURE_WORDS for word in re.findall(r"[A-Za-z_]\w*", condition)
               for part in identifier_parts(word))


def check_gateway_branches(tree, results):
    r = results["gateway-branches"]
    hits = []
    for f in (GATEWAY_HPP, GATEWAY_CPP):
        if (tree.root / f).is_file():
            code = tree.code(f)
            hits += [f"{f}:{line_of(code, at)} ({' '.join(cond.split())})"
                     for at, cond in branch_conditions(code) if names_a_feature(cond)]
    r.figure = f"{len(hits)} branches on a feature"
    r.ok = not hits
    r.offenders = hits


def check_pair_words(tree, results):
    r = results["pair-words"]
    hits = []
    for f in tree.files("src/app/*", roots=("src/app",)):
        if any(fnmatch.fnmatchcase(f, p) for p in PAIR_ALLOWED):
            continue
        text = tree.prose(f)
        for m in re.finditer(r"[A-Za-z][A-Za-z0-9_]*", text):
            parts = identifier_parts(m.group(0))
            if PAIR_WORDS.intersection(parts):
                hits.append((f, line_of(text, m.start()), m.group(0)))
    files = sorted({h[0] for h in hits})
    r.figure = f"{len(hits)} words in {len(files)} files"
    r.ok = not hits
    by_file = defaultdict(list)
    for f, line, word in hits:
        by_file[f].append(f"{line}:{word}")
    r.offenders = [f"{f} ({len(v)}: {' '.join(v[:3])}{' ...' if len(v) > 3 else ''})"
                   for f, v in sorted(by_file.items())]


def check_app_root(tree, results):
    r = results["app-root"]
    base = tree.root / "src/app"
    files = sorted(p.name for p in base.iterdir() if p.is_file()) if base.is_dir() else []
    r.figure = f"{len(files)} files (at most {MAX_APP_ROOT_FILES})"
    r.ok = len(files) <= MAX_APP_ROOT_FILES
    if not r.ok:
        r.offenders = files


def is_record(tree, path, scope, tags):
    """A plain record: a struct whose members are all public and that declares no member
    function other than operators (options, config sections, counters)."""
    kind = tags[0].get("scopeKind")
    if kind != "struct" or any(t.get("access", "public") != "public" for t in tags):
        return False
    for t in tree.tags():
        if (t["kind"] in ("function", "prototype") and t.get("scope") == scope
                and t["path"] == path and not t["name"].startswith("operator")):
            return False
    return True


def check_data_members(tree, results):
    r = results["data-members"]
    classes, records = [], []
    for (path, scope), tags in data_members(tree).items():
        if not path.startswith(("src/", "include/")) or len(tags) <= MAX_DATA_MEMBERS:
            continue
        entry = (len(tags), scope.split("::")[-1], path)
        (records if is_record(tree, path, scope, tags) else classes).append(entry)
    classes.sort(reverse=True)
    records.sort(reverse=True)
    r.figure = f"{len(classes)} classes over {MAX_DATA_MEMBERS} data members"
    r.ok = not classes
    r.offenders = [f"{name} {n} ({path})" for n, name, path in classes]
    if records:
        r.notes.append("not counted, plain records (public data, no member function): " +
                       ", ".join(f"{name} {n} ({path})" for n, name, path in records))


def check_class_files(tree, results):
    r = results["class-files"]
    defined_in_cpp = {(t["path"], (t.get("scope", "") + "::" + t["name"]).lstrip(":"))
                      for t in tree.tags()
                      if t["kind"] in ("class", "struct") and t["path"].endswith(".cpp")}
    files = defaultdict(set)
    for t in tree.tags():
        if (t["kind"] != "function" or t.get("scopeKind") not in ("class", "struct")
                or not t["path"].startswith("src/") or not t["path"].endswith(".cpp")):
            continue
        scope = t["scope"]
        key = (t["path"], scope) if (t["path"], scope) in defined_in_cpp else ("", scope)
        files[key].add(t["path"])
    spread = sorted(((len(v), k[1], sorted(v)) for k, v in files.items()
                     if len(v) > MAX_CPP_FILES_PER_CLASS), reverse=True)
    r.figure = f"{len(spread)} classes in more than {MAX_CPP_FILES_PER_CLASS} .cpp files"
    r.ok = not spread
    r.offenders = [f"{scope.split('::')[-1]} {n} ({' '.join(Path(f).name for f in fs)})"
                   for n, scope, fs in spread]


INCLUDE = re.compile(r'^\s*#\s*include\s*[<"]([^>"]+)[>"]', re.M)
YAML_LINE = re.compile(r"^(\s*)(-\s+)?[A-Za-z_][A-Za-z0-9_]*:(?:[ \t]|$)")


def include_chains(tree, rel):
    """For each project header `rel` reaches, directly or through others, the chain of
    #include paths that first reaches it (breadth first: the shortest)."""
    chains, queue, seen = [], [(rel, [])], {rel}
    while queue:
        current, chain = queue.pop(0)
        for m in INCLUDE.finditer(tree.text(current)):
            for base in ("include/", "src/"):
                target = base + m.group(1)
                if (tree.root / target).is_file():
                    break
            else:
                continue  # a system or third-party header
            if target not in seen:
                seen.add(target)
                chains.append(chain + [m.group(1)])
                queue.append((target, chain + [m.group(1)]))
    return chains


def check_core_config(tree, results):
    r = results["config-includes"]
    hits = []
    for f in tree.files(roots=("src/core/config", "include/eip2mqtt/core/config")):
        for chain in include_chains(tree, f):
            banned = [bool(re.match(r"(eip2mqtt/)?core/(command|exchange)/", h)) for h in chain]
            if banned[-1] and not any(banned[:-1]):  # the first banned header on the way
                hits.append(f"{f}: " + " -> ".join(chain))
    r.figure = f"{len(hits)} includes, direct or through other headers"
    r.ok = not hits
    r.offenders = hits

    r = results["core-yaml"]
    hits = []
    for f in tree.files(roots=("src/core", "include/eip2mqtt/core")):
        text = tree.text(f)
        for m in INCLUDE.finditer(text):
            if m.group(1).startswith("yaml-cpp/"):
                hits.append(f"{f}:{line_of(text, m.start())} includes {m.group(1)}")
        for line, content in tree.literals(f):
            lines = content.split("\n")
            for k, piece in enumerate(lines):
                m = YAML_LINE.match(piece)
                if m and (m.group(1) or m.group(2) or k < len(lines) - 1):
                    hits.append(f"{f}:{line} {json.dumps(piece.strip())}")
                    break
    r.figure = f"{len(hits)} places"
    r.ok = not hits
    r.offenders = hits


def check_clock_calls(tree, results):
    r = results["clock-calls"]
    hits = []
    roots = ("src/app", "src/adapters", "include/eip2mqtt/app", "include/eip2mqtt/adapters")
    for f in tree.files(roots=roots):
        code = tree.code(f)
        names = set(CLOCKS)
        for m in re.finditer(r"\busing\s+(\w+)\s*=\s*[\w:]*\b(" + "|".join(CLOCKS) + r")\b",
                             code):
            names.add(m.group(1))
        pattern = r"\b(" + "|".join(sorted(names)) + r")\s*::\s*now\s*\("
        hits += [f"{f}:{line_of(code, m.start())}" for m in re.finditer(pattern, code)]
    r.figure = f"{len(hits)} calls (at most {MAX_CLOCK_CALLS})"
    r.ok = len(hits) <= MAX_CLOCK_CALLS
    if not r.ok:
        counts = defaultdict(int)
        for h in hits:
            counts[h.rsplit(":", 1)[0]] += 1
        r.offenders = [f"{f} {n}" for f, n in sorted(counts.items(), key=lambda kv: -kv[1])]


LOGIC = re.compile(r"\b(if|else|for|while|do|switch|case|catch)\b|\?")


def check_app_tests(tree, results):
    r = results["app-tests"]
    missing, data_only = [], []
    sources = [f for f in tree.files(roots=("src/app",)) if f.endswith(".cpp")]
    for f in sources:
        if not LOGIC.search(tree.code(f)):
            data_only.append(f)
            continue
        rel = Path(f).relative_to("src/app")
        test = Path("tests/app") / rel.parent / (rel.stem + "_test.cpp")
        if not (tree.root / test).is_file():
            missing.append(f"{f} -> {test.as_posix()}")
    r.figure = f"{len(missing)} of {len(sources) - len(data_only)} sources with logic untested"
    r.ok = not missing
    r.offenders = missing
    if data_only:
        r.notes.append("without logic (no branch or loop), not counted: " + ", ".join(data_only))


def function_lengths(tree, roots):
    """(body lines, path, line, name) of every function defined under `roots`."""
    out, lines = [], {}
    for t in tree.tags():
        if t["kind"] != "function" or "end" not in t or not t["path"].startswith(roots):
            continue
        if t["path"] not in lines:
            lines[t["path"]] = tree.code(t["path"]).split("\n")
        code_lines = lines[t["path"]]
        brace = t["line"]
        while brace < t["end"] and "{" not in code_lines[brace - 1]:
            brace += 1
        body = max(0, t["end"] - brace - 1)
        out.append((body, t["path"], t["line"], t["name"]))
    return out


def check_sizes(tree, results):
    r = results["file-lines"]
    sizes = [(tree.text(f).count("\n"), f) for f in tree.files()]
    over = sorted((n, f) for n, f in sizes if n > MAX_FILE_LINES)
    longest = max(sizes, default=(0, ""))
    r.figure = f"{len(over)} files over {MAX_FILE_LINES} lines (longest {longest[0]}: {longest[1]})"
    r.ok = not over
    r.offenders = [f"{f} {n}" for n, f in reversed(over)]

    for rule_id, roots in (("function-lines", ("src/", "include/")),
                           ("test-function-lines", ("tests/", "bench/"))):
        r = results[rule_id]
        lengths = function_lengths(tree, roots)
        over = sorted((x for x in lengths if x[0] > MAX_FUNCTION_LINES), reverse=True)
        longest = max(lengths, default=(0, "", 0, ""))
        r.figure = (f"{len(over)} functions over {MAX_FUNCTION_LINES} body lines "
                    f"(longest {longest[0]}: {longest[1]}:{longest[2]} {longest[3]})")
        r.ok = not over
        r.offenders = [f"{path}:{line} {name} {n}" for n, path, line, name in over]


CHECKS = (check_gateway, check_gateway_branches, check_pair_words, check_app_root, check_data_members,
          check_class_files, check_core_config, check_clock_calls, check_app_tests,
          check_sizes)


def parse_rules(text):
    """Rule ids from `a,b,3` (a number: every rule of that group); `all`; `none`."""
    if text == "all":
        return [rule_id for rule_id, _, _ in RULES]
    if text in ("", "none"):
        return []
    chosen = []
    for item in text.split(","):
        item = item.strip()
        matched = [rule_id for rule_id, group, _ in RULES
                   if item == rule_id or item == str(group)]
        if not matched:
            print(f"check_tree.py: no rule {item!r}; rules: " +
                  ", ".join(rule_id for rule_id, _, _ in RULES), file=sys.stderr)
            raise SystemExit(2)
        chosen += [m for m in matched if m not in chosen]
    return chosen


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    parser.add_argument("--root", type=Path, default=Path(__file__).resolve().parent.parent,
                        help="the repository to measure (default: this script's)")
    parser.add_argument("--enforce", metavar="RULES", default=",".join(ENFORCED),
                        help="rules whose failure makes the exit status 1: ids or group "
                             "numbers, comma-separated, `all` or `none` (default: ENFORCED, "
                             + ",".join(ENFORCED) + ")")
    parser.add_argument("--json", action="store_true", help="one JSON document on stdout")
    args = parser.parse_args()
    enforced = parse_rules(args.enforce)

    if shutil.which("ctags") is None:
        print("check_tree.py: ctags not found (Debian: universal-ctags)", file=sys.stderr)
        return 2
    tree = Tree(args.root.resolve())
    try:
        tree.tags()
    except subprocess.CalledProcessError as e:
        print(f"check_tree.py: ctags failed (Universal Ctags needed): {e.stderr.strip()}",
              file=sys.stderr)
        return 2
    results = {rule_id: Result(rule_id, group, title) for rule_id, group, title in RULES}
    for check in CHECKS:
        check(tree, results)

    failed = [rule_id for rule_id in enforced if not results[rule_id].ok]
    if args.json:
        json.dump({"ok": not failed, "enforced": enforced,
                   "rules": [results[rule_id].as_dict(rule_id in enforced)
                             for rule_id, _, _ in RULES]}, sys.stdout, indent=2)
        print()
    else:
        for rule_id, group, title in RULES:
            r = results[rule_id]
            mark = "*" if rule_id in enforced else " "
            line = f"{'OK  ' if r.ok else 'FAIL'}{mark} {group} {rule_id}: {r.figure}"
            if r.offenders:
                line += ": " + "; ".join(r.offenders)
            print(line)
            for note in r.notes:
                print(f"       {note}")
        print(f"(* enforced: {', '.join(enforced) or 'none'}; "
              f"{'all hold' if not failed else 'failing: ' + ', '.join(failed)})")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
