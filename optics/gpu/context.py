"""The headless OpenGL context every GPU user of the optics shares.

An OpenGL 3.3 core context through EGL without a display: Mesa llvmpipe on a CPU-only
machine, the GPU driver elsewhere, unchanged. Each caller keeps its own context and makes
it current (``with ctx:``) before its GL calls, so several can live in one process.
"""

from __future__ import annotations

__all__ = ["RendererUnavailable", "EGL_PACKAGES", "gl_context"]

EGL_PACKAGES = "libegl1 libegl-mesa0 libgl1-mesa-dri"
"""Debian/Ubuntu packages that provide headless EGL with Mesa (llvmpipe on CPU-only machines)."""


class RendererUnavailable(RuntimeError):
    """No OpenGL 3.3 context could be created (headless EGL missing or broken)."""


def gl_context():
    """A standalone OpenGL 3.3 core context through EGL.

    Returns
    -------
    moderngl.Context
        Make it current (``with ctx:``) before GL calls: several contexts can live in a process.

    Raises
    ------
    RendererUnavailable
        No context could be made; the message says which packages to install.
    """
    try:
        import moderngl
    except ImportError as exc:  # pragma: no cover - moderngl is a dependency
        raise RendererUnavailable(f"moderngl is not installed ({exc}); pip install moderngl") from exc
    try:
        return moderngl.create_context(standalone=True, backend="egl", require=330)
    except Exception as exc:
        raise RendererUnavailable(
            f"no headless OpenGL 3.3 context through EGL ({type(exc).__name__}: {exc}). "
            f"Install the EGL and Mesa packages: apt-get install {EGL_PACKAGES} "
            f"(or your GPU driver's EGL library)") from exc
