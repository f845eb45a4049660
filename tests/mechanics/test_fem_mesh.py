"""gmsh as tactcad starts it: the user's home and signals left as they were."""

import os
def test_starting_gmsh_writes_nothing_in_the_users_home(tmp_path, monkeypatch):
    """gmsh's GUI toolkit writes ~/.fltk/fltk.org/fltk.prefs as gmsh starts; a mesh leaves
    the user's home as it was, and HOME as it was."""
    from tactcad.mechanics.fem.fem_mesh import gmsh_session

    home = tmp_path / "home"
    home.mkdir()
    monkeypatch.setenv("HOME", str(home))
    with gmsh_session("probe") as gmsh:
        gmsh.model.occ.addBox(0, 0, 0, 1, 1, 1)
    assert list(home.iterdir()) == []
    assert os.environ["HOME"] == str(home)
