#!/usr/bin/env python3
"""Writes bash's and zsh's completions of gridrt from its `--help` text, so they name every
option the program has, at build time (tools/completions/CMakeLists.txt):

    make_completions.py GRIDRT BASH_FILE ZSH_FILE

An option with choices ({a,b,c} in its value) completes to them, a TEXT or FILE value and
the scene to file names, any other value (numbers, A:B, NAME|INDEX) to nothing. A gridrt
that fails, or help text without an option, is an error (exit 1): an empty completion would
pass unnoticed."""
import re
import subprocess
import sys

# "  -o,--output TEXT   description": the names, then the value's form after one space, the
# description after two or more. A long value form puts the description on the next line.
OPTION_LINE = re.compile(r"^  (?P<names>-[^\s]+)(?: (?P<value>\S+))?(?:\s{2,}(?P<text>.*))?$")
FILE_VALUE = re.compile(r"^TEXT|FILE")
CHOICES = re.compile(r"\{([^}]*)\}")


class Option:
    def __init__(self, names, value, text):
        self.names = names          # ["-o", "--output"]
        self.value = value          # "TEXT:{png,jpg}", or None for a flag
        self.text = text.strip()

    @property
    def choices(self):
        m = CHOICES.search(self.value or "")
        return m.group(1).split(",") if m else None

    @property
    def file(self):
        return bool(self.value and FILE_VALUE.search(self.value))

    @property
    def repeatable(self):
        return "repeatable" in self.text


def parse_help(text):
    options, section = [], None
    for line in text.splitlines():
        if line and not line.startswith(" "):
            section = line.rstrip(":")
            continue
        m = OPTION_LINE.match(line)
        if section == "Options" and m:
            options.append(Option(m.group("names").split(","), m.group("value"),
                                  m.group("text") or ""))
        elif options and line.startswith("      ") and not options[-1].text:
            options[-1].text = line.strip()
    return options


def bash_script(options):
    words = " ".join(name for o in options for name in o.names)
    cases = []
    for o in options:
        if o.value is None:
            continue
        pattern = "|".join(o.names)
        if o.choices:
            action = f'COMPREPLY=($(compgen -W "{" ".join(o.choices)}" -- "$cur"))'
        elif o.file:
            action = 'COMPREPLY=($(compgen -f -- "$cur"))'
        else:
            action = "COMPREPLY=()"
        cases.append(f"    {pattern}) {action}; return ;;")
    return f"""# bash completion of gridrt's options, made from `gridrt --help` at build time
# (tools/completions/make_completions.py); it needs nothing of the bash-completion package.
_gridrt() {{
  local cur=${{COMP_WORDS[COMP_CWORD]}} prev=
  [ "$COMP_CWORD" -gt 0 ] && prev=${{COMP_WORDS[COMP_CWORD-1]}}
  case $prev in
{chr(10).join(cases)}
  esac
  if [[ $cur == -* ]]; then
    COMPREPLY=($(compgen -W "{words}" -- "$cur"))
  else
    COMPREPLY=($(compgen -f -- "$cur"))
  fi
}}
complete -o filenames -o bashdefault -F _gridrt gridrt
"""


def zsh_quote(text):
    """Text inside a single-quoted _arguments description."""
    text = re.sub(r"([\[\]:\\])", r"\\\1", text)
    return text.replace("'", "'\\''")


def zsh_script(options):
    specs = []
    for o in options:
        if o.value is None:
            action = ""
        elif o.choices:
            action = f":value:({' '.join(o.choices)})"
        elif o.file:
            action = ":file:_files"
        else:
            action = ":value: "
        text = zsh_quote(o.text)
        for name in o.names:
            star = "*" if o.repeatable else ""
            specs.append(f"  '{star}{name}[{text}]{action}'")
    specs.append("  '*:scene:_files'")
    return ("#compdef gridrt\n"
            "# zsh completion of gridrt's options, made from `gridrt --help` at build time\n"
            "# (tools/completions/make_completions.py).\n"
            "_arguments -S \\\n" + " \\\n".join(specs) + "\n")


def main(argv):
    if len(argv) != 4:
        print("usage: make_completions.py GRIDRT BASH_FILE ZSH_FILE", file=sys.stderr)
        return 2
    gridrt, bash_file, zsh_file = argv[1:]
    run = subprocess.run([gridrt, "--help"], capture_output=True, text=True)
    if run.returncode != 0:
        print(f"make_completions: '{gridrt} --help' exited {run.returncode}", file=sys.stderr)
        return 1
    options = parse_help(run.stdout)
    if not options:
        print("make_completions: no option found in the help text", file=sys.stderr)
        return 1
    with open(bash_file, "w") as f:
        f.write(bash_script(options))
    with open(zsh_file, "w") as f:
        f.write(zsh_script(options))
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
