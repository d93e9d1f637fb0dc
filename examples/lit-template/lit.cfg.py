# A lit configuration to keep your own models under golden-file tests with
# netlift (docs/guide.md). Copy this directory next to your models and run
#   lit -v path/to/this/dir                      # netlift found on PATH
#   lit -v path/to/this/dir --param netlift=/opt/netlift/bin/netlift
# lit and FileCheck come with LLVM 14 (Debian: llvm-14-tools; lit is
# /usr/lib/llvm-14/build/utils/lit/lit.py, FileCheck /usr/lib/llvm-14/bin).
import os
import shutil
import lit.formats

config.name = "my-models"
config.test_format = lit.formats.ShTest(execute_external=False)
config.suffixes = [".test"]
config.test_source_root = os.path.dirname(__file__)
# Where tests write their %t files (--param out=DIR; default: Output/ here).
config.test_exec_root = lit_config.params.get(
    "out", os.path.join(config.test_source_root, "Output"))

netlift = lit_config.params.get("netlift") or shutil.which("netlift")
if not netlift:
    lit_config.fatal("netlift not found: put it on PATH or pass "
                     "--param netlift=PATH")
config.substitutions.append(("%netlift", os.path.abspath(netlift)))
config.substitutions.append(("%models", config.test_source_root))
llvm_bin = "/usr/lib/llvm-14/bin"
config.environment["PATH"] = os.pathsep.join(
    [llvm_bin, os.environ.get("PATH", "")])

# %plantlib: netlift's plant library (cylinder.net, conveyor.net, ...) for
# closed-loop tests (`%netlift compose ctrl.st %plantlib/cylinder.net`):
# --param plantlib=DIR, else where netlift is installed
# (PREFIX/share/netlift/plant beside PREFIX/bin/netlift), else the source
# tree of a build directory (build/bin/netlift -> lib/plant).
bindir = os.path.dirname(os.path.abspath(netlift))
plantlib = lit_config.params.get("plantlib")
for candidate in (os.path.join(bindir, "..", "share", "netlift", "plant"),
                  os.path.join(bindir, "..", "..", "lib", "plant")):
    if not plantlib and os.path.isdir(candidate):
        plantlib = os.path.normpath(candidate)
if plantlib:
    config.substitutions.append(("%plantlib", plantlib))
