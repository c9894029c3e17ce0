"""``python -m bench {propagation,boundaries,walls,shallow,optics,jacobian,ship,wake,harness,halffloat,render,filtering,meshes,surfaces,scale,calibrate,planner,savings} [--json PATH] [--quick]``.

Each writes its rows as JSON and its charts as PNG next to it (default
``bench/results/``) and prints a table.
"""

from __future__ import annotations

import argparse
import json
import statistics
import sys
from pathlib import Path


def _say(msg: str) -> None:
    print(msg, file=sys.stderr, flush=True)


def _write(rows, figures, path: Path) -> None:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(json.dumps(rows, indent=2, default=float))
    for name, fig in figures.items():
        fig.savefig(path.with_name(f"{path.stem}_{name}.png"), dpi=120)
    print(f"wrote {path} and {len(figures)} chart(s) beside it")


def run_propagation(args) -> None:
    from bench.propagation import accuracy_rows, device_step_rows, step_rows
    from wavephys.plot import plot_error_vs_time

    if args.device:
        rows = device_step_rows(args.device, (1024, 2048) if args.quick else (1024, 2048, 4096, 8192), _say)
        for r in rows:
            print(f"{r['device']} N={r['n']:<5} step {r['seconds'] * 1e3:.3f} ms against its FFT floor "
                  f"{r['baseline_seconds'] * 1e3:.3f} ms: ×{r['ratio']:.2f} ({r['ratio_quartiles'][0]:.2f}–"
                  f"{r['ratio_quartiles'][1]:.2f})")
        _write(rows, {}, Path(args.json or f"bench/results/propagation_{args.device}.json"))
        return

    sizes = (256, 512) if args.quick else (256, 512, 1024, 2048)
    steps = step_rows(sizes, progress=_say)
    acc = accuracy_rows(progress=_say)
    print(f"{'method':<18}{'n':>6}{'seconds':>12}{'baseline s':>12}{'ratio':>8}{'error':>11}")
    for r in steps:
        print(f"{r['method']:<18}{r['n']:>6}{r['seconds']:>12.5f}{r['baseline_seconds']:>12.5f}"
              f"{r['ratio']:>8.2f}{r['error']:>11.2e}  (baseline {r['baseline']}; ratio quartiles "
              f"{r['ratio_quartiles'][0]:.2f}–{r['ratio_quartiles'][1]:.2f})")
    for r in acc:
        print(f"{r['method']:<18}{r['n']:>6}{r['seconds']:>12.5f}{'':>12}{'':>8}{r['error']:>11.2e}  {r['label']}")
    fig = plot_error_vs_time(acc, "deep-water packet after 8 s: error against time")
    _write(steps + acc, {"error_vs_time": fig}, Path(args.json or "bench/results/propagation.json"))


def run_walls(args) -> None:
    from bench.walls import depth_step_rows, shoaling_rows, wall_rows

    rows = wall_rows((256, 512) if args.quick else (256, 512, 1024), progress=_say)
    rows += depth_step_rows((256,) if args.quick else (256, 512), progress=_say)
    print(f"{'boundary':<24}{'n':>6}{'grid':>6}{'ms':>9}{'x periodic':>12}{'temp MB':>9}{'drift/1000':>12}")
    for r in rows:
        print(f"{r['boundary']:<24}{r['n']:>6}{r['grid']:>6}{r['seconds'] * 1e3:>9.2f}{r['ratio']:>12.2f}"
              f"{r['temp_bytes'] / 2**20:>9.1f}{r['energy_drift_1000']:>12.2e}  (quartiles {r['ratio_quartiles'][0]:.2f}–"
              f"{r['ratio_quartiles'][1]:.2f})")
    shoal = shoaling_rows(progress=_say)
    print(f"{'method':<14}{'kh0':>6}{'ramp/lam':>10}{'slope':>9}{'A/A0':>9}{'mild-slope':>12}{'R ref':>8}{'error':>9}")
    for r in shoal:
        print(f"{r['method'] + ' (' + str(r['levels']) + ')':<14}{r['kh0']:>6}{r['ramp_wavelengths']:>10}{r['slope']:>9.4f}{r['amplitude']:>9.4f}"
              f"{r['reference']:>12.4f}{r['reference_reflection']:>8.4f}{r['error']:>+9.2%}")
    _write(rows + shoal, {}, Path(args.json or "bench/results/walls.json"))


def run_shallow(args) -> None:
    from bench.shallow import compile_rows, dam_break_rows, figures, memory_rows, split_dispersion_rows, step_rows

    rows = dam_break_rows((100, 200, 400) if args.quick else (100, 200, 400, 800, 1600), progress=_say)
    print(f"{'case':<22}{'method':<26}{'n':>6}{'seconds':>10}{'L1 m':>11}{'max m':>9}")
    for r in rows:
        print(f"{r['case']:<22}{r['method']:<26}{r['n']:>6}{r['seconds']:>10.4f}{r['error']:>11.2e}{r['max_error']:>9.3f}")
    steps = step_rows((256,) if args.quick else (256, 512), progress=_say)
    print(f"{'model':<38}{'n':>6}{'ms/step':>10}{'x spectral':>12}")
    for r in steps:
        print(f"{r['method']:<38}{r['n']:>6}{r['seconds'] * 1e3:>10.3f}{r['ratio']:>12.2f}  (quartiles "
              f"{r['ratio_quartiles'][0]:.2f}–{r['ratio_quartiles'][1]:.2f})")
    compiled = compile_rows(progress=_say)
    print(f"{'stepper':<26}{'form':<26}{'n':>5}{'lower s':>9}{'compile s':>11}{'lines':>7}")
    for r in compiled:
        print(f"{r['method']:<26}{r['form']:<26}{r['n']:>5}{r['lower_seconds']:>9.2f}{r['compile_seconds']:>11.2f}"
              f"{r['lines']:>7}")
    split = split_dispersion_rows(progress=_say)
    print(f"{'model':<26}{'kh band':>14}{'max |w/w_exact - 1|':>22}")
    for r in split:
        print(f"{r['model']:<26}{r['kh'][0]:>7.2g}..{r['kh'][1]:<5.3g}{r['error']:>22.2e}")
    memory = memory_rows((60, 240) if args.quick else (60, 960, 3840), progress=_say)
    print(f"{'run':<64}{'steps':>7}{'MB held':>10}{'resident +MB':>14}{'peak +MB':>10}")
    for r in memory:
        print(f"{r['method']:<64}{r['steps']:>7}{r['bytes_held'] / 2**20:>10.2f}{r['resident_growth_mb']:>14.1f}"
              f"{r['peak_growth_mb']:>10.1f}")
    _write(rows + steps + compiled + split + memory, figures(rows), Path(args.json or "bench/results/shallow.json"))


def run_boundaries(args) -> None:
    from bench.boundaries import boundary_data

    rows, figures = boundary_data(quick=args.quick, progress=_say)
    for r in rows:
        print(r)
    _write(rows, figures, Path(args.json or "bench/results/boundaries.json"))


def run_optics(args) -> None:
    from bench import optics

    rows = optics.fresnel_rows(_say) + optics.absorption_rows()
    rows += optics.caustics_rows(_say, count=3 if args.quick else 9)
    if not args.quick:
        rows += optics.speed_rows(_say)
    for r in rows:
        if r["family"] == "fresnel":
            print(f"fresnel {r['method']:<14}{r['side']:<6} worst {r['worst_error']:+.4f} at {r['worst_angle']:5.1f}°  "
                  f"weighted mean {r['weighted_mean_error']:.4f}  {r['seconds'] * 1e3:.2f} ms/1M "
                  f"(exact {r['baseline_seconds'] * 1e3:.2f})")
        elif r["family"] == "caustics reference":
            print(f"case {r['case']} {r['spectrum']:<6} sun {r['elevation']:4.1f}° at {r['fraction']} of the first fold: "
                  f"reference refine {r['refine']}, bound {r['bound']:.1e} of the peak {r['peak']:.2f}")
        elif r["family"] == "caustics speed":
            extra = f", {r['photons_per_second']:.3g} photons/s" if "photons_per_second" in r else ""
            print(f"speed {r['method']}: {r['seconds'] * 1e3:.1f} ms vs step {r['baseline_seconds'] * 1e3:.2f} ms, "
                  f"ratio {r['ratio']:.1f}{extra}")
    ca = [r for r in rows if r["family"] == "caustics"]
    for key in sorted({(r["method"], r["label"]) for r in ca}):
        sel = [r for r in ca if (r["method"], r["label"]) == key]
        print(f"caustics {key[0]:<12}{key[1]:<18} max-norm error {min(r['error'] for r in sel):.2e}-"
              f"{max(r['error'] for r in sel):.2e} of the peak, L2 {max(r['l2_error'] for r in sel):.2e}, "
              f"cost ×{statistics.median(r['ratio'] for r in sel):.1f} a step (128²), min value "
              f"{min(r['min_value'] for r in sel):.3g}")
    ab = [r for r in rows if r["family"] == "absorption"]
    print("rgb vs spectral: " + ", ".join(f"{r['distance']:.2g} m: {r['error']:.3f}" for r in ab[::6]))
    _write(rows, optics.figures(rows), Path(args.json or "bench/results/optics.json"))


def run_jacobian(args) -> None:
    from bench import jacobian

    rows = jacobian.boundary_rows(_say, seeds=(1,), n=64 if args.quick else 128)
    rows += jacobian.size_rows(_say, sizes=(64,) if args.quick else (64, 256, 512, 1024))  # 1024²: 7 min, 12 GB
    rows += jacobian.speed_rows(_say, sizes=(256,) if args.quick else (256, 512, 1024))
    rows += jacobian.scene_rows(_say, n=128 if args.quick else 256, times=(1.0,))
    for fraction in jacobian.FRACTIONS:
        sel = [r for r in rows if r["family"] == "jacobian boundary" and r["fraction"] == fraction]
        count = {a: sum(r["answered"] == a for r in sel) for a in ("gather", "windows", "beam")}
        windows = [r["windows"] for r in sel if r["answered"] == "windows"]
        print(f"{fraction:4.2f} of the first fold: gather {count['gather']}, windows {count['windows']}"
              + (f" ({min(windows):.0%}-{max(windows):.0%} of the floor)" if windows else "")
              + f", beam {count['beam']} of {len(sel)}; max-norm {max(r['error'] for r in sel):.2e}, "
              f"L2 {max(r['l2_error'] for r in sel):.2e}")
    for r in rows:
        if r["family"] == "jacobian speed":
            print(f"speed n={r['n']} {r['method']}: {r['seconds'] * 1e3:.1f} ms = {r['ratio']:.1f} steps "
                  f"(step {r['baseline_seconds'] * 1e3:.2f} ms)")
        if r["family"] == "jacobian wind seas":
            print(f"wind sea {r['spectrum']} n={r['n']} sun {r['elevation']:.0f}: {r['answered']} "
                  f"(supersample {r['supersample']}, windows {r['windows']:.0%}): max-norm {r['error']:.2e}, "
                  f"L2 {r['l2_error']:.2e} (reference bound {r['reference_bound']:.1e})")
        if r["family"] == "jacobian scenes":
            print(f"scene {r['scene']} t={r['time']} n={r['n']}: {r['answered']} (windows {r['windows']:.0%}), "
                  f"beam {r['beam_seconds'] * 1e3:.0f} ms, jacobian {r['jacobian_seconds'] * 1e3:.0f} ms "
                  f"(x{r['saving']:.2f}); max error beam {r['beam_error']:.2%} jacobian {r['jacobian_error']:.2%}, "
                  f"L2 {r['beam_l2_error']:.3%} / {r['jacobian_l2_error']:.3%} (reference bound {r['reference_bound']:.2%})")
    _write(rows, jacobian.figures(rows), Path(args.json or "bench/results/jacobian.json"))


def run_ship(args) -> None:
    from bench import ship

    rows = ship.wake_rows(_say) + ship.fd_rows(_say)
    if not args.quick:
        rows += ship.speed_rows(_say)
    for r in rows:
        if r["family"] == "ship wake":
            print(f"{r['method']:<16} Δt={r['dt']:<5} error {r['error']:.4f}  {r['seconds']:.2f} s")
        elif r["family"] == "ship wake refused":
            print(f"{r['method']:<16} Δt={r['dt']:<5} refused: {r['reason'][:90]}")
        elif r["family"] == "fd wake":
            print(f"FD wake angle {r['angle']:.2f}° ± {r['uncertainty']:.2f}° (Mach {r['mach_angle']:.2f}°, "
                  f"Kelvin {r['kelvin_angle']:.2f}°)")
        else:
            extra = f", +{100 * r['extra_fraction']:.1f} % per step" if "extra_fraction" in r else ""
            print(f"{r['method']}: {r['seconds'] * 1e3:.2f} ms{extra}")
    _write(rows, ship.figures(rows), Path(args.json or "bench/results/ship.json"))


def run_wake(args) -> None:
    from bench import wake

    rows = wake.angle_rows((0.3, 0.5, 1.0, 2.0, 4.0) if args.quick else None, _say)
    for r in rows:
        m = "no ridge" if r["measured"] is None else f"{r['measured']:6.2f}° ± {r['measured_uncertainty']:.2f}°"
        c = "  (cusp: not resolvable)" if r["cusp"] is None else f"  cusp {r['cusp']:.2f}° ± {r['cusp_uncertainty']:.2f}°"
        print(f"Fr={r['froude']:5.2f}  max amplitude: measured {m}, theory {r['theory']:6.2f}° ± "
              f"{r['theory_uncertainty']:.2f}°, Rabaud-Moisy {r['rabaud_moisy']:6.2f}°{c}")
    _write(rows, wake.figures(rows), Path(args.json or "bench/results/wake.json"))


def run_harness(args) -> None:
    from bench import harness

    timing = harness.timing_rows(_say)
    print(f"{'check':<16}{'record':<24}{'seconds':>9}  floor on a correct record")
    for r in timing:
        floor = (f"error {r['error']:.3g} (tolerance {r['tolerance']:.3g} {r['unit']})" if r["relation"] == "~=" else
                 f"{r['measured']:.3g} {r['relation']} {r['expected']:.3g} {r['unit']}")
        print(f"{r['check']:<16}{r['record']:<24}{r['seconds']:>9.3f}  {floor}")
    sens = harness.sensitivity_rows((64,) if args.quick else (64, 256), _say)
    for r in sens:
        print(f"{r['check']:<16}{r['frames']:>5} frames: smallest fault seen {r['smallest']} ({r['fault']})")
    cost = harness.cost_rows(((128, 256),) if args.quick else ((128, 256), (256, 512)), _say)
    print(f"{'check':<16}{'record':<14}{'read':>7}{'correct warm':>14}{'cold':>8}{'faulty warm':>13}{'cold':>8}"
          f"{'faulty/correct':>16}")
    for r in cost:
        print(f"{r['check']:<16}{r['size']:<14}{r['read_seconds']:>7.2f}{r['correct_warm']:>14.3f}"
              f"{r['correct_cold']:>8.3f}{r['faulty_warm']:>13.3f}{r['faulty_cold']:>8.3f}"
              f"{r['faulty_warm'] / max(r['correct_warm'], 1e-9):>16.2f}")
    _write(dict(timing=timing, sensitivity=sens, cost=cost), {}, Path(args.json or "bench/results/harness.json"))


def run_halffloat(args) -> None:
    from bench.render import half_float_rows

    rows = half_float_rows((512,) if args.quick else (512, 1024), progress=_say)
    for r in rows:
        print(f"N={r['n']:<5} {r['heights']:<26}{r['dtype']:<9} numpy {r['numpy_seconds'] * 1e3:7.2f} ms  "
              f"to_float16 {r['seconds'] * 1e3:7.2f} ms  (x{r['ratio']:.2f}, identical bits: {r['identical']})")
    _write(rows, {}, Path(args.json or "bench/results/halffloat.json"))


def run_render(args) -> None:
    from bench import render

    if args.quick:
        rows = render.frame_rows(200, 150, 3, _say) + render.agreement_rows(80, 60, progress=_say)
    else:
        rows = render.frame_rows(progress=_say) + render.texture_rows(progress=_say) + render.agreement_rows(progress=_say)
    for r in rows:
        if r["family"] == "frame":
            print(f"{r['width']}×{r['height']} {r['coverage']:>3} % (measured {100 * r['measured_coverage']:.1f} %) "
                  f"{r['mode']:<13} {r['seconds'] * 1e3:8.1f} ms {r['hz']:6.2f} Hz  ×{r['ratio_to_refraction']:.2f} "
                  f"({r['ratio_quartiles'][0]:.2f}–{r['ratio_quartiles'][1]:.2f}) of refraction "
                  f"(paper {r['paper_hz']} Hz, ×{r['paper_ratio']:.2f})")
        elif r["family"] == "horizon cost":
            print(f"{r['width']}×{r['height']} {r['scene']} to the horizon ({r['surroundings']}): "
                  f"{r['seconds'] * 1e3:.1f} ms against {r['baseline_seconds'] * 1e3:.1f} ms in the box alone, "
                  f"×{r['ratio']:.2f} ({r['ratio_quartiles'][0]:.2f}–{r['ratio_quartiles'][1]:.2f})")
        elif r["family"] == "textures":
            print(f"N={r['n']:<5} {r['work']:<34} {r['seconds'] * 1e3:8.2f} ms  ×{r['ratio_to_step']:.2f} of a step")
        else:
            extra = "" if r["off"] == "none" else (f"  off vs on {r['effect_psnr']:.1f} dB, frame time "
                                                   f"×{r['cost_ratio']:.2f} ({r['cost_quartiles'][0]:.2f}–"
                                                   f"{r['cost_quartiles'][1]:.2f})")
            conv = "" if r["psnr_vs_converged"] is None else f" (vs 4× steps {r['psnr_vs_converged']:.1f} dB)"
            print(f"{r['scene']:<6} off={r['off']:<11} GPU vs reference {r['psnr']:.1f} dB{conv}{extra}")
    _write(rows, render.figures(rows), Path(args.json or "bench/results/render.json"))


def run_filtering(args) -> None:
    from bench import filtering

    if args.quick:
        rows = filtering.filtering_rows(160, 120, 4, ("storm", "shore"), 3, _say)
    else:
        rows = filtering.filtering_rows(progress=_say)
    print(f"{'scene':<10}{'band (sides)':>14}{'texels/px':>10}{'method':>12}{'max':>9}{'RMS':>9}{'PSNR dB':>9}"
          f"{'cost':>7}")
    for r in rows:
        band = f"{r['band'][0]:g}–{r['band'][1]:g}"
        print(f"{r['scene']:<10}{band:>14}{r['footprint_texels']:>10.2f}{r['method']:>12}{r['max']:>9.4f}"
              f"{r['rms']:>9.4f}{r['psnr']:>9.1f}{r['cost_ratio']:>7.2f}")
    _write(rows, filtering.figures(rows), Path(args.json or "bench/results/filtering.json"))


def run_meshes(args) -> None:
    from bench import meshes
    from wavephys.core.files import atomic_path

    if args.quick:
        rows = meshes.mesh_rows(("storm", "shore"), n=64, width=160, height=120, repeats=1, progress=_say)
    else:
        rows = meshes.mesh_rows(progress=_say)
    print(f"{'scene':<9}{'technique':<10}{'setting':<12}{'vertices':>10}{'mesh ms':>9}{'march ms':>9}{'band r/H':>12}"
          f"{'PSNR dB':>9}{'p99':>9}{'bare':>6}{'height m':>10}")
    for r in rows:
        if r["water"]:
            print(f"{r['scene']:<9}{r['technique']:<10}{r['setting']:<12}{r['vertices']:>10}"
                  f"{r['mesh_seconds'] * 1e3:>9.0f}{r['march_seconds'] * 1e3:>9.0f}"
                  f"{meshes._band(r['band']):>12}{r['psnr']:>9.1f}{r['p99']:>9.2g}{r['bare']:>6}{r['height_max']:>10.3g}")
    out = Path(args.json or "bench/results/meshes.json")
    _write(rows, {}, out)  # the rows first: a chart that fails loses nothing
    if not args.quick:  # the docs table comes from the full run only
        doc = Path("docs/meshes.md")
        with atomic_path(doc) as tmp:
            tmp.write_text(meshes.markdown(rows, "python -m bench meshes"))
        print(f"wrote {doc}")
    _write(rows, meshes.figures(rows), out)


def run_surfaces(args) -> None:
    from bench import surfaces

    rows = surfaces.accuracy_rows(_say) + surfaces.cost_rows((128,) if args.quick else (256, 512), _say)
    if not args.quick:
        rows += surfaces.detail_rows(_say)
    acc = {r["method"]: r for r in rows if r["family"] == "surface physics"}
    for r in rows:
        if r["family"] == "surface physics":
            print(f"{r['method']:<22} dispersion error max {r['error']:.4f}  rms {r['rms_error']:.4f}  "
                  f"({r['shells']} shells; {r['label']})")
        elif r["family"] == "surface cost":
            print(f"{r['method']:<22} N={r['n']:<5} {r['seconds'] * 1e3:8.2f} ms/frame  x{r['ratio']:.2f} of the "
                  f"spectral step ({r['baseline_seconds'] * 1e3:.2f} ms)")
        elif r["family"] == "noise normals":
            print(f"noise normals {r['method']:<8} seed {r['seed']}: max error {100 * r['error']:.2f} % at ds = "
                  f"{r['step']} m, order {r['order']:.2f}")
        elif r["family"] == "gerstner crest":
            print(f"Gerstner vs Stokes kA={r['steepness']:.2f}: crest {100 * r['crest_error']:+.3f} %, trough "
                  f"{100 * r['trough_error']:+.3f} %")
        elif r["family"] == "gerstner crest parting":
            print(f"crests part by 1 % at kA = {r['steepness']:.3f}")
        elif r["family"] == "choppy fold":
            print(f"choppy fold U={r['wind_speed']:g} m/s seed {r['seed']}: lambda_f {r['fold_choppiness']:.2f}, "
                  f"sigma1 {r['sigma1']:.4f}, lambda_f*sigma1 {r['product']:.3f}, first-order {r['first_order']:.2f}")
        elif r["family"] == "choppy resampling" and r["refine"] in (1, 2):
            print(f"choppy resampling seed {r['seed']} lambda {r['fraction_of_fold']:.2f} of fold, refine {r['refine']}: "
                  f"max {100 * r['max_error']:.3f} %, rms {100 * r['rms_error']:.4f} % of the height range")
    del acc
    _write(rows, surfaces.figures(rows), Path(args.json or "bench/results/surfaces.json"))


def run_scale(args) -> None:
    from bench import scale

    rows = scale.huge_rows(progress=_say) if args.huge else scale.scale_rows(args.quick, _say)
    for r in rows:
        if r["family"] == "huge run":
            extra = (f"; eta equals one device's to {r['max_difference_subsample']:.2e} of its max"
                     if "max_difference_subsample" in r else "")
            print(f"N={r['n']} on {r['devices']} device(s): setup and first step {r['setup_seconds']:.1f} s, one step "
                  f"{r['step_seconds']:.2f} s, peak RSS {r['peak_rss_bytes'] / 2**30:.2f} GiB{extra}")
            continue
        if r["family"] == "sharded step memory":
            sent = r["sent"].get("all-to-all", 0)
            print(f"N={r['n']:<6} {r['devices']} device(s): {r['bytes_per_device'] / 2**20:10.1f} MiB per device "
                  f"({r['bytes_per_point']:.1f} B per grid point), sends {sent / 2**20:8.2f} MiB per step "
                  f"(slab formula {r['expected_sent'] / 2**20:.2f}; other collectives: "
                  f"{sorted(set(r['sent']) - {'all-to-all'}) or 'none'})")
        elif r["family"] == "big run":
            print(f"N={r['n']} allocated and stepped: {r['seconds']:.2f} s per step on {r['devices']} forced host devices, "
                  f"{r['baseline_seconds']:.2f} s on one (x{r['ratio']:.2f}); max |eta difference| "
                  f"{r['max_difference']:.2e} of max |eta|")
        elif r["family"] == "largest grid":
            print(f"largest N on {r['devices']} device(s) of {r['memory']}: {r['n']} (power of two {r['power_of_two']})")
        else:
            print(f"N={r['n']:<5} sharded over {r['devices']} forced host devices: {r['seconds'] * 1e3:.1f} ms against "
                  f"{r['baseline_seconds'] * 1e3:.1f} ms on one, ×{r['ratio']:.2f} ({r['ratio_quartiles'][0]:.2f}–"
                  f"{r['ratio_quartiles'][1]:.2f})")
    _write(rows, {}, Path(args.json or f"bench/results/scale{'_huge' if args.huge else ''}.json"))


def run_calibrate(args) -> None:
    from bench.planner import CAL_PATH, calibrate

    data = calibrate(_say, only=args.only)
    if args.only:
        print(f"updated {', '.join(args.only)} in {CAL_PATH}")
    else:
        print(f"kappa {data['kappa']:.3g}; step at n=128 {1e3 * data['step']['first'][6]:.3f} ms; wrote {CAL_PATH}")


def run_planner(args) -> None:
    from bench import planner

    rows = planner.proof_rows(12 if args.quick else 50, progress=_say)
    ok = [r for r in rows if "measured_error" in r]
    within = sum(r["measured_error"] <= r["tolerance"] for r in ok)
    ratios = [r["measured_error"] / r["predicted_error"] for r in ok if r["predicted_error"] > 0]
    savings = sorted(r["measured_saving"] for r in ok)
    print(f"{len(ok)} scenes planned ({len(rows) - len(ok)} infeasible); {within} within tolerance; "
          f"measured/predicted error worst {max(ratios):.3g}, median {sorted(ratios)[len(ratios) // 2]:.3g}; "
          f"measured saving median ×{savings[len(savings) // 2]:.2f} (range ×{savings[0]:.2f}–×{savings[-1]:.2f})")
    _write(rows, planner.figures(rows), Path(args.json or "bench/results/planner.json"))


def run_savings(args) -> None:
    from bench import planner
    from wavephys.planner import BUILTIN_SCENES, builtin_scene, generate_scenes

    scenes = [builtin_scene(n) for n in BUILTIN_SCENES]
    scenes += generate_scenes(7 if args.quick else 21, seed=2027, texels=(32, 48, 64, 96, 128))
    rows = planner.savings_rows(scenes, rounds=5 if args.quick else 7, progress=_say)
    ok = [r for r in rows if "measured_saving" in r]
    for q in sorted({r["quanta"] for r in ok}):
        s = sorted(r["measured_saving"] for r in ok if r["quanta"] == q)
        p = sorted(r["predicted_saving"] for r in ok if r["quanta"] == q)
        print(f"{q:g} quanta: {len(s)} plans; measured saving median ×{s[len(s) // 2]:.2f} (range ×{s[0]:.2f}–"
              f"×{s[-1]:.2f}); predicted median ×{p[len(p) // 2]:.2f}")
    slow = [f"{r['scene']} at {r['quanta']:g}" for r in ok if r["slower_every_round"]]
    print(f"slower than the full model in every round: {', '.join(slow) if slow else 'none'}")
    _write(rows, {"chart": planner.savings_figure(rows)}, Path(args.json or "bench/figures/savings.json"))


def main(argv=None) -> int:
    p = argparse.ArgumentParser(prog="python -m bench", description=__doc__.split("\n\n")[0])
    sub = p.add_subparsers(dest="which", required=True)
    for name, fn, help_ in (("propagation", run_propagation, "step vs bare FFT; error vs time"),
                            ("boundaries", run_boundaries, "measured failure boundaries"),
                            ("walls", run_walls, "walled step against the periodic step (ratios, memory)"),
                            ("shallow", run_shallow, "nonlinear shallow water and virtual pipes: dam-break error vs time, step cost"),
                            ("optics", run_optics, "Fresnel, absorption and caustics: error vs cost"),
                            ("jacobian", run_jacobian, "jacobian caustics: error up to and past the first fold, cost"),
                            ("ship", run_ship, "moving hulls: kernels vs stones, FD wake, speed"),
                            ("wake", run_wake, "wake angles against Froude number: measured, theory, published law"),
                            ("harness", run_harness, "every check of a record: time on 128^2 x 256, floor, smallest fault"),
                            ("halffloat", run_halffloat, "16-bit float encoding: numpy against to_float16, heights of every size"),
                            ("render", run_render, "renderer: frame times, texture cost, GPU vs reference"),
                            ("filtering", run_filtering, "distance filtering of normals against a supersampled truth, per distance band"),
                            ("meshes", run_meshes, "the water as a mesh (uniform, clipmap, projected grid) against the march, per distance band; writes docs/meshes.md"),
                            ("surfaces", run_surfaces, "noise, Gerstner, choppy: cost per frame vs physics error"),
                            ("scale", run_scale, "sharded step: overhead, memory per device, bytes per step"),
                            ("calibrate", run_calibrate, "measure the planner's cost model (writes its calibration)"),
                            ("planner", run_planner, "the planner's proof over generated scenes"),
                            ("savings", run_savings, "plan against full model in interleaved rounds: built-in and generated scenes at ½ and 1 quantum")):
        s = sub.add_parser(name, help=help_)
        s.add_argument("--json", metavar="PATH")
        s.add_argument("--quick", action="store_true", help="smaller sizes (for CI smoke runs)")
        if name == "scale":
            s.add_argument("--huge", action="store_true", help="a 16384² run on 1 and on 4 devices (20 GiB, minutes)")
        if name == "calibrate":
            from wavephys.planner.measure import TABLES

            s.add_argument("--only", nargs="+", choices=TABLES, metavar="TABLE",
                           help="measure these tables alone and update their entries: " + ", ".join(TABLES))
        if name == "propagation":
            s.add_argument("--device", choices=("cpu", "gpu", "tpu"),
                           help="time the step on this device against its own FFT floor (N = 1024–8192)")
        s.set_defaults(func=fn)
    args = p.parse_args(argv)
    args.func(args)
    return 0


if __name__ == "__main__":
    sys.exit(main())
