"""The scene planner: the cheapest model that meets a scene's tolerance, from measured error and cost.

* :class:`Scene` — what the output must show (TOML: :meth:`Scene.from_toml`; built-in
  examples in :data:`BUILTIN_SCENES`, :func:`builtin_scene`);
* :func:`plan` — the cheapest :class:`Choices` whose predicted error stays within the
  tolerance, as a :class:`Plan` (model card, predicted error and cost, Pareto front);
* :func:`run` — simulate and shade a scene with a :class:`SceneModel`;
  :func:`full_model` — the reference configuration; :func:`compare` — measured errors;
* :func:`generate_scenes` — seeded scenes nobody picked (the proof's inputs);
* :func:`calibrate` — measure the cost model on this machine (``wavephys calibrate``);
  :func:`load_calibration` — read such a file for :func:`plan`.

How errors are predicted and costs calibrated: ``docs/planner.md``. The planner imports
the optics (Fresnel, absorption), so it belongs to the application layer.
"""

from __future__ import annotations

from wavephys.planner.builtin import BUILTIN_SCENES, builtin_scene
from wavephys.planner.measure import calibrate
from wavephys.planner.cost import load_calibration
from wavephys.planner.generate import KINDS, generate_scenes
from wavephys.planner.model import Choices, SceneModel
from wavephys.planner.plan import Candidate, Infeasible, Plan, Term, candidates, colour_errors, full_model, plan
from wavephys.planner.runner import Output, compare, run
from wavephys.planner.scene import FloorSpec, Scene, ShipSpec, StoneSpec, WindSpec

__all__ = ["calibrate", "load_calibration", "Scene", "StoneSpec", "ShipSpec", "WindSpec", "FloorSpec", "Choices", "SceneModel", "plan", "Plan", "Term", "Candidate",
           "Infeasible", "candidates", "colour_errors", "full_model", "run", "compare", "Output", "generate_scenes",
           "KINDS", "BUILTIN_SCENES", "builtin_scene"]
