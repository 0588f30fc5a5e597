#!/usr/bin/env python3
"""Runs a document's code blocks as written, so that a doc's example
cannot rot (docs/api.md's C and Python snippets are CTest tests).

    doc_snippets.py DOC.md LANG SOURCE_DIR BUILD_DIR [PYTHON]

Each fenced block of LANG ("c" or "python") runs in a scratch folder that
looks like the repository's root (its folders are links to SOURCE_DIR's,
`build` to BUILD_DIR): a C block is saved as demo.c and its first line, a
comment holding the shell command that builds and runs it, is run; a
Python block runs with PYTHON (default: python3) and SHAFTS_LIB pointing
at BUILD_DIR/libshafts.so. Exits 1 if a block fails.
"""
import os
import re
import subprocess
import sys
import tempfile


def blocks(text, lang):
    return re.findall(r"^```%s\n(.*?)^```" % re.escape(lang), text, re.S | re.M)


def main():
    doc, lang, source, build = sys.argv[1:5]
    python = sys.argv[5] if len(sys.argv) > 5 else "python3"
    with open(doc) as f:
        found = blocks(f.read(), lang)
    if not found:
        print("FAIL: no %s block in %s" % (lang, doc))
        return 1
    failed = 0
    for i, code in enumerate(found):
        with tempfile.TemporaryDirectory() as tmp:
            for name in os.listdir(source):
                if name != "build" and not name.startswith("."):
                    os.symlink(os.path.join(os.path.abspath(source), name),
                               os.path.join(tmp, name))
            os.symlink(os.path.abspath(build), os.path.join(tmp, "build"))
            env = dict(os.environ, SHAFTS_LIB=os.path.join(os.path.abspath(build),
                                                           "libshafts.so"))
            if lang == "c":
                first = code.splitlines()[0]
                command = re.match(r"/\*\s*(.*?)\s*\*/$", first)
                if not command:
                    print("FAIL: block %d does not start with /* build command */" % i)
                    failed += 1
                    continue
                with open(os.path.join(tmp, "demo.c"), "w") as f:
                    f.write(code)
                run = ["sh", "-c", command.group(1)]
            else:
                with open(os.path.join(tmp, "demo.py"), "w") as f:
                    f.write(code)
                run = [python, "demo.py"]
            r = subprocess.run(run, cwd=tmp, env=env, stdout=subprocess.PIPE,
                               stderr=subprocess.STDOUT, universal_newlines=True)
            print(r.stdout, end="")
            print("%s: %s block %d of %s" % ("ok" if r.returncode == 0 else "FAIL", lang, i, doc))
            failed += r.returncode != 0
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
