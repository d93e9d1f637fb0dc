#!/usr/bin/env python3
"""Writes netlift's man pages and shell completion from what the binary
says about itself: `netlift --help` (the subcommands and their summaries,
from the command table), `netlift SUB --help` (each subcommand's options,
from the option registry), `netlift opt --list-passes` (the pass table) and
`netlift emit --help` (the backend registry). Run at build time
(tools/CMakeLists.txt), so the pages and completions follow the registries.

Writes OUTDIR/man/man1/netlift.1 and netlift-SUB.1 (roff), and
OUTDIR/completion/netlift (bash) and OUTDIR/completion/_netlift (zsh, through
bash's completion function).

usage: make-cli-files.py NETLIFT OUTDIR
"""
import os
import re
import subprocess
import sys


def run(netlift, *args):
    r = subprocess.run([netlift, *args], capture_output=True, text=True)
    return r.stdout + r.stderr


def subcommands(top_help):
    """(name, summary) of every subcommand, in --help's order."""
    out, inside = [], False
    for line in top_help.splitlines():
        if line.startswith("SUBCOMMANDS:"):
            inside = True
            continue
        if inside:
            m = re.match(r"\s+(\S+)\s+- (.*)", line)
            if m:
                out.append((m.group(1), m.group(2)))
            elif line.strip() and not line.startswith(" "):
                break
    return out


def options(sub_help):
    """Every option a subcommand's --help lists (`--name`, `-D`), and the
    values an enumerated option takes."""
    opts, values, current = [], {}, None
    for line in sub_help.splitlines():
        m = re.match(r"\s{2}(-{1,2}[A-Za-z][\w-]*)", line)
        if m:
            current = m.group(1)
            if current not in ("--help", "--help-list", "--version"):
                opts.append(current)
            continue
        # `    =value  - ...` (an enumerated option), or a registry's list
        # under the option (`emit --to`: `      net - NetIR text`).
        v = (re.match(r"\s{4}=(\S+)\s+-", line) or
             re.match(r"\s{10,}([a-z][\w-]*) - ", line))
        if v and current:
            values.setdefault(current, []).append(v.group(1))
    return opts, values


def roff_escape(text):
    return text.replace("\\", "\\e").replace("-", "\\-")


def man_page(name, summary, version, body):
    lines = [f'.TH {name.upper()} 1 "" "netlift {version}" "netlift manual"',
             ".SH NAME", f"{name} \\- {roff_escape(summary)}",
             ".SH DESCRIPTION", ".nf"]
    for line in body.splitlines():
        # A line starting with a dot or quote would be a roff request.
        if line.startswith((".", "'")):
            line = "\\&" + line
        lines.append(roff_escape(line))
    lines += [".fi", ".SH SEE ALSO"]
    return "\n".join(lines) + "\n"


BASH = """# bash completion for netlift (made by scripts/make-cli-files.py from the
# binary's own --help: do not edit)
_netlift() {
  local cur prev sub
  cur="${COMP_WORDS[COMP_CWORD]}"
  prev="${COMP_WORDS[COMP_CWORD-1]}"
  if [ "$COMP_CWORD" -eq 1 ]; then
    COMPREPLY=($(compgen -W "%(subs)s" -- "$cur"))
    return
  fi
  sub="${COMP_WORDS[1]}"
  case "$sub:$prev" in
%(values)s
  esac
  case "$sub" in
%(opts)s
  esac
  if [[ "$cur" != -* ]]; then
    COMPREPLY=($(compgen -f -- "$cur"))
  fi
}
complete -o filenames -F _netlift netlift
"""

ZSH = """#compdef netlift
# zsh completion for netlift: bash's (scripts/make-cli-files.py), read
# through zsh's bash compatibility.
autoload -U +X bashcompinit && bashcompinit
%(bash)s"""


def main():
    if len(sys.argv) != 3:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    netlift, outdir = sys.argv[1:3]
    top = run(netlift, "--help")
    version = run(netlift, "--version").split()[1]
    subs = subcommands(top)
    if not subs:
        print("make-cli-files: no subcommands in netlift --help",
              file=sys.stderr)
        return 1
    man = os.path.join(outdir, "man", "man1")
    comp = os.path.join(outdir, "completion")
    os.makedirs(man, exist_ok=True)
    os.makedirs(comp, exist_ok=True)
    see = ", ".join(f"netlift-{s}(1)" for s, _ in subs)
    page = man_page("netlift", "lift industrial control software into "
                    "formal models", version, top)
    with open(os.path.join(man, "netlift.1"), "w") as f:
        f.write(page + roff_escape(see) + "\n")
    passes = re.findall(r"^  ([a-z][\w-]*)\s{2,}", run(netlift, "opt",
                                                       "--list-passes"),
                        re.M)
    value_cases, opt_cases = [], []
    for sub, summary in subs:
        text = run(netlift, sub, "--help")
        # The overview every subcommand's --help repeats is netlift(1)'s.
        start = text.find("SUBCOMMAND '")
        text = text[start:] if start >= 0 else text
        with open(os.path.join(man, f"netlift-{sub}.1"), "w") as f:
            f.write(man_page(f"netlift-{sub}", summary, version, text) +
                    "netlift(1)\n")
        opts, values = options(text)
        if sub == "opt":
            values["-p"] = passes
            values["--pipeline"] = passes
        for opt, vals in values.items():
            value_cases.append(f'    {sub}:{opt}) COMPREPLY=($(compgen -W '
                               f'"{" ".join(vals)}" -- "$cur")); return ;;')
        opt_cases.append(f'    {sub}) if [[ "$cur" == -* ]]; then COMPREPLY=('
                         f'$(compgen -W "{" ".join(opts)}" -- "$cur")); '
                         f'return; fi ;;')
    bash = BASH % {"subs": " ".join(s for s, _ in subs),
                   "values": "\n".join(value_cases),
                   "opts": "\n".join(opt_cases)}
    with open(os.path.join(comp, "netlift"), "w") as f:
        f.write(bash)
    with open(os.path.join(comp, "_netlift"), "w") as f:
        f.write(ZSH % {"bash": bash})
    return 0


if __name__ == "__main__":
    sys.exit(main())
