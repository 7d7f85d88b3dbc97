"""The package's surface: a clean namespace, docstrings help() shows under the right names, the
model's matrices and mode shapes (checked against scipy's own eigen-solution), and the pandas
DataFrames beside the numpy arrays. CTest runs this file in python_module."""

import math
import os
import pathlib
import pydoc
import tomllib

import numpy as np
import pytest
import scipy.linalg

import pounding

SOURCE = pathlib.Path(os.environ.get("POUNDING_SOURCE_DIR", pathlib.Path(__file__).resolve().parents[2]))
PAPER = SOURCE / "examples" / "paper" / "paper.toml"


@pytest.fixture(scope="module")
def scene():
    return pounding.load_scene(PAPER)


def test_namespace_is_the_documented_api():
    public = {name for name in dir(pounding) if not name.startswith("_")}
    # sweep, verify and bracket are submodules imported on first use (another test file of the
    # session may have)
    submodules = {"sweep", "verify", "bracket"}
    assert public - submodules == set(pounding.__all__) - submodules - {"__version__"}
    assert not {"np", "json"} & set(dir(pounding))


def test_help_shows_every_method_under_its_own_name_with_a_docstring():
    text = pydoc.render_doc(pounding.Scene, renderer=pydoc.plaintext)
    assert "_with_record" not in text and "_with_solver" not in text and "lambda" not in text
    assert "class Scene in module pounding" in text
    for name in ("with_gap", "with_restitution", "with_record", "with_method", "with_outputs", "gap_m", "name",
                 "record_file"):
        assert pydoc.getdoc(getattr(pounding.Scene, name)).strip(), name
    assert pounding.Scene.with_record.__name__ == "with_record"
    for name in set(pounding.__all__) - {"__version__"}:
        assert pydoc.getdoc(getattr(pounding, name)).strip(), name
    for cls in (pounding.RunResult, pounding.GapResult):
        for name, member in vars(cls).items():
            if not name.startswith("_") and callable(member):
                assert pydoc.getdoc(member).strip(), f"{cls.__name__}.{name}"


def test_matrices_and_shapes_are_the_modes(scene):
    """scipy's generalised eigen-solution of the exposed K and M gives the periods `pounding modes`
    prints (relative 1e-9); the shapes are M-orthonormal and K-diagonal (1e-9); C is the Rayleigh
    combination a0 M + a1 K of the printed coefficients (1e-12 of |C|)."""
    for building in pounding.modes(scene):
        M, K, C, shapes = building["M"], building["K"], building["C"], building["shapes"]
        dof = building["dof"]
        assert M.shape == K.shape == C.shape == shapes.shape == (dof, dof) and len(building["dofs"]) == dof
        assert building["dofs"][:3] == ["f1_u_m", "f1_v_m", "f1_phi_rad"]
        assert np.array_equal(M, np.diag(np.diag(M))) and np.allclose(K, K.T, rtol=0, atol=1e-9 * abs(K).max())
        omega_squared = scipy.linalg.eigh(K, M, eigvals_only=True)
        periods = np.sort(2 * np.pi / np.sqrt(omega_squared))[::-1]
        np.testing.assert_allclose(periods, building["periods_s"], rtol=1e-9)
        np.testing.assert_allclose(shapes.T @ M @ shapes, np.eye(dof), atol=1e-9)
        np.testing.assert_allclose(shapes.T @ K @ shapes, np.diag((2 * np.pi / building["periods_s"]) ** 2),
                                   rtol=1e-9, atol=1e-9 * abs(K).max())
        rayleigh = building["rayleigh"]
        np.testing.assert_allclose(C, rayleigh["a0_per_s"] * M + rayleigh["a1_s"] * K, rtol=0,
                                   atol=1e-12 * abs(C).max())
        # Storey 1 of a 7-storey building: floor 1's u couples to floor 2's u, not to floor 3's.
        assert K[0, 3] != 0 and K[0, 6] == 0


def test_frames_hold_the_arrays(scene):
    pytest.importorskip("pandas")
    result = pounding.run(scene)
    history = result.history_frame()
    assert history.index.name == "t_s" and np.array_equal(history.index.to_numpy(), result.history["t_s"])
    assert list(history.columns) == [c for c in result.history if c != "t_s"]
    assert np.array_equal(history["B2_f7_u_m"].to_numpy(), result.history["B2_f7_u_m"])
    impacts = result.impacts_frame()
    assert list(impacts.columns) == list(result.impacts_array.dtype.names) and len(impacts) == len(result.impacts)
    assert np.array_equal(impacts["impulse_kNs"].to_numpy(), result.impacts_array["impulse_kNs"])
    forces = result.contact_forces_frame()
    assert len(forces) == len(result.contact_forces["t_s"])
    modes = pounding.modes_frame(scene)
    periods = np.concatenate([b["periods_s"] for b in pounding.modes(scene)])
    assert np.array_equal(modes["period_s"].to_numpy(), periods) and modes["mode"].iloc[0] == 1
    gap = pounding.needed_gap(scene)
    frame = gap.history_frame()
    assert np.array_equal(frame.to_numpy(), gap.history_touch_gap_m) and frame.index.name == "t_s"


def test_output_schema_names_every_output_of_a_run_and_nothing_else():
    """pounding.output_schema() (`pounding outputs --json`) is the writers' own list: a run's
    history columns, impacts.csv header, per-floor peak keys and energy keys are exactly its
    fields, in its order. A column written but not declared (or the reverse) fails."""
    import re
    schema = pounding.output_schema()
    result = pounding.run(pounding.load_scene(PAPER, gap=0.05), method="cvode-bdf")
    patterns = [re.escape(f["column"]).replace(r"\{b\}", "[12]").replace(r"\{f\}", "[0-9]+")
                .replace(r"\{j\}", "[0-9]+").replace(r"\{n\}", "[0-9]+")
                if "only_when" not in f else "(?!)" for f in schema["history"]]
    columns = list(result.history)
    assert columns[0] == "t_s" and schema["history"][0]["column"] == "t_s"
    slab = re.compile("^B[12]_f[0-9]+_")
    order = []
    for column in columns[1:]:
        matched = [k for k, p in enumerate(patterns) if re.fullmatch(p, column)]
        assert len(matched) == 1, column
        order.append(matched[0])
        assert slab.match(column)
    always = [k for k, f in enumerate(schema["history"]) if "only_when" not in f]
    assert set(order) == set(always[1:])  # every declared quantity is written
    # The member forces (output.member_forces) are the last columns, each declared with its condition.
    forces = [re.escape(f["column"]).replace(r"\{b\}", "[12]").replace(r"\{j\}", "[0-9]+")
              .replace(r"\{n\}", "[0-9]+") for f in schema["history"] if f.get("only_when") == "output.member_forces"]
    with_forces = pounding.run(pounding.load_scene(PAPER, gap=0.05).with_outputs(member_forces=True),
                               method="cvode-bdf")
    extra = list(with_forces.history)[len(columns):]
    assert list(with_forces.history)[:len(columns)] == columns and extra
    assert all(sum(bool(re.fullmatch(p, c)) for p in forces) == 1 for c in extra)
    assert {k for c in extra for k, p in enumerate(forces) if re.fullmatch(p, c)} == set(range(len(forces)))
    assert "member_forces" in with_forces.summary and "member_forces" not in result.summary
    summary = result.summary
    assert list(summary["impacts"][0]) == [f["key"] for f in schema["impacts"] if "only_when" not in f]
    header = [c for f in schema["impacts"] if "only_when" not in f for c in f["csv_columns"]]
    assert list(result.impacts_array.dtype.names) == header
    floor = summary["peaks"][0]["floors"][0]
    assert list(floor)[1:] == [f["key"] for f in schema["peaks"]]
    assert list(summary["energy"]) == [f["key"] for f in schema["energy"] if "only_when" not in f]
    assert list(result.contact_forces) == [f["column"] for f in schema["contact_forces"]]
    assert len(result.contact_forces["t_s"]) > 0  # the holds' forces
    for section in schema.values():
        for field in section:
            assert field["description"].strip(), field


def test_contact_vertex_columns_are_the_exact_rigid_motion_of_the_slab():
    """history.csv's vtx{n}_dx_m and vtx{n}_dy_m against the slab's own u, v, phi: a point at
    rest r, a distance a = r - c from the centre of mass c, moves by (u, v) + (R(phi) - I) a.
    The centres are the paper scene's (examples/paper/paper.toml, at its gap 0.20 m; building 2
    moves by the change of gap); tolerance 1e-12 m."""
    import re
    result = pounding.run(pounding.load_scene(PAPER, gap=0.05), method="cvode-bdf")
    centres = {1: np.array([-10.8, 11.0]), 2: np.array([12.8 + (0.05 - 0.20), 19.25])}
    checked = 0
    for b, peaks in enumerate(result.summary["peaks"], start=1):
        rest = dict(zip(peaks["contact_vertices"], peaks["contact_vertices_rest"]))
        for column in result.history:
            found = re.fullmatch(rf"B{b}_f([0-9]+)_vtx([0-9]+)_dy_m", column)
            if not found:
                continue
            prefix = f"B{b}_f{found.group(1)}_"
            u, v, phi = (result.history[prefix + q] for q in ("u_m", "v_m", "phi_rad"))
            ax, ay = np.array(rest[int(found.group(2))]) - centres[b]
            dx = u + (np.cos(phi) - 1.0) * ax - np.sin(phi) * ay
            dy = v + np.sin(phi) * ax + (np.cos(phi) - 1.0) * ay
            assert np.max(np.abs(result.history[prefix + f"vtx{found.group(2)}_dx_m"] - dx)) < 1e-12
            assert np.max(np.abs(result.history[column] - dy)) < 1e-12
            checked += 1
    assert checked >= 2 * 7  # every contact vertex of every level


def finely_sampled_scene(tmp_path):
    """The paper's buildings 1 m apart (no contact) under the first 0.75 s of its El Centro
    digitisation re-spaced 0.0005 s apart: a record sampled a hundred times finer than hht's
    published 0.05 s step."""
    text = PAPER.read_text().replace("dt_s = 0.05", "dt_s = 0.0005").replace("duration_s = 12.2", "duration_s = 0.75")
    text = text.replace('"../records/', f'"{(SOURCE / "examples" / "records").as_posix()}/')
    path = tmp_path / "fine.toml"
    path.write_text(text)
    return pounding.load_scene(str(path), gap=1.0)


def roof_peak_m(result):
    return abs(result.peaks[0]["floors"][-1]["u_m"]["value"])


def test_hht_steps_at_the_record_spacing_unless_told_and_warns_when_told_to_skip_samples(tmp_path):
    scene = finely_sampled_scene(tmp_path)
    exact = pounding.run(scene, method="exact")
    default = pounding.run(scene, method="hht")
    # Not given, the step is the record's 0.0005 s: the roof peak agrees with the exact path to
    # 0.5 % (HHT's period error at 1/100 of a sample spacing is far smaller) and no warning.
    assert default.summary["settings"]["used"]["dt_s"] == 0.0005
    assert default.warnings == []
    assert roof_peak_m(default) == pytest.approx(roof_peak_m(exact), rel=5e-3)
    assert abs(default.energy["relative_residual"]) < 1e-2
    # Told 0.05 s, the scheme sees 1 sample in 100: the run says so, and its energy audit is that
    # of the forcing it applied (a_g straight between step ends), so it balances to the scheme's
    # own discretisation error instead of mixing two records (it was −19 kJ input for +0.1 kJ).
    coarse = pounding.run(scene, method="hht", dt_s=0.05)
    assert [w["code"] for w in coarse.warnings] == ["record_undersampled"]
    assert "0.0005" in coarse.warnings[0]["message"]
    assert abs(coarse.energy["relative_residual"]) < 0.1
    assert abs(roof_peak_m(coarse) / roof_peak_m(exact) - 1.0) > 0.5  # what the warning is about


def test_yielding_outputs_are_the_summary_per_column():
    """yielding_array holds one row per yielding column spring whose energies add up to the audit's
    hysteretic term and whose largest ductilities are the summary's per storey; an elastic scene
    has neither."""
    run = pounding.run(pounding.load_scene(SOURCE / "examples" / "paper" / "paper-yielding.toml"))
    springs = run.yielding_array
    header = run._run.yielding_csv().splitlines()[0].split(",")
    # Every declared column but those written only when some column has a shear capacity.
    always = [c["column"] for c in pounding.output_schema()["yielding"] if "only_when" not in c]
    assert header == always == list(springs.dtype.names)
    assert len(springs) == 2 * (25 * 7 + 30 * 10)  # columns × storeys × (x, y)
    assert springs["hysteretic_kJ"].sum() == pytest.approx(run.energy["hysteretic_kJ"], rel=1e-12)
    assert run.yielding["hysteretic_kJ"] == run.energy["hysteretic_kJ"]
    assert np.all(np.isnan(springs["first_yield_t_s"]) == (springs["yield_count"] == 0))
    for building in run.yielding["buildings"]:
        for storey in building["storeys"]:
            rows = springs[(springs["building"] == building["building"]) & (springs["storey"] == storey["storey"])]
            for axis in ("x", "y"):
                assert rows["peak_ductility"][rows["direction"] == axis].max() == storey[f"peak_ductility_{axis}"]
            assert storey["springs_yielded"] == int((rows["yield_count"] > 0).sum())
    elastic = pounding.run(pounding.load_scene(PAPER))
    assert elastic.yielding is None and len(elastic.yielding_array) == 0


def test_slab_to_column_impacts_carry_the_column_and_its_demands():
    """A scene whose slabs strike columns adds the column's fields to the impacts (array and
    summary, in the schema's order) and counts them apart from the levels; the demands are those
    of the fixed-fixed column under the peak force (the closed forms written here)."""
    run = pounding.run(pounding.load_scene(SOURCE / "examples" / "levels" / "ground-storey-columns.toml"))
    impacts = run.impacts_array
    schema = pounding.output_schema()["impacts"]
    columns = [c for f in schema if f.get("only_when", "slabs").startswith("slabs") for c in f["csv_columns"]]
    assert list(impacts.dtype.names) == columns  # the slab-to-column fields, not the row's
    assert len(impacts) == run.summary["impacts_slab_to_column"] > 0 and run.summary["impacts_by_level"] == {}
    for impact in impacts:
        assert impact["level"] == 0 and impact["vertex"] == 0 and impact["column"] > 0
        candidate = next(c for c in run.summary["candidates"]
                         if c["column"] == impact["column"] and c["floors"] == [impact["floors_b1"], impact["floors_b2"]])
        length, xi, force = candidate["storey_height_m"], impact["height_ratio"], impact["peak_force_kN"]
        a, b = xi * length, (1 - xi) * length
        shear = max(force * b * b * (3 * a + b), force * a * a * (a + 3 * b)) / length ** 3
        moment = max(force * a * b * b, force * a * a * b, 2 * force * a * a * b * b / length) / length ** 2
        assert impact["column_shear_kN"] == pytest.approx(shear, rel=1e-12)
        assert impact["column_moment_kNm"] == pytest.approx(moment, rel=1e-12)


def test_needed_gap_covers_the_slabs_facing_columns():
    """Without a common level every entry of the needed gap is a slab facing columns; the needed
    gap is the largest of theirs, named by its floors (level 0)."""
    gap = pounding.needed_gap(pounding.load_scene(SOURCE / "examples" / "levels" / "ground-storey-columns.toml"))
    assert len(gap.levels) == 13 and all(level["level"] == 0 and level["slab_to_column"] for level in gap.levels)
    assert gap.needed_gap_m == max(level["needed_gap_m"] for level in gap.levels)
    assert gap.level == 0 and gap.floor == [7, 7] and "facing columns" in repr(gap)
    assert gap.history_touch_gap_m.shape[1] == 13


def test_a_pair_of_components_from_python_runs_as_the_scene_would():
    """record2 / record2_column make a pair as --record2 does; a new record alone drops the pair."""
    pair_scene = pounding.load_scene(SOURCE / "examples" / "beyond-paper" / "two-components.toml")
    assert pair_scene.record2_file is not None
    kobe = SOURCE / "examples" / "records" / "kobe1995_jma_ns_ew_0.005s_cms2.txt"
    single = pair_scene.with_record(kobe, dt_s=0.005, accel_column=1)
    assert single.record2_file is None
    rebuilt = pair_scene.with_record(kobe, dt_s=0.005, accel_column=1, record2=kobe, record2_column=2)
    assert pathlib.Path(rebuilt.record2_file) == kobe
    # The same pair as the scene's [excitation.second], so the same contact-free motion.
    a = pounding.run(pair_scene.with_gap(1.0).with_outputs(history=False))
    b = pounding.run(rebuilt.with_gap(1.0).with_outputs(history=False))
    assert a.peaks == b.peaks
    with pytest.raises(pounding.InputError, match="excitation.second.accel_column"):
        pounding.load_scene(PAPER).with_record(kobe, format="single", dt_s=0.005, accel_column=1, record2_column=2)


def test_spectral_scaling_from_python():
    """scale_to_sa= is --scale-to-sa: its factor reaches the run's summary; a bad form names the key."""
    scene = pounding.load_scene(PAPER)
    record = SOURCE / "examples" / "records" / "elcentro1940_ns_0.02s.AT2"
    scaled = scene.with_record(record, dt_s=0.05, scale_to_sa="0.4g@B1")
    result = pounding.run(scaled.with_outputs(history=False))
    assert result.summary["spectral_scaling"]["asked"] == "0.4g@B1"
    assert result.summary["spectral_scaling"]["period_s"] == pytest.approx(0.765, abs=5e-4)
    with pytest.raises(pounding.InputError, match="excitation.scale_to_sa"):
        scene.with_record(record, scale_to_sa="0.4@B1")


def test_needed_gap_over_every_angle_from_python():
    """all_angles=True is `gap --all-angles`: the worst angle is never below the record's own."""
    gap = pounding.needed_gap(pounding.load_scene(PAPER), all_angles=True)
    assert gap.all_angles["method"] == "superposition"
    assert gap.all_angles["needed_gap_m"] >= gap.needed_gap_m
    assert gap.angles_array.shape == (360, 2)
    assert gap.angles_array[:, 1].max() == pytest.approx(gap.all_angles["envelope_largest"]["needed_gap_m"])


def test_spectra_and_ground_motion_from_python():
    """response_spectrum against a closed form: an undamped oscillator from rest under a constant
    ground acceleration a0 (a step at t = 0) peaks at |x| = 2 a0 / w^2, so PSA = 2 a0 at every
    period whose half period fits in the record; a pair's RotD100 of (a, 0) is a's own PSA; the
    scene's ground motion is the pair on one time base."""
    a0, t = 1.5, np.linspace(0.0, 10.0, 1001)
    spectrum = pounding.response_spectrum(t, np.full_like(t, a0), [0.2, 1.0, 3.0], damping_ratio=0.0)
    assert spectrum.psa_mps2 == pytest.approx(2 * a0, rel=1e-9)
    rotd = pounding.rotd_spectrum(t, np.full_like(t, a0), np.zeros_like(t), [0.2, 1.0], damping_ratio=0.0)
    assert rotd.rotd100_psa_mps2 == pytest.approx(2 * a0, rel=1e-9)
    motion = pounding.ground_motion(pounding.load_scene(SOURCE / "examples" / "beyond-paper" / "two-components.toml"))
    assert motion["h2_mps2"] is not None and len(motion["h2_mps2"]) == len(motion["time_s"]) == 4001
    assert max(np.abs(motion["h1_mps2"]).max(), np.abs(motion["h2_mps2"]).max()) == pytest.approx(0.4 * 9.81)
    with pytest.raises(pounding.InputError):
        pounding.response_spectrum(t, t, [0.0])


def test_with_record_names_the_key_of_an_argument_of_the_wrong_type():
    # The binding would raise a TypeError listing its signature; a sweep's record table then
    # printed that dump instead of naming records[i].pga_g.
    scene = pounding.load_scene(PAPER)
    record = SOURCE / "examples" / "records" / "elcentro1940_ns_0.02s.AT2"
    for keyword, value, key, kind in (("scale_to_pga_g", "x", "excitation.scale_to_pga_g", "number"),
                                      ("dt_s", True, "excitation.dt_s", "number"),
                                      ("accel_column", 2.5, "excitation.accel_column", "whole number"),
                                      ("record2", 3, "excitation.second.file", "path"),
                                      ("units", 9.81, "excitation.units", "text")):
        with pytest.raises(pounding.InputError) as caught:
            scene.with_record(record, **{keyword: value})
        assert caught.value.key == key and caught.value.reason == f"expected a {kind}", str(caught.value)
    assert scene.with_record(record, scale_to_pga_g=1, dt_s=0.05).name == "paper"  # an int is a number
    # numpy's numbers are numbers (np.arange's angles, float32 scales), as the binding takes them
    assert scene.with_record(record, direction_deg=np.int64(30), scale_to_pga_g=np.float32(0.25),
                             accel_column=np.int64(1)).name == "paper"


def test_a_scene_built_from_a_dict_runs_as_its_file_does():
    # tomllib's dict of the paper scene, built in code, runs bit for bit as load_scene's (the same
    # reader checks both); only the provenance differs: no scene file.
    document = tomllib.loads(PAPER.read_text())
    from_dict = pounding.run(pounding.scene_from_dict(document, folder=PAPER.parent))
    from_file = pounding.run(pounding.load_scene(PAPER))
    for key in ("impacts", "peaks", "energy", "sustained_contacts"):
        assert from_dict.summary[key] == from_file.summary[key], key
    assert from_dict.summary["provenance"]["scene_file"] is None
    assert from_dict.summary["provenance"]["record_sha256"] == from_file.summary["provenance"]["record_sha256"]
    document["building"][0]["mass_t"] = np.float64(-1.0)
    with pytest.raises(pounding.InputError) as caught:
        pounding.scene_from_dict(document, folder=PAPER.parent)
    assert caught.value.key == "building[1].mass_t" and "positive" in caught.value.reason
    # Text beyond U+FFFF and 0-d arrays are written as TOML reads them back.
    assert tomllib.loads(pounding.scene_toml({"name": "tower \U0001F600", "x": np.array(2.5)})) == \
        {"name": "tower \U0001F600", "x": 2.5}
    document["building"][0]["mass_t"] = object()
    with pytest.raises(pounding.InputError) as caught:
        pounding.scene_from_dict(document)
    assert caught.value.key == "building[1].mass_t", str(caught.value)


def test_a_one_storey_building_written_in_code_has_the_closed_form_period():
    # Four square columns b = 0.4 m, h = 3.5 m, E = 3e7 kPa, fixed-fixed (frame factor 1):
    # k = 4 · 12 E (b⁴/12) / h³ in x and in y, m = 400 t, so T = 2π √(m / k) (the CM at the centre
    # of stiffness: no coupling with torsion), within 1e-12 relative.
    def building(name, x0):
        corners = [[x0, 0.0], [x0 + 10.0, 0.0], [x0 + 10.0, 10.0], [x0, 10.0]]
        return {"name": name, "storeys": 1, "storey_height_m": 3.5, "slab": corners,
                "centre_of_mass": [x0 + 5.0, 5.0], "mass_t": 400.0, "polar_moment_tm2": "uniform", "E_kPa": 3e7,
                "frame_factor": 1.0, "columns": np.array([[x, y, 0.4, 0.4] for x, y in corners]),
                "damping": {"ratio": 0.05, "modes": [1, 3]}}
    record = SOURCE / "examples" / "records" / "elcentro1940_ns_0.02s.AT2"
    scene = pounding.scene_from_dict({"name": "in code", "building": [building("A", 0.0), building("B", 10.3)],
                                      "excitation": {"file": record, "format": "peer-at2", "units": "g"},
                                      "contact": {"gap_m": 0.3, "restitution": 0.5}})
    stiffness_kN_per_m = 4 * 12 * 3e7 * 0.4**4 / 12 / 3.5**3
    period_s = 2 * math.pi * math.sqrt(400.0 / stiffness_kN_per_m)
    periods = pounding.modes(scene)[0]["periods_s"]
    assert sorted(periods)[-1] == pytest.approx(period_s, rel=1e-12)
    assert scene.name == "in code" and scene.gap_m == pytest.approx(0.3, abs=1e-12)
    assert pounding.run(scene).status == "completed"
