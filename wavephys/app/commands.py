"""The ``wavephys`` command's subcommands as one table: how each is called, its one-line help, its description
and its exit codes. :mod:`wavephys.app.cli` builds every ``--help`` from it (and the ``check`` subcommand's
module, :mod:`wavephys.app.check_command`, its own); nothing heavy is imported here.
"""

from __future__ import annotations

from dataclasses import dataclass

__internal__ = True  # the command's help text: read through `wavephys --help`
__all__ = ["Command", "COMMANDS", "USAGE_ERROR", "NO_OPENGL", "INTERRUPTED"]

USAGE_ERROR = (2, "usage error: a bad option or output path (checked before any work starts)")
NO_OPENGL = (3, "no OpenGL context (headless EGL missing: apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri)")
INTERRUPTED = (130, "interrupted (Ctrl-C): one line says so, and what was finished is kept")


@dataclass(frozen=True)
class Command:
    """One subcommand of ``wavephys``: what ``--help`` says of it.

    Attributes
    ----------
    usage : str
        How it is called, in short (``wavephys plan SCENE``).
    help : str
        One line, for ``wavephys --help``.
    description : str
        What it does, for its own ``--help``.
    codes : tuple of (int, str)
        Its exit statuses and what each means.
    """

    usage: str
    help: str
    description: str
    codes: tuple

    def epilog(self) -> str:
        """The exit-status block of its ``--help``."""
        import textwrap

        return "exit status:\n" + "\n".join(textwrap.fill(meaning, 100, initial_indent=f"  {code:<5d}",
                                                          subsequent_indent=" " * 7) for code, meaning in self.codes)


COMMANDS = {
    "run": Command("wavephys run", "simulate the built-in default scene (the main job)",
                   "Three stones in 16 m of open water; writes surface.npz (heights, m) and surface.png.",
                   ((0, "done: OUT/surface.npz and OUT/surface.png written"), USAGE_ERROR)),
    "validate": Command("wavephys validate", "run the built-in physics validations, expected against measured",
                        "Run the built-in validations and print expected against measured, each row as it "
                        "finishes: by default every check but the long ones (under a minute on a 2-core CPU), "
                        "with --all every one (about 4.5 minutes). Ctrl-C stops after the rows finished, which "
                        "are printed (and written with --json).",
                        ((0, "every validation row ok"), (1, "a validation row failed"), USAGE_ERROR, INTERRUPTED)),
    "render": Command("wavephys render", "render a built-in scene with the headless moderngl renderer",
                      "Render a built-in scene (its water, ground, sky, caustics) to a PNG, or an animation to a "
                      "folder of PNGs (and a video with --video).",
                      ((0, "done: the frame(s) written"), USAGE_ERROR, NO_OPENGL)),
    "textures": Command("wavephys textures", "export a built-in scene's textures",
                        "Write a built-in scene's textures (water height and normals, caustics, ground; EXR, and "
                        "PNG with 16-bit heights and 8-bit normals) to a folder; with --frames, a record of EXR "
                        "height frames for 'wavephys check'.",
                        ((0, "done: the textures written"), USAGE_ERROR)),
    "plan": Command("wavephys plan SCENE", "the cheapest model that meets a tolerance (the scene planner)",
                    "",  # written in build_parser: it names the built-in scenes
                    ((0, "a plan: its model card printed"), (1, "no model meets the tolerance (the card says why)"),
                     USAGE_ERROR)),
    "calibrate": Command("wavephys calibrate --out F", "measure the planner's costs on this machine",
                         "Time every piece the planner's cost model reads (steps, frames, shading, caustics, "
                         "textures, float32 rounding) on this machine and its JAX device, and write them to a JSON "
                         "file for 'wavephys plan --calibration FILE'. All tables took 7 minutes on a 2-core CPU; "
                         "--only measures some.",
                         ((0, "done: the calibration file written"), USAGE_ERROR)),
    "report": Command("wavephys report --out DIR", "one self-contained HTML page of what is measured",
                      "Validation table, wake pattern and angles, ring waves, bench charts, model cards, rendered "
                      "frames: DIR/report.html, each validation row printed as it finishes. Ctrl-C writes the page "
                      "with the sections finished, saying which are missing.",
                      ((0, "done: DIR/report.html written"), USAGE_ERROR, INTERRUPTED)),
    "check": Command("wavephys check FRAMES... | --glsl FILE", "check exported frames, or a shader function, against "
                     "the physics", "",  # its options and description: wavephys.app.check_command
                     ((0, "every check ok (frames), or the function meets the physics (a shader)"),
                      (1, "a check failed, or the function does not meet the physics"),
                      (2, "usage error: a bad option or output path, unreadable frames, or a shader that does not "
                          "compile or whose function cannot be called as asked (said before any check runs)"),
                      (3, "no OpenGL context (apt-get install libegl1 libegl-mesa0 libgl1-mesa-dri), or for HLSL "
                          "no translator (apt-get install glslang-tools spirv-cross)"))),
}
""":data:`COMMANDS` by name: the one place the command's help and exit codes are written."""


