#!/usr/bin/env python3
"""Every command in the manuals' shell code blocks still works as written, so the manuals cannot drift
from the programs.

usage: check_readme_commands.py --source SRC --build BUILD README.md [more.md ...]

Each ```sh block is read line by line (a trailing backslash continues a line, # starts a comment) and
split into commands at &&, || and ;. Every command is checked without running the work:
  build/<dir>/<program> ARGS   run as BUILD/<dir>/<program> ARGS with UHPC_PARSE_ONLY=1 (uhpc/cli.hpp):
                               the options, the subcommand and the required options must parse (exit 0);
  make -C pipelines ARGS       `make -n` of the same target and variables must succeed (the target exists);
  bash|python3 SCRIPT ARGS     the script must exist;
  mpirun|srun OPTIONS build/... ARGS   the program's part as above (parsed in one process, no launcher);
and every argument naming a file of the source tree (data/..., pipelines/...) must exist. The programs
run in a scratch directory with data/ and pipelines/ linked; files under out/ that earlier commands of
the manual would have written are empty stand-ins. Any other
command is an error: the checker knows every kind of command the manuals show.
"""
import argparse
import os
import pathlib
import shlex
import subprocess
import sys
import tempfile

SEPARATORS = {"&&", "||", ";"}
SOURCE_PREFIXES = ("data/", "pipelines/")
LAUNCHERS = ("mpirun", "mpiexec", "srun")


def code_lines(markdown):
    """The logical lines of the ```sh / ```bash blocks, with their line numbers."""
    lines, inside, pending, start = [], False, "", 0
    for number, raw in enumerate(markdown.splitlines(), 1):
        stripped = raw.strip()
        if stripped.startswith("```"):
            inside = not inside and stripped[3:].strip() in ("sh", "bash", "shell")
            continue
        if not inside:
            continue
        if not pending:
            start = number
        if raw.rstrip().endswith("\\"):
            pending += raw.rstrip()[:-1] + " "
            continue
        lines.append((start, pending + raw))
        pending = ""
    return lines


def commands(line):
    """The commands of one shell line (comments dropped), each a list of words."""
    lexer = shlex.shlex(line, posix=True, punctuation_chars=";&|")
    lexer.whitespace_split = True
    lexer.commenters = "#"
    current, out = [], []
    for word in lexer:
        if word in SEPARATORS:
            out.append(current)
            current = []
        else:
            current.append(word)
    out.append(current)
    return [c for c in out if c]


def check(words, source, build, scratch):
    """None when the command is fine, else the reason."""
    for w in words[1:]:
        value = w.split("=", 1)[1] if w.startswith("--") and "=" in w else w
        if value.startswith(SOURCE_PREFIXES) and not (source / value).exists():
            return f"{value}: no such file in the source tree"
    program = words[0]
    if program in LAUNCHERS:  # the launcher's own options are its business: the program's must parse
        started = [w for w in words[1:] if w.startswith("build/")]
        if not started:
            return f"{program}: launches none of the build's programs"
        return check(words[words.index(started[0]):], source, build, scratch)
    if program.startswith("build/"):
        exe = build / program[len("build/"):]
        if not exe.is_file():
            return f"{exe}: no such program in the build"
        # Files under out/ are the outputs of earlier commands of the manual: empty stand-ins let the
        # options that must name an existing file parse (nothing is read in a dry run).
        for w in words[1:]:
            value = w.split("=", 1)[1] if w.startswith("--") and "=" in w else w
            if value.startswith("out/") and pathlib.Path(value).suffix in (".json", ".h5", ".csv"):
                (scratch / value).parent.mkdir(parents=True, exist_ok=True)
                (scratch / value).touch()
        env = dict(os.environ, UHPC_PARSE_ONLY="1")
        done = subprocess.run([str(exe)] + words[1:], cwd=scratch, env=env, capture_output=True, text=True)
        if done.returncode != 0:
            return f"exit {done.returncode}: {done.stderr.strip() or done.stdout.strip()}"
        if "command line parsed" not in done.stdout:
            return f"the program did not stop after parsing: {done.stdout.strip()[:200]}"
        return None
    if program == "make":
        args = words[1:]
        if args[:2] != ["-C", "pipelines"]:
            return "make is only shown as `make -C pipelines ...`"
        cmd = ["make", "-n", "-C", str(source / "pipelines")] + args[2:] + [f"BUILD={build}", f"OUT={scratch / 'out'}"]
        done = subprocess.run(cmd, cwd=source, capture_output=True, text=True)
        if done.returncode != 0:
            return f"make -n: exit {done.returncode}: {done.stderr.strip()[-300:]}"
        return None
    if program in ("bash", "python3", "/usr/bin/python3"):
        if len(words) < 2 or not (source / words[1]).is_file():
            return f"{words[1] if len(words) > 1 else '(none)'}: no such script in the source tree"
        return None
    return f"{program}: a kind of command this checker does not know (teach it, or show the command otherwise)"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--source", required=True, type=pathlib.Path)
    ap.add_argument("--build", required=True, type=pathlib.Path)
    ap.add_argument("manuals", nargs="+", type=pathlib.Path)
    args = ap.parse_args()
    failures, checked = [], 0
    with tempfile.TemporaryDirectory() as tmp:
        # The commands run from a scratch copy of the project root: the shipped inputs linked, out/ empty.
        scratch = pathlib.Path(tmp)
        for d in ("data", "pipelines"):
            (scratch / d).symlink_to(args.source / d)
        for manual in args.manuals:
            path = manual if manual.is_absolute() else args.source / manual
            for number, line in code_lines(path.read_text()):
                for words in commands(line):
                    checked += 1
                    reason = check(words, args.source, args.build, scratch)
                    if reason:
                        failures.append(f"{manual}:{number}: {' '.join(words)}\n    {reason}")
    for f in failures:
        print(f)
    print(f"{checked} commands checked, {len(failures)} failed")
    if checked == 0:
        print("no commands found: the manuals' ```sh blocks are missing")
        return 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
