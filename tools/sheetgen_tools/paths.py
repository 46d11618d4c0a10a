"""Where things are in a checkout: the repository root, the sample scenes and
the `sheetgen` binary of the default build folder."""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SAMPLE_SCENES = os.path.join(ROOT, "sample_scenes")
DEFAULT_BUILD = os.path.join(ROOT, "build")
DEFAULT_SHEETGEN = os.path.join(DEFAULT_BUILD, "native", "cli", "sheetgen")


def sheetgen_in(build_dir):
    """The CLI of a build folder."""
    return os.path.join(build_dir, "native", "cli", "sheetgen")


def scene_problem(name):
    """sample_scenes/<name>/problem.json."""
    return os.path.join(SAMPLE_SCENES, name, "problem.json")


def sample_scene_names():
    """Every folder of sample_scenes/ that holds a problem.json, sorted by name."""
    return sorted(n for n in os.listdir(SAMPLE_SCENES) if os.path.isfile(scene_problem(n)))
