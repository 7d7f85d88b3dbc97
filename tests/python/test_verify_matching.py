"""pounding.verify's impact matching with a window ([after_s, before_s)): pairs are made over the
whole lists first, so an impact just inside the window whose partner lies just outside is one
pair, not one missing and one extra; unmatched impacts outside the window are not counted."""
from pounding import verify


def impact(t_s, level=7):
    return {"t_s": t_s, "level": level, "striking_building": 2, "vertex": 1, "struck_edge": 2}


def test_a_pair_straddling_the_window_edge_is_one_pair():
    expected, observed = [impact(9.9999999)], [impact(10.0000001)]
    pairs, missing, extra = verify._match_in_window(expected, observed, {"before_s": 10.0})
    assert len(pairs) == 1 and not missing and not extra


def test_impacts_outside_the_window_do_not_count():
    expected = [impact(1.0), impact(5.0)]
    observed = [impact(1.0), impact(5.0), impact(20.0)]  # 20 s: after the stretch the expected cover
    pairs, missing, extra = verify._match_in_window(expected, observed, {"before_s": 10.0})
    assert len(pairs) == 2 and not missing and not extra
    pairs, missing, extra = verify._match_in_window(expected, observed, {"after_s": 2.0})
    assert len(pairs) == 1 and not missing and [o["t_s"] for o in extra] == [20.0]


def test_an_impact_at_another_contact_is_not_a_partner():
    pairs, missing, extra = verify._match_in_window([impact(1.0, level=6)], [impact(1.0, level=7)], {})
    assert not pairs and len(missing) == 1 and len(extra) == 1
