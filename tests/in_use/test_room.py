"""The in_use room exists as a package of its own, between the mechanics and the studies."""
import tactcad.in_use


def test_the_room_says_what_it_holds():
    assert "K_obj" in (tactcad.in_use.__doc__ or "")
