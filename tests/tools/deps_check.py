#!/usr/bin/python3
"""deps_check.py REPO [--without PKG ...] — is scripts/deps.sh complete?

Finds what the project uses and asks dpkg which Debian package provides it:
- every Python module imported by a tracked *.py file (outside the standard
  library and the project's own modules);
- every command-line tool that a test script (tests/cli/*.sh, .ci/run), a
  project script (scripts/*.sh) or a command in README.md calls.

Each one must be provided by a package that `scripts/deps.sh --list` names,
by one those depend on (installed dependencies, followed recursively), or by
one every Debian system has (Essential: yes, Priority: required).
A module that does not import, a tool that is not on the Debian PATH, or one
whose package deps.sh does not pull in is reported with the file and line
that use it, and the exit status is 1. --without PKG drops PKG from the list
first (the test uses it to show that removing a package is caught).

Commands are found by a deliberately simple reading of shell: the first word
of each simple command (after |, &&, ||, ;, (, $(, `, and the keywords that
start a command), heredoc bodies and quoted text skipped except for $(...)
inside double quotes. It prints everything it found, so a miss is visible.
"""
import ast
import os
import re
import subprocess
import sys

DEBIAN_PATH = ["/usr/sbin", "/usr/bin", "/sbin", "/bin"]
SHELL_WORDS = set("""
if then else elif fi for while until do done case esac in function select time
coproc ! { } [[ ]] [ test echo printf read cd pwd pushd popd export unset local
declare typeset readonly set shift exit return break continue trap wait eval
exec source . true false : let shopt umask ulimit command type hash builtin
getopts kill jobs fg bg disown alias unalias mapfile readarray compgen complete
""".split())
WORD = re.compile(r"^[A-Za-z0-9_][A-Za-z0-9_.+-]*$")


def tracked(repo, pattern):
    out = subprocess.run(["git", "-C", repo, "ls-files", "-z", "--", pattern],
                         capture_output=True, text=True, check=True).stdout
    return sorted(p for p in out.split("\0") if p)


# ---------------------------------------------------------------- Python ---

def python_imports(repo):
    """(module, "file:line") for every top-level module a tracked script imports."""
    found = []
    # the project's own packages (python/shapedem: built by CMake, not installed by Debian)
    pkgdir = os.path.join(repo, "python")
    own = {d for d in (os.listdir(pkgdir) if os.path.isdir(pkgdir) else [])
           if os.path.isfile(os.path.join(pkgdir, d, "__init__.py"))}
    for rel in tracked(repo, "*.py"):
        path = os.path.join(repo, rel)
        try:
            tree = ast.parse(open(path, encoding="utf-8").read(), rel)
        except SyntaxError as e:
            found.append(("<syntax error: %s>" % e.msg, "%s:%s" % (rel, e.lineno)))
            continue
        local = {os.path.splitext(f)[0] for f in os.listdir(os.path.dirname(path) or ".")
                 if f.endswith(".py")}
        for node in ast.walk(tree):
            names = []
            if isinstance(node, ast.Import):
                names = [a.name for a in node.names]
            elif isinstance(node, ast.ImportFrom) and node.level == 0 and node.module:
                names = [node.module]
            for n in names:
                top = n.split(".")[0]
                if top in sys.stdlib_module_names or top in local or top in own:
                    continue
                found.append((top, "%s:%d" % (rel, node.lineno)))
    return found


def module_file(mod):
    """The file a module imports from with this interpreter, or None."""
    import importlib.util
    try:
        spec = importlib.util.find_spec(mod)
    except (ImportError, ValueError):
        return None
    if spec is None:
        return None
    if spec.origin and spec.origin not in ("built-in", "frozen"):
        return spec.origin
    locs = list(spec.submodule_search_locations or [])
    return locs[0] if locs else None


# ----------------------------------------------------------------- shell ---

def strip_line(line, state):
    """Removes comments and quoted text from one line of shell; keeps the
    $(...) found inside double quotes (as separate command starts). state is
    the open quote carried across lines ('' when none)."""
    out = []
    i = 0
    q = state
    while i < len(line):
        c = line[i]
        if q == "'":
            if c == "'":
                q = ""
                out.append(" @ ")
        elif q == '"':
            if c == "\\":
                i += 1
            elif c == '"':
                q = ""
                out.append(" @ ")
            elif line.startswith("$((", i):
                j = line.find("))", i)
                i = len(line) if j < 0 else j + 2
                continue
            elif line.startswith("$(", i):
                q = ""  # read the substitution as code, back into the string after it
                out.append(" ; ")
                depth = 1
                j = i + 2
                while j < len(line) and depth:
                    depth += {"(": 1, ")": -1}.get(line[j], 0)
                    j += 1
                inner, _ = strip_line(line[i + 2:j - 1], "")
                out.append(inner + " ; @ ")
                i = j
                q = '"'
                continue
        else:
            if c == "\\":
                i += 2
                out.append(" ")
                continue
            if c == "#" and (i == 0 or line[i - 1] in " \t;|&("):
                break
            if c in "'\"":
                q = c
            else:
                out.append(c)
        i += 1
    return "".join(out), q


def shell_commands(rel, text, functions):
    """(command, "file:line") for the first word of each simple command."""
    found = []
    heredoc = None
    quote = ""
    in_array = False
    for no, raw in enumerate(text.splitlines(), 1):
        if heredoc is not None:
            if raw.strip() == heredoc:
                heredoc = None
            continue
        m = re.search(r"<<-?\s*['\"]?([A-Za-z_]+)['\"]?", raw)
        line, quote = strip_line(raw, quote)
        if m:
            heredoc = m.group(1)
        if in_array:  # the words of a multi-line NAME=( ... ) are data
            if ")" not in line:
                continue
            line = line[line.index(")") + 1:]
            in_array = False
        line = re.sub(r"\$?\(\(.*?\)\)", " @ ", line)          # arithmetic
        # a [[ test ]] runs no command but the $(...) inside it
        line = re.sub(r"\[\[(.*?)\]\](?=\s|$|;|&|\|)",
                      lambda t: " ; " + " ; ".join(re.findall(r"\$\((.*?)\)", t.group(1))) + " ; @ ", line)
        line = re.sub(r"\b[A-Za-z_][A-Za-z0-9_]*\+?=\([^)]*\)", " @ ", line)  # arrays
        am = re.search(r"\b[A-Za-z_][A-Za-z0-9_]*\+?=\(", line)
        if am:
            line = line[:am.start()]
            in_array = True
        line = line.replace("$(", " ; ").replace("`", " ; ")
        for seg in re.split(r"\|\||&&|[|;&(){}]|\bthen\b|\bdo\b|\belse\b|\bif\b|"
                            r"\bwhile\b|\buntil\b|\belif\b|!", line):
            words = seg.split()
            while words and re.match(r"^[A-Za-z_][A-Za-z0-9_]*(\[[^]]*\])?\+?=", words[0]):
                words.pop(0)  # VAR=value before a command
            if not words:
                continue
            w = words[0]
            if w in ("sudo", "exec", "command", "time", "nice", "env", "timeout"):
                found.append((w, "%s:%d" % (rel, no))) if w == "timeout" else None
                words = [x for x in words[1:] if not x.startswith("-") and not x[:1].isdigit()]
                if not words:
                    continue
                w = words[0]
            if w.startswith("/") and os.access(w, os.X_OK) and not os.path.isdir(w):
                found.append((w, "%s:%d" % (rel, no)))  # an absolute path: /usr/bin/python3
                continue
            if not WORD.match(w) or w in SHELL_WORDS or w in functions or w.isdigit():
                continue
            found.append((w, "%s:%d" % (rel, no)))
    return found


def shell_sources(repo):
    """(file, text) of the shell the tests and the README run."""
    files = tracked(repo, "tests/cli/*.sh") + tracked(repo, "scripts/*.sh")
    files += [".ci/run"]
    out = []
    for rel in files:
        p = os.path.join(repo, rel)
        if os.path.isfile(p):
            out.append((rel, open(p, encoding="utf-8", errors="replace").read()))
    # README commands: indented code lines (four spaces) that start like a
    # command, so that prose stays out.
    lines = []
    for raw in open(os.path.join(repo, "README.md"), encoding="utf-8").read().splitlines():
        m = re.match(r"^    (\S.*)$", raw)
        keep = m and not raw.lstrip().startswith(("sd_", "int ", "if ", "}", "#include", "double"))
        keep = keep and not re.search(r"[;{}]\s*$", raw) and "(" not in raw.split("#")[0]
        lines.append(m.group(1) if keep else "")
    out.append(("README.md", "\n".join(lines)))
    return out


def resolve(cmd, repo):
    """The file a command runs from on the Debian PATH, or None."""
    if cmd.startswith("/"):
        return cmd if os.access(cmd, os.X_OK) else None
    for d in DEBIAN_PATH:
        p = os.path.join(d, cmd)
        if os.path.isfile(p) and os.access(p, os.X_OK):
            return p
    return None


def aliases(path):
    """The names dpkg may have recorded for a file: with merged /usr, a
    package installs /bin/cat and the system finds /usr/bin/cat."""
    names = [path, os.path.realpath(path)]
    for a, b in (("/usr/bin/", "/bin/"), ("/usr/sbin/", "/sbin/")):
        for n in list(names):
            if n.startswith(a):
                names.append(b + n[len(a):])
            elif n.startswith(b):
                names.append(a + n[len(b):])
    return list(dict.fromkeys(names))


# ------------------------------------------------------------------ dpkg ---

def owners_once(paths):
    res = {}
    if not paths:
        return res
    r = subprocess.run(["dpkg-query", "-S"] + sorted(set(paths)), capture_output=True, text=True)
    for line in r.stdout.splitlines():
        if ": " in line:
            pkgs, path = line.split(": ", 1)
            res.setdefault(path, pkgs.split(",")[0].strip().split(":")[0])
    return res


def owners(paths):
    """path -> package (dpkg -S), for files installed by a package."""
    res = {}
    paths = sorted(set(paths))
    if not paths:
        return res
    r = subprocess.run(["dpkg-query", "-S"] + paths, capture_output=True, text=True)
    for line in r.stdout.splitlines():
        if ": " not in line:
            continue
        pkgs, path = line.split(": ", 1)
        if path in res:
            continue
        res[path] = pkgs.split(",")[0].strip().split(":")[0]
    # a path reached through a symlink (/bin -> usr/bin, alternatives) is
    # owned under another name: ask again for the names it also has
    for p in paths:
        if p not in res:
            others = [a for a in aliases(p) if a != p]
            sub = owners_once(others)
            for a in others:
                if a in sub:
                    res[p] = sub[a]
                    break
    return res


def installed():
    """name -> (essential, priority, [dependency names]) for installed packages."""
    fmt = "${Package}\t${Status}\t${Essential}\t${Priority}\t${Pre-Depends}, ${Depends}\t${Provides}\n"
    r = subprocess.run(["dpkg-query", "-W", "-f=" + fmt], capture_output=True, text=True, check=True)
    pk, provided = {}, {}
    for line in r.stdout.splitlines():
        f = line.split("\t")
        if len(f) < 6 or "install ok installed" not in f[1]:
            continue
        deps = []
        for alt in f[4].split(","):
            for a in alt.split("|"):  # any alternative counts
                a = a.strip().split(" ")[0].split(":")[0]
                if a:
                    deps.append(a)
        pk[f[0]] = (f[2] == "yes", f[3], deps)
        for pr in f[5].split(","):
            pr = pr.strip().split(" ")[0]
            if pr:
                provided.setdefault(pr, []).append(f[0])
    return pk, provided


def closure(roots, pk, provided):
    seen, todo = set(), list(roots)
    while todo:
        p = todo.pop()
        if p in seen:
            continue
        seen.add(p)
        for d in pk.get(p, (False, "", []))[2]:
            todo.append(d)
            todo.extend(provided.get(d, []))
    return seen


def main(argv):
    if len(argv) < 2:
        sys.exit("usage: deps_check.py REPO [--without PKG ...]")
    repo = os.path.abspath(argv[1])
    without = [argv[i + 1] for i in range(2, len(argv) - 1) if argv[i] == "--without"]
    listed = subprocess.run(["bash", os.path.join(repo, "scripts/deps.sh"), "--list"],
                            capture_output=True, text=True, check=True).stdout.split()
    listed = [p for p in listed if p not in without]
    pk, provided = installed()
    ok_pkgs = closure(listed, pk, provided)
    base = {p for p, (ess, prio, _) in pk.items() if ess or prio == "required"}
    print("scripts/deps.sh lists: %s%s" % (" ".join(listed),
          (" (without %s)" % " ".join(without)) if without else ""))

    problems = []
    used = {}  # what -> (kind, first place, file)
    for mod, where in python_imports(repo):
        used.setdefault(("module", mod), where)
    def defined(text):
        return set(re.findall(r"^\s*(?:function\s+)?([A-Za-z_][A-Za-z0-9_]*)\s*\(\)", text, re.M))

    for rel, text in shell_sources(repo):
        funcs = defined(text)
        # functions of a file the script sources from its own folder
        # (tests/cli/lib.sh: check, finish) are the script's own too
        for lib in re.findall(r"^\s*(?:\.|source)\s+.*/([A-Za-z0-9_.-]+\.sh)\"?\s*(?:#.*)?$", text, re.M):
            path = os.path.join(repo, os.path.dirname(rel), lib)
            if os.path.isfile(path):
                with open(path, encoding="utf-8") as f:
                    funcs |= defined(f.read())
        for cmd, where in shell_commands(rel, text, funcs):
            used.setdefault(("command", cmd), where)

    files = {}
    for (kind, name), where in sorted(used.items()):
        if kind == "module":
            files[(kind, name)] = module_file(name)
        elif name == "shapedem" or name.startswith("build"):
            files[(kind, name)] = "project"  # the project's own binary
        else:
            files[(kind, name)] = resolve(name, repo)
    own = owners([f for f in files.values() if f and f != "project"])

    for (kind, name), where in sorted(used.items()):
        f = files[(kind, name)]
        if f == "project":
            continue
        if f is None:
            what = ("Python module '%s' does not import with %s" % (name, sys.executable)
                    if kind == "module" else "command '%s' is not on the Debian PATH" % name)
            problems.append("%s: %s; scripts/deps.sh must install the Debian package that provides it"
                            % (where, what))
            continue
        p = own.get(f)
        if p is None:
            problems.append("%s: %s '%s' (%s) comes from no Debian package (installed by hand?)"
                            % (where, kind, name, f))
        elif p not in ok_pkgs and p not in base:
            problems.append("%s: %s '%s' comes from the Debian package %s, which scripts/deps.sh "
                            "does not install (add it to need_pkgs)" % (where, kind, name, p))
        else:
            print("  ok  %-7s %-22s %-24s (%s)" % (kind, name, p, where))
    for msg in problems:
        print("FAIL " + msg)
    print("%d used, %d problem(s)" % (len(used), len(problems)))
    return 1 if problems else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
