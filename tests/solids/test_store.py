"""The content key of a spec is the constructor's view of it: moving a field
into a keyword-only base class (as the drilled plates and the resolved design
tables do) keeps every key, so a refactor re-uses the cache and the part
hashes printed on drawings."""

from dataclasses import dataclass, field

from tactcad.design.array_plan import ClampPlateGeometry, Hole, SpacerGeometry
from tactcad.store import stable_repr


def _flat():
    @dataclass(frozen=True)
    class Plate:
        length_mm: float
        thickness_mm: float
        holes: tuple

    return Plate


def _based():
    @dataclass(frozen=True)
    class Base:
        holes: tuple = field(kw_only=True)

    @dataclass(frozen=True)
    class Plate(Base):
        length_mm: float
        thickness_mm: float

    return Plate


def test_keyword_only_base_field_keeps_the_key():
    holes = (Hole(1.0, 2.0, 3.4),)
    flat, based = _flat()(5.0, 2.0, holes), _based()(5.0, 2.0, holes=holes)
    assert stable_repr(flat) == stable_repr(based)
    assert stable_repr(_based()(5.0, 2.5, holes=holes)) != stable_repr(based)


def test_plates_key_in_constructor_order():
    spacer = SpacerGeometry(7.0, 8.0, 2.0, holes=())
    assert stable_repr(spacer).startswith("SpacerGeometry(length_mm=7.0, height_mm=8.0, "
                                          "thickness_mm=2.0, holes=")
    clamp = ClampPlateGeometry(10.0, 6.0, 8.0, 3.0, 2.0, 1.0, holes=())
    assert stable_repr(clamp).endswith("window_corner_radius_mm=1.0, holes=[])")


def test_code_digest_follows_every_source_and_data_file_but_bytecode(tmp_path):
    """The review page's script is a data file: a change of it must change every key
    (else a store hands back the page with the old script)."""
    from tactcad.store import code_digest as cached

    code_digest = cached.__wrapped__  # once per process in tactcad; here after every change
    (tmp_path / "data").mkdir()
    (tmp_path / "mod.py").write_text("x = 1\n")
    (tmp_path / "data" / "review_page.js").write_text("let a = 1;\n")
    (tmp_path / "data" / "review_page.html").write_text("<html></html>\n")
    (tmp_path / "__pycache__").mkdir()
    (tmp_path / "__pycache__" / "mod.cpython-311.pyc").write_bytes(b"1")
    before = code_digest(tmp_path)
    (tmp_path / "__pycache__" / "mod.cpython-311.pyc").write_bytes(b"2")
    assert code_digest(tmp_path) == before
    for name in ("data/review_page.js", "data/review_page.html", "mod.py"):
        (tmp_path / name).write_text((tmp_path / name).read_text() + " ")
        assert code_digest(tmp_path) != before
        before = code_digest(tmp_path)


def test_a_part_mesh_is_kept_by_its_spec_and_read_back_without_a_build(tmp_path, plan):
    import numpy as np

    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.solids.cache import PartCache
    from tactcad.store import Store, counting_results, keeping_results

    spec = array_parts(plan)["spacer"]
    with keeping_results(Store(tmp_path)), counting_results() as first:
        made = PartCache(plan).mesh(spec)
    with keeping_results(Store(tmp_path)), counting_results() as again:
        cache = PartCache(plan)
        read = cache.mesh(spec)
    from tactcad.solids.cache import SOLID_KIND

    # the solid is kept too when it is built for the mesh
    assert first.computed == {"part mesh": 1, SOLID_KIND: 1} and again.reused == {"part mesh": 1}
    assert cache.builds == 0  # a kept mesh needs no solid
    assert len(made[1]) > 0
    np.testing.assert_array_equal(read[0], made[0])
    np.testing.assert_array_equal(read[1], made[1])


def test_a_part_solid_is_kept_by_its_spec_and_read_back_without_a_build(tmp_path, plan):
    """A run where one part changed reads the others' solids back from the store: no
    build, and the STEP file written from the solid read back is the one a build writes
    (every run works on the solid as its BREP reads back)."""
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.kernel.step_writer import StepPart, write_step
    from tactcad.solids.build import BUILD_COUNTS
    from tactcad.solids.cache import SOLID_KIND, PartCache
    from tactcad.store import Store, counting_results, keeping_results

    spec = array_parts(plan)["clamp_plate"]
    with keeping_results(Store(tmp_path / "store")), counting_results() as first:
        built = PartCache(plan).solid(spec)
    before = BUILD_COUNTS[spec.name]
    with keeping_results(Store(tmp_path / "store")), counting_results() as again:
        cache = PartCache(plan)
        read = cache.solid(spec)
    assert first.computed == {SOLID_KIND: 1} and again.reused == {SOLID_KIND: 1}
    assert cache.builds == 0 and BUILD_COUNTS[spec.name] == before
    assert read.volume == built.volume
    (tmp_path / "built").mkdir()
    (tmp_path / "read").mkdir()
    one, two = tmp_path / "built" / "part.step", tmp_path / "read" / "part.step"
    write_step(one, [StepPart(spec.name, built, (0.5, 0.5, 0.5))])
    write_step(two, [StepPart(spec.name, read, (0.5, 0.5, 0.5))])
    assert one.read_bytes() == two.read_bytes()


def test_a_solid_whose_brep_does_not_read_back_is_built_in_every_run(tmp_path, plan,
                                                                      monkeypatch):
    from tactcad.catalogue.array_catalogue import array_parts
    from tactcad.solids import cache as solids_cache
    from tactcad.store import Store, keeping_results

    monkeypatch.setattr(solids_cache, "read_back", lambda solid: (None, solid))
    spec = array_parts(plan)["spacer"]
    for _ in range(2):
        with keeping_results(Store(tmp_path / "store")):
            cache = solids_cache.PartCache(plan)
            assert cache.solid(spec).volume > 0
        assert cache.builds == 1


def test_a_damaged_entry_is_a_miss_and_the_next_keep_replaces_it(tmp_path):
    """A kept file emptied, truncated or changed since it was kept is never copied into an
    export: the entry counts as a miss, is removed, and the run that rebuilds the job keeps
    its files again (a good entry reads back byte for byte)."""
    from tactcad.store import Store

    store, made = Store(tmp_path / "store"), tmp_path / "made"
    (made / "sub").mkdir(parents=True)
    (made / "sub" / "part.step").write_bytes(b"ISO-10303-21;" * 100)
    records = [{"path": "sub/part.step", "kind": "step"}]
    store.keep("ab" + "0" * 62, made, records)
    good = tmp_path / "good"
    assert store.fetch("ab" + "0" * 62, good) == records
    assert (good / "sub" / "part.step").read_bytes() == b"ISO-10303-21;" * 100
    kept = tmp_path / "store" / "ab" / ("ab" + "0" * 62) / "files" / "sub" / "part.step"
    for damage in (b"", b"ISO-10303-21;" * 99, b"ISO-10303-22;" + b"ISO-10303-21;" * 99):
        kept.write_bytes(damage)
        assert store.fetch("ab" + "0" * 62, tmp_path / "bad") is None
        assert not kept.exists()
        store.keep("ab" + "0" * 62, made, records)  # the rebuilt job kept again
        assert store.fetch("ab" + "0" * 62, tmp_path / "again") == records
