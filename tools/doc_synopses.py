#!/usr/bin/env python3
"""Checks that a page's synopses list every option of every tool: each
option a tool's --help lists (a line starting with "-x, --name" or
"--name", and the long options of its usage lines) stands, in its long or
its short form, in a fenced code block of the page that names the tool.

usage: doc_synopses.py PAGE.md TOOL...

Prints each missing option and exits 1 if there is one, else 0.
"""
import os
import re
import subprocess
import sys

OPTION_LINE = re.compile(r"^ {2}(?:(-[A-Za-z]), )?(--[a-z][a-z0-9-]*)")


def options(tool):
    """(short form or None, long form) of every option in the tool's help:
    its option lines, and the long options of its usage lines."""
    lines = subprocess.run([tool, "--help"], capture_output=True, text=True,
                           check=True).stdout.splitlines()
    found = [m.groups() for m in map(OPTION_LINE.match, lines) if m]
    usage = []
    for line in lines:
        if line.startswith("usage:") or (usage and line.startswith("       ")):
            usage.append(line)
        elif usage:
            break
    found += [(None, o) for o in re.findall(r"--[a-z][a-z0-9-]*", "\n".join(usage))]
    return found


def synopsis(readme, name):
    """The page's code blocks that name the tool, joined."""
    blocks = re.findall(r"```[a-z]*\n(.*?)```", readme, re.S)
    return "\n".join(b for b in blocks if re.search(r"\b%s\b" % re.escape(name), b))


def stands(form, text):
    return form and re.search(r"(?<![\w-])%s(?![\w-])" % re.escape(form), text)


def main(argv):
    readme = open(argv[1]).read()
    missing = 0
    for tool in argv[2:]:
        name = os.path.basename(tool)
        text = synopsis(readme, name)
        if not text:
            print("FAIL: %s has no synopsis of %s" % (argv[1], name))
            missing += 1
            continue
        absent = sorted({long for short, long in options(tool)
                         if not (stands(long, text) or stands(short, text))})
        for long in absent:
            print("FAIL: %s %s is not in %s's synopsis" % (name, long, argv[1]))
        print("%s: %s" % (name, "missing %d" % len(absent) if absent else "ok"))
        missing += len(absent)
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
