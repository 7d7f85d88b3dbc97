"""What a worker runs: plain parameters in, a plain dict out; never raises for a run's failure.
Dask sends workers references to these functions by module name (pounding.sweep.tasks.run_task)."""

import math
import time

import pounding
from pounding import InputError
from pounding import _input_error as _error  # InputError with the library's message
from pounding.sweep.table import ALL_ANGLES, PEAK_QUANTITIES, RESULTS, pair_impact_column, pair_needed_gap_column


def _scene(task):
    scene = pounding.load_scene(task["scene_file"], gap=task.get("gap_m"), restitution=task.get("restitution"),
                                contact_law=task.get("contact_law"),
                                contact_stiffness=task.get("contact_stiffness"))
    if task["record"] is not None:
        scene = scene.with_record(**task["record"])
    if task.get("direction_deg") is not None:
        scene = scene.with_direction(task["direction_deg"])
    return scene


def _failure(error):
    return str(error) if isinstance(error, InputError) else f"{type(error).__name__}: {error}"


def needed_gap_task(task):
    """The needed gap of the task's scene (its own gap and tolerances) under its record; of a row,
    each neighbouring pair's (`pounding gap` on a row), the largest in needed_gap_m."""
    try:
        scene = _scene({"scene_file": task["scene_file"], "record": task["record"],
                        "direction_deg": task.get("direction_deg")})
        if len(scene.building_names) > 2:
            return _row_needed_gaps(scene, task)
        gap = pounding.needed_gap(scene, max_wall_time_s=task.get("max_wall_time_s"),
                                  all_angles=task.get("all_angles", False))
    except Exception as error:  # noqa: BLE001  (a record that cannot be read: the rows say so)
        failed = {"needed_gap_m": None, "needed_gap_level": None, "needed_gap_t_s": None,
                  "needed_gap_status": "failed: " + _failure(error)}
        return {**failed, **({key: None for key in ALL_ANGLES} if task.get("all_angles") else {})}
    finite = gap.needed_gap_m is not None and math.isfinite(gap.needed_gap_m)
    row = {"needed_gap_m": gap.needed_gap_m if finite else None, "needed_gap_level": gap.level or None,
           "needed_gap_t_s": gap.t_s if finite else None, "needed_gap_status": gap.status}
    if gap.all_angles:
        row.update({"all_angles_needed_gap_m": gap.all_angles["needed_gap_m"],
                    "all_angles_angle_deg": gap.all_angles["angle_deg"]})
    return row


def _row_needed_gaps(scene, task):
    """A row's needed gaps, pair by pair (each pair's own contact-free run: the buildings move
    independently without contact): a column each, and in needed_gap_m and _t_s the pair that
    needs the most; the status the first pair's that did not complete, or "completed"."""
    if task.get("all_angles"):
        raise _error(task["scene_file"], "needed_gap", '"all_angles"',
                     "takes scenes of two buildings; this one is a row (run it on one pair's scene)")
    row, worst, status = {}, None, "completed"
    for pair, _, two in scene.pair_scenes():
        gap = pounding.needed_gap(two, max_wall_time_s=task.get("max_wall_time_s"))
        finite = gap.needed_gap_m is not None and math.isfinite(gap.needed_gap_m)
        row[pair_needed_gap_column(pair)] = gap.needed_gap_m if finite else None
        if gap.status != "completed" and status == "completed":
            status = f"{pair}: {gap.status}"
        if finite and (worst is None or gap.needed_gap_m > worst.needed_gap_m):
            worst = gap
    # The pair's level numbers are its own scene's, not the row's: left empty.
    row.update({"needed_gap_m": worst.needed_gap_m if worst else None, "needed_gap_level": None,
                "needed_gap_t_s": worst.t_s if worst else None, "needed_gap_status": status})
    return row


def run_task(task, needed_gap=None):
    """One run of the sweep: its result columns (RESULTS, TIMINGS and, given, the needed gap's)."""
    start = time.perf_counter()
    row = dict.fromkeys(RESULTS)
    try:
        # A row keeps impact statistics and displacement peaks only (_summarise): the run computes
        # no history and no other peaks, but the drifts a contact-free reference compares.
        scene = _scene(task)
        scene = scene.with_outputs(history=False,
                                   peaks=["displacements", *(["drifts"] if scene.contact_free_reference else [])])
        result = pounding.run(scene, method=task["method"], max_wall_time_s=task.get("max_wall_time_s"),
                              **task["settings"])
        row.update(_summarise(result))
    except Exception as error:  # noqa: BLE001  (a failed run is a row with its message, never a lost row)
        row.update(status="failed", message=_failure(error))
    if needed_gap is not None:
        row.update(needed_gap)
    row["wall_time_s"] = time.perf_counter() - start
    return row


def _summarise(result):
    impacts = result.impacts
    row = {"status": result.status, "message": result.status_detail or "",
           "impact_count": len(impacts), "touch_count": len(result.touches),
           "sustained_contact_count": len(result.sustained_contacts),
           "first_impact_s": min((i["t_s"] for i in impacts), default=None),
           "max_impulse_kNs": max((abs(i["impulse_kNs"]) for i in impacts), default=0.0),
           "max_approach_speed_mps": max((abs(i["approach_velocity_mps"]) for i in impacts), default=0.0),
           "impact_loss_kJ": result.energy["impact_loss_kJ"],
           "steps": result.statistics["steps"], "solver_time_s": result.statistics["wall_time_s"]}
    for number, building in enumerate(result.peaks, start=1):
        for quantity in PEAK_QUANTITIES:
            row[f"b{number}_peak_{quantity}"] = max(abs(f[quantity]["value"]) for f in building["floors"])
    for pair, count in result.summary.get("impacts_by_pair", {}).items():
        row[pair_impact_column(pair)] = count
    if result.yielding is not None:
        for building in result.yielding["buildings"]:
            row[f"b{building['building']}_max_ductility"] = max(
                max(s["peak_ductility_x"], s["peak_ductility_y"]) for s in building["storeys"])
        row["hysteretic_kJ"] = result.yielding["hysteretic_kJ"]
        row["yield_events"] = result.yielding["yield_events"]
    if "pounding_demand" in result.summary:
        for prefix, building in zip(("b1", "b2"), result.summary["pounding_demand"]["buildings"][:2]):
            for suffix, side in (("", "with"), ("_no_contact", "without")):
                row[f"{prefix}_max_drift_ratio{suffix}"] = max(
                    max(s["drift_x"][side], s["drift_y"][side]) for s in building["storeys"])
    if "impacts_slab_to_column" in result.summary:
        on_columns = [i for i in impacts if i["level"] == 0]
        row["slab_to_column_impact_count"] = len(on_columns)
        for name in ("column_shear", "column_total_shear"):
            row[f"max_{name}_kN"] = max((i[f"{name}_kN"] for i in on_columns), default=0.0)
            ratios = [i[f"{name}_ratio"] for i in on_columns if i[f"{name}_ratio"] is not None]
            row[f"max_{name}_ratio"] = max(ratios) if ratios else None
    return row
