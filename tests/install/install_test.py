"""`cmake --install` into a temporary prefix, moved away, run with the source and build
trees hidden (installed_tree.py): gridrt renders what the build's gridrt renders, finding
its image module in the installed tree; the tiles merge; the farm runs; the man page and
the completions name every option of --help, which help_options.py reads on its own."""
import os
import re
import shutil
import unittest

import help_options
from installed_tree import BUILT_GRIDRT, SIZE, InstalledTree, run, same_image, without_loader_log

MODULE = "gridrt_image_codec.so"
WINDOW_MODULE = "gridrt_window.so"  # the viewer's (host/viewer/sdl)


class Install(unittest.TestCase):
    @classmethod
    def setUpClass(cls):
        cls.tree = InstalledTree()
        cls.addClassCleanup(cls.tree.close)  # also when the rest of setUpClass fails
        if not cls.tree.trees.hidden:
            print(f"note: the trees stay visible ({cls.tree.trees.why_not}); the loader's "
                  "log alone shows where the module came from")
        cls.help = help_options.help_text(BUILT_GRIDRT)
        cls.options = help_options.options(cls.help)
        assert len(cls.options) > 20, "gridrt --help lists too few options to compare"

    def reference(self, name, *argv):
        """The build tree's gridrt's render, to compare the installed one's with."""
        path = self.tree.out("built_" + name)
        r = run([BUILT_GRIDRT, "-q", "-o", path, *SIZE, *argv], env=self.tree.env)
        self.assertEqual(r.returncode, 0, r.stderr)
        return path

    def test_renders_and_merges_tiles_with_the_trees_hidden(self):
        # The loader's log names every library loaded: an EXR loads the image module.
        full = self.tree.out("installed.exr")
        r = self.tree.run(["gridrt", "-q", "-o", full, *SIZE], env=dict(self.tree.env,
                                                                          LD_DEBUG="files"))
        self.assertEqual(r.returncode, 0, without_loader_log(r.stderr))
        loaded = re.findall(r"file=(\S*" + re.escape(MODULE) + r")", r.stderr)
        self.assertEqual(set(loaded), {self.tree.path("lib", "gridrt", MODULE)})
        same_image(self, full, self.reference("full.exr"))
        tiles = []
        for k, crop in enumerate(["0,0,40,48", "40,0,64,48"]):
            tiles.append(self.tree.out(f"tile{k}.exr"))
            r = self.tree.run(["gridrt", "-q", "-o", tiles[-1], *SIZE, "--crop", crop,
                               "--crop-output", "window"])
            self.assertEqual(r.returncode, 0, r.stderr)
        merged = self.tree.out("merged.exr")
        r = self.tree.run(["gridrt-merge-tiles", merged, *tiles])
        self.assertEqual(r.returncode, 0, r.stderr)
        same_image(self, merged, full)

    def test_the_viewer_loads_its_window_module_from_the_installed_tree(self):
        built = os.path.join(os.path.dirname(BUILT_GRIDRT), WINDOW_MODULE)
        if not os.path.isfile(built):
            self.skipTest("gridrt was built without SDL2 (libsdl2-dev): no window module")
        # A display that cannot open: the module loads, then says so in one line.
        r = self.tree.run(["gridrt", "--view"], env=dict(self.tree.env, DISPLAY=":65000",
                                                         LD_DEBUG="files"))
        self.assertEqual(r.returncode, 1, without_loader_log(r.stderr))
        loaded = re.findall(r"file=(\S*" + re.escape(WINDOW_MODULE) + r")", r.stderr)
        self.assertEqual(set(loaded), {self.tree.path("lib", "gridrt", WINDOW_MODULE)})
        self.assertIn("gridrt: no display:", without_loader_log(r.stderr))

    def test_the_farm_runs_from_the_installed_tree(self):
        if run(["/usr/bin/python3", "-c", "import distributed"]).returncode != 0:
            self.skipTest("Debian's python3-distributed is not installed (tools/setup.sh)")
        out = self.tree.out("farm.png")
        r = self.tree.run(["gridrt-farm", "--workers", "1", "--tiles", "2x1", "-q", "-o", out,
                           *SIZE])
        self.assertEqual(r.returncode, 0, r.stderr[-2000:])
        same_image(self, out, self.reference("farm.png"))

    def test_the_man_page_lists_every_option(self):
        page = self.tree.path("share", "man", "man1", "gridrt.1")
        if not os.path.isfile(page) and not shutil.which("help2man"):
            self.skipTest("help2man is not installed, so the build made no man page "
                          "(tools/setup.sh installs it)")
        self.assertTrue(os.path.isfile(page), page)
        with open(page) as f:
            roff = f.read()
        # Each option is an entry: ".TP" then its names in bold, hyphens as "\-".
        entries = re.findall(r"^\.TP\n(.*)$", roff, re.M)
        listed = set()
        for entry in entries:
            text = re.sub(r"\\f[BIRP]", "", entry).replace("\\-", "-")
            first = text.split()[0] if text.split() else ""
            listed.update(n for n in first.split(",") if n.startswith("-"))
        self.assertEqual(listed, self.options)

    def test_bash_completes_every_option_and_the_choices(self):
        script = self.tree.path("share", "bash-completion", "completions", "gridrt")
        self.assertTrue(os.path.isfile(script), script)

        def complete(*words):
            line = " ".join(f"'{w}'" for w in words)
            r = run(["bash", "--norc", "-c", f'source "$0" && COMP_WORDS=(gridrt {line}) && '
                     f'COMP_CWORD={len(words)} && _gridrt && printf "%s\\n" "${{COMPREPLY[@]}}"',
                     script], cwd=self.tree.scratch)
            self.assertEqual(r.returncode, 0, r.stderr)
            return set(r.stdout.split())

        self.assertEqual(complete("-"), self.options)
        self.assertEqual(complete("--wi"), {"--width"})
        for option, values in help_options.choices(self.help).items():
            self.assertEqual(complete(option, ""), set(values), option)

    def test_zsh_specifies_every_option_and_the_choices(self):
        script = self.tree.path("share", "zsh", "vendor-completions", "_gridrt")
        if not os.path.isfile(script):
            script = self.tree.path("share", "zsh", "site-functions", "_gridrt")
        self.assertTrue(os.path.isfile(script), script)
        zsh = shutil.which("zsh")
        if not zsh:
            self.skipTest("zsh is not installed (tools/setup.sh installs it)")
        # _arguments stubbed to print the specifications the completion hands it.
        r = run([zsh, "-f", "-c", '_arguments() { print -rl -- "$@" }; source "$0"', script])
        self.assertEqual(r.returncode, 0, r.stderr)
        specs = {}
        for spec in r.stdout.splitlines():
            m = re.match(r"^\*?(-[^\[=+]+)\[", spec)
            if m:
                specs[m.group(1)] = spec
        self.assertEqual(set(specs), self.options)
        for option, values in help_options.choices(self.help).items():
            self.assertTrue(specs[option].endswith(f":({' '.join(values)})"), specs[option])


if __name__ == "__main__":
    unittest.main()
