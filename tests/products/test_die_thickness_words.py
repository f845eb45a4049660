"""A die's two thicknesses, with its posts and the stack without them, are named wherever
each is printed: the design line, the bill of materials and the traveller."""

from __future__ import annotations

from conftest import run_cli


def test_each_printed_thickness_says_whether_it_has_the_posts(tmp_path):
    import tactcad
    from tactcad.products.silicon_die.design.die_mount import die_mount
    from tactcad.products.silicon_die.export.die_scene import mount_bom_rows
    from tactcad.products.silicon_die.export.traveller import traveller_steps

    r = run_cli("design", "--jaw", "5", "--kr-over-km", "10", "--kobj-range", "0.5", "5",
                "--full-scale-force", "0.009", "--out", "d", cwd=tmp_path)
    assert r.returncode == 0, r.stdout + r.stderr
    project = tactcad.load(tmp_path / "d" / "d.toml")
    plan = project.plan
    posts, stack = plan.thickness_um, plan.stack.total_um
    assert posts > stack
    head = r.stdout.splitlines()[0]
    assert f"{posts:g} um with its {plan.post_height_um:g} um posts" in head
    assert f"{stack:g} um stack without them" in head
    die = mount_bom_rows(plan, die_mount(plan, {}), "5 mm")[0]["description"]
    assert f"{stack / 1e3:.4g} mm without its posts" in die
    assert f"{posts / 1e3:.4g} mm with its {plan.post_height_um:g} um posts" in die
    bond = next(s for s in traveller_steps(plan, 100.0) if s.name == "bond and thin")
    assert f"{stack:g} um stack (the die without its posts)" in str(bond)
