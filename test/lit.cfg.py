# lit configuration of the netlift test suite.
import os
import sys
import lit.formats

config.name = "netlift"
config.test_format = lit.formats.ShTest(execute_external=False)
config.suffixes = [".net", ".test", ".st"]
# Helper scripts next to a test (x.test.py) are not tests.
config.excludes = ["Inputs", "unit", "utils", "CMakeLists.txt", "lit.cfg.py",
                   "lit.site.cfg.py.in"]
config.test_source_root = os.path.dirname(__file__)
config.test_exec_root = os.path.join(config.netlift_obj_root, "test")

# The tools the RUN lines use: netlift from the build, FileCheck, not and
# split-file from LLVM 14.
config.substitutions.append(
    ("%netlift", os.path.join(config.netlift_tools_dir, "netlift")))
config.substitutions.append(("%lit", config.lit_script))
config.substitutions.append(("%examples",
                             os.path.join(config.netlift_src_root, "examples")))
config.substitutions.append(("%srcroot", config.netlift_src_root))
config.substitutions.append(("%builddir", config.netlift_obj_root))
config.substitutions.append(("%show-exit", sys.executable + " " +
                             os.path.join(os.path.dirname(__file__), "utils",
                                          "show-exit.py")))
config.substitutions.append(("%python", sys.executable))
config.environment["PATH"] = os.pathsep.join(
    [config.llvm_tools_dir, config.netlift_tools_dir,
     config.environment.get("PATH", "")])

# `lit --param roundtrip=1`: every NetIR input any test reads must be a
# fixed point of print -> parse -> print (checked inside netlift).
# The same run replays every JSON trace netlift writes on its model at
# once (NETLIFT_VERIFY_TRACES): each must end in the state it claims.
if lit_config.params.get("roundtrip", "0") not in ("0", ""):
    config.environment["NETLIFT_VERIFY_ROUNDTRIP"] = "1"
    config.environment["NETLIFT_VERIFY_TRACES"] = "1"

# `lit --param inputs=enumerate` (or split): the exploring commands' default
# for free inputs, so that the whole suite runs in each mode and shows the
# two give the same state spaces (tests that are about one mode say so).
inputs_mode = lit_config.params.get("inputs", "")
if inputs_mode:
    config.environment["NETLIFT_INPUTS"] = inputs_mode

# spin (Debian package, installed by scripts/setup.sh) and a C compiler:
# the Promela export is cross-checked by running spin's verifier.
import shutil
if shutil.which("spin") and shutil.which("cc"):
    config.available_features.add("spin")
# GTKWave's converters (scripts/setup.sh installs gtkwave when it can): the
# VCD traces are read back by the viewer's own reader.
if shutil.which("vcd2fst") and shutil.which("fst2vcd"):
    config.available_features.add("gtkwave")
# A C compiler: IEEE arithmetic is cross-checked against what C computes.
# No fused multiply-add: a PLC rounds every operation.
if shutil.which("cc"):
    config.available_features.add("cc")
    config.substitutions.append(("%cc", "cc -O0 -ffp-contract=off"))
# Debian's chromium (scripts/setup.sh installs it when it can): the HTML
# report is tested in a real browser.
# It must also start here (headless, as root, no sandbox).
import subprocess
if shutil.which("chromium"):
    try:
        probe = subprocess.run(
            ["chromium", "--headless", "--no-sandbox", "--disable-gpu",
             "--disable-background-networking", "--no-first-run",
             "--dump-dom", "about:blank"],
            capture_output=True, timeout=60)
        if probe.returncode == 0 and b"<html" in probe.stdout:
            config.available_features.add("chromium")
    except (OSError, subprocess.TimeoutExpired):
        pass

# Suite-wide cross-checks that rerun other tests' commands (minutes): in the
# main run only (`--param roundtrip=1`, as CI runs it), not under sanitizers.
if lit_config.params.get("roundtrip", "0") not in ("0", "") and \
        not config.sanitize:
    config.available_features.add("crosscheck")

if config.sanitize:
    config.environment["ASAN_OPTIONS"] = "detect_leaks=1"
    config.environment["UBSAN_OPTIONS"] = "print_stacktrace=1:halt_on_error=1"
    config.available_features.add("sanitizer")

# Third-party corpus beside the checkout (../shared/corpus): tests that need
# it are UNSUPPORTED, with their REQUIRES line as the message, without it.
corpus = os.path.normpath(os.path.join(config.netlift_src_root, "..", "shared",
                                       "corpus"))
config.substitutions.append(("%corpus", corpus))
if os.path.exists(os.path.join(corpus, "pnml", "mcc2021",
                               "oracle-statespace.tsv")):
    config.available_features.add("mcc-corpus")
if os.path.isdir(os.path.join(corpus, "iec61499", "fb2smv", "tests", "smv")):
    config.available_features.add("fb2smv-corpus")
if os.path.isdir(os.path.join(corpus, "spaceex")):
    config.available_features.add("spaceex-corpus")
# One feature per corpus folder: each sweep runs when its own folder is here.
if os.path.isdir(corpus):
    for folder in sorted(os.listdir(corpus)):
        if os.path.isdir(os.path.join(corpus, folder)):
            config.available_features.add("corpus-" + folder)
