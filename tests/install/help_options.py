"""gridrt's options as its --help lists them, read here on their own (not with the
completions' generator), so the tests compare the installed files against the program."""
import re
import subprocess

# An option's entry: two spaces, then its names joined by commas ("-o,--output").
ENTRY = re.compile(r"^  (--?[A-Za-z0-9][\w,-]*)")
CHOICES = re.compile(r"\{([^}]*)\}")


def help_text(gridrt, env=None):
    return subprocess.run([gridrt, "--help"], capture_output=True, text=True, check=True,
                          env=env).stdout


def options(text):
    """Every option name ("-o", "--output", ...) of the Options section."""
    names, section = set(), None
    for line in text.splitlines():
        if line.endswith(":") and not line.startswith(" "):
            section = line[:-1]
        m = ENTRY.match(line)
        if section == "Options" and m:
            names.update(m.group(1).split(","))
    return names


def choices(text):
    """{option: [its choices]} for the options whose value is one of a set."""
    found = {}
    for line in text.splitlines():
        m = ENTRY.match(line)
        if not m:
            continue
        rest = line[m.end():].split("  ")[0]
        c = CHOICES.search(rest)
        if c:
            for name in m.group(1).split(","):
                found[name] = c.group(1).split(",")
    return found
